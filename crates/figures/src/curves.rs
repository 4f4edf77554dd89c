//! Curves coloured by a parameter with a colour bar (report Fig. 2: the
//! catenaries coloured by L), and the drawing shared with the chain
//! snapshots and the animation: the curves (or the current one and the
//! path of its end), markers, P0 and P1, the legend and the colour bar.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::colormap::{P0_RED, P1_BLUE};
use crate::curve_layout::{self, Geometry};
use crate::legend::{self, Swatch};
use crate::output::{self, Draw};
use crate::sizes::Sizes;
use crate::{chart, clip, colorbar, font, layout};
use crate::{FigureError, Output};

/// Curves coloured by a parameter (cyan at the smallest value, magenta at
/// the largest) with a labelled colour bar, black markers, P0 red and P1
/// blue.
#[derive(Debug, Clone)]
pub struct ColoredCurves<'a> {
    pub title: &'a str,
    /// `(parameter, points)`; drawn in increasing parameter order.
    pub curves: Vec<(f64, Vec<(f64, f64)>)>,
    /// Black dots (e.g. the lowest points of the catenaries).
    pub markers: Vec<(f64, f64)>,
    /// Legend text of the markers; empty for no entry.
    pub markers_label: &'a str,
    pub p0: [f64; 2],
    pub p1: Option<[f64; 2]>,
    pub colorbar_label: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    /// Same units per pixel on both axes; the canvas width follows the data.
    pub equal_aspect: bool,
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
}

impl<'a> ColoredCurves<'a> {
    /// Equal scales, axes "x" and "y", no markers, colour bar unlabelled.
    pub fn new(title: &'a str, curves: Vec<(f64, Vec<(f64, f64)>)>, p0: [f64; 2]) -> Self {
        ColoredCurves {
            title,
            curves,
            markers: Vec::new(),
            markers_label: "",
            p0,
            p1: None,
            colorbar_label: "",
            x_label: "x",
            y_label: "y",
            equal_aspect: true,
            x_range: None,
            y_range: None,
        }
    }
}

/// Draw `fig` to `<stem>.png` and `<stem>.svg`.
pub fn colored_curves(fig: &ColoredCurves, stem: &Path) -> Result<Output, FigureError> {
    let spec = Spec {
        title: fig.title,
        curves: fig.curves.clone(),
        markers: fig.markers.clone(),
        markers_label: fig.markers_label,
        p0: (fig.p0[0], fig.p0[1]),
        p1: fig.p1.map(|p| (p[0], p[1])),
        p1_label: "P₁",
        cbar_label: fig.colorbar_label,
        x_label: fig.x_label,
        y_label: fig.y_label,
        equal_aspect: fig.equal_aspect,
        x_range: fig.x_range,
        y_range: fig.y_range,
        x_ticks: None,
    };
    render_static(spec, stem)
}

/// What the coloured-curve figures have in common.
#[derive(Debug, Clone)]
pub(crate) struct Spec<'a> {
    pub title: &'a str,
    pub curves: Vec<(f64, Vec<(f64, f64)>)>,
    pub markers: Vec<(f64, f64)>,
    pub markers_label: &'a str,
    pub p0: (f64, f64),
    pub p1: Option<(f64, f64)>,
    /// Legend name of `p1`.
    pub p1_label: &'a str,
    pub cbar_label: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub equal_aspect: bool,
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    /// Labelled x ticks `(x, label)` in place of the numbers (linear axes
    /// without equal scales): the snapshots side by side, each labelled by
    /// its time.
    pub x_ticks: Option<Vec<(f64, String)>>,
}

pub(crate) fn render_static(mut spec: Spec, stem: &Path) -> Result<Output, FigureError> {
    font::ensure_registered()?;
    spec.sort();
    let geom = Geometry::new(&spec, 900, Sizes::STANDARD)?;
    output::save(
        &Drawing {
            spec: &spec,
            geom: &geom,
            current: None,
        },
        stem,
    )
}

/// As [`render_static`], to one file whose extension picks PNG or SVG.
pub(crate) fn render_static_to(mut spec: Spec, path: &Path) -> Result<(), FigureError> {
    font::ensure_registered()?;
    spec.sort();
    let geom = Geometry::new(&spec, 900, Sizes::STANDARD)?;
    output::save_one(
        &Drawing {
            spec: &spec,
            geom: &geom,
            current: None,
        },
        path,
    )
}

impl Spec<'_> {
    /// Increasing parameter order (stable), so later curves lie on top.
    pub fn sort(&mut self) {
        self.curves.sort_by(|a, b| a.0.total_cmp(&b.0));
    }

    /// The smallest and largest finite parameter ((0, 1) if there is none).
    pub fn value_range(&self) -> (f64, f64) {
        let vals = self.curves.iter().map(|c| c.0).filter(|v| v.is_finite());
        let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
        if lo.is_finite() {
            (lo, hi)
        } else {
            (0.0, 1.0)
        }
    }
}

/// A coloured-curves figure ready to draw: all curves, or (in an
/// animation) the one at `current` highlighted.
pub(crate) struct Drawing<'s, 'a> {
    pub spec: &'s Spec<'a>,
    pub geom: &'s Geometry,
    pub current: Option<Current>,
}

impl Draw for Drawing<'_, '_> {
    fn size(&self) -> (u32, u32) {
        self.geom.size
    }
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: u32,
    ) -> Result<(), FigureError> {
        draw_figure(root, self.spec, &self.geom.scaled(scale), self.current)
    }
}

#[derive(Clone, Copy)]
pub(crate) struct Current {
    pub index: usize,
}

/// Draw the whole figure: all curves, or (animation) only the current one
/// with the path of its free end so far.
pub(crate) fn draw_figure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    spec: &Spec,
    g: &Geometry,
    current: Option<Current>,
) -> Result<(), FigureError> {
    let sizes = &g.sizes;
    root.fill(&WHITE)?;
    let title = match current {
        Some(c) => {
            let t = spec.curves.get(c.index).map_or(0.0, |c| c.0);
            let t = format!("t = {t:.2}");
            if spec.title.is_empty() {
                t
            } else {
                format!("{}    {t}", spec.title)
            }
        }
        None => spec.title.to_string(),
    };
    let area = layout::titled(root, sizes, &title)?;
    let (aw, _) = area.dim_in_pixel();
    let (main, bar) = area.split_horizontally(aw as i32 - g.cbar_w);
    let mut chart = chart::chart(
        &main,
        sizes,
        &g.layout,
        &g.x,
        &g.y,
        spec.x_label,
        spec.y_label,
    )?;
    let xr = (g.x.lo, g.x.hi);
    let yr = (g.y.lo, g.y.hi);

    let clip = |pts: &[(f64, f64)]| {
        let p: Vec<Option<(f64, f64)>> = pts
            .iter()
            .map(|&q| (q.0.is_finite() && q.1.is_finite()).then_some(q))
            .collect();
        clip::clip_polyline(&p, xr, yr)
    };
    let inside = |q: &(f64, f64)| q.0 >= xr.0 && q.0 <= xr.1 && q.1 >= yr.0 && q.1 <= yr.1;

    match current {
        None => {
            let w = sizes.px(2.5) as u32;
            for (v, pts) in &spec.curves {
                let color = g.color(*v);
                for piece in clip(pts) {
                    chart.draw_series(LineSeries::new(piece, color.stroke_width(w)))?;
                }
            }
        }
        Some(c) => {
            // Path of the free end so far, then the current chain.
            let trail: Vec<(f64, f64)> = spec.curves[..=c.index.min(spec.curves.len() - 1)]
                .iter()
                .filter_map(|c| c.1.last().copied())
                .collect();
            for piece in clip(&trail) {
                chart.draw_series(LineSeries::new(
                    piece,
                    RGBColor(170, 170, 170).stroke_width(sizes.px(2.0) as u32),
                ))?;
            }
            if let Some((v, pts)) = spec.curves.get(c.index) {
                let color = g.color(*v);
                for piece in clip(pts) {
                    chart.draw_series(LineSeries::new(
                        piece,
                        color.stroke_width(sizes.px(4.0) as u32),
                    ))?;
                }
                if pts.len() <= 201 {
                    let dark = RGBColor(60, 60, 60);
                    chart.draw_series(
                        pts.iter()
                            .filter(|q| inside(q))
                            .map(|&q| Circle::new(q, sizes.px(3.0), dark.filled())),
                    )?;
                }
            }
        }
    }

    // Markers, then the anchor points on top.
    let mr = sizes.px(5.0);
    chart.draw_series(
        spec.markers
            .iter()
            .filter(|q| inside(q))
            .map(|&q| Circle::new(q, mr, BLACK.filled())),
    )?;
    let pr = sizes.px(9.0);
    let anchors = [
        (Some(spec.p0), P0_RED, "P₀"),
        (spec.p1, P1_BLUE, spec.p1_label),
    ];
    for (p, color, name) in anchors {
        let Some(p) = p else { continue };
        if inside(&p) {
            chart.draw_series(std::iter::once(Circle::new(p, pr, color.filled())))?;
            chart.draw_series(std::iter::once(Circle::new(
                p,
                pr,
                BLACK.stroke_width(sizes.px(1.5) as u32),
            )))?;
        }
        let swatch = Swatch::Marker { color, radius: pr };
        legend::add_entry(&mut chart, sizes, name, swatch)?;
    }
    if !spec.markers_label.is_empty() && !spec.markers.is_empty() {
        let swatch = Swatch::Marker {
            color: BLACK,
            radius: mr,
        };
        legend::add_entry(&mut chart, sizes, spec.markers_label, swatch)?;
    }
    chart::frame(&chart, sizes)?;

    let (pw, ph) = chart.plotting_area().dim_in_pixel();
    let plot = (pw as i32, ph as i32);
    let size = legend::box_size(sizes, &curve_layout::legend_lines(spec), true);
    let legend = g.legend_corner.rect(size, plot, sizes.px(14.0));
    legend::draw_legend(&mut chart, sizes, legend.origin())?;
    drop(chart);

    let marker = current.and_then(|c| spec.curves.get(c.index)).map(|c| c.0);
    colorbar::draw(&bar, g, spec.cbar_label, marker)
}
