//! The exact static equilibrium of `n` equal rigid rods pinned at both ends.
//!
//! Angles `phi_i` (rad) are measured from the horizontal, counter-clockwise;
//! rod `i` points from joint `i - 1` to joint `i`. Lengths in input units.

use crate::continuous::Catenary;
use crate::error::{check_inputs, CatenaryError, TAUT};
use crate::Point;
use std::f64::consts::PI;

/// Newton iteration cap.
const MAX_NEWTON_ITERS: u64 = 100;
/// Newton stops once the end-point residual is below this times `length`.
const NEWTON_TOL: f64 = 1e-14;
/// Accuracy required of the end point, relative to `length`.
const END_TOL: f64 = 1e-12;

/// Static equilibrium of `links` rods of length `l = length / links`.
///
/// In the frame where the chain runs towards `+x` (the mirror image `x -> -x`
/// when `x1 < x0`), `tan(phi_i) = alpha + (i - 1/2) beta`, `i = 1..=n`, with
/// `beta = m g / H > 0` (rod weight over horizontal tension). The reported
/// `angles` are those of the actual chain: for `x1 < x0`,
/// `phi_i = pi - atan(alpha + (i - 1/2) beta)`, in `(pi/2, 3pi/2)`.
/// A taut (straight) chain has `beta = 0` and `alpha = (y1 - y0) / |x1 - x0|`
/// (infinite if vertical).
#[derive(Debug, Clone, PartialEq)]
pub struct DiscreteCatenary {
    /// `phi_1..phi_n` (rad), continuous (no 2 pi jumps).
    pub angles: Vec<f64>,
    /// `tan` of the angle of a virtual rod `0` (see the type's doc).
    pub alpha: f64,
    /// Increment of `tan(phi_i)` from rod to rod, `m g / H`.
    pub beta: f64,
    /// `|r_n - p1|`, the distance by which the last joint misses `p1`.
    pub end_error: f64,
    /// Newton iterations taken (0 for a straight chain).
    pub iterations: u64,
}

/// Joint positions `r_0 = p0`, `r_k = p0 + l sum_{j<=k} (cos phi_j, sin phi_j)`,
/// `k = 0..=n`, with `l = length / n` and `n = angles.len()`.
pub fn joints(p0: Point, length: f64, angles: &[f64]) -> Vec<Point> {
    let l = length / angles.len().max(1) as f64;
    let mut r = p0;
    let mut out = Vec::with_capacity(angles.len() + 1);
    out.push(r);
    for phi in angles {
        let (s, c) = phi.sin_cos();
        r = [r[0] + l * c, r[1] + l * s];
        out.push(r);
    }
    out
}

/// Exact static equilibrium of `links` equal rigid rods (length
/// `l = length / links`) pinned at `p0` and `p1`; ends at `p1` to
/// `1e-12 * length`.
///
/// If `|p1 - p0| == length` (within `1e-12` relative) the chain is straight.
/// Otherwise needs `x1 != x0`, `links >= 2` and `length > |p1 - p0|`.
/// Solves `r_n = p1` for `(alpha, beta)` by Newton's method with backtracking,
/// started from the continuous catenary.
pub fn discrete_equilibrium(
    p0: Point,
    p1: Point,
    length: f64,
    links: usize,
) -> Result<DiscreteCatenary, CatenaryError> {
    let distance = check_inputs(p0, p1, length)?;
    if links == 0 {
        return Err(CatenaryError::NoLinks);
    }
    let dx = p1[0] - p0[0];
    let h = p1[1] - p0[1];
    let finish = |angles: Vec<f64>, alpha, beta, iterations| {
        let end = *joints(p0, length, &angles).last().expect("n + 1 joints");
        DiscreteCatenary {
            angles,
            alpha,
            beta,
            end_error: (end[0] - p1[0]).hypot(end[1] - p1[1]),
            iterations,
        }
    };
    if (length - distance).abs() <= TAUT * length {
        let alpha = h / dx.abs();
        return Ok(finish(vec![h.atan2(dx); links], alpha, 0.0, 0));
    }
    if dx == 0.0 {
        return Err(CatenaryError::Vertical { length, distance });
    }
    if links == 1 {
        return Err(CatenaryError::SingleRod { length, distance });
    }
    let d = dx.abs();
    let cat = Catenary::through(p0, [p0[0] + d, p1[1]], length)?;
    let l = length / links as f64;
    let rods = Rods {
        n: links,
        target: [d / l, h / l],
    };
    // Along the catenary tan(phi(s)) = slope_at_p0 + s / a, so the horizontal
    // tension is a / l rod weights and the vertical force at mid-chain is
    // H tan(phi(length / 2)).
    let h0 = cat.a / l;
    let start = [h0, h0 * (cat.slope_at_p0() + 0.5 * length / cat.a)];
    let (sol, iterations, residual) = rods.newton(start, NEWTON_TOL * links as f64);
    let [tension, mid_force] = sol;
    let mirror = dx < 0.0;
    let angles = (0..links)
        .map(|k| {
            let phi = (mid_force + rods.centred(k)).atan2(tension);
            if mirror {
                PI - phi
            } else {
                phi
            }
        })
        .collect();
    let beta = 1.0 / tension;
    let alpha = (mid_force - 0.5 * links as f64) / tension;
    let out = finish(angles, alpha, beta, iterations);
    if !(out.end_error <= END_TOL * length) {
        return Err(CatenaryError::NoConvergence {
            solver: "discrete equilibrium (Newton)",
            iterations,
            residual: residual * l,
        });
    }
    Ok(out)
}

/// The end-point equations in rod units for a chain running towards `+x`,
/// in terms of the forces (in rod weights `W = m g`) that rod `i + 1` exerts
/// on rod `i`: horizontal `H` and vertical `V_i`. Force balance gives
/// `V_i = V_c + i - n/2`, torque balance `tan(phi_i) = (V_{i-1} + V_i) / (2H)`
/// `= (V_c + i - (n+1)/2) / H`, so `beta = 1 / H`.
///
/// The residual `sum_i (cos, sin) phi_i - (d, h) / l` is the gradient of the
/// strictly convex `Phi(H, V_c) = sum_i |(H, V_c + i - (n+1)/2)| - (H, V_c) . (d, h) / l`
/// (it is bounded below iff the chain is longer than the anchor distance), so
/// Newton with a line search on `Phi` converges from any start with `H > 0`.
struct Rods {
    n: usize,
    /// `(d, h) / l`.
    target: [f64; 2],
}

/// Value, gradient (the end-point residual) and Hessian of `Phi`.
struct Eval {
    phi: f64,
    grad: [f64; 2],
    hess: [[f64; 2]; 2],
}

impl Rods {
    /// `i - (n+1)/2` for rod `i = k + 1`.
    fn centred(&self, k: usize) -> f64 {
        k as f64 - 0.5 * (self.n as f64 - 1.0)
    }

    fn eval(&self, [h, vc]: [f64; 2]) -> Eval {
        let mut e = Eval {
            phi: -h * self.target[0] - vc * self.target[1],
            grad: [-self.target[0], -self.target[1]],
            hess: [[0.0; 2]; 2],
        };
        for k in 0..self.n {
            let v = vc + self.centred(k);
            let rho = h.hypot(v);
            let (cos, sin) = (h / rho, v / rho);
            e.phi += rho;
            e.grad[0] += cos;
            e.grad[1] += sin;
            e.hess[0][0] += sin * sin / rho;
            e.hess[0][1] -= sin * cos / rho;
            e.hess[1][1] += cos * cos / rho;
        }
        e.hess[1][0] = e.hess[0][1];
        e
    }

    /// Damped Newton on `Phi` keeping `H > 0`: a step is taken if it satisfies
    /// Armijo on `Phi`, or (where `Phi` is flat to rounding) halves the residual.
    /// Returns the parameters, iterations and final `|residual|` (rod lengths).
    fn newton(&self, mut x: [f64; 2], tol: f64) -> ([f64; 2], u64, f64) {
        let norm = |r: [f64; 2]| r[0].hypot(r[1]);
        let mut e = self.eval(x);
        let mut iterations = 0;
        while norm(e.grad) > tol && iterations < MAX_NEWTON_ITERS {
            let [[a, b], [_, c]] = e.hess;
            let det = a * c - b * b;
            let step = [
                -(c * e.grad[0] - b * e.grad[1]) / det,
                -(a * e.grad[1] - b * e.grad[0]) / det,
            ];
            let slope = step[0] * e.grad[0] + step[1] * e.grad[1];
            if !(step[0].is_finite() && step[1].is_finite() && slope < 0.0) {
                break;
            }
            let mut lambda = 1.0;
            let mut accepted = None;
            for _ in 0..60 {
                let cand = [x[0] + lambda * step[0], x[1] + lambda * step[1]];
                if cand[0] > 0.0 {
                    let ec = self.eval(cand);
                    if ec.phi <= e.phi + 1e-4 * lambda * slope
                        || norm(ec.grad) <= 0.5 * norm(e.grad)
                    {
                        accepted = Some((cand, ec));
                        break;
                    }
                }
                lambda *= 0.5;
            }
            let Some((cand, ec)) = accepted else {
                break;
            };
            (x, e) = (cand, ec);
            iterations += 1;
        }
        (x, iterations, norm(e.grad))
    }
}
