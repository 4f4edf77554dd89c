//! The study's figures: plain data in, files out.
//!
//! Every figure function takes finished data (never runs a simulation) and
//! writes `<stem>.png` and `<stem>.svg` (or, for animations, one GIF).
//! This crate depends on nothing of the project.
//!
//! Invariants:
//! - text uses DejaVu Sans compiled into the binary (no system fonts, no
//!   fontconfig, nothing fetched at run time), so a PNG is the same on every
//!   machine;
//! - the same input gives the same bytes (no timestamps, no hash-order
//!   output);
//! - files are written atomically (temporary file + rename, [`atomic`], the
//!   project's one atomic writer): an error leaves no half-written file.
//!
//! Look: the 'cool' colormap (cyan -> magenta) for time with a labelled
//! colour bar, P0 red, P1 blue, equal axis scales for chain shapes; PNGs are
//! about 1200 x 900 px with text of at least ~20 px, readable in print.

mod animation;
/// The atomic writer (the fc-atomic crate, under its old path).
pub use fc_atomic as atomic;
mod category;
mod chart;
mod clip;
mod colorbar;
mod colormap;
mod curve_layout;
mod curves;
mod font;
mod format;
mod layout;
mod legend;
mod line_layout;
mod lines;
mod marks;
mod output;
mod placement;
mod sizes;
mod sketch;
mod snapshots;
mod ticks;

pub use animation::{chain_animation, ANIMATION_HEIGHT};
pub use category::{category_map, category_map_to, CategoryMap, CategoryPanel};
pub use colormap::{cool, palette, P0_RED, P1_BLUE, PALETTE};
pub use curves::{colored_curves, ColoredCurves};
pub use format::format_number;
pub use line_layout::{line_plot_boxes, LinePlotBoxes, PanelLayout, MIN_FILL};
pub use lines::{
    line_plot, line_plot_pair, line_plot_pair_to, LinePlot, Marker, Series, Style, LINE_PLOT_SIZE,
    PAIR_SIZE,
};
pub use output::{FigureError, Output};
pub use placement::PixelRect;
pub use plotters::style::RGBColor;
pub use sketch::{sketch, SKETCH_SIZE};
pub use snapshots::{chain_snapshots, chain_snapshots_to, ChainSnapshots};
