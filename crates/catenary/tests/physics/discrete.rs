//! The discrete equilibrium of n rods against statics and the continuum limit.

use super::{cross, dist, torque_check, CASES};
use catenary::{discrete_equilibrium, joints, Catenary, Point};
use std::f64::consts::PI;

const LINKS: [usize; 6] = [2, 3, 10, 50, 301, 2000];

#[test]
fn ends_at_p1() {
    for (p0, p1, l) in CASES {
        for n in LINKS {
            let eq = discrete_equilibrium(p0, p1, l, n).unwrap();
            let r = joints(p0, l, &eq.angles);
            assert_eq!(r.len(), n + 1);
            assert_eq!(r[0], p0);
            let miss = dist(r[n], p1);
            assert!(miss <= 1e-12 * l, "{p0:?} {p1:?} {l} n={n}: {miss:e}");
            assert!((eq.end_error - miss).abs() <= 1e-15 * l);
        }
    }
}

#[test]
fn is_a_static_equilibrium() {
    for (p0, p1, l) in CASES {
        for n in [3, 10, 50, 301] {
            let eq = discrete_equilibrium(p0, p1, l, n).unwrap();
            let (h, worst) = torque_check(&joints(p0, l, &eq.angles));
            assert!(worst < 1e-12, "{p0:?} {p1:?} {l} n={n}: torque {worst:e}");
            // beta = W / H with W = 1, H measured towards p1
            let sign = (p1[0] - p0[0]).signum();
            assert!((eq.beta - sign / h).abs() <= 1e-9 * eq.beta.abs());
            // a span of at least one rod: every rod in tension (hanging, not an arch)
            if (p1[0] - p0[0]).abs() >= l / n as f64 {
                assert!(eq.beta > 0.0);
            }
        }
    }
}

#[test]
fn torque_check_rejects_a_non_equilibrium() {
    // a chain through the continuous catenary's points at arc length k l is not exact
    let (p0, p1, l, n) = ([0.0, 0.0], [5.0, 1.0], 6.0, 10);
    let cat = Catenary::through(p0, p1, l).unwrap();
    let r: Vec<Point> = (0..=n)
        .map(|k| cat.point_at_arc_length(l * k as f64 / n as f64))
        .collect();
    assert!(torque_check(&r).1 > 1e-6);
}

#[test]
fn hangs_below_the_chord() {
    for (p0, p1, l) in CASES {
        let eq = discrete_equilibrium(p0, p1, l, 40).unwrap();
        let c = [p1[0] - p0[0], p1[1] - p0[1]];
        let r = joints(p0, l, &eq.angles);
        for q in &r[1..40] {
            assert!(cross(c, [q[0] - p0[0], q[1] - p0[1]]) * c[0].signum() < 0.0);
        }
    }
}

#[test]
fn tangents_follow_alpha_beta() {
    for (p0, p1, l) in CASES {
        let eq = discrete_equilibrium(p0, p1, l, 25).unwrap();
        let sign = (p1[0] - p0[0]).signum();
        for (i, phi) in eq.angles.iter().enumerate() {
            let t = eq.alpha + (i as f64 + 0.5) * eq.beta;
            assert!((sign * phi.tan() - t).abs() <= 1e-10 * (1.0 + t.abs()));
        }
    }
}

/// Consecutive rods turn by less than pi (no 2 pi jumps); with every rod in
/// tension each points towards p1's side, `cos(phi) * (x1 - x0) > 0`.
#[test]
fn angles_are_continuous_and_in_range() {
    for (p0, p1, l) in CASES {
        for n in LINKS {
            let eq = discrete_equilibrium(p0, p1, l, n).unwrap();
            let (lo, hi) = if p1[0] > p0[0] {
                (-PI / 2.0, PI / 2.0)
            } else {
                (PI / 2.0, 1.5 * PI)
            };
            if eq.beta > 0.0 {
                assert!(eq.angles.iter().all(|&a| lo < a && a < hi));
            } else {
                assert!(lo - PI < eq.angles[0] && eq.angles[0] < hi + PI);
            }
            assert!(eq.angles.windows(2).all(|w| (w[1] - w[0]).abs() < PI));
        }
    }
}

#[test]
fn mirrored_p1_gives_mirrored_chain() {
    for (p0, p1, l) in CASES {
        let a = discrete_equilibrium(p0, p1, l, 33).unwrap();
        let b = discrete_equilibrium(p0, [2.0 * p0[0] - p1[0], p1[1]], l, 33).unwrap();
        assert_eq!((a.alpha, a.beta), (b.alpha, b.beta));
        for (x, y) in a.angles.iter().zip(&b.angles) {
            assert!((x + y - PI).abs() < 1e-14);
        }
    }
}

#[test]
fn taut_chain_is_straight() {
    for (p1, n) in [
        ([3.0, 4.0], 7),
        ([-3.0, 4.0], 1),
        ([-3.0, -4.0], 3),
        ([0.0, -5.0], 4),
        ([5.0, 0.0], 50),
    ] {
        let eq = discrete_equilibrium([0.0, 0.0], p1, 5.0, n).unwrap();
        assert_eq!(eq.angles.len(), n);
        let first = eq.angles[0];
        assert!(eq.angles.iter().all(|&a| a == first));
        assert!((first.cos() * 5.0 - p1[0]).abs() < 1e-15 * 5.0);
        assert!((first.sin() * 5.0 - p1[1]).abs() < 1e-15 * 5.0);
        if p1[0] < 0.0 {
            assert!(PI / 2.0 < first && first < 1.5 * PI);
        }
        assert!(eq.end_error <= 1e-14 * 5.0, "{p1:?}: {:e}", eq.end_error);
        assert_eq!((eq.beta, eq.iterations), (0.0, 0));
    }
}

#[test]
fn two_rods_meet_at_the_lower_circle_intersection() {
    for (p0, p1, l) in CASES.into_iter().chain([
        ([0.0, 0.0], [0.05, 3.2247960820488197], 3.26),
        ([0.0, 0.0], [-0.3, 1.0], 2.5),
        ([0.0, 0.0], [1e-3, -1.0], 1.7),
    ]) {
        let eq = discrete_equilibrium(p0, p1, l, 2).unwrap();
        let j = joints(p0, l, &eq.angles)[1];
        let mid = [(p0[0] + p1[0]) / 2.0, (p0[1] + p1[1]) / 2.0];
        let dd = dist(p0, p1);
        let off = ((l / 2.0).powi(2) - (dd / 2.0).powi(2)).sqrt() / dd;
        let perp = [-(p1[1] - p0[1]) * off, (p1[0] - p0[0]) * off];
        let (a, b) = (
            [mid[0] + perp[0], mid[1] + perp[1]],
            [mid[0] - perp[0], mid[1] - perp[1]],
        );
        let lower = if a[1] < b[1] { a } else { b };
        assert!(
            dist(j, lower) <= 1e-12 * l,
            "{p0:?} {p1:?} {l}: {j:?} vs {lower:?}"
        );
    }
}

/// Three rods on a level span `d`: the symmetric trapezoid with the middle rod
/// level at depth `sqrt(l^2 - ((l - d)/2)^2)`. For `d < l` the legs lean
/// inwards and the middle rod is in compression (`beta < 0`).
#[test]
fn three_rods_on_a_level_span_form_a_trapezoid() {
    let l = 1.0;
    for d in [0.06, 0.5, 1.0 - 1e-9, 1.0, 1.0 + 1e-9, 1.5, 2.7] {
        let eq = discrete_equilibrium([0.0, 0.0], [d, 0.0], 3.0 * l, 3).unwrap();
        let r = joints([0.0, 0.0], 3.0 * l, &eq.angles);
        let depth = (l * l - ((l - d) / 2.0).powi(2)).sqrt();
        assert!(dist(r[1], [(d - l) / 2.0, -depth]) <= 1e-12, "d={d}: {r:?}");
        assert!(dist(r[2], [(d + l) / 2.0, -depth]) <= 1e-12, "d={d}: {r:?}");
        if d != l {
            assert_eq!(eq.beta > 0.0, d > l, "d={d}");
        }
    }
}

#[test]
fn newton_converges_in_few_iterations() {
    let mut worst = 0;
    for (p0, p1, l) in CASES {
        for n in LINKS {
            worst = worst.max(discrete_equilibrium(p0, p1, l, n).unwrap().iterations);
        }
    }
    eprintln!("most Newton iterations over CASES x LINKS: {worst}");
    assert!(worst <= 10, "{worst}");
}

#[test]
fn converges_to_the_continuous_catenary_like_one_over_n_squared() {
    let (p0, p1, l) = ([0.0, 0.0], [5.0, 1.0], 8.0);
    let cat = Catenary::through(p0, p1, l).unwrap();
    let ns = [25usize, 50, 100, 200, 400];
    let errs: Vec<f64> = ns
        .iter()
        .map(|&n| {
            let eq = discrete_equilibrium(p0, p1, l, n).unwrap();
            let r = joints(p0, l, &eq.angles);
            (0..=n)
                .map(|k| dist(r[k], cat.point_at_arc_length(l * k as f64 / n as f64)))
                .fold(0.0, f64::max)
        })
        .collect();
    // least-squares slope of ln(err) against ln(n)
    let xs: Vec<f64> = ns.iter().map(|&n| (n as f64).ln()).collect();
    let ys: Vec<f64> = errs.iter().map(|e| e.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / 5.0, ys.iter().sum::<f64>() / 5.0);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    let order = -sxy / sxx;
    let shown: Vec<String> = errs.iter().map(|e| format!("{e:.3e}")).collect();
    eprintln!("max joint error vs n {ns:?}: {shown:?}; order {order:.4}");
    assert!((1.8..=2.2).contains(&order), "order {order}");
}
