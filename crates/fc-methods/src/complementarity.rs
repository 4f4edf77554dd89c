//! One step's contact problem, solved on the chain's band: the impulses
//! `P` of the rows of a [`Nonsmooth`](crate::Nonsmooth) problem such that
//! the velocities `u = W P + b` (`W = J M⁻¹ Jᵀ`, the Delassus matrix, block
//! tridiagonal; `b` the rows' velocities without the impulses, less their
//! targets) satisfy every row's law: a bilateral row `u = 0`; a normal row
//! `0 <= P ⊥ u >= 0`; a tangent row Coulomb's `|P_T| <= mu P_N`, `u_T = 0`
//! below the bound and `P_T = −mu P_N sign(u_T)` at it.
//!
//! **Method.** A semismooth Newton iteration on the Alart–Curnier
//! function (Alart & Curnier 1991; the form Siconos' `fc2d` Newton solvers
//! use), with the row scales `r_i = 1 / W_ii`:
//!
//! ```text
//! bilateral   Φ = r u
//! normal      Φ = P − max(0, P − r u)              (= min(P, r u))
//! tangent     Φ = P − proj[−mu P_N, mu P_N](P − r u)
//! ```
//!
//! `Φ = 0` is exactly the rows' laws. Its generalised Jacobian has, row by
//! row, either the row of `r W` (a bilateral row, a normal row pressing, a
//! tangent row sticking), a unit row (a normal row leaving, `P = 0`), or
//! `e_T ∓ mu e_N` (a tangent row sliding): block tridiagonal like `W`, so
//! each Newton iteration is one block-tridiagonal factorisation and solve,
//! O(n) ([`DenseTridiagonal`]). The iteration is globalised by a
//! backtracking line search on `|Φ|²` (Armijo, halving, at most
//! [`LINE_SEARCH`] times).
//!
//! **Degenerate contact.** `W` is singular where the rows are dependent
//! (a rod whose two ends both stick; two contacts on one point): the
//! impulses are then not unique, though the velocities are. The Newton
//! matrix takes `W + ε diag(W)` (`ε` = [`PROXIMAL`]) in the rows of `W`,
//! a proximal regularisation: each iteration moves `P` least along the
//! directions `W` does not see, and the fixed point is still `Φ = 0`
//! exactly (the regularisation is in the step, not in the equations), so
//! a plastic impact is exact to rounding once the contacts that press are
//! found. Rows whose `W_ii` is zero (a row that touches no mass) take no
//! impulse.

use crate::block_lu::DenseTridiagonal;

/// `Σ a_c m_c b_c`.
fn weighted(a: &[f64], m: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(m).zip(b).map(|((a, m), b)| a * m * b).sum()
}
use crate::nonsmooth::{Row, RowKind, MAX_BODY};

/// The regularisation `ε` of the rows of `W` in the Newton matrix
/// (relative to each row's diagonal): small enough that the iteration
/// contracts by `ε / (λ + ε)` on the smallest eigenvalues `λ ~ 1 / n²` of
/// a chain's joints (`2.5e-6` at `n = 640`), large enough to keep the
/// factorisation of a singular `W` (every rod sticking) finite.
pub const PROXIMAL: f64 = 1e-9;

/// The most halvings of a Newton step in its line search.
pub const LINE_SEARCH: usize = 30;

/// The most Newton iterations of one solve.
pub const MAX_ITERATIONS: usize = 100;

/// The residual, relative to the largest `|b|`, at which a solve stops:
/// the rows' laws hold to rounding.
pub const RELATIVE_TOLERANCE: f64 = 1e-14;

/// The residual, relative to the largest `|b|`, below which a solve that
/// stops improving (rounding) has converged.
pub const ROUNDING: f64 = 1e-10;

/// How one solve went.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solved {
    /// Newton iterations (factorisations).
    pub iterations: u64,
    /// The largest violation of a row's law at the end, in the rows'
    /// velocity units: `|Φ_i| W_ii` (for a bilateral or pressing row, its
    /// velocity `|u_i|`; for a row that must not push, its impulse times
    /// `W_ii`).
    pub residual: f64,
    /// Whether it met [`RELATIVE_TOLERANCE`] (or stalled below
    /// [`ROUNDING`]).
    pub converged: bool,
}

/// What a row's Newton equation is at the present iterate.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Equation {
    /// `P_i = 0`: the unit row.
    Unit,
    /// The row of `r W`: a bilateral row, a pressing normal row, a
    /// sticking tangent row.
    Delassus,
    /// `P_T ∓ mu P_N = 0` (`sign` the slip's, `mu`).
    Slide(f64, f64),
}

/// The contact problem of one chain of `blocks` blocks of `size` rows on
/// `bodies` bodies of `body_dim` coordinates, with its scratch (allocated
/// once per run).
pub struct Complementarity {
    blocks: usize,
    size: usize,
    body_dim: usize,
    minv: Vec<f64>,
    /// `[W_{k,k−1} | W_kk | W_{k,k+1}]` per block (`S x S`, row-major).
    w: Vec<f64>,
    newton: DenseTridiagonal,
    /// The impulses (the warm start of the next solve).
    pub impulses: Vec<f64>,
    u: Vec<f64>,
    phi: Vec<f64>,
    step: Vec<f64>,
    trial: Vec<f64>,
    u_trial: Vec<f64>,
    diag: Vec<f64>,
    equations: Vec<Equation>,
}

impl Complementarity {
    /// The solver for `bodies` bodies of `body_dim` coordinates with the
    /// inverse masses `minv`, and `size` rows per block.
    pub fn new(bodies: usize, body_dim: usize, size: usize, minv: Vec<f64>) -> Self {
        let blocks = bodies + 1;
        let rows = blocks * size;
        Self {
            blocks,
            size,
            body_dim,
            minv,
            w: vec![0.0; 3 * size * size * blocks],
            newton: DenseTridiagonal::new(size, blocks),
            impulses: vec![0.0; rows],
            u: vec![0.0; rows],
            phi: vec![0.0; rows],
            step: vec![0.0; rows],
            trial: vec![0.0; rows],
            u_trial: vec![0.0; rows],
            diag: vec![0.0; rows],
            equations: vec![Equation::Unit; rows],
        }
    }

    /// The entries of body `body` (if it exists) of `row`'s half `half`
    /// (0: body `k − 1`, 1: body `k`).
    fn body_of(&self, k: usize, half: usize) -> Option<usize> {
        let body = (k + half).checked_sub(1)?;
        (body + 1 < self.blocks).then_some(body)
    }

    /// `W = J M⁻¹ Jᵀ` for `rows` (their kinds aside: every row's `jac`).
    pub fn delassus(&mut self, rows: &[Row]) {
        let (s, b) = (self.size, self.body_dim);
        let ss = s * s;
        self.w.fill(0.0);
        for k in 0..self.blocks {
            let here = &rows[k * s..(k + 1) * s];
            // W_kk over bodies k − 1 and k.
            for half in 0..2 {
                let Some(body) = self.body_of(k, half) else {
                    continue;
                };
                let m = &self.minv[body * b..(body + 1) * b];
                let at = half * MAX_BODY;
                for (i, ri) in here.iter().enumerate() {
                    for (j, rj) in here.iter().enumerate() {
                        self.w[3 * ss * k + ss + i * s + j] +=
                            weighted(&ri.jac[at..at + b], m, &rj.jac[at..at + b]);
                    }
                }
            }
            // W_{k,k+1} over body k, and its transpose W_{k+1,k}.
            if k + 1 < self.blocks {
                let Some(body) = self.body_of(k, 1) else {
                    continue;
                };
                let next = &rows[(k + 1) * s..(k + 2) * s];
                let m = &self.minv[body * b..(body + 1) * b];
                for (i, ri) in here.iter().enumerate() {
                    for (j, rj) in next.iter().enumerate() {
                        let acc = weighted(&ri.jac[MAX_BODY..MAX_BODY + b], m, &rj.jac[..b]);
                        self.w[3 * ss * k + 2 * ss + i * s + j] = acc;
                        self.w[3 * ss * (k + 1) + j * s + i] = acc;
                    }
                }
            }
        }
    }

    /// `out = J v` for `rows`.
    pub fn velocities(&self, rows: &[Row], v: &[f64], out: &mut [f64]) {
        let (s, b) = (self.size, self.body_dim);
        for (g, (row, o)) in rows.iter().zip(out.iter_mut()).enumerate() {
            let k = g / s;
            let mut acc = 0.0;
            for half in 0..2 {
                if let Some(body) = self.body_of(k, half) {
                    for c in 0..b {
                        acc += row.jac[half * MAX_BODY + c] * v[body * b + c];
                    }
                }
            }
            *o = acc;
        }
    }

    /// `dv += M⁻¹ Jᵀ p` for `rows`.
    pub fn add_impulses(&self, rows: &[Row], p: &[f64], dv: &mut [f64]) {
        let (s, b) = (self.size, self.body_dim);
        for (g, (row, &pg)) in rows.iter().zip(p).enumerate() {
            if pg == 0.0 {
                continue;
            }
            let k = g / s;
            for half in 0..2 {
                if let Some(body) = self.body_of(k, half) {
                    for c in 0..b {
                        let i = body * b + c;
                        dv[i] += self.minv[i] * row.jac[half * MAX_BODY + c] * pg;
                    }
                }
            }
        }
    }

    /// `out = W p + bias`.
    fn apply(&self, p: &[f64], bias: &[f64], out: &mut [f64]) {
        let s = self.size;
        let ss = s * s;
        for k in 0..self.blocks {
            let blk = &self.w[3 * ss * k..3 * ss * (k + 1)];
            for i in 0..s {
                let g = k * s + i;
                let mut acc = bias[g];
                for (part, kk) in [(0usize, k.wrapping_sub(1)), (1, k), (2, k + 1)] {
                    if kk < self.blocks {
                        for j in 0..s {
                            acc += blk[part * ss + i * s + j] * p[kk * s + j];
                        }
                    }
                }
                out[g] = acc;
            }
        }
    }

    /// Solves the rows' laws for the impulses (warm-started from
    /// [`Complementarity::impulses`], which hold the answer), with
    /// `u = W P + bias` and the rows' `kinds` (after
    /// [`Complementarity::delassus`] of the same rows).
    pub fn solve(&mut self, kinds: &[RowKind], bias: &[f64]) -> Solved {
        let (s, ss) = (self.size, self.size * self.size);
        let mut diag = std::mem::take(&mut self.diag);
        for (g, d) in diag.iter_mut().enumerate() {
            *d = self.w[3 * ss * (g / s) + ss + (g % s) * (s + 1)];
        }
        for (p, kind) in self.impulses.iter_mut().zip(kinds) {
            if *kind == RowKind::Off {
                *p = 0.0;
            }
        }
        let scale = bias
            .iter()
            .zip(kinds)
            .filter(|(_, k)| **k != RowKind::Off)
            .fold(0.0f64, |a, (b, _)| a.max(b.abs()));
        let tolerance = RELATIVE_TOLERANCE * scale;
        let mut p = std::mem::take(&mut self.impulses);
        let mut u = std::mem::take(&mut self.u);
        self.apply(&p, bias, &mut u);
        let laws = Laws {
            kinds,
            diag: &diag,
            size: s,
        };
        let (mut merit, mut worst) =
            laws.residual(&p, &u, Some((&mut self.phi, &mut self.equations)));
        let mut iterations = 0u64;
        let mut converged = false;
        let mut last_worst = f64::INFINITY;
        while iterations < MAX_ITERATIONS as u64 {
            if worst <= tolerance || (worst <= ROUNDING * scale && worst >= 0.5 * last_worst) {
                converged = true;
                break;
            }
            last_worst = worst;
            self.assemble(&diag);
            iterations += 1;
            if !self.newton.factorise() {
                break;
            }
            for (d, f) in self.step.iter_mut().zip(&self.phi) {
                *d = -f;
            }
            if !self.newton.solve(&mut self.step) {
                break;
            }
            // Backtracking on |Φ|²; without a decrease along the Newton
            // direction (a kink of Φ), the full step, as the semismooth
            // iteration takes it.
            let mut alpha = 1.0;
            let mut decreased = false;
            for _ in 0..LINE_SEARCH {
                for ((t, &pg), &d) in self.trial.iter_mut().zip(&p).zip(&self.step) {
                    *t = pg + alpha * d;
                }
                let mut ut = std::mem::take(&mut self.u_trial);
                self.apply(&self.trial, bias, &mut ut);
                let (m, _) = laws.residual(&self.trial, &ut, None);
                self.u_trial = ut;
                if m <= (1.0 - 1e-4 * alpha) * merit {
                    decreased = true;
                    break;
                }
                alpha *= 0.5;
            }
            if !decreased {
                alpha = 1.0;
            }
            for (pg, &d) in p.iter_mut().zip(&self.step) {
                *pg += alpha * d;
            }
            self.apply(&p, bias, &mut u);
            (merit, worst) = laws.residual(&p, &u, Some((&mut self.phi, &mut self.equations)));
            if !merit.is_finite() {
                break;
            }
        }
        self.impulses = p;
        self.u = u;
        self.diag = diag;
        Solved {
            iterations,
            residual: worst,
            converged,
        }
    }

    /// The Newton matrix of the present equations, block by block.
    fn assemble(&mut self, diag: &[f64]) {
        let (s, ss) = (self.size, self.size * self.size);
        let a = &mut self.newton.assembled;
        a.fill(0.0);
        for (g, &d) in diag.iter().enumerate() {
            let (k, i) = (g / s, g % s);
            let base = 3 * ss * k;
            let diag = base + ss + i * s + i;
            match self.equations[g] {
                Equation::Unit => a[diag] = 1.0,
                Equation::Slide(sign, mu) => {
                    a[diag] = 1.0;
                    a[diag - 1] = -sign * mu;
                }
                Equation::Delassus => {
                    let r = 1.0 / d;
                    for part in 0..3 {
                        for j in 0..s {
                            let at = base + part * ss + i * s + j;
                            a[at] = r * self.w[at];
                        }
                    }
                    a[diag] += PROXIMAL;
                }
            }
        }
    }
}

/// The rows' laws, as the residual `Φ` reads them.
struct Laws<'a> {
    kinds: &'a [RowKind],
    /// `W_ii` per row.
    diag: &'a [f64],
    size: usize,
}

impl Laws<'_> {
    /// `Φ` at the impulses `p` with the velocities `u = W p + bias`:
    /// `|Φ|²` and the largest `|Φ_i| W_ii`; into `out` (if given) `Φ` and
    /// each row's Newton equation.
    fn residual(
        &self,
        p: &[f64],
        u: &[f64],
        mut out: Option<(&mut [f64], &mut [Equation])>,
    ) -> (f64, f64) {
        let (mut sum, mut worst) = (0.0, 0.0f64);
        for (g, &kind) in self.kinds.iter().enumerate() {
            let d = self.diag[g];
            let (phi, eq) = if d.is_nan() || d <= 0.0 {
                (p[g], Equation::Unit)
            } else {
                let ru = u[g] / d;
                match kind {
                    RowKind::Off => (p[g], Equation::Unit),
                    RowKind::Bilateral => (ru, Equation::Delassus),
                    RowKind::Normal { .. } => {
                        if p[g] - ru > 0.0 {
                            (ru, Equation::Delassus)
                        } else {
                            (p[g], Equation::Unit)
                        }
                    }
                    RowKind::Tangent { friction } => {
                        let normal = if g % self.size > 0 { p[g - 1] } else { 0.0 };
                        let bound = friction * normal.max(0.0);
                        let z = p[g] - ru;
                        if bound.is_nan() || bound <= 0.0 {
                            (p[g], Equation::Unit)
                        } else if z.abs() < bound {
                            (ru, Equation::Delassus)
                        } else {
                            let sign = z.signum();
                            (p[g] - sign * bound, Equation::Slide(sign, friction))
                        }
                    }
                }
            };
            if let Some((phis, eqs)) = out.as_mut() {
                phis[g] = phi;
                eqs[g] = eq;
            }
            sum += phi * phi;
            worst = worst.max(phi.abs() * if d > 0.0 { d } else { 1.0 });
        }
        (sum, worst)
    }
}
