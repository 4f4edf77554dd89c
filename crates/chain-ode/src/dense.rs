//! The dense O(n^3) reference: assemble `A(phi)` and `b(phi, w)` exactly as
//! `docs/model.md` states them and solve with faer's Cholesky factorisation.
//! Tests compare the O(n) recursion against it; it is never on a hot path.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use crate::chain::Chain;
use crate::kinematics::lever_arm;
use crate::load::{Load, Loads, RodForce, RodSlices, Units};

/// `mt_ij`: `n - i + 1/3` on the diagonal, `n - max(i,j) + 1/2` off it (1-based),
/// for a chain without a tip mass. A tip mass `mu = M_t / m` adds `mu` to
/// every entry ([`mt_tip`]).
pub fn mt(n: usize, i: usize, j: usize) -> f64 {
    // 0-based i, j here: 1-based index k is k0 + 1.
    let k = i.max(j) + 1;
    if i == j {
        (n - k) as f64 + 1.0 / 3.0
    } else {
        lever_arm(n, k - 1)
    }
}

/// `mt_ij + mu`: the tip mass `M_t = mu m` at `r_n = l sum_j u_j` adds
/// `(M_t l^2 / 2) sum_ij w_i w_j cos(phi_i - phi_j)` to `T` and
/// `M_t g l sum_i sin phi_i` to `V`.
pub fn mt_tip(n: usize, i: usize, j: usize, mu: f64) -> f64 {
    mt(n, i, j) + mu
}

/// The mass matrix `A_ij = mt_ij cos(phi_i - phi_j)` (rod units:
/// `T = m l^2/2 w^T A w`) of a chain without a tip mass.
pub fn mass_matrix(phi: &[f64]) -> Mat<f64> {
    mass_matrix_with_tip(phi, 0.0)
}

/// The mass matrix `A_ij = (mt_ij + mu) cos(phi_i - phi_j)` (rod units:
/// `T = m l^2/2 w^T A w`), `mu = M_t / m` the tip mass.
pub fn mass_matrix_with_tip(phi: &[f64], mu: f64) -> Mat<f64> {
    let n = phi.len();
    Mat::from_fn(n, n, |i, j| mt_tip(n, i, j, mu) * (phi[i] - phi[j]).cos())
}

/// The right-hand side `b_i = -sum_j (mt_ij + mu) s_ij w_j^2 + Q_i`: the
/// centripetal terms and the loads' generalised forces `Q` (gravity, the
/// tip mass's weight, friction, bending, ...: [`generalised_forces`]), in
/// rod units, of equal rods (`mu = M_t / m`, the tip mass).
pub fn forcing(chain: &Chain, phi: &[f64], w: &[f64]) -> Vec<f64> {
    let n = phi.len();
    let mu = chain.tip_mass_ratio();
    let q = generalised_forces(chain, &Layout::of(chain), phi, w, [0.0, 0.0]).0;
    (0..n)
        .map(|i| {
            let centripetal: f64 = (0..n)
                .map(|j| mt_tip(n, i, j, mu) * (phi[i] - phi[j]).sin() * w[j] * w[j])
                .sum();
            -centripetal + q[i]
        })
        .collect()
}

/// The loads' generalised forces on the angles, by virtual work: every
/// load's force `F_k` at rod `k`'s centre and torque `tau_k` (rod units,
/// [`Loads`]), and the field on the tip mass at `r_n`, give
/// `Q_i = tau_i + sum_k (d c_k / d phi_i) . F_k + (d r_n / d phi_i) . mu_t a`
/// with `d c_k / d phi_i = lambda_i v_i` above rod `k` (`i < k`), half that
/// at it, and `d r_n / d phi_i = lambda_i v_i`. Also the total force on the
/// chain (the pivot's generalised force). The pivot moves at `v0` (rod
/// units), which loads that read the centres see. Written from the
/// Cartesian forces, apart from the recursion's articulated bodies.
fn generalised_forces(
    chain: &Chain,
    rods: &Layout,
    phi: &[f64],
    w: &[f64],
    v0: [f64; 2],
) -> (Vec<f64>, [f64; 2]) {
    let n = phi.len();
    let loads = Loads::of(chain, Units::Rod);
    let trig: Vec<(f64, f64)> = phi.iter().map(|p| p.sin_cos()).collect();
    let (mut centre, mut velocity) = (vec![[0.0; 2]; n], vec![[0.0; 2]; n]);
    let (mut p, mut v) = ([0.0, 0.0], v0);
    for i in 0..n {
        let (s, c) = trig[i];
        let lam = rods.lambda[i];
        let (u, nv) = ([lam * c, lam * s], [-lam * s * w[i], lam * c * w[i]]);
        centre[i] = [p[0] + 0.5 * u[0], p[1] + 0.5 * u[1]];
        velocity[i] = [v[0] + 0.5 * nv[0], v[1] + 0.5 * nv[1]];
        p = [p[0] + u[0], p[1] + u[1]];
        v = [v[0] + nv[0], v[1] + nv[1]];
    }
    let view = RodSlices {
        phi,
        w,
        trig: &trig,
        length: Some(&rods.lambda),
        mass: Some(&rods.mu),
        centre: &centre,
        velocity: &velocity,
    };
    let a = loads.field.acceleration;
    let mut q = vec![0.0; n];
    let mut total = [rods.mu_t * a[0], rods.mu_t * a[1]];
    // Beyond rod i: the force below it (the tip mass's weight, then each
    // rod's), which a turn of rod i carries by its length.
    let mut below = total;
    for i in (0..n).rev() {
        let mut f = RodForce::zero();
        loads.field.add_to_rod(i, &view, &mut f);
        loads.add_to_rod(i, &view, &mut f);
        let (s, c) = trig[i];
        let lam = rods.lambda[i];
        let vi = [-s, c];
        let dot = |x: [f64; 2]| vi[0] * x[0] + vi[1] * x[1];
        q[i] = f.torque + lam * dot(below) + 0.5 * lam * dot(f.force);
        below = [below[0] + f.force[0], below[1] + f.force[1]];
        total = [total[0] + f.force[0], total[1] + f.force[1]];
    }
    (q, total)
}

/// The mass below rod `i` and half of its own, `S_{i+1} + mu_i / 2 + mu_t`,
/// and the mass below it, `S_{i+1} + mu_t` (mean-rod masses `mu`, the tip
/// mass `mu_t` beyond the last rod), for every `i`.
fn masses_below(mu: &[f64], mu_t: f64) -> Vec<(f64, f64)> {
    let n = mu.len();
    let mut out = vec![(0.0, 0.0); n];
    let mut below = mu_t;
    for i in (0..n).rev() {
        out[i] = (below + 0.5 * mu[i], below);
        below += mu[i];
    }
    out
}

/// `mt_ij` of rods of unequal mass `mu_i` and length `lambda_i` (mean-rod
/// units), from `T = (1/2) sum_k mu_k (|c_k'|^2 + lambda_k^2 w_k^2 / 12)`
/// with `c_k = sum_{j<k} lambda_j u_j + lambda_k u_k / 2`:
/// `lambda_i lambda_j (S_{k+1} + mu_k / 2)` off the diagonal (`k = max(i, j)`,
/// `S_{k+1}` the mass of the rods below rod `k`) and
/// `lambda_i^2 (S_{i+1} + mu_i / 3)` on it. Equal rods give [`mt`].
pub fn mt_rods(mu: &[f64], lambda: &[f64]) -> Mat<f64> {
    mt_rods_tip(mu, lambda, 0.0)
}

/// [`mt_rods`] with a tip mass `mu_t` (mean-rod masses) at the free end,
/// `r_n = l sum_j lambda_j u_j`: its `(mu_t / 2) |r_n'|^2` adds
/// `mu_t lambda_i lambda_j` to every entry, i.e. `S_{k+1}` counts it.
pub fn mt_rods_tip(mu: &[f64], lambda: &[f64], mu_t: f64) -> Mat<f64> {
    let n = mu.len();
    let below = masses_below(mu, mu_t);
    Mat::from_fn(n, n, |i, j| {
        let k = i.max(j);
        if i == j {
            lambda[i] * lambda[i] * (below[i].1 + mu[i] / 3.0)
        } else {
            lambda[i] * lambda[j] * below[k].0
        }
    })
}

/// The chain's rods as the dense reference reads them: masses `mu_i`,
/// lengths `lambda_i` (all 1 for equal rods) and the tip mass `mu_t`. (The
/// loads, the bending springs among them, are the chain's: [`Loads`].)
struct Layout {
    mu: Vec<f64>,
    lambda: Vec<f64>,
    mu_t: f64,
}

impl Layout {
    fn of(chain: &Chain) -> Self {
        let n = chain.links();
        match chain.rods() {
            Some(r) => Self::from(&r.mass, &r.length, chain.tip_mass_ratio()),
            None => Self::from(&vec![1.0; n], &vec![1.0; n], chain.tip_mass_ratio()),
        }
    }

    fn from(mu: &[f64], lambda: &[f64], mu_t: f64) -> Self {
        Self {
            mu: mu.to_vec(),
            lambda: lambda.to_vec(),
            mu_t,
        }
    }
}

/// `phi''` of a profiled chain ([`crate::Rods`]) by the dense solve of
/// `A phi'' = b`, `A_ij = mt_ij cos(phi_i - phi_j)` ([`mt_rods_tip`]) and
/// `b_i = -sum_j mt_ij sin(phi_i - phi_j) w_j^2 + Q_i` (`Q` the loads'
/// generalised forces by virtual work, the field on every mass among them:
/// `-(g/l) lambda_i (S_{i+1} + mu_i/2) cos phi_i`, `S_{i+1}` with the tip
/// mass), in mean-rod units, the pivot fixed.
/// `mu` and `lambda` are the chain's rods (given, so that a test may pass
/// its own).
pub fn accelerations_rods(
    chain: &Chain,
    mu: &[f64],
    lambda: &[f64],
    phi: &[f64],
    w: &[f64],
) -> Vec<f64> {
    let layout = Layout::from(mu, lambda, chain.tip_mass_ratio());
    pivot_dynamics(chain, &layout, Pivoted::Fixed, phi, w).0
}

/// How the pivot is held in [`accelerations_on`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pivoted {
    /// Pinned.
    Fixed,
    /// Moved with the given acceleration `P0''` (physical units).
    Driven([f64; 2]),
    /// Free: no force at the pivot.
    Free,
}

/// The rigid chain with its pivot `P0` as two more coordinates, every term
/// included (unequal rods, tip mass, friction, bending), by a dense solve:
/// `phi''`, `P0''` and the pivot's force on rod 1 (physical units).
///
/// In rod units (`P` = `P0 / l`), with `B_i = lambda_i (S_{i+1} + mu_i/2 + mu_t)`
/// (the mass beyond rod `i`'s centre) and `M = n + mu_t`, the Lagrangian
/// `T = (m l^2 / 2) (M |P'|^2 + 2 P' . sum_i B_i w_i v_i + w^T A w)`,
/// `V = m g l (M P_y + sum_i B_i sin phi_i)` gives
///
/// ```text
/// A phi'' + B v P''   = b                                  (the angles)
/// sum_i B_i v_i phi_i'' + M P'' = F / (m l) + sum_i B_i w_i^2 u_i - M (0, g/l)   (the pivot)
/// ```
///
/// with `b` of [`accelerations_rods`]. A fixed pivot solves the first with
/// `P'' = 0`; a driven one moves `B v P''` to the right; a free one
/// (`F = 0`) solves both, an SPD system of `n + 2` unknowns. The force `F`
/// then follows from the second line.
pub fn accelerations_on(
    chain: &Chain,
    pivot: Pivoted,
    phi: &[f64],
    w: &[f64],
) -> (Vec<f64>, [f64; 2], [f64; 2]) {
    pivot_dynamics(chain, &Layout::of(chain), pivot, phi, w)
}

fn pivot_dynamics(
    chain: &Chain,
    rods: &Layout,
    pivot: Pivoted,
    phi: &[f64],
    w: &[f64],
) -> (Vec<f64>, [f64; 2], [f64; 2]) {
    let n = phi.len();
    let (mu, lambda) = (&rods.mu, &rods.lambda);
    let mt = mt_rods_tip(mu, lambda, rods.mu_t);
    let below = masses_below(mu, rods.mu_t);
    let l = chain.rod_length();
    let (q, total) = generalised_forces(chain, rods, phi, w, [0.0, 0.0]);
    let m_tot: f64 = mu.iter().sum::<f64>() + rods.mu_t;
    let lever: Vec<f64> = (0..n).map(|i| lambda[i] * below[i].0).collect();
    let (v, u): (Vec<[f64; 2]>, Vec<[f64; 2]>) = phi
        .iter()
        .map(|p| ([-p.sin(), p.cos()], [p.cos(), p.sin()]))
        .unzip();
    let mut b: Vec<f64> = (0..n)
        .map(|i| {
            let centripetal: f64 = (0..n)
                .map(|j| mt[(i, j)] * (phi[i] - phi[j]).sin() * w[j] * w[j])
                .sum();
            -centripetal + q[i]
        })
        .collect();
    // The pivot's row: sum_i B_i w_i^2 u_i plus every force on the chain
    // (its weight `M (0, -g/l)` and the loads'), less the pivot's force.
    let mut p_rhs = total;
    for i in 0..n {
        for k in 0..2 {
            p_rhs[k] += lever[i] * w[i] * w[i] * u[i][k];
        }
    }
    let a = Mat::from_fn(n, n, |i, j| mt[(i, j)] * (phi[i] - phi[j]).cos());
    let (alpha, p2) = match pivot {
        Pivoted::Fixed | Pivoted::Driven(_) => {
            let p2 = match pivot {
                Pivoted::Driven([x, y]) => [x / l, y / l],
                _ => [0.0, 0.0],
            };
            for i in 0..n {
                b[i] -= lever[i] * (v[i][0] * p2[0] + v[i][1] * p2[1]);
            }
            (solve_spd(&a, &b), p2)
        }
        Pivoted::Free => {
            let big = Mat::from_fn(n + 2, n + 2, |i, j| match (i < n, j < n) {
                (true, true) => a[(i, j)],
                (true, false) => lever[i] * v[i][j - n],
                (false, true) => lever[j] * v[j][i - n],
                (false, false) => {
                    if i == j {
                        m_tot
                    } else {
                        0.0
                    }
                }
            });
            let mut rhs = b.clone();
            rhs.extend_from_slice(&p_rhs);
            let x = solve_spd(&big, &rhs);
            (x[..n].to_vec(), [x[n], x[n + 1]])
        }
    };
    // F / (m l) = sum_i B_i v_i phi_i'' + M P'' - (pivot's right-hand side).
    let mut f = [0.0; 2];
    for k in 0..2 {
        f[k] = m_tot * p2[k] - p_rhs[k];
        for i in 0..n {
            f[k] += lever[i] * v[i][k] * alpha[i];
        }
    }
    let ml = chain.mass() * l;
    let force = if pivot == Pivoted::Free {
        [0.0, 0.0]
    } else {
        [f[0] * ml, f[1] * ml]
    };
    (alpha, [p2[0] * l, p2[1] * l], force)
}

/// `x` of `a x = b` by Cholesky; NaN everywhere if `a` is not SPD.
fn solve_spd(a: &Mat<f64>, b: &[f64]) -> Vec<f64> {
    let rhs = Mat::from_fn(b.len(), 1, |i, _| b[i]);
    let Ok(llt) = a.llt(Side::Lower) else {
        return vec![f64::NAN; b.len()];
    };
    let x = llt.solve(&rhs);
    (0..b.len()).map(|i| x[(i, 0)]).collect()
}

/// `phi''` by a dense Cholesky solve of `A phi'' = b`. The mass matrix is
/// symmetric positive definite for finite angles; if the factorisation
/// fails all the same (a non-finite angle), every entry is NaN. A profiled
/// chain is solved by [`accelerations_rods`].
pub fn accelerations(chain: &Chain, phi: &[f64], w: &[f64]) -> Vec<f64> {
    if let Some(rods) = chain.rods() {
        return accelerations_rods(chain, &rods.mass, &rods.length, phi, w);
    }
    let a = mass_matrix_with_tip(phi, chain.tip_mass_ratio());
    let b = forcing(chain, phi, w);
    let rhs = Mat::from_fn(b.len(), 1, |i, _| b[i]);
    let Ok(llt) = a.llt(Side::Lower) else {
        return vec![f64::NAN; b.len()];
    };
    let x = llt.solve(&rhs);
    (0..b.len()).map(|i| x[(i, 0)]).collect()
}

/// Kinetic energy `T = (m l^2 / 2) w^T A w` from the dense matrix.
pub fn kinetic_energy(chain: &Chain, phi: &[f64], w: &[f64]) -> f64 {
    let n = phi.len();
    let a = match chain.rods() {
        Some(rods) => {
            let mt = mt_rods_tip(&rods.mass, &rods.length, chain.tip_mass_ratio());
            Mat::from_fn(n, n, |i, j| mt[(i, j)] * (phi[i] - phi[j]).cos())
        }
        None => mass_matrix_with_tip(phi, chain.tip_mass_ratio()),
    };
    let mut q = 0.0;
    for i in 0..n {
        for j in 0..n {
            q += w[i] * a[(i, j)] * w[j];
        }
    }
    0.5 * chain.mass() * chain.rod_length().powi(2) * q
}
