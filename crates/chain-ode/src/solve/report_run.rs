//! Runs of the report's model ([`crate::report`]): [`solve_report`], and
//! the report's own stepper (erratum 4), which its code calls RK4.
//!
//! The stepper advances `y = [phi, w, W]` by `h` as the report's code does
//! (its notebook's step loop):
//!
//! ```text
//! phi1 = phi + h w                               (explicit Euler)
//! k1 = a(phi, w)           k2 = a(phi, w + h/2 k1)
//! k3 = a(phi1, w + h/2 k2) k4 = a(phi1, w + h k3)
//! w1 = w + h/6 (k1 + 2 k2 + 2 k3 + k4)
//! ```
//!
//! RK4's weights on the rates, with the angles frozen at `phi` for the
//! first two stages and at the Euler update `phi1` for the last two (`W`
//! takes the same stages as `w`): a first-order method, measured so by a
//! test.

use std::time::Instant;

use super::integrator::{Run, Settings, Span};
use super::observer::ChainObserver;
use super::{registry, state_tip, state_tip_velocity, Method, SolveOptions, Summary, Trajectory};
use crate::chain::{check, Chain, InvalidParameter};
use crate::ode::{
    all_finite, Counted, Hermite, Observer, OdeSystem, Outcome, Stats, Status, StepView,
};
use crate::report::{ReportModel, ReportSystem};
use crate::state::State;
use crate::system::ChainSystem;

/// The methods the report's model runs: `rk4` (the report's stepper when
/// [`ReportModel::stepper`] is set, else RK4), `dopri5` and `dop853`.
/// `bdf` and `bdf-dense` need forms it does not state, and `auto` is a
/// policy over them.
pub const REPORT_METHODS: [Method; 3] = [Method::Rk4, Method::Dopri5, Method::Dop853];

/// Runs the report's `model` of `chain` from `start` with `method` over
/// `[0, options.t_end]`, in the model's own time unit (with the clock
/// erratum, `sqrt(l/g)` of ours: [`ReportModel::time_unit`]). As
/// [`super::solve`] otherwise: the same checks first, the same statuses,
/// the summary's energies are the model's own ([`ReportModel::energy`]) and
/// its tip speeds the exact ones in its time unit (the report's finite
/// differences: [`crate::report::finite_difference_tip_speeds`]).
/// `Trajectory::energy` of a sample is the corrected chain's.
pub fn solve_report(
    chain: &Chain,
    start: &State,
    model: ReportModel,
    method: Method,
    options: &SolveOptions,
) -> Result<Trajectory, InvalidParameter> {
    check(
        REPORT_METHODS.contains(&method),
        "run.method",
        "one of rk4, dopri5, dop853 with model.report = true",
        method,
    )?;
    model.validate(chain)?;
    options.validate_for(chain, method)?;
    let n = chain.links();
    check(
        start.angles.len() == n && start.rates.len() == n,
        "start",
        "a state with chain.links angles and rates",
        start.angles.len(),
    )?;
    let y0 = ChainSystem::pack(&start.angles, &start.rates, 0.0);
    let mut obs = ChainObserver::for_report(
        chain,
        model,
        options.t_end,
        options.output_dt,
        options.cancel.clone(),
    );
    let clock = Instant::now();
    let settings = Settings::of(options);
    let span = Span {
        t0: 0.0,
        y0: &y0,
        t_end: options.t_end,
        settings: &settings,
    };
    let mut sys = ReportSystem::new(chain, model);
    let Run { outcome, segments } = if method == Method::Rk4 && model.stepper {
        let outcome = integrate(&mut sys, &span, &mut obs);
        Run {
            outcome,
            segments: vec![super::Segment {
                method,
                t_start: 0.0,
                t_end: options.t_end,
            }],
        }
    } else {
        registry::run(method, &mut sys, &span, &mut obs)
    };
    let wall_seconds = clock.elapsed().as_secs_f64();
    obs.finish(outcome.t_reached, &outcome.y_end);
    let y = &outcome.y_end;
    let summary = Summary {
        energy_start: obs.energy_start,
        energy_end: obs.energy_end,
        dissipated: y[2 * n],
        energy_balance_error: obs.energy_balance_error,
        max_energy_rise: obs.max_energy_rise,
        tip_end: state_tip(chain, start.anchor, y),
        tip_velocity_end: state_tip_velocity(chain, y),
        tip_speed_max: obs.tip_speed_max,
        t_tip_speed_max: obs.t_tip_speed_max,
        // Tracked for elastic links only; the report's chain is rigid.
        pivot_force_max: None,
        wall_seconds,
    };
    let (status, t_failed) = if outcome.status.is_ok() && !summary.all_finite() {
        (
            Status::Diverged,
            Some(obs.t_nonfinite.unwrap_or(outcome.t_reached)),
        )
    } else if outcome.status.is_ok() && summary.energy_balance_error > model.energy_scale(chain) {
        (
            Status::Inaccurate,
            Some(obs.t_inaccurate.unwrap_or(outcome.t_reached)),
        )
    } else {
        (outcome.status, outcome.t_failed)
    };
    let mut segments = segments;
    if let Some(s) = segments.last_mut() {
        s.t_end = outcome.t_reached;
    }
    Ok(Trajectory {
        chain: chain.clone(),
        anchor: start.anchor,
        // The report's pivot never moves (`model.report` refuses `pivot.*`).
        pivot: crate::pivot::PivotPath::new(chain, start.anchor),
        method,
        status,
        t_end: options.t_end,
        t_reached: outcome.t_reached,
        t_failed,
        stats: outcome.stats,
        segments,
        summary,
        times: std::mem::take(&mut obs.times),
        states: std::mem::take(&mut obs.states),
        final_state: outcome.y_end,
    })
}

/// The report's stepper over `span` at steps of `span.settings.dt` (the
/// last one shortened), on a system whose state is `[q (n), v (n), rest]`
/// with `q' = v`; the observer sees each step with the cubic Hermite
/// interpolant.
pub(crate) fn integrate<S: OdeSystem>(
    sys: &mut S,
    span: &Span<'_>,
    obs: &mut dyn Observer,
) -> Outcome {
    Counted::run(sys, |sys| steps(sys, span, obs))
}

fn steps<S: OdeSystem>(sys: &mut S, span: &Span<'_>, obs: &mut dyn Observer) -> Outcome {
    let (t0, t_end, dt) = (span.t0, span.t_end, span.settings.dt);
    let max_steps = span.settings.max_steps;
    let d = sys.dim();
    let n = (d - 1) / 2;
    let mut y = span.y0.to_vec();
    let mut f = vec![0.0; d];
    let (mut k2, mut k3, mut k4) = (vec![0.0; d], vec![0.0; d], vec![0.0; d]);
    let (mut tmp, mut y1, mut f1) = (vec![0.0; d], vec![0.0; d], vec![0.0; d]);
    let mut stats = Stats::default();
    let fail = Outcome::ended;

    sys.rhs(t0, &y, &mut f);
    if !all_finite(&f) {
        return fail(Status::Diverged, t0, Some(t0), stats, y);
    }
    obs.start(t0, &y, &f);
    let mut t = t0;
    let mut k: u64 = 0;
    while t < t_end {
        if stats.steps >= max_steps {
            return fail(Status::MaxSteps, t, Some(t), stats, y);
        }
        if obs.stop() {
            return fail(Status::Interrupted, t, Some(t), stats, y);
        }
        let mut t1 = t0 + (k + 1) as f64 * dt;
        if t1 > t_end - 1e-9 * dt {
            t1 = t_end;
        }
        let h = t1 - t;
        // The angles by explicit Euler first: the last two stages use them.
        for i in 0..n {
            y1[i] = y[i] + h * y[n + i];
        }
        // Stages in the rates (and W) only, at the angles `at`.
        let stage = |out: &mut [f64], at: &[f64], y: &[f64], a: f64, k: &[f64]| {
            out[..n].copy_from_slice(&at[..n]);
            for i in n..d {
                out[i] = y[i] + a * k[i];
            }
        };
        stage(&mut tmp, &y, &y, 0.5 * h, &f);
        sys.rhs(t, &tmp, &mut k2);
        stage(&mut tmp, &y1, &y, 0.5 * h, &k2);
        sys.rhs(t1, &tmp, &mut k3);
        stage(&mut tmp, &y1, &y, h, &k3);
        sys.rhs(t1, &tmp, &mut k4);
        for i in n..d {
            y1[i] = y[i] + h / 6.0 * (f[i] + 2.0 * (k2[i] + k3[i]) + k4[i]);
        }
        if !all_finite(&y1) {
            return fail(Status::Diverged, t, Some(t1), stats, y);
        }
        sys.rhs(t1, &y1, &mut f1);
        if !all_finite(&f1) {
            return fail(Status::Diverged, t, Some(t1), stats, y);
        }
        stats.steps += 1;
        obs.step(&StepView {
            t0: t,
            t1,
            y0: &y,
            y1: &y1,
            f1: &f1,
            interpolant: &Hermite {
                t0: t,
                h,
                y0: &y,
                f0: &f,
                y1: &y1,
                f1: &f1,
            },
        });
        std::mem::swap(&mut y, &mut y1);
        std::mem::swap(&mut f, &mut f1);
        t = t1;
        k += 1;
    }
    Outcome::ended(Status::Ok, t, None, stats, y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::test_problems::Quiet;

    /// `q'' = -q` as `[q, v, W]` with `W' = 0`: the layout the stepper reads.
    struct Spring;

    impl OdeSystem for Spring {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = -y[0];
            dy[2] = 0.0;
        }
        fn jvp(&mut self, _t: f64, _y: &[f64], v: &[f64], jv: &mut [f64]) {
            jv[0] = v[1];
            jv[1] = -v[0];
            jv[2] = 0.0;
        }
    }

    #[test]
    fn one_step_is_the_reports_by_hand() {
        // From (q, v) = (1, 1) by h: q1 = q + h v = 1 + h; the rates' stages
        // are -q, -q, -q1, -q1, so v1 = v - h/6 (q + 2 q + 2 q1 + q1)
        // = 1 - h - h^2/2 (at frozen old angles it would be 1 - h).
        let h = 0.1;
        let settings = Settings {
            dt: h,
            rtol: 1e-6,
            atol: 1e-8,
            h_min: 0.0,
            max_steps: 10,
            h0: None,
        };
        let span = Span {
            t0: 0.0,
            y0: &[1.0, 1.0, 0.0],
            t_end: h,
            settings: &settings,
        };
        let out = integrate(&mut Spring, &span, &mut Quiet);
        assert_eq!(out.status, Status::Ok);
        assert_eq!(out.stats.steps, 1);
        assert!((out.y_end[0] - 1.1).abs() < 1e-15, "{:?}", out.y_end);
        assert!(
            (out.y_end[1] - (1.0 - h - 0.5 * h * h)).abs() < 1e-15,
            "{:?}",
            out.y_end
        );
    }
}
