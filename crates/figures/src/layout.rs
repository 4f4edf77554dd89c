//! Where a chart sits on its canvas: margins and label areas, the title
//! above it, equal axis scales, and the bounds of the data.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::sizes::{text_size, Sizes};
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

/// Space above a title.
fn title_margin(sizes: &Sizes) -> i32 {
    sizes.px(20.0)
}

/// Height of the band [`titled`] takes from the top of an area (0 for no
/// title): our margin, then plotters' title (its text height and a padding
/// of up to 5 px above and below).
pub(crate) fn title_height(sizes: &Sizes, title: &str) -> i32 {
    if title.is_empty() {
        return 0;
    }
    let text_h = text_size(title, sizes.title()).1;
    title_margin(sizes) + text_h + 2 * (text_h / 2).min(5)
}

/// Draw `title` centred at the top of `area` (below our margin, in the
/// band [`title_height`] takes) and return the area under it. A title
/// wider than the area is set in a smaller font, so that it never runs off
/// the canvas.
pub(crate) fn titled<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    sizes: &Sizes,
    title: &str,
) -> Result<DrawingArea<DB, Shift>, FigureError> {
    if title.is_empty() {
        return Ok(area.clone());
    }
    let (band, below) = area.split_vertically(title_height(sizes, title));
    let (w, _) = band.dim_in_pixel();
    let room = w as i32 - 2 * sizes.px(10.0);
    let size = fitted(sizes.title(), text_size(title, sizes.title()).0, room);
    let text_h = text_size(title, sizes.title()).1;
    let y = title_margin(sizes) + (text_h / 2).min(5) + text_h / 2;
    let style = sizes.font(size).pos(Pos::new(HPos::Center, VPos::Center));
    band.draw(&Text::new(title, (w as i32 / 2, y), style))?;
    Ok(below)
}

/// `size` scaled down so that a text `width` px wide at it fits in `room`
/// px (`size` itself when it fits).
pub(crate) fn fitted(size: f64, width: i32, room: i32) -> f64 {
    if width > room && width > 0 && room > 0 {
        size * f64::from(room) / f64::from(width)
    } else {
        size
    }
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
