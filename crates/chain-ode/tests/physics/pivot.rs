//! A pivot that moves or is let go (`pivot.*`, issue 18): both ends let go
//! (every rod falls at g, the shape kept), a uniformly accelerating support
//! against a fixed one under gravity `g - a`, Kapitza's inverted pendulum on
//! both sides of its threshold, a release during the fall against the free
//! fall of the centre of mass, and the banded DAE's residual and Jacobian
//! with a driven and a free pivot.

use chain_ode::dae::ChainDae;
use chain_ode::dynamics::{accelerations_with, Base, Workspace};
use chain_ode::pivot::centre_of_mass;
use chain_ode::{
    solve, Chain, ChainParams, ChainSystem, Method, Pivot, SolveOptions, Start, Status,
};

fn chain(n: usize, gravity: f64, damping: f64, tip_mass: f64, pivot: Pivot) -> Chain {
    Chain::new(ChainParams {
        links: n,
        length: 3.0,
        mass: 0.6 / n as f64,
        gravity,
        damping,
        tip_mass,
        pivot,
        ..ChainParams::default()
    })
    .unwrap()
}

fn released(at: f64) -> Pivot {
    Pivot {
        release: Some(at),
        ..Pivot::default()
    }
}

fn catenary() -> Start {
    Start::Catenary {
        p0: [0.0, 0.0],
        p1: [1.8, -0.4],
    }
}

fn options(t_end: f64, method: Method) -> SolveOptions {
    SolveOptions {
        t_end,
        output_dt: Some(t_end / 20.0),
        dt: 2e-3,
        ..SolveOptions::default()
    }
    .at_accuracy(method, if method == Method::Rk4 { 2e-3 } else { 1e-10 })
}

/// Both ends let go at rest: the tension vanishes everywhere, every rod
/// falls at `g` and the U keeps its shape. The recursion says so to
/// rounding at the start (the pivot's and tip's accelerations are
/// `(0, -g)`, every `phi''` zero), and every method keeps the angles and
/// falls the tip as `g t^2 / 2` along a run, the tip's acceleration staying
/// within `1e-10 g` of gravity.
#[test]
fn both_ends_let_go_fall_at_g_with_the_shape_kept() {
    let g = 1.7;
    for tip_mass in [0.0, 0.3] {
        // Without joint friction: the rates stay at rounding (1e-12 in an
        // adaptive method's dense output), and friction's `gamma w` would
        // turn even those into 1e-10 of acceleration.
        let chain = chain(24, g, 0.0, tip_mass, released(0.0));
        let s = catenary().state(&chain).unwrap();
        let n = chain.links();
        let mut acc = vec![0.0; n];
        let r = accelerations_with(
            &chain,
            Base::Free,
            &s.angles,
            &s.rates,
            &mut acc,
            &mut Workspace::new(n),
        );
        let tol = 1e-10 * g;
        assert!(acc.iter().all(|a| a.abs() < 1e-10), "{acc:?}");
        for a in [r.pivot_acceleration, r.tip_acceleration] {
            assert!(a[0].abs() < tol && (a[1] + g).abs() < tol, "{a:?}");
        }
        assert_eq!(r.pivot_force, [0.0, 0.0]);
        for method in crate::smooth_methods() {
            let t_end = 1.5;
            let tr = solve(&chain, &s, method, &options(t_end, method)).unwrap();
            assert_eq!(tr.status, Status::Ok, "{method}");
            let tip0 = tr.tip(0);
            let mut sys = ChainSystem::new(&chain);
            sys.set_released(true);
            let mut dy = vec![0.0; 2 * n + 1];
            for k in 0..tr.len() {
                let t = tr.times[k];
                let smp = tr.sample(k);
                for (a, b) in smp.angles.iter().zip(&s.angles) {
                    assert!((a - b).abs() < 1e-12, "{method}: t = {t}: {a} vs {b}");
                }
                let tip = tr.tip(k);
                let fall = [tip0[0], tip0[1] - 0.5 * g * t * t];
                assert!(
                    (tip[0] - fall[0]).abs() < 1e-9 && (tip[1] - fall[1]).abs() < 1e-9,
                    "{method}: t = {t}: {tip:?} vs {fall:?}"
                );
                let r = sys.rhs_at(t, tr.state(k), &mut dy);
                let a = r.tip_acceleration;
                assert!(
                    a[0].abs() <= tol && (a[1] + g).abs() <= tol,
                    "{method}: t = {t}: tip acceleration {a:?}"
                );
            }
            assert!(tr.summary.energy_balance_error < 1e-9 * chain.energy_scale());
        }
    }
}

/// A support accelerating at `a` (vertical, `|a| < g`) gives the same
/// motion relative to it as a fixed support under gravity `g - a`.
#[test]
fn a_uniformly_accelerating_support_is_gravity_minus_its_acceleration() {
    let (g, a) = (1.0, -0.35);
    let moving = chain(
        12,
        g,
        0.002,
        0.1,
        Pivot {
            acceleration: [0.0, a],
            ..Pivot::default()
        },
    );
    let fixed = chain(12, g + a, 0.002, 0.1, Pivot::default());
    assert!((fixed.gravity() - (g + a)).abs() < 1e-15);
    for method in [Method::Dopri5, Method::Bdf, Method::BdfDense, Method::Rk4] {
        let s = catenary().state(&moving).unwrap();
        let o = options(3.0, method);
        let tm = solve(&moving, &s, method, &o).unwrap();
        let tf = solve(&fixed, &s, method, &o).unwrap();
        assert_eq!(tm.status, Status::Ok, "{method}");
        let tol = if method == Method::Rk4 { 1e-8 } else { 1e-6 };
        let mut moved = 0.0f64;
        for k in 0..tm.len() {
            for (x, y) in tm.sample(k).angles.iter().zip(tf.sample(k).angles) {
                assert!((x - y).abs() < tol, "{method}: {x} vs {y}");
            }
            let t = tm.times[k];
            // The joints ride on the support: P0(t) = P0 + a t^2 / 2.
            let (jm, jf) = (tm.joints(k), tf.joints(k));
            for (p, q) in jm.iter().zip(&jf) {
                assert!((p[1] - q[1] - 0.5 * a * t * t).abs() < 1e-5, "{method}");
            }
            for (x, y) in tm.sample(k).angles.iter().zip(&s.angles) {
                moved = moved.max((x - y).abs());
            }
        }
        // The chain did move, and the inertial-frame energy balance (the
        // support's work counted in W) holds.
        assert!(moved > 0.1, "{method}: {moved}");
        assert!(
            tm.summary.energy_balance_error < 1e-5 * moving.energy_scale(),
            "{method}: {}",
            tm.summary.energy_balance_error
        );
    }
}

/// Kapitza's pendulum: one uniform rod, upside down on a support that
/// oscillates vertically as `A sin(Omega t)`, is stable when
/// `A^2 Omega^2 > 2 g l_e`, `l_e = 2 l / 3`. Five percent above the
/// threshold it stays up, five percent below it falls.
#[test]
fn kapitza_threshold_for_one_rod_holds_on_both_sides() {
    let (g, l, amp): (f64, f64, f64) = (1.0, 1.0, 0.02);
    let omega_c = (2.0 * g * 2.0 * l / 3.0).sqrt() / amp;
    let up = std::f64::consts::FRAC_PI_2;
    let run = |factor: f64| {
        let chain = Chain::new(ChainParams {
            links: 1,
            length: l,
            mass: 1.0,
            gravity: g,
            pivot: Pivot {
                amplitude: [0.0, amp],
                frequency: factor * omega_c,
                ..Pivot::default()
            },
            ..ChainParams::default()
        })
        .unwrap();
        let s = Start::Angles {
            p0: [0.0, 0.0],
            angles: vec![up + 0.01],
            rates: None,
        }
        .state(&chain)
        .unwrap();
        let o = SolveOptions {
            t_end: 40.0,
            output_dt: Some(0.05),
            rtol: 1e-9,
            atol: 1e-11,
            ..SolveOptions::default()
        };
        let tr = solve(&chain, &s, Method::Dop853, &o).unwrap();
        assert_eq!(tr.status, Status::Ok);
        // The support's work, counted in W, keeps the inertial balance.
        let e = tr.summary.energy_balance_error;
        assert!(e < 1e-6 * chain.energy_scale(), "{factor}: {e}");
        tr.samples()
            .map(|smp| (smp.angles[0] - up).abs())
            .fold(0.0f64, f64::max)
    };
    let above = run(1.05);
    let below = run(0.95);
    assert!(above < 0.5, "5% above the threshold: deviation {above}");
    assert!(below > 1.5, "5% below the threshold: deviation {below}");
}

/// Released during the fall: after `t_r` the pivot is a free end. The
/// pivot's path (placed by the free fall of the centre of mass) has the
/// second derivative that the recursion's free joint 0 states, and the
/// energy balance holds across the release.
#[test]
fn a_pivot_released_during_the_fall_moves_as_the_recursion_says() {
    let t_r = 0.8;
    let chain = chain(16, 1.0, 0.003, 0.05, released(t_r));
    let s = catenary().state(&chain).unwrap();
    let n = chain.links();
    for method in [Method::Dop853, Method::Bdf] {
        let o = SolveOptions {
            t_end: 2.0,
            output_dt: Some(1e-3),
            ..SolveOptions::default()
        }
        .at_accuracy(method, 1e-11);
        let tr = solve(&chain, &s, method, &o).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method}");
        assert_eq!(tr.segments.len(), 2, "{method}: held, then free");
        let mut sys = ChainSystem::new(&chain);
        let mut dy = vec![0.0; 2 * n + 1];
        let mut checked = 0;
        for k in 1..tr.len() - 1 {
            let (t0, t1, t2) = (tr.times[k - 1], tr.times[k], tr.times[k + 1]);
            let h = t1 - t0;
            let p = [
                tr.pivot_at(k - 1)[0],
                tr.pivot_at(k)[0],
                tr.pivot_at(k + 1)[0],
            ];
            let fd = [
                (p[2][0] - 2.0 * p[1][0] + p[0][0]) / (h * h),
                (p[2][1] - 2.0 * p[1][1] + p[0][1]) / (h * h),
            ];
            sys.set_released(t1 >= t_r);
            let a = sys.rhs_at(t1, tr.state(k), &mut dy).pivot_acceleration;
            if t0 < t_r - 1e-9 && t2 > t_r + 1e-9 {
                continue;
            }
            if t1 >= t_r {
                if t1 < t_r + 0.01 {
                    continue;
                }
                assert!(
                    (fd[0] - a[0]).abs() < 1e-3 && (fd[1] - a[1]).abs() < 1e-3,
                    "{method}: t = {t1}: {fd:?} vs {a:?}"
                );
                checked += 1;
            } else {
                assert_eq!(a, [0.0, 0.0]);
                assert!(fd[0].abs() < 1e-6 && fd[1].abs() < 1e-6);
            }
        }
        assert!(checked > 1000, "{checked}");
        // The pivot accelerates: it is not held, and not a free particle.
        let [_, v_end] = tr.pivot_at(tr.len() - 1);
        assert!(v_end[1] < -0.1, "{v_end:?}");
        assert!(
            tr.summary.energy_balance_error < 1e-7 * chain.energy_scale(),
            "{method}: {}",
            tr.summary.energy_balance_error
        );
        // The centre of mass falls freely after the release.
        let k_end = tr.len() - 1;
        let k_r = tr.times.iter().position(|&t| t >= t_r).unwrap();
        let com = |k: usize| {
            let smp = tr.sample(k);
            let [c, v] = centre_of_mass(&chain, smp.angles, smp.rates);
            let [p, pv] = tr.pivot_at(k);
            ([p[0] + c[0], p[1] + c[1]], [pv[0] + v[0], pv[1] + v[1]])
        };
        let ((c_r, v_r), (c_e, _)) = (com(k_r), com(k_end));
        let dt = tr.times[k_end] - tr.times[k_r];
        assert!((c_e[0] - c_r[0] - v_r[0] * dt).abs() < 1e-9);
        assert!((c_e[1] - c_r[1] - v_r[1] * dt + 0.5 * dt * dt).abs() < 1e-9);
    }
}

/// The banded DAE with a driven and with a free pivot: consistent states
/// have zero residual, its `alpha` is the recursion's, and its Jacobian is
/// the residual's finite-difference derivative.
#[test]
fn banded_dae_with_a_moving_or_free_pivot_is_consistent_and_exact() {
    let driven = Pivot {
        acceleration: [0.2, -0.3],
        amplitude: [0.05, 0.1],
        frequency: 3.0,
        jerk: [0.4, 0.0],
        jerk_time: 0.7,
        release: None,
    };
    for (n, tip, pivot, free) in [
        (1, 0.0, driven, false),
        (5, 0.4, driven, false),
        (1, 0.7, released(0.0), true),
        (6, 0.0, released(0.0), true),
        (4, 0.3, released(0.0), true),
    ] {
        let chain = chain(n, 1.3, 0.02, tip, pivot);
        let dae = ChainDae::new(&chain).released(free);
        let t = 0.37;
        let mut y = vec![0.0; dae.dim()];
        for i in 0..n {
            y[i] = (1.7 * i as f64 + 0.4).sin() * 2.0 - 1.0;
            y[n + i] = (0.9 * i as f64 + 0.8).cos() * 1.5;
        }
        dae.make_consistent_at(t, &mut y, &mut Workspace::new(n));
        let mut out = vec![0.0; dae.dim()];
        dae.rhs_at(t, &y, &mut out);
        let d = dae.differential_dim();
        for (k, r) in out[d..].iter().enumerate() {
            assert!(
                r.abs() < 1e-11,
                "n = {n}, free = {free}: residual {k} = {r}"
            );
        }
        let mut acc = vec![0.0; n];
        let base = if free {
            Base::Free
        } else {
            Base::Driven(pivot.acceleration_at(t))
        };
        let r = accelerations_with(
            &chain,
            base,
            &y[..n],
            &y[n..2 * n],
            &mut acc,
            &mut Workspace::new(n),
        );
        for i in 0..n {
            assert!((acc[i] - y[d + i]).abs() < 1e-11);
        }
        if free {
            assert!(dae.pivot_force(&y) == [0.0, 0.0]);
            let l = chain.rod_length();
            assert!((y[d + n] * l - r.pivot_acceleration[0]).abs() < 1e-11);
        } else {
            let ml = chain.mass() * chain.rod_length();
            let f0 = dae.pivot_force(&y);
            assert!((f0[0] * ml - r.pivot_force[0]).abs() < 1e-11);
            assert!((f0[1] * ml - r.pivot_force[1]).abs() < 1e-11);
        }
        // The Jacobian against central differences of the residual (rows
        // past W's), perturbing every unknown (so every row of a free pivot
        // is checked against its a_0 columns too).
        let dim = dae.dim();
        let mut jac = vec![0.0; dim * dim];
        dae.jacobian_entries(&y, |r, c, v| jac[r * dim + c] += v);
        let eps = 1e-6;
        for c in 0..dim {
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[c] += eps;
            ym[c] -= eps;
            let (mut op, mut om) = (vec![0.0; dim], vec![0.0; dim]);
            dae.rhs_at(t, &yp, &mut op);
            dae.rhs_at(t, &ym, &mut om);
            for r in (0..dim).filter(|&r| r != 2 * n) {
                let fd = (op[r] - om[r]) / (2.0 * eps);
                assert!(
                    (fd - jac[r * dim + c]).abs() < 1e-6 * (1.0 + fd.abs()),
                    "n = {n}, free = {free}: d{r}/d{c}: {fd} vs {}",
                    jac[r * dim + c]
                );
            }
        }
    }
}
