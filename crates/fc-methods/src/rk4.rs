//! Classical fixed-step RK4 on the whole state (angles and rates together),
//! with the cubic Hermite interpolant as its continuous extension, and the
//! one fixed-step loop ([`integrate`] over a [`FixedStep`]), which the
//! report's stepper (`report_stepper.rs`) shares.

use super::integrator::{Integrator, Span};
use crate::ode::{
    all_finite, Counted, Hermite, Observer, OdeSystem, Outcome, Stats, Status, StepView,
};

/// A fixed-step method's step, as the one fixed-step loop ([`integrate`])
/// sees it: the stages that take `(t, y)`, with `f = f(t, y)`, by `h` to
/// `t1 = t + h` (the solution in `y1`). The loop owns the rest: the step
/// times, the budget, the cancel check, the finiteness checks, `f(t1, y1)`,
/// the observer with the cubic Hermite interpolant.
pub trait FixedStep {
    /// One step's stages, into `y1`, with `w`'s vectors as scratch.
    fn step<S: OdeSystem>(
        sys: &mut S,
        t: f64,
        t1: f64,
        y: &[f64],
        f: &[f64],
        y1: &mut [f64],
        w: &mut Work,
    );
}

/// A fixed step's scratch: three stage slopes and one stage state, each of
/// the state's size, allocated once per run.
pub struct Work {
    pub k2: Vec<f64>,
    pub k3: Vec<f64>,
    pub k4: Vec<f64>,
    pub tmp: Vec<f64>,
}

/// Classical RK4 on the whole state.
pub(crate) struct Classic;

impl FixedStep for Classic {
    fn step<S: OdeSystem>(
        sys: &mut S,
        t: f64,
        t1: f64,
        y: &[f64],
        f: &[f64],
        y1: &mut [f64],
        w: &mut Work,
    ) {
        let h = t1 - t;
        let axpy = |out: &mut [f64], y: &[f64], a: f64, x: &[f64]| {
            for i in 0..out.len() {
                out[i] = y[i] + a * x[i];
            }
        };
        axpy(&mut w.tmp, y, 0.5 * h, f);
        sys.rhs(t + 0.5 * h, &w.tmp, &mut w.k2);
        axpy(&mut w.tmp, y, 0.5 * h, &w.k2);
        sys.rhs(t + 0.5 * h, &w.tmp, &mut w.k3);
        axpy(&mut w.tmp, y, h, &w.k3);
        sys.rhs(t1, &w.tmp, &mut w.k4);
        for i in 0..y.len() {
            y1[i] = y[i] + h / 6.0 * (f[i] + 2.0 * (w.k2[i] + w.k3[i]) + w.k4[i]);
        }
    }
}

/// Integrates `sys` over `span` with the fixed-step method `M` at steps of
/// `span.settings.dt` (the last one shortened), under the step budget
/// `span.settings.max_steps`. Every right-hand side is counted.
pub fn integrate<M: FixedStep, S: OdeSystem + ?Sized>(
    sys: &mut S,
    span: &Span<'_>,
    obs: &mut dyn Observer,
) -> Outcome {
    Counted::run(sys, |sys| steps::<M, _>(sys, span, obs))
}

fn steps<M: FixedStep, S: OdeSystem>(
    sys: &mut S,
    span: &Span<'_>,
    obs: &mut dyn Observer,
) -> Outcome {
    let (t0, t_end, dt) = (span.t0, span.t_end, span.settings.dt);
    let max_steps = span.settings.max_steps;
    let d = sys.dim();
    let mut y = span.y0.to_vec();
    let mut f = vec![0.0; d];
    let mut w = Work {
        k2: vec![0.0; d],
        k3: vec![0.0; d],
        k4: vec![0.0; d],
        tmp: vec![0.0; d],
    };
    let (mut y1, mut f1) = (vec![0.0; d], vec![0.0; d]);
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
        // Step times from the step count, not by accumulation; the last step
        // lands on t_end exactly (absorbing a sliver below 1e-9 dt).
        let mut t1 = t0 + (k + 1) as f64 * dt;
        if t1 > t_end - 1e-9 * dt {
            t1 = t_end;
        }
        let h = t1 - t;
        M::step(sys, t, t1, &y, &f, &mut y1, &mut w);
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

/// `rk4`: classical fixed-step RK4; `dt` sets its accuracy.
pub(crate) const RK4: Integrator = Integrator {
    name: "rk4",
    adaptive: false,
    nonsmooth: false,
    run: |p, s, obs| integrate::<Classic, _>(p, s, obs).into(),
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::all_finite;
    use crate::test_problems::{Quiet, OSCILLATOR};

    #[test]
    fn a_step_budget_ends_with_max_steps_where_it_ran_out() {
        let mut sys = (OSCILLATOR.system)();
        let settings = crate::integrator::Settings {
            dt: 0.01,
            rtol: 1e-6,
            atol: 1e-8,
            h_min: 0.0,
            max_steps: 10,
            h0: None,
            scales: crate::TimeScales::NONE,
            rho_inf: crate::DEFAULT_RHO_INF,
        };
        let span = Span {
            t0: 0.0,
            y0: &[1.0, 0.0],
            t_end: 1.0,
            settings: &settings,
        };
        let out = integrate::<Classic, _>(&mut sys, &span, &mut Quiet);
        assert_eq!(out.status, Status::MaxSteps);
        assert!((out.t_reached - 0.1).abs() < 1e-12);
        assert_eq!(out.stats.steps, 10);
        assert_eq!(out.t_failed, Some(out.t_reached));
        // The state at t = 0.1 of y'' = -y from (1, 0).
        assert!((out.y_end[0] - 0.1f64.cos()).abs() < 1e-9 && all_finite(&out.y_end));
    }
}
