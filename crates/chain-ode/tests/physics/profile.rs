//! Rods of unequal mass and length (`chain.taper`, `chain.rod_masses`,
//! `chain.rod_lengths`): the recursion against a hand-written two-rod
//! Lagrangian and the dense reference, the catenary start as an exact
//! equilibrium, and a run's energy.

use chain_ode::dynamics::{accelerations, Workspace};
use chain_ode::kinematics::{joints, potential_energy};
use chain_ode::{dense, solve, Chain, ChainParams, Method, Profile, Start};

use crate::{max_abs, tolerances};

/// Two rods: masses 0.3 and 1.7 (mean 1), lengths 1.5 and 0.5 (mean 1).
fn two_rods(gravity: f64, damping: f64) -> Chain {
    Chain::new(ChainParams {
        length: 2.0,
        links: 2,
        mass: 1.0,
        gravity,
        damping,
        profile: Profile {
            masses: Some(vec![0.3, 1.7]),
            lengths: Some(vec![1.5, 0.5]),
            ..Profile::default()
        },
        ..ChainParams::default()
    })
    .unwrap()
}

/// The double physical pendulum written out from its Lagrangian: rods of
/// mass `m1, m2`, length `l1, l2`, about their ends;
/// `T = (m1 l1^2 / 6 + m2 l1^2 / 2) w1^2 + (m2 l2^2 / 6) w2^2 + (m2 l1 l2 / 2) cos(phi1 - phi2) w1 w2`,
/// `V = g (m1 l1 / 2 + m2 l1) sin phi1 + g m2 (l2 / 2) sin phi2`, friction
/// `r (w2 - w1)` on rod 1 and `-r (w2 - w1)` on rod 2.
fn double_pendulum(
    [m1, m2, l1, l2, g, r]: [f64; 6],
    [p1, p2]: [f64; 2],
    [w1, w2]: [f64; 2],
) -> [f64; 2] {
    let (c12, s12) = ((p1 - p2).cos(), (p1 - p2).sin());
    let a11 = m1 * l1 * l1 / 3.0 + m2 * l1 * l1;
    let a12 = m2 * l1 * l2 / 2.0 * c12;
    let a22 = m2 * l2 * l2 / 3.0;
    let b1 = -m2 * l1 * l2 / 2.0 * s12 * w2 * w2 - g * (m1 * l1 / 2.0 + m2 * l1) * p1.cos()
        + r * (w2 - w1);
    let b2 = m2 * l1 * l2 / 2.0 * s12 * w1 * w1 - g * m2 * l2 / 2.0 * p2.cos() - r * (w2 - w1);
    let det = a11 * a22 - a12 * a12;
    [(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det]
}

#[test]
fn two_unequal_rods_follow_their_lagrangian_and_the_dense_reference() {
    for (g, r) in [(9.81, 0.0), (1.0, 0.37), (0.0, 0.05)] {
        let chain = two_rods(g, r);
        for (phi, w) in [
            ([-0.3, 0.8], [1.1, -2.0]),
            ([2.0, -1.2], [0.0, 0.4]),
            ([-1.2, -1.9], [0.0, 0.0]),
        ] {
            let mut acc = [0.0; 2];
            accelerations(&chain, &phi, &w, &mut acc, &mut Workspace::new(2));
            let exact = double_pendulum([0.3, 1.7, 1.5, 0.5, g, r], phi, w);
            let reference = dense::accelerations(&chain, &phi, &w);
            let scale = max_abs(&exact).max(1.0);
            for i in 0..2 {
                assert!(
                    (acc[i] - exact[i]).abs() <= 1e-13 * scale,
                    "{acc:?} vs {exact:?}"
                );
                assert!((reference[i] - exact[i]).abs() <= 1e-13 * scale);
            }
        }
    }
}

/// A catenary start of unequal rods is a static equilibrium with the end
/// held: the potential's gradient (by central differences of the
/// potential energy, independent of the recursion) is the generalised
/// force of one end force `F`, `dV/dphi_i = F . d r_n / dphi_i`, on every
/// rod. So at rest, with `r = 0`, the held chain's accelerations vanish.
#[test]
fn the_catenary_start_of_a_tapered_chain_is_an_exact_equilibrium() {
    for (profile, n) in [
        (
            Profile {
                taper: 10.0,
                ..Profile::default()
            },
            40,
        ),
        (
            Profile {
                taper: 0.2,
                lengths: Some((0..25).map(|i| 1.0 + (i % 3) as f64).collect()),
                ..Profile::default()
            },
            25,
        ),
    ] {
        let chain = Chain::new(ChainParams {
            links: n,
            profile,
            ..ChainParams::default()
        })
        .unwrap();
        let (p0, p1) = ([0.0, 0.0], [3.0, 0.0]);
        let state = Start::Catenary { p0, p1 }.state(&chain).unwrap();
        let phi = &state.angles;
        let r = joints(&chain, p0, phi);
        assert!((r[n][0] - p1[0]).hypot(r[n][1] - p1[1]) < 1e-11);
        // dV/dphi_i by a central difference; d r_n / dphi_i = l_i (-sin, cos).
        let h = 1e-6;
        let grad: Vec<f64> = (0..n)
            .map(|i| {
                let (mut a, mut b) = (phi.clone(), phi.clone());
                a[i] += h;
                b[i] -= h;
                (potential_energy(&chain, &a) - potential_energy(&chain, &b)) / (2.0 * h)
            })
            .collect();
        let lever = |i: usize| {
            let d = [r[i + 1][0] - r[i][0], r[i + 1][1] - r[i][1]];
            [-d[1], d[0]]
        };
        // F from the first and last rods, then every rod checked.
        let (a, b) = (lever(0), lever(n - 1));
        let det = a[0] * b[1] - a[1] * b[0];
        let f = [
            (grad[0] * b[1] - grad[n - 1] * a[1]) / det,
            (a[0] * grad[n - 1] - b[0] * grad[0]) / det,
        ];
        let scale = chain.weight() * chain.length();
        for (i, g) in grad.iter().enumerate() {
            let l = lever(i);
            let res = g - (f[0] * l[0] + f[1] * l[1]);
            assert!(res.abs() < 1e-8 * scale, "rod {i}: {res:e}");
        }
        // The end force carries the weight the pivot does not: F_y in (0, W).
        assert!(f[1] > 0.0 && f[1] < chain.weight());
    }
}

/// A tapered chain released without friction keeps its energy (the
/// observer's per-rod energy, a tight DOPRI5 run).
#[test]
fn a_tapered_chain_released_keeps_its_energy() {
    let chain = Chain::new(ChainParams {
        links: 30,
        profile: Profile {
            taper: 10.0,
            ..Profile::default()
        },
        ..ChainParams::default()
    })
    .unwrap();
    let state = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    let tr = solve(
        &chain,
        &state,
        Method::Dopri5,
        &tolerances(2.0, 1e-10, 1e-12),
    )
    .unwrap();
    let s = &tr.summary;
    assert!(s.energy_balance_error.is_finite());
    let drift = s.energy_balance_error / chain.energy_scale();
    assert!(drift < 1e-7, "drift {drift:e}");
    // The energy the observer fuses per step is the kinematics' one.
    let e0 = chain_ode::kinematics::energy(&chain, &state.angles, &state.rates);
    assert!((s.energy_start - e0).abs() <= 1e-14 * chain.energy_scale());
}

/// The sparse BDF (the banded DAE with per-rod terms) and the dense BDF
/// (the recursion's Jacobian) agree with DOPRI5 on a tapered chain with
/// friction, at the end of the run.
#[test]
fn bdf_on_the_banded_dae_agrees_with_dopri5_on_a_tapered_chain() {
    let chain = Chain::new(ChainParams {
        links: 20,
        damping: 2e-3,
        profile: Profile {
            taper: 10.0,
            lengths: Some((0..20).map(|i| 2.0 - i as f64 / 20.0).collect()),
            ..Profile::default()
        },
        ..ChainParams::default()
    })
    .unwrap();
    let state = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    let opts = tolerances(1.5, 1e-10, 1e-12);
    let end = |m: Method| {
        let tr = solve(&chain, &state, m, &opts).unwrap();
        tr.summary.tip_end
    };
    let reference = end(Method::Dopri5);
    for m in [Method::Bdf, Method::BdfDense] {
        let tip = end(m);
        let d = (tip[0] - reference[0]).hypot(tip[1] - reference[1]);
        assert!(d < 1e-6 * chain.length(), "{}: {d:e}", m.as_str());
    }
}
