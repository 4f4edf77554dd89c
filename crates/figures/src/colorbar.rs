//! The vertical colour bar beside a coloured-curves figure ('cool', from
//! the smallest parameter value at the bottom to the largest at the top),
//! with ticks, a label, and in an animation a marker at the current value.
//! plotters has no colour bar.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::colormap::cool;
use crate::curve_layout::Geometry;
use crate::sizes::{text_width, Sizes};
use crate::ticks::Axis;
use crate::FigureError;

/// Short colour-bar labels are written upright, longer ones rotated.
fn label_upright(label: &str) -> bool {
    label.chars().count() <= 3
}

/// Width of the colour bar with its tick labels and `label`.
pub(crate) fn width(sizes: &Sizes, cbar: &Axis, label: &str) -> i32 {
    let base = sizes.px(40.0) + sizes.px(34.0) + sizes.px(8.0) + sizes.px(10.0);
    let labels = cbar.max_label_width(sizes.tick());
    let desc = if label.is_empty() {
        0
    } else if label_upright(label) {
        sizes.px(18.0) + text_width(label, sizes.label())
    } else {
        sizes.px(12.0) + (sizes.label() * 1.2) as i32
    };
    base + labels + desc + sizes.px(24.0)
}

/// The vertical colour bar, aligned with the plot area.
pub(crate) fn draw<DB: DrawingBackend>(
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
        if label_upright(label) {
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
