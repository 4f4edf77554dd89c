//! The one drawing of the study's tables, used by the CLI's `--plot` and by
//! `cargo xtask figures` alike: the work-precision pair (error against wall
//! time and against work, a line per method, [`work_precision`]) and the
//! stability map (a panel per method, a row per scene, a cell per step or
//! tolerance coloured by how the run ended, [`stability_map`]). Both draw
//! from the CSV table of [`crate::precision::csv_text`] or
//! [`crate::stability::csv_text`] as read back ([`Table`]), so a figure drawn
//! from a file is the figure drawn from the computation. The paper's own
//! drawings are fc-paper-figures' (its `plot`), which build on these.

use std::path::Path;

use chain_ode::{Method, Status};
use figures::{
    palette, CategoryMap, CategoryPanel, FigureError, LinePlot, Output, RGBColor, Series, Style,
};

use crate::stability::{Outcome, MAX_STEPS};
use crate::work_cost::{UnitWeights, Weights};
use fc_csv::format::{exp, short_err};
use fc_csv::table::{distinct, parse_num, Table};

/// What a drawing reads its tables with: the table of the given suffix
/// (`""` for the main table, `"-law"`, `"-times"`, ...; the caller maps
/// the suffix to a file).
pub type Reader<'a> = &'a dyn Fn(&str) -> Result<Table, String>;

/// Errors below this are drawn at it (a log axis cannot show 0).
pub const DRAW_FLOOR: f64 = 1e-16;

fn data(e: String) -> FigureError {
    FigureError::Data(e)
}

/// A row of a work-precision table as the drawing needs it.
pub struct WpPoint {
    pub method: String,
    pub param_name: String,
    pub param: f64,
    pub status: String,
    pub switched: bool,
    pub err_tip: f64,
    pub err_vmax: f64,
    pub rhs_equiv: f64,
    /// The counts of [`chain_ode::Stats`] the weighted work is made of.
    pub rhs_evals: f64,
    pub jacobian_evals: f64,
    pub lu_factorizations: f64,
    /// Wall time (s; NaN: none).
    pub wall: f64,
}

impl WpPoint {
    fn plotted(&self) -> bool {
        self.status == Status::Ok.as_str() && self.err_tip.is_finite()
    }
    fn err(&self) -> f64 {
        self.err_tip.max(self.err_vmax)
    }
}

/// The rows of a work-precision table and its evaluation time. The wall
/// times come from `timing` (`method,param,wall_median`, joined by method
/// and accuracy) if given, else from the table's own `wall_seconds` column
/// (the CLI's), else none.
pub fn wp_points(t: &Table, timing: Option<&Table>) -> Result<(f64, Vec<WpPoint>), String> {
    let (method, param_name, param) = (t.strs("method")?, t.strs("param_name")?, t.strs("param")?);
    let (status, switched) = (t.strs("status")?, t.strs("switched")?);
    let (err_tip, err_vmax, rhs) = (
        t.nums("err_tip")?,
        t.nums("err_vmax")?,
        t.nums("rhs_equiv")?,
    );
    let (evals, jacs, lus) = (
        t.nums("rhs_evals")?,
        t.nums("jacobian_evals")?,
        t.nums("lu_factorizations")?,
    );
    let walls: Vec<f64> = match timing {
        Some(w) => {
            let (wm, wp, wall) = (w.strs("method")?, w.strs("param")?, w.nums("wall_median")?);
            (0..t.len())
                .map(|k| {
                    (0..w.len())
                        .find(|&j| wm[j] == method[k] && wp[j] == param[k])
                        .map_or(f64::NAN, |j| wall[j])
                })
                .collect()
        }
        None if t.col("wall_seconds").is_ok() => t.nums("wall_seconds")?,
        None => vec![f64::NAN; t.len()],
    };
    let t_eval = t.nums("t_eval")?.first().copied().unwrap_or(f64::NAN);
    let rows = (0..t.len())
        .map(|k| {
            Ok(WpPoint {
                method: method[k].to_string(),
                param_name: param_name[k].to_string(),
                param: parse_num(param[k])?,
                status: status[k].to_string(),
                switched: switched[k] == "1",
                err_tip: err_tip[k],
                err_vmax: err_vmax[k],
                rhs_equiv: rhs[k],
                rhs_evals: evals[k],
                jacobian_evals: jacs[k],
                lu_factorizations: lus[k],
                wall: walls[k],
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok((t_eval, rows))
}

/// `a … b` of the parameters of `pts` (or the one, or a list of two).
fn span(pts: &[&WpPoint]) -> String {
    match pts {
        [] => String::new(),
        [a] => exp(a.param),
        [a, b] => format!("{}, {}", exp(a.param), exp(b.param)),
        [a, .., b] => format!("{} … {}", exp(a.param), exp(b.param)),
    }
}

/// The legend entry of a method's line: what ran, what failed.
fn method_label<'a>(method: &str, rows: &'a [WpPoint]) -> (String, Vec<&'a WpPoint>) {
    let mine: Vec<&WpPoint> = rows.iter().filter(|pt| pt.method == method).collect();
    let ok: Vec<&WpPoint> = mine.iter().copied().filter(|pt| pt.plotted()).collect();
    let failed: Vec<&WpPoint> = mine
        .iter()
        .copied()
        .filter(|pt| pt.status != "ok" && pt.status != "not_run")
        .collect();
    let name = method.to_uppercase();
    let param = mine.first().map_or("", |pt| pt.param_name.as_str());
    let mut label =
        if method == Method::Auto.as_str() && !ok.is_empty() && ok.iter().all(|pt| !pt.switched) {
            format!("{name} (dashed, on top; one method per run)")
        } else if ok.is_empty() {
            format!("{name}: no run completed")
        } else {
            format!("{name} ({param} {})", span(&ok))
        };
    if !failed.is_empty() {
        label.push_str(&format!("; fails at {}", span(&failed)));
    }
    (label, ok)
}

/// Which explicit method each of auto's points is (same parameter, same
/// errors and work): lines "AUTO = DOPRI5 at 1e-3 … 1e-6," and
/// "  = DOP853 at 1e-7 … 1e-12".
fn same_as(auto: &[&WpPoint], rows: &[WpPoint]) -> Vec<String> {
    let twin = |pt: &WpPoint| {
        rows.iter()
            .find(|r| {
                r.method != pt.method
                    && Method::ALL.iter().any(|m| m.as_str() == r.method)
                    && r.param == pt.param
                    && r.err_tip == pt.err_tip
                    && r.err_vmax == pt.err_vmax
                    && r.rhs_equiv == pt.rhs_equiv
            })
            .map_or("?".to_string(), |r| r.method.to_uppercase())
    };
    let mut groups: Vec<(String, Vec<&WpPoint>)> = vec![];
    for &pt in auto {
        let m = twin(pt);
        match groups.last_mut() {
            Some((g, v)) if *g == m => v.push(pt),
            _ => groups.push((m, vec![pt])),
        }
    }
    groups
        .iter()
        .enumerate()
        .map(|(k, (m, v))| {
            let head = if k == 0 { "AUTO" } else { "   " };
            let tail = if k + 1 < groups.len() { "," } else { "" };
            format!("{head} = {m} at {}{tail}", span(v))
        })
        .collect()
}

/// How far the checks agree with the reference, from their rows (none if
/// the table has no reference rows, as a shard of the CLI's may not).
fn agreement(rows: &[WpPoint]) -> Option<(f64, Vec<String>)> {
    let find = |m: &str| rows.iter().find(|r| r.method == m);
    let reference = find("reference-dopri5")?;
    let rk4 = match find("check-rk4-richardson") {
        Some(r) => format!("RK4 (extrapolated) to {}", short_err(r.err())),
        None => {
            let r = find("check-rk4")?;
            format!("RK4 dt {} to {}", exp(r.param), short_err(r.err()))
        }
    };
    let bdf = find("check-bdf")?;
    let bdf = format!("BDF {} to {}", exp(bdf.param), short_err(bdf.err()));
    Some((reference.param, vec![rk4, bdf]))
}

/// A pair of line plots side by side under one title.
pub struct PlotPair {
    pub left: LinePlot<'static>,
    pub right: LinePlot<'static>,
    pub title: String,
}

impl PlotPair {
    /// Draws it to `<stem>.png` and `<stem>.svg`.
    pub fn save(&self, stem: &Path) -> Result<figures::Output, FigureError> {
        figures::line_plot_pair(&self.left, &self.right, &self.title, stem)
    }
    /// Draws it to the one file `path` (`.png` or `.svg`).
    pub fn save_to(&self, path: &Path) -> Result<(), FigureError> {
        figures::line_plot_pair_to(&self.left, &self.right, &self.title, path)
    }
}

/// The work-precision pair of a table's rows ([`wp_points`]) of the scene
/// called `label`, evaluated at `t_eval`, with `notes` added under the
/// agreement of the reference with its checks; the work is counted in
/// right-hand sides (a Jacobian of BDF as one per JVP).
pub fn work_precision(label: &str, rows: &(f64, Vec<WpPoint>), notes: Vec<String>) -> PlotPair {
    work_precision_weighted(label, rows, notes, None)
}

/// As [`work_precision`], with the work of the implicit methods weighted
/// by measured unit costs when `weights` are given
/// ([`crate::work_cost`]): every residual (with its Newton solve),
/// Jacobian and LU factorisation in right-hand sides.
pub fn work_precision_weighted(
    label: &str,
    (t_eval, rows): &(f64, Vec<WpPoint>),
    notes: Vec<String>,
    weights: Option<Weights>,
) -> PlotPair {
    // The error the paper uses: the larger of the two relative errors.
    let y_label = "max(|Δr_tip| / L, |Δv_max| / v_max)";
    let mut left = LinePlot::new("error vs wall time", "wall time (s, median)", y_label);
    let work_label = if weights.is_some() {
        "work in RHS (BDF's units at measured cost)"
    } else {
        "RHS evaluations (+ one per JVP of BDF)"
    };
    let mut right = LinePlot::new("error vs work", work_label, y_label);
    let floor = |e: f64| e.max(DRAW_FLOOR);
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for (i, method) in Method::ALL.into_iter().enumerate() {
        // A method the table does not name is not drawn (no legend entry):
        // a table of fewer methods draws as it did before they were added.
        if !rows.iter().any(|pt| pt.method == method.as_str()) {
            continue;
        }
        let (label, pts) = method_label(method.as_str(), rows);
        let color = palette(i);
        // auto runs one of the explicit methods: drawn dashed and on top
        // (last), so that the curve it coincides with shows through.
        let style = if method == Method::Auto {
            Style::Dashed
        } else {
            Style::LinePoints
        };
        let wall = |pt: &WpPoint| pt.wall;
        let work = |pt: &WpPoint| match weights
            .and_then(|w| w.of(&pt.method, pt.lu_factorizations > 0.0))
        {
            Some(u) => u.work(pt.rhs_evals, pt.jacobian_evals, pt.lu_factorizations),
            None => pt.rhs_equiv,
        };
        for (plot, x, label) in [
            (&mut left, &wall as &dyn Fn(&WpPoint) -> f64, label.as_str()),
            (&mut right, &work, ""),
        ] {
            let pts: Vec<(f64, f64)> = pts
                .iter()
                .filter(|pt| x(pt).is_finite())
                .map(|pt| (x(pt), floor(pt.err())))
                .collect();
            for p in &pts {
                lo = lo.min(p.1);
                hi = hi.max(p.1);
            }
            plot.series
                .push(Series::new(label, pts, style).with_color(color));
        }
    }
    let mut text = vec![];
    if let Some((ref_rtol, agree)) = agreement(rows) {
        text.push(format!("reference: DOPRI5 rtol {}; checks:", exp(ref_rtol)));
        text.push(format!("  {}", agree.join(", ")));
    }
    text.push(format!("tip position error Δr_tip at t = {t_eval}"));
    let (_, auto) = method_label(Method::Auto.as_str(), rows);
    if !auto.is_empty() && auto.iter().all(|pt| !pt.switched) {
        text.extend(same_as(&auto, rows));
    }
    if let Some(w) = weights {
        // One line: what a factorisation and a Jacobian cost (each
        // residual with its solve costs about one RHS: in the caption).
        let one = |u: UnitWeights| format!("{:.0}, {:.0}", u.lu, u.jacobian);
        text.push(format!(
            "LU, Jacobian in RHS: BDF {}; BDF-DENSE {}",
            one(w.bdf),
            one(w.dense)
        ));
    }
    text.extend(notes);
    right.annotations = text;
    // Fitted to the data, with a third of a decade to spare either way,
    // the same for both panels; the legend and the note go where they hide
    // no data (beside the plot if need be).
    let margin = 10f64.powf(1.0 / 3.0);
    for plot in [&mut left, &mut right] {
        plot.log_x = true;
        plot.log_y = true;
        if lo.is_finite() && hi > 0.0 {
            plot.y_range = Some((lo / margin, hi * margin));
        }
    }
    let title =
        format!("Work-precision: {label}; error: larger of tip position, max tip speed errors");
    PlotPair { left, right, title }
}

/// The CLI's `precision --plot`: the work-precision pair of its table
/// (`csv`, with its `wall_seconds`) to `path` (`.png` or `.svg`).
pub fn precision(label: &str, csv: &str, path: &Path) -> Result<(), FigureError> {
    let t = Table::parse("precision", csv).map_err(data)?;
    let rows = wp_points(&t, None).map_err(data)?;
    work_precision(label, &rows, vec![]).save_to(path)
}

/// A legend line that is not an outcome: the mark of `auto`'s cells (the
/// figures crate adds the line for cells not run).
const AUTO_MARK_LEGEND: [(&str, RGBColor); 1] = [(
    "B in an AUTO cell: auto ran BDF (from the start, or from when its detector fired)",
    RGBColor(255, 255, 255),
)];

/// The legend line of an outcome.
fn legend(o: Outcome) -> String {
    match o {
        Outcome::Completed => "completed, energy error ≤ 1% MgL".into(),
        Outcome::EnergyError => "completed, energy error > 1% MgL".into(),
        Outcome::Diverged => "diverged (non-finite)".into(),
        Outcome::StepSizeTooSmall => "step size too small".into(),
        Outcome::MaxSteps => format!("step budget ({}) used up", exp(MAX_STEPS as f64)),
    }
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

/// The paper's stability map ([`stability_map`]) of its table (`""`),
/// saved at `stem`.
pub fn stability_figure(read: Reader, stem: &Path, title: &str) -> Result<Output, String> {
    let map = stability_map(&read("")?, title)?;
    figures::category_map(&map, stem).map_err(|e| e.to_string())
}

/// Cell text: the energy error's power of ten for a completed run, the
/// time it stopped otherwise.
fn cell_text(status: &str, energy_error_rel: f64, t_reached: f64) -> String {
    if status == Status::Ok.as_str() {
        if energy_error_rel > 0.0 {
            format!("{}", energy_error_rel.log10().floor() as i64)
        } else {
            "0".into()
        }
    } else if t_reached < 0.01 {
        format!("t {t_reached:.4}")
    } else {
        format!("t {t_reached:.2}")
    }
}

/// The stability map of a stability table (its rows in their order, a
/// panel per method, the columns in the order they first appear).
pub fn stability_map<'a>(t: &Table, title: &'a str) -> Result<CategoryMap<'a>, String> {
    let (scene, label, method) = (t.strs("scene")?, t.strs("label")?, t.strs("method")?);
    let (param_name, param) = (t.strs("param_name")?, t.strs("param")?);
    let (outcome, status) = (t.strs("outcome")?, t.strs("status")?);
    let (energy, t_reached) = (t.nums("energy_error_rel")?, t.nums("t_reached")?);
    // auto: the time it ran BDF from (empty when it stayed explicit).
    let bdf_from = t.strs("bdf_from")?;
    let scenes = distinct(&scene);
    let rows: Vec<Option<Outcome>> = outcome.iter().map(|o| Outcome::parse(o)).collect();
    // Only the categories that occur.
    let used: Vec<Outcome> = Outcome::ALL
        .into_iter()
        .filter(|o| rows.contains(&Some(*o)))
        .collect();
    let index = |o: Outcome| used.iter().position(|u| *u == o);
    let panels: Vec<CategoryPanel> = distinct(&method)
        .into_iter()
        .map(|m| {
            let mine: Vec<usize> = (0..t.len()).filter(|&k| method[k] == m).collect();
            let name = m.to_uppercase();
            let cols = distinct(&mine.iter().map(|&k| param[k]).collect::<Vec<_>>());
            let mut panel = CategoryPanel {
                title: match param_name[mine[0]] {
                    "dt" => format!("{name}: step dt"),
                    other => format!("{name}: {other}"),
                },
                row_labels: scenes
                    .iter()
                    .map(|s| {
                        let k = scene.iter().position(|x| x == s).unwrap_or(0);
                        label[k].replace(';', ",")
                    })
                    .collect(),
                col_labels: cols
                    .iter()
                    .map(|c| parse_num(c).map_or(c.to_string(), exp))
                    .collect(),
                ..CategoryPanel::default()
            };
            for s in &scenes {
                let mut row = vec![];
                let mut cell = vec![];
                for c in &cols {
                    let k = mine
                        .iter()
                        .copied()
                        .find(|&k| scene[k] == *s && param[k] == *c);
                    match k.and_then(|k| rows[k].map(|o| (k, o))) {
                        Some((k, o)) => {
                            row.push(index(o));
                            let text = cell_text(status[k], energy[k], t_reached[k]);
                            cell.push(if bdf_from[k].is_empty() {
                                text
                            } else {
                                format!("B {text}")
                            });
                        }
                        None => {
                            row.push(None);
                            cell.push("–".into());
                        }
                    }
                }
                panel.cells.push(row);
                panel.cell_text.push(cell);
            }
            panel
        })
        .collect();
    Ok(CategoryMap {
        title,
        x_label: "cell: the power of ten of the energy-balance error / MgL (−5: 1e-5 to 1e-4) \
                  if completed, else the time t it stopped",
        y_label: "scene",
        categories: used
            .iter()
            .map(|&o| (legend(o), color(o)))
            .chain(AUTO_MARK_LEGEND.iter().map(|&(l, c)| (l.to_string(), c)))
            .collect(),
        panels,
    })
}

/// The CLI's `stability --plot`: the map of its table (`csv`) to `path`.
pub fn stability(title: &str, csv: &str, path: &Path) -> Result<(), FigureError> {
    let t = Table::parse("stability", csv).map_err(data)?;
    figures::category_map_to(&stability_map(&t, title).map_err(data)?, path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::work_cost::UnitWeights;

    fn point(
        method: &str,
        param: f64,
        err: f64,
        counts: (f64, f64, f64),
        rhs_equiv: f64,
    ) -> WpPoint {
        WpPoint {
            method: method.into(),
            param_name: "rtol".into(),
            param,
            status: "ok".into(),
            switched: false,
            err_tip: err,
            err_vmax: err / 2.0,
            rhs_equiv,
            rhs_evals: counts.0,
            jacobian_evals: counts.1,
            lu_factorizations: counts.2,
            wall: 1e-3 / err.sqrt().sqrt(),
        }
    }

    /// The work panel puts a BDF point at its residuals, Jacobians and
    /// LUs times their weights (an explicit point at its right-hand
    /// sides), or at its RHS equivalents without weights; and the y range
    /// leaves the legend and the note over no point.
    #[test]
    fn the_work_panel_weighs_bdf_by_its_unit_costs() {
        let rows = vec![
            point("dopri5", 1e-6, 1e-6, (600.0, 0.0, 0.0), 600.0),
            point("dopri5", 1e-8, 1e-8, (1200.0, 0.0, 0.0), 1200.0),
            point("bdf", 1e-6, 1e-6, (100.0, 2.0, 10.0), 302.0),
            point("bdf", 1e-8, 1e-8, (300.0, 4.0, 30.0), 704.0),
        ];
        let unit = UnitWeights {
            residual: 1.5,
            jacobian: 5.0,
            lu: 10.0,
        };
        let weights = Weights {
            bdf: unit,
            dense: unit,
        };
        let names: Vec<&'static str> = Method::ALL
            .iter()
            .map(|m| m.as_str())
            .filter(|m| rows.iter().any(|r| r.method == *m))
            .collect();
        let xs = |pair: &PlotPair, name: &str| -> Vec<f64> {
            // The series of the methods the table names, in ALL's order.
            let named: Vec<&str> = Method::ALL
                .iter()
                .map(|m| m.as_str())
                .filter(|m| names.contains(m))
                .collect();
            let k = named.iter().position(|&m| m == name).unwrap();
            pair.right.series[k].points.iter().map(|p| p.0).collect()
        };
        let data = (4.0, rows);
        let weighted = work_precision_weighted("test", &data, vec![], Some(weights));
        assert_eq!(
            xs(&weighted, "bdf"),
            vec![150.0 + 10.0 + 100.0, 450.0 + 20.0 + 300.0]
        );
        assert_eq!(xs(&weighted, "dopri5"), vec![600.0, 1200.0]);
        let plain = work_precision("test", &data, vec![]);
        assert_eq!(xs(&plain, "bdf"), vec![302.0, 704.0]);
        for panel in [&weighted.left, &weighted.right] {
            assert_eq!(figures::line_plot_boxes(panel).unwrap().hidden, 0);
        }
    }
}
