//! Generic 2-D line and point plots: several series, linear or log axes,
//! a legend placed where it hides the least, and an optional note box.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::colormap::palette;
use crate::layout;
use crate::legend::{self, Swatch};
use crate::line_layout::{has_line, has_marks, to_plot, Plan};
use crate::output::{self, Draw};
use crate::sizes::Sizes;
use crate::{chart, clip};
use crate::{FigureError, Output};

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    Line,
    Points,
    LinePoints,
    Dashed,
}

/// One series of a [`LinePlot`].
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text; empty for no legend entry.
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
    /// `None`: palette colour by series index (see [`crate::palette`]);
    /// `Some(c)`: e.g. `palette(2)` or `cool(0.3)`.
    pub color: Option<RGBColor>,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Series {
        Series {
            label: label.into(),
            points,
            style,
            color: None,
        }
    }
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series::new(label, points, Style::Line)
    }
    pub fn points(label: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series::new(label, points, Style::Points)
    }
    pub fn with_color(mut self, color: RGBColor) -> Series {
        self.color = Some(color);
        self
    }
}

/// A line plot. Points that cannot be shown (non-finite, or <= 0 on a log
/// axis) break a line; data outside a fixed range is clipped.
#[derive(Debug, Clone)]
pub struct LinePlot<'a> {
    /// Drawn above the plot; empty for none.
    pub title: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub series: Vec<Series>,
    pub log_x: bool,
    pub log_y: bool,
    /// Same data units per pixel on both axes (ignored on log axes).
    pub equal_aspect: bool,
    /// Fixed ranges (data units); `None` fits the data.
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    /// Lines of text in a box in a free corner (e.g. a fitted order).
    pub annotations: Vec<String>,
    /// A fixed step between x ticks (linear axes only); `None` chooses one
    /// by the plot's width.
    pub x_tick_step: Option<f64>,
}

impl<'a> LinePlot<'a> {
    pub fn new(title: &'a str, x_label: &'a str, y_label: &'a str) -> LinePlot<'a> {
        LinePlot {
            title,
            x_label,
            y_label,
            series: Vec::new(),
            log_x: false,
            log_y: false,
            equal_aspect: false,
            x_range: None,
            y_range: None,
            annotations: Vec::new(),
            x_tick_step: None,
        }
    }
}

/// Canvas of a single plot.
pub const LINE_PLOT_SIZE: (u32, u32) = (1200, 900);
/// Canvas of a pair of plots side by side.
pub const PAIR_SIZE: (u32, u32) = (2000, 900);

/// Draw `p` to `<stem>.png` and `<stem>.svg`.
pub fn line_plot(p: &LinePlot, stem: &Path) -> Result<Output, FigureError> {
    output::save(&Single(p), stem)
}

/// Draw two plots side by side under a common `title` (empty for none).
pub fn line_plot_pair(
    left: &LinePlot,
    right: &LinePlot,
    title: &str,
    stem: &Path,
) -> Result<Output, FigureError> {
    output::save(&Pair { left, right, title }, stem)
}

/// As [`line_plot_pair`], to the one file `path` (`.png` or `.svg`).
pub fn line_plot_pair_to(
    left: &LinePlot,
    right: &LinePlot,
    title: &str,
    path: &Path,
) -> Result<(), FigureError> {
    output::save_one(&Pair { left, right, title }, path)
}

struct Single<'p, 'a>(&'p LinePlot<'a>);

impl Draw for Single<'_, '_> {
    fn size(&self) -> (u32, u32) {
        LINE_PLOT_SIZE
    }
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: u32,
    ) -> Result<(), FigureError> {
        root.fill(&WHITE)?;
        draw_plot(root, self.0, &Sizes::STANDARD.scaled(scale))
    }
}

struct Pair<'p, 'a> {
    left: &'p LinePlot<'a>,
    right: &'p LinePlot<'a>,
    title: &'p str,
}

impl Draw for Pair<'_, '_> {
    fn size(&self) -> (u32, u32) {
        PAIR_SIZE
    }
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: u32,
    ) -> Result<(), FigureError> {
        root.fill(&WHITE)?;
        let sizes = Sizes { scale: 1.1 }.scaled(scale);
        let area = layout::titled(root, &sizes, self.title)?;
        let (w, _) = area.dim_in_pixel();
        let (l, r) = area.split_horizontally(w / 2);
        draw_plot(&l, self.left, &sizes)?;
        draw_plot(&r, self.right, &sizes)
    }
}

fn draw_plot<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    p: &LinePlot,
    sizes: &Sizes,
) -> Result<(), FigureError> {
    let area = layout::titled(area, sizes, p.title)?;
    let plan = Plan::new(p, sizes, area.dim_in_pixel());
    let (x, y) = (&plan.x, &plan.y);
    let mut chart = chart::chart(&area, sizes, &plan.layout, x, y, p.x_label, p.y_label)?;

    let line_w = sizes.line();
    let radius = sizes.px(5.5);
    for (i, s) in p.series.iter().enumerate() {
        let color = s.color.unwrap_or_else(|| palette(i));
        let pts = to_plot(s, x, y);
        if has_line(s.style) {
            for piece in clip::clip_polyline(&pts, (x.lo, x.hi), (y.lo, y.hi)) {
                if piece.len() < 2 {
                    continue;
                }
                if s.style == Style::Dashed {
                    chart.draw_series(DashedLineSeries::new(
                        piece,
                        sizes.px(14.0),
                        sizes.px(8.0),
                        color.stroke_width(line_w),
                    ))?;
                } else {
                    chart.draw_series(LineSeries::new(piece, color.stroke_width(line_w)))?;
                }
            }
        }
        if has_marks(s.style) {
            chart.draw_series(
                pts.iter()
                    .flatten()
                    .filter(|q| q.0 >= x.lo && q.0 <= x.hi && q.1 >= y.lo && q.1 <= y.hi)
                    .map(|&q| Circle::new(q, radius, color.filled())),
            )?;
        }
        if !s.label.is_empty() {
            let swatch = match s.style {
                Style::Line => Swatch::Line {
                    color,
                    width: line_w,
                    dashed: false,
                },
                Style::Dashed => Swatch::Line {
                    color,
                    width: line_w,
                    dashed: true,
                },
                Style::Points => Swatch::Marker { color, radius },
                Style::LinePoints => Swatch::LineMarker {
                    color,
                    width: line_w,
                    radius,
                },
            };
            legend::add_entry(&mut chart, sizes, &s.label, swatch)?;
        }
    }
    chart::frame(&chart, sizes)?;

    let pa = chart.plotting_area().strip_coord_spec();
    let (pw, ph) = pa.dim_in_pixel();
    debug_assert_eq!((pw as i32, ph as i32), plan.plot, "plot area as planned");
    if let Some(r) = plan.boxes.legend {
        legend::draw_legend(&mut chart, sizes, r.origin())?;
    }
    if let Some(r) = plan.boxes.note {
        legend::draw_note(&pa, sizes, r.origin(), &p.annotations)?;
    }
    Ok(())
}
