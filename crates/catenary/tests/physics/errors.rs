//! Each invalid input gives its own error, whose message names the field.

use catenary::{discrete_equilibrium, Catenary, CatenaryError, Input};

fn both(p0: [f64; 2], p1: [f64; 2], l: f64, n: usize) -> [CatenaryError; 2] {
    [
        Catenary::through(p0, p1, l).unwrap_err(),
        discrete_equilibrium(p0, p1, l, n).unwrap_err(),
    ]
}

fn starts_with(e: &CatenaryError, field: &str) {
    let text = e.to_string();
    assert!(text.starts_with(&format!("{field}: ")), "{text}");
    assert!(!text.contains('\n'));
    // The same, as fields: the input, and the reason after its name.
    assert_eq!(e.input().map_or("solver", Input::as_str), field);
    assert_eq!(text, format!("{field}: {}", e.reason()));
}

#[test]
fn non_finite_inputs_name_their_field() {
    let nan = f64::NAN;
    for (p0, p1, l, field) in [
        ([nan, 0.0], [1.0, 0.0], 2.0, "p0"),
        ([0.0, 0.0], [1.0, f64::INFINITY], 2.0, "p1"),
        ([0.0, 0.0], [1.0, 0.0], nan, "length"),
        ([0.0, 0.0], [1.0, 0.0], f64::INFINITY, "length"),
    ] {
        for e in both(p0, p1, l, 5) {
            assert!(matches!(e, CatenaryError::NonFinite { input, .. } if input.as_str() == field));
            starts_with(&e, field);
        }
    }
}

#[test]
fn non_positive_length() {
    for l in [0.0, -3.0] {
        for e in both([0.0, 0.0], [1.0, 0.0], l, 5) {
            assert_eq!(e, CatenaryError::NonPositiveLength { length: l });
            starts_with(&e, "length");
        }
    }
}

#[test]
fn zero_links() {
    let e = discrete_equilibrium([0.0, 0.0], [1.0, 0.0], 2.0, 0).unwrap_err();
    assert_eq!(e, CatenaryError::NoLinks);
    starts_with(&e, "links");
}

#[test]
fn chain_shorter_than_the_anchor_distance() {
    for e in both([0.0, 0.0], [5.0, 1.0], 4.0, 5) {
        assert!(matches!(e, CatenaryError::TooShort { .. }));
        starts_with(&e, "length");
        assert!(e.to_string().contains("5.099"), "{e}");
    }
}

#[test]
fn taut_chain_has_no_continuous_catenary() {
    let e = Catenary::through([0.0, 0.0], [3.0, 4.0], 5.0).unwrap_err();
    assert!(matches!(e, CatenaryError::TooShort { .. }));
    starts_with(&e, "length");
    assert!(e.to_string().contains("stretched"));
    // but the discrete equilibrium is the straight chain
    assert!(discrete_equilibrium([0.0, 0.0], [3.0, 4.0], 5.0, 3).is_ok());
}

#[test]
fn vertical_anchors_point_to_the_folded_start() {
    for e in both([1.0, 0.0], [1.0, -3.0], 5.0, 6) {
        assert!(matches!(e, CatenaryError::Vertical { .. }));
        starts_with(&e, "p1");
        let text = e.to_string();
        assert!(
            text.contains("unstable equilibrium") && text.contains("folded"),
            "{text}"
        );
    }
}

#[test]
fn single_rod_must_be_taut() {
    let e = discrete_equilibrium([0.0, 0.0], [1.0, 0.0], 2.0, 1).unwrap_err();
    assert!(matches!(e, CatenaryError::SingleRod { .. }));
    starts_with(&e, "links");
}

#[test]
fn no_convergence_is_one_line_with_the_solver_its_iterations_and_residual() {
    // Neither solver fails on any input the other tests reach, so the error
    // is built here; what is checked is the whole line a user would read.
    let e = CatenaryError::NoConvergence {
        solver: "discrete equilibrium (Newton)",
        iterations: 100,
        residual: 1.5e-9,
    };
    starts_with(&e, "solver");
    assert_eq!(
        e.to_string(),
        "solver: discrete equilibrium (Newton) did not converge after 100 iterations \
         (residual 1.5e-9)"
    );
}

/// The next float above `x`, and the one below (`x > 0`).
fn up(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}
fn down(x: f64) -> f64 {
    f64::from_bits(x.to_bits() - 1)
}

#[test]
fn huge_finite_inputs_name_the_input_that_is_out_of_range() {
    use catenary::{MAX_MAGNITUDE, MIN_LENGTH};
    assert_eq!((MAX_MAGNITUDE, MIN_LENGTH), (1e150, 1e-150));
    // The two cases: |P1 - P0| overflowed to inf and was blamed on
    // a finite p1; length + distance overflowed and the root finder's
    // "did not converge after 0 iterations" leaked out.
    for (p0, p1, l, field) in [
        ([-1e308, 0.0], [1e308, 0.0], 1.7e308, "p0"),
        ([0.0, 0.0], [1e308, 1e308], 1.7e308, "p1"),
        ([-1e308, 0.0], [1e308, 1e308], 1.7e308, "p0"),
        ([0.0, 0.0], [1.0, 0.0], 1.7e308, "length"),
        ([0.0, 0.0], [1e-300, 0.0], 2e-300, "length"),
        ([0.0, up(MAX_MAGNITUDE)], [1.0, 0.0], 2.0, "p0"),
        ([0.0, 0.0], [-up(MAX_MAGNITUDE), 0.0], 2.0, "p1"),
        ([0.0, 0.0], [1e-151, 0.0], down(MIN_LENGTH), "length"),
    ] {
        for e in both(p0, p1, l, 5) {
            assert!(
                matches!(e, CatenaryError::OutOfRange { input, .. } if input.as_str() == field),
                "{e}"
            );
            starts_with(&e, field);
            let text = e.to_string();
            assert!(
                !text.contains("inf") && !text.contains("converge"),
                "{text}"
            );
            assert!(text.contains("1e150"), "{text}");
        }
    }
}

#[test]
fn the_bounds_themselves_are_accepted_and_solved() {
    use catenary::{discrete_equilibrium, MAX_MAGNITUDE, MIN_LENGTH};
    // Coordinates at +-1e150 and a length of 1e150.
    let (p0, p1, l) = (
        [-MAX_MAGNITUDE, 0.0],
        [-0.5 * MAX_MAGNITUDE, 0.0],
        MAX_MAGNITUDE,
    );
    let c = Catenary::through(p0, p1, l).unwrap();
    assert!(crate::dist([c.p1[0], c.y(c.p1[0])], p1) <= 1e-9 * l);
    let d = discrete_equilibrium(p0, p1, l, 7).unwrap();
    assert!(d.end_error <= 1e-12 * l);
    // The shortest length.
    let (p0, p1, l) = ([0.0, 0.0], [0.5 * MIN_LENGTH, 0.0], MIN_LENGTH);
    assert!(Catenary::through(p0, p1, l).is_ok());
    let d = discrete_equilibrium(p0, p1, l, 7).unwrap();
    assert!(d.end_error <= 1e-12 * l);
}

#[test]
fn the_same_chain_at_every_scale_within_the_bounds_is_the_same_shape() {
    // The equations are scale-free: scaling anchors and length by s scales
    // the solution by s, at every s the bounds admit.
    for s in [1e-148, 1e-100, 1e-10, 1.0, 1e10, 1e100, 1e148] {
        for &(p0, p1, l) in &crate::CASES {
            let sc = |p: [f64; 2]| [p[0] * s, p[1] * s];
            let c = Catenary::through(sc(p0), sc(p1), l * s).unwrap();
            let c1 = Catenary::through(p0, p1, l).unwrap();
            assert!(
                (c.a / (c1.a * s) - 1.0).abs() < 1e-9,
                "s = {s}: {} vs {}",
                c.a,
                c1.a
            );
            let d = discrete_equilibrium(sc(p0), sc(p1), l * s, 9).unwrap();
            let d1 = discrete_equilibrium(p0, p1, l, 9).unwrap();
            assert!(d.end_error <= 1e-12 * l * s, "s = {s}");
            for (a, b) in d.angles.iter().zip(&d1.angles) {
                assert!((a - b).abs() < 1e-9, "s = {s}: {a} vs {b}");
            }
        }
    }
}

#[test]
fn a_count_of_links_past_the_cap_is_refused_before_allocation() {
    use catenary::MAX_LINKS;
    assert_eq!(MAX_LINKS, 1_000_000);
    // usize::MAX rods would abort on allocation (capacity overflow): the
    // cap is checked first, taut chain or not.
    for links in [MAX_LINKS + 1, usize::MAX] {
        for (p1, l) in [([3.0, 4.0], 5.0), ([3.0, 0.0], 6.0)] {
            let e = discrete_equilibrium([0.0, 0.0], p1, l, links).unwrap_err();
            assert_eq!(e, CatenaryError::TooManyLinks { links });
            starts_with(&e, "links");
            assert!(e.to_string().contains("1..=1000000"), "{e}");
        }
    }
    // The cap itself is solved.
    let d = discrete_equilibrium([0.0, 0.0], [3.0, 0.0], 6.0, MAX_LINKS).unwrap();
    assert_eq!(d.angles.len(), MAX_LINKS);
    assert!(d.end_error <= 1e-12 * 6.0);
}
