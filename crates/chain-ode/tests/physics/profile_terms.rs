//! Rods of unequal mass and length with every other term (issue 18): a tip
//! mass, bending springs, and a moving or released pivot. The recursion
//! against the dense Lagrangian with the pivot as two more coordinates
//! (random chains, every base) and against a two-rod Lagrangian written out
//! by hand; the bending springs of unequal rods against the continuum's
//! energy on a circle; the banded DAE's residual and Jacobian; and runs
//! against closed forms: the energy balance, both ends let go, and a
//! uniformly accelerating support against gravity `g - a`.

use chain_ode::dae::ChainDae;
use chain_ode::dense::{self, Pivoted};
use chain_ode::dynamics::{accelerations, accelerations_with, Base, Workspace};
use chain_ode::kinematics::bending_energy;
use chain_ode::{
    solve, Chain, ChainParams, ChainSystem, Method, Pivot, Profile, SolveOptions, Start, Status,
};
use proptest::prelude::*;

use crate::{chain_and_state, max_abs};

/// `chain` with its pivot moving as `pivot`.
fn with_pivot(chain: &Chain, pivot: Pivot) -> Chain {
    Chain::new(ChainParams {
        pivot,
        ..chain.params().clone()
    })
    .unwrap()
}

/// A prescribed motion with every part: `P0''(t)` is nonzero in both axes.
fn driven(a: [f64; 2]) -> Pivot {
    Pivot {
        acceleration: a,
        amplitude: [0.05, -0.1],
        frequency: 2.0,
        jerk: [0.3, 0.2],
        jerk_time: 0.9,
        release: None,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The O(n) recursion with a fixed, driven or free pivot against the
    /// dense solve of the chain's Lagrangian with the pivot's two
    /// coordinates (`dense::accelerations_on`): every `phi''`, the pivot's
    /// acceleration and its force, for random profiles, tip masses,
    /// friction and bending.
    #[test]
    fn every_base_matches_the_dense_lagrangian(
        (chain, phi, w) in chain_and_state(60),
        a in prop::array::uniform2(-3.0f64..3.0),
        which in 0u8..3,
    ) {
        let n = chain.links();
        let (base, pivoted) = match which {
            0 => (Base::Fixed, Pivoted::Fixed),
            1 => (Base::Driven(a), Pivoted::Driven(a)),
            _ => (Base::Free, Pivoted::Free),
        };
        let mut acc = vec![0.0; n];
        let r = accelerations_with(&chain, base, &phi, &w, &mut acc, &mut Workspace::new(n));
        let (alpha, p2, force) = dense::accelerations_on(&chain, pivoted, &phi, &w);
        // Angular accelerations scale as w^2, g/l and a/l (1/time^2).
        let l = chain.rod_length();
        let scale = max_abs(&alpha) + max_abs(&w).powi(2) + chain.gravity_rate()
            + (a[0].abs() + a[1].abs()) / l + 1e-300;
        for i in 0..n {
            prop_assert!((acc[i] - alpha[i]).abs() <= 1e-9 * scale,
                "rod {}: {} vs {} (scale {})", i, acc[i], alpha[i], scale);
        }
        // Accelerations and forces scale as l phi'' and m l^2 phi'' per rod.
        let m_tot = chain.total_mass() + chain.tip_mass();
        let a_scale = l * (scale * n as f64 + max_abs(&w).powi(2) * n as f64) + chain.gravity() + a[0].abs() + a[1].abs();
        for k in 0..2 {
            prop_assert!((r.pivot_acceleration[k] - p2[k]).abs() <= 1e-9 * a_scale,
                "P0''[{}]: {} vs {}", k, r.pivot_acceleration[k], p2[k]);
            prop_assert!((r.pivot_force[k] - force[k]).abs() <= 1e-9 * m_tot * a_scale,
                "F0[{}]: {} vs {}", k, r.pivot_force[k], force[k]);
        }
    }

    /// The banded DAE of random chains (profiles, tip masses, bending,
    /// friction) with a driven or free pivot: zero residual at the
    /// recursion's state, and its analytic Jacobian equal to central
    /// differences of its residual in every column.
    #[test]
    fn the_banded_dae_with_every_term_is_consistent_and_its_jacobian_exact(
        (chain, phi, w) in chain_and_state(8),
        a in prop::array::uniform2(-2.0f64..2.0),
        free in any::<bool>(),
    ) {
        let n = chain.links();
        let pivot = if free {
            Pivot { release: Some(0.0), ..Pivot::default() }
        } else {
            driven(a)
        };
        let chain = with_pivot(&chain, pivot);
        let dae = ChainDae::new(&chain).released(free);
        let t = 0.41;
        let dim = dae.dim();
        let mut y = vec![0.0; dim];
        y[..n].copy_from_slice(&phi);
        y[n..2 * n].copy_from_slice(&w);
        dae.make_consistent_at(t, &mut y, &mut Workspace::new(n));
        let mut out = vec![0.0; dim];
        dae.rhs_at(t, &y, &mut out);
        let d = dae.differential_dim();
        let scale = 1.0 + max_abs(&y[d..]);
        prop_assert!(max_abs(&out[d..]) < 1e-11 * scale, "residual {:e}", max_abs(&out[d..]));
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
                let an = jac[r * dim + c];
                prop_assert!((fd - an).abs() < 1e-5 * (1.0 + fd.abs() + scale),
                    "d{}/d{}: {} vs {}", r, c, fd, an);
            }
        }
    }
}

/// Two rods of masses `m1, m2` and lengths `l1, l2` with a point mass `M`
/// at the end and a bending spring `k = EI / ((l1 + l2) / 2)` at their
/// joint, written out from the Lagrangian:
/// `T = (m1/6 + (m2 + M)/2) l1^2 w1^2 + (m2/6 + M/2) l2^2 w2^2 + (m2/2 + M) l1 l2 cos(phi1 - phi2) w1 w2`,
/// `V = g ((m1/2 + m2 + M) l1 sin phi1 + (m2/2 + M) l2 sin phi2) + k (phi2 - phi1)^2 / 2`,
/// friction `r (w2 - w1)` on rod 1 and its opposite on rod 2.
fn two_rods_with_a_tip(
    [m1, m2, tip, l1, l2, g, r, ei]: [f64; 8],
    [p1, p2]: [f64; 2],
    [w1, w2]: [f64; 2],
) -> [f64; 2] {
    let k = ei / (0.5 * (l1 + l2));
    let (c12, s12) = ((p1 - p2).cos(), (p1 - p2).sin());
    let cross = (m2 / 2.0 + tip) * l1 * l2;
    let a11 = (m1 / 3.0 + m2 + tip) * l1 * l1;
    let a12 = cross * c12;
    let a22 = (m2 / 3.0 + tip) * l2 * l2;
    let spring = k * (p2 - p1);
    let b1 =
        -cross * s12 * w2 * w2 - g * (m1 / 2.0 + m2 + tip) * l1 * p1.cos() + r * (w2 - w1) + spring;
    let b2 = cross * s12 * w1 * w1 - g * (m2 / 2.0 + tip) * l2 * p2.cos() - r * (w2 - w1) - spring;
    let det = a11 * a22 - a12 * a12;
    [(a22 * b1 - a12 * b2) / det, (a11 * b2 - a12 * b1) / det]
}

#[test]
fn two_unequal_rods_with_a_tip_mass_and_a_spring_follow_their_lagrangian() {
    // Masses 0.3 and 1.7 (mean 1), lengths 1.5 and 0.5 (mean 1).
    for (g, r, tip, ei) in [
        (9.81, 0.0, 0.4, 0.0),
        (1.0, 0.37, 0.0, 2.0),
        (0.0, 0.05, 2.5, 0.6),
    ] {
        let chain = Chain::new(ChainParams {
            length: 2.0,
            links: 2,
            mass: 1.0,
            gravity: g,
            damping: r,
            tip_mass: tip,
            bending_stiffness: ei,
            profile: Profile {
                masses: Some(vec![0.3, 1.7]),
                lengths: Some(vec![1.5, 0.5]),
                ..Profile::default()
            },
            ..ChainParams::default()
        })
        .unwrap();
        for (phi, w) in [
            ([-0.3, 0.8], [1.1, -2.0]),
            ([2.0, -1.2], [0.0, 0.4]),
            ([-1.2, -1.9], [0.0, 0.0]),
        ] {
            let mut acc = [0.0; 2];
            accelerations(&chain, &phi, &w, &mut acc, &mut Workspace::new(2));
            let exact = two_rods_with_a_tip([0.3, 1.7, tip, 1.5, 0.5, g, r, ei], phi, w);
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

/// Bending of unequal rods: a chain whose joints lie on a circle of
/// radius `R` bends at every joint by the angle its two rods' chords turn
/// through, `(l_{i-1} + l_i) / 2R` to second order; the joint's spring
/// `EI / ((l_{i-1} + l_i) / 2)` then stores `(EI / 2R^2) (l_{i-1} + l_i) / 2`,
/// and the chain `(EI / 2R^2) (L - (l_1 + l_n) / 2)`: the continuum's
/// `(EI / 2) integral (1/R)^2 ds` but for half of each end rod. A spring on
/// either rod's own length instead (`EI / l_i`) misses it by a factor that
/// does not shrink with `n` when neighbours differ.
#[test]
fn the_bending_energy_of_unequal_rods_on_a_circle_is_the_continuums() {
    let (ei, radius, length) = (0.7, 3.0, 2.0);
    for n in [50, 200, 800] {
        // Lengths from 1 to 4, irregular.
        let lengths: Vec<f64> = (0..n).map(|i| 1.0 + ((i * 7) % 4) as f64).collect();
        let chain = Chain::new(ChainParams {
            length,
            links: n,
            bending_stiffness: ei,
            profile: Profile {
                lengths: Some(lengths),
                ..Profile::default()
            },
            ..ChainParams::default()
        })
        .unwrap();
        let rods = chain.rods().unwrap();
        let l: Vec<f64> = rods.length.iter().map(|x| x * chain.rod_length()).collect();
        // Each rod a chord: it turns through 2 asin(l / 2R); the joint
        // between two rods turns the direction by half of each.
        let theta: Vec<f64> = l
            .iter()
            .map(|x| 2.0 * (x / (2.0 * radius)).asin())
            .collect();
        let mut phi = vec![0.3; n];
        for i in 1..n {
            phi[i] = phi[i - 1] + 0.5 * (theta[i - 1] + theta[i]);
        }
        let u = bending_energy(&chain, &phi);
        let expect = ei / (2.0 * radius * radius) * (length - 0.5 * (l[0] + l[n - 1]));
        let rel = u / expect - 1.0;
        // The chords' second-order error, (l / R)^2 / 24 ~ 1e-5 at n = 50.
        assert!(rel.abs() < 1e-4, "n = {n}: {u} vs {expect} ({rel:e})");
        // Against the continuum `EI L / 2R^2`: the end rods' halves, O(1/n).
        let continuum = ei * length / (2.0 * radius * radius);
        assert!((u / continuum - 1.0).abs() < 5.0 / n as f64, "n = {n}");
    }
}

/// A profiled chain with a tip mass and bending springs keeps its energy
/// (`r = 0`) and balances it with friction (`E + W = E(0)`), with DOPRI5
/// and the sparse BDF on the per-rod banded DAE; their tips agree.
#[test]
fn a_tapered_chain_with_a_tip_mass_and_bending_balances_its_energy() {
    for damping in [0.0, 2e-3] {
        let chain = Chain::new(ChainParams {
            links: 16,
            damping,
            tip_mass: 0.5,
            bending_stiffness: 0.02,
            profile: Profile {
                taper: 10.0,
                lengths: Some((0..16).map(|i| 2.0 - i as f64 / 16.0).collect()),
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
        let mut tips = vec![];
        for method in [Method::Dopri5, Method::Bdf] {
            let o = SolveOptions {
                t_end: 1.5,
                output_dt: Some(0.5),
                ..SolveOptions::default()
            }
            .at_accuracy(method, 1e-10);
            let tr = solve(&chain, &state, method, &o).unwrap();
            assert_eq!(tr.status, Status::Ok, "{method}: {:?}", tr.summary);
            let s = &tr.summary;
            let drift = s.energy_balance_error / chain.energy_scale();
            assert!(drift < 1e-8, "{method}, r = {damping}: drift {drift:e}");
            if damping > 0.0 {
                assert!(
                    s.dissipated > 1e-5 * chain.energy_scale(),
                    "{method}: {:e}",
                    s.dissipated / chain.energy_scale()
                );
            }
            // The observer's energy is the kinematics' (tip and U_b included).
            let e0 = chain_ode::kinematics::energy(&chain, &state.angles, &state.rates);
            assert!((s.energy_start - e0).abs() <= 1e-14 * chain.energy_scale());
            tips.push(s.tip_end);
        }
        let d = (tips[0][0] - tips[1][0]).hypot(tips[0][1] - tips[1][1]);
        assert!(d < 1e-5 * chain.length(), "r = {damping}: {d:e}");
    }
}

/// Both ends of a profiled chain let go at rest, with a tip mass (from the
/// U of unequal rods) and with bending (from a straight start, where the
/// springs are at rest): no tension anywhere, every rod falls at `g`, the
/// angles stay, and the tip's acceleration is `g` to rounding.
#[test]
fn a_profiled_chain_with_both_ends_let_go_falls_at_g() {
    let g = 1.3;
    let profile = Profile {
        taper: 10.0,
        lengths: Some((0..20).map(|i| 1.0 + (i % 3) as f64).collect()),
        ..Profile::default()
    };
    let make = |ei: f64| {
        Chain::new(ChainParams {
            links: 20,
            length: 3.0,
            mass: 0.03,
            gravity: g,
            tip_mass: 0.2,
            bending_stiffness: ei,
            pivot: Pivot {
                release: Some(0.0),
                ..Pivot::default()
            },
            profile: profile.clone(),
            ..ChainParams::default()
        })
        .unwrap()
    };
    let cases = [
        (
            make(0.0),
            Start::Catenary {
                p0: [0.0, 0.0],
                p1: [1.8, -0.4],
            },
        ),
        (
            make(0.05),
            Start::Stretched {
                p0: [0.0, 0.0],
                p1: [3.0 * 0.6, 3.0 * 0.8],
            },
        ),
    ];
    for (chain, start) in cases {
        let s = start.state(&chain).unwrap();
        let n = chain.links();
        let tol = 1e-10 * g;
        for method in [Method::Dopri5, Method::Bdf, Method::Rk4] {
            let o = SolveOptions {
                t_end: 1.2,
                output_dt: Some(0.1),
                dt: 2e-3,
                ..SolveOptions::default()
            }
            .at_accuracy(method, if method == Method::Rk4 { 2e-3 } else { 1e-10 });
            let tr = solve(&chain, &s, method, &o).unwrap();
            assert_eq!(tr.status, Status::Ok, "{method}");
            let tip0 = tr.tip(0);
            let mut sys = ChainSystem::new(&chain);
            sys.set_released(true);
            let mut dy = vec![0.0; 2 * n + 1];
            for k in 0..tr.len() {
                let t = tr.times[k];
                for (a, b) in tr.sample(k).angles.iter().zip(&s.angles) {
                    assert!((a - b).abs() < 1e-11, "{method}: t = {t}: {a} vs {b}");
                }
                let tip = tr.tip(k);
                assert!(
                    (tip[0] - tip0[0]).abs() < 1e-9
                        && (tip[1] - (tip0[1] - 0.5 * g * t * t)).abs() < 1e-9,
                    "{method}: t = {t}: {tip:?}"
                );
                let r = sys.rhs_at(t, tr.state(k), &mut dy);
                for acc in [r.tip_acceleration, r.pivot_acceleration] {
                    assert!(
                        acc[0].abs() <= tol && (acc[1] + g).abs() <= tol,
                        "{method}: t = {t}: {acc:?}"
                    );
                }
            }
            assert!(tr.summary.energy_balance_error < 1e-9 * chain.energy_scale());
        }
    }
}

/// A support accelerating at `a` under a profiled chain with a tip mass
/// and bending gives the motion, relative to it, of a fixed support under
/// gravity `g - a`; the inertial frame's energy balance holds.
#[test]
fn a_uniformly_accelerating_support_under_a_profile_is_gravity_minus_a() {
    let (g, a) = (1.0, -0.35);
    let make = |gravity: f64, pivot: Pivot| {
        Chain::new(ChainParams {
            links: 12,
            length: 3.0,
            mass: 0.05,
            gravity,
            damping: 2e-3,
            tip_mass: 0.1,
            bending_stiffness: 5e-3,
            pivot,
            profile: Profile {
                taper: 5.0,
                lengths: Some((0..12).map(|i| 1.0 + (i % 2) as f64).collect()),
                ..Profile::default()
            },
            ..ChainParams::default()
        })
        .unwrap()
    };
    let moving = make(
        g,
        Pivot {
            acceleration: [0.0, a],
            ..Pivot::default()
        },
    );
    let fixed = make(g + a, Pivot::default());
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [1.8, -0.4],
    }
    .state(&moving)
    .unwrap();
    for method in [Method::Dopri5, Method::Bdf] {
        let o = SolveOptions {
            t_end: 3.0,
            output_dt: Some(0.15),
            ..SolveOptions::default()
        }
        .at_accuracy(method, 1e-10);
        let tm = solve(&moving, &s, method, &o).unwrap();
        let tf = solve(&fixed, &s, method, &o).unwrap();
        assert_eq!(tm.status, Status::Ok, "{method}");
        let mut moved = 0.0f64;
        for k in 0..tm.len() {
            for (x, y) in tm.sample(k).angles.iter().zip(tf.sample(k).angles) {
                assert!((x - y).abs() < 1e-6, "{method}: {x} vs {y}");
            }
            let t = tm.times[k];
            for (p, q) in tm.joints(k).iter().zip(&tf.joints(k)) {
                assert!((p[1] - q[1] - 0.5 * a * t * t).abs() < 1e-5, "{method}");
            }
            for (x, y) in tm.sample(k).angles.iter().zip(&s.angles) {
                moved = moved.max((x - y).abs());
            }
        }
        assert!(moved > 0.1, "{method}: {moved}");
        assert!(
            tm.summary.energy_balance_error < 1e-6 * moving.energy_scale(),
            "{method}: {}",
            tm.summary.energy_balance_error
        );
    }
}

/// A profiled pivot released during the fall: after `t_r` the centre of
/// mass (of unequal rods and the tip mass) falls freely, the pivot's path
/// has the recursion's free acceleration, and the balance holds.
#[test]
fn a_profiled_pivot_released_late_frees_the_centre_of_mass() {
    let t_r = 0.7;
    let chain = Chain::new(ChainParams {
        links: 14,
        length: 3.0,
        mass: 0.04,
        damping: 3e-3,
        tip_mass: 0.08,
        bending_stiffness: 2e-3,
        pivot: Pivot {
            release: Some(t_r),
            ..driven([0.0, 0.0])
        },
        profile: Profile {
            taper: 8.0,
            lengths: Some((0..14).map(|i| 1.0 + (i % 4) as f64).collect()),
            ..Profile::default()
        },
        ..ChainParams::default()
    })
    .unwrap();
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [1.8, -0.4],
    }
    .state(&chain)
    .unwrap();
    let n = chain.links();
    let o = SolveOptions {
        t_end: 1.8,
        output_dt: Some(1e-3),
        ..SolveOptions::default()
    }
    .at_accuracy(Method::Dop853, 1e-11);
    let tr = solve(&chain, &s, Method::Dop853, &o).unwrap();
    assert_eq!(tr.status, Status::Ok);
    let com = |k: usize| {
        let smp = tr.sample(k);
        let [c, v] = chain_ode::pivot::centre_of_mass(&chain, smp.angles, smp.rates);
        let [p, pv] = tr.pivot_at(k);
        ([p[0] + c[0], p[1] + c[1]], [pv[0] + v[0], pv[1] + v[1]])
    };
    // The centre of mass against the mass-weighted joints of the sample
    // (independent of `centre_of_mass`): rods at their midpoints, the tip.
    let k_r = tr.times.iter().position(|&t| t >= t_r).unwrap();
    let k_end = tr.len() - 1;
    for k in [0, k_r, k_end] {
        let j = tr.joints(k);
        let rods = chain.rods().unwrap();
        let m = chain.mass();
        let (mut c, mut total) = ([0.0, 0.0], 0.0);
        for i in 0..n {
            let mi = rods.mass[i] * m;
            c[0] += mi * 0.5 * (j[i][0] + j[i + 1][0]);
            c[1] += mi * 0.5 * (j[i][1] + j[i + 1][1]);
            total += mi;
        }
        c[0] += chain.tip_mass() * j[n][0];
        c[1] += chain.tip_mass() * j[n][1];
        total += chain.tip_mass();
        let (cc, _) = com(k);
        assert!((c[0] / total - cc[0]).abs() < 1e-12 && (c[1] / total - cc[1]).abs() < 1e-12);
    }
    let ((c_r, v_r), (c_e, _)) = (com(k_r), com(k_end));
    let dt = tr.times[k_end] - tr.times[k_r];
    let g = chain.gravity();
    assert!((c_e[0] - c_r[0] - v_r[0] * dt).abs() < 1e-9);
    assert!((c_e[1] - c_r[1] - v_r[1] * dt + 0.5 * g * dt * dt).abs() < 1e-9);
    // The pivot's second difference is the recursion's free a_0.
    let mut sys = ChainSystem::new(&chain);
    sys.set_released(true);
    let mut dy = vec![0.0; 2 * n + 1];
    let mut checked = 0;
    for k in (k_r + 20)..k_end {
        let h = tr.times[k] - tr.times[k - 1];
        let p = [
            tr.pivot_at(k - 1)[0],
            tr.pivot_at(k)[0],
            tr.pivot_at(k + 1)[0],
        ];
        let fd = [
            (p[2][0] - 2.0 * p[1][0] + p[0][0]) / (h * h),
            (p[2][1] - 2.0 * p[1][1] + p[0][1]) / (h * h),
        ];
        let a = sys
            .rhs_at(tr.times[k], tr.state(k), &mut dy)
            .pivot_acceleration;
        assert!(
            (fd[0] - a[0]).abs() < 1e-3 && (fd[1] - a[1]).abs() < 1e-3,
            "{fd:?} vs {a:?}"
        );
        checked += 1;
    }
    assert!(checked > 500);
    assert!(tr.summary.energy_balance_error < 1e-7 * chain.energy_scale());
}

/// The support's force along a run with a moving pivot: a hanging
/// profiled chain with a tip mass, its support accelerating at `a`
/// vertically, hangs still and is carried by `(0, M (g + a))`, `M` the
/// whole mass (`analysis::pivot_forces`, which takes the pivot's
/// acceleration at each sample); let go, the support carries nothing.
#[test]
fn the_support_force_of_a_moving_or_released_profiled_pivot() {
    let (g, a) = (1.0, 0.4);
    for (pivot, load) in [
        (
            Pivot {
                acceleration: [0.0, a],
                ..Pivot::default()
            },
            g + a,
        ),
        (
            Pivot {
                release: Some(0.3),
                ..Pivot::default()
            },
            0.0,
        ),
    ] {
        let chain = Chain::new(ChainParams {
            links: 10,
            length: 2.0,
            mass: 0.05,
            gravity: g,
            tip_mass: 0.2,
            bending_stiffness: 1e-3,
            pivot,
            profile: Profile {
                taper: 4.0,
                lengths: Some((0..10).map(|i| 1.0 + (i % 3) as f64).collect()),
                ..Profile::default()
            },
            ..ChainParams::default()
        })
        .unwrap();
        let s = Start::Angles {
            p0: [0.0, 0.0],
            angles: vec![-std::f64::consts::FRAC_PI_2; 10],
            rates: None,
        }
        .state(&chain)
        .unwrap();
        let o = SolveOptions {
            t_end: 1.0,
            output_dt: Some(0.1),
            ..SolveOptions::default()
        }
        .at_accuracy(Method::Dopri5, 1e-10);
        let tr = solve(&chain, &s, Method::Dopri5, &o).unwrap();
        assert_eq!(tr.status, Status::Ok);
        let weight = chain.total_mass() + chain.tip_mass();
        for (t, f) in chain_ode::analysis::pivot_forces(&tr) {
            let want = if t < 0.3 && load == 0.0 { g } else { load };
            assert!(
                f[0].abs() < 1e-9 && (f[1] - weight * want).abs() < 1e-9,
                "t = {t}: {f:?} vs {}",
                weight * want
            );
        }
    }
}
