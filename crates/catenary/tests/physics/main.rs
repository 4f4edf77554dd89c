//! Physics tests of the `catenary` crate: closed forms, the discrete
//! equilibrium, the error cases and random anchors.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "test code, helpers included: a failed unwrap is a failed test"
)]

mod continuous;
mod discrete;
mod errors;
mod profiled_compression;
mod random;

use catenary::Point;

/// `|p - q|`.
pub fn dist(p: Point, q: Point) -> f64 {
    (p[0] - q[0]).hypot(p[1] - q[1])
}

/// Anchor pairs and lengths covering either anchor higher, `P1` left of `P0`,
/// nearly taut and very slack chains.
pub const CASES: [(Point, Point, f64); 8] = [
    ([0.0, 0.0], [5.0, 1.0], 6.0),
    ([0.0, 0.0], [5.0, -1.0], 6.0),
    ([2.0, 3.0], [-4.0, 1.0], 9.0),
    ([2.0, 3.0], [-4.0, 5.0], 7.0),
    ([-1.0, 0.5], [3.0, 0.5], 4.000001),
    ([0.0, 0.0], [1.0, 0.0], 50.0),
    ([10.0, -3.0], [10.5, 4.0], 7.5),
    ([0.0, 0.0], [-3.0, -4.0], 5.2),
];

/// 2D cross product.
pub fn cross(u: Point, v: Point) -> f64 {
    u[0] * v[1] - u[1] * v[0]
}

/// Statics from the joints alone: rod weight `W = 1`, force `T_k = (H, V_k)`
/// exerted on rod `k` by rod `k + 1`, `V_k = V_0 + k W` (force balance:
/// uniform vertical differences). Rod `i` has zero net torque about its
/// centre iff `u_i x (T_{i-1} + T_i) = 0`, linear in `(V_0, H)`: fit them by
/// least squares over all rods and return `H` and the largest torque left,
/// relative to `l` times the largest force.
pub fn torque_check(r: &[Point]) -> (f64, f64) {
    let u: Vec<Point> = r
        .windows(2)
        .map(|w| [w[1][0] - w[0][0], w[1][1] - w[0][1]])
        .collect();
    // torque_i = 2 u_x V0 - 2 u_y H + u_x (2i - 1), i = 1..=n
    let rows: Vec<([f64; 2], f64)> = u
        .iter()
        .enumerate()
        .map(|(k, ui)| ([2.0 * ui[0], -2.0 * ui[1]], ui[0] * (2.0 * k as f64 + 1.0)))
        .collect();
    let (mut a, mut b) = ([[0.0; 2]; 2], [0.0; 2]);
    for (row, rhs) in &rows {
        for p in 0..2 {
            b[p] -= row[p] * rhs;
            for q in 0..2 {
                a[p][q] += row[p] * row[q];
            }
        }
    }
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let v0 = (b[0] * a[1][1] - a[0][1] * b[1]) / det;
    let h = (a[0][0] * b[1] - a[1][0] * b[0]) / det;
    let n = u.len() as f64;
    let force = h.hypot(v0.abs().max((v0 + n).abs()));
    let len = u[0][0].hypot(u[0][1]);
    let worst = rows
        .iter()
        .map(|(row, rhs)| (row[0] * v0 + row[1] * h + rhs).abs() / (2.0 * len * force))
        .fold(0.0, f64::max);
    (h, worst)
}
