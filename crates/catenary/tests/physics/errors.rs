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
