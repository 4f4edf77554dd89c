//! The equilibrium of unequal rods with one rod in compression (or in
//! tension next to that configuration), for [`crate::discrete_equilibrium_rods`].
//!
//! Units and frame as in `profiled.rs`: lengths in mean rods `l`, forces in
//! mean-rod weights, the chain running towards `+x`; rod `i` has length
//! `lambda_i` and carries `W_i` (the weight beyond its centre), and the force
//! through its centre is `F_i = (H, V - W_i)`. Moment balance about its
//! centre makes rod `i` parallel to `F_i`, pointing along it (tension) or
//! against it (compression).
//!
//! The equal rods' analysis (`rods.rs`) carries over. At `H = 0`, `V = W_j`
//! rod `j`'s force vanishes, the rods before it hang straight down
//! (`V - W_i < 0`) and the rods after it stand straight up, so the free end
//! lies within `lambda_j` of `(0, k_j)`, `k_j = sum_{i>j} lambda_i -
//! sum_{i<j} lambda_i`. These disks touch but do not overlap (`k_j - k_{j+1}
//! = lambda_j + lambda_{j+1}`): an end `(d, h)` with `|(d, h - k_j)| <=
//! lambda_j` (it needs `d <= l_j`) is held by a chain whose rod `j` is in
//! compression (`H < 0`, the other rods leaning back past the vertical). In
//! polar coordinates about that kink, `(H, V - W_j) = r (cos psi, sin psi)`
//! with rod `j` along `(cos psi, sin psi)`, `|psi| < pi/2`, the end condition
//!
//! ```text
//! lambda_j (cos psi, sin psi) + sum_{i != j} lambda_i F_i / |F_i| = (d, h)
//! ```
//!
//! is smooth through `r = 0` (`r < 0`: rod `j` in compression), and is solved
//! by Newton's method with backtracking on the residual's norm.

use std::f64::consts::FRAC_PI_2;

/// Newton's cap.
const MAX_ITERATIONS: u64 = 100;

/// A solution in the `+x` frame.
pub(crate) struct KinkSolution {
    /// `phi_i` (rad).
    pub angles: Vec<f64>,
    /// `H` (negative: rod `j` in compression).
    pub tension: f64,
    /// `V`.
    pub vertical: f64,
    pub iterations: u64,
}

/// The kink nearest the end `target = (d, h)`: rod `j` and `|w_j| /
/// lambda_j`, `w_j = (d, h - k_j)` (at most 1: rod `j` in compression).
pub(crate) fn nearest_kink(lambda: &[f64], target: [f64; 2]) -> (usize, f64) {
    // k_0 = sum_{i>0} lambda_i; k_{j+1} = k_j - lambda_j - lambda_{j+1}.
    let mut k: f64 = lambda.iter().skip(1).sum();
    let mut best = (0, f64::INFINITY);
    for j in 0..lambda.len() {
        if j > 0 {
            k -= lambda[j - 1] + lambda[j];
        }
        let ratio = target[0].hypot(target[1] - k) / lambda[j];
        if ratio < best.1 {
            best = (j, ratio);
        }
    }
    best
}

/// The end residual and its Jacobian in `(r, psi)` about the kink of rod `j`.
fn residual(
    lambda: &[f64],
    weight: &[f64],
    target: [f64; 2],
    j: usize,
    [r, psi]: [f64; 2],
) -> ([f64; 2], [[f64; 2]; 2]) {
    let (s, c) = psi.sin_cos();
    let lj = lambda[j];
    let h = r * c;
    let mut g = [lj * c - target[0], lj * s - target[1]];
    let mut jac = [[0.0, -lj * s], [0.0, lj * c]];
    for (i, (&lam, &wi)) in lambda.iter().zip(weight).enumerate() {
        if i == j {
            continue;
        }
        // V - W_i = r s + m.
        let m = weight[j] - wi;
        let v = r * s + m;
        let rho = h.hypot(v);
        let rho3 = rho * rho * rho;
        g[0] += lam * h / rho;
        g[1] += lam * v / rho;
        // d/dr (h, v)/rho = c m (v, -h)/rho^3; d/dpsi = r (r + m s) (-v, h)/rho^3.
        let (dr, dpsi) = (lam * c * m / rho3, lam * r * (r + m * s) / rho3);
        jac[0][0] += dr * v;
        jac[1][0] -= dr * h;
        jac[0][1] -= dpsi * v;
        jac[1][1] += dpsi * h;
    }
    (g, jac)
}

fn norm(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

/// Newton about the kink of rod `j` for the end `target`, to `tol` (in mean
/// rods) or the iteration cap; `None` if it stalls.
pub(crate) fn solve_near_kink(
    lambda: &[f64],
    weight: &[f64],
    target: [f64; 2],
    j: usize,
    tol: f64,
) -> Option<KinkSolution> {
    let n = lambda.len();
    let [d, h] = target;
    let lj = lambda[j];
    // k_j and, to first order about the kink, sum_{i != j} lambda_i /
    // |W_i - W_j| (the other rods' horizontal reach per unit r cos psi).
    let before: f64 = lambda[..j].iter().sum();
    let after: f64 = lambda[j + 1..].iter().sum();
    let kj = after - before;
    let s1: f64 = (0..n)
        .filter(|&i| i != j)
        .map(|i| lambda[i] / (weight[i] - weight[j]).abs())
        .sum();
    let psi0 = ((h - kj) / lj).clamp(-1.0, 1.0).asin();
    let r0 = (d - lj * psi0.cos()) / (s1 * psi0.cos());
    let mut x = [r0, psi0];
    if !(x[0].is_finite() && x[1].is_finite()) {
        return None;
    }
    let mut e = residual(lambda, weight, target, j, x);
    let mut iterations = 0;
    while norm(e.0) > tol && iterations < MAX_ITERATIONS {
        let jac = e.1;
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        let step = [
            -(jac[1][1] * e.0[0] - jac[0][1] * e.0[1]) / det,
            -(jac[0][0] * e.0[1] - jac[1][0] * e.0[0]) / det,
        ];
        if !(step[0].is_finite() && step[1].is_finite()) {
            break;
        }
        let mut lambda_step = 1.0;
        let mut moved = false;
        for _ in 0..60 {
            let c = [x[0] + lambda_step * step[0], x[1] + lambda_step * step[1]];
            if c[1].abs() < FRAC_PI_2 {
                let ec = residual(lambda, weight, target, j, c);
                if norm(ec.0) < norm(e.0) {
                    (x, e) = (c, ec);
                    moved = true;
                    break;
                }
            }
            lambda_step *= 0.5;
        }
        if !moved {
            break;
        }
        iterations += 1;
    }
    let [r, psi] = x;
    let (tension, vj) = (r * psi.cos(), r * psi.sin());
    let angles = (0..n)
        .map(|i| {
            if i == j {
                psi
            } else {
                (vj + weight[j] - weight[i]).atan2(tension)
            }
        })
        .collect();
    Some(KinkSolution {
        angles,
        tension,
        vertical: weight[j] + vj,
        iterations,
    })
}
