//! Legend and note boxes: their size, the legend drawn by plotters' series
//! labels, and the note box drawn to look the same.

use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use crate::lines::Marker;
use crate::marks::{self, Mark};
use crate::sizes::{text_size, Sizes};
use crate::FigureError;

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Swatch {
    /// A filled circle (the snapshots' anchors and markers).
    Marker { color: RGBColor, radius: i32 },
    /// A line (dashed or not) and a mark of any shape, or the mark alone
    /// (`width` 0): what a line plot's series draws.
    Series {
        color: RGBColor,
        width: u32,
        dashed: bool,
        mark: Option<(Marker, i32, bool)>,
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

/// The entries of each of `columns` columns of a legend of `count`
/// entries, filled column by column: `(first, count)`.
fn column_ranges(count: usize, columns: usize) -> Vec<(usize, usize)> {
    let columns = columns.clamp(1, count.max(1));
    let rows = count.div_ceil(columns);
    (0..columns)
        .map(|c| (c * rows, rows.min(count.saturating_sub(c * rows))))
        .filter(|r| r.1 > 0)
        .collect()
}

/// Gap between two columns of a legend.
fn column_gap(sizes: &Sizes) -> i32 {
    sizes.px(24.0)
}

/// Size in pixels of a legend of `labels` in `columns` columns (filled
/// column by column); one column is [`box_size`]'s.
pub(crate) fn legend_size(sizes: &Sizes, labels: &[String], columns: usize) -> (i32, i32) {
    let parts: Vec<(i32, i32)> = column_ranges(labels.len(), columns)
        .into_iter()
        .map(|(a, n)| box_size(sizes, &labels[a..a + n], true))
        .collect();
    let pad = 2 * padding(sizes);
    let w = parts.iter().map(|p| p.0 - pad).sum::<i32>()
        + column_gap(sizes) * (parts.len() as i32 - 1).max(0)
        + pad;
    let h = parts.iter().map(|p| p.1).max().unwrap_or(pad);
    (w, h)
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
    let entry = chart
        .draw_series(std::iter::empty::<EmptyElement<(f64, f64), DB>>())?
        .label(label);
    match swatch {
        Swatch::Marker { color, radius } => {
            entry.legend(move |(x, y)| Circle::new((x + len / 2, y), radius, color.filled()))
        }
        // A line plot's series: drawn by `draw_entries`, not here; its
        // colour as a line.
        Swatch::Series { color, width, .. } => entry.legend(move |(x, y)| {
            PathElement::new(vec![(x, y), (x + len, y)], color.stroke_width(width.max(1)))
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

/// Draws a legend of `entries` (label and swatch) in `columns` columns in
/// a box like the note's, its top-left corner at `origin` in pixels of
/// `area`; its size is [`legend_size`]. Drawn by us rather than by
/// plotters' series labels, so that it may sit outside the plot area.
pub(crate) fn draw_entries<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    sizes: &Sizes,
    origin: (i32, i32),
    entries: &[(String, Swatch)],
    columns: usize,
) -> Result<(), FigureError> {
    let labels: Vec<String> = entries.iter().map(|e| e.0.clone()).collect();
    let (w, h) = legend_size(sizes, &labels, columns);
    let (x, y) = origin;
    // Where each entry goes: its column's left edge and its row.
    let mut place = vec![(0, 0); entries.len()];
    let mut left = x;
    for (a, n) in column_ranges(entries.len(), columns) {
        for (row, k) in (a..a + n).enumerate() {
            place[k] = (left, row);
        }
        let (cw, _) = box_size(sizes, &labels[a..a + n], true);
        left += cw - 2 * padding(sizes) + column_gap(sizes);
    }
    let corners = [(x, y), (x + w, y + h)];
    area.draw(&Rectangle::new(corners, WHITE.mix(0.9).filled()))?;
    area.draw(&Rectangle::new(
        corners,
        BORDER.stroke_width(sizes.px(1.0) as u32),
    ))?;
    let size = sizes.legend();
    let font = sizes.font(size);
    let pad = padding(sizes);
    let len = swatch_length(sizes);
    let (dash, gap) = (sizes.px(12.0), sizes.px(7.0));
    for (i, (label, swatch)) in entries.iter().enumerate() {
        let (cx, row) = place[i];
        let top = y + pad + (row as f64 * size * LINE_SPACING).round() as i32;
        let (_, th) = text_size(label, size);
        let mid = top + th / 2;
        let x0 = cx + pad;
        area.draw(&Text::new(
            label.as_str(),
            (x0 + swatch_area(sizes), top),
            font.clone(),
        ))?;
        let line = |color: RGBColor, width: u32, dashed: bool| -> Result<(), FigureError> {
            let pts = vec![(x0, mid), (x0 + len, mid)];
            if dashed {
                area.draw(&DashedPathElement::new(
                    pts,
                    dash,
                    gap,
                    color.stroke_width(width),
                ))?;
            } else {
                area.draw(&PathElement::new(pts, color.stroke_width(width)))?;
            }
            Ok(())
        };
        let mark = |color: RGBColor, marker: Marker, radius: i32, hollow: bool| {
            marks::draw(
                area,
                std::iter::once((x0 + len / 2, mid)),
                Mark {
                    marker,
                    radius,
                    color,
                    hollow,
                    outline: sizes.px(2.0) as u32,
                },
            )
        };
        match *swatch {
            Swatch::Marker { color, radius } => mark(color, Marker::Circle, radius, false)?,
            Swatch::Series {
                color,
                width,
                dashed,
                mark: m,
            } => {
                if width > 0 {
                    line(color, width, dashed)?;
                }
                if let Some((marker, radius, hollow)) = m {
                    mark(color, marker, radius, hollow)?;
                }
            }
        }
    }
    Ok(())
}
