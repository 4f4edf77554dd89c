//! Shared plot machinery: sizes (the theme), axis ranges and ticks with
//! their labels, linear and logarithmic axes, equal scales, the frame of a
//! chart, clipping of polylines to the axes, and placing boxes (legend,
//! notes) where they hide the least data.
//!
//! Logarithmic axes are drawn as linear axes over `log10` of the data with
//! our own key points, so every chart has one coordinate type and tick
//! labels are exactly the powers of ten.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontDesc;

use crate::font::FAMILY;
use crate::FigureError;

/// The coordinate type of every chart in this crate: linear over plot
/// space with our own ticks (bold key points) and minor grid lines (light).
#[derive(Debug, Clone)]
pub(crate) struct Coord {
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
    minor: Vec<f64>,
}

impl Ranged for Coord {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let t = ((v - self.lo) / (self.hi - self.lo)).clamp(-1e4, 1e4);
        let t = if t.is_nan() { 0.0 } else { t };
        limit.0 + (f64::from(limit.1 - limit.0) * t).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.ticks.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}
pub(crate) type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<Coord, Coord>>;

/// Sizes of text and lines, in pixels, for a canvas about 900 px tall.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Theme {
    pub k: f64,
}

impl Theme {
    pub const STANDARD: Theme = Theme { k: 1.0 };

    /// This theme on a canvas `s` times larger.
    pub fn scaled(self, s: u32) -> Theme {
        Theme {
            k: self.k * f64::from(s),
        }
    }

    /// plotters' font size is the line height (ascent + descent); the em is
    /// about 0.86 of it, so a tick label of 28 has an em of about 24 px.
    pub fn title(&self) -> f64 {
        40.0 * self.k
    }
    pub fn label(&self) -> f64 {
        34.0 * self.k
    }
    pub fn tick(&self) -> f64 {
        28.0 * self.k
    }
    pub fn legend(&self) -> f64 {
        28.0 * self.k
    }
    pub fn note(&self) -> f64 {
        26.0 * self.k
    }
    /// Width of a data line.
    pub fn line(&self) -> u32 {
        self.px(3.0) as u32
    }
    /// Width of axes and frames.
    pub fn axis(&self) -> u32 {
        self.px(2.0) as u32
    }
    pub fn px(&self, v: f64) -> i32 {
        (v * self.k).round().max(1.0) as i32
    }
    pub fn font(&self, size: f64) -> TextStyle<'static> {
        TextStyle::from(FontDesc::new(
            FontFamily::Name(FAMILY),
            size,
            FontStyle::Normal,
        ))
    }
}

/// Width in pixels of `text` in the embedded font at `size`.
pub(crate) fn text_width(text: &str, size: f64) -> i32 {
    FontDesc::new(FontFamily::Name(FAMILY), size, FontStyle::Normal)
        .box_size(text)
        .map(|(w, _)| w as i32)
        .unwrap_or_else(|_| (text.chars().count() as f64 * 0.6 * size) as i32)
}

/// One axis: its range and ticks in plot space (`log10` of the data on a
/// log axis) and the tick labels.
#[derive(Debug, Clone)]
pub(crate) struct Axis {
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
    pub ticks: Vec<f64>,
    pub labels: Vec<String>,
    /// Minor grid lines (log axes: 2..9 times each decade).
    pub minor: Vec<f64>,
}

impl Axis {
    /// A linear axis over `[lo, hi]` with about `target` ticks.
    pub fn linear(lo: f64, hi: f64, target: usize) -> Axis {
        let (lo, hi) = nondegenerate(lo, hi);
        let ticks_for = |n: usize| {
            let step = nice_step((hi - lo) / n as f64);
            let first = (lo / step - 1e-9).ceil() as i64;
            let last = (hi / step + 1e-9).floor() as i64;
            let ticks: Vec<f64> = (first..=last).map(|i| i as f64 * step).collect();
            (step, ticks)
        };
        // At least three labelled ticks, whatever the range.
        let mut n = target.max(2);
        let (mut step, mut ticks) = ticks_for(n);
        while ticks.len() < 3 && n < 12 {
            n += 1;
            (step, ticks) = ticks_for(n);
        }
        let labels = linear_labels(&ticks, step);
        Axis {
            lo,
            hi,
            log: false,
            ticks,
            labels,
            minor: Vec::new(),
        }
    }

    /// A log axis over `[lo, hi]` given in `log10` units.
    pub fn log(lo: f64, hi: f64, target: usize) -> Axis {
        let (lo, hi) = nondegenerate(lo, hi);
        let first = (lo - 1e-9).ceil() as i64;
        let last = (hi + 1e-9).floor() as i64;
        let count = (last - first + 1).max(0) as usize;
        let every = count.div_ceil(target.max(2)).max(1) as i64;
        let ticks: Vec<f64> = (first..=last)
            .filter(|k| k.rem_euclid(every) == 0)
            .map(|k| k as f64)
            .collect();
        let labels = ticks.iter().map(|&k| power_of_ten(k as i64)).collect();
        let mut minor = Vec::new();
        if every == 1 && count <= 8 {
            for k in (first - 1)..=last {
                for j in 2..=9 {
                    let v = k as f64 + (j as f64).log10();
                    if v > lo && v < hi {
                        minor.push(v);
                    }
                }
            }
        }
        Axis {
            lo,
            hi,
            log: true,
            ticks,
            labels,
            minor,
        }
    }

    /// Choose a range for data values in `[min, max]` (data space), padded
    /// by `pad` of the span, or exactly `fixed` if given.
    pub fn auto(
        min: f64,
        max: f64,
        fixed: Option<(f64, f64)>,
        log: bool,
        pad: f64,
        target: usize,
    ) -> Axis {
        if log {
            let (lo, hi) = match fixed {
                Some((a, b)) if a > 0.0 && b > 0.0 => (a.log10(), b.log10()),
                _ => log_range(min, max, pad),
            };
            Axis::log(lo, hi, target)
        } else {
            let (lo, hi) = fixed.unwrap_or_else(|| {
                let (lo, hi) = nondegenerate(min, max);
                let p = (hi - lo) * pad;
                (lo - p, hi + p)
            });
            Axis::linear(lo, hi, target)
        }
    }

    /// Data value to plot space; `None` if it cannot be shown.
    pub fn to_plot(&self, v: f64) -> Option<f64> {
        let p = if self.log {
            if v > 0.0 {
                v.log10()
            } else {
                return None;
            }
        } else {
            v
        };
        p.is_finite().then_some(p)
    }

    pub fn span(&self) -> f64 {
        self.hi - self.lo
    }

    /// The label of the tick nearest to `v` (for plotters' formatter).
    pub fn label_at(&self, v: f64) -> String {
        let tol = 1e-6 * self.span().abs();
        self.ticks
            .iter()
            .position(|t| (t - v).abs() <= tol)
            .map(|i| self.labels[i].clone())
            .unwrap_or_default()
    }

    pub fn coord(&self) -> Coord {
        Coord {
            lo: self.lo,
            hi: self.hi,
            ticks: self.ticks.clone(),
            minor: self.minor.clone(),
        }
    }

    /// Widest tick label in pixels.
    pub fn max_label_width(&self, size: f64) -> i32 {
        self.labels
            .iter()
            .map(|l| text_width(l, size))
            .max()
            .unwrap_or(0)
    }
}

fn nondegenerate(lo: f64, hi: f64) -> (f64, f64) {
    let (lo, hi) = if lo.is_finite() && hi.is_finite() {
        (lo.min(hi), lo.max(hi))
    } else {
        (0.0, 1.0)
    };
    if hi - lo > 1e-12 * lo.abs().max(hi.abs()) && hi > lo {
        (lo, hi)
    } else {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        (lo - d, hi + d)
    }
}

/// A log range (log10 units) that always holds at least two powers of ten.
fn log_range(min: f64, max: f64, pad: f64) -> (f64, f64) {
    if !(min > 0.0 && max > 0.0 && min.is_finite() && max.is_finite()) {
        return (0.0, 1.0);
    }
    let (a, b) = (min.log10(), max.log10());
    let p = (b - a) * pad;
    let (lo, hi) = (a - p, b + p);
    if hi.floor() - lo.ceil() >= 1.0 {
        (lo, hi)
    } else {
        // Less than two decades inside: widen to whole decades.
        let lo = lo.floor();
        let hi = hi.ceil().max(lo + 1.0);
        (lo, hi)
    }
}

/// 1, 2, 2.5 or 5 times a power of ten, at least `raw`.
pub(crate) fn nice_step(raw: f64) -> f64 {
    let raw = if raw.is_finite() && raw > 0.0 {
        raw
    } else {
        1.0
    };
    let e = raw.log10().floor();
    let base = 10f64.powf(e);
    let m = raw / base;
    let nice = if m <= 1.0 + 1e-9 {
        1.0
    } else if m <= 2.0 + 1e-9 {
        2.0
    } else if m <= 2.5 + 1e-9 {
        2.5
    } else if m <= 5.0 + 1e-9 {
        5.0
    } else {
        10.0
    };
    nice * base
}

const SUPERSCRIPT: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];

fn superscript(k: i64) -> String {
    let mut s = String::new();
    if k < 0 {
        s.push('⁻');
    }
    for d in k.unsigned_abs().to_string().bytes() {
        s.push(SUPERSCRIPT[(d - b'0') as usize]);
    }
    s
}

/// "10³", "10⁻⁴".
pub(crate) fn power_of_ten(k: i64) -> String {
    format!("10{}", superscript(k))
}

/// Typographic minus for negative numbers.
fn minus(s: String) -> String {
    if let Some(rest) = s.strip_prefix('-') {
        format!("−{rest}")
    } else {
        s
    }
}

/// Labels for ticks `step` apart: plain decimals, or "m×10ᵏ" for very
/// small or large values.
fn linear_labels(ticks: &[f64], step: f64) -> Vec<String> {
    let max_abs = ticks.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    let step_exp = step.log10().floor() as i64;
    // 0.25, 2.5 need one digit more than their power of ten; 25 does not.
    let extra = usize::from(is_two_and_half(step) && step_exp <= 0);
    let sci = max_abs >= 1e5 || step < 1e-3;
    ticks
        .iter()
        .map(|&t| {
            let zero = t.abs() < step * 1e-6;
            if sci {
                if zero {
                    return "0".to_string();
                }
                let e = t.abs().log10().floor() as i64;
                let m = t / 10f64.powi(e as i32);
                let decimals =
                    (e - step_exp).clamp(0, 6) as usize + usize::from(is_two_and_half(step));
                let m = trim_zeros(format!("{m:.decimals$}"));
                minus(format!("{m}×{}", power_of_ten(e)))
            } else {
                let decimals = (-step_exp).max(0) as usize + extra;
                // No "−0.0".
                let t = if zero { 0.0 } else { t };
                minus(format!("{t:.decimals$}"))
            }
        })
        .collect()
}

fn is_two_and_half(step: f64) -> bool {
    let m = step / 10f64.powf(step.log10().floor());
    (m - 2.5).abs() < 1e-6
}

fn trim_zeros(s: String) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Format a number for text (legends, notes): up to `sig` significant
/// digits, typographic minus.
pub fn format_number(v: f64, sig: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let e = v.abs().log10().floor() as i64;
    if !(-3..5).contains(&e) {
        let m = v / 10f64.powi(e as i32);
        let m = trim_zeros(format!("{m:.*}", sig.saturating_sub(1)));
        return minus(format!("{m}×{}", power_of_ten(e)));
    }
    let decimals = (sig as i64 - 1 - e).max(0) as usize;
    minus(trim_zeros(format!("{v:.decimals$}")))
}

/// Expand the shorter range so both axes have the same data units per pixel.
pub(crate) fn equalize(
    x: (f64, f64),
    y: (f64, f64),
    (pw, ph): (i32, i32),
) -> ((f64, f64), (f64, f64)) {
    let (pw, ph) = (pw.max(1) as f64, ph.max(1) as f64);
    let sx = (x.1 - x.0) / pw;
    let sy = (y.1 - y.0) / ph;
    let s = sx.max(sy);
    let grow = |r: (f64, f64), n: f64| {
        let c = 0.5 * (r.0 + r.1);
        (c - 0.5 * s * n, c + 0.5 * s * n)
    };
    (grow(x, pw), grow(y, ph))
}

/// Bounds of finite points: (xmin, xmax, ymin, ymax).
pub(crate) fn bounds<'a, I: IntoIterator<Item = &'a (f64, f64)>>(
    pts: I,
) -> Option<(f64, f64, f64, f64)> {
    let mut b: Option<(f64, f64, f64, f64)> = None;
    for &(x, y) in pts {
        if !(x.is_finite() && y.is_finite()) {
            continue;
        }
        b = Some(match b {
            None => (x, x, y, y),
            Some((a, bb, c, d)) => (a.min(x), bb.max(x), c.min(y), d.max(y)),
        });
    }
    b
}

/// Margins and label areas of a chart, in pixels.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Layout {
    pub top: i32,
    pub right: i32,
    pub bottom: i32,
    pub left: i32,
    /// Height of the area under the plot (tick labels and x label).
    pub x_area: i32,
    /// Width of the area left of the plot (tick labels and y label).
    pub y_area: i32,
}

impl Layout {
    /// Standard margins; the y area fits `y_label_width` px tick labels.
    pub fn standard(theme: &Theme, y_label_width: i32) -> Layout {
        Layout {
            top: theme.px(20.0),
            right: theme.px(30.0),
            bottom: theme.px(10.0),
            left: theme.px(10.0),
            x_area: (theme.tick() + theme.label() * 1.3 + theme.px(22.0) as f64) as i32,
            y_area: y_label_width + (theme.label() * 1.3) as i32 + theme.px(24.0),
        }
    }

    /// Plot area size inside a `(w, h)` area.
    pub fn plot_size(&self, (w, h): (u32, u32)) -> (i32, i32) {
        (
            w as i32 - self.left - self.right - self.y_area,
            h as i32 - self.top - self.bottom - self.x_area,
        )
    }
}

/// Build a chart with axes `x`, `y` and draw its grid, ticks, labels and
/// axis names.
pub(crate) fn chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    theme: &Theme,
    layout: &Layout,
    x: &Axis,
    y: &Axis,
    x_desc: &str,
    y_desc: &str,
) -> Result<Chart<'a, DB>, FigureError> {
    let mut chart = ChartBuilder::on(area)
        .margin_top(layout.top)
        .margin_right(layout.right)
        .margin_bottom(layout.bottom)
        .margin_left(layout.left)
        .x_label_area_size(layout.x_area)
        .y_label_area_size(layout.y_area)
        .build_cartesian_2d(x.coord(), y.coord())?;
    let fx = |v: &f64| x.label_at(*v);
    let fy = |v: &f64| y.label_at(*v);
    chart
        .configure_mesh()
        .bold_line_style(RGBColor(220, 220, 220).stroke_width(theme.px(1.0) as u32))
        .light_line_style(RGBColor(240, 240, 240).stroke_width(theme.px(1.0) as u32))
        .axis_style(BLACK.stroke_width(theme.axis()))
        .set_all_tick_mark_size(theme.px(8.0))
        .label_style(theme.font(theme.tick()))
        .axis_desc_style(theme.font(theme.label()))
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()?;
    Ok(chart)
}

/// Close the frame around the plot area: plotters draws the left and
/// bottom axes, this adds the top and right sides.
pub(crate) fn frame<DB: DrawingBackend>(
    chart: &Chart<'_, DB>,
    theme: &Theme,
) -> Result<(), FigureError> {
    let pa = chart.plotting_area().strip_coord_spec();
    let (w, h) = pa.dim_in_pixel();
    let (w, h) = (w as i32 - 1, h as i32 - 1);
    pa.draw(&PathElement::new(
        vec![(0, 0), (w, 0), (w, h)],
        BLACK.stroke_width(theme.axis()),
    ))?;
    Ok(())
}

/// Split a polyline (plot space) into the pieces inside the rectangle
/// `[x0, x1] x [y0, y1]`; `None` points break the line.
pub(crate) fn clip_polyline(
    pts: &[Option<(f64, f64)>],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let inside = |p: (f64, f64)| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1;
    if pts.len() == 1 {
        if let Some(p) = pts[0] {
            if inside(p) {
                out.push(vec![p]);
            }
        }
        return out;
    }
    for w in pts.windows(2) {
        let (Some(a), Some(b)) = (w[0], w[1]) else {
            if cur.len() > 1 {
                out.push(std::mem::take(&mut cur));
            }
            cur.clear();
            continue;
        };
        match clip_segment(a, b, (x0, x1), (y0, y1)) {
            Some((ca, cb)) => {
                if cur.last() != Some(&ca) {
                    if cur.len() > 1 {
                        out.push(std::mem::take(&mut cur));
                    }
                    cur.clear();
                    cur.push(ca);
                }
                cur.push(cb);
                if cb != b {
                    out.push(std::mem::take(&mut cur));
                }
            }
            None => {
                if cur.len() > 1 {
                    out.push(std::mem::take(&mut cur));
                }
                cur.clear();
            }
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// Liang-Barsky clipping of the segment `a`-`b`.
fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let mut t0 = 0.0f64;
    let mut t1 = 1.0f64;
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            a
        } else if t == 1.0 {
            b
        } else {
            (a.0 + t * dx, a.1 + t * dy)
        }
    };
    Some((at(t0), at(t1)))
}

/// A corner of the plot area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Corner {
    UpperRight,
    UpperLeft,
    LowerLeft,
    LowerRight,
}

impl Corner {
    pub const ALL: [Corner; 4] = [
        Corner::UpperRight,
        Corner::UpperLeft,
        Corner::LowerLeft,
        Corner::LowerRight,
    ];
}

/// Where the data is, in pixels of the plot area: samples along every
/// polyline at most `step` px apart.
pub(crate) struct Occupancy {
    samples: Vec<(f64, f64)>,
}

impl Occupancy {
    pub fn new(lines: &[Vec<(f64, f64)>], x: &Axis, y: &Axis, (pw, ph): (i32, i32)) -> Occupancy {
        let to_px = |p: (f64, f64)| {
            (
                (p.0 - x.lo) / x.span() * pw as f64,
                (y.hi - p.1) / y.span() * ph as f64,
            )
        };
        let mut samples = Vec::new();
        for line in lines {
            let px: Vec<(f64, f64)> = line.iter().map(|&p| to_px(p)).collect();
            if let Some(&first) = px.first() {
                samples.push(first);
            }
            for w in px.windows(2) {
                let (a, b) = (w[0], w[1]);
                let n = ((b.0 - a.0).hypot(b.1 - a.1) / 6.0)
                    .ceil()
                    .clamp(1.0, 400.0) as usize;
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    samples.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
                }
            }
        }
        Occupancy { samples }
    }

    /// Top-left pixel of a `(bw, bh)` box in `corner`, `inset` px from the edges.
    pub fn origin(
        corner: Corner,
        (bw, bh): (i32, i32),
        (pw, ph): (i32, i32),
        inset: i32,
    ) -> (i32, i32) {
        match corner {
            Corner::UpperRight => (pw - inset - bw, inset),
            Corner::UpperLeft => (inset, inset),
            Corner::LowerLeft => (inset, ph - inset - bh),
            Corner::LowerRight => (pw - inset - bw, ph - inset - bh),
        }
    }

    /// The corner (not in `taken`) where a box of `size` covers the fewest
    /// samples; ties go to the order of [`Corner::ALL`].
    pub fn best(&self, size: (i32, i32), plot: (i32, i32), inset: i32, taken: &[Corner]) -> Corner {
        self.best_with_count(size, plot, inset, taken).0
    }

    /// [`Occupancy::best`] and how many samples that box still covers.
    pub fn best_with_count(
        &self,
        size: (i32, i32),
        plot: (i32, i32),
        inset: i32,
        taken: &[Corner],
    ) -> (Corner, usize) {
        let pad = 6.0;
        let mut best = (usize::MAX, Corner::UpperRight);
        for c in Corner::ALL {
            if taken.contains(&c) {
                continue;
            }
            let (ox, oy) = Self::origin(c, size, plot, inset);
            let (x0, y0) = (ox as f64 - pad, oy as f64 - pad);
            let (x1, y1) = (
                x0 + size.0 as f64 + 2.0 * pad,
                y0 + size.1 as f64 + 2.0 * pad,
            );
            let n = self
                .samples
                .iter()
                .filter(|p| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1)
                .count();
            if n < best.0 {
                best = (n, c);
            }
        }
        (best.1, best.0)
    }
}

/// How a legend entry is drawn.
#[derive(Debug, Clone)]
pub(crate) enum Swatch {
    Line {
        color: RGBColor,
        width: u32,
        dashed: bool,
    },
    Marker {
        color: RGBColor,
        radius: i32,
    },
    LineMarker {
        color: RGBColor,
        width: u32,
        radius: i32,
    },
}

/// Size in pixels of a legend (or, with no swatches, a note box).
pub(crate) fn box_size(theme: &Theme, lines: &[String], swatch: bool) -> (i32, i32) {
    let size = theme.legend();
    let row = (size * 1.25) as i32;
    let pad = theme.px(12.0);
    let sw = if swatch {
        theme.px(56.0) + theme.px(12.0)
    } else {
        0
    };
    let tw = lines.iter().map(|l| text_width(l, size)).max().unwrap_or(0);
    (2 * pad + sw + tw, 2 * pad + row * lines.len() as i32)
}

/// Draw a legend (entries with swatches) or a note box (no swatches) with
/// its top-left corner at `origin` in plot-area pixels.
pub(crate) fn draw_box<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    theme: &Theme,
    origin: (i32, i32),
    entries: &[(String, Option<Swatch>)],
) -> Result<(), FigureError> {
    let lines: Vec<String> = entries.iter().map(|e| e.0.clone()).collect();
    let has_swatch = entries.iter().any(|e| e.1.is_some());
    let (bw, bh) = box_size(theme, &lines, has_swatch);
    let (ox, oy) = origin;
    area.draw(&Rectangle::new(
        [(ox, oy), (ox + bw, oy + bh)],
        WHITE.mix(0.9).filled(),
    ))?;
    area.draw(&Rectangle::new(
        [(ox, oy), (ox + bw, oy + bh)],
        RGBColor(120, 120, 120).stroke_width(theme.px(1.0) as u32),
    ))?;
    let size = theme.legend();
    let row = (size * 1.25) as i32;
    let pad = theme.px(12.0);
    let sw_len = theme.px(56.0);
    let text_x = ox
        + pad
        + if has_swatch {
            sw_len + theme.px(12.0)
        } else {
            0
        };
    let style = theme.font(size).pos(Pos::new(HPos::Left, VPos::Center));
    for (i, (text, swatch)) in entries.iter().enumerate() {
        let cy = oy + pad + row * i as i32 + row / 2;
        let (sx0, sx1) = (ox + pad, ox + pad + sw_len);
        match swatch {
            Some(Swatch::Line {
                color,
                width,
                dashed,
            }) => {
                let st = color.stroke_width(*width);
                if *dashed {
                    area.draw(&DashedPathElement::new(
                        vec![(sx0, cy), (sx1, cy)],
                        theme.px(12.0),
                        theme.px(7.0),
                        st,
                    ))?;
                } else {
                    area.draw(&PathElement::new(vec![(sx0, cy), (sx1, cy)], st))?;
                }
            }
            Some(Swatch::Marker { color, radius }) => {
                area.draw(&Circle::new(((sx0 + sx1) / 2, cy), *radius, color.filled()))?;
            }
            Some(Swatch::LineMarker {
                color,
                width,
                radius,
            }) => {
                area.draw(&PathElement::new(
                    vec![(sx0, cy), (sx1, cy)],
                    color.stroke_width(*width),
                ))?;
                area.draw(&Circle::new(((sx0 + sx1) / 2, cy), *radius, color.filled()))?;
            }
            None => {}
        }
        area.draw(&Text::new(text.clone(), (text_x, cy), style.clone()))?;
    }
    Ok(())
}

/// Draw `title` centred at the top of `area` and return the area below it.
pub(crate) fn titled<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    theme: &Theme,
    title: &str,
) -> Result<DrawingArea<DB, Shift>, FigureError> {
    if title.is_empty() {
        return Ok(area.clone());
    }
    let size = theme.title();
    let h = (size * 1.6) as i32;
    let (w, _) = area.dim_in_pixel();
    let style = theme.font(size).pos(Pos::new(HPos::Center, VPos::Center));
    area.draw(&Text::new(
        title.to_string(),
        (w as i32 / 2, h / 2 + theme.px(8.0)),
        style,
    ))?;
    let (_, rest) = area.split_vertically(h + theme.px(8.0));
    Ok(rest)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(0.13), 0.2);
        assert_eq!(nice_step(0.9), 1.0);
        assert_eq!(nice_step(2.2), 2.5);
        assert_eq!(nice_step(30.0), 50.0);
        assert_eq!(nice_step(70.0), 100.0);
    }

    #[test]
    fn linear_ticks_and_labels() {
        let a = Axis::linear(-1.05, 6.3, 8);
        assert_eq!(a.ticks.first(), Some(&-1.0));
        assert_eq!(a.labels.first().map(String::as_str), Some("−1"));
        assert!(a.labels.contains(&"6".to_string()));
        let b = Axis::linear(0.0, 0.3, 3);
        assert_eq!(b.labels, vec!["0.0", "0.1", "0.2", "0.3"]);
        let d = Axis::linear(0.0, 100.0, 4);
        assert_eq!(d.labels, vec!["0", "25", "50", "75", "100"]);
        let f = Axis::linear(-1.6, 1.6, 3);
        assert!(f.ticks.len() >= 3, "{:?}", f.labels);
        let e = Axis::linear(-0.5, 0.5, 4);
        assert_eq!(e.labels, vec!["−0.50", "−0.25", "0.00", "0.25", "0.50"]);
        let c = Axis::linear(0.0, 5e-6, 5);
        assert!(c.labels.iter().any(|l| l == "1×10⁻⁶"), "{:?}", c.labels);
    }

    #[test]
    fn log_ticks_are_powers_of_ten() {
        let a = Axis::auto(2e-7, 3e-2, None, true, 0.03, 8);
        assert!(a.log);
        assert!(a.labels.contains(&"10⁻⁶".to_string()), "{:?}", a.labels);
        assert!(a.labels.iter().all(|l| l.starts_with("10")));
        // Less than a decade of data still gets two labelled decades.
        let b = Axis::auto(2.0, 8.0, None, true, 0.03, 8);
        assert_eq!(b.labels, vec!["10⁰", "10¹"]);
        assert!(!b.minor.is_empty());
        // Many decades: labels thinned.
        let c = Axis::auto(1e-14, 1e2, None, true, 0.0, 6);
        assert!(c.ticks.len() <= 6, "{:?}", c.labels);
    }

    #[test]
    fn numbers_format() {
        assert_eq!(format_number(2.5, 3), "2.5");
        assert_eq!(format_number(-0.126, 2), "−0.13");
        assert_eq!(format_number(1.5e-6, 2), "1.5×10⁻⁶");
        assert_eq!(power_of_ten(-12), "10⁻¹²");
    }

    #[test]
    fn equal_scales() {
        let (x, y) = equalize((0.0, 1.0), (0.0, 1.0), (200, 100));
        assert!(((x.1 - x.0) / 200.0 - (y.1 - y.0) / 100.0).abs() < 1e-12);
        assert!((x.1 - x.0 - 2.0).abs() < 1e-12 && (y.1 - y.0 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn clipping_splits_lines() {
        let pts: Vec<Option<(f64, f64)>> = vec![
            Some((-1.0, 0.5)),
            Some((0.5, 0.5)),
            Some((2.0, 0.5)),
            Some((2.0, 0.7)),
            Some((0.5, 0.7)),
            None,
            Some((0.2, 0.2)),
            Some((0.3, 0.3)),
        ];
        let pieces = clip_polyline(&pts, (0.0, 1.0), (0.0, 1.0));
        assert_eq!(pieces.len(), 3, "{pieces:?}");
        assert_eq!(pieces[0], vec![(0.0, 0.5), (0.5, 0.5), (1.0, 0.5)]);
        assert_eq!(pieces[1], vec![(1.0, 0.7), (0.5, 0.7)]);
        assert_eq!(pieces[2], vec![(0.2, 0.2), (0.3, 0.3)]);
    }

    #[test]
    fn legend_avoids_data() {
        let x = Axis::linear(0.0, 1.0, 5);
        let y = Axis::linear(0.0, 1.0, 5);
        // Data along the top edge only.
        let lines = vec![vec![(0.0, 0.95), (1.0, 0.95)]];
        let occ = Occupancy::new(&lines, &x, &y, (1000, 800));
        let c = occ.best((200, 100), (1000, 800), 10, &[]);
        assert_eq!(c, Corner::LowerLeft);
        let c2 = occ.best((200, 100), (1000, 800), 10, &[Corner::LowerLeft]);
        assert_eq!(c2, Corner::LowerRight);
    }
}
