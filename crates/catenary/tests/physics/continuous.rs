//! The continuous catenary against its defining properties.

use super::{dist, CASES};
use catenary::Catenary;

/// The textbook form `a cosh((x - x0)/a) + c`, evaluated independently of `Catenary::y`.
fn raw_y(cat: &Catenary, x: f64) -> f64 {
    cat.a * ((x - cat.x0) / cat.a).cosh() + cat.c
}

/// Arc length from `xa` to `xb` by composite Simpson on `sqrt(1 + y'^2)`.
fn simpson_length(cat: &Catenary, xa: f64, xb: f64) -> f64 {
    let m = 20_000;
    let h = (xb - xa) / m as f64;
    let g = |x: f64| (1.0 + ((x - cat.x0) / cat.a).sinh().powi(2)).sqrt();
    let inner: f64 = (1..m)
        .map(|k| g(xa + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    h / 3.0 * (g(xa) + inner + g(xb))
}

#[test]
fn known_parameter_a() {
    let cat = Catenary::through([0.0, 0.0], [5.0, 1.0], 6.0).unwrap();
    assert!((cat.a - 2.447359627).abs() < 1e-9, "a = {}", cat.a);
    // and a itself satisfies 2 a sinh(d / 2a) = sqrt(L^2 - h^2)
    let lhs = 2.0 * cat.a * (5.0 / (2.0 * cat.a)).sinh();
    assert!((lhs - 35f64.sqrt()).abs() < 1e-13 * 6.0);
}

#[test]
fn passes_through_both_anchors() {
    for (p0, p1, l) in CASES {
        let cat = Catenary::through(p0, p1, l).unwrap();
        for p in [p0, p1] {
            assert!((cat.y(p[0]) - p[1]).abs() <= 1e-12 * l, "{p0:?} {p1:?} {l}");
            assert!((raw_y(&cat, p[0]) - p[1]).abs() <= 1e-12 * l * (1.0 + cat.a / l));
        }
        // y() agrees with the textbook form everywhere in the span
        for k in 0..=10 {
            let x = p0[0] + (p1[0] - p0[0]) * k as f64 / 10.0;
            assert!((cat.y(x) - raw_y(&cat, x)).abs() <= 1e-11 * l * (1.0 + cat.a / l));
        }
    }
}

#[test]
fn arc_length_between_anchors_is_length() {
    for (p0, p1, l) in CASES {
        let cat = Catenary::through(p0, p1, l).unwrap();
        let sign = (p1[0] - p0[0]).signum();
        let closed = cat.arc_length(p0[0], p1[0]);
        assert!((closed - sign * l).abs() <= 1e-10 * l, "{closed} vs {l}");
        let quad = simpson_length(&cat, p0[0], p1[0]);
        assert!((quad - sign * l).abs() <= 1e-10 * l, "{quad} vs {l}");
    }
}

#[test]
fn extreme_chains_are_solved_without_overflow() {
    for (p1, l) in [
        ([3.0, 4.0], 5.0 * (1.0 + 1e-10)),
        ([3.0, 4.0], 5.0e6),
        ([1e-6, 1.0], 2.0),
        ([1.0, 0.0], 1e12),
    ] {
        let p0 = [0.0, 0.0];
        let cat = Catenary::through(p0, p1, l).unwrap();
        assert!(cat.a.is_finite() && cat.a > 0.0);
        assert!((cat.y(p1[0]) - p1[1]).abs() <= 1e-12 * l, "{p1:?} {l}");
        assert!(
            (cat.arc_length(0.0, p1[0]) - l).abs() <= 1e-10 * l,
            "{p1:?} {l}"
        );
    }
}

#[test]
fn symmetric_span_has_vertex_at_mid_span() {
    let cat = Catenary::through([1.0, 2.0], [7.0, 2.0], 10.0).unwrap();
    assert!((cat.x0 - 4.0).abs() < 1e-12);
    let v = cat.vertex();
    assert!((v[1] - raw_y(&cat, 4.0)).abs() < 1e-12 && v[1] < 2.0);
    assert!((v[1] - (cat.a + cat.c)).abs() < 1e-12);
    assert_eq!(cat.lowest_point(), v);
    // the vertex is the lowest point: neighbours are higher
    assert!(cat.y(3.9) > v[1] && cat.y(4.1) > v[1]);
}

#[test]
fn lowest_point_is_lower_anchor_when_vertex_outside_span() {
    // nearly taut and steep: the vertex lies left of the span
    let cat = Catenary::through([0.0, 0.0], [1.0, 3.0], 3.2).unwrap();
    assert!(cat.x0 < 0.0);
    assert_eq!(cat.lowest_point(), [0.0, 0.0]);
    let cat = Catenary::through([0.0, 3.0], [1.0, 0.0], 3.2).unwrap();
    assert!(cat.x0 > 1.0);
    assert_eq!(cat.lowest_point(), [1.0, 0.0]);
}

#[test]
fn mirrored_p1_gives_mirrored_curve() {
    for (p0, p1, l) in CASES {
        let m1 = [2.0 * p0[0] - p1[0], p1[1]];
        let cat = Catenary::through(p0, p1, l).unwrap();
        let mir = Catenary::through(p0, m1, l).unwrap();
        assert!((cat.a - mir.a).abs() <= 1e-12 * cat.a);
        assert!((mir.x0 - (2.0 * p0[0] - cat.x0)).abs() <= 1e-10 * (l + cat.a));
        for k in 0..=10 {
            let x = p0[0] + (p1[0] - p0[0]) * k as f64 / 10.0;
            assert!((mir.y(2.0 * p0[0] - x) - cat.y(x)).abs() <= 1e-12 * l);
            let s = l * k as f64 / 10.0;
            let (p, q) = (cat.point_at_arc_length(s), mir.point_at_arc_length(s));
            assert!(dist([2.0 * p0[0] - p[0], p[1]], q) <= 1e-12 * l);
        }
    }
}

#[test]
fn point_at_arc_length_walks_from_p0_to_p1() {
    for (p0, p1, l) in CASES {
        let cat = Catenary::through(p0, p1, l).unwrap();
        assert!(dist(cat.point_at_arc_length(0.0), p0) <= 1e-12 * l);
        assert!(
            dist(cat.point_at_arc_length(l), p1) <= 1e-11 * l,
            "{p0:?} {p1:?}"
        );
        let sign = (p1[0] - p0[0]).signum();
        for k in 1..10 {
            let s = l * k as f64 / 10.0;
            let p = cat.point_at_arc_length(s);
            assert!((cat.y(p[0]) - p[1]).abs() <= 1e-12 * l);
            assert!((sign * cat.arc_length(p0[0], p[0]) - s).abs() <= 1e-11 * l);
        }
    }
}
