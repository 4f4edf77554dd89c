//! Unequal rods with one rod in compression (`discrete_equilibrium_rods`
//! about a kink): closed forms and the equal rods' solver.

use catenary::{discrete_equilibrium, discrete_equilibrium_rods, joints_rods};

use crate::dist;

/// `values` scaled to sum to their count (the relative form the solver takes).
fn relative(values: &[f64]) -> Vec<f64> {
    let s: f64 = values.iter().sum();
    values.iter().map(|v| v * values.len() as f64 / s).collect()
}

/// Three rods of lengths `a, b, a` and masses `2, 1, 2` on a level span `d`
/// hang as the symmetric trapezoid (by symmetry): joints at
/// `((d - b)/2, -depth)` and `((d + b)/2, -depth)`, `depth^2 = a^2 - ((b - d)/2)^2`.
/// For `d < b` the middle rod is pushed apart: compression, `H < 0`.
#[test]
fn three_unequal_rods_on_a_level_span_form_a_trapezoid() {
    let (a, b) = (1.5, 0.8);
    let lambda = relative(&[a, b, a]);
    let mu = relative(&[2.0, 1.0, 2.0]);
    let length = 2.0 * a + b;
    for d in [0.05, 0.3, 0.7, 0.79, 0.81, 1.2, 2.5] {
        let eq = discrete_equilibrium_rods([0.0, 0.0], [d, 0.0], length, &mu, &lambda).unwrap();
        let r = joints_rods([0.0, 0.0], length, &lambda, &eq.angles);
        let depth = (a * a - ((b - d) / 2.0).powi(2)).sqrt();
        assert!(dist(r[1], [(d - b) / 2.0, -depth]) <= 1e-12, "d={d}: {r:?}");
        assert!(dist(r[2], [(d + b) / 2.0, -depth]) <= 1e-12, "d={d}: {r:?}");
        assert!(dist(r[3], [d, 0.0]) <= 1e-12 * length, "d={d}: {r:?}");
        assert_eq!(eq.tension > 0.0, d > b, "d={d}: H = {}", eq.tension);
    }
}

/// Equal rods given as lists take the profiled solver's kink path; the
/// equal rods' own solver (`rods.rs`, polar about its kink) agrees.
#[test]
fn equal_rods_in_compression_agree_with_the_equal_rods_solver() {
    let n = 7;
    let ones = vec![1.0; n];
    // Rod 3 (0-based) of 7 at the kink (0, 0): within one rod of it.
    for p1 in [[0.4, 0.3], [0.9, -0.2], [0.2, 0.95], [-0.5, 0.1]] {
        let u = discrete_equilibrium([0.0, 0.0], p1, 7.0, n).unwrap();
        assert!(
            u.beta < 0.0,
            "{p1:?}: the equal rods are not in compression"
        );
        let p = discrete_equilibrium_rods([0.0, 0.0], p1, 7.0, &ones, &ones).unwrap();
        assert!(p.tension < 0.0);
        for (x, y) in u.angles.iter().zip(&p.angles) {
            let diff = (x - y).sin().abs() + (1.0 - (x - y).cos()).abs();
            assert!(diff < 1e-10, "{p1:?}: {x} vs {y}");
        }
    }
}
