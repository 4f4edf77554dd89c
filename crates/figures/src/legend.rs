//! Legend and note boxes: their size and drawing.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::sizes::{text_width, Sizes};
use crate::FigureError;

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
pub(crate) fn box_size(sizes: &Sizes, lines: &[String], swatch: bool) -> (i32, i32) {
    let size = sizes.legend();
    let row = (size * 1.25) as i32;
    let pad = sizes.px(12.0);
    let sw = if swatch {
        sizes.px(56.0) + sizes.px(12.0)
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
    sizes: &Sizes,
    origin: (i32, i32),
    entries: &[(String, Option<Swatch>)],
) -> Result<(), FigureError> {
    let lines: Vec<String> = entries.iter().map(|e| e.0.clone()).collect();
    let has_swatch = entries.iter().any(|e| e.1.is_some());
    let (bw, bh) = box_size(sizes, &lines, has_swatch);
    let (ox, oy) = origin;
    area.draw(&Rectangle::new(
        [(ox, oy), (ox + bw, oy + bh)],
        WHITE.mix(0.9).filled(),
    ))?;
    area.draw(&Rectangle::new(
        [(ox, oy), (ox + bw, oy + bh)],
        RGBColor(120, 120, 120).stroke_width(sizes.px(1.0) as u32),
    ))?;
    let size = sizes.legend();
    let row = (size * 1.25) as i32;
    let pad = sizes.px(12.0);
    let sw_len = sizes.px(56.0);
    let text_x = ox
        + pad
        + if has_swatch {
            sw_len + sizes.px(12.0)
        } else {
            0
        };
    let style = sizes.font(size).pos(Pos::new(HPos::Left, VPos::Center));
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
                        sizes.px(12.0),
                        sizes.px(7.0),
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
