//! The step loop around diffsol's BDF, shared by `bdf` (the sparse DAE) and
//! `bdf-dense` (the explicit form): the step budget, the step floor, the map
//! from diffsol's errors to a [`Status`], and the observer, which sees
//! diffsol's own dense output.
//!
//! Three things about diffsol 0.18 shape it:
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
//!
//! The observed state is the first `y.len()` unknowns of diffsol's state (all
//! of them for the explicit form; `[phi, w, W]` of the DAE).

use std::cell::{Cell, RefCell};

use diffsol::error::OdeSolverError;
use diffsol::{
    BdfConfig, DiffsolError, FaerContext, FaerVec, OdeEquations, OdeSolverMethod,
    OdeSolverStopReason, Vector, VectorCommon,
};

use super::integrator::Settings;
use super::step_size::initial_step_with;
use crate::ode::{all_finite, Interpolant, Observer, Status, StepView};

/// diffsol's first step (in `state`, from Hairer's guess with its order-1
/// exponent) raised where it is below the step floor of a run to `t_end`:
/// its guess trusts an Euler trial that a start at rest makes tiny, and a
/// very stiff start then stopped at `t = 0` with `step_size_too_small`
/// ([`initial_step_with`], which grows the trial while its own estimate
/// allows; a guess at or above the floor is kept, bit for bit). `rhs` is
/// the problem's right-hand side over diffsol's whole state.
pub(crate) fn raise_first_step(
    state: &mut impl diffsol::OdeSolverState<FaerVec<f64>>,
    t_end: f64,
    opts: &Settings,
    rhs: &mut crate::step_size::RhsFn<'_>,
) {
    let (t0, h) = (state.as_ref().t, state.as_ref().h);
    let span = t_end - t0;
    // The rounding floor only (a user's h_min is a bound, not a step).
    let floor = opts.floor_towards(t0, t_end).min(1e-14 * t0.abs().max(1.0));
    if span.is_nan() || span <= 0.0 || h >= floor {
        return;
    }
    let y0 = slice(state.as_ref().y).to_vec();
    let f0 = slice(state.as_ref().dy).to_vec();
    let (mut a, mut b) = (vec![0.0; y0.len()], vec![0.0; y0.len()]);
    // diffsol's exponent is 1 / (1 + order) at order 1.
    let raised = initial_step_with(rhs, (t0, &y0, &f0), span, opts, 2, (&mut a, &mut b));
    if raised.is_finite() && raised > h {
        *state.as_mut().h = raised;
    }
}

/// The entries of a (single-batch) faer vector.
pub(crate) fn slice(v: &FaerVec<f64>) -> &[f64] {
    v.inner().col_as_slice(0)
}

/// The entries of a (single-batch) faer vector, mutably.
pub(crate) fn slice_mut(v: &mut FaerVec<f64>) -> &mut [f64] {
    v.inner_mut().col_as_slice_mut(0)
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

impl Driven {
    /// A run whose `t_end` is within rounding of `t0`: there is nothing to
    /// integrate, and it ends at `t_end` in state `y`.
    fn nothing_to_do(t_end: f64, y: Vec<f64>) -> Self {
        Self {
            status: Status::Ok,
            t: t_end,
            t_failed: None,
            discarded: 0,
            y,
        }
    }

    /// The run's outcome: steps and rejections from diffsol's statistics
    /// (a step accepted below the floor counts as rejected), one LU per
    /// linear-solver setup, and the call counts the caller made exactly.
    pub(crate) fn outcome(
        self,
        s: &diffsol::ode_solver::OdeSolverStatistics,
        rhs_evals: u64,
        jacobian_evals: u64,
    ) -> crate::ode::Outcome {
        let stats = crate::ode::Stats {
            steps: s.number_of_steps as u64 - self.discarded,
            rejected_steps: (s.number_of_error_test_failures + s.number_of_nonlinear_solver_fails)
                as u64
                + self.discarded,
            rhs_evals,
            jacobian_evals,
            lu_factorizations: s.number_of_linear_solver_setups as u64,
            stiffness_detections: 0,
            error_test_failures: s.number_of_error_test_failures as u64,
            newton_failures: s.number_of_nonlinear_solver_fails as u64,
            newton_iterations: s.number_of_nonlinear_solver_iterations as u64,
            step_size_changes: 0,
        };
        crate::ode::Outcome::ended(self.status, self.t, self.t_failed, stats, self.y)
    }
}

/// `rhs(t, y, f)` at an accepted state (full unknowns in and out).
pub(crate) type StateRhs<'a> = &'a mut dyn FnMut(f64, &[f64], &mut [f64]);

/// How the loop ended.
pub(crate) struct Driven {
    pub status: Status,
    pub t: f64,
    pub t_failed: Option<f64>,
    /// A step diffsol accepted below the floor (0 or 1): counted as rejected.
    pub discarded: u64,
    /// The observed state at `t`.
    pub y: Vec<f64>,
}

/// How the driver reaches the problem between diffsol's steps.
pub(crate) struct Hooks<'h> {
    /// `rhs(t, y_full, f_full)`: the right-hand side at an accepted state,
    /// for the observer's `f1` (only its first `y.len()` entries are read,
    /// and only those need be written).
    pub rhs: StateRhs<'h>,
    /// Set by the caller's right-hand sides when they produce a non-finite
    /// value; cleared by the driver after every accepted step.
    pub nonfinite: &'h Cell<bool>,
    /// Whether the last linear solve failed.
    pub linear_failed: &'h dyn Fn() -> bool,
}

/// Sets `solver`'s stop time to `t_end` and steps it there from `t0`
/// (observed state `y`, already shown to `obs`), reaching the problem
/// through `hooks`. A `t_end` diffsol cannot stop at (within rounding of
/// `t0`) leaves nothing to do.
pub(crate) fn drive<'a, Eqn, S>(
    solver: &mut S,
    t0: f64,
    mut y: Vec<f64>,
    t_end: f64,
    opts: &Settings,
    obs: &mut dyn Observer,
    hooks: Hooks<'_>,
) -> Driven
where
    Eqn: OdeEquations<T = f64, V = FaerVec<f64>, C = FaerContext> + 'a,
    S: OdeSolverMethod<'a, Eqn, Config = BdfConfig<f64>>,
{
    if solver.set_stop_time(t_end).is_err() {
        return Driven::nothing_to_do(t_end, y);
    }
    let Hooks {
        rhs,
        nonfinite,
        linear_failed,
    } = hooks;
    let d = y.len();
    let full = solver.state().y.len();
    let mut t = t0;
    let mut f1 = vec![0.0; full];
    let buf = RefCell::new(FaerVec::zeros(full, *solver.problem().context()));
    let mut discarded = 0;
    macro_rules! finish {
        ($status:expr, $t:expr, $t_failed:expr) => {
            return Driven {
                status: $status,
                t: $t,
                t_failed: $t_failed,
                discarded,
                y,
            }
        };
    }
    loop {
        let st = solver.get_statistics();
        let nl_fails = st.number_of_nonlinear_solver_fails;
        let attempts = (st.number_of_steps
            + st.number_of_error_test_failures
            + st.number_of_nonlinear_solver_fails) as u64;
        if attempts >= opts.max_steps {
            finish!(Status::MaxSteps, t, Some(t));
        }
        if obs.stop() {
            finish!(Status::Interrupted, t, Some(t));
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
                finish!(Status::Diverged, t, Some(t1));
            }
            if !landed && t1 - t < opts.floor(t) {
                // Not taken: counted as a rejected attempt.
                discarded = 1;
                finish!(Status::StepSizeTooSmall, t, Some(t1));
            }
            rhs(t1, y1, &mut f1);
            if !all_finite(&f1[..d]) {
                finish!(Status::Diverged, t, Some(t1));
            }
            let t_top = state.t;
            let eval = |tq: f64, out: &mut [f64]| {
                let mut b = buf.borrow_mut();
                // The stop time may sit a rounding error past diffsol's time.
                match solver.interpolate_inplace(tq.min(t_top), &mut b) {
                    Ok(()) => out.copy_from_slice(&slice(&b)[..d]),
                    // Unreachable: the time is in the step and the shapes match.
                    Err(_) => out.copy_from_slice(&y1[..d]),
                }
            };
            obs.step(&StepView {
                t0: t,
                t1,
                y0: &y,
                y1: &y1[..d],
                f1: &f1[..d],
                interpolant: &Dense { eval: &eval },
            });
            y.copy_from_slice(&y1[..d]);
            t = t1;
            nonfinite.set(false);
        }

        match result {
            Ok(OdeSolverStopReason::TstopReached) => {
                finish!(Status::Ok, t_end, None);
            }
            Ok(_) => {}
            Err(e) => {
                let state = solver.state();
                let (h, t_try) = (state.h, state.t + state.h);
                let bad = nonfinite.get() || !h.is_finite();
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
                    _ if bad => Status::Diverged,
                    // The Newton matrix could not be factorised, and smaller
                    // steps did not help.
                    _ if linear_failed() => Status::LinearSolveFailed,
                    DiffsolError::OdeSolverError(OdeSolverError::StepSizeTooSmall { .. }) => {
                        Status::StepSizeTooSmall
                    }
                    // Anything else means the solver could not go on from a
                    // finite state: the closest is "the step could not be
                    // made", i.e. StepSizeTooSmall.
                    _ => Status::StepSizeTooSmall,
                };
                let t_failed = if t_try.is_finite() { t_try } else { t };
                finish!(status, t, Some(t_failed));
            }
        }
    }
}
