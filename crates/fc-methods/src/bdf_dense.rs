//! `bdf-dense`: diffsol's BDF (variable order 1-5) on the explicit form
//! `y' = f(y)` with the exact Jacobian-vector product of the system.
//!
//! diffsol builds the dense Jacobian column by column from `dim` calls of
//! [`OdeSystem::jvp`] (O(n^2)) and factorises `I - c J` with faer's dense LU
//! (O(n^3)). It is kept beside the O(n) `bdf` to show what the banded form
//! buys; the step loop around diffsol is [`super::diffsol_driver`].

use std::cell::{Cell, RefCell};

use diffsol::{FaerLU, FaerMat, OdeBuilder, OdeSolverMethod};

use super::diffsol_driver::{drive, raise_first_step, Hooks};
use super::integrator::{Integrator, Span};
use crate::ode::{all_finite, Counted, Observer, OdeSystem, Outcome, Stats, Status};

type Mat = FaerMat<f64>;
type Lu = FaerLU<f64>;

/// Integrates from `t0` to `t_end` with diffsol's BDF on the explicit form.
/// Every call to the system, diffsol's and the loop's own, goes through one
/// [`Counted`]: `rhs_evals` is its count.
pub(crate) fn integrate<S>(sys: &mut S, s: &Span<'_>, obs: &mut dyn Observer) -> Outcome
where
    S: OdeSystem + ?Sized,
{
    Counted::run(sys, |sys| run(sys, s, obs))
}

fn run<S: OdeSystem>(sys: &mut Counted<S>, s: &Span<'_>, obs: &mut dyn Observer) -> Outcome {
    let Span {
        t0,
        y0,
        t_end,
        settings: opts,
    } = *s;
    let d = sys.dim();
    let stats = Stats::default();
    let y = y0.to_vec();
    let mut f = vec![0.0; d];

    sys.rhs(t0, &y, &mut f);
    if !all_finite(&y) || !all_finite(&f) {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y);
    }
    obs.start(t0, &y, &f);
    if t_end <= t0 {
        return Outcome::ended(Status::Ok, t0, None, stats, y);
    }

    // diffsol's closures are `Fn`: the system is reached through a RefCell.
    // Borrowing it allocates nothing; it is never borrowed twice, because
    // diffsol never calls back while the driver holds it.
    let sys = RefCell::new(sys);
    // A non-finite value came out of `rhs` or `jvp` since the last reset.
    let nonfinite = Cell::new(false);
    let rhs = |x: &[f64], _p: &[f64], t: f64, dy: &mut [f64]| {
        sys.borrow_mut().rhs(t, x, dy);
        if !all_finite(dy) {
            nonfinite.set(true);
        }
    };
    let jvp = |x: &[f64], _p: &[f64], t: f64, v: &[f64], jv: &mut [f64]| {
        sys.borrow_mut().jvp(t, x, v, jv);
        if !all_finite(jv) {
            nonfinite.set(true);
        }
    };
    // Building the problem or the solver only fails on a programming error
    // (a shape mismatch): reported as a failure at the start.
    let fail_setup =
        |stats: Stats, y: Vec<f64>| Outcome::ended(Status::Diverged, t0, Some(t0), stats, y);
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
    let Ok(mut state) = problem.bdf_state::<Lu>() else {
        return fail_setup(stats, y);
    };
    raise_first_step(&mut state, t_end, opts, &mut |t, y, f| {
        sys.borrow_mut().rhs(t, y, f)
    });
    let Ok(mut solver) = problem.bdf_solver::<Lu>(state) else {
        return fail_setup(stats, y);
    };
    let hooks = Hooks {
        rhs: &mut |t: f64, y: &[f64], f: &mut [f64]| sys.borrow_mut().rhs(t, y, f),
        nonfinite: &nonfinite,
        linear_failed: &|| false,
    };
    let driven = drive(&mut solver, t0, y, t_end, opts, obs, hooks);
    let jvp_calls = sys.borrow().jvp_calls();
    // diffsol builds each dense Jacobian from exactly `d` JVPs and calls the
    // JVP for nothing else; `rhs_evals` is filled in by [`Counted::run`].
    driven.outcome(solver.get_statistics(), 0, jvp_calls / d as u64)
}

/// `bdf-dense`: diffsol's BDF on the explicit form, dense LU: the O(n^3)
/// reference for `bdf`.
pub(crate) const BDF_DENSE: Integrator = Integrator {
    name: "bdf-dense",
    adaptive: true,
    run: |p, s, obs| integrate(p, s, obs).into(),
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_problems::{options, oscillator_dense_check, van_der_pol, Quiet};

    #[test]
    fn oscillator_matches_the_exact_solution_with_dense_output() {
        let o = options(1e-10, 1e-12);
        oscillator_dense_check(1e-7, |sys, t0, y0, t_end, obs| {
            let span = Span {
                t0,
                y0,
                t_end,
                settings: &o,
            };
            integrate(sys, &span, obs)
        });
    }

    #[test]
    fn counters_are_exact_on_a_stiff_problem() {
        let mut sys = van_der_pol(1000.0);
        let span = Span {
            t0: 0.0,
            y0: &[2.0, 0.0],
            t_end: 3000.0,
            settings: &options(1e-6, 1e-8),
        };
        let out = integrate(&mut sys, &span, &mut Quiet);
        assert_eq!(out.status, Status::Ok);
        assert!(out.stats.rejected_steps > 0, "{:?}", out.stats);
        assert_eq!(out.stats.rhs_evals, sys.rhs_calls);
        assert_eq!(out.stats.jacobian_evals * 2, sys.jvp_calls);
        assert!(out.stats.lu_factorizations >= out.stats.jacobian_evals);
        let st = out.stats;
        assert_eq!(
            st.error_test_failures + st.newton_failures,
            st.rejected_steps
        );
        assert!(st.newton_iterations >= st.steps, "{st:?}");
        // A relaxation oscillation of period ~ (3 - 2 ln 2) mu ~ 1614:
        // after 3000 time units x is on the slow branch, |x| in [1, 2].
        assert!((1.0..=2.0).contains(&out.y_end[0].abs()), "{:?}", out.y_end);
    }
}
