//! The reference the errors are measured against (DOPRI5 at [`REF_RTOL`])
//! and its checks (RK4 at a step, optionally extrapolated; BDF at
//! [`CHECK_BDF_RTOL`]), their runs under the scene's cancel, how far they
//! agree, and the check's step bound.

use super::*;
use chain_ode::{Cancel, Method, Model, SolveOptions, Status, Trajectory};

use crate::subject::Subject;
use fc_csv::format::{exp, num};
use fc_scene::error::Error;

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
