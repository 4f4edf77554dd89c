//! `stability-map`: where each method fails. Every method at every step or
//! tolerance on five scenes, each run to its end under a step budget, sorted
//! into completed / completed with an energy-balance error above 1% of
//! `M g L` / stopped with a status. One panel per method (so that a panel's
//! columns are all steps or all tolerances), one row per scene.

use std::fmt::Write as _;

use chain_ode::{solve, Accuracy, Method, Status, Trajectory};
use falling_chain::Prepared;
use figures::{CategoryMap, CategoryPanel, RGBColor};
use rayon::prelude::*;

use super::{prepare, short, write_text, written, Ctx};

const ID: &str = "stability-map";
/// The step budget of every run (accepted and rejected steps).
const MAX_STEPS: u64 = 200_000;
/// The energy-balance error allowed, as a fraction of `M g L`.
const ENERGY_LIMIT: f64 = 0.01;
/// RK4's steps.
const DTS: [f64; 8] = [0.02, 0.01, 0.005, 0.002, 0.001, 5e-4, 2e-4, 1e-4];
/// The adaptive methods' relative tolerances (atol = rtol / 100).
const RTOLS: [f64; 7] = [1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12];

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

/// The categories, in legend order.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Outcome {
    Completed,
    EnergyError,
    Diverged,
    StepSizeTooSmall,
    MaxSteps,
}

impl Outcome {
    const ALL: [Outcome; 5] = [
        Outcome::Completed,
        Outcome::EnergyError,
        Outcome::Diverged,
        Outcome::StepSizeTooSmall,
        Outcome::MaxSteps,
    ];

    fn of(t: &Trajectory) -> Outcome {
        match t.status {
            Status::Ok => {
                if relative_energy_error(t) <= ENERGY_LIMIT {
                    Outcome::Completed
                } else {
                    Outcome::EnergyError
                }
            }
            Status::Diverged => Outcome::Diverged,
            // A Newton matrix that cannot be factorised even at smaller
            // steps is, for the map, a step that could not be made.
            Status::StepSizeTooSmall | Status::LinearSolveFailed => Outcome::StepSizeTooSmall,
            Status::MaxSteps => Outcome::MaxSteps,
        }
    }

    fn as_str(self) -> &'static str {
        match self {
            Outcome::Completed => "completed",
            Outcome::EnergyError => "energy_error",
            Outcome::Diverged => "diverged",
            Outcome::StepSizeTooSmall => "step_size_too_small",
            Outcome::MaxSteps => "max_steps",
        }
    }

    fn legend(self) -> String {
        match self {
            Outcome::Completed => "completed, energy error ≤ 1% MgL".into(),
            Outcome::EnergyError => "completed, energy error > 1% MgL".into(),
            Outcome::Diverged => "diverged (non-finite)".into(),
            Outcome::StepSizeTooSmall => "step size too small".into(),
            Outcome::MaxSteps => format!("step budget ({}) used up", short(MAX_STEPS as f64)),
        }
    }

    fn color(self) -> RGBColor {
        match self {
            Outcome::Completed => RGBColor(116, 196, 118),
            Outcome::EnergyError => RGBColor(253, 174, 97),
            Outcome::Diverged => RGBColor(215, 48, 39),
            Outcome::StepSizeTooSmall => RGBColor(117, 107, 177),
            Outcome::MaxSteps => RGBColor(90, 90, 90),
        }
    }
}

/// `max |E + W - E(0)| / (M g L)`.
fn relative_energy_error(t: &Trajectory) -> f64 {
    t.summary.energy_balance_error / (t.chain.weight() * t.chain.length)
}

/// One cell: a run, or the reason it was not made.
struct Cell {
    scene: usize,
    method: Method,
    param: f64,
    run: Result<Trajectory, String>,
}

fn params(m: Method) -> &'static [f64] {
    match m.accuracy() {
        Accuracy::Step => &DTS,
        Accuracy::Tolerance => &RTOLS,
    }
}

fn run_cell(p: &Prepared, method: Method, param: f64) -> Result<Trajectory, String> {
    let mut o = p.options.clone().at_accuracy(method, param);
    o.output_dt = None;
    o.max_steps = MAX_STEPS;
    solve(&p.chain, &p.state, method, &o).map_err(|e| e.to_string())
}

/// Cell text: the energy error's power of ten for a completed run, the
/// time it stopped otherwise.
fn cell_text(t: &Trajectory) -> String {
    match t.status {
        Status::Ok => {
            let e = relative_energy_error(t);
            if e > 0.0 {
                format!("{}", e.log10().floor() as i64)
            } else {
                "0".into()
            }
        }
        _ if t.t_reached < 0.01 => format!("t {:.4}", t.t_reached),
        _ => format!("t {:.2}", t.t_reached),
    }
}

pub fn make(ctx: &Ctx) -> Result<Vec<String>, String> {
    let prepared: Vec<Prepared> = SCENES
        .iter()
        .map(|s| {
            let o: Vec<String> = s.overrides.iter().map(|x| x.to_string()).collect();
            prepare(ctx, s.scene, &o)
        })
        .collect::<Result<_, _>>()?;
    let mut jobs: Vec<(usize, Method, f64)> = vec![];
    for s in 0..SCENES.len() {
        for m in Method::ALL {
            for &x in params(m) {
                jobs.push((s, m, x));
            }
        }
    }
    // Untimed runs: in parallel, at most `ctx.jobs` at once.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(ctx.jobs.max(1))
        .build()
        .map_err(|e| e.to_string())?;
    let cells: Vec<Cell> = pool.install(|| {
        jobs.par_iter()
            .map(|&(s, method, param)| {
                let skipped = SCENES[s]
                    .skip
                    .filter(|(ms, below, _)| ms.contains(&method) && param < *below)
                    .map(|(_, _, why)| why.to_string());
                let run = match skipped {
                    Some(why) => Err(why),
                    None => run_cell(&prepared[s], method, param),
                };
                Cell {
                    scene: s,
                    method,
                    param,
                    run,
                }
            })
            .collect()
    });

    // The data.
    let mut csv = String::from(
        "scene,links,damping,damping_rate,t_end,method,param_name,param,outcome,status,\
         t_reached,t_failed,steps,rejected_steps,rhs_evals,energy_balance_error,energy_scale_mgl,\
         energy_error_rel,bdf_from,wall_seconds,note\n",
    );
    for c in &cells {
        let p = &prepared[c.scene];
        let ch = &p.chain;
        let mgl = ch.weight() * ch.length;
        write!(
            csv,
            "{},{},{},{},{},{},{},{:e},",
            SCENES[c.scene].key,
            ch.links,
            ch.damping,
            ch.damping_rate(),
            p.options.t_end,
            c.method,
            c.method.accuracy_name(),
            c.param
        )
        .unwrap();
        match &c.run {
            Ok(t) => writeln!(
                csv,
                "{},{},{},{},{},{},{},{:e},{mgl},{:e},{},{},",
                Outcome::of(t).as_str(),
                t.status,
                t.t_reached,
                t.t_failed.map_or(String::new(), |x| x.to_string()),
                t.stats.steps,
                t.stats.rejected_steps,
                t.stats.rhs_evals,
                t.summary.energy_balance_error,
                relative_energy_error(t),
                // auto: when it switched to BDF.
                t.segments
                    .iter()
                    .find(|g| g.method == Method::Bdf && c.method == Method::Auto)
                    .map_or(String::new(), |g| g.t_start.to_string()),
                t.summary.wall_seconds,
            ),
            Err(why) => writeln!(csv, "not_run,,,,,,,,{mgl},,,,{}", why.replace(',', ";")),
        }
        .unwrap();
    }
    let mut files = vec![write_text(ctx, &ctx.data.join(format!("{ID}.csv")), &csv)?];

    // The figure: only the categories that occur.
    let used: Vec<Outcome> = Outcome::ALL
        .into_iter()
        .filter(|o| {
            cells
                .iter()
                .any(|c| c.run.as_ref().is_ok_and(|t| Outcome::of(t) == *o))
        })
        .collect();
    let index = |o: Outcome| used.iter().position(|u| *u == o);
    let panels: Vec<CategoryPanel> = Method::ALL
        .into_iter()
        .map(|m| {
            let mut panel = CategoryPanel {
                title: if m == Method::Rk4 {
                    "RK4: step dt".into()
                } else {
                    format!("{}: rtol", m.as_str().to_uppercase())
                },
                row_labels: SCENES.iter().map(|s| s.label.to_string()).collect(),
                col_labels: params(m).iter().map(|&x| short(x)).collect(),
                ..CategoryPanel::default()
            };
            for s in 0..SCENES.len() {
                let mut row = vec![];
                let mut text = vec![];
                for &x in params(m) {
                    let c = cells
                        .iter()
                        .find(|c| c.scene == s && c.method == m && c.param == x)
                        .expect("every cell was run");
                    match &c.run {
                        Ok(t) => {
                            row.push(index(Outcome::of(t)));
                            text.push(cell_text(t));
                        }
                        Err(_) => {
                            row.push(None);
                            text.push("–".into());
                        }
                    }
                }
                panel.cells.push(row);
                panel.cell_text.push(text);
            }
            panel
        })
        .collect();
    let map = CategoryMap {
        title: "Where each method fails (each scene run to its end, step budget 2e5)",
        x_label: "cell: the power of ten of the energy-balance error / MgL (−5: 1e-5 to 1e-4) if \
                  completed, else the time t it stopped",
        y_label: "scene",
        categories: used.iter().map(|o| (o.legend(), o.color())).collect(),
        panels,
    };
    let out = figures::category_map(&map, &ctx.out.join(ID)).map_err(|e| e.to_string())?;
    files.extend(written(ctx, &out));
    Ok(files)
}
