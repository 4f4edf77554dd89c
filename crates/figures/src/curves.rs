//! Curves coloured by a parameter with a colour bar (report Fig. 2: the
//! catenaries coloured by L), and the machinery shared with the chain
//! snapshots and the animation: equal axis scales with a canvas width that
//! follows the data's aspect, the 'cool' colour bar, P0 and P1 markers.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::colormap::{cool, P0_RED, P1_BLUE};
use crate::font;
use crate::layout::{self, Layout};
use crate::legend::{self, Swatch};
use crate::output::{self, Draw};
use crate::placement::{Corner, Occupancy};
use crate::sizes::{text_width, Sizes};
use crate::ticks::Axis;
use crate::{chart, clip};
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
        cbar_label: fig.colorbar_label,
        x_label: fig.x_label,
        y_label: fig.y_label,
        equal_aspect: fig.equal_aspect,
        x_range: fig.x_range,
        y_range: fig.y_range,
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
    pub cbar_label: &'a str,
    pub x_label: &'a str,
    pub y_label: &'a str,
    pub equal_aspect: bool,
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
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

    fn value_range(&self) -> (f64, f64) {
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
    cbar: Axis,
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
        let cbar_w = cbar_width(&sizes, &cbar, spec.cbar_label);
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
fn legend_lines(spec: &Spec) -> Vec<String> {
    let mut v = vec!["P₀".to_string()];
    if spec.p1.is_some() {
        v.push("P₁".into());
    }
    if !spec.markers_label.is_empty() && !spec.markers.is_empty() {
        v.push(spec.markers_label.to_string());
    }
    v
}

/// Short colour-bar labels are written upright, longer ones rotated.
fn cbar_label_upright(label: &str) -> bool {
    label.chars().count() <= 3
}

fn cbar_width(sizes: &Sizes, cbar: &Axis, label: &str) -> i32 {
    let base = sizes.px(40.0) + sizes.px(34.0) + sizes.px(8.0) + sizes.px(10.0);
    let labels = cbar.max_label_width(sizes.tick());
    let desc = if label.is_empty() {
        0
    } else if cbar_label_upright(label) {
        sizes.px(18.0) + text_width(label, sizes.label())
    } else {
        sizes.px(12.0) + (sizes.label() * 1.2) as i32
    };
    base + labels + desc + sizes.px(24.0)
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
    let anchors = [(Some(spec.p0), P0_RED, "P₀"), (spec.p1, P1_BLUE, "P₁")];
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
    let size = legend::box_size(sizes, &legend_lines(spec), true);
    let legend = g.legend_corner.rect(size, plot, sizes.px(14.0));
    legend::draw_legend(&mut chart, sizes, legend.origin())?;
    drop(chart);

    let marker = current.and_then(|c| spec.curves.get(c.index)).map(|c| c.0);
    draw_colorbar(&bar, g, spec.cbar_label, marker)
}

/// The vertical colour bar, aligned with the plot area.
fn draw_colorbar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    g: &Geometry,
    label: &str,
    marker: Option<f64>,
) -> Result<(), FigureError> {
    let sizes = &g.sizes;
    let (_, ah) = area.dim_in_pixel();
    let top = g.layout.top;
    let bottom = ah as i32 - g.layout.bottom - g.layout.x_area - 1;
    let x0 = sizes.px(40.0);
    let x1 = x0 + sizes.px(34.0);
    let bands = 128;
    let h = (bottom - top) as f64;
    for i in 0..bands {
        // Band i covers [i, i+1] / bands from the bottom (vmin) up.
        let ya = bottom as f64 - h * i as f64 / bands as f64;
        let yb = bottom as f64 - h * (i + 1) as f64 / bands as f64;
        let color = cool((i as f64 + 0.5) / bands as f64);
        area.draw(&Rectangle::new(
            [(x0, yb.floor() as i32), (x1, ya.ceil() as i32)],
            color.filled(),
        ))?;
    }
    area.draw(&Rectangle::new(
        [(x0, top), (x1, bottom)],
        BLACK.stroke_width(sizes.axis()),
    ))?;
    let to_y = |v: f64| bottom as f64 - h * (v - g.vmin) / (g.vmax - g.vmin);
    let tick_style = sizes
        .font(sizes.tick())
        .pos(Pos::new(HPos::Left, VPos::Center));
    let tick = sizes.px(8.0);
    for (v, text) in g.cbar.ticks.iter().zip(&g.cbar.labels) {
        let y = to_y(*v).round() as i32;
        area.draw(&PathElement::new(
            vec![(x1, y), (x1 + tick, y)],
            BLACK.stroke_width(sizes.axis()),
        ))?;
        area.draw(&Text::new(
            text.clone(),
            (x1 + tick + sizes.px(8.0), y),
            tick_style.clone(),
        ))?;
    }
    if let Some(v) = marker {
        let y = to_y(v).round() as i32;
        let k = sizes.px(7.0);
        area.draw(&PathElement::new(
            vec![(x0, y), (x1, y)],
            BLACK.stroke_width(sizes.px(3.0) as u32),
        ))?;
        area.draw(&Polygon::new(
            vec![(x0 - 2 * k, y - k), (x0 - 2, y), (x0 - 2 * k, y + k)],
            BLACK.filled(),
        ))?;
    }
    if !label.is_empty() {
        let lx = x1 + tick + sizes.px(8.0) + g.cbar.max_label_width(sizes.tick());
        let cy = (top + bottom) / 2;
        if cbar_label_upright(label) {
            let st = sizes
                .font(sizes.label())
                .pos(Pos::new(HPos::Left, VPos::Center));
            area.draw(&Text::new(label.to_string(), (lx + sizes.px(18.0), cy), st))?;
        } else {
            let st = sizes
                .font(sizes.label())
                .transform(FontTransform::Rotate90)
                .pos(Pos::new(HPos::Center, VPos::Top));
            area.draw(&Text::new(
                label.to_string(),
                (lx + sizes.px(12.0) + (sizes.label() * 1.2) as i32, cy),
                st,
            ))?;
        }
    }
    Ok(())
}
