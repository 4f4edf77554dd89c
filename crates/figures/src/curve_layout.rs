//! The layout of a coloured-curves figure (also of every frame of an
//! animation): axes with equal scales, a canvas width that follows the
//! data, room for the colour bar, and the legend's corner.

use plotters::prelude::*;

use crate::colorbar;
use crate::colormap::cool;
use crate::curves::Spec;
use crate::layout::{self, Layout};
use crate::legend;
use crate::placement::{Corner, Occupancy};
use crate::sizes::Sizes;
use crate::ticks::Axis;
use crate::FigureError;

/// Sizes and axes, fixed once per figure (also across animation frames).
#[derive(Debug, Clone)]
pub(crate) struct Geometry {
    pub sizes: Sizes,
    pub size: (u32, u32),
    pub x: Axis,
    pub y: Axis,
    pub layout: Layout,
    pub cbar_w: i32,
    pub vmin: f64,
    pub vmax: f64,
    pub cbar: Axis,
    /// Where the legend goes (the same in every animation frame).
    pub legend_corner: Corner,
}

impl Geometry {
    pub fn new(spec: &Spec, height: u32, sizes: Sizes) -> Result<Geometry, FigureError> {
        let mut pts: Vec<(f64, f64)> = spec
            .curves
            .iter()
            .flat_map(|c| c.1.iter().copied())
            .chain(spec.markers.iter().copied())
            .collect();
        pts.push(spec.p0);
        pts.extend(spec.p1);
        let (bx0, bx1, by0, by1) = layout::bounds(&pts)
            .ok_or_else(|| FigureError::Data("no finite point to draw".into()))?;
        let pad = 0.04;
        let padded = |lo: f64, hi: f64| {
            let (lo, hi) = if hi - lo <= 1e-12 * lo.abs().max(hi.abs()).max(1.0) {
                let d = 0.5 * lo.abs().max(1.0);
                (lo - d, hi + d)
            } else {
                (lo, hi)
            };
            (lo - pad * (hi - lo), hi + pad * (hi - lo))
        };
        let xr = spec.x_range.unwrap_or_else(|| padded(bx0, bx1));
        let mut yr = spec.y_range.unwrap_or_else(|| padded(by0, by1));

        let (vmin, vmax) = spec.value_range();
        let cbar = Axis::linear(vmin, vmax, 6);
        let mut g = Self::lay_out(spec, height, sizes, xr, yr, cbar.clone());

        // Where the legend goes; if it would hide data anywhere, make room
        // above the data (unless the y range is fixed).
        let lines: Vec<Vec<(f64, f64)>> = spec
            .curves
            .iter()
            .map(|c| c.1.clone())
            .chain(std::iter::once(spec.p0).chain(spec.p1).map(|p| vec![p]))
            .chain(spec.markers.iter().map(|&p| vec![p]))
            .collect();
        let legend = legend::box_size(&sizes, &legend_lines(spec), true);
        let inset = sizes.px(14.0);
        let plot = g.layout.plot_size((
            g.size.0 - g.cbar_w as u32,
            g.size.1 - layout::title_height(&sizes, spec.title) as u32,
        ));
        let occ = Occupancy::new(&lines, &g.x, &g.y, plot);
        let (corner, hidden) = occ.best_corner(legend, plot, inset);
        g.legend_corner = corner;
        if hidden > 0 && spec.y_range.is_none() {
            let extra = (legend.1 + 2 * inset) as f64 / plot.1.max(1) as f64 * (yr.1 - yr.0);
            yr.1 += extra;
            g = Self::lay_out(spec, height, sizes, xr, yr, cbar);
            g.legend_corner = if matches!(corner, Corner::UpperLeft | Corner::LowerLeft) {
                Corner::UpperLeft
            } else {
                Corner::UpperRight
            };
        }
        Ok(g)
    }

    /// Axes and canvas for data ranges `xr`, `yr`.
    fn lay_out(
        spec: &Spec,
        height: u32,
        sizes: Sizes,
        xr: (f64, f64),
        yr: (f64, f64),
        cbar: Axis,
    ) -> Geometry {
        let (vmin, vmax) = (cbar.lo, cbar.hi);
        let cbar_w = colorbar::width(&sizes, &cbar, spec.cbar_label);
        let title_h = layout::title_height(&sizes, spec.title);
        let area_h = height as i32 - title_h;
        let mut layout = Layout::standard(&sizes, 0);
        let ph = area_h - layout.top - layout.bottom - layout.x_area;
        let ty = (ph as f64 / (95.0 * sizes.scale)).round().clamp(3.0, 10.0) as usize;
        let mut y = Axis::linear(yr.0, yr.1, ty);
        layout = Layout::standard(&sizes, y.max_label_width(sizes.tick()));
        let fixed = layout.left + layout.y_area + layout.right + cbar_w;
        let width = if spec.equal_aspect {
            let pw = ph as f64 * (xr.1 - xr.0) / (yr.1 - yr.0);
            (pw as i32 + fixed).clamp((0.85 * height as f64) as i32, 2 * height as i32)
        } else {
            (height as f64 * 4.0 / 3.0) as i32
        };
        let plot = |l: &Layout| (width - cbar_w - l.left - l.right - l.y_area, ph);
        let tx = |pw: i32| (pw as f64 / (170.0 * sizes.scale)).round().clamp(3.0, 10.0) as usize;
        let mut x = Axis::linear(xr.0, xr.1, tx(plot(&layout).0));
        if let (Some(at), false) = (&spec.x_ticks, spec.equal_aspect) {
            x = x.with_labelled_ticks(at);
        }
        if spec.equal_aspect {
            for _ in 0..2 {
                let (ex, ey) = layout::equalize(xr, yr, plot(&layout));
                x = Axis::linear(ex.0, ex.1, tx(plot(&layout).0));
                y = Axis::linear(ey.0, ey.1, ty);
                layout = Layout::standard(&sizes, y.max_label_width(sizes.tick()));
            }
        }
        Geometry {
            sizes,
            size: (width as u32, height),
            x,
            y,
            layout,
            cbar_w,
            vmin,
            vmax,
            cbar,
            legend_corner: Corner::UpperRight,
        }
    }

    /// The same figure on a canvas `s` times larger.
    pub fn scaled(&self, s: u32) -> Geometry {
        let k = s as i32;
        let l = &self.layout;
        Geometry {
            sizes: self.sizes.scaled(s),
            size: (self.size.0 * s, self.size.1 * s),
            layout: Layout {
                top: l.top * k,
                right: l.right * k,
                bottom: l.bottom * k,
                left: l.left * k,
                x_area: l.x_area * k,
                y_area: l.y_area * k,
            },
            cbar_w: self.cbar_w * k,
            ..self.clone()
        }
    }

    /// Colour of parameter value `v`.
    pub fn color(&self, v: f64) -> RGBColor {
        cool((v - self.vmin) / (self.vmax - self.vmin))
    }
}

/// Legend texts: P0, P1 if any, the markers if labelled.
pub(crate) fn legend_lines(spec: &Spec) -> Vec<String> {
    let mut v = vec!["P₀".to_string()];
    if spec.p1.is_some() {
        v.push(spec.p1_label.to_string());
    }
    if !spec.markers_label.is_empty() && !spec.markers.is_empty() {
        v.push(spec.markers_label.to_string());
    }
    v
}
