//! Where a chart sits on its canvas: margins and label areas, the title
//! above it, equal axis scales, and the bounds of the data.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::sizes::Sizes;
use crate::FigureError;

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
    pub fn standard(sizes: &Sizes, y_label_width: i32) -> Layout {
        Layout {
            top: sizes.px(20.0),
            right: sizes.px(30.0),
            bottom: sizes.px(10.0),
            left: sizes.px(10.0),
            x_area: (sizes.tick() + sizes.label() * 1.3 + sizes.px(22.0) as f64) as i32,
            y_area: y_label_width + (sizes.label() * 1.3) as i32 + sizes.px(24.0),
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

/// Draw `title` centred at the top of `area` and return the area below it.
pub(crate) fn titled<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    sizes: &Sizes,
    title: &str,
) -> Result<DrawingArea<DB, Shift>, FigureError> {
    if title.is_empty() {
        return Ok(area.clone());
    }
    let size = sizes.title();
    let h = (size * 1.6) as i32;
    let (w, _) = area.dim_in_pixel();
    let style = sizes.font(size).pos(Pos::new(HPos::Center, VPos::Center));
    area.draw(&Text::new(
        title.to_string(),
        (w as i32 / 2, h / 2 + sizes.px(8.0)),
        style,
    ))?;
    let (_, rest) = area.split_vertically(h + sizes.px(8.0));
    Ok(rest)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_scales() {
        let (x, y) = equalize((0.0, 1.0), (0.0, 1.0), (200, 100));
        assert!(((x.1 - x.0) / 200.0 - (y.1 - y.0) / 100.0).abs() < 1e-12);
        assert!((x.1 - x.0 - 2.0).abs() < 1e-12 && (y.1 - y.0 - 1.0).abs() < 1e-12);
    }
}
