//! The exact static equilibrium of rods of unequal mass and length pinned
//! at both ends (the tapered chain's catenary start).
//!
//! Rod `i` (0-based, from `p0`) has mass `mu_i` and length `lambda_i` in
//! units of the mean rod (`m = M / n`, `l = L / n`). Take the chain's end
//! force at `p1` as `(H, V)` mean-rod weights (the frame in which the chain
//! runs towards `+x`). Rod `i` carries the weight `W_i = S_{i+1} + mu_i / 2`
//! beyond its centre (`S_{i+1}` the rods after it), and its moment balance
//! about its centre gives
//!
//! ```text
//! tan(phi_i) = (V - W_i) / H.
//! ```
//!
//! The end conditions `sum_i lambda_i (cos phi_i, sin phi_i) = (d, h) / l`
//! are the gradient of the convex function
//! `Psi(H, V) = sum_i lambda_i sqrt(H^2 + (V - W_i)^2) - (d H + h V) / l`
//! (the complementary energy), so the equilibrium is its minimum, found by
//! Newton's method with a backtracking line search on `Psi` (globally
//! convergent on a convex function). Equal rods give the `alpha + (i - 1/2) beta`
//! law of [`crate::discrete_equilibrium`], which supplies the start.

use crate::error::{check_inputs, CatenaryError, MAX_LINKS, TAUT};
use crate::Point;
use std::f64::consts::PI;

/// Newton's cap.
const MAX_ITERATIONS: u64 = 200;
/// Accuracy required of the end point, relative to the length.
const END_TOL: f64 = 1e-12;

/// A profiled chain's equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfiledCatenary {
    /// `phi_1..phi_n` (rad).
    pub angles: Vec<f64>,
    /// The horizontal end force `H` in mean-rod weights (`m g`).
    pub tension: f64,
    /// The vertical end force at `p1`, `V`, in mean-rod weights.
    pub vertical: f64,
    /// `|r_n - p1|`.
    pub end_error: f64,
    /// Newton iterations taken.
    pub iterations: u64,
}

/// Joint positions of rods of lengths `lambda_i length / n` at `angles`.
pub fn joints_rods(p0: Point, length: f64, lambda: &[f64], angles: &[f64]) -> Vec<Point> {
    let l = length / angles.len().max(1) as f64;
    let mut r = p0;
    let mut out = Vec::with_capacity(angles.len() + 1);
    out.push(r);
    for (phi, lam) in angles.iter().zip(lambda) {
        let (s, c) = phi.sin_cos();
        r = [r[0] + lam * l * c, r[1] + lam * l * s];
        out.push(r);
    }
    out
}

/// The equilibrium of rods of relative masses `mu` and lengths `lambda`
/// (each summing to `n = mu.len()`) pinned at `p0` and `p1`, total length
/// `length`; ends at `p1` to `1e-12 * length`. Needs a slack chain
/// (`length > |p1 - p0|`, `x1 != x0`, at least 2 rods); a taut chain is
/// straight. Every rod is in tension (`tension > 0`) unless `p1` lies
/// within rod `j`'s length of the end of the chain folded with rods
/// `0..j` straight down and the rest straight up: then rod `j` is in
/// compression, `tension < 0` (`profiled_kink.rs`), as for equal rods.
pub fn discrete_equilibrium_rods(
    p0: Point,
    p1: Point,
    length: f64,
    mu: &[f64],
    lambda: &[f64],
) -> Result<ProfiledCatenary, CatenaryError> {
    let links = mu.len();
    if links > MAX_LINKS {
        return Err(CatenaryError::TooManyLinks { links });
    }
    let distance = check_inputs(p0, p1, length)?;
    if links == 0 || lambda.len() != links {
        return Err(CatenaryError::NoLinks);
    }
    let dx = p1[0] - p0[0];
    let h = p1[1] - p0[1];
    let l = length / links as f64;
    let finish = |mut angles: Vec<f64>, tension, vertical, iterations| {
        if dx < 0.0 {
            angles.iter_mut().for_each(|phi| *phi = PI - *phi);
        }
        let end = joints_rods(p0, length, lambda, &angles)
            .last()
            .copied()
            .unwrap_or(p0);
        ProfiledCatenary {
            angles,
            tension,
            vertical,
            end_error: (end[0] - p1[0]).hypot(end[1] - p1[1]),
            iterations,
        }
    };
    if (length - distance).abs() <= TAUT * length {
        let phi = h.atan2(dx.abs());
        return Ok(finish(vec![phi; links], f64::INFINITY, 0.0, 0));
    }
    // The equal rods' solution on the same span: the start (and the checks
    // of a vertical span and of one rod).
    let uniform = crate::discrete_equilibrium(p0, p1, length, links)?;
    let n = links as f64;
    // Equal rods in compression (beta < 0) start the convex solve at H > 0.
    let (mut big_h, mut v) = ((1.0 / uniform.beta).abs(), n + uniform.alpha / uniform.beta);
    // W_i = S_{i+1} + mu_i / 2.
    let mut below = 0.0;
    let mut weight = vec![0.0; links];
    for i in (0..links).rev() {
        weight[i] = below + 0.5 * mu[i];
        below += mu[i];
    }
    let target = [dx.abs() / l, h / l];
    // A rod in compression (the end within a rod of a folded chain's end),
    // or next to it: Newton about that kink (`profiled_kink.rs`).
    let (kink, ratio) = crate::profiled_kink::nearest_kink(lambda, target);
    let about_kink = || {
        crate::profiled_kink::solve_near_kink(lambda, &weight, target, kink, 1e-14 * n)
            .map(|k| finish(k.angles, k.tension, k.vertical, k.iterations))
    };
    if ratio <= 1.0 {
        return match about_kink() {
            Some(out) if out.end_error <= END_TOL * length => Ok(out),
            other => Err(CatenaryError::NoConvergence {
                solver: "discrete equilibrium of unequal rods, one in compression (Newton)",
                iterations: other.as_ref().map_or(0, |o| o.iterations),
                residual: other.map_or(f64::NAN, |o| o.end_error),
            }),
        };
    }
    let psi = |hh: f64, vv: f64| -> f64 {
        let s: f64 = weight
            .iter()
            .zip(lambda)
            .map(|(&wi, &lam)| lam * hh.hypot(vv - wi))
            .sum();
        s - target[0] * hh - target[1] * vv
    };
    let mut iterations = 0;
    loop {
        // Gradient (the end residual) and Hessian of Psi.
        let (mut gx, mut gy) = (-target[0], -target[1]);
        let (mut hxx, mut hxy, mut hyy) = (0.0, 0.0, 0.0);
        for (&wi, &lam) in weight.iter().zip(lambda) {
            let t = v - wi;
            let rho = big_h.hypot(t);
            gx += lam * big_h / rho;
            gy += lam * t / rho;
            let k = lam / (rho * rho * rho);
            hxx += k * t * t;
            hxy -= k * big_h * t;
            hyy += k * big_h * big_h;
        }
        if gx.hypot(gy) <= 1e-14 * n || iterations >= MAX_ITERATIONS {
            break;
        }
        iterations += 1;
        let det = hxx * hyy - hxy * hxy;
        let (sx, sy) = (-(hyy * gx - hxy * gy) / det, -(hxx * gy - hxy * gx) / det);
        if !(sx.is_finite() && sy.is_finite()) {
            break;
        }
        // Backtrack until Psi decreases (Armijo) or, where Psi's changes
        // are below its rounding (next to the minimum), the end residual
        // does (the Newton step descends both); H stays > 0.
        let p = psi(big_h, v);
        let slope = gx * sx + gy * sy;
        let g0 = gx.hypot(gy);
        let mut step = 1.0;
        let mut moved = false;
        for _ in 0..60 {
            let (hn, vn) = (big_h + step * sx, v + step * sy);
            let better = hn > 0.0
                && (psi(hn, vn) <= p + 1e-4 * step * slope
                    || gradient_norm(&weight, lambda, target, hn, vn) < (1.0 - 1e-4 * step) * g0);
            if better {
                (big_h, v) = (hn, vn);
                moved = true;
                break;
            }
            step *= 0.5;
        }
        if !moved {
            break;
        }
    }
    let angles: Vec<f64> = weight.iter().map(|&wi| (v - wi).atan2(big_h)).collect();
    let mut out = finish(angles, big_h, v, iterations);
    // Next to a kink Psi is nearly singular: the polar chart there.
    if (out.end_error.is_nan() || out.end_error > END_TOL * length) && ratio < 2.0 {
        if let Some(k) = about_kink().filter(|k| k.tension > 0.0 && k.end_error <= END_TOL * length)
        {
            out = k;
        }
    }
    if out.end_error.is_nan() || out.end_error > END_TOL * length {
        return Err(CatenaryError::NoConvergence {
            solver: "discrete equilibrium of unequal rods (Newton)",
            iterations,
            residual: out.end_error,
        });
    }
    Ok(out)
}

/// `|grad Psi(H, V)|`: the end point's miss in mean-rod lengths.
fn gradient_norm(weight: &[f64], lambda: &[f64], target: [f64; 2], big_h: f64, v: f64) -> f64 {
    let (mut gx, mut gy) = (-target[0], -target[1]);
    for (&wi, &lam) in weight.iter().zip(lambda) {
        let rho = big_h.hypot(v - wi);
        gx += lam * big_h / rho;
        gy += lam * (v - wi) / rho;
    }
    gx.hypot(gy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_rods_give_the_equal_rods_equilibrium() {
        let (p0, p1) = ([0.0, 0.0], [3.0, 0.0]);
        let u = crate::discrete_equilibrium(p0, p1, 6.0, 20).unwrap();
        let p = discrete_equilibrium_rods(p0, p1, 6.0, &[1.0; 20], &[1.0; 20]).unwrap();
        for (a, b) in u.angles.iter().zip(&p.angles) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }

    #[test]
    fn a_tapered_chain_ends_at_p1_both_ways() {
        let n = 30;
        let mu: Vec<f64> = (0..n)
            .map(|i| 10.0 - 9.0 * (i as f64 + 0.5) / n as f64)
            .collect();
        let s: f64 = mu.iter().sum();
        let mu: Vec<f64> = mu.iter().map(|m| m * n as f64 / s).collect();
        let lam = vec![1.0; n];
        let (p0, p1) = ([0.0, 0.0], [3.0, 0.0]);
        let p = discrete_equilibrium_rods(p0, p1, 6.0, &mu, &lam).unwrap();
        assert!(p.end_error <= 1e-12 * 6.0);
        // Mirrored span: the mirror image.
        let m = discrete_equilibrium_rods(p1, p0, 6.0, &mu, &lam).unwrap();
        assert!(m.end_error <= 1e-12 * 6.0);
        assert!(p.iterations < 50 && m.iterations < 50);
    }
}
