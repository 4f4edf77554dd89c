//! The layout of a line plot, made before drawing: both axes (fitted to
//! the data), and where the legend and the note box go: in a corner of the
//! plot where they hide no data, else beside the plot (right of it, or
//! under it when a column would leave the plot too narrow). The axes never
//! grow to make room for the boxes, so the data fill their ranges.

use crate::colormap::palette;
use crate::layout::{self, Layout};
use crate::legend;
use crate::lines::{LinePlot, Marker, Series, Style, LINE_PLOT_SIZE};
use crate::placement::{self, Boxes, Occupancy, PixelRect};
use crate::sizes::{text_width, Sizes};
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
    matches!(
        style,
        Style::Line | Style::LinePoints | Style::Dashed | Style::DashedPoints
    )
}

pub(crate) fn has_marks(style: Style) -> bool {
    matches!(
        style,
        Style::Points | Style::LinePoints | Style::DashedPoints
    )
}

pub(crate) fn is_dashed(style: Style) -> bool {
    matches!(style, Style::Dashed | Style::DashedPoints)
}

/// The radius of a series' marks: hollow marks are drawn larger, so that
/// a filled mark under one shows inside it.
pub(crate) fn mark_radius(s: &Series, sizes: &Sizes) -> i32 {
    sizes.px(if s.hollow { 8.0 } else { 5.5 })
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

/// Every piece of data of `p` as drawn on `x`, `y`.
fn all_pieces(p: &LinePlot, x: &Axis, y: &Axis) -> Vec<Vec<(f64, f64)>> {
    p.series
        .iter()
        .flat_map(|s| drawn_pieces(s, x, y))
        .collect()
}

/// Where the data of `p` is drawn, in pixels of a `plot` area.
fn occupancy(p: &LinePlot, x: &Axis, y: &Axis, plot: (i32, i32)) -> Occupancy {
    Occupancy::new(&all_pieces(p, x, y), x, y, plot)
}

/// The legend lines of `p`: the labelled series.
fn legend_labels(p: &LinePlot) -> Vec<String> {
    p.series
        .iter()
        .filter(|s| !s.label.is_empty())
        .map(|s| s.label.clone())
        .collect()
}

/// Size of the legend of `p` in `columns` columns (`None` if no series is
/// labelled).
fn legend_size(p: &LinePlot, sizes: &Sizes, columns: usize) -> Option<(i32, i32)> {
    let labels = legend_labels(p);
    (!labels.is_empty()).then(|| legend::legend_size(sizes, &labels, columns))
}

/// Size of the note box of `p` (`None` without notes).
fn note_size(p: &LinePlot, sizes: &Sizes) -> Option<(i32, i32)> {
    (!p.annotations.is_empty()).then(|| legend::box_size(sizes, &p.annotations, false))
}

/// Distance of the boxes from the edges of the plot area and each other.
fn inset(sizes: &Sizes) -> i32 {
    sizes.px(14.0)
}

/// The data of `p` that can be shown on its axes (data space).
fn shown_points(p: &LinePlot) -> Vec<(f64, f64)> {
    let valid = |v: f64, log: bool| v.is_finite() && (!log || v > 0.0);
    p.series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|&(x, y)| valid(x, p.log_x) && valid(y, p.log_y))
        .collect()
}

/// Both axes of `p` for an area of `size` pixels, fitted to its data (or
/// its fixed ranges), with `extra` pixels `(right, bottom)` kept beside
/// the plot for the boxes. The padding keeps every mark clear of the frame.
fn build_axes(
    p: &LinePlot,
    sizes: &Sizes,
    size: (u32, u32),
    extra: (i32, i32),
) -> (Axis, Axis, Layout) {
    let pts = shown_points(p);
    let (x0, x1, y0, y1) = layout::bounds(&pts).unwrap_or((1.0, 10.0, 1.0, 10.0));
    let radius = p
        .series
        .iter()
        .filter(|s| has_marks(s.style))
        .map(|s| mark_radius(s, sizes))
        .max()
        .unwrap_or(0);
    let with_extra = |mut l: Layout| {
        l.right += extra.0;
        l.bottom += extra.1;
        l
    };
    let mut layout = with_extra(Layout::standard(sizes, 0));
    let (_, ph) = layout.plot_size(size);
    // A mark's radius and a few pixels, as a fraction of the plot.
    let clear = |px: i32| (f64::from(radius) + f64::from(sizes.px(4.0))) / f64::from(px.max(1));
    let ty = (ph as f64 / (95.0 * sizes.scale)).round().clamp(3.0, 10.0) as usize;
    let y = Axis::auto(y0, y1, p.y_range, p.log_y, 0.04 + clear(ph), ty);
    layout = with_extra(Layout::standard(sizes, y.max_label_width(sizes.tick())));
    let (pw, _) = layout.plot_size(size);
    let tx = (pw as f64 / (170.0 * sizes.scale)).round().clamp(3.0, 10.0) as usize;
    let mut x = Axis::auto(x0, x1, p.x_range, p.log_x, 0.04 + clear(pw), tx);
    let mut y = y;
    if let (Some(step), false) = (p.x_tick_step, p.log_x) {
        x = Axis::linear_step(x.lo, x.hi, step);
    }
    if p.equal_aspect && !p.log_x && !p.log_y {
        let (bx, by) = ((x.lo, x.hi), (y.lo, y.hi));
        for _ in 0..2 {
            let (ex, ey) = layout::equalize(bx, by, layout.plot_size(size));
            // One tick step on both axes: equal scales read as equal.
            let (ax, ay) = (Axis::linear(ex.0, ex.1, tx), Axis::linear(ey.0, ey.1, ty));
            let step = ax.step().max(ay.step());
            x = Axis::linear_step(ex.0, ex.1, step);
            y = Axis::linear_step(ey.0, ey.1, step);
            layout = with_extra(Layout::standard(sizes, y.max_label_width(sizes.tick())));
        }
    }
    if let Some(at) = &p.x_ticks {
        x = x.with_ticks_at(at);
    }
    (x, y, layout)
}

/// Axes, margins and the places of the legend and the note box of one plot.
pub(crate) struct Plan {
    pub x: Axis,
    pub y: Axis,
    pub layout: Layout,
    /// Size of the plot area.
    pub plot: (i32, i32),
    /// In pixels of the plot area (y down): in it, hiding no data, or
    /// beside it (right of the plot, or under its x label).
    pub boxes: Boxes,
    /// The legend's columns (more than one only under the plot).
    pub columns: usize,
}

/// The sizes of a legend and a note box, either absent.
type BoxSizes = (Option<(i32, i32)>, Option<(i32, i32)>);

/// The legend and the note stacked (`true`) or side by side: its size.
fn group((l, n): BoxSizes, inset: i32, stacked: bool) -> (i32, i32) {
    match (l, n) {
        (Some(a), Some(b)) if stacked => (a.0.max(b.0), a.1 + inset + b.1),
        (Some(a), Some(b)) => (a.0 + inset + b.0, a.1.max(b.1)),
        (Some(a), None) | (None, Some(a)) => a,
        (None, None) => (0, 0),
    }
}

/// The boxes of a group whose top-left corner is `at`.
fn place_group((l, n): BoxSizes, inset: i32, stacked: bool, at: (i32, i32)) -> Boxes {
    let legend = l.map(|s| PixelRect::new(at, s));
    let note = n.map(|s| match (l, stacked) {
        (Some(a), true) => PixelRect::new((at.0, at.1 + a.1 + inset), s),
        (Some(a), false) => PixelRect::new((at.0 + a.0 + inset, at.1), s),
        (None, _) => PixelRect::new(at, s),
    });
    Boxes {
        legend,
        note,
        hidden: 0,
    }
}

impl Plan {
    /// The plan of `p` in an area of `size` pixels (under its title).
    pub fn new(p: &LinePlot, sizes: &Sizes, size: (u32, u32)) -> Plan {
        let one = (legend_size(p, sizes, 1), note_size(p, sizes));
        let inset = inset(sizes);
        let (x, y, layout) = build_axes(p, sizes, size, (0, 0));
        let plot = layout.plot_size(size);
        let occ = occupancy(p, &x, &y, plot);
        let inside = placement::place_boxes(&occ, plot, inset, one.0, one.1);
        if inside.hidden == 0 {
            return Plan {
                x,
                y,
                layout,
                plot,
                boxes: inside,
                columns: 1,
            };
        }
        // Right of the plot: stacked if that fits its height, else side by
        // side; taken if it leaves the plot at least 60% of its width.
        let stacked_r = group(one, inset, true).1 <= plot.1;
        let (gw, _) = group(one, inset, stacked_r);
        let (xr, yr, lr) = build_axes(p, sizes, size, (gw + inset, 0));
        let plot_r = lr.plot_size(size);
        let right = Plan {
            x: xr,
            y: yr,
            layout: lr,
            plot: plot_r,
            boxes: place_group(one, inset, stacked_r, (plot_r.0 + inset, 0)),
            columns: 1,
        };
        if 10 * plot_r.0 >= 6 * plot.0 {
            return right;
        }
        // Under the plot, across the whole panel: the legend in as many
        // columns as fit, the note beside it if both fit, else under it;
        // taken unless it leaves the plot less of its height than the
        // column leaves of its width.
        let width = size.0 as i32 - 2 * inset;
        let count = legend_labels(p).len().max(1);
        let columns = (1..=count)
            .rev()
            .find(|&c| legend_size(p, sizes, c).is_none_or(|s| s.0 <= width))
            .unwrap_or(1);
        let both = (legend_size(p, sizes, columns), one.1);
        let stacked = group(both, inset, false).0 > width;
        let (gw, gh) = group(both, inset, stacked);
        let (xb, yb, lb) = build_axes(p, sizes, size, (0, gh + inset));
        let plot_b = lb.plot_size(size);
        // Centred in the panel, whose left edge is this far left of the plot.
        let left = lb.left + lb.y_area;
        let at = (
            (size.0 as i32 - gw) / 2 - left,
            plot_b.1 + lb.x_area + inset,
        );
        if i64::from(plot_b.1) * i64::from(plot.0) < i64::from(plot_r.0) * i64::from(plot.1) {
            return right;
        }
        Plan {
            x: xb,
            y: yb,
            layout: lb,
            plot: plot_b,
            boxes: place_group(both, inset, stacked, at),
            columns,
        }
    }

    /// What this plan draws (at `sizes`): its axes, the extent of its
    /// data, its boxes, how large its axis names are set, its legend's keys.
    pub fn report(&self, p: &LinePlot, sizes: &Sizes) -> PanelLayout {
        let pieces = all_pieces(p, &self.x, &self.y);
        let data = layout::bounds(pieces.iter().flatten()).map(|(a, b, c, d)| ((a, b), (c, d)));
        // As `chart::chart` sets them: a name longer than its side shrinks.
        let label = sizes.label();
        let share =
            |name: &str, room: i32| layout::fitted(label, text_width(name, label), room) / label;
        let axis_names = share(p.x_label, self.plot.0).min(share(p.y_label, self.plot.1));
        let keys = p
            .series
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.label.is_empty())
            .map(|(i, s)| (s, s.color.unwrap_or_else(|| palette(i))))
            .map(|(s, c)| LegendKey {
                label: s.label.clone(),
                color: (c.0, c.1, c.2),
                style: s.style,
                marker: has_marks(s.style).then_some(s.marker),
                hollow: has_marks(s.style) && s.hollow,
            })
            .collect();
        PanelLayout {
            axis_names,
            keys,
            plot: self.plot,
            x: (self.x.lo, self.x.hi),
            y: (self.y.lo, self.y.hi),
            log_x: self.x.log,
            log_y: self.y.log,
            equal_aspect: p.equal_aspect && !p.log_x && !p.log_y,
            data,
            legend: self.boxes.legend,
            note: self.boxes.note,
            hidden: self.boxes.hidden,
        }
    }
}

/// What one panel of a line plot draws, for the checks of the figures
/// that use it: its axis ranges, how much of them its data span, where its
/// boxes are and what data they cover. Ranges are in plot space (`log10`
/// of the data on a log axis), pixels those of the SVG.
#[derive(Debug, Clone, PartialEq)]
pub struct PanelLayout {
    /// Size of the plot area (inside the axes).
    pub plot: (i32, i32),
    pub x: (f64, f64),
    pub y: (f64, f64),
    pub log_x: bool,
    pub log_y: bool,
    /// Equal scales on both axes, so that one axis holds more than its data.
    pub equal_aspect: bool,
    /// The extent of the data drawn (inside the axes), `(x, y)`.
    pub data: Option<((f64, f64), (f64, f64))>,
    /// Legend and note box, in pixels of the plot area (outside it when
    /// they sit beside the plot).
    pub legend: Option<PixelRect>,
    pub note: Option<PixelRect>,
    /// Samples of the drawn data (about 6 px apart along every line, and
    /// every mark) that the boxes cover or come within 6 px of.
    pub hidden: usize,
    /// The size the smaller axis name is set at, as a share of the label
    /// size (1: full size; a name longer than its side is shrunk).
    pub axis_names: f64,
    /// The legend's entries, in order: what each says and how it is drawn.
    pub keys: Vec<LegendKey>,
}

/// One legend entry: its text and its swatch (colour, line style, mark).
#[derive(Debug, Clone, PartialEq)]
pub struct LegendKey {
    pub label: String,
    /// `(r, g, b)`.
    pub color: (u8, u8, u8),
    pub style: Style,
    /// The mark drawn, if the style draws marks.
    pub marker: Option<Marker>,
    pub hollow: bool,
}

impl LegendKey {
    /// The swatch alone: two keys with the same swatch look the same.
    fn swatch(&self) -> ((u8, u8, u8), Style, Option<Marker>, bool) {
        (self.color, self.style, self.marker, self.hollow)
    }
}

/// The least share of the label size an axis name may be shrunk to (the
/// referee read the names shrunk to 45-55% as about 6 pt).
pub const MIN_NAME_SHARE: f64 = 0.6;

/// Pairs of entries of one legend `keys` that draw the same swatch for
/// different texts (a reader cannot tell which is which).
pub fn same_swatch_two_meanings(keys: &[LegendKey]) -> Vec<String> {
    let mut out = vec![];
    for (i, a) in keys.iter().enumerate() {
        for b in &keys[i + 1..] {
            if a.swatch() == b.swatch() && a.label != b.label {
                out.push(format!(
                    "one legend swatch for two meanings: '{}' and '{}'",
                    a.label, b.label
                ));
            }
        }
    }
    out
}

/// The least share of an axis's range (decades on a log axis) its data
/// must span.
pub const MIN_FILL: f64 = 0.5;

impl PanelLayout {
    /// The share of each axis's range that the data span.
    pub fn fill(&self) -> (f64, f64) {
        let share = |(a, b): (f64, f64), (lo, hi): (f64, f64)| (b - a) / (hi - lo);
        self.data.map_or((0.0, 0.0), |(dx, dy)| {
            (share(dx, self.x), share(dy, self.y))
        })
    }

    /// What is wrong with this panel: data spanning less than
    /// [`MIN_FILL`] of an axis (of either one for equal scales, which fix
    /// the other), or a box over data. Empty when nothing is.
    pub fn problems(&self) -> Vec<String> {
        let mut out = vec![];
        let (fx, fy) = self.fill();
        let unit = |log: bool| if log { " (decades)" } else { "" };
        if self.data.is_none() {
            out.push("no data drawn".to_string());
        } else if self.equal_aspect {
            if fx.max(fy) < MIN_FILL {
                out.push(format!(
                    "the data span {:.0}% of x and {:.0}% of y (equal scales)",
                    100.0 * fx,
                    100.0 * fy
                ));
            }
        } else {
            for (name, f, log) in [("x", fx, self.log_x), ("y", fy, self.log_y)] {
                if f < MIN_FILL {
                    out.push(format!(
                        "the data span {:.0}% of the {name} axis{}",
                        100.0 * f,
                        unit(log)
                    ));
                }
            }
        }
        if self.hidden > 0 {
            out.push(format!(
                "the legend or note covers {} data samples",
                self.hidden
            ));
        }
        out.extend(same_swatch_two_meanings(&self.keys));
        if self.axis_names < MIN_NAME_SHARE {
            out.push(format!(
                "an axis name set at {:.0}% of the label size (shorten it)",
                100.0 * self.axis_names
            ));
        }
        out
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

/// The plan of `p` drawn alone on [`LINE_PLOT_SIZE`] at the SVG's scale.
pub(crate) fn single_plan(p: &LinePlot) -> Plan {
    let sizes = Sizes::STANDARD;
    let (w, h) = LINE_PLOT_SIZE;
    let title_h = layout::title_height(&sizes, p.title) as u32;
    Plan::new(p, &sizes, (w, h - title_h))
}

/// The layout [`line_plot`](crate::line_plot) draws `p` with: where its legend and note box go.
pub fn line_plot_boxes(p: &LinePlot) -> Result<LinePlotBoxes, FigureError> {
    font::ensure_registered()?;
    let plan = single_plan(p);
    Ok(LinePlotBoxes {
        plot: plan.plot,
        legend: plan.boxes.legend,
        note: plan.boxes.note,
        hidden: plan.boxes.hidden,
    })
}
