//! The layout of a line plot, made before drawing: both axes (with room
//! above the data when the boxes would hide it), and where the legend and
//! the note box go.

use crate::layout::{self, Layout};
use crate::legend;
use crate::lines::{LinePlot, Series, Style, LINE_PLOT_SIZE};
use crate::placement::{self, Boxes, Occupancy, PixelRect};
use crate::sizes::Sizes;
use crate::ticks::Axis;
use crate::{clip, font, FigureError};

/// Series points in plot space (`None` where a point cannot be shown).
pub(crate) fn to_plot(s: &Series, x: &Axis, y: &Axis) -> Vec<Option<(f64, f64)>> {
    s.points
        .iter()
        .map(|&(px, py)| Some((x.to_plot(px)?, y.to_plot(py)?)))
        .collect()
}

pub(crate) fn has_line(style: Style) -> bool {
    matches!(style, Style::Line | Style::LinePoints | Style::Dashed)
}

pub(crate) fn has_marks(style: Style) -> bool {
    matches!(style, Style::Points | Style::LinePoints)
}

/// The pieces of series `s` drawn on axes `x`, `y` (plot space): its line
/// clipped to the axes, and each of its marks inside them as one point.
fn drawn_pieces(s: &Series, x: &Axis, y: &Axis) -> Vec<Vec<(f64, f64)>> {
    let pts = to_plot(s, x, y);
    let mut pieces = Vec::new();
    if has_line(s.style) {
        pieces.extend(
            clip::clip_polyline(&pts, (x.lo, x.hi), (y.lo, y.hi))
                .into_iter()
                .filter(|piece| piece.len() >= 2),
        );
    }
    if has_marks(s.style) {
        pieces.extend(
            pts.iter()
                .flatten()
                .filter(|q| q.0 >= x.lo && q.0 <= x.hi && q.1 >= y.lo && q.1 <= y.hi)
                .map(|&q| vec![q]),
        );
    }
    pieces
}

/// Where the data of `p` is drawn, in pixels of a `plot` area.
fn occupancy(p: &LinePlot, x: &Axis, y: &Axis, plot: (i32, i32)) -> Occupancy {
    let pieces: Vec<Vec<(f64, f64)>> = p
        .series
        .iter()
        .flat_map(|s| drawn_pieces(s, x, y))
        .collect();
    Occupancy::new(&pieces, x, y, plot)
}

/// Size of the legend of `p` (`None` if no series is labelled).
fn legend_size(p: &LinePlot, sizes: &Sizes) -> Option<(i32, i32)> {
    let labels: Vec<String> = p
        .series
        .iter()
        .filter(|s| !s.label.is_empty())
        .map(|s| s.label.clone())
        .collect();
    (!labels.is_empty()).then(|| legend::box_size(sizes, &labels, true))
}

/// Size of the note box of `p` (`None` without notes).
fn note_size(p: &LinePlot, sizes: &Sizes) -> Option<(i32, i32)> {
    (!p.annotations.is_empty()).then(|| legend::box_size(sizes, &p.annotations, false))
}

/// Distance of the boxes from the edges of the plot area and each other.
fn inset(sizes: &Sizes) -> i32 {
    sizes.px(14.0)
}

/// Choose both axes for `p` in an area of `size` pixels. If the legend and
/// the note box would hide data wherever they go, room is made above the
/// data (unless the y range is fixed).
fn choose_axes(p: &LinePlot, sizes: &Sizes, size: (u32, u32)) -> (Axis, Axis, Layout) {
    let valid = |v: f64, log: bool| v.is_finite() && (!log || v > 0.0);
    let pts: Vec<(f64, f64)> = p
        .series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|&(x, y)| valid(x, p.log_x) && valid(y, p.log_y))
        .collect();
    let (x0, x1, y0, y1) = layout::bounds(&pts).unwrap_or((1.0, 10.0, 1.0, 10.0));
    let pad = 0.04;
    let build = |headroom: f64| {
        let mut layout = Layout::standard(sizes, 0);
        let (_, ph) = layout.plot_size(size);
        let ty = (ph as f64 / (95.0 * sizes.scale)).round().clamp(3.0, 10.0) as usize;
        let mut y = Axis::auto(y0, y1, p.y_range, p.log_y, pad, ty);
        if headroom > 0.0 {
            let hi = y.hi + headroom * y.span();
            y = if y.log {
                Axis::log(y.lo, hi, ty)
            } else {
                Axis::linear(y.lo, hi, ty)
            };
        }
        layout = Layout::standard(sizes, y.max_label_width(sizes.tick()));
        let (pw, _) = layout.plot_size(size);
        let tx = (pw as f64 / (170.0 * sizes.scale)).round().clamp(3.0, 10.0) as usize;
        let mut x = Axis::auto(x0, x1, p.x_range, p.log_x, pad, tx);
        if let (Some(step), false) = (p.x_tick_step, p.log_x) {
            x = Axis::linear_step(x.lo, x.hi, step);
        }
        if p.equal_aspect && !p.log_x && !p.log_y {
            let (bx, by) = ((x.lo, x.hi), (y.lo, y.hi));
            for _ in 0..2 {
                let (ex, ey) = layout::equalize(bx, by, layout.plot_size(size));
                x = Axis::linear(ex.0, ex.1, tx);
                y = Axis::linear(ey.0, ey.1, ty);
                layout = Layout::standard(sizes, y.max_label_width(sizes.tick()));
            }
        }
        (x, y, layout)
    };
    let (x, y, layout) = build(0.0);
    let (legend, note) = (legend_size(p, sizes), note_size(p, sizes));
    if (legend.is_none() && note.is_none()) || p.y_range.is_some() {
        return (x, y, layout);
    }
    let plot = layout.plot_size(size);
    let occ = occupancy(p, &x, &y, plot);
    let inset = inset(sizes);
    if placement::place_boxes(&occ, plot, inset, legend, note).hidden == 0 {
        return (x, y, layout);
    }
    let band = placement::top_band(plot, inset, legend, note);
    let frac = (band + 2 * inset) as f64 / plot.1.max(1) as f64;
    build(frac / (1.0 - frac).max(0.3))
}

/// Axes, margins and the places of the legend and the note box of one plot.
pub(crate) struct Plan {
    pub x: Axis,
    pub y: Axis,
    pub layout: Layout,
    /// Size of the plot area.
    pub plot: (i32, i32),
    pub boxes: Boxes,
}

impl Plan {
    /// The plan of `p` in an area of `size` pixels (under its title).
    pub fn new(p: &LinePlot, sizes: &Sizes, size: (u32, u32)) -> Plan {
        let (x, y, layout) = choose_axes(p, sizes, size);
        let plot = layout.plot_size(size);
        let occ = occupancy(p, &x, &y, plot);
        let boxes = placement::place_boxes(
            &occ,
            plot,
            inset(sizes),
            legend_size(p, sizes),
            note_size(p, sizes),
        );
        Plan {
            x,
            y,
            layout,
            plot,
            boxes,
        }
    }
}

/// Where [`line_plot`](crate::line_plot) puts the legend and the note box of `p`, in pixels of
/// its plot area as drawn in the SVG (the PNG is drawn at twice the size).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LinePlotBoxes {
    /// Size of the plot area (inside the axes).
    pub plot: (i32, i32),
    /// The legend; `None` if no series is labelled.
    pub legend: Option<PixelRect>,
    /// The note box of [`LinePlot::annotations`]; `None` without notes.
    pub note: Option<PixelRect>,
    /// How many samples of the drawn data (about 6 px apart along every
    /// line, and every mark) the two boxes cover.
    pub hidden: usize,
}

/// The layout [`line_plot`](crate::line_plot) draws `p` with: where its legend and note box go.
pub fn line_plot_boxes(p: &LinePlot) -> Result<LinePlotBoxes, FigureError> {
    font::ensure_registered()?;
    let sizes = Sizes::STANDARD;
    let (w, h) = LINE_PLOT_SIZE;
    let title_h = layout::title_height(&sizes, p.title) as u32;
    let plan = Plan::new(p, &sizes, (w, h - title_h));
    Ok(LinePlotBoxes {
        plot: plan.plot,
        legend: plan.boxes.legend,
        note: plan.boxes.note,
        hidden: plan.boxes.hidden,
    })
}
