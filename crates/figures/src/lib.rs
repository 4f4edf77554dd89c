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
//!
//! Its files:
//! * `animation.rs`: Animated GIF of the chain: fixed axes (those of the snapshot figure), the current chain in its time colour, the path of the free end so far ...
//! * `category.rs`: Categorical maps (the stability map): panels of rows x columns of cells, each cell a category drawn as a colour, with a legend.
//! * `chart.rs`: A chart with our axes: grid, ticks, tick labels, axis names, and the frame around the plot area.
//! * `clip.rs`: Clipping polylines to the plot area (plotters draws outside it).
//! * `colorbar.rs`: The vertical colour bar beside a coloured-curves figure ('cool', from the smallest parameter value at the bottom to the largest at the top), with ticks, a label ...
//! * `colormap.rs`: Colours: the 'cool' colormap (cyan -> magenta) used for time, and a categorical palette for line plots.
//! * `curve_layout.rs`: The layout of a coloured-curves figure (also of every frame of an animation): axes with equal scales, a canvas width that follows the data, room for the colour bar ...
//! * `curves.rs`: Curves coloured by a parameter with a colour bar (report Fig. 2: the catenaries coloured by L), and the drawing shared with the chain snapshots and the animation ...
//! * `font.rs`: The embedded font.
//! * `format.rs`: Number formats: tick labels of linear axes, powers of ten with superscript exponents, numbers for legends and notes, the typographic minus.
//! * `layout.rs`: Where a chart sits on its canvas: margins and label areas, the title above it, equal axis scales, and the bounds of the data.
//! * `legend.rs`: Legend and note boxes: their size, the legend drawn by plotters' series labels, and the note box drawn to look the same.
//! * `line_layout.rs`: The layout of a line plot, made before drawing: both axes (fitted to the data), and where the legend and the note box go: in a corner of the plot where they hide no data ...
//! * `lines.rs`: Generic 2-D line and point plots: several series, linear or log axes, a legend placed where it hides the least, and an optional note box.
//! * `marks.rs`: Data marks of every shape (`Marker`), filled or hollow, drawn on any drawing area at its own coordinates (a chart's data, or pixels for a legend's swatch).
//! * `output.rs`: Errors, rendering a figure to both backends, and atomic file output.
//! * `placement.rs`: Placing boxes (a legend, a note box) in the plot area where they hide the least data and never each other; plotters only knows fixed positions.
//! * `sizes.rs`: Sizes of text, lines and margins in pixels, the embedded font as a text style, and text widths.
//! * `sketch.rs`: The schematic of the problem (report Fig. 1): a chain of n rods hangs from P0 and P1; P1's end is released and falls under gravity.
//! * `snapshots.rs`: Chain snapshots coloured by time (report Figs. 3-7, 10, 12).
//! * `ticks.rs`: Axis ranges and ticks: linear axes with nice steps, logarithmic axes drawn as linear axes over `log10` of the data with our own key points (exactly the powers of ten) ...

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
pub use line_layout::{
    line_plot_boxes, same_swatch_two_meanings, LegendKey, LinePlotBoxes, PanelLayout, MIN_FILL,
    MIN_NAME_SHARE,
};
pub use lines::{
    line_plot, line_plot_pair, line_plot_pair_to, LinePlot, Marker, Series, Style, LINE_PLOT_SIZE,
    PAIR_SIZE,
};
pub use output::{FigureError, Output};
pub use placement::PixelRect;
pub use plotters::style::RGBColor;
pub use sketch::{sketch, SKETCH_SIZE};
pub use snapshots::{chain_snapshots, chain_snapshots_to, ChainSnapshots};
