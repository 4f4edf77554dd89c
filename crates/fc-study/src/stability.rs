//! Where each method fails: every method at every step or tolerance, each
//! run to the scene's end under a step budget, sorted into completed /
//! completed with an energy-balance error above 1% of the energy scale
//! `M g L` / stopped with a status. Rows are scenes (one, or one per value
//! of a varied key); the cells of a row are the methods' accuracies.

use chain_ode::{Method, Status, Trajectory};

use crate::measure::{Measure, Measures, Values};
use rayon::prelude::*;

use fc_batch::budget::Budget;
use fc_batch::shard::Provenance;
use fc_csv::format::{exp, num, opt, short, text};
use fc_csv::Column::{self, Float, Int, Text};
use fc_scene::error::Error;
use fc_scene::scene::Prepared;

/// The step budget of every run (accepted and rejected steps).
pub const MAX_STEPS: u64 = 200_000;
/// The energy-balance error allowed, as a fraction of `M g L`.
pub const ENERGY_LIMIT: f64 = 0.01;
/// RK4's steps.
pub const DTS: [f64; 8] = [0.02, 0.01, 0.005, 0.002, 0.001, 5e-4, 2e-4, 1e-4];
/// The adaptive methods' relative tolerances (atol = rtol / 100).
pub const RTOLS: [f64; 7] = [1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12];

/// The columns of the table ([`csv_text`]), before the CLI's extra ones,
/// each with its type (the CSV layer's [`Column`]).
pub const COLUMNS: [(&str, Column); 21] = [
    ("scene", Text),
    ("label", Text),
    ("links", Int),
    ("damping", Float),
    ("damping_rate", Float),
    ("t_end", Float),
    ("method", Text),
    ("param_name", Text),
    ("param", Float),
    ("outcome", Text),
    ("status", Text),
    ("t_reached", Float),
    ("t_failed", Float),
    ("steps", Int),
    ("rejected_steps", Int),
    ("rhs_evals", Int),
    ("energy_balance_error", Float),
    ("energy_scale_mgl", Float),
    ("energy_error_rel", Float),
    ("bdf_from", Float),
    ("note", Text),
];

/// The columns the CLI's table adds before the provenance's
/// ([`fc_batch::shard::COLUMNS`]): the run's wall time (empty for a cell
/// not run) and its number.
pub const CLI_COLUMNS: [(&str, Column); 2] = [("wall_seconds", Float), ("run", Int)];

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
    t.summary.energy_balance_error / t.chain().energy_scale()
}

/// `gen-alpha`'s tolerances: [`RTOLS`] to 1e-8 (of second order, its
/// tighter cells would cost steps no map affords; see
/// `precision::GEN_ALPHA_RTOLS`).
pub const GEN_ALPHA_RTOLS: [f64; 5] = [1e-2, 1e-3, 1e-4, 1e-6, 1e-8];

/// The accuracies of a method's cells.
pub fn params(m: Method) -> &'static [f64] {
    if m.accuracy_name() == "dt" {
        &DTS
    } else if m == Method::GenAlpha {
        &GEN_ALPHA_RTOLS
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
    /// What it measured, and the values (`--measure`; the table's last
    /// columns when not `tip` alone).
    pub measures: Measures,
    pub values: Values,
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

/// The options of a cell: the scene's at the method's accuracy `param`, no
/// samples, at most [`MAX_STEPS`] steps.
pub fn cell_options(p: &Prepared, method: Method, param: f64) -> chain_ode::SolveOptions {
    let mut o = p.options.clone().at_accuracy(method, param);
    o.output_dt = None;
    o.max_steps = MAX_STEPS;
    o
}

/// Runs one cell to the scene's end with at most [`MAX_STEPS`] steps.
pub fn run_cell(
    p: &Prepared,
    method: Method,
    param: f64,
    budget: Option<&Budget>,
) -> Result<Trajectory, String> {
    run_cell_measuring(p, method, param, budget, Measures::TIP)
}

/// [`run_cell`] measuring `measures`: the pivot's force and the tensions
/// tracked exactly when it measures one of them (the studies' one rule),
/// samples kept when it measures the floor's reading.
pub fn run_cell_measuring(
    p: &Prepared,
    method: Method,
    param: f64,
    budget: Option<&Budget>,
    measures: Measures,
) -> Result<Trajectory, String> {
    let mut o = cell_options(p, method, param);
    o.cancel = budget.map(|b| b.cancel().clone());
    o.output_dt = measures.output_dt(o.t_end);
    let run = chain_ode::Solve::new(&p.chain, &p.state, method, &o);
    let t = if measures.tracks_forces() {
        run.run()
    } else {
        run.without_force_peaks().run()
    }
    .map_err(|e| e.to_string())?;
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
    run_cells_measuring(rows, jobs, take, skip, budget, progress, Measures::TIP)
}

/// [`run_cells`] measuring `measures`.
pub fn run_cells_measuring(
    rows: &[Row],
    jobs: &[(usize, Method, f64)],
    take: &(dyn Fn(usize) -> bool + Sync),
    skip: &(dyn Fn(usize, Method, f64) -> Option<String> + Sync),
    budget: Option<&Budget>,
    progress: &(dyn Fn() + Sync),
    measures: Measures,
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
                run_cell_measuring(&rows[row].prepared, method, param, budget, measures)
            };
            progress();
            let values = match &run {
                Ok(t) if !measures.is_tip() => Values::of(t, measures),
                _ => Values::NONE,
            };
            Cell {
                row,
                method,
                param,
                run,
                number,
                measures,
                values,
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

/// The paper's map: each of `methods` at every accuracy on every row
/// ([`jobs`], [`run_cells`] on the current rayon pool, each row's
/// [`Skip`] honoured), as `(suffix, csv)`: the table ([`csv_text`], `""`)
/// and, when `timings`, each run's wall time ([`timing_text`],
/// `-timing`).
pub fn map_tables(
    rows: &[Row],
    methods: &[Method],
    skips: &[Option<Skip>],
    timings: bool,
) -> Vec<(&'static str, String)> {
    let jobs = jobs(rows.len(), methods);
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
    let mut csv = fc_csv::header(&COLUMNS);
    if provenance.is_some() {
        csv.push(',');
        csv.push_str(&fc_csv::header(&CLI_COLUMNS));
        csv.push_str(&Provenance::header_suffix());
    }
    // `--measure` other than the tip: each measure's value, last.
    let measures = cells.first().map_or(Measures::TIP, |c| c.measures);
    let extra: Vec<Measure> = if measures.is_tip() {
        vec![]
    } else {
        measures
            .list()
            .into_iter()
            .filter(|&m| m != Measure::Tip)
            .collect()
    };
    for m in &extra {
        csv.push(',');
        csv.push_str(m.name());
    }
    csv.push('\n');
    for c in cells {
        let row = &rows[c.row];
        let p = &row.prepared;
        let ch = &p.chain;
        let mgl = ch.energy_scale();
        let mut line = [
            fc_csv::field(&row.key).into_owned(),
            text(&row.label),
            ch.links().to_string(),
            short(ch.damping()),
            short(ch.damping_rate()),
            short(p.options.t_end),
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
                    short(t.t_reached),
                    opt(t.t_failed, short),
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
        for &m in &extra {
            line.push(',');
            line.push_str(&num(c.values.get(m)));
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
                fc_csv::field(&rows[c.row].key),
                c.method,
                c.method.accuracy_name(),
                exp(c.param),
                exp(t.summary.wall_seconds)
            ));
        }
    }
    timing
}

/// How one cell of the map ended, for its method's verdict ([`verdict`]).
#[derive(Clone, Debug, PartialEq)]
pub enum CellState {
    Completed,
    /// Ran and failed: any outcome but completed.
    Failed,
    /// Not run (the budget, a bound of the run): why.
    NotRun(String),
}

impl CellState {
    /// The state of `cell`.
    pub fn of(cell: &Cell) -> CellState {
        match &cell.run {
            Ok(t) if Outcome::of(t).failed() => CellState::Failed,
            Ok(_) => CellState::Completed,
            Err(why) => CellState::NotRun(why.clone()),
        }
    }
}

/// One method's line of the CLI's summary, derived from its cells
/// `(accuracy, state)` (every row's, in any order) so that it is true of
/// the table: an accuracy where every row completed is a pass, one where a
/// row failed a fail (one where only some rows ran, all completing, is
/// neither). The passes and fails are given as runs of neighbouring
/// accuracies tried, `<= x` for a run down to the smallest tried, `>= x`
/// for one up to the largest (so "completes every row at dt <= 2e-4; fails
/// at dt >= 5e-4" for RK4's stability limit, and "completes every row at
/// rtol >= 1e-8; fails at rtol <= 1e-10" for a method that fails only
/// when tight). A method that ran nowhere says why; one whose every run failed
/// "fails everywhere tried". `name` is the accuracy's (`dt`, `rtol`).
pub fn verdict(name: &str, cells: &[(f64, CellState)]) -> String {
    let mut params: Vec<f64> = cells.iter().map(|c| c.0).collect();
    params.sort_by(f64::total_cmp);
    params.dedup();
    let not_run = cells
        .iter()
        .filter(|c| matches!(c.1, CellState::NotRun(_)))
        .count();
    let ran = cells.len() - not_run;
    if ran == 0 {
        let why = cells
            .iter()
            .find_map(|c| match &c.1 {
                CellState::NotRun(why) => Some(why.as_str()),
                _ => None,
            })
            .unwrap_or("no cell");
        return format!("not run ({why})");
    }
    // Each accuracy where a verdict holds: Some(true) pass, Some(false) fail.
    let labelled: Vec<(f64, bool)> = params
        .iter()
        .filter_map(|&x| {
            let at = || cells.iter().filter(move |c| c.0 == x).map(|c| &c.1);
            if at().any(|s| *s == CellState::Failed) {
                Some((x, false))
            } else if at().all(|s| *s == CellState::Completed) {
                Some((x, true))
            } else {
                None
            }
        })
        .collect();
    // Runs of neighbours with one label, as text.
    let groups = |pass: bool| -> Vec<String> {
        let mut out = vec![];
        let mut k = 0;
        while k < labelled.len() {
            if labelled[k].1 != pass {
                k += 1;
                continue;
            }
            let start = k;
            while k + 1 < labelled.len() && labelled[k + 1].1 == pass {
                k += 1;
            }
            let (lo, hi) = (labelled[start].0, labelled[k].0);
            let (bottom, top) = (start == 0, k + 1 == labelled.len());
            out.push(match (bottom, top) {
                (true, true) => format!("every {name} tried"),
                _ if lo == hi => format!("{name} {}", exp(lo)),
                (true, false) => format!("{name} <= {}", exp(hi)),
                (false, true) => format!("{name} >= {}", exp(lo)),
                (false, false) => format!("{name} {} to {}", exp(lo), exp(hi)),
            });
            k += 1;
        }
        out
    };
    let (passes, fails) = (groups(true), groups(false));
    let completed = cells.iter().any(|c| c.1 == CellState::Completed);
    let mut line = match (passes.is_empty(), fails.is_empty()) {
        (false, true) => format!(
            "completes every row at {}; fails nowhere it ran",
            passes.join(" and ")
        ),
        (true, false) if !completed => "fails everywhere tried".to_string(),
        (true, false) => format!(
            "completes every row at no {name} tried; fails at {}",
            fails.join(" and ")
        ),
        (false, false) => format!(
            "completes every row at {}; fails at {}",
            passes.join(" and "),
            fails.join(" and ")
        ),
        // Every run completed, but at no accuracy did every row run.
        (true, true) => "completes every run it made; no accuracy ran on every row".to_string(),
    };
    if not_run > 0 {
        line.push_str(&format!("; {not_run} of {} cells not run", cells.len()));
    }
    line
}

/// Each of `methods`' line of the summary ([`verdict`] of its cells).
pub fn verdicts(cells: &[Cell], methods: &[Method]) -> Vec<(Method, String)> {
    methods
        .iter()
        .map(|&m| {
            let mine: Vec<(f64, CellState)> = cells
                .iter()
                .filter(|c| c.method == m)
                .map(|c| (c.param, CellState::of(c)))
                .collect();
            (m, verdict(m.accuracy_name(), &mine))
        })
        .collect()
}

/// Checks, before any run, the bounds of every cell of `methods` on `rows`:
/// a method that no cell of the study can run (`bdf-dense` past its
/// largest chain) is refused, naming `--methods`; a cell whose own bound
/// is broken (RK4's steps past the step budget) stays in the study as not
/// run, with the bound as its reason ([`run_cell`]).
pub fn check_bounds(rows: &[Row], methods: &[Method]) -> Result<(), Error> {
    for &m in methods {
        let mut first = None;
        let mut any = false;
        for row in rows {
            for &x in params(m) {
                match cell_options(&row.prepared, m, x).validate_for(&row.prepared.chain, m) {
                    Ok(()) => any = true,
                    Err(e) => {
                        first.get_or_insert(e);
                    }
                }
            }
        }
        if let (false, Some(e)) = (any, first) {
            return Err(Error::field(
                "--methods",
                format!(
                    "{m} cannot run any cell of this study (leave it out): {}",
                    Error::from(e)
                ),
            ));
        }
    }
    Ok(())
}

/// Runs the study of `rows` with `methods` (every cell, or the shard's) in
/// parallel, with an optional budget: the cells in number order.
pub fn study(
    rows: &[Row],
    methods: &[Method],
    take: &(dyn Fn(usize) -> bool + Sync),
    budget: Option<&Budget>,
    progress: &(dyn Fn(usize) + Sync),
    measures: Measures,
) -> Result<Vec<Cell>, Error> {
    let jobs = jobs(rows.len(), methods);
    let done = std::sync::atomic::AtomicUsize::new(0);
    Ok(run_cells_measuring(
        rows,
        &jobs,
        take,
        &|_, _, _| None,
        budget,
        &|| {
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
        },
        measures,
    ))
}

/// The most rows of a study with a varied key.
pub const MAX_ROWS: usize = 1000;

/// What the CLI's `stability` and Python's `stability` run.
#[derive(Clone, Debug)]
pub struct Options {
    pub methods: Vec<Method>,
    /// A row per value of this key (else one row, the scene).
    pub vary: Option<fc_batch::sweep::Vary>,
    /// Seconds (checked: [`fc_batch::budget::check_budget`]).
    pub budget: Option<f64>,
    pub shard: Option<fc_batch::shard::Shard>,
    /// Threads, 1..=256 (checked: [`fc_batch::sweep::check_jobs`]).
    pub jobs: usize,
    /// What each cell reports beyond its outcome (`--measure`).
    pub measures: Measures,
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
    scene: &fc_scene::scene::Scene,
    vary: Option<&fc_batch::sweep::Vary>,
) -> Result<Vec<Row>, Error> {
    scene.prepare()?.require_corrected("stability")?;
    // A row whose start its run would refuse (a floor above the chain) is
    // refused here, before any cell runs, as the other studies refuse it.
    let checked = |s: &fc_scene::scene::Scene| -> Result<Prepared, Error> {
        let p = s.prepare()?;
        p.check_start()?;
        Ok(p)
    };
    let Some(v) = vary else {
        return Ok(vec![Row {
            key: scene.name().to_string(),
            label: scene.name().to_string(),
            prepared: checked(scene)?,
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
            let s = fc_batch::sweep::scene_for(
                scene,
                std::slice::from_ref(v),
                std::slice::from_ref(x),
            )?;
            // A number in its shortest form (1 and 1.0 are the same row;
            // 1e-300 is not 302 digits).
            let cell = match x {
                toml::Value::String(t) => t.clone(),
                toml::Value::Float(f) => short(*f),
                other => other.to_string(),
            };
            Ok(Row {
                key: format!("{}={cell}", v.key),
                label: format!("{} = {cell}", v.key),
                prepared: checked(&s)?,
            })
        })
        .collect()
}

/// Why the study exits 1, if it does: no cell ran (the budget), or every
/// cell that ran failed; "every method failed" only when every cell ran.
pub fn cells_failure(cells: &[Cell]) -> Option<String> {
    let ran: Vec<&Cell> = cells.iter().filter(|c| c.run.is_ok()).collect();
    let not_run = cells.len() - ran.len();
    let budget = cells
        .iter()
        .filter(|c| c.run.as_ref().is_err_and(|why| why.starts_with("budget")))
        .count();
    if ran.is_empty() {
        return (!cells.is_empty()).then(|| {
            if budget == cells.len() {
                "no cell ran within --budget".to_string()
            } else {
                format!(
                    "no cell ran ({budget} not run within --budget, {} not run for a bound: \
                     see the notes)",
                    not_run - budget
                )
            }
        });
    }
    if ran
        .iter()
        .any(|c| c.run.as_ref().is_ok_and(|t| !Outcome::of(t).failed()))
    {
        return None;
    }
    Some(if not_run == 0 {
        "every method failed on this scene at every step and tolerance".to_string()
    } else {
        format!(
            "every cell that ran failed ({} ran; {not_run} not run: see the notes)",
            ran.len()
        )
    })
}

/// Runs the stability study of `scene` (its rows: [`rows_of`]) with
/// `options`: every cell of the shard, within the budget, on
/// `options.jobs` threads. `outer` stops it from outside
/// ([`Error::Interrupted`]); `progress` hears of each cell.
pub fn run_study(
    scene: &fc_scene::scene::Scene,
    options: &Options,
    outer: Option<&chain_ode::Cancel>,
    progress: &(dyn Fn() + Sync),
) -> Result<Study, Error> {
    let rows = rows_of(scene, options.vary.as_ref())?;
    let methods = &options.methods;
    check_bounds(&rows, methods)?;
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
    let take = |run: usize| shard.is_none_or(|s| s.takes(run));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.max(1))
        .build()
        .map_err(|e| Error::field("--jobs", e))?;
    let limited = options.budget.is_some() || outer.is_some();
    let cells = Budget::run(options.budget, outer, |b| {
        let cells = pool.install(|| {
            study(
                &rows,
                methods,
                &take,
                limited.then_some(b),
                &|_| progress(),
                options.measures,
            )
        });
        if b.interrupted() {
            return Err(Error::Interrupted);
        }
        cells
    })?;
    let failures = cells_failure(&cells).into_iter().collect();
    Ok(Study {
        name: scene.name().to_string(),
        rows,
        cells,
        provenance,
        failures,
    })
}

#[cfg(test)]
mod tests {
    use super::CellState::{Completed, Failed, NotRun};
    use super::*;

    fn cells(states: &[(f64, CellState)]) -> Vec<(f64, CellState)> {
        states.to_vec()
    }

    /// The verdict is what the cells say, whichever way the accuracy runs:
    /// RK4 fails at large steps, an implicit method at tight tolerances (the
    /// line once said "completes every row at rtol <= 1e-2; fails at rtol
    /// >= 1e-12" of the second, both false).
    #[test]
    fn the_verdict_follows_the_cells() {
        let rk4 = cells(&[
            (2e-2, Failed),
            (1e-2, Failed),
            (5e-3, Completed),
            (1e-3, Completed),
        ]);
        assert_eq!(
            verdict("dt", &rk4),
            "completes every row at dt <= 5e-3; fails at dt >= 1e-2"
        );
        let tight = cells(&[
            (1e-2, Completed),
            (1e-4, Completed),
            (1e-8, Completed),
            (1e-10, Failed),
            (1e-12, Failed),
        ]);
        assert_eq!(
            verdict("rtol", &tight),
            "completes every row at rtol >= 1e-8; fails at rtol <= 1e-10"
        );
        // Failing at both ends, and a lone failure inside (a run of one
        // accuracy is named alone).
        let both = cells(&[
            (1e-2, Failed),
            (1e-3, Completed),
            (1e-4, Failed),
            (1e-6, Completed),
            (1e-8, Completed),
            (1e-12, Failed),
        ]);
        assert_eq!(
            verdict("rtol", &both),
            "completes every row at rtol 1e-8 to 1e-6 and rtol 1e-3; \
             fails at rtol 1e-12 and rtol 1e-4 and rtol 1e-2"
        );
    }

    /// With two rows, an accuracy passes only where both completed; a cell
    /// not run makes its accuracy neither, and is counted.
    #[test]
    fn the_verdict_of_several_rows_and_cells_not_run() {
        let two = cells(&[
            (1e-2, Completed),
            (1e-2, Failed),
            (1e-3, Completed),
            (1e-3, Completed),
            (1e-4, Completed),
            (1e-4, NotRun("budget: not run within --budget".into())),
        ]);
        assert_eq!(
            verdict("rtol", &two),
            "completes every row at rtol 1e-3; fails at rtol 1e-2; 1 of 6 cells not run"
        );
    }

    /// Nothing ran: the reason, never "none tried" or "fails nowhere";
    /// every run failed: "fails everywhere tried"; every run completed:
    /// "every rtol tried".
    #[test]
    fn the_verdict_when_nothing_ran_or_everything_failed() {
        let why = "budget: not run within --budget";
        let none = cells(&[(1e-2, NotRun(why.into())), (1e-3, NotRun(why.into()))]);
        assert_eq!(verdict("rtol", &none), format!("not run ({why})"));
        let failed = cells(&[(1e-2, Failed), (1e-3, Failed)]);
        assert_eq!(verdict("rtol", &failed), "fails everywhere tried");
        let ok = cells(&[(1e-2, Completed), (1e-3, Completed)]);
        assert_eq!(
            verdict("rtol", &ok),
            "completes every row at every rtol tried; fails nowhere it ran"
        );
    }
}
