//! Work-precision: every method across tolerances (RK4 across steps), the
//! error of two well-conditioned quantities (the tip position at the end,
//! the maximum tip speed up to it) against a reference computed far tighter
//! than any point and checked by two other methods, and the work (steps,
//! right-hand sides, Jacobians) and wall time of each run.
//!
//! Errors are relative: `|tip - tip_ref| / L` and `|v_max - v_max_ref| /
//! v_max_ref`; the error of a point is the larger of the two.
//!
//! Which points run is a [`Plan`]: the CLI runs every point of the ladder
//! (each method's line from loose to tight, RK4's stopping once it reaches
//! the reference's level, [`ERR_FLOOR`]) within its time budget; `cargo xtask
//! figures` runs the plan its timing file records ([`run_planned`]), or makes
//! it from wall times ([`timed_line`]).

//!
//! The study's parts: its rows ([`Point`], [`Plan`]; `point.rs`), the
//! reference and its checks (`reference.rs`), each method's line of points
//! and how it is run, planned or timed (`lines.rs`), the table and its
//! fastest points (`table.rs`); here, the study of a subject ([`study_of`])
//! and the bounds it checks before any run ([`check_bounds`]).

mod lines;
mod point;
mod reference;
mod table;

pub use lines::*;
pub use point::*;
pub use reference::*;
pub use table::*;

use chain_ode::{Method, Model};

use crate::measure::Measures;
use crate::subject::{Measured, Subject};
use fc_batch::budget::Budget;
use fc_batch::shard::Provenance;
use fc_csv::format::{exp, num};
use fc_scene::error::{echo, Error};

/// The reference: DOPRI5 at these tolerances.
pub const REF_RTOL: f64 = 1e-13;
pub const REF_ATOL: f64 = 1e-15;
/// The second check of the reference: BDF at these tolerances.
pub const CHECK_BDF_RTOL: f64 = 1e-12;
pub const CHECK_BDF_ATOL: f64 = 1e-14;
/// The default RK4 step of the first check of the reference.
pub const CHECK_DT: f64 = 1e-4;

/// RK4's steps, coarse to fine.
pub const RK4_DTS: [f64; 11] = [
    0.02, 0.01, 0.005, 0.002, 0.001, 5e-4, 2e-4, 1e-4, 5e-5, 3e-5, 2e-5,
];
/// The adaptive methods' relative tolerances, loose to tight (atol = rtol / 100).
pub const RTOLS: [f64; 10] = [
    1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12,
];
/// RK4's line stops once both errors are below this (the reference's level).
pub const ERR_FLOOR: f64 = 1e-12;
/// A timed point whose single run is predicted to take longer (s) is not run.
pub const MAX_RUN: f64 = 2.0;
/// Seconds of timed repeats one method's line may spend.
pub const LINE_BUDGET: f64 = 8.0;
/// A timed line whose first run takes longer (s) runs every third tolerance only.
pub const THIN_ABOVE: f64 = 0.5;
/// Repeats of a timed run: more for cheap runs, whose times are noisier.
pub const REPEATS_CHEAP: usize = 5;
pub const REPEATS: usize = 3;

/// Checks, before any run, every bound of every run a study would make on
/// `p`: the reference and its `checks` up to `t_eval`, and each of
/// `methods` at each of its [`params`] (the scene's options, as
/// [`options_for`] sets them). The first bound broken is the error, naming
/// the key and its range; a method none of whose points can run this scene
/// is refused naming `--methods` (leave it out), while a single point out
/// of its method's bounds (RK4's steps past `run.max_steps`) is a row not
/// run, plan [`Plan::Bound`], its note the bound.
pub fn check_bounds<S: Subject>(
    p: &S,
    t_eval: f64,
    checks: Checks,
    methods: &[Method],
) -> Result<(), Error> {
    let plan = ReferencePlan::for_subject(p, STIFF_REF_RTOL);
    for (what, method, o) in reference_runs_planned(t_eval, checks, plan) {
        p.validate(method, &o).map_err(|e| {
            Error::field(
                e.field,
                format!("must be {} for {what} (got {})", e.accepted, echo(&e.got)),
            )
        })?;
    }
    for &m in methods {
        let refused: Vec<_> = params(m)
            .iter()
            .filter_map(|&x| bound_of(p, m, x).map(|e| (x, e)))
            .collect();
        if refused.len() == params(m).len() {
            let (x, e) = &refused[0];
            return Err(Error::field(
                "--methods",
                format!(
                    "{m} cannot run this scene at any {} (leave it out); at {}: {e}",
                    m.accuracy_name(),
                    exp(*x),
                ),
            ));
        }
    }
    Ok(())
}

/// The bound that `method` at accuracy `param` breaks on `p`, if any, as
/// the one line of its error (the point is then not run: plan
/// [`Plan::Bound`]).
pub fn bound_of<S: Subject>(p: &S, method: Method, param: f64) -> Option<String> {
    p.validate(method, &options_for(p, method, param))
        .err()
        .map(|e| Error::from(e).to_string())
}

/// What the CLI's `precision` and Python's `precision` run.
#[derive(Clone, Debug)]
pub struct Options {
    pub methods: Vec<Method>,
    pub checks: Checks,
    /// Seconds (checked: [`fc_batch::budget::check_budget`]).
    pub budget: Option<f64>,
    pub shard: Option<fc_batch::shard::Shard>,
    /// Threads, 1..=256 (checked: [`fc_batch::sweep::check_jobs`]).
    pub jobs: usize,
    /// What the errors measure (`--measure`; `tip` by default).
    pub measures: Measures,
}

/// A finished precision study: the table's rows and what went wrong.
#[derive(Clone, Debug)]
pub struct Study {
    pub name: String,
    pub links: usize,
    pub t_eval: f64,
    /// NaN values when the reference failed.
    pub reference: Reference,
    /// The reference and its checks, then the points in run order.
    pub rows: Vec<Point>,
    pub provenance: Provenance,
    /// One line per reason for exit status 1 (the reference failed or is
    /// not confirmed, every method failed, nothing ran within the budget).
    pub failures: Vec<String>,
    /// Which reference it ran (from the scene's stiffness).
    pub plan: ReferencePlan,
    /// What its errors measure.
    pub measures: Measures,
}

impl Study {
    /// The table, with the wall time, run and provenance columns.
    pub fn csv(&self) -> String {
        csv_text(
            &self.name,
            self.t_eval,
            &self.reference,
            &self.rows,
            Some(&self.provenance),
        )
    }

    /// The points not run (or stopped) for the budget, `method param
    /// value`; a method none of whose points ran as one entry, `method
    /// param first to last (all k)`.
    pub fn skipped(&self) -> Vec<String> {
        let budget = |r: &&Point| r.plan == Plan::Budget;
        let mut out = vec![];
        let mut k = 0;
        while k < self.rows.len() {
            let r = &self.rows[k];
            let line = |p: &&Point| p.run.is_some() && p.method == r.method;
            let mine: Vec<&Point> = self.rows[k..].iter().take_while(line).collect();
            if r.run.is_some() && mine.len() > 2 && mine.iter().all(budget) {
                let last = mine[mine.len() - 1];
                out.push(format!(
                    "{} {} {} to {} (all {})",
                    r.method,
                    r.param_name,
                    exp(r.param),
                    exp(last.param),
                    mine.len()
                ));
                k += mine.len();
                continue;
            }
            if budget(&r) {
                out.push(format!("{} {} {}", r.method, r.param_name, exp(r.param)));
            }
            k += 1;
        }
        out
    }
}

/// Runs the work-precision study of `scene` at its `t_end`: every bound of
/// every run checked first ([`check_bounds`]), then the reference and its
/// checks and the lines of `options.methods` (the shard's points), every
/// phase within the budget, on `options.jobs` threads. `outer` stops it
/// from outside ([`Error::Interrupted`]) in every phase; `progress` hears
/// of each point.
pub fn study(
    scene: &fc_scene::scene::Scene,
    options: &Options,
    outer: Option<&chain_ode::Cancel>,
    progress: &(dyn Fn() + Sync),
) -> Result<Study, Error> {
    let p = scene.prepare()?;
    p.require_corrected("precision")?;
    let methods = &options.methods;
    let mut args = vec![
        methods
            .iter()
            .map(|m| m.as_str())
            .collect::<Vec<_>>()
            .join(","),
        exp(options.checks.check_dt),
        options.checks.richardson.to_string(),
    ];
    if !options.measures.is_tip() {
        args.push(options.measures.names());
    }
    let provenance = Provenance::new(scene, "precision", &args, ladder(methods).len());
    let p = Measured {
        subject: p,
        measures: options.measures,
    };
    study_of(p, scene.name(), provenance, options, outer, progress)
}

/// [`study`] of any [`Subject`] (a model with its start and options, such
/// as BEAM or a model of another crate), named `name` in the table, at its
/// options' `t_end`, with the given provenance columns.
pub fn study_of<S: Subject>(
    mut p: S,
    name: &str,
    provenance: Provenance,
    options: &Options,
    outer: Option<&chain_ode::Cancel>,
    progress: &(dyn Fn() + Sync),
) -> Result<Study, Error> {
    p.options_mut().output_dt = None;
    let t_eval = p.options().t_end;
    let methods = &options.methods;
    check_bounds(&p, t_eval, options.checks, methods)?;
    let shard = options.shard;
    let take = |run: usize| shard.is_none_or(|s| s.takes(run));
    let ref_plan = ReferencePlan::for_subject(&p, STIFF_REF_RTOL);
    let stiff = ref_plan != ReferencePlan::Explicit;
    // A stiff reference resolves errors down to its agreement with its
    // check: a line stops once a point is within ten times that (its
    // tighter points would measure the reference, and on stiff links
    // they are the costliest).
    let level = std::sync::Mutex::new(f64::NAN);
    let resolved = || {
        *level
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    };
    // The floor rule needs the coarser points of RK4's line: a
    // shard runs those it does not own to decide it (`run_lines`).
    let stop = |pt: &Point| rk4_floor(pt) || (stiff && pt.err() < resolved());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.max(1))
        .build()
        .map_err(|e| Error::field("--jobs", e))?;
    // Every phase, the reference and its checks included, runs under the
    // budget and the caller's cancel.
    let (reference, mut rows) = Budget::run(options.budget, outer, |b| {
        let mut p = p.clone();
        p.options_mut().cancel = Some(b.cancel().clone());
        let (reference, mut rows) =
            reference_planned(&p, t_eval, options.checks, ref_plan, &|_, _| {})?;
        if b.interrupted() {
            return Err(Error::Interrupted);
        }
        if stiff {
            let a = agreement(&rows).0;
            if a.is_finite() {
                *level
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner) = (10.0 * a).max(ERR_FLOOR);
            }
        }
        if let Some(r) = &reference {
            let lines = pool.install(|| run_lines(&p, methods, r, &take, b, &stop, progress))?;
            if b.interrupted() {
                return Err(Error::Interrupted);
            }
            rows.extend(lines);
        }
        Ok((reference, rows))
    })?;
    if stiff {
        let level = resolved();
        for r in rows.iter_mut().filter(|r| r.plan == Plan::Floor) {
            r.note = format!(
                "a looser point is already at the stiff reference's level (< {})",
                exp(level)
            );
        }
    }
    let mut failures = vec![];
    let reference = match reference {
        Some(r) => r,
        None => {
            // No error can be measured: every point is a row not run, and
            // says why.
            let stopped = rows[0].plan == Plan::Budget;
            let (plan, note) = if stopped {
                (
                    Plan::Budget,
                    "budget: not run: the reference did not finish within --budget".to_string(),
                )
            } else {
                (Plan::NoReference, Plan::NoReference.note())
            };
            for (run, (m, x)) in ladder(methods).into_iter().enumerate() {
                if take(run) {
                    let mut pt = Point::not_run(m, x, plan, String::new());
                    pt.note.clone_from(&note);
                    pt.run = Some(run);
                    rows.push(pt);
                }
            }
            failures.push(if stopped {
                format!(
                    "--budget stopped the reference run ({}) at t = {} of {}: \
                     no point ran, no error can be measured",
                    reference_name(ref_plan),
                    num(rows[0].t_reached),
                    num(t_eval)
                )
            } else {
                format!(
                    "the reference run ({}) ended {}: no errors can be measured",
                    reference_name(ref_plan),
                    rows[0].status
                )
            });
            Reference::none(p.length())
        }
    };
    let (a_rk4, a_bdf) = agreement(&rows);
    if failures.is_empty() && ![a_rk4, a_bdf].iter().any(|&a| a <= CONFIRMED) {
        let checks = || {
            rows.iter()
                .filter(|r| r.run.is_none() && !r.method.starts_with("reference-"))
        };
        let budget: Vec<&str> = checks()
            .filter(|r| r.plan == Plan::Budget)
            .map(|r| r.method.as_str())
            .collect();
        failures.push(if budget.is_empty() {
            format!(
                "the reference is not confirmed: {} agrees with it to {}",
                if stiff { "its check" } else { "neither check" },
                exp(CONFIRMED)
            )
        } else {
            format!(
                "the reference is not confirmed: --budget stopped its checks before they \
                 finished ({})",
                budget.join(", ")
            )
        });
    }
    // With no reference the points never ran: said above.
    if rows[0].ok() {
        failures.extend(points_failure(&rows));
    }
    Ok(Study {
        name: name.to_string(),
        links: p.model().layout().links,
        t_eval,
        reference,
        rows,
        provenance,
        failures,
        plan: ref_plan,
        measures: p.measures(),
    })
}

/// The reference run of `plan`, as the failures name it (`DOPRI5 rtol
/// 1e-13`).
pub fn reference_name(plan: ReferencePlan) -> String {
    let (_, m, rtol, _) = plan.reference();
    format!("{} rtol {}", m.as_str().to_uppercase(), exp(rtol))
}

/// What went wrong with the points of `rows` (those with a run number), if
/// every one that ran failed or none ran: "every method failed" only when
/// every point that could run ran (none was left out or stopped by the
/// budget, none out of its bounds) and none completed.
pub fn points_failure(rows: &[Point]) -> Option<String> {
    let points = || rows.iter().filter(|r| r.run.is_some());
    let ran: Vec<&Point> = points().filter(|r| r.plan == Plan::Run).collect();
    if points().any(Point::ok) {
        return None;
    }
    let budget = points().filter(|r| r.plan == Plan::Budget).count();
    let bound = points().filter(|r| r.plan == Plan::Bound).count();
    if ran.is_empty() {
        return match (budget, bound) {
            (0, 0) => None,
            (_, 0) => Some("no point ran within --budget".to_string()),
            _ => Some(format!(
                "no point ran ({budget} not run within --budget, {bound} out of their \
                 method's bounds: see the notes)"
            )),
        };
    }
    if budget == 0 && bound == 0 {
        return Some("every method failed on this scene (see the statuses)".into());
    }
    let mut methods: Vec<&str> = ran.iter().map(|r| r.method.as_str()).collect();
    methods.dedup();
    Some(format!(
        "no point completed: {} ran and failed ({}); {budget} not run or stopped by \
         --budget, {bound} out of their method's bounds",
        ran.len(),
        methods.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use chain_ode::Cancel;
    use fc_scene::scene::Prepared;
    use std::sync::Mutex;
    use std::time::Duration;
    use std::time::Instant;

    /// Three rods for `t_end` (the span-d3 chain, cut short).
    fn small(t_end: f64) -> Prepared {
        let text = format!(
            "[chain]\nlength = 6.0\nlinks = 3\nmass = 0.2\ndamping = 0.0005\n\
             [start]\nkind = \"catenary\"\np0 = [0.0, 0.0]\np1 = [3.0, 0.0]\n\
             [run]\nt_end = {t_end}\n"
        );
        let mut p = fc_scene::scene::Scene::from_toml_str(&text)
            .unwrap()
            .prepare()
            .unwrap();
        p.options.output_dt = None;
        p
    }

    /// The budget bounds every phase of the reference: a cancel set 50 ms
    /// after the run of `(row, param)` starts stops that run (its row is
    /// `budget`, `interrupted`, with the time it reached), and the checks
    /// after it are rows not run for the budget. A run that ignored the
    /// cancel (the reference's, a check's) would end `ok`.
    #[test]
    fn a_cancel_stops_each_phase_of_the_reference() {
        let t_end = 1000.0;
        // RK4 at 1e-3 is 10^6 steps, its half 2 10^6: seconds each.
        let checks = Checks {
            check_dt: 1e-3,
            richardson: true,
        };
        let phases = [
            ("reference-dopri5", REF_RTOL),
            ("check-rk4", 1e-3),
            ("check-rk4", 5e-4),
            ("check-bdf", CHECK_BDF_RTOL),
        ];
        for (k, &(row, param)) in phases.iter().enumerate() {
            let mut p = small(t_end);
            let cancel = Cancel::new();
            p.options.cancel = Some(cancel.clone());
            let started: Mutex<Option<Instant>> = Mutex::new(None);
            let done = std::sync::atomic::AtomicBool::new(false);
            let (reference, rows) = std::thread::scope(|s| {
                s.spawn(|| {
                    while !done.load(std::sync::atomic::Ordering::Relaxed) {
                        let at = *started.lock().unwrap();
                        if at.is_some_and(|t| t.elapsed() > Duration::from_millis(50)) {
                            cancel.cancel();
                            return;
                        }
                        std::thread::sleep(Duration::from_millis(5));
                    }
                });
                let out = reference_phases(&p, t_end, checks, &|r, x| {
                    if r == row && x == param {
                        *started.lock().unwrap() = Some(Instant::now());
                    }
                })
                .unwrap();
                done.store(true, std::sync::atomic::Ordering::Relaxed);
                out
            });
            let at = rows
                .iter()
                .position(|r| r.method == row && r.param == param)
                .unwrap_or_else(|| panic!("no row {row} {param}: {rows:?}"));
            let stopped = &rows[at];
            assert_eq!(stopped.status, "interrupted", "{row} {param}: {stopped:?}");
            assert_eq!(stopped.plan, Plan::Budget, "{stopped:?}");
            assert!(stopped.t_reached < t_end, "{stopped:?}");
            assert!(
                stopped.note.starts_with("budget: stopped at t = "),
                "{stopped:?}"
            );
            for later in &rows[at + 1..] {
                assert_eq!(
                    (later.status.as_str(), later.plan),
                    ("not_run", Plan::Budget),
                    "{later:?}"
                );
            }
            assert_eq!(reference.is_some(), k > 0, "{row}");
        }
    }
}
