//! The validation claims of issue 5 as tests against physics: the folded
//! chain against its energy-conserving law, the hanging chain's lowest mode
//! against the Bessel value, the energy balance `E + W = E(0)` along a damped
//! run, and the pivot force against the chain's weight and momentum balance.
//! Expected values are closed forms and conservation laws, never earlier output.

use chain_ode::analysis::{
    bessel_frequencies, first_time_below, folded_law, pivot_force, refined, tip_track,
};
use chain_ode::kinematics::{dissipation_rate, energy};
use chain_ode::modes::hanging_frequencies;
use chain_ode::{solve, Chain, ChainParams, ChainSystem, Method, SolveOptions, Start, State};
use std::f64::consts::FRAC_PI_2;

/// `integral_a^b f` by composite Simpson with `panels` (even) intervals.
fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let h = (b - a) / panels as f64;
    let inner: f64 = (1..panels)
        .map(|k| f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    h / 3.0 * (f(a) + inner + f(b))
}

/// The law's `t(x) / sqrt(L/g)` by a quadrature independent of the library's:
/// with `x = L u^2`, `dt = 2 sqrt(L/g) sqrt((1 - u^2)/(2 - u^2)) du` (the
/// `1/sqrt(x)` singularity of `1/v` at the start is gone).
fn law_time_by_simpson(xi: f64) -> f64 {
    simpson(
        |u| 2.0 * ((1.0 - u * u) / (2.0 - u * u)).sqrt(),
        0.0,
        xi.sqrt(),
        20_000,
    )
}

#[test]
fn folded_law_times_are_the_quadrature_of_one_over_v() {
    // docs/model.md's constants, in units of sqrt(L/g).
    for (xi, stated, tol) in [
        (0.5, 0.948_025_3, 1e-7f64),
        (0.9, 1.177_013_0, 1e-7),
        (1.0, 1.198_140_235, 1e-8),
    ] {
        // The integrand has a square-root end point at u = 1 (xi = 1):
        // Simpson converges slowly there, so compare it more loosely.
        let by_simpson = law_time_by_simpson(xi);
        let simpson_tol = if xi < 1.0 { 1e-10 } else { 1e-6 };
        assert!(
            (by_simpson - stated).abs() < tol.max(simpson_tol),
            "xi = {xi}: Simpson {by_simpson} vs docs/model.md {stated}"
        );
        // The library's Gauss-Legendre form, in other units (L = 6, g = 2).
        let lib = folded_law::time(xi * 6.0, 6.0, 2.0) / (6.0f64 / 2.0).sqrt();
        assert!(
            (lib - stated).abs() < tol,
            "xi = {xi}: library {lib} vs {stated}"
        );
    }
    // dt/dx = 1/v: the library's time and speed are consistent.
    let (x, h) = (2.0, 1e-5);
    let dtdx = (folded_law::time(x + h, 6.0, 1.0) - folded_law::time(x - h, 6.0, 1.0)) / (2.0 * h);
    assert!((dtdx * folded_law::speed(x, 6.0, 1.0) - 1.0).abs() < 1e-8);
    // The support force from the momentum balance of the whole chain,
    // derived here independently of the library's form: the moving side,
    // of length (L - x)/2, carries momentum p = lambda (L - x) v / 2, and
    // F = M g - dp/dt = M g - lambda ((L - x) a - v^2) / 2, with
    // v^2 = g x (2L - x) / (L - x) (energy conservation) and
    // a = d(v^2/2)/dx = g (1 + x (2L - x) / (2 (L - x)^2)).
    // In units of M g, with xi = x / L:
    // F = (1 + xi) / 2 + xi (2 - xi) / (4 (1 - xi)): half the weight at
    // release, growing like 1 / (4 (1 - xi)) at the snap (25.99 at 0.99).
    for xi in [0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999] {
        let balance = (1.0 + xi) / 2.0 + xi * (2.0 - xi) / (4.0 * (1.0 - xi));
        let lib = folded_law::support_force(xi);
        assert!(
            (lib - balance).abs() <= 1e-13 * balance,
            "xi = {xi}: {lib} vs {balance}"
        );
    }
    assert_eq!(folded_law::support_force(0.0), 0.5);
}

/// The first times the free end of a folded chain (n rods, r = 0) has fallen
/// `x = xi L` below its start height, and the law's times for them.
///
/// Convention: `x` is measured from the free end's own start height
/// (`P0.y - l`), where it is released at rest, as the law's free end is at
/// `x = 0`. Measured from the pivot's height instead, the discrete start
/// would begin at `x = l` with `v = 0`, a time offset of about
/// `sqrt(2 l / g)` (12% of t(L/2) at n = 100).
fn folded_times(n: usize, fractions: &[f64]) -> Vec<(f64, f64)> {
    let chain = Chain::new(ChainParams {
        links: n,
        mass: 10.0 / n as f64,
        ..ChainParams::default()
    })
    .unwrap();
    let start = Start::Folded {
        p0: [0.0, 0.0],
        down: None,
    }
    .state(&chain)
    .unwrap();
    let tau = (chain.length() / chain.gravity()).sqrt();
    let xi_max = fractions.iter().copied().fold(0.0, f64::max);
    let options = SolveOptions {
        // Past the last crossing, before the whip at t = 1.198 tau.
        t_end: (folded_law::time(xi_max * chain.length(), chain.length(), chain.gravity()) / tau
            + 0.004)
            * tau,
        rtol: 1e-9,
        atol: 1e-11,
        output_dt: Some(1e-3),
        ..Default::default()
    };
    let traj = solve(&chain, &start, Method::Dopri5, &options).unwrap();
    assert!(traj.status.is_ok(), "n = {n}: {}", traj.status);
    let track = tip_track(&traj);
    let y_start = track[0].1[1];
    assert!((y_start + chain.rod_length()).abs() < 1e-12);
    fractions
        .iter()
        .map(|&xi| {
            let x = xi * chain.length();
            let t = first_time_below(&track, y_start - x)
                .unwrap_or_else(|| panic!("n = {n}: the tip never fell {x}"));
            (t, folded_law::time(x, chain.length(), chain.gravity()))
        })
        .collect()
}

#[test]
fn folded_chain_reaches_half_its_length_when_the_law_says() {
    for n in [100, 200] {
        let times = folded_times(n, &[0.5, 0.9]);
        for ((t, law), xi) in times.iter().zip([0.5, 0.9]) {
            let rel = t / law - 1.0;
            assert!(
                rel.abs() < 5e-3,
                "n = {n}: t({xi} L) = {t} vs the law's {law} ({:+.3}%)",
                100.0 * rel
            );
        }
    }
}

#[test]
fn folded_chain_falls_faster_than_free_fall() {
    // The law's t(L/2) is 0.948 sqrt(L/g); a free fall of L/2 takes
    // sqrt(L/g) = 1.054 times as long. The chain must beat free fall.
    let (t, _) = folded_times(100, &[0.5])[0];
    let free = (2.0 * 3.0 / 1.0f64).sqrt();
    assert!(t < 0.96 * free, "t(L/2) = {t}, free fall {free}");
}

#[test]
fn lowest_hanging_mode_is_the_bessel_value_within_1e4_at_n_100() {
    let err = |n: usize| {
        let chain = Chain::report(n, 0.0).unwrap();
        hanging_frequencies(&chain)[0] / bessel_frequencies(&chain)[0] - 1.0
    };
    let (e100, e200) = (err(100), err(200));
    assert!(e100.abs() < 1e-4, "n = 100: relative error {e100:e}");
    // And it is the discretisation error, O(1/n^2): halving l quarters it.
    let order = (e100 / e200).log2();
    assert!(
        (1.95..2.05).contains(&order),
        "order {order} ({e100:e}, {e200:e})"
    );
}

#[test]
fn energy_plus_dissipated_work_stays_constant_along_a_damped_run() {
    for r in [0.0, 5e-4, 1e-2] {
        let chain = Chain::report(50, r).unwrap();
        let start = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [3.0, 0.0],
        }
        .state(&chain)
        .unwrap();
        let options = SolveOptions {
            t_end: 4.157,
            rtol: 1e-10,
            atol: 1e-12,
            output_dt: Some(0.005),
            ..Default::default()
        };
        let traj = solve(&chain, &start, Method::Dopri5, &options).unwrap();
        assert!(traj.status.is_ok());
        let scale = chain.energy_scale();
        let e0 = energy(&chain, &start.angles, &start.rates);
        let mut last_w = 0.0;
        let mut worst: f64 = 0.0;
        let mut rate = vec![];
        for s in traj.samples() {
            let e = energy(&chain, s.angles, s.rates);
            worst = worst.max((e + s.dissipated - e0).abs() / scale);
            assert!(s.dissipated >= last_w - 1e-15 * scale, "W decreased");
            last_w = s.dissipated;
            rate.push((s.t, dissipation_rate(&chain, s.rates)));
        }
        // rtol = 1e-10: the balance holds to ten times that (measured ~3e-12).
        assert!(worst < 1e-9, "r = {r}: |E + W - E0| / (M g L) = {worst:e}");
        // W is the time integral of the dissipation rate 2R (trapezoid rule
        // on the samples, error O(dt^2)).
        let by_hand: f64 = rate
            .windows(2)
            .map(|p| 0.5 * (p[1].0 - p[0].0) * (p[1].1 + p[0].1))
            .sum();
        let w_end = traj.summary.dissipated;
        assert!(
            (by_hand - w_end).abs() <= 1e-5 * w_end + 1e-12 * scale,
            "r = {r}: W = {w_end} vs integral of 2R {by_hand}"
        );
        if r > 0.0 {
            // A damped run really dissipates (not a trivial balance).
            assert!(w_end > 1e-3 * scale * r / 1e-2, "r = {r}: W = {w_end}");
        } else {
            assert_eq!(w_end, 0.0);
        }
    }
}

/// Acceleration of the centre of mass from the angular accelerations alone
/// (kinematics, not the recursion's forces): rod k's centre is
/// `P0 + l sum_{j<k} u_j + (l/2) u_k`, `u = (cos, sin)`.
fn centre_of_mass_acceleration(chain: &Chain, phi: &[f64], w: &[f64], acc: &[f64]) -> [f64; 2] {
    let l = chain.rod_length();
    let (mut jx, mut jy) = (0.0, 0.0); // acceleration of the rod's first joint
    let (mut sx, mut sy) = (0.0, 0.0);
    for k in 0..phi.len() {
        let (s, c) = phi[k].sin_cos();
        // d2/dt2 of l u_k: l (phi'' n - w^2 u), n = (-sin, cos).
        let ax = l * (-acc[k] * s - w[k] * w[k] * c);
        let ay = l * (acc[k] * c - w[k] * w[k] * s);
        sx += jx + 0.5 * ax;
        sy += jy + 0.5 * ay;
        jx += ax;
        jy += ay;
    }
    let n = phi.len() as f64;
    [sx / n, sy / n]
}

/// The pivot force from the recursion and `M g + M a_cm` from kinematics.
fn force_and_momentum_balance(chain: &Chain, phi: &[f64], w: &[f64]) -> ([f64; 2], [f64; 2]) {
    let mut sys = ChainSystem::new(chain);
    let y = ChainSystem::pack(phi, w, 0.0);
    let mut dy = vec![0.0; y.len()];
    let f = sys.rhs_with_reactions(&y, &mut dy).pivot_force;
    let n = chain.links();
    let a = centre_of_mass_acceleration(chain, phi, w, &dy[n..2 * n]);
    let m = chain.total_mass();
    (f, [m * a[0], m * (a[1] + chain.gravity())])
}

#[test]
fn pivot_force_of_a_chain_hanging_at_rest_is_its_weight() {
    for (n, mass, g, r) in [
        (1, 0.7, 9.81, 0.0),
        (50, 0.2, 1.0, 5e-4),
        (333, 0.01, 2.5, 1.0),
    ] {
        let chain = Chain::new(ChainParams {
            length: 6.0,
            links: n,
            mass,
            gravity: g,
            damping: r,
            ..ChainParams::default()
        })
        .unwrap();
        let start = State {
            anchor: [0.0, 0.0],
            angles: vec![-FRAC_PI_2; n],
            rates: vec![0.0; n],
        };
        let mut sys = ChainSystem::new(&chain);
        let f = pivot_force(&mut sys, &start.angles, &start.rates);
        let weight = chain.weight();
        assert!(f[0].abs() < 1e-12 * weight, "n = {n}: {f:?}");
        assert!(
            (f[1] / weight - 1.0).abs() < 1e-12,
            "n = {n}: {f:?} vs M g = {weight}"
        );
    }
}

#[test]
fn pivot_force_after_release_is_momentum_balance_and_below_the_weight() {
    // Released from a pinned catenary at rest, the chain is no longer in
    // equilibrium: F_pivot - M g = M a_cm. As T grows from 0 and E is
    // conserved, V must fall, so a_cm points down: F_y < M g at t = 0+.
    let chain = refined(&Chain::report(50, 5e-4).unwrap(), 80).unwrap();
    for d in [1.0, 3.0, 5.0] {
        let start = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [d, 0.0],
        }
        .state(&chain)
        .unwrap();
        let (f, balance) = force_and_momentum_balance(&chain, &start.angles, &start.rates);
        let weight = chain.weight();
        for k in 0..2 {
            assert!(
                (f[k] - balance[k]).abs() < 1e-10 * weight,
                "d = {d}: F = {f:?}, M (g + a_cm) = {balance:?}"
            );
        }
        assert!(f[1] < weight, "d = {d}: F_y = {} >= M g = {weight}", f[1]);
    }
    // And along a moving run (centripetal terms, damping): the same balance.
    let start = Start::Folded {
        p0: [0.0, 0.0],
        down: None,
    }
    .state(&chain)
    .unwrap();
    let options = SolveOptions {
        t_end: 2.0,
        output_dt: Some(0.25),
        ..Default::default()
    };
    let traj = solve(&chain, &start, Method::Dopri5, &options).unwrap();
    let weight = chain.weight();
    for s in traj.samples() {
        let (f, balance) = force_and_momentum_balance(&chain, s.angles, s.rates);
        for k in 0..2 {
            assert!(
                (f[k] - balance[k]).abs() < 1e-9 * weight,
                "t = {}: F = {f:?}, M (g + a_cm) = {balance:?}",
                s.t
            );
        }
    }
}

#[test]
fn refinement_keeps_total_mass_and_bending_viscosity() {
    let base = Chain::report(50, 5e-4).unwrap();
    for n in [25, 100, 800] {
        let c = refined(&base, n).unwrap();
        assert!((c.total_mass() - base.total_mass()).abs() < 1e-12);
        assert!(
            (c.damping() * c.rod_length() - base.damping() * base.rod_length()).abs() < 1e-18,
            "eta changed at n = {n}"
        );
        // gamma = eta n^4 / (M L^3).
        let ratio = (n as f64 / 50.0).powi(4);
        assert!((c.damping_rate() / base.damping_rate() / ratio - 1.0).abs() < 1e-12);
    }
}
