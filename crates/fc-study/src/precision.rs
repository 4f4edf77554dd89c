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

use std::time::Instant;

use chain_ode::{Cancel, Method, Model, SolveOptions, Stats, Status, Trajectory};
use rayon::prelude::*;

use crate::subject::Subject;
use fc_batch::budget::Budget;
use fc_batch::shard::Provenance;
use fc_csv::format::{exp, num, text};
use fc_csv::Column::{self, Float, Int, Text};
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

/// The columns of the table ([`csv_text`]), before the CLI's extra ones,
/// each with its type (the CSV layer's [`Column`]).
pub const COLUMNS: [(&str, Column); 20] = [
    ("scene", Text),
    ("t_eval", Float),
    ("method", Text),
    ("param_name", Text),
    ("param", Float),
    ("status", Text),
    ("t_reached", Float),
    ("steps", Int),
    ("rejected_steps", Int),
    ("rhs_evals", Int),
    ("jacobian_evals", Int),
    ("lu_factorizations", Int),
    ("rhs_equiv", Int),
    ("switched", Int),
    ("err_tip", Float),
    ("err_vmax", Float),
    ("tip_ref_x", Float),
    ("tip_ref_y", Float),
    ("vmax_ref", Float),
    ("note", Text),
];

/// The columns the CLI's table adds before the provenance's
/// ([`fc_batch::shard::COLUMNS`]): the median wall time and the run number
/// (empty for the reference and its checks).
pub const CLI_COLUMNS: [(&str, Column); 2] = [("wall_seconds", Float), ("run", Int)];

/// Whether a point runs, and if not, why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plan {
    Run,
    /// Predicted too costly when timed (see [`MAX_RUN`], [`LINE_BUDGET`]).
    Cost,
    /// Thinned: the timed line's first run took more than [`THIN_ABOVE`].
    Thinned,
    /// RK4 only: a coarser step already reached [`ERR_FLOOR`].
    Floor,
    /// Not run, or stopped, within the time budget (`--budget`).
    Budget,
    /// Not run: the reference run failed, so no error could be measured.
    NoReference,
    /// Not run: the point's options break a bound of its method (RK4's
    /// steps past `run.max_steps`); the note gives it.
    Bound,
}

impl Plan {
    pub const ALL: [Plan; 7] = [
        Plan::Run,
        Plan::Cost,
        Plan::Thinned,
        Plan::Floor,
        Plan::Budget,
        Plan::NoReference,
        Plan::Bound,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            Plan::Run => "run",
            Plan::Cost => "cost",
            Plan::Thinned => "thinned",
            Plan::Floor => "floor",
            Plan::Budget => "budget",
            Plan::NoReference => "no_reference",
            Plan::Bound => "bound",
        }
    }

    pub fn parse(s: &str) -> Result<Plan, String> {
        Plan::ALL
            .into_iter()
            .find(|p| p.as_str() == s)
            .ok_or_else(|| format!("unknown plan '{s}'"))
    }

    /// Why the point was not run, without wall times.
    pub fn note(self) -> String {
        match self {
            Plan::Run => String::new(),
            Plan::Cost => format!(
                "cost: predicted above {MAX_RUN} s per run or {LINE_BUDGET} s per line when timed"
            ),
            Plan::Thinned => format!("thinned: a run took > {THIN_ABOVE} s when timed"),
            Plan::Floor => format!(
                "a coarser dt is already at the reference's level (< {})",
                exp(ERR_FLOOR)
            ),
            Plan::Budget => "budget: not run within --budget".into(),
            Plan::NoReference => {
                "not run: the reference run failed (no error can be measured)".into()
            }
            Plan::Bound => "not run: out of its method's bounds".into(),
        }
    }
}

/// The reference values the errors are measured against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reference {
    pub tip: [f64; 2],
    pub vmax: f64,
    pub length: f64,
}

impl Reference {
    /// Relative errors `(|tip - tip_ref| / L, |vmax - vmax_ref| / vmax_ref)`.
    pub fn errors<M: Model>(&self, t: &Trajectory<M>) -> (f64, f64) {
        let s = &t.summary;
        self.errors_of(s.tip_end, s.tip_speed_max)
    }

    /// The relative errors of a tip position and maximum speed.
    pub fn errors_of(&self, tip: [f64; 2], vmax: f64) -> (f64, f64) {
        let e_tip = (tip[0] - self.tip[0]).hypot(tip[1] - self.tip[1]) / self.length;
        let e_v = (vmax - self.vmax).abs() / self.vmax;
        (e_tip, e_v)
    }
}

/// One row of the table: a run (or a point not run) and its errors.
#[derive(Clone, Debug)]
pub struct Point {
    /// A method's name, or `reference-dopri5`, `check-rk4`,
    /// `check-rk4-richardson`, `check-bdf`.
    pub method: String,
    /// `dt` or `rtol`.
    pub param_name: &'static str,
    pub param: f64,
    pub plan: Plan,
    pub status: String,
    pub t_reached: f64,
    pub stats: Stats,
    /// The size of the state (`2 n + 1`).
    pub dim: usize,
    pub err_tip: f64,
    pub err_vmax: f64,
    /// For `auto`: whether it switched to BDF.
    pub switched: bool,
    /// Why it failed or was not run (no wall times).
    pub note: String,
    /// Wall times (s) of its runs (one, or the repeats when timed).
    pub walls: Vec<f64>,
    /// A timed point's note with wall times (for the timing file).
    pub timing_note: String,
    /// How to run it again (completed, timed points only).
    pub rerun: Option<(Method, SolveOptions)>,
    /// Its number in the ladder (`None` for the reference and its checks).
    pub run: Option<usize>,
}

impl Point {
    /// RHS evaluations plus one per Jacobian-vector product.
    pub fn rhs_equiv(&self) -> u64 {
        self.stats.rhs_evals + self.stats.jacobian_evals * self.dim as u64
    }

    /// The larger of the two errors (NaN if not run or failed).
    pub fn err(&self) -> f64 {
        self.err_tip.max(self.err_vmax)
    }

    /// Whether it completed with finite errors.
    pub fn ok(&self) -> bool {
        self.status == "ok" && self.err_tip.is_finite() && self.err_vmax.is_finite()
    }

    /// A point of `method` at accuracy `param` that was not run.
    pub fn not_run(method: Method, param: f64, plan: Plan, timing_note: String) -> Point {
        Point {
            method: method.as_str().into(),
            param_name: method.accuracy_name(),
            param,
            plan,
            status: "not_run".into(),
            t_reached: f64::NAN,
            stats: Stats::default(),
            dim: 0,
            err_tip: f64::NAN,
            err_vmax: f64::NAN,
            switched: false,
            note: plan.note(),
            walls: vec![],
            timing_note,
            rerun: None,
            run: None,
        }
    }

    /// The row of a finished run of `subject`, its errors measured
    /// against `reference` ([`Subject::errors`]).
    pub fn from_run<S: Subject>(
        method: String,
        param_name: &'static str,
        param: f64,
        t: &Trajectory<S::Model>,
        subject: &S,
        reference: &Reference,
    ) -> Point {
        let (err_tip, err_vmax) = if t.status.is_ok() {
            subject.errors(reference, t)
        } else {
            (f64::NAN, f64::NAN)
        };
        let note = match t.t_failed {
            Some(tf) => format!("failed at t = {tf:.4}"),
            None => String::new(),
        };
        Point {
            method,
            param_name,
            param,
            plan: Plan::Run,
            status: t.status.as_str().into(),
            t_reached: t.t_reached,
            stats: t.stats,
            dim: 2 * t.model.layout().links + 1,
            err_tip,
            err_vmax,
            switched: t.segments.len() > 1,
            note,
            walls: vec![t.summary.wall_seconds],
            timing_note: String::new(),
            rerun: None,
            run: None,
        }
    }
}

/// `gen-alpha`'s tolerances, loose to tight: of second order, it reaches
/// the tighter ones only in steps that no study affords (its steps grow
/// like `rtol^(-1/3)`), so its line stops at 1e-8.
pub const GEN_ALPHA_RTOLS: [f64; 6] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];

/// The accuracies a method's line runs over: RK4's steps, the others'
/// tolerances (gen-alpha's its own, [`GEN_ALPHA_RTOLS`]).
pub fn params(method: Method) -> &'static [f64] {
    if method.accuracy_name() == "dt" {
        &RK4_DTS
    } else if method == Method::GenAlpha {
        &GEN_ALPHA_RTOLS
    } else {
        &RTOLS
    }
}

/// The ladder's points, numbered in this order: each of `methods`, each of
/// its [`params`].
pub fn ladder(methods: &[Method]) -> Vec<(Method, f64)> {
    methods
        .iter()
        .flat_map(|&m| params(m).iter().map(move |&x| (m, x)))
        .collect()
}

/// The options of a point: the subject's, with the method's accuracy
/// `param` and no samples ([`Subject::options_for`]; for a scene, atol =
/// rtol / 100).
pub fn options_for<S: Subject>(p: &S, method: Method, param: f64) -> SolveOptions {
    p.options_for(method, param)
}

/// The reference's options: DOPRI5's [`REF_RTOL`], [`REF_ATOL`] up to `t_end`.
pub fn reference_options(t_end: f64) -> SolveOptions {
    SolveOptions {
        t_end,
        rtol: REF_RTOL,
        atol: REF_ATOL,
        output_dt: None,
        ..SolveOptions::default()
    }
}

/// How the reference is checked: RK4 at `check_dt` (and, with `richardson`,
/// at its half, extrapolated), and BDF at [`CHECK_BDF_RTOL`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Checks {
    pub check_dt: f64,
    pub richardson: bool,
}

impl Default for Checks {
    fn default() -> Self {
        Self {
            check_dt: CHECK_DT,
            richardson: false,
        }
    }
}

/// The reference run and its checks: the reference (if its run ended
/// `ok`) and their rows (the reference's first). Runs on the scene's chain
/// and start up to `t_eval`, stopped by the scene's cancel flag if it has
/// one (a time budget): a run it stops is a row of plan `budget` whose note
/// says where it stopped, and the checks after it are rows not run (plan
/// `budget`), so that the table says which phase the budget ended.
pub fn reference<S: Subject>(
    p: &S,
    t_eval: f64,
    checks: Checks,
) -> Result<(Option<Reference>, Vec<Point>), Error> {
    reference_phases(p, t_eval, checks, &|_, _| {})
}

/// [`reference`], calling `phase(row, param)` as each of its runs starts
/// (`reference-dopri5`, `check-rk4` at `check_dt` and at its half,
/// `check-bdf`).
pub fn reference_phases<S: Subject>(
    p: &S,
    t_eval: f64,
    checks: Checks,
    phase: &dyn Fn(&str, f64),
) -> Result<(Option<Reference>, Vec<Point>), Error> {
    let ref_opts = SolveOptions {
        cancel: p.options().cancel.clone(),
        ..reference_options(t_eval)
    };
    let cancelled = || ref_opts.cancel.as_ref().is_some_and(Cancel::is_cancelled);
    let run = |method: Method, o: &SolveOptions| -> Result<Trajectory<S::Model>, Error> {
        Ok(p.solve(method, o)?)
    };
    phase("reference-dopri5", REF_RTOL);
    let r = run(Method::Dopri5, &ref_opts)?;
    let reference = Reference {
        tip: r.summary.tip_end,
        vmax: r.summary.tip_speed_max,
        length: p.length(),
    };
    let row = |name: &str, param_name: &'static str, param: f64, t: &Trajectory<S::Model>| {
        let mut pt = Point::from_run(name.into(), param_name, param, t, p, &reference);
        if t.status == Status::Interrupted {
            pt.plan = Plan::Budget;
            pt.note = format!(
                "budget: stopped at t = {} of {} after {:.1} s",
                num(t.t_reached),
                num(t_eval),
                t.summary.wall_seconds
            );
        }
        pt
    };
    let mut rows = vec![row("reference-dopri5", "rtol", REF_RTOL, &r)];
    if !r.status.is_ok() {
        return Ok((None, rows));
    }
    // A check the budget left no time for: a row not run.
    let not_run = |name: &str, param_name: &'static str, param: f64| Point {
        method: name.into(),
        param_name,
        note: "budget: not run: the budget ended before this check".into(),
        ..Point::not_run(Method::Rk4, param, Plan::Budget, String::new())
    };
    let h2 = checks.check_dt / 2.0;
    // RK4 with a small step, and (where that alone is not close enough)
    // Richardson's extrapolation from it and its half: (16 y(h/2) - y(h)) / 15.
    phase("check-rk4", checks.check_dt);
    let coarse = run(
        Method::Rk4,
        &SolveOptions {
            dt: checks.check_dt,
            ..ref_opts.clone()
        },
    )?;
    rows.push(row("check-rk4", "dt", checks.check_dt, &coarse));
    if checks.richardson {
        let fine = if cancelled() {
            None
        } else {
            phase("check-rk4", h2);
            Some(run(
                Method::Rk4,
                &SolveOptions {
                    dt: h2,
                    ..ref_opts.clone()
                },
            )?)
        };
        match &fine {
            Some(fine) => rows.push(row("check-rk4", "dt", h2, fine)),
            None => rows.push(not_run("check-rk4", "dt", h2)),
        }
        match fine {
            Some(fine) if fine.status.is_ok() && coarse.status.is_ok() => {
                let x = |f: f64, c: f64| (16.0 * f - c) / 15.0;
                let (sf, sc) = (&fine.summary, &coarse.summary);
                let tip = [
                    x(sf.tip_end[0], sc.tip_end[0]),
                    x(sf.tip_end[1], sc.tip_end[1]),
                ];
                let (err_tip, err_vmax) =
                    reference.errors_of(tip, x(sf.tip_speed_max, sc.tip_speed_max));
                rows.push(Point {
                    method: "check-rk4-richardson".into(),
                    err_tip,
                    err_vmax,
                    note: format!(
                        "(16 y(dt/2) - y(dt)) / 15 from dt {} and {}",
                        exp(checks.check_dt),
                        exp(h2)
                    ),
                    status: "ok".into(),
                    plan: Plan::Run,
                    walls: vec![coarse.summary.wall_seconds + fine.summary.wall_seconds],
                    ..Point::not_run(Method::Rk4, checks.check_dt, Plan::Run, String::new())
                });
            }
            _ if cancelled() => rows.push(not_run("check-rk4-richardson", "dt", checks.check_dt)),
            // A check run that failed: no extrapolation (its error stays NaN).
            _ => rows.push(Point {
                method: "check-rk4-richardson".into(),
                status: "not_run".into(),
                plan: Plan::Run,
                note: "not extrapolated: a check run did not end ok".into(),
                ..Point::not_run(Method::Rk4, checks.check_dt, Plan::Run, String::new())
            }),
        }
    }
    if cancelled() {
        rows.push(not_run("check-bdf", "rtol", CHECK_BDF_RTOL));
    } else {
        phase("check-bdf", CHECK_BDF_RTOL);
        let bdf = run(
            Method::Bdf,
            &SolveOptions {
                rtol: CHECK_BDF_RTOL,
                atol: CHECK_BDF_ATOL,
                ..ref_opts.clone()
            },
        )?;
        rows.push(row("check-bdf", "rtol", CHECK_BDF_RTOL, &bdf));
    }
    Ok((Some(reference), rows))
}

/// The options of every run of the reference and its `checks` up to
/// `t_eval`, as `(name, method, options)`.
pub fn reference_runs(t_eval: f64, checks: Checks) -> Vec<(&'static str, Method, SolveOptions)> {
    let o = reference_options(t_eval);
    let mut runs = vec![
        (
            "the reference (DOPRI5 rtol 1e-13)",
            Method::Dopri5,
            o.clone(),
        ),
        (
            "the reference's RK4 check (--check-dt)",
            Method::Rk4,
            SolveOptions {
                dt: checks.check_dt,
                ..o.clone()
            },
        ),
    ];
    if checks.richardson {
        runs.push((
            "the reference's RK4 check at --check-dt / 2 (--richardson)",
            Method::Rk4,
            SolveOptions {
                dt: checks.check_dt / 2.0,
                ..o.clone()
            },
        ));
    }
    runs.push((
        "the reference's BDF check (rtol 1e-12)",
        Method::Bdf,
        SolveOptions {
            rtol: CHECK_BDF_RTOL,
            atol: CHECK_BDF_ATOL,
            ..o
        },
    ));
    runs
}

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
    for (what, method, o) in reference_runs(t_eval, checks) {
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

/// How far the checks agree with the reference: the larger error of the
/// Richardson check (else the RK4 check) and of the BDF check. These bound
/// the smallest error the table can resolve.
pub fn agreement(rows: &[Point]) -> (f64, f64) {
    let find = |m: &str| {
        rows.iter()
            .find(|r| r.method == m)
            .map_or(f64::NAN, Point::err)
    };
    let rk4 = match rows.iter().find(|r| r.method == "check-rk4-richardson") {
        Some(r) => r.err(),
        None => find("check-rk4"),
    };
    (rk4, find("check-bdf"))
}

/// One point, run once.
pub fn run_point<S: Subject>(
    p: &S,
    method: Method,
    param: f64,
    reference: &Reference,
) -> Result<Point, Error> {
    let t = p.solve(method, &options_for(p, method, param))?;
    Ok(Point::from_run(
        method.as_str().into(),
        method.accuracy_name(),
        param,
        &t,
        p,
        reference,
    ))
}

/// Every point of `jobs` as its plan says, each run once, untimed, in
/// parallel on the current rayon pool (the order of `jobs` kept).
pub fn run_planned<S: Subject>(
    p: &S,
    jobs: &[(Method, f64, Plan)],
    reference: &Reference,
) -> Result<Vec<Point>, Error> {
    jobs.par_iter()
        .map(|&(m, x, plan)| {
            if plan != Plan::Run {
                return Ok(Point::not_run(m, x, plan, String::new()));
            }
            run_point(p, m, x, reference)
        })
        .collect()
}

/// Repeats of a point whose first run took `wall` seconds.
pub fn repeats_for(wall: f64) -> usize {
    if wall < 0.2 {
        REPEATS_CHEAP
    } else {
        REPEATS
    }
}

/// Runs every timed point again until it has its repeats, a round over all
/// points at a time (so that a burst of load elsewhere on the machine falls
/// on many points once rather than on one point every time).
pub fn repeat_interleaved<S: Subject>(p: &S, rows: &mut [Point]) -> Result<(), Error> {
    for _ in 1..REPEATS_CHEAP.max(REPEATS) {
        for pt in rows.iter_mut() {
            let Some((method, o)) = &pt.rerun else {
                continue;
            };
            if pt.walls.len() >= repeats_for(pt.walls.first().copied().unwrap_or(0.0)) {
                continue;
            }
            let t = p.solve(*method, o)?;
            pt.walls.push(t.summary.wall_seconds);
        }
    }
    Ok(())
}

/// The wall time a line's next point is predicted to take, from its
/// completed points `(param, wall)`: RK4's scales with the number of steps,
/// an adaptive line's grows as its last two did (by 1.6 after one point).
fn predict(rk4: bool, x: f64, done: &[(f64, f64)]) -> f64 {
    match done {
        [] => 0.0,
        [.., (px, pw)] if rk4 => pw * px / x,
        [(_, w0)] => w0 * 1.6,
        [.., (_, w1), (_, w2)] => w2 * (w2 / w1).clamp(1.0, 4.0),
    }
}

/// One method's line, timed (`cargo xtask figures --timings`): RK4 over
/// [`RK4_DTS`], the others over [`RTOLS`].
///
/// Points are run once each, from cheap to costly (their repeats come
/// later, see [`repeat_interleaved`]). A point whose single run is
/// predicted (from the last completed point) to exceed [`MAX_RUN`] s, or to
/// overrun the line's [`LINE_BUDGET`], is not run, nor is any point after
/// it; RK4 stops once its errors reach [`ERR_FLOOR`]; an adaptive line whose
/// first run exceeds [`THIN_ABOVE`] s runs every third tolerance only.
pub fn timed_line<S: Subject>(
    p: &S,
    method: Method,
    reference: &Reference,
) -> Result<Vec<Point>, Error> {
    let rk4 = method.accuracy_name() == "dt";
    let mut out = vec![];
    let mut spent = 0.0;
    let mut done: Vec<(f64, f64)> = vec![];
    let mut stop: Option<(Plan, String)> = None;
    let mut thin = false;
    for (k, &x) in params(method).iter().enumerate() {
        if let Some((plan, why)) = &stop {
            out.push(Point::not_run(method, x, *plan, why.clone()));
            continue;
        }
        if thin && k % 3 != 0 {
            out.push(Point::not_run(method, x, Plan::Thinned, String::new()));
            continue;
        }
        let predicted = predict(rk4, x, &done);
        let reps = repeats_for(predicted) as f64;
        if predicted > MAX_RUN || spent + reps * predicted > LINE_BUDGET {
            let why = format!(
                "cost: predicted {predicted:.1} s per run (limit {MAX_RUN} s per run; \
                 {LINE_BUDGET} s per line)"
            );
            out.push(Point::not_run(method, x, Plan::Cost, why.clone()));
            stop = Some((Plan::Cost, why));
            continue;
        }
        let o = options_for(p, method, x);
        let t = p.solve(method, &o)?;
        let wall = t.summary.wall_seconds;
        let mut pt = Point::from_run(
            method.as_str().into(),
            method.accuracy_name(),
            x,
            &t,
            p,
            reference,
        );
        if t.status.is_ok() {
            // The repeats come later (see `repeat_interleaved`); count them now.
            spent += wall * repeats_for(wall) as f64;
            pt.rerun = Some((method, o));
            if done.is_empty() && !rk4 && wall > THIN_ABOVE {
                thin = true;
            }
            done.push((x, wall));
            if rk4 && pt.err() < ERR_FLOOR {
                stop = Some((Plan::Floor, String::new()));
            }
        }
        out.push(pt);
    }
    Ok(out)
}

/// The lines of the CLI's `precision`: the points of [`ladder`]`(methods)`
/// whose run number `take` accepts (a shard), each method's line from loose
/// to tight on one thread, the lines in parallel on the current rayon pool.
/// A line stops once a completed point passes `stop` (the later points are
/// `floor`; the CLI's [`rk4_floor`]); a point that the budget cannot fit (predicted from the line's
/// last point as [`timed_line`] does, or not started before the deadline)
/// is `budget`, and so is a run the deadline stops. `progress` is called
/// after each point. On RK4's line a shard runs the coarser points it does
/// not own, unrecorded, while they can still fire `stop`, so that its rows
/// are the whole run's rows of its run numbers (`merge` gives the
/// unsharded table).
pub fn run_lines<S: Subject>(
    p: &S,
    methods: &[Method],
    reference: &Reference,
    take: &(dyn Fn(usize) -> bool + Sync),
    budget: &Budget,
    stop: &(dyn Fn(&Point) -> bool + Sync),
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Point>, Error> {
    let mut first = 0;
    let lines: Vec<(Method, usize)> = methods
        .iter()
        .map(|&m| {
            let start = first;
            first += params(m).len();
            (m, start)
        })
        .collect();
    let per_line: Vec<Vec<Point>> = lines
        .par_iter()
        .map(|&(method, start)| {
            let rk4 = method.accuracy_name() == "dt";
            let mut out = vec![];
            let mut done: Vec<(f64, f64)> = vec![];
            let mut floor = false;
            let xs = params(method);
            // One run of the line at `x` within the budget: its point, or
            // `Err(t_reached)` if the deadline stopped it. A completed
            // point joins `done` and tells whether `stop` fired.
            let run_at = |x: f64,
                          done: &mut Vec<(f64, f64)>,
                          floor: &mut bool|
             -> Result<Result<Point, f64>, Error> {
                let mut o = options_for(p, method, x);
                o.cancel = Some(budget.cancel().clone());
                let t = p.solve(method, &o)?;
                if t.status == chain_ode::Status::Interrupted {
                    return Ok(Err(t.t_reached));
                }
                let pt = Point::from_run(
                    method.as_str().into(),
                    method.accuracy_name(),
                    x,
                    &t,
                    p,
                    reference,
                );
                if pt.ok() {
                    done.push((x, t.summary.wall_seconds));
                    *floor = stop(&pt);
                }
                Ok(Ok(pt))
            };
            for (k, &x) in xs.iter().enumerate() {
                let run = start + k;
                if !take(run) {
                    // A shard decides RK4's stop rule as the whole run does:
                    // while the rule has not fired and a finer point of the
                    // line is its own, it runs the coarser point it does not
                    // own (cheaper than its own, RK4's cost being 1/dt) and
                    // records nothing of it but the rule's answer.
                    let finer_own = (k + 1..xs.len()).any(|j| take(start + j));
                    if rk4
                        && !floor
                        && finer_own
                        && bound_of(p, method, x).is_none()
                        && budget.fits(predict(rk4, x, &done))
                    {
                        run_at(x, &mut done, &mut floor)?.ok();
                    }
                    continue;
                }
                let bound = bound_of(p, method, x);
                let plan = if floor {
                    Plan::Floor
                } else if bound.is_some() {
                    Plan::Bound
                } else if !budget.fits(predict(rk4, x, &done)) {
                    Plan::Budget
                } else {
                    Plan::Run
                };
                let mut pt = if plan == Plan::Run {
                    let started = Instant::now();
                    match run_at(x, &mut done, &mut floor)? {
                        Ok(pt) => pt,
                        Err(t_reached) => {
                            let mut pt = Point::not_run(method, x, Plan::Budget, String::new());
                            pt.note = format!(
                                "budget: stopped at t = {} after {:.1} s",
                                num(t_reached),
                                started.elapsed().as_secs_f64()
                            );
                            pt
                        }
                    }
                } else {
                    let mut pt = Point::not_run(method, x, plan, String::new());
                    if let Some(why) = &bound {
                        pt.note = format!("not run: {why}");
                    }
                    pt
                };
                pt.run = Some(run);
                out.push(pt);
                progress();
            }
            Ok(out)
        })
        .collect::<Result<_, Error>>()?;
    Ok(per_line.into_iter().flatten().collect())
}

/// The stop rule of the CLI's lines: RK4's line stops once both errors are
/// below [`ERR_FLOOR`], as in the study's figures.
pub fn rk4_floor(p: &Point) -> bool {
    p.param_name == "dt" && p.err() < ERR_FLOOR
}

/// The table: a header line ([`COLUMNS`]) and a row per point, every
/// number in the formats of [`fc_csv::format`]. With `provenance` (the
/// CLI's), each row also has its median wall time, its run number and the
/// provenance columns: `wall_seconds,run,runs,scene_hash`.
pub fn csv_text(
    scene: &str,
    t_eval: f64,
    reference: &Reference,
    rows: &[Point],
    provenance: Option<&Provenance>,
) -> String {
    let mut csv = fc_csv::header(&COLUMNS);
    if provenance.is_some() {
        csv.push(',');
        csv.push_str(&fc_csv::header(&CLI_COLUMNS));
        csv.push_str(&Provenance::header_suffix());
    }
    csv.push('\n');
    for pt in rows {
        let s = &pt.stats;
        let cells = [
            fc_csv::field(scene).into_owned(),
            num(t_eval),
            pt.method.clone(),
            pt.param_name.to_string(),
            exp(pt.param),
            pt.status.clone(),
            num(pt.t_reached),
            s.steps.to_string(),
            s.rejected_steps.to_string(),
            s.rhs_evals.to_string(),
            s.jacobian_evals.to_string(),
            s.lu_factorizations.to_string(),
            pt.rhs_equiv().to_string(),
            u8::from(pt.switched).to_string(),
            exp(pt.err_tip),
            exp(pt.err_vmax),
            num(reference.tip[0]),
            num(reference.tip[1]),
            num(reference.vmax),
            text(&pt.note),
        ];
        csv.push_str(&cells.join(","));
        if let Some(prov) = provenance {
            let wall = if pt.walls.is_empty() {
                String::new()
            } else {
                exp(super::median(&pt.walls))
            };
            let run = pt.run.map_or_else(String::new, |r| r.to_string());
            csv.push_str(&format!(",{wall},{run}{}", prov.cells()));
        }
        csv.push('\n');
    }
    csv
}

/// The fastest method at each error level: for each level `1e-k`, the
/// completed point of a method (not the reference or its checks) whose
/// error is at most it at the least cost (`cost` of the point: wall time
/// or work), as `(level, point)`.
pub fn fastest<'a>(
    rows: &'a [Point],
    levels: &[f64],
    cost: impl Fn(&Point) -> f64,
) -> Vec<(f64, Option<&'a Point>)> {
    levels
        .iter()
        .map(|&level| {
            let best = rows
                .iter()
                .filter(|pt| {
                    pt.run.is_some() || Method::ALL.iter().any(|m| m.as_str() == pt.method)
                })
                .filter(|pt| pt.ok() && pt.err() <= level && cost(pt).is_finite())
                .min_by(|a, b| cost(a).total_cmp(&cost(b)));
            (level, best)
        })
        .collect()
}

/// A reference is confirmed when one check agrees with it to this.
pub const CONFIRMED: f64 = 1e-6;

/// The most RK4 steps the reference's checks may take in all: `t_end /
/// check_dt`, and with Richardson `2 t_end / check_dt` more (10^7 steps are
/// seconds to a minute at 50 rods, the cost of the whole study).
pub const MAX_CHECK_STEPS: f64 = 1e7;

/// The smallest `--check-dt` for `t_end`: the checks' RK4 steps within
/// [`MAX_CHECK_STEPS`].
pub fn min_check_dt(t_end: f64, richardson: bool) -> f64 {
    let runs = if richardson { 3.0 } else { 1.0 };
    runs * t_end / MAX_CHECK_STEPS
}

/// Checks the RK4 step of the reference's check before any run: in
/// `[min_check_dt, t_end]` (its cost is known in advance: `t_end / dt`
/// steps, three times that with `richardson`, at most
/// [`MAX_CHECK_STEPS`]); `what` names it (`--check-dt`, Python's
/// `check_dt`).
pub fn check_check_dt(what: &str, dt: f64, t_end: f64, richardson: bool) -> Result<f64, Error> {
    let lo = min_check_dt(t_end, richardson);
    if dt.is_finite() && dt >= lo && dt <= t_end {
        Ok(dt)
    } else {
        Err(Error::field(
            what,
            format!(
                "must be a step in [{lo:e}, run.t_end = {}]: the reference's checks take \
                 t_end / dt RK4 steps (3 t_end / dt with Richardson), at most \
                 {MAX_CHECK_STEPS:e} (got {})",
                fc_scene::error::number(t_end),
                fc_scene::error::number(dt)
            ),
        ))
    }
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
    let provenance = Provenance::new(
        scene,
        "precision",
        &[
            methods
                .iter()
                .map(|m| m.as_str())
                .collect::<Vec<_>>()
                .join(","),
            exp(options.checks.check_dt),
            options.checks.richardson.to_string(),
        ],
        ladder(methods).len(),
    );
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
    // The floor rule needs the coarser points of RK4's line: a
    // shard runs those it does not own to decide it (`run_lines`).
    let stop = |pt: &Point| rk4_floor(pt);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.jobs.max(1))
        .build()
        .map_err(|e| Error::field("--jobs", e))?;
    // Every phase, the reference and its checks included, runs under the
    // budget and the caller's cancel.
    let (reference, mut rows) = Budget::run(options.budget, outer, |b| {
        let mut p = p.clone();
        p.options_mut().cancel = Some(b.cancel().clone());
        let (reference, mut rows) = reference(&p, t_eval, options.checks)?;
        if b.interrupted() {
            return Err(Error::Interrupted);
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
                    "--budget stopped the reference run (DOPRI5 rtol {}) at t = {} of {}: \
                     no point ran, no error can be measured",
                    exp(REF_RTOL),
                    num(rows[0].t_reached),
                    num(t_eval)
                )
            } else {
                format!(
                    "the reference run (DOPRI5 rtol {}) ended {}: no errors can be measured",
                    exp(REF_RTOL),
                    rows[0].status
                )
            });
            Reference {
                tip: [f64::NAN; 2],
                vmax: f64::NAN,
                length: p.length(),
            }
        }
    };
    let (a_rk4, a_bdf) = agreement(&rows);
    if failures.is_empty() && ![a_rk4, a_bdf].iter().any(|&a| a <= CONFIRMED) {
        let checks = || {
            rows.iter()
                .filter(|r| r.run.is_none() && r.method != "reference-dopri5")
        };
        let budget: Vec<&str> = checks()
            .filter(|r| r.plan == Plan::Budget)
            .map(|r| r.method.as_str())
            .collect();
        failures.push(if budget.is_empty() {
            format!(
                "the reference is not confirmed: neither check agrees with it to {}",
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
    })
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
    use fc_scene::scene::Prepared;
    use std::sync::Mutex;
    use std::time::Duration;

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
