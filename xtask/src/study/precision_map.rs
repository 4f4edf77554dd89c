//! `stability-map`: where each method fails. Every method at every step or
//! tolerance on five scenes, each run to its end under a step budget, sorted
//! into completed / completed with an energy-balance error above 1% of
//! `M g L` / stopped with a status. One panel per method (so that a panel's
//! columns are all steps or all tolerances), one row per scene.
//!
//! The runs are untimed and run in parallel: `stability-map.csv` holds no
//! wall time; with `--timings` each run's wall time (measured beside
//! another run) goes to `stability-map-timing.csv`.

use chain_ode::{Method, Status};
use falling_chain::study::stability::{self, Outcome, Row, MAX_STEPS};
use figures::{CategoryMap, CategoryPanel, RGBColor};

use crate::ctx::Ctx;
use crate::data::{distinct, exp, parse_num};
use crate::registry::{Figure, Make};

/// One row of every panel.
struct MapScene {
    /// Its name in the CSV.
    key: &'static str,
    /// Row label.
    label: &'static str,
    scene: &'static str,
    overrides: &'static [&'static str],
    /// Runs not made, with the reason: (method, tolerances below which).
    skip: Option<(&'static [Method], f64, &'static str)>,
}

const SCENES: [MapScene; 5] = [
    MapScene {
        key: "span-d3",
        label: "span d = 3 (n 50)",
        scene: "span-d3",
        overrides: &[],
        skip: None,
    },
    MapScene {
        key: "folded",
        label: "folded (r = 1e-3)",
        scene: "folded",
        overrides: &[],
        skip: None,
    },
    MapScene {
        key: "folded-r0",
        label: "folded, r = 0",
        scene: "folded",
        overrides: &["chain.damping=0"],
        skip: None,
    },
    MapScene {
        key: "many-rods-n400",
        label: "n = 400 (d = 3)",
        scene: "span-d3",
        overrides: &["chain.links=400", "chain.damping=5e-4"],
        // bdf-dense: 2.5 s per run at rtol 1e-2, 7 s at 1e-3, 11 s at 1e-4
        // (measured on two shared cores): dense 801 x 801 Jacobians and LU.
        skip: Some((
            &[Method::BdfDense],
            1e-3,
            "cost: bdf-dense at n = 400 takes 2.5 to 11 s per run (dense 801 x 801 Jacobian and LU)",
        )),
    },
    MapScene {
        key: "stiff-rope",
        label: "stiff rope (n 100, r 1)",
        scene: "stiff-rope",
        overrides: &[],
        skip: None,
    },
];

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

/// Okabe & Ito's colour-blind-safe palette.
fn color(o: Outcome) -> RGBColor {
    match o {
        Outcome::Completed => RGBColor(0, 158, 115),
        Outcome::EnergyError => RGBColor(230, 159, 0),
        Outcome::Diverged => RGBColor(213, 94, 0),
        Outcome::StepSizeTooSmall => RGBColor(204, 121, 167),
        Outcome::MaxSteps => RGBColor(0, 114, 178),
    }
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

pub struct StabilityMap;

impl Make for StabilityMap {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let rows: Vec<Row> = SCENES
            .iter()
            .map(|s| {
                Ok(Row {
                    key: s.key.into(),
                    label: s.label.into(),
                    prepared: ctx.prepare(s.scene, s.overrides)?,
                })
            })
            .collect::<Result<_, String>>()?;
        let jobs = stability::jobs(rows.len(), &Method::ALL);
        let skip = |row: usize, method: Method, param: f64| {
            SCENES[row]
                .skip
                .filter(|(ms, below, _)| ms.contains(&method) && param < *below)
                .map(|(_, _, why)| why.to_string())
        };
        // Untimed runs: in parallel, at most `ctx.jobs` at once (the order
        // of `jobs` is kept).
        let cells = ctx
            .pool()?
            .install(|| stability::run_cells(&rows, &jobs, &|_| true, &skip, None, &|| {}));
        let csv = stability::csv_text(&rows, &cells, None);
        let mut files = vec![ctx.write(&format!("{}.csv", fig.id), &csv)?];
        if ctx.timings {
            let timing = stability::timing_text(&rows, &cells);
            files.push(ctx.write(&format!("{}-timing.csv", fig.id), &timing)?);
        }
        Ok(files)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
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
        let map = CategoryMap {
            title: "Where each method fails (each scene run to its end, step budget 2e5)",
            x_label: "cell: the power of ten of the energy-balance error / MgL (−5: 1e-5 to 1e-4) \
                      if completed, else the time t it stopped",
            y_label: "scene",
            categories: used
                .iter()
                .map(|&o| (legend(o), color(o)))
                .chain(AUTO_MARK_LEGEND.iter().map(|&(l, c)| (l.to_string(), c)))
                .collect(),
            panels,
        };
        let out = figures::category_map(&map, &ctx.stem(fig.id)).map_err(|e| e.to_string())?;
        Ok(ctx.drawn(&out))
    }
}
