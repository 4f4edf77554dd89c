//! The figures of the CLI's `--plot`: the work-precision pair (error
//! against wall time and against work, a line per method) and the
//! stability map (a panel per method, a row per scene, a cell per step or
//! tolerance coloured by how the run ended). `cargo xtask figures` draws
//! the paper's versions from its data files, with its notes.

use std::path::Path;

use chain_ode::Method;
use figures::{
    palette, CategoryMap, CategoryPanel, FigureError, LinePlot, RGBColor, Series, Style,
};

use super::format::exp;
use super::precision::Point;
use super::stability::{relative_energy_error, Cell, Outcome, Row, MAX_STEPS};

/// Errors below this are drawn at it (a log axis cannot show 0).
const DRAW_FLOOR: f64 = 1e-16;

/// Draws the work-precision pair of `rows` (the methods' completed
/// points) to `path` (`.png` or `.svg`).
pub fn precision(title: &str, rows: &[Point], path: &Path) -> Result<(), FigureError> {
    let y_label = "max(|Δr_tip| / L, |Δv_max| / v_max)";
    let mut left = LinePlot::new("error vs wall time", "wall time (s)", y_label);
    let mut right = LinePlot::new(
        "error vs work",
        "RHS evaluations (+ one per JVP of BDF)",
        y_label,
    );
    for (i, method) in Method::ALL.into_iter().enumerate() {
        let pts: Vec<&Point> = rows
            .iter()
            .filter(|p| p.run.is_some() && p.method == method.as_str() && p.ok())
            .collect();
        if pts.is_empty() {
            continue;
        }
        let style = if method == Method::Auto {
            Style::Dashed
        } else {
            Style::LinePoints
        };
        let wall: Vec<(f64, f64)> = pts
            .iter()
            .map(|p| (super::median(&p.walls), p.err().max(DRAW_FLOOR)))
            .filter(|(x, _)| x.is_finite() && *x > 0.0)
            .collect();
        let work: Vec<(f64, f64)> = pts
            .iter()
            .map(|p| (p.rhs_equiv() as f64, p.err().max(DRAW_FLOOR)))
            .collect();
        let label = method.as_str().to_uppercase();
        left.series
            .push(Series::new(&label, wall, style).with_color(palette(i)));
        right
            .series
            .push(Series::new("", work, style).with_color(palette(i)));
    }
    for plot in [&mut left, &mut right] {
        plot.log_x = true;
        plot.log_y = true;
    }
    figures::line_plot_pair_to(&left, &right, title, path)
}

/// Okabe & Ito's colour-blind-safe palette, one colour per outcome.
fn color(o: Outcome) -> RGBColor {
    match o {
        Outcome::Completed => RGBColor(0, 158, 115),
        Outcome::EnergyError => RGBColor(230, 159, 0),
        Outcome::Diverged => RGBColor(213, 94, 0),
        Outcome::StepSizeTooSmall => RGBColor(204, 121, 167),
        Outcome::MaxSteps => RGBColor(0, 114, 178),
    }
}

fn legend(o: Outcome) -> String {
    match o {
        Outcome::Completed => "completed, energy error ≤ 1% MgL".into(),
        Outcome::EnergyError => "completed, energy error > 1% MgL".into(),
        Outcome::Diverged => "diverged (non-finite)".into(),
        Outcome::StepSizeTooSmall => "step size too small".into(),
        Outcome::MaxSteps => format!("step budget ({}) used up", exp(MAX_STEPS as f64)),
    }
}

/// Draws the stability map of `cells` on `rows` to `path`.
pub fn stability(
    title: &str,
    rows: &[Row],
    cells: &[Cell],
    path: &Path,
) -> Result<(), FigureError> {
    let methods: Vec<Method> = Method::ALL
        .into_iter()
        .filter(|m| cells.iter().any(|c| c.method == *m))
        .collect();
    let panels = methods
        .iter()
        .map(|&m| {
            let mut params: Vec<f64> = cells
                .iter()
                .filter(|c| c.method == m)
                .map(|c| c.param)
                .collect();
            params.sort_by(|a, b| b.total_cmp(a));
            params.dedup();
            let mut panel = CategoryPanel {
                title: format!("{}: {}", m.as_str().to_uppercase(), m.accuracy_name()),
                row_labels: rows.iter().map(|r| r.label.replace(',', ";")).collect(),
                col_labels: params.iter().map(|&x| exp(x)).collect(),
                ..CategoryPanel::default()
            };
            for r in 0..rows.len() {
                let mut line = vec![];
                let mut text = vec![];
                for &x in &params {
                    let cell = cells
                        .iter()
                        .find(|c| c.row == r && c.method == m && c.param == x)
                        .and_then(|c| c.run.as_ref().ok());
                    match cell {
                        Some(t) => {
                            let o = Outcome::of(t);
                            line.push(Outcome::ALL.iter().position(|a| *a == o));
                            text.push(if t.status.is_ok() {
                                let e = relative_energy_error(t);
                                if e > 0.0 {
                                    format!("{}", e.log10().floor() as i64)
                                } else {
                                    "0".into()
                                }
                            } else {
                                format!("t {:.2}", t.t_reached)
                            });
                        }
                        None => {
                            line.push(None);
                            text.push("–".into());
                        }
                    }
                }
                panel.cells.push(line);
                panel.cell_text.push(text);
            }
            panel
        })
        .collect();
    let map = CategoryMap {
        title,
        x_label: "cell: the power of ten of the energy-balance error / MgL if completed, \
                  else the time t it stopped",
        y_label: "scene",
        categories: Outcome::ALL
            .iter()
            .map(|&o| (legend(o), color(o)))
            .collect(),
        panels,
    };
    figures::category_map_to(&map, path)
}
