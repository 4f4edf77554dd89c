//! Data marks of every shape ([`Marker`]), filled or hollow, drawn on any
//! drawing area at its own coordinates (a chart's data, or pixels for a
//! legend's swatch).

use plotters::coord::CoordTranslate;
use plotters::prelude::*;

use crate::lines::Marker;
use crate::FigureError;

/// How a mark is drawn: its shape, radius (px), colour, whether hollow
/// (an outline through which what lies under it shows), and the width of
/// that outline.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Mark {
    pub marker: Marker,
    pub radius: i32,
    pub color: RGBColor,
    pub hollow: bool,
    pub outline: u32,
}

/// The corners of a polygon mark around its centre (pixels, y down).
fn corners(marker: Marker, r: i32) -> Vec<(i32, i32)> {
    let f = |v: f64| (v * f64::from(r)).round() as i32;
    match marker {
        Marker::Triangle => vec![(0, -f(1.15)), (f(1.0), f(0.6)), (-f(1.0), f(0.6))],
        Marker::Diamond => vec![(0, -f(1.2)), (f(1.0), 0), (0, f(1.2)), (-f(1.0), 0)],
        Marker::Square => {
            let s = f(0.85);
            vec![(-s, -s), (s, -s), (s, s), (-s, s)]
        }
        Marker::Circle => vec![],
    }
}

/// Draws `mark` at each of `points` (coordinates of `area`).
pub(crate) fn draw<DB: DrawingBackend, CT: CoordTranslate>(
    area: &DrawingArea<DB, CT>,
    points: impl IntoIterator<Item = CT::From>,
    mark: Mark,
) -> Result<(), FigureError>
where
    CT::From: Clone,
{
    let r = mark.radius;
    let shape = corners(mark.marker, r);
    let fill = mark.color.filled();
    let edge = mark.color.stroke_width(mark.outline);
    for p in points {
        match (mark.marker, mark.hollow) {
            (Marker::Circle, false) => {
                area.draw(&(EmptyElement::at(p) + Circle::new((0, 0), r, fill)))?
            }
            (Marker::Circle, true) => {
                area.draw(&(EmptyElement::at(p) + Circle::new((0, 0), r, edge)))?
            }
            (_, false) => area.draw(&(EmptyElement::at(p) + Polygon::new(shape.clone(), fill)))?,
            (_, true) => {
                let mut ring = shape.clone();
                ring.push(shape[0]);
                area.draw(&(EmptyElement::at(p) + PathElement::new(ring, edge)))?
            }
        }
    }
    Ok(())
}
