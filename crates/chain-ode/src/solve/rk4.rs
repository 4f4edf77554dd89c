//! Classical fixed-step RK4 on the whole state (angles and rates together),
//! with the cubic Hermite interpolant as its continuous extension.

use super::integrator::Integrator;
use crate::ode::{
    all_finite, Counted, Hermite, Observer, OdeSystem, Outcome, Stats, Status, StepView,
};

/// Integrates from `t0` to `t_end` with steps of `dt` (the last one shortened).
pub(crate) fn integrate<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    dt: f64,
    max_steps: u64,
    obs: &mut dyn Observer,
) -> Outcome {
    Counted::run(sys, |sys| steps(sys, t0, y0, t_end, dt, max_steps, obs))
}

fn steps<S: OdeSystem>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    dt: f64,
    max_steps: u64,
    obs: &mut dyn Observer,
) -> Outcome {
    let d = sys.dim();
    let mut y = y0.to_vec();
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
        // Step times from the step count, not by accumulation; the last step
        // lands on t_end exactly (absorbing a sliver below 1e-9 dt).
        let mut t1 = t0 + (k + 1) as f64 * dt;
        if t1 > t_end - 1e-9 * dt {
            t1 = t_end;
        }
        let h = t1 - t;
        let axpy = |out: &mut [f64], y: &[f64], a: f64, x: &[f64]| {
            for i in 0..out.len() {
                out[i] = y[i] + a * x[i];
            }
        };
        axpy(&mut tmp, &y, 0.5 * h, &f);
        sys.rhs(t + 0.5 * h, &tmp, &mut k2);
        axpy(&mut tmp, &y, 0.5 * h, &k2);
        sys.rhs(t + 0.5 * h, &tmp, &mut k3);
        axpy(&mut tmp, &y, h, &k3);
        sys.rhs(t1, &tmp, &mut k4);
        for i in 0..d {
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

/// `rk4`: classical fixed-step RK4; `dt` sets its accuracy.
pub(crate) const RK4: Integrator = Integrator {
    name: "rk4",
    adaptive: false,
    run: |p, s, obs| {
        integrate(
            p,
            s.t0,
            s.y0,
            s.t_end,
            s.settings.dt,
            s.settings.max_steps,
            obs,
        )
        .into()
    },
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::all_finite;
    use crate::solve::test_problems::{Quiet, OSCILLATOR};

    #[test]
    fn a_step_budget_ends_with_max_steps_where_it_ran_out() {
        let mut sys = (OSCILLATOR.system)();
        let out = integrate(&mut sys, 0.0, &[1.0, 0.0], 1.0, 0.01, 10, &mut Quiet);
        assert_eq!(out.status, Status::MaxSteps);
        assert!((out.t_reached - 0.1).abs() < 1e-12);
        assert_eq!(out.stats.steps, 10);
        assert_eq!(out.t_failed, Some(out.t_reached));
        // The state at t = 0.1 of y'' = -y from (1, 0).
        assert!((out.y_end[0] - 0.1f64.cos()).abs() < 1e-9 && all_finite(&out.y_end));
    }
}
