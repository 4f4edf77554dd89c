//! Generic 2-D line and point plots: several series, linear or log axes,
//! a legend placed where it hides the least, and an optional note box.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::colormap::palette;
use crate::layout;
use crate::legend::{self, Swatch};
use crate::line_layout::{self, has_line, has_marks, is_dashed, mark_radius, to_plot, Plan};
use crate::marks::{self, Mark};
use crate::output::{self, Draw};
use crate::placement::PixelRect;
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
    /// A dashed line with a mark at every point.
    DashedPoints,
}

/// The shape of a series' marks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Marker {
    #[default]
    Circle,
    Square,
    Triangle,
    Diamond,
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
    /// The shape of its marks.
    pub marker: Marker,
    /// Marks drawn as outlines, larger than filled ones, so that a mark on
    /// another series' mark or line shows both.
    pub hollow: bool,
}

impl Series {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, style: Style) -> Series {
        Series {
            label: label.into(),
            points,
            style,
            color: None,
            marker: Marker::Circle,
            hollow: false,
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
    pub fn with_marker(mut self, marker: Marker) -> Series {
        self.marker = marker;
        self
    }
    /// Its marks as outlines ([`Series::hollow`]).
    pub fn hollow(mut self) -> Series {
        self.hollow = true;
        self
    }
    /// An entry of the legend alone (no data): its label and how it is
    /// drawn, e.g. a colour or a line style that several series share.
    pub fn legend_only(label: impl Into<String>, style: Style) -> Series {
        Series::new(label, vec![], style)
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
    /// Ticks at these x values (data units, linear or log axis), labelled
    /// as plain numbers: a ladder such as n = 25, 50, .., 400.
    pub x_ticks: Option<Vec<f64>>,
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
            x_ticks: None,
        }
    }
}

/// Canvas of a single plot.
pub const LINE_PLOT_SIZE: (u32, u32) = (1200, 900);
/// Canvas of a pair of plots side by side.
pub const PAIR_SIZE: (u32, u32) = (2000, 1000);
/// The text of a pair is this many times a single plot's: a pair is
/// printed at the width of the text, where a single plot of 1200 px is
/// printed at most as wide, so that its legends stay readable.
const PAIR_SCALE: f64 = 1.2;

/// Draw `p` to `<stem>.png` and `<stem>.svg`; the output says what was
/// drawn ([`Output::panels`]).
pub fn line_plot(p: &LinePlot, stem: &Path) -> Result<Output, FigureError> {
    let mut out = output::save(&Single(p), stem)?;
    out.panels = vec![line_layout::single_plan(p).report(p, &Sizes::STANDARD)];
    Ok(out)
}

/// Draw two plots side by side under a common `title` (empty for none).
pub fn line_plot_pair(
    left: &LinePlot,
    right: &LinePlot,
    title: &str,
    stem: &Path,
) -> Result<Output, FigureError> {
    let mut out = output::save(&Pair { left, right, title }, stem)?;
    out.panels = pair_plans(left, right, title)
        .iter()
        .zip([left, right])
        .map(|(plan, p)| plan.report(p, &Sizes { scale: PAIR_SCALE }))
        .collect();
    Ok(out)
}

/// The plans of a pair's two panels at the SVG's scale.
fn pair_plans(left: &LinePlot, right: &LinePlot, title: &str) -> [Plan; 2] {
    let sizes = Sizes { scale: PAIR_SCALE };
    let (w, h) = PAIR_SIZE;
    let h = h - layout::title_height(&sizes, title) as u32;
    let halves = [w / 2, w - w / 2];
    let plan = |p: &LinePlot, hw: u32| {
        let ph = h - layout::title_height(&sizes, p.title) as u32;
        Plan::new(p, &sizes, (hw, ph))
    };
    [plan(left, halves[0]), plan(right, halves[1])]
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
        let sizes = Sizes { scale: PAIR_SCALE }.scaled(scale);
        let area = layout::titled(root, &sizes, self.title)?;
        let (w, _) = area.dim_in_pixel();
        let (l, r) = area.split_horizontally(w / 2);
        draw_plot(&l, self.left, &sizes)?;
        draw_plot(&r, self.right, &sizes)
    }
}

/// The legend swatch of series `s`, drawn in `color`.
fn swatch(s: &Series, color: RGBColor, sizes: &Sizes) -> Swatch {
    Swatch::Series {
        color,
        width: if has_line(s.style) { sizes.line() } else { 0 },
        dashed: is_dashed(s.style),
        mark: has_marks(s.style).then(|| (s.marker, mark_radius(s, sizes), s.hollow)),
    }
}

/// `piece` (plot space) cut at every vertex where it turns back by more
/// than 120 degrees on the plot (pixels of a `plot` area): plotters joins a
/// thick bitmap line's segments with mitres, which at such a turn reach far
/// past the vertex, out of the frame.
fn split_sharp(
    piece: &[(f64, f64)],
    x: &crate::ticks::Axis,
    y: &crate::ticks::Axis,
    plot: (i32, i32),
) -> Vec<Vec<(f64, f64)>> {
    let px = |p: (f64, f64)| {
        (
            (p.0 - x.lo) / x.span() * f64::from(plot.0),
            (p.1 - y.lo) / y.span() * f64::from(plot.1),
        )
    };
    let mut out = vec![];
    let mut cur: Vec<(f64, f64)> = vec![];
    for (k, &p) in piece.iter().enumerate() {
        cur.push(p);
        if k == 0 || k + 1 == piece.len() {
            continue;
        }
        let (a, b, c) = (px(piece[k - 1]), px(p), px(piece[k + 1]));
        let (u, v) = ((b.0 - a.0, b.1 - a.1), (c.0 - b.0, c.1 - b.1));
        let norms = u.0.hypot(u.1) * v.0.hypot(v.1);
        if norms > 0.0 && (u.0 * v.0 + u.1 * v.1) / norms < -0.5 {
            out.push(std::mem::replace(&mut cur, vec![p]));
        }
    }
    out.push(cur);
    out
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
    let color_of = |i: usize, s: &Series| s.color.unwrap_or_else(|| palette(i));
    // Every line first, then every mark, so that no line hides a mark.
    for (i, s) in p.series.iter().enumerate() {
        if !has_line(s.style) {
            continue;
        }
        let color = color_of(i, s);
        let pts = to_plot(s, x, y);
        let pieces = clip::clip_polyline(&pts, (x.lo, x.hi), (y.lo, y.hi));
        for piece in pieces.iter().flat_map(|p| split_sharp(p, x, y, plan.plot)) {
            if piece.len() < 2 {
                continue;
            }
            if is_dashed(s.style) {
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
    for (i, s) in p.series.iter().enumerate() {
        if !has_marks(s.style) {
            continue;
        }
        let pts: Vec<(f64, f64)> = to_plot(s, x, y)
            .into_iter()
            .flatten()
            .filter(|q| q.0 >= x.lo && q.0 <= x.hi && q.1 >= y.lo && q.1 <= y.hi)
            .collect();
        marks::draw(
            chart.plotting_area(),
            pts,
            Mark {
                marker: s.marker,
                radius: mark_radius(s, sizes),
                color: color_of(i, s),
                hollow: s.hollow,
                outline: sizes.px(2.5) as u32,
            },
        )?;
    }
    chart::frame(&chart, sizes)?;
    drop(chart);

    // The boxes, in pixels of the plot area, drawn on the panel (they may
    // sit beside the plot).
    let origin = (plan.layout.left + plan.layout.y_area, plan.layout.top);
    let at = |r: &PixelRect| (origin.0 + r.x0, origin.1 + r.y0);
    if let Some(r) = plan.boxes.legend {
        let entries: Vec<(String, Swatch)> = p
            .series
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.label.is_empty())
            .map(|(i, s)| (s.label.clone(), swatch(s, color_of(i, s), sizes)))
            .collect();
        legend::draw_entries(&area, sizes, at(&r), &entries, plan.columns)?;
    }
    if let Some(r) = plan.boxes.note {
        legend::draw_note(&area, sizes, at(&r), &p.annotations)?;
    }
    Ok(())
}
