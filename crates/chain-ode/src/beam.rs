//! BEAM: the one external stiff benchmark of the study, a problem that is
//! itself a chain.
//!
//! The motion of an elastic, inextensible thin beam clamped at one end and
//! pushed at the free end, discretised into `n = 40` rigid segments joined
//! by angular springs, in angle coordinates (Hairer & Wanner, *Solving
//! Ordinary Differential Equations II*, §IV.1 and §IV.10; the problem
//! BEAM of the IVP test set of Mazzia & Magherini, University of Bari,
//! release 2.4, whose statement this module follows). With `z = theta`
//! (the `n` segment angles, rad, in the problem's own dimensionless time):
//!
//! ```text
//! z'' = C(z) v + D(z) u,        C(z) u = D(z) v + (z'_1^2, ..., z'_n^2)
//! v_l = n^4 (z_{l-1} - 2 z_l + z_{l+1}) + n^2 (F_y cos z_l - F_x sin z_l),
//!       z_0 = -z_1,  z_{n+1} = z_n,
//! C: tridiagonal, C_11 = 1, C_nn = 3, C_ll = 2 otherwise,
//!    C_{l,l+-1} = -cos(z_l - z_{l+-1});
//! D: zero diagonal, D_{l,l+-1} = -sin(z_l - z_{l+-1});
//! F_x = -phi(t), F_y = phi(t), phi(t) = 1.5 sin^2 t for t <= pi, 0 after.
//! ```
//!
//! It starts at rest and straight (`z = z' = 0`) and runs to `t = 5`. The
//! state is `y = [z_1..z_n, z'_1..z'_n]` (80 unknowns; `y1`, `y40`, `y41`,
//! `y80` in the test set's 1-based numbering are the clamped and the free
//! segment's angle and rate).
//!
//! Two forms, one set of equations:
//! * [`BeamSystem`], the explicit ODE `y' = f(t, y)` (O(n): one tridiagonal
//!   solve per evaluation) with its exact Jacobian-vector product by dual
//!   numbers, for RK4, DOPRI5, DOP853 and `bdf-dense`;
//! * [`BeamDae`], the same problem as a banded index-1 DAE for the sparse
//!   `bdf`: `u` and `v` become algebraic unknowns (`0 = C u - D v - z'^2`,
//!   `0 = v - n^4 (...) - n^2 (...)`), so that every equation couples a
//!   segment to its two neighbours only, and the unknowns group segment by
//!   segment into blocks of four (`z_l, z'_l, u_l, v_l`): the Newton
//!   matrices are block tridiagonal, as the chain's are. Its algebraic
//!   block `[[C, -D], [0, I]]` is nonsingular (`C` is symmetric positive
//!   definite: it is `Re(E G E*)` with `E = diag(exp(i z))` and `G` the
//!   positive definite `C` at `z = 0`), so the index is 1.

use crate::scalar::{Dual, Scalar};
use fc_methods::{BandedDae, OdeSystem, Problem, SemiExplicitDae};

/// Segments of the test set's beam.
pub const SEGMENTS: usize = 40;

/// The end of the test set's interval `[0, 5]`.
pub const T_END: f64 = 5.0;

/// The test set's reference solution at `t = 5` in the four components it
/// prints, `(1-based index, value)`: `y1` and `y40` (the angles of the
/// clamped and the free segment, rad) and `y41`, `y80` (their rates). From
/// the BEAM problem of the IVP test set (Mazzia & Magherini, Test Set for
/// IVP Solvers, University of Bari, release 2.4: the reference solution
/// of the problem BEAM, given there to 16 digits). Our own DOP853 run at
/// rtol = atol = 1e-12 agrees with every value to 1.3e-9 or better (the
/// test `dop853_at_tight_tolerance_reproduces_the_reference`).
pub const REFERENCE: [(usize, f64); 4] = [
    (1, -5.792_366_591_285_007e-3),
    (40, -1.767_201_761_075_488e-1),
    (41, 3.747_362_681_329_794e-2),
    (80, 1.186_724_615_113_034),
];

/// The end load's magnitude `phi(t)`: `1.5 sin^2 t` up to `t = pi`, then 0
/// (`F_x = -phi`, `F_y = phi`).
pub fn load(t: f64) -> f64 {
    if t <= std::f64::consts::PI {
        1.5 * t.sin().powi(2)
    } else {
        0.0
    }
}

/// `C_ll`: 1 at the clamped end, 3 at the free end, 2 between.
fn c_diag(l: usize, n: usize) -> f64 {
    if l == 0 {
        1.0
    } else if l + 1 == n {
        3.0
    } else {
        2.0
    }
}

/// The second difference `z_{l-1} - 2 z_l + z_{l+1}` with `z_0 = -z_1`
/// and `z_{n+1} = z_n` (0-based `l`), as a function of the angles.
fn second_difference<S: Scalar>(z: impl Fn(usize) -> S, l: usize, n: usize) -> S {
    if n == 1 {
        // z_0 = -z_1 and z_2 = z_1.
        z(0) * (-2.0)
    } else if l == 0 {
        z(1) - z(0) * 3.0
    } else if l + 1 == n {
        z(l - 1) - z(l)
    } else {
        z(l - 1) - z(l) * 2.0 + z(l + 1)
    }
}

/// `v_l` of segment `l` (0-based) at time `t` (the spring torques and the
/// load), as a function of the angles.
fn v_of<S: Scalar>(t: f64, z: impl Fn(usize) -> S, l: usize, n: usize) -> S {
    let n2 = (n * n) as f64;
    let (s, c) = z(l).sin_cos();
    second_difference(&z, l, n) * (n2 * n2) + (c + s) * (n2 * load(t))
}

/// Buffers of one evaluation of the explicit form, for scalars `S`.
#[derive(Clone, Debug)]
struct Work<S> {
    z: Vec<S>,
    w: Vec<S>,
    v: Vec<S>,
    u: Vec<S>,
    /// `(sin, cos)` of `z_l - z_{l+1}`.
    sc: Vec<(S, S)>,
    /// The Thomas algorithm's modified diagonal.
    diag: Vec<S>,
    acc: Vec<S>,
}

impl<S: Scalar + Default> Work<S> {
    fn new(n: usize) -> Self {
        let z = vec![S::default(); n];
        Self {
            w: z.clone(),
            v: z.clone(),
            u: z.clone(),
            sc: vec![(S::default(), S::default()); n],
            diag: z.clone(),
            acc: z.clone(),
            z,
        }
    }

    /// From `self.z`, `self.w` at `t`: `self.v`, `self.u` (the solution of
    /// `C u = D v + w^2`, by the Thomas algorithm, stable because `C` is
    /// symmetric positive definite) and `self.acc = C v + D u`. O(n), no
    /// allocation.
    fn evaluate(&mut self, t: f64) {
        let n = self.z.len();
        for l in 0..n {
            self.v[l] = v_of(t, |k| self.z[k], l, n);
        }
        for l in 0..n.saturating_sub(1) {
            self.sc[l] = (self.z[l] - self.z[l + 1]).sin_cos();
        }
        // sc[l] = (sin, cos)(z_l - z_{l+1}): D_{l,l+1} = -sin, D_{l+1,l} = +sin,
        // C_{l,l+1} = C_{l+1,l} = -cos.
        for l in 0..n {
            let mut g = self.w[l] * self.w[l];
            if l + 1 < n {
                g -= self.sc[l].0 * self.v[l + 1];
            }
            if l > 0 {
                g += self.sc[l - 1].0 * self.v[l - 1];
            }
            self.u[l] = g;
        }
        // Forward elimination on C (off-diagonal e_l = -cos between l, l+1).
        self.diag[0] = S::cst(c_diag(0, n));
        for l in 1..n {
            let e = -self.sc[l - 1].1;
            let q = e / self.diag[l - 1];
            self.diag[l] = S::cst(c_diag(l, n)) - q * e;
            let prev = self.u[l - 1];
            self.u[l] -= q * prev;
        }
        self.u[n - 1] = self.u[n - 1] / self.diag[n - 1];
        for l in (0..n - 1).rev() {
            let e = -self.sc[l].1;
            let next = self.u[l + 1];
            self.u[l] = (self.u[l] - e * next) / self.diag[l];
        }
        for l in 0..n {
            let mut a = self.v[l] * c_diag(l, n);
            if l + 1 < n {
                let (s, c) = self.sc[l];
                a -= c * self.v[l + 1] + s * self.u[l + 1];
            }
            if l > 0 {
                let (s, c) = self.sc[l - 1];
                a += s * self.u[l - 1] - c * self.v[l - 1];
            }
            self.acc[l] = a;
        }
    }
}

/// BEAM as the explicit ODE `y' = f(t, y)`, `y = [z, z']`, with
/// preallocated buffers (the right-hand side and its JVP allocate nothing).
#[derive(Clone, Debug)]
pub struct BeamSystem {
    n: usize,
    work: Work<f64>,
    dual: Work<Dual>,
}

impl BeamSystem {
    /// The test set's beam of [`SEGMENTS`] segments.
    pub fn new() -> Self {
        Self::with_segments(SEGMENTS)
    }

    /// The same equations with `n >= 1` segments (at least 1).
    pub fn with_segments(n: usize) -> Self {
        let n = n.max(1);
        Self {
            n,
            work: Work::new(n),
            dual: Work::new(n),
        }
    }

    /// The start: at rest and straight, `y = 0`.
    pub fn start(&self) -> Vec<f64> {
        vec![0.0; 2 * self.n]
    }

    /// `(v, u)` at `(t, y)`: the algebraic unknowns of [`BeamDae`].
    pub fn internal(&mut self, t: f64, y: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = self.n;
        self.work.z.copy_from_slice(&y[..n]);
        self.work.w.copy_from_slice(&y[n..2 * n]);
        self.work.evaluate(t);
        (self.work.v.clone(), self.work.u.clone())
    }
}

impl Default for BeamSystem {
    fn default() -> Self {
        Self::new()
    }
}

impl OdeSystem for BeamSystem {
    fn dim(&self) -> usize {
        2 * self.n
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        self.work.z.copy_from_slice(&y[..n]);
        self.work.w.copy_from_slice(&y[n..2 * n]);
        self.work.evaluate(t);
        dy[..n].copy_from_slice(&y[n..2 * n]);
        dy[n..2 * n].copy_from_slice(&self.work.acc);
    }

    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        let n = self.n;
        for l in 0..n {
            self.dual.z[l] = Dual::new(y[l], v[l]);
            self.dual.w[l] = Dual::new(y[n + l], v[n + l]);
        }
        self.dual.evaluate(t);
        jv[..n].copy_from_slice(&v[n..2 * n]);
        for (o, a) in jv[n..2 * n].iter_mut().zip(&self.dual.acc) {
            *o = a.d;
        }
    }
}

impl Problem for BeamSystem {
    fn banded_dae(&self, t0: f64, y0: &[f64]) -> Option<BandedDae> {
        let n = self.n;
        let (v, u) = self.clone().internal(t0, y0);
        let mut full = Vec::with_capacity(4 * n);
        full.extend_from_slice(&y0[..2 * n]);
        full.extend_from_slice(&u);
        full.extend_from_slice(&v);
        Some(BandedDae {
            dae: Box::new(BeamDae::new(n)),
            y0: full,
        })
    }
}

/// BEAM as a banded index-1 DAE: unknowns `[z (n), z' (n), u (n), v (n)]`,
/// the first `2 n` differential. Rows: `z' = w`; `w' = C v + D u`;
/// `0 = C u - D v - w^2`; `0 = v - n^4 (second difference) - n^2 phi(t)
/// (cos z + sin z)`. Each row reads only its segment and the two
/// neighbours; its Jacobian is taken entry by entry with dual numbers from
/// the same row function, so the two cannot disagree.
#[derive(Clone, Copy, Debug)]
pub struct BeamDae {
    n: usize,
}

/// Kinds of unknowns and of rows: the angle, its rate, `u`, `v`.
const KINDS: usize = 4;

impl BeamDae {
    /// The DAE of `n >= 1` segments.
    pub fn new(n: usize) -> Self {
        Self { n: n.max(1) }
    }

    /// Whether row kind `p` reads unknown kind `q` of the segment `d` away
    /// (`d` = the unknown's segment less the row's, in `-1..=1`): the
    /// Jacobian's pattern, independent of the state.
    fn reads(p: usize, q: usize, d: isize) -> bool {
        match (p, q) {
            // z' = w
            (0, 1) => d == 0,
            // w' = C v + D u (D has no diagonal)
            (1, 0) | (1, 3) => true,
            (1, 2) => d != 0,
            // 0 = C u - D v - w^2
            (2, 0) | (2, 2) => true,
            (2, 1) => d == 0,
            (2, 3) => d != 0,
            // 0 = v - n^4 (...) - n^2 (...)
            (3, 0) => true,
            (3, 3) => d == 0,
            _ => false,
        }
    }

    /// Row `p n + m` of `f(t, y)`, the unknowns read through `y(index)`.
    fn row<S: Scalar>(&self, t: f64, p: usize, m: usize, y: impl Fn(usize) -> S) -> S {
        let n = self.n;
        let (z, w, u, v) = (
            |l: usize| y(l),
            |l: usize| y(n + l),
            |l: usize| y(2 * n + l),
            |l: usize| y(3 * n + l),
        );
        // (sin, cos)(z_m - z_k) for the neighbours k of m.
        let neighbours = [m.checked_sub(1), (m + 1 < n).then_some(m + 1)];
        match p {
            0 => w(m),
            1 => {
                let mut a = v(m) * c_diag(m, n);
                for k in neighbours.into_iter().flatten() {
                    let (s, c) = (z(m) - z(k)).sin_cos();
                    a -= c * v(k) + s * u(k);
                }
                a
            }
            2 => {
                let mut r = u(m) * c_diag(m, n) - w(m) * w(m);
                for k in neighbours.into_iter().flatten() {
                    let (s, c) = (z(m) - z(k)).sin_cos();
                    r += s * v(k) - c * u(k);
                }
                r
            }
            _ => v(m) - v_of(t, z, m, n),
        }
    }
}

impl SemiExplicitDae for BeamDae {
    fn dim(&self) -> usize {
        KINDS * self.n
    }

    fn differential_dim(&self) -> usize {
        2 * self.n
    }

    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let n = self.n;
        for (r, o) in out.iter_mut().enumerate().take(KINDS * n) {
            *o = self.row(t, r / n, r % n, |j| y[j]);
        }
    }

    fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        let n = self.n;
        for col in 0..KINDS * n {
            let (q, l) = (col / n, col % n);
            let seeded = |j: usize| Dual::new(y[j], if j == col { 1.0 } else { 0.0 });
            for m in l.saturating_sub(1)..(l + 2).min(n) {
                let d = l as isize - m as isize;
                for p in 0..KINDS {
                    if Self::reads(p, q, d) {
                        emit(p * n + m, col, self.row(t, p, m, seeded).d);
                    }
                }
            }
        }
    }

    fn blocks(&self) -> Option<Vec<usize>> {
        Some((0..KINDS * self.n).map(|u| u % self.n).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A state away from rest, every coupling awake.
    fn state(n: usize) -> Vec<f64> {
        (0..2 * n)
            .map(|i| 0.3 * ((i as f64) * 0.7).sin() + 0.05 * i as f64 / n as f64)
            .collect()
    }

    /// The Thomas solve against the definition: `C u = D v + w^2` and
    /// `z'' = C v + D u` rebuilt with dense matrices.
    #[test]
    fn the_explicit_form_solves_its_defining_equations() {
        let n = 7;
        let mut sys = BeamSystem::with_segments(n);
        let y = state(n);
        let t = 1.1;
        let mut dy = vec![0.0; 2 * n];
        sys.rhs(t, &y, &mut dy);
        let (v, u) = sys.internal(t, &y);
        let z = &y[..n];
        let mut c = vec![vec![0.0; n]; n];
        let mut d = vec![vec![0.0; n]; n];
        for l in 0..n {
            c[l][l] = c_diag(l, n);
            for k in [l.wrapping_sub(1), l + 1] {
                if k < n {
                    c[l][k] = -(z[l] - z[k]).cos();
                    d[l][k] = -(z[l] - z[k]).sin();
                }
            }
        }
        for l in 0..n {
            let cu: f64 = (0..n).map(|k| c[l][k] * u[k]).sum();
            let dv: f64 = (0..n).map(|k| d[l][k] * v[k]).sum();
            let g = dv + y[n + l] * y[n + l];
            assert!((cu - g).abs() < 1e-9 * g.abs().max(1e3), "{l}: {cu} {g}");
            let acc: f64 = (0..n).map(|k| c[l][k] * v[k] + d[l][k] * u[k]).sum();
            assert!((dy[n + l] - acc).abs() < 1e-9 * acc.abs().max(1e3));
            assert_eq!(dy[l], y[n + l]);
        }
    }

    /// The JVP against central differences of the right-hand side.
    #[test]
    fn the_jvp_matches_finite_differences() {
        let n = 6;
        let mut sys = BeamSystem::with_segments(n);
        let y = state(n);
        let dir: Vec<f64> = (0..2 * n)
            .map(|i| ((i * 3 % 5) as f64 - 2.0) / 3.0)
            .collect();
        let t = 0.8;
        let mut jv = vec![0.0; 2 * n];
        sys.jvp(t, &y, &dir, &mut jv);
        let h = 1e-6;
        let (mut fp, mut fm) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
        let yp: Vec<f64> = y.iter().zip(&dir).map(|(a, b)| a + h * b).collect();
        let ym: Vec<f64> = y.iter().zip(&dir).map(|(a, b)| a - h * b).collect();
        sys.rhs(t, &yp, &mut fp);
        sys.rhs(t, &ym, &mut fm);
        for i in 0..2 * n {
            let fd = (fp[i] - fm[i]) / (2.0 * h);
            assert!(
                (jv[i] - fd).abs() < 1e-6 * fd.abs().max(1e2),
                "{i}: {} {fd}",
                jv[i]
            );
        }
    }

    /// The DAE at the explicit form's `u`, `v` has zero algebraic residuals
    /// and the explicit form's derivatives: an independent check of both.
    #[test]
    fn the_dae_agrees_with_the_explicit_form() {
        let n = 9;
        let sys = BeamSystem::with_segments(n);
        let y = state(n);
        let t = 2.0;
        let BandedDae { dae, y0 } = sys.banded_dae(t, &y).expect("BEAM has a DAE form");
        let mut out = vec![0.0; 4 * n];
        dae.rhs(t, &y0, &mut out);
        let mut dy = vec![0.0; 2 * n];
        sys.clone().rhs(t, &y, &mut dy);
        for i in 0..2 * n {
            assert!((out[i] - dy[i]).abs() < 1e-9 * dy[i].abs().max(1e3), "{i}");
        }
        for (i, r) in out[2 * n..].iter().enumerate() {
            assert!(r.abs() < 1e-7, "algebraic row {i}: {r}");
        }
    }

    /// The DAE's Jacobian entries against central differences of its rows,
    /// column by column, and nothing outside the stated pattern.
    #[test]
    fn the_dae_jacobian_matches_finite_differences() {
        let n = 5;
        let dae = BeamDae::new(n);
        let mut y: Vec<f64> = (0..4 * n).map(|i| (i as f64 * 0.37).cos()).collect();
        for x in &mut y[2 * n..] {
            *x *= 50.0;
        }
        let t = 1.3;
        let dim = 4 * n;
        let mut jac = vec![vec![0.0; dim]; dim];
        dae.jacobian_entries(t, &y, &mut |r, c, v| jac[r][c] += v);
        let h = 1e-6;
        let (mut fp, mut fm) = (vec![0.0; dim], vec![0.0; dim]);
        for c in 0..dim {
            let mut yp = y.clone();
            let mut ym = y.clone();
            yp[c] += h;
            ym[c] -= h;
            dae.rhs(t, &yp, &mut fp);
            dae.rhs(t, &ym, &mut fm);
            for r in 0..dim {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                let tol = 1e-5 * fd.abs().max(1e2);
                assert!(
                    (jac[r][c] - fd).abs() < tol,
                    "({r}, {c}): {} {fd}",
                    jac[r][c]
                );
            }
        }
    }
}
