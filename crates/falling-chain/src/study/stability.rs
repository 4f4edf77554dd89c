//! Where each method fails: every method at every step or tolerance, each
//! run to the scene's end under a step budget, sorted into completed /
//! completed with an energy-balance error above 1% of the energy scale
//! `M g L` / stopped with a status. Rows are scenes (one, or one per value
//! of a varied key); the cells of a row are the methods' accuracies.

use chain_ode::{solve, Method, Status, Trajectory};
use rayon::prelude::*;

use super::budget::Budget;
use super::format::{exp, num, opt, text};
use super::shard::Provenance;
use crate::error::Error;
use crate::scene::Prepared;

/// The step budget of every run (accepted and rejected steps).
pub const MAX_STEPS: u64 = 200_000;
/// The energy-balance error allowed, as a fraction of `M g L`.
pub const ENERGY_LIMIT: f64 = 0.01;
/// RK4's steps.
pub const DTS: [f64; 8] = [0.02, 0.01, 0.005, 0.002, 0.001, 5e-4, 2e-4, 1e-4];
/// The adaptive methods' relative tolerances (atol = rtol / 100).
pub const RTOLS: [f64; 7] = [1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12];

/// The columns of the table ([`csv_text`]), before the CLI's extra ones.
pub const COLUMNS: &str = "scene,label,links,damping,damping_rate,t_end,method,param_name,param,\
                           outcome,status,t_reached,t_failed,steps,rejected_steps,rhs_evals,\
                           energy_balance_error,energy_scale_mgl,energy_error_rel,bdf_from,note";

/// How a cell's run ended, in legend order.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Outcome {
    Completed,
    EnergyError,
    Diverged,
    StepSizeTooSmall,
    MaxSteps,
}

impl Outcome {
    pub const ALL: [Outcome; 5] = [
        Outcome::Completed,
        Outcome::EnergyError,
        Outcome::Diverged,
        Outcome::StepSizeTooSmall,
        Outcome::MaxSteps,
    ];

    pub fn parse(s: &str) -> Option<Outcome> {
        Outcome::ALL.into_iter().find(|o| o.as_str() == s)
    }

    pub fn of(t: &Trajectory) -> Outcome {
        match t.status {
            Status::Ok => {
                if relative_energy_error(t) <= ENERGY_LIMIT {
                    Outcome::Completed
                } else {
                    Outcome::EnergyError
                }
            }
            // Past the energy scale: already more than the map's 1% limit.
            Status::Inaccurate => Outcome::EnergyError,
            Status::Diverged => Outcome::Diverged,
            // A Newton matrix that cannot be factorised even at smaller
            // steps is, for the map, a step that could not be made.
            Status::StepSizeTooSmall | Status::LinearSolveFailed => Outcome::StepSizeTooSmall,
            // A run stopped from outside would, like a spent budget, not
            // have reached t_end (the study lists budget stops as not run).
            Status::MaxSteps | Status::Interrupted => Outcome::MaxSteps,
        }
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Outcome::Completed => "completed",
            Outcome::EnergyError => "energy_error",
            Outcome::Diverged => "diverged",
            Outcome::StepSizeTooSmall => "step_size_too_small",
            Outcome::MaxSteps => "max_steps",
        }
    }

    /// Whether the method failed here (did not complete within the
    /// energy limit).
    pub fn failed(self) -> bool {
        self != Outcome::Completed
    }
}

/// `max |E + W - E(0)| / E_s`, with `E_s` the chain's energy scale
/// ([`chain_ode::Chain::energy_scale`]: `M g L`, or `M L^2` per time unit
/// squared at `g = 0`).
pub fn relative_energy_error(t: &Trajectory) -> f64 {
    t.summary.energy_balance_error / t.chain.energy_scale()
}

/// The accuracies of a method's cells.
pub fn params(m: Method) -> &'static [f64] {
    if m.accuracy_name() == "dt" {
        &DTS
    } else {
        &RTOLS
    }
}

/// One row of the map: a scene, its name in the table and its label.
#[derive(Clone, Debug)]
pub struct Row {
    pub key: String,
    pub label: String,
    pub prepared: Prepared,
}

/// One cell: a run, or the reason it was not made.
pub struct Cell {
    /// The index of its row.
    pub row: usize,
    pub method: Method,
    pub param: f64,
    pub run: Result<Trajectory, String>,
    /// Its number in the study ([`jobs`] order).
    pub number: usize,
}

/// The cells of the study, numbered in this order: each row, each of
/// `methods`, each of its [`params`].
pub fn jobs(rows: usize, methods: &[Method]) -> Vec<(usize, Method, f64)> {
    let mut jobs = vec![];
    for r in 0..rows {
        for &m in methods {
            for &x in params(m) {
                jobs.push((r, m, x));
            }
        }
    }
    jobs
}

/// Runs one cell to the scene's end with at most [`MAX_STEPS`] steps.
pub fn run_cell(
    p: &Prepared,
    method: Method,
    param: f64,
    budget: Option<&Budget>,
) -> Result<Trajectory, String> {
    let mut o = p.options.clone().at_accuracy(method, param);
    o.output_dt = None;
    o.max_steps = MAX_STEPS;
    o.cancel = budget.map(|b| b.cancel().clone());
    let t = solve(&p.chain, &p.state, method, &o).map_err(|e| e.to_string())?;
    if budget.is_some() && t.status == Status::Interrupted {
        return Err(format!(
            "budget: stopped at t = {} by --budget",
            num(t.t_reached)
        ));
    }
    Ok(t)
}

/// Runs the cells `jobs` (row, method, accuracy) whose number `take`
/// accepts, in parallel on the current rayon pool (their order kept);
/// `skip(row, method, accuracy)` gives the reason a cell is not made, if
/// any; a cell the budget has no time left for is not made either.
/// `progress` is called after each cell.
pub fn run_cells(
    rows: &[Row],
    jobs: &[(usize, Method, f64)],
    take: &(dyn Fn(usize) -> bool + Sync),
    skip: &(dyn Fn(usize, Method, f64) -> Option<String> + Sync),
    budget: Option<&Budget>,
    progress: &(dyn Fn() + Sync),
) -> Vec<Cell> {
    let chosen: Vec<(usize, (usize, Method, f64))> = jobs
        .iter()
        .copied()
        .enumerate()
        .filter(|&(k, _)| take(k))
        .collect();
    chosen
        .par_iter()
        .map(|&(number, (row, method, param))| {
            let run = if let Some(why) = skip(row, method, param) {
                Err(why)
            } else if budget.is_some_and(|b| !b.fits(0.0)) {
                Err("budget: not run within --budget".to_string())
            } else {
                run_cell(&rows[row].prepared, method, param, budget)
            };
            progress();
            Cell {
                row,
                method,
                param,
                run,
                number,
            }
        })
        .collect()
}

/// Cells of a row not made, and why: those of `methods` at accuracies
/// below `below` (for the cost of a run).
#[derive(Clone, Copy, Debug)]
pub struct Skip {
    pub methods: &'static [Method],
    pub below: f64,
    pub why: &'static str,
}

/// The paper's map: every method at every accuracy on every row
/// ([`jobs`], [`run_cells`] on the current rayon pool, each row's
/// [`Skip`] honoured), as `(suffix, csv)`: the table ([`csv_text`], `""`)
/// and, when `timings`, each run's wall time ([`timing_text`],
/// `-timing`).
pub fn map_tables(
    rows: &[Row],
    skips: &[Option<Skip>],
    timings: bool,
) -> Vec<(&'static str, String)> {
    let jobs = jobs(rows.len(), &Method::ALL);
    let skip = |row: usize, method: Method, param: f64| {
        skips[row]
            .filter(|s| s.methods.contains(&method) && param < s.below)
            .map(|s| s.why.to_string())
    };
    let cells = run_cells(rows, &jobs, &|_| true, &skip, None, &|| {});
    let mut files = vec![("", csv_text(rows, &cells, None))];
    if timings {
        files.push(("-timing", timing_text(rows, &cells)));
    }
    files
}

/// The table: a header line ([`COLUMNS`]) and a row per cell. With
/// `provenance` (the CLI's), each row also has its wall time, its number
/// and the provenance columns: `wall_seconds,run,runs,scene_hash`.
pub fn csv_text(rows: &[Row], cells: &[Cell], provenance: Option<&Provenance>) -> String {
    let mut csv = String::from(COLUMNS);
    if provenance.is_some() {
        csv.push_str(",wall_seconds,run");
        csv.push_str(&Provenance::header_suffix());
    }
    csv.push('\n');
    for c in cells {
        let row = &rows[c.row];
        let p = &row.prepared;
        let ch = &p.chain;
        let mgl = ch.energy_scale();
        let mut line = [
            crate::csv::field(&row.key).into_owned(),
            text(&row.label),
            ch.links().to_string(),
            num(ch.damping()),
            num(ch.damping_rate()),
            num(p.options.t_end),
            c.method.to_string(),
            c.method.accuracy_name().to_string(),
            exp(c.param),
        ]
        .join(",");
        line.push(',');
        let wall = match &c.run {
            Ok(t) => {
                let cells = [
                    Outcome::of(t).as_str().to_string(),
                    t.status.to_string(),
                    num(t.t_reached),
                    opt(t.t_failed, num),
                    t.stats.steps.to_string(),
                    t.stats.rejected_steps.to_string(),
                    t.stats.rhs_evals.to_string(),
                    exp(t.summary.energy_balance_error),
                    num(mgl),
                    exp(relative_energy_error(t)),
                    // auto: when it switched to BDF.
                    opt(
                        t.segments
                            .iter()
                            .find(|g| g.method == Method::Bdf && c.method == Method::Auto)
                            .map(|g| g.t_start),
                        num,
                    ),
                    String::new(),
                ];
                line.push_str(&cells.join(","));
                exp(t.summary.wall_seconds)
            }
            Err(why) => {
                line.push_str(&format!("not_run,,,,,,,,{},,,{}", num(mgl), text(why)));
                String::new()
            }
        };
        if let Some(prov) = provenance {
            line.push_str(&format!(",{wall},{}{}", c.number, prov.cells()));
        }
        csv.push_str(&line);
        csv.push('\n');
    }
    csv
}

/// The timing table of `cargo xtask figures --timings`:
/// `scene,method,param_name,param,wall_seconds`, a line per cell that ran.
pub fn timing_text(rows: &[Row], cells: &[Cell]) -> String {
    let mut timing = String::from("scene,method,param_name,param,wall_seconds\n");
    for c in cells {
        if let Ok(t) = &c.run {
            timing.push_str(&format!(
                "{},{},{},{},{}\n",
                crate::csv::field(&rows[c.row].key),
                c.method,
                c.method.accuracy_name(),
                exp(c.param),
                exp(t.summary.wall_seconds)
            ));
        }
    }
    timing
}

/// The largest step or tolerance at which each method completed every row
/// of `cells` within the energy limit, and the smallest at which it failed
/// one: `(method, largest_completed, smallest_failed)` in `methods` order.
/// For RK4 (a step) a failure at a large step and success below it is the
/// stability limit.
pub fn limits(cells: &[Cell], methods: &[Method]) -> Vec<(Method, Option<f64>, Option<f64>)> {
    methods
        .iter()
        .map(|&m| {
            let mine = || cells.iter().filter(move |c| c.method == m);
            let failed = |c: &Cell| c.run.as_ref().is_ok_and(|t| Outcome::of(t).failed());
            let completed = |c: &Cell| c.run.as_ref().is_ok_and(|t| !Outcome::of(t).failed());
            let params: Vec<f64> = {
                let mut v: Vec<f64> = mine().map(|c| c.param).collect();
                v.sort_by(f64::total_cmp);
                v.dedup();
                v
            };
            // An accuracy passes if every row completed there.
            let passes = |x: f64| mine().filter(|c| c.param == x).all(completed);
            let largest_ok = params.iter().rev().copied().find(|&x| passes(x));
            let smallest_failed = mine()
                .filter(|c| failed(c))
                .map(|c| c.param)
                .min_by(f64::total_cmp);
            (m, largest_ok, smallest_failed)
        })
        .collect()
}

/// Runs the study of `rows` with `methods` (every cell, or the shard's) in
/// parallel, with an optional budget: the cells in number order.
pub fn study(
    rows: &[Row],
    methods: &[Method],
    take: &(dyn Fn(usize) -> bool + Sync),
    budget: Option<&Budget>,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<Cell>, Error> {
    let jobs = jobs(rows.len(), methods);
    let done = std::sync::atomic::AtomicUsize::new(0);
    Ok(run_cells(
        rows,
        &jobs,
        take,
        &|_, _, _| None,
        budget,
        &|| {
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
        },
    ))
}

/// The most rows of a study with a varied key.
pub const MAX_ROWS: usize = 1000;

/// What the CLI's `stability` and Python's `stability` run.
#[derive(Clone, Debug)]
pub struct Options {
    pub methods: Vec<Method>,
    /// A row per value of this key (else one row, the scene).
    pub vary: Option<crate::sweep::Vary>,
    /// Seconds (checked: [`super::budget::check_budget`]).
    pub budget: Option<f64>,
    pub shard: Option<crate::sweep::Shard>,
    /// Threads, 1..=256 (checked: [`crate::sweep::check_jobs`]).
    pub jobs: usize,
}

/// A finished stability study.
pub struct Study {
    pub name: String,
    pub rows: Vec<Row>,
    pub cells: Vec<Cell>,
    pub provenance: Provenance,
    /// One line per reason for exit status 1 (every run failed).
    pub failures: Vec<String>,
}

impl Study {
    /// The table, with the wall time, run and provenance columns.
    pub fn csv(&self) -> String {
        csv_text(&self.rows, &self.cells, Some(&self.provenance))
    }

    /// The cells not run (or stopped) for the budget.
    pub fn skipped(&self) -> Vec<String> {
        self.cells
            .iter()
            .filter_map(|c| match &c.run {
                Err(why) if why.starts_with("budget") => Some(format!(
                    "{} {} {} ({})",
                    c.method,
                    c.method.accuracy_name(),
                    exp(c.param),
                    self.rows[c.row].key
                )),
                _ => None,
            })
            .collect()
    }
}

/// The rows of a study of `scene`: the scene, or one per value of `vary`
/// (at most [`MAX_ROWS`], each scene checked), named `KEY=VALUE`.
pub fn rows_of(
    scene: &crate::scene::Scene,
    vary: Option<&crate::sweep::Vary>,
) -> Result<Vec<Row>, Error> {
    scene.prepare()?.require_corrected("stability")?;
    let Some(v) = vary else {
        return Ok(vec![Row {
            key: scene.name().to_string(),
            label: scene.name().to_string(),
            prepared: scene.prepare()?,
        }]);
    };
    if v.values.len() > MAX_ROWS {
        return Err(Error::field(
            "--vary",
            format!("at most {MAX_ROWS} values (got {})", v.values.len()),
        ));
    }
    v.values
        .iter()
        .map(|x| {
            let s =
                crate::sweep::scene_for(scene, std::slice::from_ref(v), std::slice::from_ref(x))?;
            // A number as `{}` prints it: 1 and 1.0 are the same row.
            let cell = match x {
                toml::Value::String(t) => t.clone(),
                toml::Value::Float(f) => format!("{f}"),
                other => other.to_string(),
            };
            Ok(Row {
                key: format!("{}={cell}", v.key),
                label: format!("{} = {cell}", v.key),
                prepared: s.prepare()?,
            })
        })
        .collect()
}

/// Runs the stability study of `scene` (its rows: [`rows_of`]) with
/// `options`: every cell of the shard, within the budget, on
/// `options.jobs` threads. `outer` stops it from outside
/// ([`Error::Interrupted`]); `progress` hears of each cell.
pub fn run_study(
    scene: &crate::scene::Scene,
    options: &Options,
    outer: Option<&chain_ode::Cancel>,
    progress: &(dyn Fn() + Sync),
) -> Result<Study, Error> {
    let rows = rows_of(scene, options.vary.as_ref())?;
    let methods = &options.methods;
    let total = jobs(rows.len(), methods).len();
    let keys: Vec<String> = rows.iter().map(|r| r.key.clone()).collect();
    let provenance = Provenance::new(
        scene,
        "stability",
        &[
            methods
                .iter()
                .map(|m| m.as_str())
                .collect::<Vec<_>>()
                .join(","),
            keys.join(";"),
        ],
        total,
    );
    let shard = options.shard;
    let take = |run: usize| shard.is_none_or(|s| run % s.count == s.index);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.max(1))
        .build()
        .map_err(|e| Error::field("--jobs", e))?;
    let limited = options.budget.is_some() || outer.is_some();
    let cells = Budget::run(options.budget, outer, |b| {
        let cells =
            pool.install(|| study(&rows, methods, &take, limited.then_some(b), &|_| progress()));
        if b.interrupted() {
            return Err(Error::Interrupted);
        }
        cells
    })?;
    let ran: Vec<&Cell> = cells.iter().filter(|c| c.run.is_ok()).collect();
    let mut failures = vec![];
    if !ran.is_empty()
        && ran
            .iter()
            .all(|c| c.run.as_ref().is_ok_and(|t| Outcome::of(t).failed()))
    {
        failures.push("every method failed on this scene at every step and tolerance".to_string());
    }
    Ok(Study {
        name: scene.name().to_string(),
        rows,
        cells,
        provenance,
        failures,
    })
}
