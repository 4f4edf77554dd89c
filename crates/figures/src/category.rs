//! Categorical maps (the stability map): panels of rows x columns of
//! cells, each cell a category drawn as a colour, with a legend.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::font;
use crate::layout;
use crate::output::{self, Draw};
use crate::sizes::{text_width, Sizes};
use crate::{FigureError, Output};

/// One map: `cells[row][col]` is a category index, or `None` (not run,
/// drawn light grey).
#[derive(Debug, Clone, Default)]
pub struct CategoryPanel {
    /// Drawn above the panel (e.g. the scene); empty for none.
    pub title: String,
    /// Top to bottom.
    pub row_labels: Vec<String>,
    /// Left to right.
    pub col_labels: Vec<String>,
    pub cells: Vec<Vec<Option<usize>>>,
    /// Optional short text in each cell (same shape as `cells`, or empty).
    pub cell_text: Vec<Vec<String>>,
}

/// Several panels (in rows, as many per row as suit a 4:3 page) sharing
/// the categories and axis names.
#[derive(Debug, Clone)]
pub struct CategoryMap<'a> {
    pub title: &'a str,
    /// Under the panels (e.g. "step size / tolerance").
    pub x_label: &'a str,
    /// Left of the panels (e.g. "method").
    pub y_label: &'a str,
    /// `(label, colour)` of each category index.
    pub categories: Vec<(String, RGBColor)>,
    pub panels: Vec<CategoryPanel>,
}

/// Draw `map` to `<stem>.png` and `<stem>.svg`.
pub fn category_map(map: &CategoryMap, stem: &Path) -> Result<Output, FigureError> {
    output::save(&figure(map)?, stem)
}

/// As [`category_map`], to the one file `path` (`.png` or `.svg`).
pub fn category_map_to(map: &CategoryMap, path: &Path) -> Result<(), FigureError> {
    output::save_one(&figure(map)?, path)
}

fn figure<'m, 'a>(map: &'m CategoryMap<'a>) -> Result<Figure<'m, 'a>, FigureError> {
    font::ensure_registered()?;
    validate(map)?;
    // As many panels per row as give the shape closest to a page's 4:3.
    let plan = (1..=map.panels.len().min(4))
        .map(|per_row| Plan::new(map, Sizes::STANDARD, per_row))
        .min_by(|a, b| a.misfit().total_cmp(&b.misfit()))
        .ok_or_else(|| FigureError::Data("category map without panels".into()))?;
    Ok(Figure { map, plan })
}

fn validate(map: &CategoryMap) -> Result<(), FigureError> {
    if map.panels.is_empty() {
        return Err(FigureError::Data("category map without panels".into()));
    }
    for (i, p) in map.panels.iter().enumerate() {
        let bad = |what: &str| Err(FigureError::Data(format!("panel {i}: {what}")));
        if p.cells.len() != p.row_labels.len() {
            return bad("rows of cells differ from row labels");
        }
        if p.cells.iter().any(|r| r.len() != p.col_labels.len()) {
            return bad("a row's cells differ from the column labels");
        }
        if p.cells
            .iter()
            .flatten()
            .flatten()
            .any(|&c| c >= map.categories.len())
        {
            return bad("a cell names an unknown category");
        }
        if !p.cell_text.is_empty()
            && (p.cell_text.len() != p.cells.len()
                || p.cell_text
                    .iter()
                    .zip(&p.cells)
                    .any(|(t, c)| t.len() != c.len()))
        {
            return bad("cell text differs in shape from the cells");
        }
    }
    Ok(())
}

/// Pixel layout of one panel.
#[derive(Debug, Clone)]
struct PanelPlan {
    /// Top-left of the grid.
    gx: i32,
    gy: i32,
    cw: i32,
    ch: i32,
    row_label_w: i32,
    cols_rotated: bool,
    /// Whether its row labels are drawn (a panel right of one with the
    /// same rows shares that one's).
    show_rows: bool,
}

#[derive(Debug, Clone)]
struct Plan {
    sizes: Sizes,
    size: (u32, u32),
    panels: Vec<PanelPlan>,
    legend_y: i32,
    x_label_y: i32,
    /// Vertical extent of all grids (for the y label).
    grids_y: (i32, i32),
    per_row: usize,
}

/// Colour of cells without a category.
const NOT_RUN: RGBColor = RGBColor(232, 232, 232);

/// The legend: every category, and "not run" if a cell has none.
fn legend_entries(map: &CategoryMap) -> Vec<(String, RGBColor)> {
    let mut v = map.categories.clone();
    if map
        .panels
        .iter()
        .flat_map(|p| p.cells.iter().flatten())
        .any(|c| c.is_none())
    {
        v.push(("not run".to_string(), NOT_RUN));
    }
    v
}

impl Plan {
    /// How far the canvas is from a 4:3 shape (0 is best).
    fn misfit(&self) -> f64 {
        let aspect = self.size.0 as f64 / self.size.1 as f64;
        (aspect / (4.0 / 3.0)).ln().abs()
    }

    fn new(map: &CategoryMap, sizes: Sizes, per_row: usize) -> Plan {
        let t = &sizes;
        let tick = t.tick();
        let margin = t.px(30.0);
        let gap = t.px(60.0);
        let title_h = layout::title_height(t, map.title);
        let ylab_w = if map.y_label.is_empty() {
            0
        } else {
            (t.label() * 1.3) as i32 + t.px(10.0)
        };
        // Size every panel.
        let mut panel_sizes = Vec::new();
        for p in &map.panels {
            let row_label_w = p
                .row_labels
                .iter()
                .map(|l| text_width(l, tick))
                .max()
                .unwrap_or(0);
            let col_label_w = p
                .col_labels
                .iter()
                .map(|l| text_width(l, tick))
                .max()
                .unwrap_or(0);
            let text_w = p
                .cell_text
                .iter()
                .flatten()
                .map(|s| text_width(s, cell_text_size(t)))
                .max()
                .unwrap_or(0);
            let mut cw = t.px(84.0).max(text_w + t.px(14.0));
            let cols_rotated = col_label_w + t.px(12.0) > cw;
            if cols_rotated {
                cw = cw.max((tick * 1.4) as i32);
            }
            let ch = t.px(64.0);
            let col_area = if cols_rotated {
                col_label_w + t.px(16.0)
            } else {
                (tick * 1.2) as i32 + t.px(12.0)
            };
            let ptitle = if p.title.is_empty() {
                0
            } else {
                (t.label() * 1.4) as i32
            };
            let gw = cw * p.col_labels.len() as i32;
            let gh = ch * p.row_labels.len() as i32;
            let w = row_label_w + t.px(12.0) + gw;
            panel_sizes.push((w, ptitle, gh, col_area, cw, ch, row_label_w, cols_rotated));
        }
        // Rows of panels.
        let mut panels = Vec::new();
        let mut y = title_h + margin;
        let mut width = 0;
        let mut grids_y = (i32::MAX, 0);
        for chunk in panel_sizes.chunks(per_row.max(1)) {
            let ptitle = chunk.iter().map(|s| s.1).max().unwrap_or(0);
            let gh = chunk.iter().map(|s| s.2).max().unwrap_or(0);
            let col_area = chunk.iter().map(|s| s.3).max().unwrap_or(0);
            let mut x = margin + ylab_w;
            let first = panels.len();
            for (k, s) in chunk.iter().enumerate() {
                // Rows as the first panel of this row of panels: their
                // labels are that panel's.
                let same_rows =
                    k > 0 && map.panels[first + k].row_labels == map.panels[first].row_labels;
                let label_w = if same_rows { 0 } else { s.6 + t.px(12.0) };
                let gx = x + label_w;
                let gy = y + ptitle;
                panels.push(PanelPlan {
                    gx,
                    gy,
                    cw: s.4,
                    ch: s.5,
                    row_label_w: s.6,
                    cols_rotated: s.7,
                    show_rows: !same_rows,
                });
                grids_y = (grids_y.0.min(gy), grids_y.1.max(gy + s.2));
                x += s.0 - s.6 - t.px(12.0) + label_w + gap;
            }
            width = width.max(x - gap + margin);
            y += ptitle + gh + col_area + t.px(20.0);
        }
        let x_label_y = y;
        if !map.x_label.is_empty() {
            y += (t.label() * 1.4) as i32;
        }
        let legend_y = y + t.px(10.0);
        let width = width.max(t.px(900.0));
        let (_, legend_h) = legend_size(map, &sizes, width - 2 * margin);
        let height = legend_y + legend_h + margin;
        Plan {
            sizes,
            size: (width as u32, height.max(t.px(500.0)) as u32),
            panels,
            legend_y,
            x_label_y,
            grids_y,
            per_row,
        }
    }
}

/// The size of cell texts: as large as tick labels, so that the cells can
/// be read where the figure is printed at the width of a page.
fn cell_text_size(t: &Sizes) -> f64 {
    t.tick() * 1.1
}

/// The legend's entries in rows at most `width` wide (each row's entries
/// in order), filled greedily.
fn legend_rows(map: &CategoryMap, t: &Sizes, width: i32) -> Vec<Vec<(String, RGBColor)>> {
    let mut rows: Vec<Vec<(String, RGBColor)>> = vec![];
    let mut used = 0;
    for e in legend_entries(map) {
        let w = legend_item_w(&e.0, t);
        match rows.last_mut() {
            Some(row) if used + w <= width => {
                used += w;
                row.push(e);
            }
            _ => {
                used = w;
                rows.push(vec![e]);
            }
        }
    }
    rows
}

/// The legend's size when its rows are at most `width` wide.
fn legend_size(map: &CategoryMap, t: &Sizes, width: i32) -> (i32, i32) {
    let rows = legend_rows(map, t, width);
    let w = rows
        .iter()
        .map(|r| r.iter().map(|(l, _)| legend_item_w(l, t)).sum::<i32>())
        .max()
        .unwrap_or(0);
    (w, (t.legend() * 1.5) as i32 * rows.len().max(1) as i32)
}

fn legend_item_w(label: &str, t: &Sizes) -> i32 {
    t.px(32.0) + t.px(10.0) + text_width(label, t.legend()) + t.px(36.0)
}

struct Figure<'m, 'a> {
    map: &'m CategoryMap<'a>,
    plan: Plan,
}

impl Draw for Figure<'_, '_> {
    fn size(&self) -> (u32, u32) {
        self.plan.size
    }
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: u32,
    ) -> Result<(), FigureError> {
        let plan = &Plan::new(self.map, self.plan.sizes.scaled(scale), self.plan.per_row);
        let (map, t) = (self.map, &plan.sizes);
        root.fill(&WHITE)?;
        let (w, _) = root.dim_in_pixel();
        let w = w as i32;
        let center = |size: f64| t.font(size).pos(Pos::new(HPos::Center, VPos::Center));
        layout::titled(root, t, map.title)?;
        for (p, pp) in map.panels.iter().zip(&plan.panels) {
            let gw = pp.cw * p.col_labels.len() as i32;
            let gh = pp.ch * p.row_labels.len() as i32;
            if !p.title.is_empty() {
                root.draw(&Text::new(
                    p.title.clone(),
                    (pp.gx + gw / 2, pp.gy - (t.label() * 0.7) as i32),
                    center(t.label()),
                ))?;
            }
            for (r, row) in p.cells.iter().enumerate() {
                for (c, cell) in row.iter().enumerate() {
                    let x0 = pp.gx + c as i32 * pp.cw;
                    let y0 = pp.gy + r as i32 * pp.ch;
                    let color = cell.map_or(NOT_RUN, |k| map.categories[k].1);
                    root.draw(&Rectangle::new(
                        [(x0, y0), (x0 + pp.cw, y0 + pp.ch)],
                        color.filled(),
                    ))?;
                    let text = p
                        .cell_text
                        .get(r)
                        .and_then(|row| row.get(c))
                        .cloned()
                        .unwrap_or_else(|| {
                            if cell.is_none() {
                                "–".into()
                            } else {
                                String::new()
                            }
                        });
                    if !text.is_empty() {
                        let RGBColor(cr, cg, cb) = color;
                        let lum = 0.299 * cr as f64 + 0.587 * cg as f64 + 0.114 * cb as f64;
                        let ink = if lum < 110.0 { &WHITE } else { &BLACK };
                        let style = center(cell_text_size(t)).color(ink);
                        root.draw(&Text::new(text, (x0 + pp.cw / 2, y0 + pp.ch / 2), style))?;
                    }
                }
            }
            // White cell borders, then a frame.
            for c in 1..p.col_labels.len() as i32 {
                let x = pp.gx + c * pp.cw;
                root.draw(&PathElement::new(
                    vec![(x, pp.gy), (x, pp.gy + gh)],
                    WHITE.stroke_width(t.px(3.0) as u32),
                ))?;
            }
            for r in 1..p.row_labels.len() as i32 {
                let y = pp.gy + r * pp.ch;
                root.draw(&PathElement::new(
                    vec![(pp.gx, y), (pp.gx + gw, y)],
                    WHITE.stroke_width(t.px(3.0) as u32),
                ))?;
            }
            root.draw(&Rectangle::new(
                [(pp.gx, pp.gy), (pp.gx + gw, pp.gy + gh)],
                BLACK.stroke_width(t.axis()),
            ))?;
            let right = t.font(t.tick()).pos(Pos::new(HPos::Right, VPos::Center));
            let shown = if pp.show_rows { &p.row_labels[..] } else { &[] };
            for (r, l) in shown.iter().enumerate() {
                let y = pp.gy + r as i32 * pp.ch + pp.ch / 2;
                root.draw(&Text::new(
                    l.clone(),
                    (pp.gx - t.px(12.0), y),
                    right.clone(),
                ))?;
            }
            debug_assert!(pp.row_label_w >= 0);
            for (c, l) in p.col_labels.iter().enumerate() {
                let x = pp.gx + c as i32 * pp.cw + pp.cw / 2;
                let y = pp.gy + gh + t.px(10.0);
                let style = if pp.cols_rotated {
                    // Reads bottom to top, ending just under the grid.
                    t.font(t.tick())
                        .transform(FontTransform::Rotate270)
                        .pos(Pos::new(HPos::Right, VPos::Center))
                } else {
                    t.font(t.tick()).pos(Pos::new(HPos::Center, VPos::Top))
                };
                root.draw(&Text::new(l.clone(), (x, y), style))?;
            }
        }
        if !map.x_label.is_empty() {
            let size = layout::fitted(
                t.label(),
                text_width(map.x_label, t.label()),
                w - 2 * t.px(30.0),
            );
            root.draw(&Text::new(
                map.x_label.to_string(),
                (w / 2, plan.x_label_y + (t.label() * 0.7) as i32),
                center(size),
            ))?;
        }
        if !map.y_label.is_empty() {
            let style = t
                .font(t.label())
                .transform(FontTransform::Rotate270)
                .pos(Pos::new(HPos::Center, VPos::Top));
            root.draw(&Text::new(
                map.y_label.to_string(),
                (t.px(30.0), (plan.grids_y.0 + plan.grids_y.1) / 2),
                style,
            ))?;
        }
        // Legend, each row centred.
        let sq = t.px(32.0);
        let row_h = (t.legend() * 1.5) as i32;
        let left = t.font(t.legend()).pos(Pos::new(HPos::Left, VPos::Center));
        for (k, row) in legend_rows(map, t, w - 2 * t.px(30.0)).iter().enumerate() {
            let rw: i32 = row.iter().map(|(l, _)| legend_item_w(l, t)).sum();
            let mut x = (w - rw) / 2 + t.px(18.0);
            let cy = plan.legend_y + k as i32 * row_h + row_h / 2;
            for (label, color) in row {
                root.draw(&Rectangle::new(
                    [(x, cy - sq / 2), (x + sq, cy + sq / 2)],
                    color.filled(),
                ))?;
                root.draw(&Rectangle::new(
                    [(x, cy - sq / 2), (x + sq, cy + sq / 2)],
                    BLACK.stroke_width(t.px(1.0) as u32),
                ))?;
                root.draw(&Text::new(
                    label.clone(),
                    (x + sq + t.px(10.0), cy),
                    left.clone(),
                ))?;
                x += legend_item_w(label, t);
            }
        }
        Ok(())
    }
}
