//! Implicit BDF (variable order 1-5) from diffsol, on the explicit form
//! `y' = f(y)` with the exact Jacobian-vector product of the system.
//!
//! diffsol builds the dense Jacobian column by column from `dim` calls of
//! [`OdeSystem::jvp`] and factorises `I - c J` with faer's LU. It steps with
//! `Bdf::step`; this driver owns everything around a step: the step budget,
//! the step floor, the map from diffsol's errors to a [`Status`], the work
//! counters, and the observer, which sees diffsol's own dense output.
//!
//! Three things about diffsol 0.18 shape the driver:
//! * One `step()` call retries rejected attempts internally. To count every
//!   attempt against `max_steps`, the error-test limit is set to 1 (diffsol
//!   then returns after each rejection, with the smaller step already set, and
//!   the next `step()` carries on from there) and the nonlinear-failure limit
//!   (cumulative over the run in diffsol) to the failures so far plus what is
//!   left of the budget.
//! * Its minimum step is absolute: it is reset to `floor(t)` before each call.
//!   diffsol's first step is its own guess and is not checked against the
//!   minimum, so an accepted step below the floor (other than the one that
//!   lands on `t_end`) is treated as the failure.
//! * Its stop time lands the last step on `t_end` only to rounding; the run's
//!   end time is reported as `t_end` exactly.

use std::cell::{Cell, RefCell};

use diffsol::error::OdeSolverError;
use diffsol::ode_solver::OdeSolverStatistics;
use diffsol::{
    DiffsolError, FaerLU, FaerMat, FaerVec, OdeBuilder, OdeSolverMethod, OdeSolverStopReason,
    Vector, VectorCommon,
};

use super::adaptive::AdaptiveOptions;
use crate::ode::{all_finite, Interpolant, Observer, OdeSystem, Outcome, Stats, Status, StepView};

type Mat = FaerMat<f64>;
type Lu = FaerLU<f64>;
type Vf = FaerVec<f64>;

/// The entries of a (single-batch) faer vector.
fn slice(v: &Vf) -> &[f64] {
    v.inner().col_as_slice(0)
}

/// What the wrapped system has been asked to do, counted exactly.
#[derive(Default)]
struct Counters {
    rhs: Cell<u64>,
    jvp: Cell<u64>,
    /// A non-finite value came out of `rhs` or `jvp` since the last reset.
    nonfinite: Cell<bool>,
}

/// diffsol's dense output of the last accepted step, as an [`Interpolant`].
struct Dense<'a> {
    eval: &'a dyn Fn(f64, &mut [f64]),
}

impl Interpolant for Dense<'_> {
    fn eval(&self, t: f64, out: &mut [f64]) {
        (self.eval)(t, out)
    }
}

/// Integrates from `t0` to `t_end` with diffsol's BDF.
pub(crate) fn integrate<S: OdeSystem, O: Observer>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    opts: &AdaptiveOptions,
    obs: &mut O,
) -> Outcome {
    let d = sys.dim();
    let mut stats = Stats::default();
    let mut y = y0.to_vec();
    let mut f = vec![0.0; d];

    sys.rhs(t0, &y, &mut f);
    stats.rhs_evals += 1;
    if !all_finite(&y) || !all_finite(&f) {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y);
    }
    obs.start(t0, &y, &f);
    if t_end <= t0 {
        return Outcome::ended(Status::Ok, t0, None, stats, y);
    }

    // diffsol's closures are `Fn`: the system is reached through a RefCell.
    // Borrowing it allocates nothing; it is never borrowed twice, because
    // diffsol never calls back while this driver holds it.
    let sys = RefCell::new(sys);
    let counters = Counters::default();
    let rhs = |x: &[f64], _p: &[f64], t: f64, dy: &mut [f64]| {
        sys.borrow_mut().rhs(t, x, dy);
        counters.rhs.set(counters.rhs.get() + 1);
        if !all_finite(dy) {
            counters.nonfinite.set(true);
        }
    };
    let jvp = |x: &[f64], _p: &[f64], t: f64, v: &[f64], jv: &mut [f64]| {
        sys.borrow_mut().jvp(t, x, v, jv);
        counters.jvp.set(counters.jvp.get() + 1);
        if !all_finite(jv) {
            counters.nonfinite.set(true);
        }
    };
    let fail_setup = |stats: Stats, y: Vec<f64>| {
        // Building the problem or the solver only fails on a programming
        // error (a shape mismatch): reported as a failure at the start.
        Outcome::ended(Status::Diverged, t0, Some(t0), stats, y)
    };
    let mut builder = OdeBuilder::<Mat>::new()
        .t0(t0)
        .rtol(opts.rtol)
        .atol([opts.atol])
        .rhs_implicit(rhs, jvp)
        .init(|_p, _t, out| out.copy_from_slice(y0), d);
    if let Some(h0) = opts.h0 {
        // Only its sign is used: diffsol picks the first step itself.
        builder = builder.h0(h0);
    }
    let Ok(problem) = builder.build() else {
        return fail_setup(stats, y);
    };
    let Ok(mut solver) = problem.bdf::<Lu>() else {
        return fail_setup(stats, y);
    };
    if solver.set_stop_time(t_end).is_err() {
        // t_end is within rounding of t0: there is nothing to integrate.
        let st = solver.get_statistics();
        return outcome(
            Status::Ok,
            t_end,
            None,
            st,
            &counters,
            stats.rhs_evals,
            0,
            d,
            y,
        );
    }

    let mut t = t0;
    let mut f1 = vec![0.0; d];
    let buf = RefCell::new(Vf::zeros(d, *problem.context()));
    // RHS calls made by this driver itself (f0, and f1 of each step).
    let mut own_rhs: u64 = stats.rhs_evals;
    // A step diffsol accepted below the floor (at most one, the last).
    let mut discarded: u64 = 0;
    macro_rules! finish {
        ($status:expr, $t:expr, $t_failed:expr, $y:expr) => {
            return outcome(
                $status,
                $t,
                $t_failed,
                solver.get_statistics(),
                &counters,
                own_rhs,
                discarded,
                d,
                $y,
            )
        };
    }
    loop {
        let st = solver.get_statistics();
        let nl_fails = st.number_of_nonlinear_solver_fails;
        let attempts = (st.number_of_steps
            + st.number_of_error_test_failures
            + st.number_of_nonlinear_solver_fails) as u64;
        if attempts >= opts.max_steps {
            finish!(Status::MaxSteps, t, Some(t), y);
        }
        let remaining = usize::try_from(opts.max_steps - attempts).unwrap_or(usize::MAX);
        {
            let cfg = solver.config_mut();
            cfg.minimum_timestep = opts.floor(t);
            cfg.maximum_error_test_failures = 1;
            cfg.maximum_newton_fails = nl_fails.saturating_add(remaining - 1);
        }
        let result = solver.step();

        // A step can be accepted and the call still fail (the next step size
        // fell below the minimum): take the accepted step first.
        let state = solver.state();
        if state.t > t {
            let landed = matches!(result, Ok(OdeSolverStopReason::TstopReached));
            let t1 = if landed { t_end } else { state.t };
            let y1 = slice(state.y);
            if !all_finite(y1) {
                finish!(Status::Diverged, t, Some(t1), y);
            }
            if !landed && t1 - t < opts.floor(t) {
                // Not taken: counted as a rejected attempt.
                discarded = 1;
                finish!(Status::StepSizeTooSmall, t, Some(t1), y);
            }
            sys.borrow_mut().rhs(t1, y1, &mut f1);
            own_rhs += 1;
            if !all_finite(&f1) {
                finish!(Status::Diverged, t, Some(t1), y);
            }
            let t_top = state.t;
            let eval = |tq: f64, out: &mut [f64]| {
                let mut b = buf.borrow_mut();
                // The stop time may sit a rounding error past diffsol's time.
                match solver.interpolate_inplace(tq.min(t_top), &mut b) {
                    Ok(()) => out.copy_from_slice(slice(&b)),
                    // Unreachable: the time is in the step and the shapes match.
                    Err(_) => out.copy_from_slice(y1),
                }
            };
            obs.step(&StepView {
                t0: t,
                t1,
                y0: &y,
                y1,
                f1: &f1,
                interpolant: &Dense { eval: &eval },
            });
            y.copy_from_slice(y1);
            t = t1;
            counters.nonfinite.set(false);
        }

        match result {
            Ok(OdeSolverStopReason::TstopReached) => {
                finish!(Status::Ok, t_end, None, y);
            }
            Ok(_) => {}
            Err(e) => {
                let state = solver.state();
                let (h, t_try) = (state.h, state.t + state.h);
                let nonfinite = counters.nonfinite.get() || !h.is_finite();
                let status = match e {
                    // One rejected attempt (the limit is 1); diffsol has set
                    // the smaller step, and the next call goes on from it. A
                    // NaN error norm leaves a NaN step: diverged.
                    DiffsolError::OdeSolverError(OdeSolverError::TooManyErrorTestFailures {
                        ..
                    }) if h.is_finite() => continue,
                    // Only reachable through the budget set above.
                    DiffsolError::OdeSolverError(
                        OdeSolverError::TooManyNonlinearSolverFailures { .. },
                    ) => Status::MaxSteps,
                    _ if nonfinite => Status::Diverged,
                    DiffsolError::OdeSolverError(OdeSolverError::StepSizeTooSmall { .. }) => {
                        Status::StepSizeTooSmall
                    }
                    // Anything else (a linear-algebra error, which faer's
                    // full-pivoting LU does not raise on a singular matrix)
                    // means the solver could not go on from a finite state:
                    // the closest is "the step could not be made", i.e.
                    // StepSizeTooSmall.
                    _ => Status::StepSizeTooSmall,
                };
                let t_failed = if t_try.is_finite() { t_try } else { t };
                finish!(status, t, Some(t_failed), y);
            }
        }
    }
}

/// The outcome of a run, with diffsol's counters and the exact call counts.
#[allow(clippy::too_many_arguments)]
fn outcome(
    status: Status,
    t: f64,
    t_failed: Option<f64>,
    s: &OdeSolverStatistics,
    counters: &Counters,
    own_rhs: u64,
    discarded: u64,
    d: usize,
    y: Vec<f64>,
) -> Outcome {
    let stats = Stats {
        steps: s.number_of_steps as u64 - discarded,
        rejected_steps: (s.number_of_error_test_failures + s.number_of_nonlinear_solver_fails)
            as u64
            + discarded,
        rhs_evals: own_rhs + counters.rhs.get(),
        // diffsol builds each dense Jacobian from exactly `d` JVPs and calls
        // the JVP for nothing else (no sensitivities here).
        jacobian_evals: counters.jvp.get() / d as u64,
        // Every linear-solver setup is one faer LU of `I - c J`.
        lu_factorizations: s.number_of_linear_solver_setups as u64,
        stiffness_detections: 0,
    };
    Outcome::ended(status, t, t_failed, stats, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    type Rhs = Box<dyn Fn(f64, &[f64], &mut [f64])>;
    type Jvp = Box<dyn Fn(f64, &[f64], &[f64], &mut [f64])>;

    /// A small system given by closures, counting its own calls.
    struct Toy {
        dim: usize,
        f: Rhs,
        j: Jvp,
        rhs_calls: u64,
        jvp_calls: u64,
    }

    impl OdeSystem for Toy {
        fn dim(&self) -> usize {
            self.dim
        }
        fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
            self.rhs_calls += 1;
            (self.f)(t, y, dy)
        }
        fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
            self.jvp_calls += 1;
            (self.j)(t, y, v, jv)
        }
    }

    fn toy(dim: usize, f: Rhs, j: Jvp) -> Toy {
        Toy {
            dim,
            f,
            j,
            rhs_calls: 0,
            jvp_calls: 0,
        }
    }

    /// `x'' = -x`: `y = [x, v]`.
    fn oscillator() -> Toy {
        toy(
            2,
            Box::new(|_t, y, dy| {
                dy[0] = y[1];
                dy[1] = -y[0];
            }),
            Box::new(|_t, _y, v, jv| {
                jv[0] = v[1];
                jv[1] = -v[0];
            }),
        )
    }

    /// Van der Pol with `mu = 1000`: stiff, nonlinear, with rejections.
    fn van_der_pol() -> Toy {
        const MU: f64 = 1000.0;
        toy(
            2,
            Box::new(|_t, y, dy| {
                dy[0] = y[1];
                dy[1] = MU * (1.0 - y[0] * y[0]) * y[1] - y[0];
            }),
            Box::new(|_t, y, v, jv| {
                jv[0] = v[1];
                jv[1] = (-2.0 * MU * y[0] * y[1] - 1.0) * v[0] + MU * (1.0 - y[0] * y[0]) * v[1];
            }),
        )
    }

    fn options(rtol: f64, atol: f64) -> AdaptiveOptions {
        AdaptiveOptions {
            rtol,
            atol,
            h_min: 0.0,
            max_steps: 1_000_000,
            h0: None,
            stop_when_stiff: false,
            switch_lambda: 0.0,
        }
    }

    /// Checks the oscillator's steps against `x = cos(t), v = -sin(t)`.
    #[derive(Default)]
    struct Exact {
        starts: u32,
        steps: u32,
        t_last: f64,
        worst_dense: f64,
        worst_ends: f64,
    }

    impl Observer for Exact {
        fn start(&mut self, t0: f64, _y0: &[f64], _f0: &[f64]) {
            self.starts += 1;
            self.t_last = t0;
        }
        fn step(&mut self, s: &StepView<'_>) {
            assert_eq!(s.t0, self.t_last, "steps are contiguous");
            assert!(s.t1 > s.t0);
            self.t_last = s.t1;
            self.steps += 1;
            let mut out = [0.0; 2];
            // The dense output passes through both ends of the step ...
            for (t, y) in [(s.t0, s.y0), (s.t1, s.y1)] {
                s.interpolant.eval(t, &mut out);
                let e = (out[0] - y[0]).abs().max((out[1] - y[1]).abs());
                self.worst_ends = self.worst_ends.max(e);
            }
            // ... and follows the solution in between.
            for k in 1..4 {
                let t = s.t0 + (s.t1 - s.t0) * k as f64 / 4.0;
                s.interpolant.eval(t, &mut out);
                let e = (out[0] - t.cos()).abs().max((out[1] + t.sin()).abs());
                self.worst_dense = self.worst_dense.max(e);
            }
            // f1 is f(t1, y1).
            assert_eq!(s.f1, &[s.y1[1], -s.y1[0]]);
        }
    }

    #[test]
    fn oscillator_matches_the_exact_solution_with_dense_output() {
        for t0 in [0.0, 1.5] {
            let mut sys = oscillator();
            let mut obs = Exact::default();
            let y0 = [f64::cos(t0), -f64::sin(t0)];
            let t_end = 10.0;
            let out = integrate(&mut sys, t0, &y0, t_end, &options(1e-10, 1e-12), &mut obs);
            assert_eq!(out.status, Status::Ok);
            assert_eq!(out.t_reached, t_end);
            assert_eq!(out.t_failed, None);
            assert_eq!(obs.starts, 1);
            assert_eq!(obs.t_last, t_end, "the last step lands on t_end");
            assert_eq!(obs.steps as u64, out.stats.steps);
            let e = (out.y_end[0] - t_end.cos()).abs() + (out.y_end[1] + t_end.sin()).abs();
            assert!(e < 1e-7, "end error {e:e}");
            assert!(obs.worst_dense < 1e-7, "dense error {:e}", obs.worst_dense);
            assert!(obs.worst_ends < 1e-12, "ends {:e}", obs.worst_ends);
        }
    }

    /// Records nothing.
    struct Quiet;
    impl Observer for Quiet {
        fn start(&mut self, _: f64, _: &[f64], _: &[f64]) {}
        fn step(&mut self, _: &StepView<'_>) {}
    }

    #[test]
    fn counters_are_exact_on_a_stiff_problem() {
        let mut sys = van_der_pol();
        let out = integrate(
            &mut sys,
            0.0,
            &[2.0, 0.0],
            3000.0,
            &options(1e-6, 1e-8),
            &mut Quiet,
        );
        assert_eq!(out.status, Status::Ok);
        assert!(out.stats.rejected_steps > 0, "{:?}", out.stats);
        assert_eq!(out.stats.rhs_evals, sys.rhs_calls);
        assert_eq!(out.stats.jacobian_evals * 2, sys.jvp_calls);
        assert!(out.stats.lu_factorizations >= out.stats.jacobian_evals);
        // A relaxation oscillation of period ~ (3 - 2 ln 2) mu ~ 1614:
        // after 3000 time units x is on the slow branch, |x| in [1, 2].
        assert!((1.0..=2.0).contains(&out.y_end[0].abs()), "{:?}", out.y_end);
    }

    #[test]
    fn the_budget_counts_every_attempt() {
        let mut rejected_seen = false;
        for max_steps in 1..200 {
            let mut sys = van_der_pol();
            let o = AdaptiveOptions {
                max_steps,
                ..options(1e-6, 1e-8)
            };
            let out = integrate(&mut sys, 0.0, &[2.0, 0.0], 3000.0, &o, &mut Quiet);
            assert_eq!(out.status, Status::MaxSteps, "budget {max_steps}");
            assert_eq!(out.stats.steps + out.stats.rejected_steps, max_steps);
            assert!(out.t_reached < 3000.0 && all_finite(&out.y_end));
            rejected_seen |= out.stats.rejected_steps > 0;
        }
        assert!(rejected_seen);
    }

    #[test]
    fn a_blow_up_ends_with_a_status_and_a_finite_state() {
        // y' = y^2, y(0) = 1: y = 1 / (1 - t) leaves every bound at t = 1.
        let mut sys = toy(
            1,
            Box::new(|_t, y, dy| dy[0] = y[0] * y[0]),
            Box::new(|_t, y, v, jv| jv[0] = 2.0 * y[0] * v[0]),
        );
        let out = integrate(
            &mut sys,
            0.0,
            &[1.0],
            2.0,
            &options(1e-8, 1e-10),
            &mut Quiet,
        );
        assert!(
            matches!(out.status, Status::Diverged | Status::StepSizeTooSmall),
            "{:?}",
            out.status
        );
        assert!(out.t_reached < 1.0);
        assert!(out.t_failed.is_some_and(|t| t >= out.t_reached));
        assert!(all_finite(&out.y_end));
        // It stopped on the numerical solution's pole: y = 1 / (t_pole - t)
        // with t_pole = 1 to the tolerance (y itself is ill-conditioned there).
        let t_pole = out.t_reached + 1.0 / out.y_end[0];
        assert!((t_pole - 1.0).abs() < 1e-5, "{out:?}");
    }

    #[test]
    fn a_non_finite_start_is_diverged() {
        let mut sys = oscillator();
        let out = integrate(
            &mut sys,
            0.0,
            &[f64::NAN, 0.0],
            1.0,
            &options(1e-8, 1e-10),
            &mut Quiet,
        );
        assert_eq!(out.status, Status::Diverged);
        assert_eq!(out.t_reached, 0.0);
    }
}
