//! The exact static equilibrium of `n` equal rigid rods pinned at both ends.
//!
//! Angles `phi_i` (rad) are measured from the horizontal, counter-clockwise;
//! rod `i` points from joint `i - 1` to joint `i`. Lengths in input units.

use crate::continuous::Catenary;
use crate::error::{check_inputs, CatenaryError, MAX_LINKS, TAUT};
use crate::rods::Rods;
use crate::Point;
use std::f64::consts::{PI, TAU};

/// Newton stops once the end-point residual is below this times `length`.
const NEWTON_TOL: f64 = 1e-14;
/// Accuracy required of the end point, relative to `length`.
const END_TOL: f64 = 1e-12;

/// Static equilibrium of `links` rods of length `l = length / links`.
///
/// In the frame where the chain runs towards `+x` (the mirror image `x -> -x`
/// when `x1 < x0`), `tan(phi_i) = alpha + (i - 1/2) beta`, `i = 1..=n`, with
/// `beta = m g / H` (rod weight over horizontal tension). The reported
/// `angles` are those of the actual chain: for `x1 < x0`, `phi -> pi - phi`.
///
/// Normally every rod is in tension: `beta > 0` and the angles lie in
/// `(-pi/2, pi/2)` (`(pi/2, 3pi/2)` for `x1 < x0`). Only when the span is
/// shorter than one rod (`|x1 - x0| < l`) and `p1` lies within one rod
/// length of the end of a vertically folded chain (rods `1..j` straight
/// down, the rest straight up) is rod `j` in compression: then `beta < 0`
/// and the other rods lean back beyond the vertical.
///
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
/// `links` is at most [`MAX_LINKS`](crate::MAX_LINKS), checked before
/// anything is allocated; the inputs' bounds are the crate's (see its doc).
///
/// If `|p1 - p0| == length` (within `1e-12` relative) the chain is straight:
/// every angle is `atan2(y1 - y0, |x1 - x0|)` (mirrored to `pi - ...` for
/// `x1 < x0`). Otherwise needs `x1 != x0`, `links >= 2` and
/// `length > |p1 - p0|`, and solves `r_n = p1` for the two force unknowns by
/// damped Newton: on a convex potential started from the continuous
/// catenary, or, next to a configuration with a rod in compression, in polar
/// coordinates about it (see the type's doc).
pub fn discrete_equilibrium(
    p0: Point,
    p1: Point,
    length: f64,
    links: usize,
) -> Result<DiscreteCatenary, CatenaryError> {
    if links > MAX_LINKS {
        return Err(CatenaryError::TooManyLinks { links });
    }
    let distance = check_inputs(p0, p1, length)?;
    if links == 0 {
        return Err(CatenaryError::NoLinks);
    }
    let dx = p1[0] - p0[0];
    let h = p1[1] - p0[1];
    let finish = |angles: Vec<f64>, alpha, beta, iterations| {
        // `joints` returns n + 1 >= 1 points.
        let end = joints(p0, length, &angles).last().copied().unwrap_or(p0);
        DiscreteCatenary {
            angles,
            alpha,
            beta,
            end_error: (end[0] - p1[0]).hypot(end[1] - p1[1]),
            iterations,
        }
    };
    if (length - distance).abs() <= TAUT * length {
        let phi = h.atan2(dx.abs());
        let phi = if dx < 0.0 { PI - phi } else { phi };
        return Ok(finish(vec![phi; links], h / dx.abs(), 0.0, 0));
    }
    if dx == 0.0 {
        return Err(CatenaryError::Vertical { length, distance });
    }
    if links == 1 {
        return Err(CatenaryError::SingleRod { length, distance });
    }
    let d = dx.abs();
    let l = length / links as f64;
    let rods = Rods {
        n: links,
        target: [d / l, h / l],
    };
    let tol = NEWTON_TOL * links as f64;
    // The kink chart where Phi is (nearly) singular; the convex solver elsewhere
    // and as a fallback for a chain in tension.
    let (j, w) = rods.nearest_kink();
    let compressed = w[0].hypot(w[1]) <= 1.0;
    let near = (compressed || w[0].hypot(w[1]) < 2.0) && w[1].abs() < 1.0;
    let sol = near
        .then(|| rods.solve_near_kink(j, tol))
        .filter(|s| compressed || (s.tension > 0.0 && s.residual <= END_TOL * links as f64));
    let sol = match sol {
        Some(sol) => sol,
        None => {
            // Along the catenary tan(phi(s)) = slope_at_p0 + s / a: H = a / l
            // rod weights, V_c = H tan(phi(length / 2)).
            let cat = Catenary::through(p0, [p0[0] + d, p1[1]], length)?;
            let h0 = cat.a / l;
            let start = [h0, h0 * (cat.slope_at_p0() + 0.5 * length / cat.a)];
            rods.solve_in_tension(start, tol)
        }
    };
    let mut angles = sol.angles;
    if dx < 0.0 {
        angles.iter_mut().for_each(|phi| *phi = PI - *phi);
    }
    unwrap(&mut angles);
    let beta = 1.0 / sol.tension;
    let alpha = (sol.mid_force - 0.5 * links as f64) / sol.tension;
    let out = finish(angles, alpha, beta, sol.iterations);
    // (NaN-safe: a NaN end error fails too)
    if out.end_error.is_nan() || out.end_error > END_TOL * length {
        return Err(CatenaryError::NoConvergence {
            solver: "discrete equilibrium (Newton)",
            iterations: sol.iterations,
            residual: sol.residual * l,
        });
    }
    Ok(out)
}

/// Shifts angles by multiples of `2 pi` so that consecutive ones differ by at most `pi`.
fn unwrap(angles: &mut [f64]) {
    for k in 1..angles.len() {
        let prev = angles[k - 1];
        angles[k] -= TAU * ((angles[k] - prev) / TAU).round();
    }
}
