//! Physics tests of the `catenary` crate: closed forms, the discrete
//! equilibrium, the error cases and random anchors.

mod continuous;
mod discrete;
mod errors;
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
