//! The reference the errors are measured against and its checks, chosen
//! from the subject's stiffness ([`ReferencePlan`]): on a scene without
//! stiff axial modes DOPRI5 at [`REF_RTOL`], checked by RK4 at a step
//! (optionally extrapolated) and BDF at [`CHECK_BDF_RTOL`]; on elastic links
//! whose axial modes an explicit method can still follow, DOPRI5 at
//! [`STIFF_REF_RTOL`] checked by DOP853 at the same tolerance (an
//! independent method); beyond that, BDF at [`IMPLICIT_REF_RTOL`] checked by
//! BDF ten times tighter. Their runs go under the scene's cancel; how far
//! they agree; the check's step bound.

use super::*;
use chain_ode::{Cancel, Method, Model, SolveOptions, Status, Trajectory};

use crate::measure::Values;
use crate::subject::Subject;
use fc_csv::format::{exp, num};
use fc_scene::error::Error;

/// The reference values the errors are measured against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reference {
    pub tip: [f64; 2],
    pub vmax: f64,
    pub length: f64,
    /// The values of the study's measures (`--measure`; NaN where not
    /// measured).
    pub values: Values,
}

/// `omega_max t_end` above which the reference is no longer DOPRI5 at
/// [`REF_RTOL`]: its axial modes hold an explicit method at its stability
/// limit (about `omega_max t_end / 3` steps at any tolerance), and DOPRI5 at
/// 1e-13 takes ten times that (the steel rope of issue 49, `omega_max
/// t_end = 2.9e6`: DOPRI5 at 1e-13 reached t = 0.065 of 3.2 in 500 s).
pub const STIFF_ABOVE: f64 = 1e4;
/// `omega_max t_end` above which no explicit reference is tried: about
/// 10^7 steps, minutes at 50 rods.
pub const EXPLICIT_UP_TO: f64 = 3e7;
/// The stiff explicit reference: DOPRI5 at this tolerance, checked by
/// DOP853 at it. Measured on issue 49's steel rope (`omega_max t_end =
/// 2.9e6`): at 1e-8 they agree to 2e-8 on the peak pivot force (280,351 and
/// 399,589 steps); DOP853 at 1e-9 takes 3.6 million steps (400 s), DOPRI5
/// 488,157 (15 s).
pub const STIFF_REF_RTOL: f64 = 1e-8;
/// The implicit reference: BDF at this tolerance, checked by BDF at a
/// tenth of it.
pub const IMPLICIT_REF_RTOL: f64 = 1e-10;

/// How a subject's reference is run, chosen from its stiffness
/// ([`Subject::axial_radians`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ReferencePlan {
    /// DOPRI5 at [`REF_RTOL`], checked by RK4 and BDF: no stiff axial
    /// modes (every rigid chain; today's reference, byte for byte).
    Explicit,
    /// DOPRI5 at `rtol`, checked by DOP853 at `rtol`.
    StiffExplicit { rtol: f64 },
    /// BDF at `rtol`, checked by BDF at `rtol / 10`.
    Implicit { rtol: f64 },
}

impl ReferencePlan {
    /// The plan for `p` up to its end time, at `rtol` where it is stiff
    /// (precision: [`STIFF_REF_RTOL`]; `needs`: from its `--tol`).
    pub fn for_subject<S: Subject>(p: &S, rtol: f64) -> Self {
        let radians = p.axial_radians();
        if radians <= STIFF_ABOVE {
            Self::Explicit
        } else if radians <= EXPLICIT_UP_TO {
            Self::StiffExplicit { rtol }
        } else {
            Self::Implicit {
                rtol: rtol.min(IMPLICIT_REF_RTOL),
            }
        }
    }

    /// The reference's run: its row's name, method and tolerances.
    pub fn reference(self) -> (&'static str, Method, f64, f64) {
        match self {
            Self::Explicit => ("reference-dopri5", Method::Dopri5, REF_RTOL, REF_ATOL),
            Self::StiffExplicit { rtol } => {
                ("reference-dopri5", Method::Dopri5, rtol, rtol / 100.0)
            }
            Self::Implicit { rtol } => ("reference-bdf", Method::Bdf, rtol, rtol / 100.0),
        }
    }

    /// The independent check of a stiff reference (none for
    /// [`ReferencePlan::Explicit`], whose checks are RK4's and BDF's).
    pub fn check(self) -> Option<(&'static str, Method, f64, f64)> {
        match self {
            Self::Explicit => None,
            Self::StiffExplicit { rtol } => {
                Some(("check-dop853", Method::Dop853, rtol, rtol / 100.0))
            }
            Self::Implicit { rtol } => {
                Some(("check-bdf-tighter", Method::Bdf, rtol / 10.0, rtol / 1000.0))
            }
        }
    }

    /// One line saying which reference and why.
    pub fn describe(self) -> String {
        let (_, m, rtol, _) = self.reference();
        match self {
            Self::Explicit => format!("{} rtol {}", m.as_str().to_uppercase(), exp(rtol)),
            Self::StiffExplicit { .. } | Self::Implicit { .. } => {
                let (_, c, crtol, _) = self.check().unwrap_or(("", m, rtol, 0.0));
                format!(
                    "{} rtol {} checked by {} rtol {} (stiff axial modes: omega_max t_end above {})",
                    m.as_str().to_uppercase(),
                    exp(rtol),
                    c.as_str().to_uppercase(),
                    exp(crtol),
                    exp(STIFF_ABOVE)
                )
            }
        }
    }
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

    /// No reference: every value NaN.
    pub fn none(length: f64) -> Self {
        Self {
            tip: [f64::NAN; 2],
            vmax: f64::NAN,
            length,
            values: Values::NONE,
        }
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
    reference_planned(
        p,
        t_eval,
        checks,
        ReferencePlan::for_subject(p, STIFF_REF_RTOL),
        phase,
    )
}

/// [`reference_phases`] with the reference's `plan` given.
pub fn reference_planned<S: Subject>(
    p: &S,
    t_eval: f64,
    checks: Checks,
    plan: ReferencePlan,
    phase: &dyn Fn(&str, f64),
) -> Result<(Option<Reference>, Vec<Point>), Error> {
    let (ref_name, ref_method, ref_rtol, ref_atol) = plan.reference();
    let ref_opts = SolveOptions {
        cancel: p.options().cancel.clone(),
        rtol: ref_rtol,
        atol: ref_atol,
        output_dt: p.measures().output_dt(t_eval),
        ..reference_options(t_eval)
    };
    let cancelled = || ref_opts.cancel.as_ref().is_some_and(Cancel::is_cancelled);
    let run = |method: Method, o: &SolveOptions| -> Result<Trajectory<S::Model>, Error> {
        Ok(p.solve(method, o)?)
    };
    phase(ref_name, ref_rtol);
    let r = run(ref_method, &ref_opts)?;
    let reference = Reference {
        tip: r.summary.tip_end,
        vmax: r.summary.tip_speed_max,
        length: p.length(),
        values: Values::of(&r, p.measures()),
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
    let mut rows = vec![row(ref_name, "rtol", ref_rtol, &r)];
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
    if let Some((name, method, rtol, atol)) = plan.check() {
        if cancelled() {
            rows.push(not_run(name, "rtol", rtol));
        } else {
            phase(name, rtol);
            let c = run(
                method,
                &SolveOptions {
                    rtol,
                    atol,
                    ..ref_opts.clone()
                },
            )?;
            rows.push(row(name, "rtol", rtol, &c));
        }
        return Ok((Some(reference), rows));
    }
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
    reference_runs_planned(t_eval, checks, ReferencePlan::Explicit)
}

/// [`reference_runs`] of `plan`.
pub fn reference_runs_planned(
    t_eval: f64,
    checks: Checks,
    plan: ReferencePlan,
) -> Vec<(&'static str, Method, SolveOptions)> {
    let o = reference_options(t_eval);
    if plan != ReferencePlan::Explicit {
        let (_, m, rtol, atol) = plan.reference();
        let mut runs = vec![(
            "the stiff scene's reference",
            m,
            SolveOptions {
                rtol,
                atol,
                ..o.clone()
            },
        )];
        if let Some((_, c, rtol, atol)) = plan.check() {
            runs.push((
                "the stiff reference's check",
                c,
                SolveOptions { rtol, atol, ..o },
            ));
        }
        return runs;
    }
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
/// Richardson check (else the RK4 check) and of the BDF check; for a stiff
/// reference ([`ReferencePlan`]), its one check's and NaN. These bound
/// the smallest error the table can resolve.
pub fn agreement(rows: &[Point]) -> (f64, f64) {
    let find = |m: &str| {
        rows.iter()
            .find(|r| r.method == m)
            .map_or(f64::NAN, Point::err)
    };
    if let Some(r) = rows
        .iter()
        .find(|r| r.method == "check-dop853" || r.method == "check-bdf-tighter")
    {
        return (r.err(), f64::NAN);
    }
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
