//! The dense O(n^3) reference: assemble `A(phi)` and `b(phi, w)` exactly as
//! `docs/model.md` states them and solve with faer's Cholesky factorisation.
//! Tests compare the O(n) recursion against it; it is never on a hot path.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use crate::chain::Chain;
use crate::dynamics::damping_stencil;
use crate::kinematics::lever_arm;

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

/// The right-hand side
/// `b_i = -sum_j (mt_ij + mu) s_ij w_j^2 - (g/l) (q_i + mu) cos phi_i + gamma D_i(w) + kappa D_i(phi)`
/// (`kappa = EI / (l m l^2)`, the bending springs; `mu = M_t / m`, the tip mass).
pub fn forcing(chain: &Chain, phi: &[f64], w: &[f64]) -> Vec<f64> {
    let n = phi.len();
    let g = chain.gravity_rate();
    let gamma = chain.damping_rate();
    let kappa = chain.bending_rate();
    let mu = chain.tip_mass_ratio();
    (0..n)
        .map(|i| {
            let centripetal: f64 = (0..n)
                .map(|j| mt_tip(n, i, j, mu) * (phi[i] - phi[j]).sin() * w[j] * w[j])
                .sum();
            let q = lever_arm(n, i) + mu;
            let bending = if kappa != 0.0 {
                kappa * damping_stencil(phi, i)
            } else {
                0.0
            };
            -centripetal - g * q * phi[i].cos() + gamma * damping_stencil(w, i) + bending
        })
        .collect()
}

/// The mass below rod `i` and half of its own, `S_{i+1} + mu_i / 2`, and
/// the rods below it, `S_{i+1}` (mean-rod masses `mu`), for every `i`.
fn masses_below(mu: &[f64]) -> Vec<(f64, f64)> {
    let n = mu.len();
    let mut out = vec![(0.0, 0.0); n];
    let mut below = 0.0;
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
    let n = mu.len();
    let below = masses_below(mu);
    Mat::from_fn(n, n, |i, j| {
        let k = i.max(j);
        if i == j {
            lambda[i] * lambda[i] * (below[i].1 + mu[i] / 3.0)
        } else {
            lambda[i] * lambda[j] * below[k].0
        }
    })
}

/// `phi''` of a profiled chain ([`crate::Rods`]) by the dense solve of
/// `A phi'' = b`, `A_ij = mt_ij cos(phi_i - phi_j)` ([`mt_rods`]) and
/// `b_i = -sum_j mt_ij sin(phi_i - phi_j) w_j^2 - (g/l) lambda_i (S_{i+1} + mu_i/2) cos phi_i + gamma D_i(w)`
/// (the potential `V = m g l sum_k mu_k y_k`), in mean-rod units.
pub fn accelerations_rods(
    chain: &Chain,
    mu: &[f64],
    lambda: &[f64],
    phi: &[f64],
    w: &[f64],
) -> Vec<f64> {
    let n = phi.len();
    let mt = mt_rods(mu, lambda);
    let below = masses_below(mu);
    let g = chain.gravity_rate();
    let gamma = chain.damping_rate();
    let a = Mat::from_fn(n, n, |i, j| mt[(i, j)] * (phi[i] - phi[j]).cos());
    let b: Vec<f64> = (0..n)
        .map(|i| {
            let centripetal: f64 = (0..n)
                .map(|j| mt[(i, j)] * (phi[i] - phi[j]).sin() * w[j] * w[j])
                .sum();
            -centripetal - g * lambda[i] * below[i].0 * phi[i].cos() + gamma * damping_stencil(w, i)
        })
        .collect();
    solve_spd(&a, &b)
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
            let mt = mt_rods(&rods.mass, &rods.length);
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
