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
//! in O(n).
//!
//! The local error of a step is estimated from the method's derivatives,
//! `e = |C_3| h^3 d'''` with `d'''` their second divided difference and
//! `C_3 = -(rho^2 - rho + 1) / (3 (1 + rho)^2)` the method's error
//! constant, and filtered by the Newton matrix (`(E - beta J)^-1 e`, as
//! implicit Runge-Kutta codes filter theirs), so that a damped mode the
//! step does not resolve does not count as error. docs/model.md, "The
//! generalized-alpha method", derives both.

use std::rc::Rc;

use diffsol::{FaerContext, FaerSparseMat, FaerVec, Matrix, Vector};
use diffsol_la::{LinearOp, LinearSolver};
use faer::sparse::SymbolicSparseColMat;

use crate::bdf::NewtonLu;
use crate::diffsol_driver::{slice, slice_mut};
use crate::integrator::{Integrator, Span};
use crate::ode::{
    all_finite, BandedDae, Counted, Interpolant, Observer, OdeSystem, Outcome, Problem,
    SemiExplicitDae, Stats, Status, StepView,
};
use crate::sparse_lu::LuLog;

/// `run.rho_inf`'s range: the spectral radius at infinity.
pub const RHO_INF_RANGE: (f64, f64) = (0.0, 1.0);

/// `run.rho_inf`'s default (docs/model.md, "The generalized-alpha method":
/// chosen from the measured steps and errors on the elastic snap).
pub const DEFAULT_RHO_INF: f64 = 0.9;

/// Newton iterations per attempt before the step is retried smaller.
const NEWTON_MAX: u32 = 10;
/// A contraction `theta` of the Newton corrections at least this refreshes
/// the Jacobian at the iterate, at most [`REFRESHES`] times an attempt.
const SLOW: f64 = 0.5;
const REFRESHES: u32 = 2;

/// The step may grow at most this much per step, and shrink at most
/// [`SHRINK_MIN`] on a failed error test.
const GROW_MAX: f64 = 3.0;
const SHRINK_MIN: f64 = 0.2;
/// A step whose Newton iteration fails is retried this much smaller.
const NEWTON_SHRINK: f64 = 0.25;
/// The step controller's safety factor.
const SAFETY: f64 = 0.9;
/// A step grows only when the controller allows at least this factor
/// (measured on the elastic snap: 1.3 halves the error at the same steps
/// against growing by any factor, docs/model.md).
const GROW_MIN: f64 = 1.3;

/// The method's coefficients for one `rho_inf`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Coefficients {
    pub a_m: f64,
    pub a_f: f64,
    pub gamma: f64,
    /// The error constant `C_3` (negative): the local error of a step is
    /// `C_3 h^3 d'''`.
    pub c3: f64,
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
        }
    }
}

/// The Newton matrix `E - beta J` on the DAE's pattern (the Jacobian's
/// entries and the differential rows' diagonal), its values in CSC order,
/// as the LU reads it. Assembled in O(nnz), allocation-free.
struct NewtonOp {
    dim: usize,
    pattern: SymbolicSparseColMat<usize>,
    /// The CSC position of each Jacobian entry, in emission order.
    jac_slots: Vec<usize>,
    /// The CSC position of each differential row's diagonal.
    diag_slots: Vec<usize>,
    values: Vec<f64>,
    ctx: FaerContext,
}

impl NewtonOp {
    /// The pattern of `dae` at its start; `None` if it is malformed.
    fn new(dae: &dyn SemiExplicitDae, t0: f64, y0: &[f64]) -> Option<Self> {
        let (dim, nd) = (dae.dim(), dae.differential_dim());
        let mut entries = Vec::with_capacity(7 * dim);
        dae.jacobian_entries(t0, y0, &mut |r, c, _| entries.push((r, c)));
        let m = entries.len();
        entries.extend((0..nd).map(|i| (i, i)));
        // The Jacobian's entries and the differential diagonal, with their
        // CSC positions (bdf's pattern builder).
        let (pattern, slots) = crate::bdf::pattern(dim, &entries)?;
        let row_idx = pattern.row_idx();
        let nnz = row_idx.len();
        Some(Self {
            dim,
            jac_slots: slots[..m].to_vec(),
            diag_slots: slots[m..].to_vec(),
            pattern,
            values: vec![0.0; nnz],
            ctx: FaerContext::default(),
        })
    }

    /// `E - beta J(t, u)`.
    fn assemble(&mut self, dae: &dyn SemiExplicitDae, t: f64, u: &[f64], beta: f64) {
        self.values.fill(0.0);
        for &s in &self.diag_slots {
            self.values[s] = 1.0;
        }
        let (values, slots) = (&mut self.values, &self.jac_slots);
        let mut k = 0;
        dae.jacobian_entries(t, u, &mut |_, _, j| {
            if let Some(&s) = slots.get(k) {
                values[s] -= beta * j;
            }
            k += 1;
        });
    }
}

impl LinearOp for NewtonOp {
    type T = f64;
    type V = FaerVec<f64>;
    type M = FaerSparseMat<f64>;
    type C = FaerContext;
    fn nrows(&self) -> usize {
        self.dim
    }
    fn ncols(&self) -> usize {
        self.dim
    }
    fn context(&self) -> &FaerContext {
        &self.ctx
    }
    fn matrix_inplace(&self, y: &mut FaerSparseMat<f64>) {
        y.inner_mut()[0].val_mut().copy_from_slice(&self.values);
    }
    fn sparsity(&self) -> Option<SymbolicSparseColMat<usize>> {
        Some(self.pattern.clone())
    }
}

/// The weighted RMS norm of `x[..nd]` with weights `atol + rtol |s_i|`.
fn wrms(x: &[f64], scale: &[f64], rtol: f64, atol: f64) -> f64 {
    let nd = scale.len();
    if nd == 0 {
        return 0.0;
    }
    let sum: f64 = x[..nd]
        .iter()
        .zip(scale)
        .map(|(xi, si)| {
            let q = xi / (atol + rtol * si.abs());
            q * q
        })
        .sum();
    (sum / nd as f64).sqrt()
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
    let mut measured: Vec<usize> = problem
        .configuration()
        .into_iter()
        .flatten()
        .filter(|&i| i < nd)
        .collect();
    if measured.is_empty() {
        measured = (0..nd).collect();
    }
    let mut out = Counted::run(problem, |sys| {
        run(sys, dae.as_ref(), full, &measured, s, obs)
    });
    // The loop counts the DAE's residuals into `rhs_evals` too.
    out.stats.rhs_evals += out.stats.newton_iterations;
    out
}

/// The step loop: `sys` (counted) gives the derivatives the observer and
/// the dense output see, `dae` the equations Newton solves; `full` is
/// every unknown at `t0`, consistent.
fn run<S: OdeSystem>(
    sys: &mut S,
    dae: &dyn SemiExplicitDae,
    full: Vec<f64>,
    measured: &[usize],
    span: &Span<'_>,
    obs: &mut dyn Observer,
) -> Outcome {
    let (t0, t_end, set) = (span.t0, span.t_end, span.settings);
    let (dim, nd) = (dae.dim(), dae.differential_dim());
    let mut stats = Stats::default();
    let mut d = span.y0.to_vec();
    if full.len() != dim || d.len() != nd {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, d);
    }
    let Some(mut newton) = NewtonOp::new(dae, t0, &full) else {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, d);
    };
    let log = Rc::new(LuLog::default());
    let mut lu = NewtonLu::choose(dae.blocks(), &newton.pattern, log.clone());
    lu.set_sparsity(&newton);
    let k = Coefficients::of(set.rho_inf);

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
    let mut vacc = f.clone();
    // The previous step's derivatives and size, once there is one.
    let mut v_prev = vec![0.0; nd];
    let mut h_prev: Option<f64> = None;
    let mut z = full[nd..].to_vec();

    // Scratch, allocated once.
    let mut u = vec![0.0; dim];
    let mut res = vec![0.0; dim];
    let mut x = FaerVec::from_vec(vec![0.0; dim], FaerContext::default());
    let (mut d1, mut v1, mut f1) = (vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]);

    // The first step: the explicit heuristic at second order, capped.
    let mut h = match set.h0 {
        Some(h0) => h0.abs(),
        None => {
            let (mut a, mut b) = (vec![0.0; nd], vec![0.0; nd]);
            crate::step_size::initial_step(sys, t0, &d, &f, t_end - t0, set, 2, (&mut a, &mut b))
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
        if landing {
            h = t_end - t;
        }
        let v = &vacc;
        let t_star = t + k.a_f * h;
        let beta = k.a_f * k.gamma * h / k.a_m;
        // `R = (d* - d_n) + beta k1 v_n - beta f(t*, u)` on the differential
        // rows, `-beta g(t*, u)` on the algebraic ones.
        let k1 = (1.0 - k.a_m) - k.a_m * (1.0 - k.gamma) / k.gamma;
        for i in 0..nd {
            u[i] = d[i] + k.a_f * h * v[i];
        }
        u[nd..].copy_from_slice(&z);
        newton.assemble(dae, t_star, &u, beta);
        stats.jacobian_evals += 1;
        lu.set_linearisation(&newton);
        stats.lu_factorizations += 1;
        let mut converged = !log.last_failed.get();
        let mut prev_norm = f64::INFINITY;
        let tol = (10.0 * f64::EPSILON / set.rtol).max(set.rtol.sqrt().min(0.03));
        let mut iter = 0;
        let mut refreshes = 0;
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
                xs[i] = (u[i] - d[i]) + beta * (k1 * v[i] - res[i]);
            }
            for i in nd..dim {
                xs[i] = -beta * res[i];
            }
            if lu.solve_in_place(&mut x).is_err() {
                converged = false;
                break;
            }
            let dx = slice(&x);
            let norm = wrms(dx, &d, set.rtol, set.atol);
            if !norm.is_finite() {
                converged = false;
                break;
            }
            let theta = norm / prev_norm;
            if theta >= SLOW && norm > 1e-3 * tol {
                // Slow or diverging with the Jacobian of an earlier iterate:
                // refresh it here (without taking the correction), at most
                // REFRESHES times an attempt; then the attempt fails.
                if refreshes == REFRESHES {
                    converged = false;
                    break;
                }
                refreshes += 1;
                newton.assemble(dae, t_star, &u, beta);
                stats.jacobian_evals += 1;
                lu.set_linearisation(&newton);
                stats.lu_factorizations += 1;
                converged = !log.last_failed.get();
                prev_norm = f64::INFINITY;
                continue;
            }
            for i in 0..dim {
                u[i] -= dx[i];
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
            h *= NEWTON_SHRINK;
            continue;
        }
        // The step's end and the method's derivatives there.
        for i in 0..nd {
            d1[i] = (u[i] - (1.0 - k.a_f) * d[i]) / k.a_f;
            v1[i] = (d1[i] - d[i] - h * (1.0 - k.gamma) * v[i]) / (h * k.gamma);
        }
        // The local error: |C_3| h^3 d''' from the derivatives' second
        // divided difference (the first step: the first-order term
        // h^2 d'' / 2, an overestimate), filtered by the Newton matrix.
        let xs = slice_mut(&mut x);
        match h_prev {
            Some(hp) => {
                let c = k.c3.abs() * h * h * h * 2.0 / (h + hp);
                for i in 0..nd {
                    xs[i] = c * ((v1[i] - v[i]) / h - (v[i] - v_prev[i]) / hp);
                }
            }
            None => {
                for i in 0..nd {
                    xs[i] = 0.5 * h * (v1[i] - v[i]);
                }
            }
        }
        xs[nd..].fill(0.0);
        let filtered = lu.solve_in_place(&mut x).is_ok();
        let e = slice(&x);
        let mut sum = 0.0;
        for &i in measured {
            let q = e[i] / (set.atol + set.rtol * d[i].abs().max(d1[i].abs()));
            sum += q * q;
        }
        let err = if filtered && !measured.is_empty() {
            (sum / measured.len() as f64).sqrt()
        } else {
            f64::INFINITY
        };
        if !err.is_finite() || err > 1.0 {
            stats.rejected_steps += 1;
            stats.error_test_failures += 1;
            let shrink = if err.is_finite() {
                (SAFETY * err.powf(-1.0 / 3.0)).max(SHRINK_MIN)
            } else {
                SHRINK_MIN
            };
            h *= shrink;
            continue;
        }
        let t1 = if landing { t_end } else { t + h };
        sys.rhs(t1, &d1, &mut f1);
        if !all_finite(&d1) || !all_finite(&f1) {
            // The step's end left the domain of `f`: retried smaller, as a
            // failed solve; a run that cannot get past it ends at the floor.
            stats.rejected_steps += 1;
            stats.newton_failures += 1;
            h *= NEWTON_SHRINK;
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
            interpolant: &Linear {
                t0: t,
                h: t1 - t,
                y0: &d,
                y1: &d1,
            },
        });
        let v_acc = &mut vacc;
        std::mem::swap(&mut v_prev, v_acc);
        std::mem::swap(v_acc, &mut v1);
        std::mem::swap(&mut d, &mut d1);
        std::mem::swap(&mut f, &mut f1);
        z.copy_from_slice(&u[nd..]);
        h_prev = Some(h);
        t = t1;
        saw_nonfinite = false;
        let grow = if err > 0.0 {
            (SAFETY * err.powf(-1.0 / 3.0)).min(GROW_MAX)
        } else {
            GROW_MAX
        };
        // A step grows only by a factor worth it: each change of `h`
        // shifts the derivative sequence of the modes the step damps.
        if !(1.0..GROW_MIN).contains(&grow) {
            h *= grow;
        }
    }
    Outcome::ended(Status::Ok, t, None, stats, d)
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

/// The dense output: linear between a step's ends. A derivative-based
/// interpolant (the cubic Hermite of the explicit methods) would carry the
/// derivatives of the modes the step damps without resolving them (at
/// `EA = 1e8` it put the snap's largest tip speed 9% high); the state at
/// the step ends is the method's, of second order.
struct Linear<'a> {
    t0: f64,
    h: f64,
    y0: &'a [f64],
    y1: &'a [f64],
}

impl Interpolant for Linear<'_> {
    fn eval(&self, t: f64, out: &mut [f64]) {
        let s = (t - self.t0) / self.h;
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.y0[i] + s * (self.y1[i] - self.y0[i]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::{Settings, TimeScales};
    use crate::testing::Quiet;

    /// Damped linear oscillators `x_k'' + 2 zeta_k w_k x_k' + w_k^2 x_k = 0`
    /// (or, with `mu`, van der Pol's `x'' = mu (1 - x^2) x' - x`), as a
    /// problem with the state `[x_1, v_1, x_2, v_2, ..]` and a banded DAE
    /// whose algebraic unknowns are the accelerations.
    #[derive(Clone)]
    struct Oscillators {
        modes: Vec<(f64, f64)>,
        mu: Option<f64>,
    }

    impl Oscillators {
        fn accel(&self, k: usize, x: f64, v: f64) -> f64 {
            match self.mu {
                Some(mu) => mu * (1.0 - x * x) * v - x,
                None => {
                    let (w, z) = self.modes[k];
                    -2.0 * z * w * v - w * w * x
                }
            }
        }
    }

    impl OdeSystem for Oscillators {
        fn dim(&self) -> usize {
            2 * self.modes.len()
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            for k in 0..self.modes.len() {
                dy[2 * k] = y[2 * k + 1];
                dy[2 * k + 1] = self.accel(k, y[2 * k], y[2 * k + 1]);
            }
        }
        fn jvp(&mut self, _t: f64, _y: &[f64], _v: &[f64], jv: &mut [f64]) {
            jv.fill(0.0);
        }
    }

    struct OscillatorsDae(Oscillators);

    impl SemiExplicitDae for OscillatorsDae {
        fn dim(&self) -> usize {
            3 * self.0.modes.len()
        }
        fn differential_dim(&self) -> usize {
            2 * self.0.modes.len()
        }
        fn rhs(&self, _t: f64, y: &[f64], out: &mut [f64]) {
            let m = self.0.modes.len();
            for k in 0..m {
                let (x, v, a) = (y[2 * k], y[2 * k + 1], y[2 * m + k]);
                out[2 * k] = v;
                out[2 * k + 1] = a;
                out[2 * m + k] = a - self.0.accel(k, x, v);
            }
        }
        fn jacobian_entries(&self, _t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
            let m = self.0.modes.len();
            for k in 0..m {
                let (x, v) = (y[2 * k], y[2 * k + 1]);
                let (dx, dv) = match self.0.mu {
                    Some(mu) => (2.0 * mu * x * v + 1.0, -mu * (1.0 - x * x)),
                    None => {
                        let (w, z) = self.0.modes[k];
                        (w * w, 2.0 * z * w)
                    }
                };
                emit(2 * k, 2 * k + 1, 1.0);
                emit(2 * k + 1, 2 * m + k, 1.0);
                emit(2 * m + k, 2 * m + k, 1.0);
                emit(2 * m + k, 2 * k, dx);
                emit(2 * m + k, 2 * k + 1, dv);
            }
        }
    }

    impl Problem for Oscillators {
        fn banded_dae(&self, t0: f64, y0: &[f64]) -> Option<BandedDae> {
            let m = self.modes.len();
            let mut full = y0.to_vec();
            let mut f = vec![0.0; 2 * m];
            self.clone().rhs(t0, y0, &mut f);
            full.extend((0..m).map(|k| f[2 * k + 1]));
            Some(BandedDae {
                dae: Box::new(OscillatorsDae(self.clone())),
                y0: full,
            })
        }
        fn configuration(&self) -> Vec<std::ops::Range<usize>> {
            (0..self.modes.len()).map(|k| 2 * k..2 * k + 1).collect()
        }
    }

    fn settings(rtol: f64) -> Settings {
        Settings {
            dt: 0.01,
            rtol,
            atol: rtol * 1e-2,
            h_min: 0.0,
            max_steps: 10_000_000,
            h0: None,
            scales: TimeScales::NONE,
            rho_inf: crate::DEFAULT_RHO_INF,
        }
    }

    fn run(p: &mut Oscillators, y0: &[f64], t_end: f64, s: &Settings) -> Outcome {
        integrate(
            p,
            &Span {
                t0: 0.0,
                y0,
                t_end,
                settings: s,
            },
            &mut Quiet,
        )
    }

    /// The scheme's coefficients: second order (`gamma = 1/2 + a_m - a_f`),
    /// and the roots of the two-step method at `h lambda -> infinity` (of
    /// `sigma`) are `-rho`; at `rho = 1` it is the trapezoidal rule, whose
    /// error constant is `-1/12`.
    #[test]
    fn the_coefficients_are_second_order_with_the_spectral_radius_rho() {
        for rho in [0.0, 0.3, 0.6, 0.9, 1.0] {
            let k = Coefficients::of(rho);
            assert!((k.gamma - (0.5 + k.a_m - k.a_f)).abs() < 1e-15);
            assert!((-(1.0 - k.gamma) / k.gamma + rho).abs() < 1e-12, "{rho}");
            assert!((-(1.0 - k.a_f) / k.a_f + rho).abs() < 1e-12, "{rho}");
        }
        assert!((Coefficients::of(1.0).c3 + 1.0 / 12.0).abs() < 1e-15);
    }

    /// On `x'' = -x` the error at `t = 10` falls at second order in the
    /// steps (the log-log slope between rtol 1e-4 and 1e-8 is -2 to within
    /// 0.3), and it tracks the tolerance as a second-order method with
    /// local error control should (`err ~ rtol^(2/3)`, within a factor 10
    /// over four decades): an estimate of the wrong order or constant, or
    /// one that does not see the error, fails one of them.
    #[test]
    fn the_error_is_second_order_and_tracks_the_tolerance() {
        let mut p = Oscillators {
            modes: vec![(1.0, 0.0)],
            mu: None,
        };
        let exact = [10f64.cos(), -10f64.sin()];
        let mut pts = vec![];
        for rtol in [1e-4, 1e-5, 1e-6, 1e-7, 1e-8] {
            let out = run(&mut p, &[1.0, 0.0], 10.0, &settings(rtol));
            assert_eq!(out.status, Status::Ok);
            let e = (out.y_end[0] - exact[0]).hypot(out.y_end[1] - exact[1]);
            pts.push((rtol, out.stats.steps as f64, e));
        }
        let (first, last) = (pts[0], pts[pts.len() - 1]);
        let slope = (last.2 / first.2).ln() / (last.1 / first.1).ln();
        assert!((slope + 2.0).abs() < 0.3, "slope {slope}: {pts:?}");
        let c: Vec<f64> = pts.iter().map(|p| p.2 / p.0.powf(2.0 / 3.0)).collect();
        let (lo, hi) = c
            .iter()
            .fold((f64::MAX, 0.0f64), |a, &x| (a.0.min(x), a.1.max(x)));
        assert!(hi / lo < 10.0, "{c:?}");
    }

    /// A slow mode beside a stiff, lightly damped one (`w = 1e5`, 1%
    /// damping, excited at the start): the stiff mode is damped instead of
    /// followed (following it would take some 3e5 steps to `t = 10`): the
    /// run takes less than a twentieth of that (6,224 steps when written,
    /// against 779 for the slow mode alone: the stiff transient's position
    /// is in the error norm until it is damped below the tolerance), the
    /// slow one is accurate, and the stiff one is gone.
    #[test]
    fn a_stiff_mode_is_stepped_over_and_the_slow_one_kept() {
        let mut p = Oscillators {
            modes: vec![(1.0, 0.0), (1e5, 0.01)],
            mu: None,
        };
        let out = run(&mut p, &[1.0, 0.0, 1e-3, 0.0], 10.0, &settings(1e-6));
        assert_eq!(out.status, Status::Ok);
        // Following the mode: about `w t / pi` steps at least.
        let follow = 1e5 * 10.0 / std::f64::consts::PI;
        assert!((out.stats.steps as f64) < follow / 20.0, "{:?}", out.stats);
        let e = (out.y_end[0] - 10f64.cos()).hypot(out.y_end[1] + 10f64.sin());
        // 3.2e-4 when written: the transient's many step changes cost the
        // slow mode accuracy (alone it ends within 2e-5 at this rtol).
        assert!(e < 1e-3, "{e:e}");
        assert!(out.y_end[2].abs() < 1e-9, "{:?}", out.y_end);
    }

    /// A first step far too large for Newton on stiff van der Pol
    /// (`mu = 1000`) is retried smaller, never accepted: the run counts its
    /// Newton failures and still lands on the same state as a run with a
    /// fine start, to the tolerance.
    #[test]
    fn a_step_whose_newton_fails_is_retried_smaller() {
        let mut p = Oscillators {
            modes: vec![(1.0, 0.0)],
            mu: Some(1000.0),
        };
        let y0 = [2.0, 0.0];
        let fine = run(&mut p, &y0, 500.0, &settings(1e-8));
        let big = Settings {
            h0: Some(400.0),
            ..settings(1e-6)
        };
        let out = run(&mut p, &y0, 500.0, &big);
        assert_eq!((fine.status, out.status), (Status::Ok, Status::Ok));
        assert!(out.stats.newton_failures > 0, "{:?}", out.stats);
        assert_eq!(
            out.stats.rejected_steps,
            out.stats.newton_failures + out.stats.error_test_failures
        );
        assert!(
            (out.y_end[0] - fine.y_end[0]).abs() < 1e-3,
            "{:?} {:?}",
            out.y_end,
            fine.y_end
        );
    }
}
