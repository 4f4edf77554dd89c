//! The discrete equilibrium of n rods against statics and the continuum limit.

use super::{dist, CASES};
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
fn all_rods_have_length_l() {
    for (p0, p1, l) in CASES {
        let n = 37;
        let r = joints(p0, l, &discrete_equilibrium(p0, p1, l, n).unwrap().angles);
        for w in r.windows(2) {
            assert!((dist(w[0], w[1]) - l / n as f64).abs() <= 1e-12 * l);
        }
    }
}

/// 2D cross product.
fn cross(u: Point, v: Point) -> f64 {
    u[0] * v[1] - u[1] * v[0]
}

/// Statics from the joints alone: rod weight `W = 1`, force `T_k = (H, V_k)`
/// exerted on rod `k` by rod `k + 1`, `V_k = V_{k-1} + W` (force balance,
/// uniform vertical differences). `H` and `V_0` are fixed by the torque
/// balance of rods 1 and 2; every other rod must then have zero net torque
/// about its centre, `u_i x (T_{i-1} + T_i) = 0`. Returns `H` and the largest
/// relative torque.
fn torque_check(r: &[Point]) -> (f64, f64) {
    let u: Vec<Point> = r
        .windows(2)
        .map(|w| [w[1][0] - w[0][0], w[1][1] - w[0][1]])
        .collect();
    // rod 1: u1x (2 V0 + 1) - u1y 2H = 0 ; rod 2: u2x (2 V0 + 3) - u2y 2H = 0
    let (a, b) = (u[0], u[1]);
    let det = 2.0 * a[0] * (-2.0 * b[1]) - (-2.0 * a[1]) * 2.0 * b[0];
    let rhs = [-a[0], -3.0 * b[0]];
    let v0 = (rhs[0] * (-2.0 * b[1]) - (-2.0 * a[1]) * rhs[1]) / det;
    let h = (2.0 * a[0] * rhs[1] - 2.0 * b[0] * rhs[0]) / det;
    let n = u.len() as f64;
    let scale = h.abs() + n + v0.abs();
    let worst = u
        .iter()
        .enumerate()
        .map(|(k, ui)| {
            let (vl, vr) = (v0 + k as f64, v0 + k as f64 + 1.0);
            let len = ui[0].hypot(ui[1]);
            cross(*ui, [2.0 * h, vl + vr]).abs() / (len * scale)
        })
        .fold(0.0, f64::max);
    (h, worst)
}

#[test]
fn is_a_static_equilibrium() {
    for (p0, p1, l) in CASES {
        for n in [3, 10, 50, 301] {
            let eq = discrete_equilibrium(p0, p1, l, n).unwrap();
            let (h, worst) = torque_check(&joints(p0, l, &eq.angles));
            assert!(worst < 1e-12, "{p0:?} {p1:?} {l} n={n}: torque {worst:e}");
            // in tension (a hanging chain, not an arch): rod k+1 pulls rod k towards p1
            assert!(h * (p1[0] - p0[0]).signum() > 0.0);
            // beta = W / |H| with W = 1
            assert!((eq.beta - 1.0 / h.abs()).abs() <= 1e-9 * eq.beta);
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
        assert!(eq.beta > 0.0);
        let sign = (p1[0] - p0[0]).signum();
        for (i, phi) in eq.angles.iter().enumerate() {
            let t = eq.alpha + (i as f64 + 0.5) * eq.beta;
            assert!((sign * phi.tan() - t).abs() <= 1e-10 * (1.0 + t.abs()));
        }
    }
}

#[test]
fn angles_are_continuous_and_in_range() {
    for (p0, p1, l) in CASES {
        let eq = discrete_equilibrium(p0, p1, l, 60).unwrap();
        let (lo, hi) = if p1[0] > p0[0] {
            (-PI / 2.0, PI / 2.0)
        } else {
            (PI / 2.0, 1.5 * PI)
        };
        assert!(eq.angles.iter().all(|&a| lo < a && a < hi));
        assert!(eq.angles.windows(2).all(|w| (w[1] - w[0]).abs() < PI / 2.0));
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
        ([0.0, -5.0], 4),
        ([5.0, 0.0], 50),
    ] {
        let eq = discrete_equilibrium([0.0, 0.0], p1, 5.0, n).unwrap();
        let dir = p1[1].atan2(p1[0]);
        assert!(eq.angles.len() == n && eq.angles.iter().all(|&a| a == dir));
        assert!(eq.end_error <= 1e-14 * 5.0, "{p1:?}: {:e}", eq.end_error);
        assert_eq!((eq.beta, eq.iterations), (0.0, 0));
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
    eprintln!("max joint error vs n {ns:?}: {errs:.3?}; order {order:.4}");
    assert!((1.8..=2.2).contains(&order), "order {order}");
}
