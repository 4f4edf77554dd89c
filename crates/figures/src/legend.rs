//! Legend and note boxes: their size, the legend drawn by plotters' series
//! labels, and the note box drawn to look the same.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use crate::sizes::{text_size, Sizes};
use crate::FigureError;

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy)]
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

/// Length of a swatch.
fn swatch_length(sizes: &Sizes) -> i32 {
    sizes.px(56.0)
}

/// Width left of a legend's text: the swatch and a gap.
fn swatch_area(sizes: &Sizes) -> i32 {
    swatch_length(sizes) + sizes.px(12.0)
}

/// Space between a box's border and its content.
fn padding(sizes: &Sizes) -> i32 {
    sizes.px(12.0)
}

/// Text lines are this many font sizes apart (plotters' multi-line text).
const LINE_SPACING: f64 = 1.25;

const BORDER: RGBColor = RGBColor(120, 120, 120);

/// Size in pixels of a legend (`swatch`) or a note box of `lines`, laid out
/// as plotters lays out series labels.
pub(crate) fn box_size(sizes: &Sizes, lines: &[String], swatch: bool) -> (i32, i32) {
    let size = sizes.legend();
    let (mut w, mut h) = (0, 0);
    for (i, line) in lines.iter().enumerate() {
        let (tw, th) = text_size(line, size);
        let top = (i as f64 * size * LINE_SPACING).round() as i32;
        w = w.max(tw);
        h = h.max(top + th);
    }
    let left = if swatch { swatch_area(sizes) } else { 0 };
    (w + left + 2 * padding(sizes), h + 2 * padding(sizes))
}

/// Add a legend entry to `chart`. plotters keeps a label with each series
/// drawn; this series draws nothing, so every entry is one series whatever
/// the pieces its data was drawn in. plotters calls the swatch closure with
/// the left end of the swatch's place, level with the middle of the text.
pub(crate) fn add_entry<'a, DB: DrawingBackend + 'a, CT: CoordTranslate<From = (f64, f64)>>(
    chart: &mut ChartContext<'a, DB, CT>,
    sizes: &Sizes,
    label: &str,
    swatch: Swatch,
) -> Result<(), FigureError> {
    let len = swatch_length(sizes);
    let (dash, gap) = (sizes.px(12.0), sizes.px(7.0));
    let entry = chart
        .draw_series(std::iter::empty::<EmptyElement<(f64, f64), DB>>())?
        .label(label);
    match swatch {
        Swatch::Line {
            color,
            width,
            dashed: false,
        } => entry.legend(move |(x, y)| {
            PathElement::new(vec![(x, y), (x + len, y)], color.stroke_width(width))
        }),
        Swatch::Line {
            color,
            width,
            dashed: true,
        } => entry.legend(move |(x, y)| {
            DashedPathElement::new(
                vec![(x, y), (x + len, y)],
                dash,
                gap,
                color.stroke_width(width),
            )
        }),
        Swatch::Marker { color, radius } => {
            entry.legend(move |(x, y)| Circle::new((x + len / 2, y), radius, color.filled()))
        }
        Swatch::LineMarker {
            color,
            width,
            radius,
        } => entry.legend(move |(x, y)| {
            EmptyElement::at((x, y))
                + PathElement::new(vec![(0, 0), (len, 0)], color.stroke_width(width))
                + Circle::new((len / 2, 0), radius, color.filled())
        }),
    };
    Ok(())
}

/// Draw the legend of `chart` (its entries from [`add_entry`]) with plotters'
/// series labels, the top-left corner at `origin` in plot-area pixels; its
/// size is [`box_size`].
pub(crate) fn draw_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    sizes: &Sizes,
    origin: (i32, i32),
) -> Result<(), FigureError> {
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::Coordinate(origin.0, origin.1))
        .margin(padding(sizes))
        .legend_area_size(swatch_area(sizes))
        .background_style(WHITE.mix(0.9))
        .border_style(BORDER.stroke_width(sizes.px(1.0) as u32))
        .label_font(sizes.font(sizes.legend()))
        .draw()?;
    Ok(())
}

/// Draw a note box, `lines` of text in a box like the legend's, with its
/// top-left corner at `origin` in pixels of `area`; its size is
/// [`box_size`] without swatches.
pub(crate) fn draw_note<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    sizes: &Sizes,
    origin: (i32, i32),
    lines: &[String],
) -> Result<(), FigureError> {
    let (w, h) = box_size(sizes, lines, false);
    let (x, y) = origin;
    let corners = [(x, y), (x + w, y + h)];
    area.draw(&Rectangle::new(corners, WHITE.mix(0.9).filled()))?;
    area.draw(&Rectangle::new(
        corners,
        BORDER.stroke_width(sizes.px(1.0) as u32),
    ))?;
    let font = sizes.font(sizes.legend());
    let pad = padding(sizes);
    let mut text = MultiLineText::<_, &str>::new((x + pad, y + pad), &font);
    text.set_line_height(LINE_SPACING);
    for line in lines {
        text.push_line(line.as_str());
    }
    area.draw(&text)?;
    Ok(())
}
