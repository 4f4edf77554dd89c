//! `gen-alpha`: the generalized-alpha method of Chung & Hulbert (1993), in
//! the first-order form of Jansen, Whiting & Hulbert (2000), on a problem's
//! banded DAE ([`Problem::banded_dae`]), with adaptive steps, O(n) per step
//! (the block-tridiagonal LU of `bdf`).
//!
//! For the semi-explicit DAE `d' = f(t, d, z)`, `0 = g(t, d, z)` (`d` the
//! differential unknowns, the problem's state; `z` the algebraic ones) the
//! method carries the state `d_n` and a derivative sequence of its own
//! `v_n` (`v_0 = d'(t_0)`), and a step of size `h` solves
//!
//! ```text
//! d_{n+1} = d_n + h ((1 - gamma) v_n + gamma v_{n+1})
//! (1 - a_m) v_n + a_m v_{n+1} = f(t_n + a_f h, d_{n+a_f}, z)
//!                           0 = g(t_n + a_f h, d_{n+a_f}, z)
//! d_{n+a_f} = (1 - a_f) d_n + a_f d_{n+1}
//! ```
//!
//! with `a_m = (3 - rho)/(2 (1 + rho))`, `a_f = 1/(1 + rho)` and
//! `gamma = 1/2 + a_m - a_f`: second order, A-stable, and with the
//! spectral radius `rho` (`run.rho_inf`) as `h |lambda| -> infinity`, so
//! that modes far above `1/h` are damped by `rho` per step instead of
//! followed. Newton's unknowns are `u = (d_{n+a_f}, z)`; its matrix is
//! `E - beta J(u)` (`E` the identity on the differential rows, `beta =
//! a_f gamma h / a_m`), the shape of BDF's, so that the same LU solves it
//! in O(n). The Jacobian and the LU are kept across steps and attempts
//! while the Newton iteration contracts fast ([`newton`]).
//!
//! On a smooth solution `v_n` is the derivative at `t_n + c h`, `c = a_f -
//! a_m = (rho - 1) / (2 (1 + rho))`, not at `t_n`: a change of the step
//! from `h` to `h'` moves it to `v_n + c (h' - h) d''` ([`shifted`]), or
//! every change costs the method an order.
//!
//! The local error of a step is `C_3 h^3 d'''`, `C_3 = -(rho^2 - rho +
//! 1) / (3 (1 + rho)^2)` the method's error constant, with `d'''` the
//! derivative sequence's second divided difference at the times its
//! values stand for, filtered by the Newton matrix (`(E - beta J)^-1 e`,
//! as implicit Runge-Kutta codes filter theirs) so that a damped mode the
//! step does not resolve does not count as error; it is measured on the
//! problem's configuration ([`Problem::configuration`]) and on the
//! quantities it measures ([`Problem::measured`]). The step follows it
//! through [`control`]'s PI filter, which keeps `h` inside a dead band:
//! on a problem with modes the step damps, each change of `h` costs
//! accuracy. docs/model.md, "The generalized-alpha method", derives all of
//! it and gives the measurements behind [`policy`]'s constants.
//!
//! Its files: [`control`], [`newton`] and [`policy`] as above, and
//! `tests.rs`, the method's own tests.

mod control;
mod newton;
mod policy;
#[cfg(test)]
mod tests;

use diffsol::{FaerContext, FaerVec, Vector};

use crate::diffsol_driver::{slice, slice_mut};
use crate::integrator::{Integrator, Span};
use crate::ode::{
    all_finite, BandedDae, Counted, Interpolant, Measured, Observer, OdeSystem, Outcome, Problem,
    SemiExplicitDae, Stats, Status, StepView,
};
use control::Controller;
use newton::Newton;
pub use policy::{with_gen_alpha_policy, ControlPolicy, GenAlphaPolicy, ReusePolicy};

/// `run.rho_inf`'s range: the spectral radius at infinity.
pub const RHO_INF_RANGE: (f64, f64) = (0.0, 1.0);

/// `run.rho_inf`'s default (docs/model.md, "The generalized-alpha method":
/// chosen from the measured steps and errors on the elastic snap).
pub const DEFAULT_RHO_INF: f64 = 0.9;

/// Newton iterations per attempt before the step is retried smaller.
const NEWTON_MAX: u32 = 10;
/// A step whose Newton iteration fails with a Jacobian evaluated in the
/// attempt is retried this much smaller.
const NEWTON_SHRINK: f64 = 0.25;

/// The method's coefficients for one `rho_inf`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Coefficients {
    pub a_m: f64,
    pub a_f: f64,
    pub gamma: f64,
    /// The error constant `C_3` (negative): the local error of a step is
    /// `C_3 h^3 d'''`.
    pub c3: f64,
    /// `c = a_f - a_m`: on a smooth solution `v_n` is the derivative at
    /// `t_n + c h`.
    pub shift: f64,
}

impl Coefficients {
    /// Chung & Hulbert's choice for the spectral radius `rho` at infinity
    /// (Jansen, Whiting & Hulbert's first-order form).
    pub fn of(rho: f64) -> Self {
        let a_m = (3.0 - rho) / (2.0 * (1.0 + rho));
        let a_f = 1.0 / (1.0 + rho);
        Self {
            a_m,
            a_f,
            gamma: 0.5 + a_m - a_f,
            c3: -(rho * rho - rho + 1.0) / (3.0 * (1.0 + rho) * (1.0 + rho)),
            shift: a_f - a_m,
        }
    }
}

/// The weighted RMS norm of `x` over the unknowns `rows`, with weights
/// `atol + rtol |s_i|`.
fn wrms(x: &[f64], scale: &[f64], rows: &[usize], rtol: f64, atol: f64) -> f64 {
    if rows.is_empty() {
        return 0.0;
    }
    let sum: f64 = rows
        .iter()
        .map(|&i| {
            let q = x[i] / (atol + rtol * scale[i].abs());
            q * q
        })
        .sum();
    (sum / rows.len() as f64).sqrt()
}

/// `out = v + c (h - hv) a`: the derivative sequence's last value `v`,
/// which stands for the derivative at `t + c hv`, moved to `t + c h` with
/// the second derivative `a` (docs/model.md: without it a change of the
/// step costs the method an order).
fn shifted(out: &mut [f64], v: &[f64], a: &[f64], c: f64, h: f64, hv: f64) {
    let k = c * (h - hv);
    for ((o, &vi), &ai) in out.iter_mut().zip(v).zip(a) {
        *o = vi + k * ai;
    }
}

/// Integrates `problem` over `span` on its banded DAE; a problem without
/// one ends at the start, `diverged` (the model refuses the method first).
pub(crate) fn integrate(
    problem: &mut dyn Problem,
    s: &Span<'_>,
    obs: &mut dyn Observer,
) -> Outcome {
    let (t0, y0) = (s.t0, s.y0);
    let Some(BandedDae { dae, y0: full }) = problem.banded_dae(t0, y0) else {
        return Outcome::ended(
            Status::Diverged,
            t0,
            Some(t0),
            Stats::default(),
            y0.to_vec(),
        );
    };
    // The unknowns the error is measured on: the configuration, else all.
    let nd = dae.differential_dim();
    let mut configuration: Vec<usize> = problem
        .configuration()
        .into_iter()
        .flatten()
        .filter(|&i| i < nd)
        .collect();
    // Newton's tolerance: tight where the step resolves every mode (the
    // error measured on every unknown), RADAU5's where it damps modes it
    // does not resolve (`GenAlphaPolicy::newton_tol`).
    let newton_tol = if configuration.is_empty() {
        policy::current().newton_tol
    } else {
        1.0
    };
    if configuration.is_empty() || policy::current().measure_all {
        configuration = (0..nd).collect();
    }
    let measured = if policy::current().measured {
        problem.measured()
    } else {
        None
    };
    let control = ErrorControl {
        configuration: &configuration,
        measured: measured.as_deref(),
        newton_tol,
    };
    let mut out = Counted::run(problem, |sys| {
        run(sys, dae.as_ref(), full, &control, s, obs)
    });
    // The loop counts the DAE's residuals into `rhs_evals` too.
    out.stats.rhs_evals += out.stats.newton_iterations;
    out
}

/// What the local error is measured on: unknowns of the state, and
/// quantities of it.
struct ErrorControl<'a> {
    configuration: &'a [usize],
    measured: Option<&'a dyn Measured>,
    /// Newton's stopping tolerance as a fraction of RADAU5's.
    newton_tol: f64,
}

/// The step loop: `sys` (counted) gives the derivatives the observer and
/// the dense output see, `dae` the equations Newton solves; `full` is
/// every unknown at `t0`, consistent.
fn run<S: OdeSystem>(
    sys: &mut S,
    dae: &dyn SemiExplicitDae,
    full: Vec<f64>,
    measure: &ErrorControl<'_>,
    span: &Span<'_>,
    obs: &mut dyn Observer,
) -> Outcome {
    let (t0, t_end, set) = (span.t0, span.t_end, span.settings);
    let (dim, nd) = (dae.dim(), dae.differential_dim());
    let policy = policy::current();
    let mut stats = Stats::default();
    let mut d = span.y0.to_vec();
    if full.len() != dim || d.len() != nd {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, d);
    }
    let Some(mut newton) = Newton::new(dae, t0, &full, policy.reuse) else {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, d);
    };
    let mut control = Controller::new(policy.control);
    let k = Coefficients::of(set.rho_inf);
    let c = if policy.shift { k.shift } else { 0.0 };
    // `R = (d* - d_n) + beta k1 v_n - beta f(t*, u)` on the differential
    // rows, `-beta g(t*, u)` on the algebraic ones.
    let k1 = (1.0 - k.a_m) - k.a_m * (1.0 - k.gamma) / k.gamma;
    // Newton's tolerance in the error norm: a fraction of RADAU5's
    // (`ErrorControl::newton_tol`).
    let tol = (10.0 * f64::EPSILON / set.rtol).max(set.rtol.sqrt().min(0.03) * measure.newton_tol);

    // The derivatives at the start: the method's `v_0` and the dense
    // output's `f_0`.
    let mut f = vec![0.0; nd];
    sys.rhs(t0, &d, &mut f);
    if !all_finite(&f) || !all_finite(&full) {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, d);
    }
    obs.start(t0, &d, &f);
    if t_end <= t0 {
        return Outcome::ended(Status::Ok, t0, None, stats, d);
    }
    // The derivative sequence: its last value `v` stands for the
    // derivative at `t + c hv` (`hv = 0` at the start: `v_0 = f_0`); `a`
    // is the second derivative over the last step, at `t - a_lag`, once
    // there is one.
    let mut v = f.clone();
    let mut hv = 0.0;
    let mut a = vec![0.0; nd];
    let mut a_lag: Option<f64> = None;
    let mut z = full[nd..].to_vec();
    // The state before `d` and the step from it, once there is one (the
    // dense output's third point).
    let mut back: Option<(f64, Vec<f64>)> = None;

    // Scratch, allocated once.
    let mut vu = vec![0.0; nd];
    let mut u = vec![0.0; dim];
    let mut res = vec![0.0; dim];
    let mut x = FaerVec::from_vec(vec![0.0; dim], FaerContext::default());
    let (mut d1, mut v1, mut f1) = (vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]);
    let mq = measure.measured.map_or(0, |m| m.count());
    let (mut q1, mut qe, mut de) = (vec![0.0; mq], vec![0.0; mq], vec![0.0; nd]);

    // The first step: the explicit heuristic at second order, capped.
    let mut h = match (policy.fixed_step, set.h0) {
        (Some(hf), _) => hf,
        (None, Some(h0)) => h0.abs(),
        (None, None) => {
            let (mut a1, mut b1) = (vec![0.0; nd], vec![0.0; nd]);
            crate::step_size::initial_step(sys, t0, &d, &f, t_end - t0, set, 2, (&mut a1, &mut b1))
        }
    };
    let mut t = t0;
    // The last attempt met a non-finite value (reset by an accepted step).
    let mut saw_nonfinite = false;
    while t < t_end {
        if stats.steps + stats.rejected_steps >= set.max_steps {
            return Outcome::ended(Status::MaxSteps, t, Some(t), stats, d);
        }
        if obs.stop() {
            return Outcome::ended(Status::Interrupted, t, Some(t), stats, d);
        }
        h = h.min(set.scales.max_step_at(t));
        let floor = set.floor_towards(t, t_end);
        if h.is_nan() || h < floor {
            // Cut to the floor by non-finite values: the run diverged there.
            let status = if saw_nonfinite {
                Status::Diverged
            } else {
                Status::StepSizeTooSmall
            };
            return Outcome::ended(status, t, Some(t + h), stats, d);
        }
        // Land on t_end (a sliver below 1e-9 h absorbed).
        let landing = t + h >= t_end - 1e-9 * h;
        let h_step = if landing { t_end - t } else { h };
        // The derivative sequence at this step's shift.
        if a_lag.is_some() && h_step != hv {
            shifted(&mut vu, &v, &a, c, h_step, hv);
        } else {
            vu.copy_from_slice(&v);
        }
        let t_star = t + k.a_f * h_step;
        let beta = k.a_f * k.gamma * h_step / k.a_m;
        // The predictor: the state at the step's alpha-point along the
        // derivative sequence, the last algebraic unknowns.
        for i in 0..nd {
            u[i] = d[i] + k.a_f * h_step * vu[i];
        }
        u[nd..].copy_from_slice(&z);
        let mut converged = newton.prepare(dae, t_star, &u, beta, &mut stats);
        let mut prev_norm = f64::INFINITY;
        let mut iter = 0;
        // The largest contraction rate of this attempt's corrections.
        let mut theta_max: f64 = 0.0;
        while converged {
            if iter == NEWTON_MAX {
                converged = false;
                break;
            }
            iter += 1;
            stats.newton_iterations += 1;
            dae.rhs(t_star, &u, &mut res);
            if !all_finite(&res) {
                converged = false;
                saw_nonfinite = true;
                break;
            }
            let xs = slice_mut(&mut x);
            for i in 0..nd {
                xs[i] = (u[i] - d[i]) + beta * (k1 * vu[i] - res[i]);
            }
            for i in nd..dim {
                xs[i] = -beta * res[i];
            }
            if !newton.solve(&mut x) {
                converged = false;
                break;
            }
            let dx = slice(&x);
            let norm = wrms(dx, &d, newton.rows(), set.rtol, set.atol);
            if !norm.is_finite() || !all_finite(dx) {
                converged = false;
                break;
            }
            let theta = norm / prev_norm;
            // Diverging, or with a Jacobian kept from earlier too slow to
            // converge within its iterations at this rate (RADAU5's
            // test): a kept Jacobian is evaluated again here (a converging
            // correction taken first), a fresh one fails the attempt.
            let reuse = newton.policy();
            let left = reuse.stale_iters.saturating_sub(iter);
            let slow = prev_norm.is_finite()
                && norm > 1e-3 * tol
                && (theta >= 1.0
                    || (!newton.fresh()
                        && (theta >= reuse.theta_slow
                            || theta.powi(left as i32) / (1.0 - theta) * norm > tol)));
            if slow {
                if newton.fresh() {
                    converged = false;
                    break;
                }
                if theta < 1.0 {
                    for (ui, &dxi) in u.iter_mut().zip(dx) {
                        *ui -= dxi;
                    }
                }
                converged = newton.refresh(dae, t_star, &u, beta, &mut stats);
                prev_norm = f64::INFINITY;
                continue;
            }
            for (ui, &dxi) in u.iter_mut().zip(dx) {
                *ui -= dxi;
            }
            if prev_norm.is_finite() {
                theta_max = theta_max.max(theta);
            }
            // Converged: a correction far below the tolerance (at rounding
            // level, no rate can be measured), or the rate-corrected one
            // within it.
            if norm <= 1e-3 * tol || (prev_norm.is_finite() && theta / (1.0 - theta) * norm <= tol)
            {
                break;
            }
            prev_norm = norm;
        }
        if !converged || !all_finite(&u) {
            stats.rejected_steps += 1;
            stats.newton_failures += 1;
            control.newton_failed();
            // Retried with a Jacobian evaluated at the new predictor: at
            // the same step if the failed attempt's was older, else at a
            // quarter of it.
            if newton.fresh() {
                h = h_step * NEWTON_SHRINK;
            }
            newton.mark_stale();
            continue;
        }
        // The step's end and the method's derivatives there.
        for i in 0..nd {
            d1[i] = (u[i] - (1.0 - k.a_f) * d[i]) / k.a_f;
            v1[i] = (d1[i] - d[i] - h_step * (1.0 - k.gamma) * vu[i]) / (h_step * k.gamma);
        }
        // The local error: |C_3| h^3 d''' from the derivatives' second
        // divided difference at the times they stand for (the first step:
        // the first-order term h^2 d'' / 2, an overestimate), filtered by
        // the Newton matrix.
        let xs = slice_mut(&mut x);
        match a_lag {
            Some(lag) => {
                let q = k.c3.abs() * h_step * h_step * h_step / (h_step * (0.5 + c) + lag);
                for i in 0..nd {
                    xs[i] = q * ((v1[i] - vu[i]) / h_step - a[i]);
                }
            }
            None => {
                for i in 0..nd {
                    xs[i] = 0.5 * h_step * (v1[i] - vu[i]);
                }
            }
        }
        xs[nd..].fill(0.0);
        let filtered = !policy.filter || newton.solve(&mut x);
        let t1 = if landing { t_end } else { t + h_step };
        let e = slice(&x);
        let err = if filtered {
            error_norm(
                measure,
                e,
                &d,
                &d1,
                t1,
                set.rtol,
                set.atol,
                (&mut de, &mut q1, &mut qe),
            )
        } else {
            f64::INFINITY
        };
        if policy.fixed_step.is_none() && (!err.is_finite() || err > 1.0) {
            stats.rejected_steps += 1;
            stats.error_test_failures += 1;
            h = h_step * control.rejected(err);
            continue;
        }
        // The dense output over the step, and its derivative at the end
        // for the observer (the slope its maxima search reads).
        let dense = Quadratic {
            t0: t,
            h: t1 - t,
            y0: &d,
            y1: &d1,
            before: match &back {
                Some((hp, dp)) if policy.quadratic => Before::State(*hp, dp),
                _ if policy.quadratic && stats.steps == 0 => Before::Slope(&f),
                _ => Before::None,
            },
        };
        if policy.quadratic {
            dense.slope_at_end(&mut f1);
        } else {
            sys.rhs(t1, &d1, &mut f1);
        }
        if !all_finite(&d1) || !all_finite(&f1) {
            // The step's end left the domain of `f`: retried smaller, as a
            // failed solve; a run that cannot get past it ends at the floor.
            stats.rejected_steps += 1;
            stats.newton_failures += 1;
            h = h_step * NEWTON_SHRINK;
            saw_nonfinite = true;
            continue;
        }
        stats.steps += 1;
        obs.step(&StepView {
            t0: t,
            t1,
            y0: &d,
            y1: &d1,
            f1: &f1,
            interpolant: &dense,
        });
        // The second derivative over this step, at `t + h (1/2 + c)`: `h
        // (1/2 - c)` before the step's end.
        for i in 0..nd {
            a[i] = (v1[i] - vu[i]) / h_step;
        }
        a_lag = Some(h_step * (0.5 - c));
        std::mem::swap(&mut v, &mut v1);
        hv = h_step;
        // The step's start becomes the state before the next one.
        match &mut back {
            Some((hp, dp)) => {
                *hp = h_step;
                dp.copy_from_slice(&d);
            }
            None => back = Some((h_step, d.clone())),
        }
        std::mem::swap(&mut d, &mut d1);
        std::mem::swap(&mut f, &mut f1);
        z.copy_from_slice(&u[nd..]);
        t = t1;
        saw_nonfinite = false;
        newton.accepted(theta_max);
        match policy.fixed_step {
            Some(hf) => h = hf,
            None => {
                let fac = control.accepted(err);
                if fac != 1.0 {
                    stats.step_size_changes += 1;
                }
                h = h_step * fac;
            }
        }
    }
    Outcome::ended(Status::Ok, t, None, stats, d)
}

/// The local error `e` of the step from `d` to `d1` (ending at `t1`) in the
/// tolerance's units: the weighted RMS norm over the configuration and,
/// for each measured quantity `q`, `q(d1 + e) - q(d1)` weighted by `atol +
/// rtol |q(d1)|`. `scratch` holds `d1 + e` and the quantities.
#[allow(clippy::too_many_arguments)]
fn error_norm(
    measure: &ErrorControl<'_>,
    e: &[f64],
    d: &[f64],
    d1: &[f64],
    t1: f64,
    rtol: f64,
    atol: f64,
    (de, q1, qe): (&mut [f64], &mut [f64], &mut [f64]),
) -> f64 {
    let mut sum = 0.0;
    for &i in measure.configuration {
        let q = e[i] / (atol + rtol * d[i].abs().max(d1[i].abs()));
        sum += q * q;
    }
    let mut count = measure.configuration.len();
    if let Some(m) = measure.measured {
        for ((o, &y), &ei) in de.iter_mut().zip(d1).zip(e) {
            *o = y + ei;
        }
        m.values(t1, d1, q1);
        m.values(t1, de, qe);
        for (&a, &b) in q1.iter().zip(qe.iter()) {
            let q = (b - a) / (atol + rtol * a.abs());
            sum += q * q;
        }
        count += q1.len();
    }
    if count == 0 {
        return 0.0;
    }
    (sum / count as f64).sqrt()
}

/// `gen-alpha`: the generalized-alpha method on the banded DAE, adaptive,
/// O(n) per step; `rtol` sets its accuracy, `run.rho_inf` its damping of
/// the modes it steps over.
pub(crate) const GEN_ALPHA: Integrator = Integrator {
    name: "gen-alpha",
    adaptive: true,
    nonsmooth: false,
    run: |p, s, obs| integrate(p, s, obs).into(),
};

/// What the dense output knows before a step besides its ends.
enum Before<'a> {
    /// The state `h` before the step's start.
    State(f64, &'a [f64]),
    /// The derivative at the start (the first step: `f_0`, exact).
    Slope(&'a [f64]),
    /// Nothing: linear.
    None,
}

/// The dense output: the quadratic through the states at the step's ends
/// and the one before (on the first step, through the ends with the start's
/// derivative), third order like the method's local error. It is built on
/// the states alone: the cubic Hermite of the explicit methods, built on
/// the model's derivatives, carries the accelerations of the modes the
/// step damps without resolving them (at `EA = 1e8` it put the snap's
/// largest tip speed 9% high), where the states carry those modes at their
/// damped amplitude, which the quadratic's weights (at most 1.25 in sum)
/// keep. docs/model.md measures it against the linear interpolant.
struct Quadratic<'a> {
    t0: f64,
    h: f64,
    y0: &'a [f64],
    y1: &'a [f64],
    before: Before<'a>,
}

impl Quadratic<'_> {
    /// The interpolant's derivative at the step's end into `out`: what the
    /// observer gets as `f1`, the slope consistent with the interpolant.
    fn slope_at_end(&self, out: &mut [f64]) {
        let h = self.h;
        for (i, o) in out.iter_mut().enumerate() {
            let d1 = (self.y1[i] - self.y0[i]) / h;
            *o = match self.before {
                Before::State(hp, ym) => {
                    let d2 = (d1 - (self.y0[i] - ym[i]) / hp) / (h + hp);
                    d1 + d2 * h
                }
                Before::Slope(f0) => 2.0 * d1 - f0[i],
                Before::None => d1,
            };
        }
    }
}

impl Interpolant for Quadratic<'_> {
    fn eval(&self, t: f64, out: &mut [f64]) {
        let (s, h) = (t - self.t0, self.h);
        for (i, o) in out.iter_mut().enumerate() {
            let d1 = (self.y1[i] - self.y0[i]) / h;
            // Newton's form on the nodes t1, t0 (and the one before).
            let curve = match self.before {
                Before::State(hp, ym) => {
                    let d2 = (d1 - (self.y0[i] - ym[i]) / hp) / (h + hp);
                    d2 * s * (s - h)
                }
                Before::Slope(f0) => (d1 - f0[i]) / h * s * (s - h),
                Before::None => 0.0,
            };
            *o = self.y0[i] + d1 * s + curve;
        }
    }
}
