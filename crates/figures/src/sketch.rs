//! The schematic of the problem (report Fig. 1): a chain of n rods hangs
//! from P0 and P1; P1's end is released and falls under gravity.

use std::path::Path;

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::colormap::{cool, P0_RED, P1_BLUE};
use crate::font;
use crate::output::{self, Draw};
use crate::sizes::Sizes;
use crate::{FigureError, Output};

/// Canvas of the sketch.
pub const SKETCH_SIZE: (u32, u32) = (1200, 900);

/// Draw the schematic to `<stem>.png` and `<stem>.svg`.
pub fn sketch(stem: &Path) -> Result<Output, FigureError> {
    font::ensure_registered()?;
    output::save(&Sketch::new(), stem)
}

/// Geometry of the drawing, in chain units (y up).
struct Sketch {
    p0: (f64, f64),
    p1: (f64, f64),
    /// Joints of the hanging chain.
    hanging: Vec<(f64, f64)>,
    /// Where the arrow of the released end's fall ends (no later shape is
    /// drawn: the falling chain does not keep the hanging one's U; its
    /// shapes are Figs. 3 to 12).
    fall_to: (f64, f64),
}

const D: f64 = 3.6;
const H: f64 = 1.2;
const L: f64 = 6.0;
const RODS: usize = 12;

impl Sketch {
    fn new() -> Sketch {
        let hanging = catenary_joints(D, H, L, RODS);
        Sketch {
            p0: (0.0, 0.0),
            p1: (D, H),
            hanging,
            fall_to: (D + 0.3, H - 2.5),
        }
    }
}

/// Joints of `n` equal rods along the catenary of length `l` from (0, 0)
/// to (d, h).
fn catenary_joints(d: f64, h: f64, l: f64, n: usize) -> Vec<(f64, f64)> {
    // sqrt(l^2 - h^2) = 2 a sinh(d / 2a), solved for a by bisection.
    let target = (l * l - h * h).sqrt();
    let f = |a: f64| 2.0 * a * (d / (2.0 * a)).sinh() - target;
    let (mut lo, mut hi) = (1e-3, 1e3);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let a = 0.5 * (lo + hi);
    let x0 = 0.5 * d - a * (h / l).atanh();
    let y = |x: f64| a * ((x - x0) / a).cosh() - a * (x0 / a).cosh();
    // Arc length from 0 to x.
    let s = |x: f64| a * (((x - x0) / a).sinh() + (x0 / a).sinh());
    let mut joints = vec![(0.0, 0.0)];
    for k in 1..n {
        let want = l * k as f64 / n as f64;
        let (mut lo, mut hi) = (0.0, d);
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if s(mid) < want {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let x = 0.5 * (lo + hi);
        joints.push((x, y(x)));
    }
    joints.push((d, h));
    joints
}

/// Affine map from chain units to pixels, same scale on both axes.
struct ToPx {
    s: f64,
    ox: f64,
    oy: f64,
}

impl ToPx {
    fn p(&self, (x, y): (f64, f64)) -> (i32, i32) {
        (
            (self.ox + self.s * x).round() as i32,
            (self.oy - self.s * y).round() as i32,
        )
    }
}

fn arrow<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    from: (i32, i32),
    to: (i32, i32),
    color: RGBColor,
    width: u32,
    head: i32,
    both: bool,
) -> Result<(), FigureError> {
    let (dx, dy) = ((to.0 - from.0) as f64, (to.1 - from.1) as f64);
    let len = dx.hypot(dy).max(1.0);
    let (ux, uy) = (dx / len, dy / len);
    let h = head as f64;
    let tip = |p: (i32, i32), sx: f64, sy: f64| {
        let base = (p.0 as f64 - sx * h, p.1 as f64 - sy * h);
        vec![
            p,
            (
                (base.0 - sy * 0.45 * h) as i32,
                (base.1 + sx * 0.45 * h) as i32,
            ),
            (
                (base.0 + sy * 0.45 * h) as i32,
                (base.1 - sx * 0.45 * h) as i32,
            ),
        ]
    };
    let start = if both {
        (
            from.0 + (ux * h * 0.8) as i32,
            from.1 + (uy * h * 0.8) as i32,
        )
    } else {
        from
    };
    let end = (to.0 - (ux * h * 0.8) as i32, to.1 - (uy * h * 0.8) as i32);
    area.draw(&PathElement::new(
        vec![start, end],
        color.stroke_width(width),
    ))?;
    area.draw(&Polygon::new(tip(to, ux, uy), color.filled()))?;
    if both {
        area.draw(&Polygon::new(tip(from, -ux, -uy), color.filled()))?;
    }
    Ok(())
}

impl Draw for Sketch {
    fn size(&self) -> (u32, u32) {
        SKETCH_SIZE
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: u32,
    ) -> Result<(), FigureError> {
        let t = Sizes::STANDARD.scaled(scale);
        root.fill(&WHITE)?;
        let (w, h) = root.dim_in_pixel();
        // Chain-unit box to show, then fit it with equal scales.
        let (x0, x1) = (-2.0, D + 2.5);
        let ymin = self
            .hanging
            .iter()
            .chain(std::iter::once(&self.fall_to))
            .fold(0.0f64, |m, p| m.min(p.1));
        let (y0, y1) = (ymin - 0.3, H + 1.0);
        let m = 30.0 * t.scale;
        let s = ((w as f64 - 2.0 * m) / (x1 - x0)).min((h as f64 - 2.0 * m) / (y1 - y0));
        let ox = w as f64 / 2.0 - s * (x0 + x1) / 2.0;
        let oy = h as f64 / 2.0 + s * (y0 + y1) / 2.0;
        let px = ToPx { s, ox, oy };

        let grey = RGBColor(130, 130, 130);
        let ink = RGBColor(40, 40, 40);
        let text = |size: f64, h: HPos, v: VPos| t.font(size).pos(Pos::new(h, v));
        let big = t.label() * 1.1;
        let dashed = |pts: Vec<(i32, i32)>, color: RGBColor, width: i32| {
            DashedPathElement::new(pts, t.px(12.0), t.px(9.0), color.stroke_width(width as u32))
        };

        // Guides: the levels of P0 and P1, the verticals through them.
        let p0 = px.p(self.p0);
        let p1 = px.p(self.p1);
        let hx = D + 1.15;
        root.draw(&dashed(vec![p0, px.p((hx + 0.15, 0.0))], grey, t.px(2.0)))?;
        root.draw(&dashed(vec![p1, px.p((hx + 0.15, H))], grey, t.px(2.0)))?;
        for p in [self.p0, self.p1] {
            root.draw(&dashed(
                vec![px.p(p), px.p((p.0, H + 0.75))],
                grey,
                t.px(2.0),
            ))?;
        }

        // d and h.
        let dim = RGBColor(60, 60, 60);
        arrow(
            root,
            px.p((0.0, H + 0.6)),
            px.p((D, H + 0.6)),
            dim,
            t.px(3.0) as u32,
            t.px(20.0),
            true,
        )?;
        root.draw(&Text::new(
            "d",
            px.p((D / 2.0, H + 0.68)),
            text(big, HPos::Center, VPos::Bottom),
        ))?;
        arrow(
            root,
            px.p((hx, 0.0)),
            px.p((hx, H)),
            dim,
            t.px(3.0) as u32,
            t.px(20.0),
            true,
        )?;
        root.draw(&Text::new(
            "h",
            px.p((hx + 0.12, H / 2.0)),
            text(big, HPos::Left, VPos::Center),
        ))?;

        // The path of the released end.
        let end = self.fall_to;
        let fall = cool(1.0);
        arrow(
            root,
            px.p((D + 0.3, H - 0.2)),
            px.p((end.0 + 0.3, end.1 + 0.1)),
            fall,
            t.px(4.0) as u32,
            t.px(24.0),
            false,
        )?;
        root.draw(&Text::new(
            "released end falls",
            px.p((end.0 + 0.5, end.1 + 0.45)),
            text(t.legend(), HPos::Left, VPos::Center),
        ))?;

        // The hanging chain: rods and joints.
        let joints: Vec<(i32, i32)> = self.hanging.iter().map(|&p| px.p(p)).collect();
        root.draw(&PathElement::new(
            joints.clone(),
            ink.stroke_width(t.px(5.0) as u32),
        ))?;
        for &j in &joints[1..joints.len() - 1] {
            root.draw(&Circle::new(j, t.px(6.0), ink.filled()))?;
        }
        root.draw(&Text::new(
            "L = n·l,  mass m per rod",
            px.p((0.5 * D, -0.45)),
            text(t.legend(), HPos::Center, VPos::Center),
        ))?;

        // Anchors.
        for (p, color) in [(p0, P0_RED), (p1, P1_BLUE)] {
            root.draw(&Circle::new(p, t.px(12.0), color.filled()))?;
            root.draw(&Circle::new(
                p,
                t.px(12.0),
                BLACK.stroke_width(t.px(2.0) as u32),
            ))?;
        }
        root.draw(&Text::new(
            "P₀, fixed",
            (p0.0 - t.px(20.0), p0.1 - t.px(16.0)),
            text(big, HPos::Right, VPos::Bottom),
        ))?;
        root.draw(&Text::new(
            "P₁ = P₀ + (d, h), released at t = 0",
            (p1.0 - t.px(22.0), p1.1 - t.px(14.0)),
            text(t.legend(), HPos::Right, VPos::Bottom),
        ))?;

        // Gravity.
        arrow(
            root,
            px.p((-1.4, 0.3)),
            px.p((-1.4, -1.3)),
            ink,
            t.px(4.0) as u32,
            t.px(26.0),
            false,
        )?;
        root.draw(&Text::new(
            "g",
            px.p((-1.25, -0.5)),
            text(big, HPos::Left, VPos::Center),
        ))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn catenary_rods_have_equal_length() {
        let j = catenary_joints(D, H, L, RODS);
        assert_eq!(j.len(), RODS + 1);
        let lens: Vec<f64> = j
            .windows(2)
            .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
            .collect();
        let total: f64 = lens.iter().sum();
        // Chords of equal arcs: slightly shorter than L / n, all alike.
        assert!(total < L && total > 0.98 * L, "{total}");
        let (lo, hi) = lens
            .iter()
            .fold((f64::MAX, 0.0f64), |(a, b), &l| (a.min(l), b.max(l)));
        assert!(hi - lo < 1e-2, "{lens:?}");
        assert!(j.iter().any(|p| p.1 < -1.0), "the chain sags");
    }
}
