//! Statics of `n` equal rods pinned at both ends, for a chain running towards
//! `+x`, in rod units (lengths in `l`, forces in rod weights `W = m g`).
//!
//! Rod `i + 1` exerts `(H, V_i)` on rod `i`. Force balance gives
//! `V_i = V_c + i - n/2` (`V_c` the vertical force at mid-chain), torque
//! balance about each rod's centre makes rod `i` parallel to
//! `(H, v_i)`, `v_i = (V_{i-1} + V_i)/2 = V_c + i - (n+1)/2`, so that
//! `tan(phi_i) = v_i / H`: `beta = 1 / H`, `alpha = (V_c - n/2) / H`.
//!
//! If every rod is in tension, rod `i` points along `+(H, v_i)` and the end
//! condition `sum_i u_i = (d, h)` is the gradient of the strictly convex
//! `Phi(H, V_c) = sum_i |(H, v_i)| - H d - V_c h`, minimised by damped Newton.
//! `Phi` is the dual of the least-energy problem with rods allowed to shorten;
//! its minimiser has `H > 0` unless it sits at a kink `H = 0, v_j = 0`: this
//! happens exactly when `|(d, h - k_j)| <= 1`, `k_j = n + 1 - 2j` (1-based
//! `j`: the end lies within one rod of the folded chain with `j - 1` rods
//! down and the rest up; it needs `d <= l`). There rod `j` is in compression,
//! `H < 0`. Polar coordinates about the kink make the equations smooth
//! through it; they are used there and, for a chain in tension, near it
//! (where `Phi` is nearly singular).

use std::f64::consts::FRAC_PI_2;

/// Iteration cap of both Newton solvers.
const MAX_ITERS: u64 = 100;

/// The end-point equations for `n` rods reaching `target = (d, h) / l`, `d > 0`.
pub(crate) struct Rods {
    pub n: usize,
    pub target: [f64; 2],
}

/// An equilibrium in the `+x` frame.
pub(crate) struct Solution {
    /// `phi_i` (rad), not yet unwrapped.
    pub angles: Vec<f64>,
    /// `H` in rod weights (negative when a rod is in compression).
    pub tension: f64,
    /// `V_c` in rod weights.
    pub mid_force: f64,
    pub iterations: u64,
    /// `|sum_i u_i - target|` in rod lengths.
    pub residual: f64,
}

fn norm(r: [f64; 2]) -> f64 {
    r[0].hypot(r[1])
}

/// Solves `J x = -r` for 2x2 `J`.
fn newton_step(j: [[f64; 2]; 2], r: [f64; 2]) -> [f64; 2] {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    [
        -(j[1][1] * r[0] - j[0][1] * r[1]) / det,
        -(j[0][0] * r[1] - j[1][0] * r[0]) / det,
    ]
}

impl Rods {
    /// `i - (n+1)/2` for rod `i = k + 1`.
    pub fn centred(&self, k: usize) -> f64 {
        k as f64 - 0.5 * (self.n as f64 - 1.0)
    }

    /// The kink nearest to the target: rod `j` (0-based) and
    /// `w = (d, h - k_j)`, the direction rod `j` would need were all others
    /// vertical. Rod `j` is in compression iff `|w| <= 1`.
    pub fn nearest_kink(&self) -> (usize, [f64; 2]) {
        let n = self.n as f64;
        // k_j = n - 1 - 2j for 0-based j; nearest to h
        let j = (0.5 * (n - 1.0 - self.target[1]))
            .round()
            .clamp(0.0, n - 1.0);
        let w = [self.target[0], self.target[1] - (n - 1.0 - 2.0 * j)];
        (j as usize, w)
    }

    /// All rods in tension: Newton on `Phi` from `start = (H, V_c)`, `H > 0`.
    pub fn solve_in_tension(&self, start: [f64; 2], tol: f64) -> Solution {
        let mut x = start;
        let mut e = self.phi(x);
        let mut iterations = 0;
        while norm(e.grad) > tol && iterations < MAX_ITERS {
            let step = newton_step(e.hess, e.grad);
            let slope = step[0] * e.grad[0] + step[1] * e.grad[1];
            if !(step[0].is_finite() && step[1].is_finite() && slope < 0.0) {
                break;
            }
            // Armijo on Phi, or (where Phi is flat to rounding) a halved residual.
            let accept = |c: [f64; 2], ec: &PhiEval, lambda: f64| {
                c[0] > 0.0
                    && (ec.value <= e.value + 1e-4 * lambda * slope
                        || norm(ec.grad) <= 0.5 * norm(e.grad))
            };
            let Some((c, ec)) = backtrack(x, step, |c| self.phi(c), accept) else {
                break;
            };
            (x, e) = (c, ec);
            iterations += 1;
        }
        let [h, vc] = x;
        Solution {
            angles: (0..self.n)
                .map(|k| (vc + self.centred(k)).atan2(h))
                .collect(),
            tension: h,
            mid_force: vc,
            iterations,
            residual: norm(e.grad),
        }
    }

    /// Near the kink of rod `j`: Newton on the end condition in polar
    /// coordinates `(H, v_j) = r (cos psi, sin psi)`, with rod `j` along
    /// `(cos psi, sin psi)`, `|psi| < pi/2` (so `r < 0` means rod `j` is in
    /// compression), backtracking on the residual norm. Smooth through the
    /// kink `r = 0`, where `Phi` is not.
    pub fn solve_near_kink(&self, j: usize, tol: f64) -> Solution {
        let [d, h] = self.target;
        // First order about the kink: sum_{i != j} u_i = (r cos psi S1, k_j).
        let kj = self.n as f64 - 1.0 - 2.0 * j as f64;
        let s1: f64 = (0..self.n)
            .filter(|&i| i != j)
            .map(|i| 1.0 / (i as f64 - j as f64).abs())
            .sum();
        let psi0 = (h - kj).clamp(-1.0, 1.0).asin();
        let r0 = (d - psi0.cos()) / (s1 * psi0.cos());
        let mut x = [r0, psi0];
        let mut e = self.polar(j, x);
        let mut iterations = 0;
        while norm(e.0) > tol && iterations < MAX_ITERS {
            let step = newton_step(e.1, e.0);
            if !(step[0].is_finite() && step[1].is_finite()) {
                break;
            }
            let accept = |c: [f64; 2], ec: &([f64; 2], [[f64; 2]; 2]), _| {
                c[1].abs() < FRAC_PI_2 && norm(ec.0) < norm(e.0)
            };
            let Some((c, ec)) = backtrack(x, step, |c| self.polar(j, c), accept) else {
                break;
            };
            (x, e) = (c, ec);
            iterations += 1;
        }
        let [r, psi] = x;
        let (tension, vj) = (r * psi.cos(), r * psi.sin());
        let angles = (0..self.n)
            .map(|i| {
                if i == j {
                    psi
                } else {
                    (vj + i as f64 - j as f64).atan2(tension)
                }
            })
            .collect();
        Solution {
            angles,
            tension,
            mid_force: vj - self.centred(j),
            iterations,
            residual: norm(e.0),
        }
    }

    /// `Phi`, its gradient (the end-point residual) and Hessian at `(H, V_c)`.
    fn phi(&self, [h, vc]: [f64; 2]) -> PhiEval {
        let mut e = PhiEval {
            value: -h * self.target[0] - vc * self.target[1],
            grad: [-self.target[0], -self.target[1]],
            hess: [[0.0; 2]; 2],
        };
        for k in 0..self.n {
            let v = vc + self.centred(k);
            let rho = h.hypot(v);
            let (cos, sin) = (h / rho, v / rho);
            e.value += rho;
            e.grad[0] += cos;
            e.grad[1] += sin;
            e.hess[0][0] += sin * sin / rho;
            e.hess[0][1] -= sin * cos / rho;
            e.hess[1][1] += cos * cos / rho;
        }
        e.hess[1][0] = e.hess[0][1];
        e
    }

    /// End-point residual and its Jacobian in the polar coordinates `(r, psi)`
    /// about the kink of rod `j`.
    fn polar(&self, j: usize, [r, psi]: [f64; 2]) -> ([f64; 2], [[f64; 2]; 2]) {
        let (s, c) = psi.sin_cos();
        let h = r * c;
        let mut g = [c - self.target[0], s - self.target[1]];
        let mut jac = [[0.0, -s], [0.0, c]];
        for i in (0..self.n).filter(|&i| i != j) {
            let m = i as f64 - j as f64;
            let v = r * s + m;
            let rho = h.hypot(v);
            let rho3 = rho * rho * rho;
            g[0] += h / rho;
            g[1] += v / rho;
            // d/dr (h, v)/rho = c m (v, -h)/rho^3 ; d/dpsi = r (r + m s) (-v, h)/rho^3
            let (dr, dpsi) = (c * m / rho3, r * (r + m * s) / rho3);
            jac[0][0] += dr * v;
            jac[1][0] -= dr * h;
            jac[0][1] -= dpsi * v;
            jac[1][1] += dpsi * h;
        }
        (g, jac)
    }
}

struct PhiEval {
    value: f64,
    grad: [f64; 2],
    hess: [[f64; 2]; 2],
}

/// Halves the step from `x` until `accept(candidate, eval, lambda)` holds.
fn backtrack<E>(
    x: [f64; 2],
    step: [f64; 2],
    eval: impl Fn([f64; 2]) -> E,
    accept: impl Fn([f64; 2], &E, f64) -> bool,
) -> Option<([f64; 2], E)> {
    let mut lambda = 1.0;
    for _ in 0..60 {
        let c = [x[0] + lambda * step[0], x[1] + lambda * step[1]];
        let ec = eval(c);
        if accept(c, &ec, lambda) {
            return Some((c, ec));
        }
        lambda *= 0.5;
    }
    None
}
