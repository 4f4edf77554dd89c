//! The report's own model (`chain_ode::report`): its equations against a
//! hand derivation at `n = 2`, its corrected form against the O(n)
//! recursion, its clock, its stepper's order, and what it refuses.

use chain_ode::report::{ReportModel, ReportSystem, REPORT_MAX_LINKS};
use chain_ode::{
    dynamics, solve, Chain, ChainParams, Method, ReportChain, SolveOptions, Start, Status,
};

use crate::{max_abs, span, tolerances};

/// `phi''` of the report's equations at `n = 2`, from the 2 x 2 system
/// written out by hand (1-based): with `delta = 1` for the 0-based
/// indices, `mt_11 = 4/3 + delta`, `mt_22 = 1/3 + delta`, `mt_12 = 1/2 + delta`,
/// `q_1 = 3/2 + delta`, `q_2 = 1/2 + delta`, `c = cos(phi1 - phi2)`,
/// `s = sin(phi1 - phi2)`:
///
/// ```text
/// mt_11 phi1'' + mt_12 c phi2'' + mt_12 s w2^2 + G q_1 cos phi1 = sigma gamma (w2 - w1)
/// mt_12 c phi1'' + mt_22 phi2'' - mt_12 s w1^2 + G q_2 cos phi2 = sigma gamma (w1 - w2)
/// ```
///
/// solved by Cramer's rule.
fn two_rods(delta: f64, g: f64, sigma_gamma: f64, phi: [f64; 2], w: [f64; 2]) -> [f64; 2] {
    let (m11, m22, m12) = (4.0 / 3.0 + delta, 1.0 / 3.0 + delta, 0.5 + delta);
    let (q1, q2) = (1.5 + delta, 0.5 + delta);
    let (c, s) = ((phi[0] - phi[1]).cos(), (phi[0] - phi[1]).sin());
    let b1 = sigma_gamma * (w[1] - w[0]) - m12 * s * w[1] * w[1] - g * q1 * phi[0].cos();
    let b2 = sigma_gamma * (w[0] - w[1]) + m12 * s * w[0] * w[0] - g * q2 * phi[1].cos();
    let det = m11 * m22 - m12 * m12 * c * c;
    [
        (m22 * b1 - m12 * c * b2) / det,
        (m11 * b2 - m12 * c * b1) / det,
    ]
}

fn chain(n: usize, damping: f64, gravity: f64) -> Chain {
    Chain::new(ChainParams {
        links: n,
        damping,
        gravity,
        ..ChainParams::default()
    })
    .unwrap()
}

#[test]
fn two_rods_follow_the_hand_derived_equations_of_the_report() {
    // L = 6, n = 2: l = 3, m = 0.2; r = 0.05 gives gamma = r / (m l^2).
    let (r, g) = (0.05, 1.7);
    let c = chain(2, r, g);
    let gamma = r / (0.2 * 9.0);
    let states = [
        ([0.3, -1.1], [0.7, -2.0]),
        ([-2.5, 0.4], [-1.3, 0.9]),
        ([1.0, 1.0], [0.0, 3.0]),
    ];
    let models = [
        // As coded: 0-based indices, G = 1, dissipative friction.
        (ReportModel::AS_CODED, 1.0, 1.0, gamma),
        // As printed: the friction's sign flipped.
        (
            ReportModel {
                printed_friction_sign: true,
                ..ReportModel::AS_CODED
            },
            1.0,
            1.0,
            -gamma,
        ),
        // Corrected: 1-based indices, G = g/l.
        (ReportModel::CORRECTED, 0.0, g / 3.0, gamma),
    ];
    for (model, delta, big_g, sg) in models {
        let mut sys = ReportSystem::new(&c, model);
        for (phi, w) in states {
            let mut acc = [0.0; 2];
            sys.accelerations(&phi, &w, &mut acc);
            let want = two_rods(delta, big_g, sg, phi, w);
            for i in 0..2 {
                assert!(
                    (acc[i] - want[i]).abs() <= 1e-13 * (1.0 + want[i].abs()),
                    "{model:?} at {phi:?}, {w:?}: {acc:?} against {want:?}"
                );
            }
        }
    }
}

#[test]
fn corrected_it_is_the_chain_of_the_o_n_recursion() {
    // An independent formulation of the corrected model: the dense report
    // system with every erratum off against the articulated-body recursion.
    let c = chain(9, 3e-3, 1.3);
    let mut sys = ReportSystem::new(&c, ReportModel::CORRECTED);
    let phi: Vec<f64> = (0..9).map(|i| (0.7 * i as f64).sin() * 2.0 - 0.4).collect();
    let w: Vec<f64> = (0..9).map(|i| (1.3 * i as f64).cos() * 1.5).collect();
    let mut dense = vec![0.0; 9];
    sys.accelerations(&phi, &w, &mut dense);
    let mut ws = dynamics::Workspace::new(9);
    let mut fast = vec![0.0; 9];
    dynamics::accelerations(&c, &phi, &w, &mut fast, &mut ws);
    let scale = 1.0 + max_abs(&fast);
    for i in 0..9 {
        assert!(
            (dense[i] - fast[i]).abs() < 1e-11 * scale,
            "{i}: {dense:?} {fast:?}"
        );
    }
}

#[test]
fn its_indices_are_a_tip_mass_of_one_rod() {
    // One added to every mt_ij and every q_i is a point mass m at the free
    // end: the report's 0-based indices against the O(n) recursion of the
    // corrected chain with chain.tip_mass = m (its own, independent model).
    let with_tip = Chain::new(ChainParams {
        links: 7,
        damping: 2e-3,
        gravity: 1.3,
        tip_mass: 0.2,
        ..ChainParams::default()
    })
    .unwrap();
    let plain = chain(7, 2e-3, 1.3);
    let indices_only = ReportModel {
        indices: true,
        ..ReportModel::CORRECTED
    };
    let mut sys = ReportSystem::new(&plain, indices_only);
    let phi: Vec<f64> = (0..7).map(|i| (0.9 * i as f64).cos() * 1.7).collect();
    let w: Vec<f64> = (0..7).map(|i| (0.4 * i as f64).sin() * 2.0 - 0.3).collect();
    let mut report = vec![0.0; 7];
    sys.accelerations(&phi, &w, &mut report);
    let mut ws = dynamics::Workspace::new(7);
    let mut tip = vec![0.0; 7];
    dynamics::accelerations(&with_tip, &phi, &w, &mut tip, &mut ws);
    let scale = 1.0 + max_abs(&tip);
    for i in 0..7 {
        assert!(
            (report[i] - tip[i]).abs() < 1e-11 * scale,
            "{i}: {report:?} {tip:?}"
        );
    }
}

/// Options of a tight DOPRI5 run to `t_end`.
fn tight(t_end: f64) -> SolveOptions {
    tolerances(t_end, 1e-12, 1e-14)
}

#[test]
fn its_clock_runs_in_units_of_sqrt_l_over_g() {
    // Gravity without g/l, nothing else: the corrected chain with time
    // rescaled by sqrt(l/g). g != 1 and l != 1 so that neither sqrt(l)
    // nor sqrt(1/g) nor no rescaling passes.
    let c = chain(8, 0.0, 2.5);
    let l = c.rod_length();
    let start = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&c)
    .unwrap();
    let clock_only = ReportModel {
        clock: true,
        ..ReportModel::CORRECTED
    };
    let unit = clock_only.time_unit(&c);
    assert!((unit - (l / 2.5f64).sqrt()).abs() < 1e-15, "{unit}");
    let tau = 3.0;
    let rep = solve(
        ReportChain::new(&c, clock_only),
        &start,
        Method::Dopri5,
        &tight(tau),
    )
    .unwrap();
    let cor = solve(&c, &start, Method::Dopri5, &tight(tau * unit)).unwrap();
    assert_eq!((rep.status, cor.status), (Status::Ok, Status::Ok));
    let n = c.links();
    let diff: Vec<f64> = (0..n)
        .map(|i| rep.final_state[i] - cor.final_state[i])
        .collect();
    assert!(max_abs(&diff) < 1e-7, "angles differ by {}", max_abs(&diff));
    // Rates and speeds in the report's unit are ours times that unit.
    for i in n..2 * n {
        let want = cor.final_state[i] * unit;
        assert!((rep.final_state[i] - want).abs() < 1e-7, "{i}");
    }
    let v = rep.summary.tip_speed_max / unit;
    assert!(
        (v / cor.summary.tip_speed_max - 1.0).abs() < 1e-7,
        "{v} against {}",
        cor.summary.tip_speed_max
    );
}

#[test]
fn the_reports_stepper_is_first_order() {
    // The report's model as coded, span d = 3, n = 5, to tau = 2: the error
    // of its "RK4" against a tight DOPRI5 run of the same equations halves
    // with the step, where RK4 on the same equations falls 16-fold.
    let (c, s) = span(5, 1e-3, 3.0);
    let reference = solve(
        ReportChain::new(&c, ReportModel::AS_CODED),
        &s,
        Method::Dopri5,
        &tight(2.0),
    )
    .unwrap()
    .final_state;
    let error = |model: ReportModel, dt: f64| {
        let opts = SolveOptions {
            t_end: 2.0,
            dt,
            ..Default::default()
        };
        let run = solve(ReportChain::new(&c, model), &s, Method::Rk4, &opts).unwrap();
        assert_eq!(run.status, Status::Ok);
        let d: Vec<f64> = (0..10).map(|i| run.final_state[i] - reference[i]).collect();
        max_abs(&d)
    };
    let reports: Vec<f64> = [0.01, 0.005, 0.0025]
        .iter()
        .map(|&dt| error(ReportModel::AS_CODED, dt))
        .collect();
    for k in 0..2 {
        let rate = (reports[k] / reports[k + 1]).log2();
        assert!((0.85..1.15).contains(&rate), "order {rate}: {reports:?}");
    }
    let rk4 = ReportModel {
        stepper: false,
        ..ReportModel::AS_CODED
    };
    let (e1, e2) = (error(rk4, 0.01), error(rk4, 0.005));
    let rate = (e1 / e2).log2();
    assert!(rate > 3.5, "RK4 order {rate}: {e1:e} {e2:e}");
}

#[test]
fn the_printed_friction_sign_feeds_energy_in() {
    // E + W = E(0) holds in both signs; the printed sign's work is negative
    // (energy in), the coded one's positive.
    let (c, s) = span(6, 2e-2, 4.0);
    for (printed, sign) in [(false, 1.0), (true, -1.0)] {
        let model = ReportModel {
            printed_friction_sign: printed,
            ..ReportModel::AS_CODED
        };
        let run = solve(ReportChain::new(&c, model), &s, Method::Dopri5, &tight(3.0)).unwrap();
        assert_eq!(run.status, Status::Ok);
        assert!(run.summary.energy_balance_error < 1e-8, "{printed}");
        assert!(
            sign * run.summary.dissipated > 1e-3,
            "{printed}: {}",
            run.summary.dissipated
        );
    }
}

#[test]
fn it_refuses_what_the_report_has_not() {
    let (c, s) = span(6, 1e-3, 3.0);
    let opts = SolveOptions::default();
    for m in [Method::Bdf, Method::BdfDense, Method::Auto] {
        let e = solve(ReportChain::new(&c, ReportModel::AS_CODED), &s, m, &opts).unwrap_err();
        assert_eq!(e.field, "run.method", "{m}");
    }
    for (field, params) in [
        (
            "chain.axial_stiffness",
            ChainParams {
                links: 6,
                axial_stiffness: Some(1e4),
                ..ChainParams::default()
            },
        ),
        (
            "chain.bending_stiffness",
            ChainParams {
                links: 6,
                bending_stiffness: 0.1,
                ..ChainParams::default()
            },
        ),
        (
            "chain.tip_mass",
            ChainParams {
                links: 6,
                tip_mass: 0.1,
                ..ChainParams::default()
            },
        ),
        (
            "chain.links",
            ChainParams {
                links: REPORT_MAX_LINKS + 1,
                ..ChainParams::default()
            },
        ),
    ] {
        let c = Chain::new(params).unwrap();
        let s = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [3.0, 0.0],
        }
        .state(&c)
        .unwrap();
        let e = solve(
            ReportChain::new(&c, ReportModel::AS_CODED),
            &s,
            Method::Rk4,
            &opts,
        )
        .unwrap_err();
        assert_eq!(e.field, field);
    }
}

#[test]
fn the_reports_tip_speed_leaves_out_rod_one_and_ends_mid_rod() {
    // Three rods, rod 1 turning alone: the report's point does not move.
    // Rod 3 turning alone at rate 1: its midpoint moves at l/2.
    let c = chain(3, 0.0, 1.0);
    let l = c.rod_length();
    let times = [0.0, 1e-6];
    let a0 = [0.3, -0.2, 0.5];
    let rod1 = [0.3 + 1e-6, -0.2, 0.5];
    let rod3 = [0.3, -0.2, 0.5 + 1e-6];
    let v = chain_ode::report::finite_difference_tip_speeds(&c, &times, &[&a0, &rod1]);
    assert_eq!(v.len(), 1);
    assert!(v[0][1].abs() < 1e-12, "{v:?}");
    let v = chain_ode::report::finite_difference_tip_speeds(&c, &times, &[&a0, &rod3]);
    assert!((v[0][1] - 0.5 * l).abs() < 1e-6, "{v:?}");
    assert_eq!(v[0][0], 1e-6);
}

#[test]
fn the_reports_tip_velocity_is_the_chord_of_its_point() {
    // A straight chain of n rods turning rigidly about P0 at rate w: the
    // report's point lies at R = l (n - 1.5) from P0 (rod 1 left out, the
    // last rod's midpoint), so between two samples it moves along the chord
    // R (cos phi1 - cos phi0, sin phi1 - sin phi0).
    let c = chain(5, 0.0, 1.0);
    let l = c.rod_length();
    let r = l * 3.5;
    let (w, dt) = (2.0, 0.05);
    let times = [0.0, dt, 2.0 * dt];
    let at = |t: f64| vec![-0.4 + w * t; 5];
    let (a0, a1, a2) = (at(times[0]), at(times[1]), at(times[2]));
    let angles = [&a0[..], &a1[..], &a2[..]];
    let v = chain_ode::report::finite_difference_tip_velocities(&c, &times, &angles);
    let s = chain_ode::report::finite_difference_tip_speeds(&c, &times, &angles);
    assert_eq!(v.len(), 2);
    for k in 0..2 {
        let (p0, p1) = (angles[k][0], angles[k + 1][0]);
        let want = [
            r * (p1.cos() - p0.cos()) / dt,
            r * (p1.sin() - p0.sin()) / dt,
        ];
        assert_eq!(v[k][0], times[k + 1]);
        assert!((v[k][1] - want[0]).abs() < 1e-12, "{v:?} {want:?}");
        assert!((v[k][2] - want[1]).abs() < 1e-12, "{v:?} {want:?}");
        // Its norm is the report's speed: the chord over the step, not w R.
        assert!((v[k][1].hypot(v[k][2]) - s[k][1]).abs() < 1e-12);
        let chord = 2.0 * r * (0.5 * w * dt).sin() / dt;
        assert!((s[k][1] - chord).abs() < 1e-12, "{s:?} {chord}");
    }
}

/// The report's model carries gravity and joint friction alone: every
/// other load of `chain_ode::load::KINDS`, switched on, is refused by its
/// own key (through the scene's model too), and the two it carries are
/// not. A load added to the crate is walked here without a line of this
/// test changing.
#[test]
fn the_report_model_refuses_every_load_it_cannot_carry_by_its_key() {
    use chain_ode::load::KINDS;
    use chain_ode::report::{ReportModel, REPORT_LOADS};
    use chain_ode::{ChainParams, ReportChain};
    let mut refused = 0;
    for kind in KINDS {
        let mut params = ChainParams {
            links: 10,
            ..ChainParams::default()
        };
        (kind.switch_on)(&mut params);
        let chain = Chain::new(params).unwrap();
        let s = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [1.0, 0.0],
        }
        .state(&chain)
        .unwrap();
        let model = ReportChain::new(&chain, ReportModel::AS_CODED);
        let run = solve(model, &s, Method::Dopri5, &SolveOptions::default());
        if REPORT_LOADS.contains(&kind.key) {
            assert!(
                ReportModel::AS_CODED.validate(&chain).is_ok(),
                "{}",
                kind.name
            );
            assert!(run.is_ok(), "{}", kind.name);
        } else {
            let e = ReportModel::AS_CODED.validate(&chain).unwrap_err();
            assert_eq!(e.field, kind.key, "{}: {e}", kind.name);
            assert_eq!(run.unwrap_err().field, kind.key, "{}", kind.name);
            refused += 1;
        }
    }
    assert_eq!(refused, KINDS.len() - REPORT_LOADS.len());
}
