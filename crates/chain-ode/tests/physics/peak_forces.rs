//! The forces a run reports as properties of the run (issue 49.1): the
//! support's largest force `|F_1|` (`Summary::pivot_force_max`) and the
//! largest joint tension (`PeakForce::Tension`), tracked at every accepted
//! step and refined inside it on the method's continuous extension, never
//! read off the output samples. Checked against closed forms (a rod let go
//! from the horizontal, a chain hanging at rest) and for their independence
//! of the output spacing.

use chain_ode::{
    solve, Chain, ChainParams, Method, PeakForce, SolveOptions, Start, Status, Trajectory,
};

use crate::smooth_methods;

/// One rigid rod (`L = 6`, `m = 0.2`, `g = 1`, no friction), or with
/// `axial_stiffness` an elastic link of that stiffness (critically damped
/// axially), from the horizontal at rest.
fn rod(axial_stiffness: Option<f64>) -> (Chain, chain_ode::State) {
    let (m, l) = (0.2, 6.0);
    let chain = Chain::new(ChainParams {
        links: 1,
        axial_stiffness,
        axial_damping: axial_stiffness.map_or(0.0, |ea| 2.0 * (ea * m * l).sqrt()),
        ..ChainParams::default()
    })
    .unwrap();
    let s = Start::Angles {
        p0: [0.0, 0.0],
        angles: vec![0.0],
        rates: None,
    }
    .state(&chain)
    .unwrap();
    (chain, s)
}

/// `(value, t, reference)` of `force`'s peak.
fn peak(tr: &Trajectory, force: PeakForce) -> (f64, f64, f64) {
    let p = tr.summary.peak(force).unwrap();
    (p.value, p.t, p.reference)
}

/// A uniform rod let go from the horizontal at rest swings down with
/// `w^2 = 3 g sin(theta) / l` (`theta` below the horizontal); the pivot's
/// force on it is `m g (5/2 sin theta, 1/4 cos theta)` along and across
/// the rod, whose magnitude peaks at the bottom at `5/2 m g`, all of it
/// tension, reached at `t = sqrt(l / 3g) Gamma(1/4)^2 / (2 sqrt(2 pi))`.
/// Every smooth method's tracked peaks meet that to its tolerance (rk4 at
/// a fixed step of 1e-3); the bottom is inside a step, so a peak read at
/// the step ends alone would miss it by the curvature's share (about 1e-5
/// at DOPRI5's steps here).
#[test]
fn a_rod_let_go_from_the_horizontal_peaks_at_five_halves_of_its_weight_at_the_bottom() {
    let (chain, s) = rod(None);
    let weight = chain.weight();
    let gamma_quarter: f64 = 3.625_609_908_221_908;
    let t_bottom =
        (6.0f64 / 3.0).sqrt() * gamma_quarter.powi(2) / (2.0 * (2.0 * std::f64::consts::PI).sqrt());
    for method in smooth_methods() {
        let rtol = if method == Method::GenAlpha {
            1e-9
        } else {
            1e-10
        };
        let opts = SolveOptions {
            t_end: 4.5,
            rtol,
            atol: 1e-2 * rtol,
            dt: 1e-3,
            output_dt: Some(0.5),
            ..Default::default()
        };
        let tr = solve(&chain, &s, method, &opts).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method}");
        let tol = if method == Method::Rk4 {
            1e-9
        } else {
            100.0 * rtol
        };
        let (f, t, _) = peak(&tr, PeakForce::Pivot);
        assert!(
            (f / (2.5 * weight) - 1.0).abs() < tol,
            "{method}: pivot {f} against {}",
            2.5 * weight
        );
        assert!(
            (t - t_bottom).abs() < 1e-3,
            "{method}: at {t}, not {t_bottom}"
        );
        let (tension, tt, joint) = peak(&tr, PeakForce::Tension);
        assert!(
            (tension / (2.5 * weight) - 1.0).abs() < tol && joint == 0.0,
            "{method}: tension {tension} at joint {joint}"
        );
        assert!((tt - t).abs() < 1e-3, "{method}: tension at {tt}");
        assert_eq!(tr.summary.pivot_force_max, Some((f, t)), "{method}");
    }
    // A stiff elastic link: the same to its stretch's share, about
    // `2.5 m g / EA` (2.5e-7).
    let (chain, s) = rod(Some(2e6));
    let opts = SolveOptions {
        t_end: 4.5,
        rtol: 1e-9,
        atol: 1e-11,
        ..Default::default()
    };
    for method in [Method::Dopri5, Method::Dop853] {
        let tr = solve(&chain, &s, method, &opts).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method}");
        let (f, t, _) = peak(&tr, PeakForce::Pivot);
        assert!(
            (f / (2.5 * weight) - 1.0).abs() < 1e-5,
            "elastic {method}: {f}"
        );
        assert!((t - t_bottom).abs() < 1e-2, "elastic {method}: at {t}");
        let (tension, _, joint) = peak(&tr, PeakForce::Tension);
        assert!(
            (tension / (2.5 * weight) - 1.0).abs() < 1e-5 && joint == 0.0,
            "elastic {method}: {tension} at {joint}"
        );
    }
}

/// A chain hanging straight down at rest: the pivot carries the weight
/// `M g` and the first joint is the most stretched, `M g` (each joint `k`
/// carries the rods below it); the report's model too (the corrected
/// chain's forces at its state).
#[test]
fn a_hanging_chain_at_rest_carries_its_weight_at_the_pivot() {
    for axial_stiffness in [None, Some(1e5)] {
        let chain = Chain::new(ChainParams {
            links: 12,
            damping: 1e-3,
            axial_stiffness,
            axial_damping: 10.0,
            ..ChainParams::default()
        })
        .unwrap();
        let s = Start::Angles {
            p0: [0.0, 0.0],
            angles: vec![-std::f64::consts::FRAC_PI_2; 12],
            rates: None,
        }
        .state(&chain)
        .unwrap();
        let tr = solve(
            &chain,
            &s,
            Method::Dopri5,
            &crate::tolerances(2.0, 1e-9, 1e-11),
        )
        .unwrap();
        assert_eq!(tr.status, Status::Ok);
        let w = chain.weight();
        let (f, _, _) = peak(&tr, PeakForce::Pivot);
        let (tension, _, joint) = peak(&tr, PeakForce::Tension);
        // The elastic start is the springs' static stretch to rounding;
        // DOPRI5 at 1e-9 lets it ring at 4e-8 of the weight.
        assert!(
            (f / w - 1.0).abs() < 1e-7,
            "{axial_stiffness:?}: {f} vs {w}"
        );
        assert!(
            (tension / w - 1.0).abs() < 1e-7 && joint == 0.0,
            "{axial_stiffness:?}: {tension} at {joint}"
        );
    }
}

/// Changing the output spacing 100 times changes no tracked peak beyond
/// the run's tolerance (they are the steps', not the samples'), on a rigid
/// chain, an elastic rope and a chain landing on a penalty floor; the
/// peaks read off the samples do change.
#[test]
fn the_peak_forces_do_not_depend_on_the_output_spacing() {
    let span = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    };
    let rigid = Chain::new(ChainParams {
        links: 12,
        damping: 5e-4,
        ..ChainParams::default()
    })
    .unwrap();
    let rope = Chain::new(ChainParams {
        axial_stiffness: Some(1e5),
        axial_damping: 0.1 * (1e5f64 * 0.2 * 0.5).sqrt(),
        ..rigid.params().clone()
    })
    .unwrap();
    let rtol = 1e-7;
    for (chain, method) in [
        (&rigid, Method::Dopri5),
        (&rigid, Method::Bdf),
        (&rope, Method::Dopri5),
        (&rope, Method::Bdf),
    ] {
        let s = span.state(chain).unwrap();
        let run = |dt: f64| {
            let opts = SolveOptions {
                t_end: 3.2,
                rtol,
                atol: 1e-2 * rtol,
                output_dt: Some(dt),
                ..Default::default()
            };
            solve(chain, &s, method, &opts).unwrap()
        };
        let (coarse, fine) = (run(0.1), run(1e-3));
        assert_eq!(coarse.status, Status::Ok);
        assert_eq!(fine.status, Status::Ok);
        for force in [PeakForce::Pivot, PeakForce::Tension] {
            let (a, ta, _) = peak(&coarse, force);
            let (b, tb, _) = peak(&fine, force);
            assert!(
                (a - b).abs() <= 10.0 * rtol * b && (ta - tb).abs() < 1e-3,
                "{method} {force:?}: {a} at {ta} against {b} at {tb}"
            );
            // The snap: far above the weight, and beyond what the coarse
            // samples see.
            assert!(b > 3.0 * chain.weight(), "{method} {force:?}: {b}");
        }
        let sampled = (0..coarse.len())
            .map(|k| {
                let f = coarse.support_force(k);
                f[0].hypot(f[1])
            })
            .fold(0.0, f64::max);
        assert!(
            sampled < 0.99 * peak(&coarse, PeakForce::Pivot).0,
            "{sampled}"
        );
    }
}

/// Cayley's reading (`analysis::floor_reading_of`) of the ideal chain's
/// samples, `x = g t^2 / 2` landed and the rest falling freely (`P_y =
/// -mu (L - x) g t`), is 1 over any window, from the momentum (exact
/// whatever the samples miss) and from the sampled force `3 mu g x` alike,
/// to the trapezoid's `O(dt^2)` (checked from `x = 0.02 L` on, samples
/// 1e-3 apart); a window out of range is refused, naming it.
#[test]
fn cayleys_reading_of_the_ideal_chain_is_one() {
    use chain_ode::analysis::{floor_reading_of, FloorSamples};
    use chain_ode::Pivot;
    for release in [Some(0.0), None] {
        let chain = Chain::new(ChainParams {
            length: 1.0,
            links: 40,
            mass: 0.025,
            pivot: Pivot {
                release,
                ..Pivot::default()
            },
            ..ChainParams::default()
        })
        .unwrap();
        let (mu, g, l) = (1.0, 1.0, 1.0);
        let times: Vec<f64> = (0..=1200).map(|k| k as f64 * 1e-3).collect();
        let x = |t: f64| 0.5 * g * t * t;
        let momentum: Vec<[f64; 2]> = times
            .iter()
            .map(|&t| [0.0, -mu * (l - x(t)) * g * t])
            .collect();
        let floor_force: Vec<[f64; 2]> =
            times.iter().map(|&t| [0.0, 3.0 * mu * g * x(t)]).collect();
        let landed: Vec<f64> = times.iter().map(|&t| x(t)).collect();
        let s = FloorSamples {
            times: &times,
            momentum: &momentum,
            floor_force: &floor_force,
            landed_length: &landed,
        };
        for window in [0.02, 0.05, 0.2] {
            let r = floor_reading_of(&chain, 0.0, s, window).unwrap();
            assert!(!r.t.is_empty());
            assert!(r.from_momentum.iter().all(|&m| m == release.is_some()));
            for (t, v) in r.t.iter().zip(&r.reading).filter(|(t, _)| **t >= 0.2) {
                assert!((v - 1.0).abs() < 1e-5, "{release:?} {window}: {v} at {t}");
            }
        }
        let e = floor_reading_of(&chain, 0.0, s, 5.0).unwrap_err();
        assert!(e.starts_with("window must be in"), "{e}");
    }
}

/// A run that landed on the penalty floor does not claim its forces
/// (`solve/forces.rs`, `floor_resolved`: the contact's kinks are where the
/// error estimate does not see the error; measured on 8 rods of the Cayley
/// chain, the largest floor force was 4e-6 to 3e-5 off at rtol 1e-10);
/// the same chain missing the floor does.
#[test]
fn a_run_that_landed_on_the_penalty_floor_does_not_claim_its_forces() {
    use chain_ode::{Floor, FloorLaw, Pivot};
    for (height, landed) in [(None, true), (Some(-3.0), false)] {
        let chain = Chain::new(ChainParams {
            length: 1.0,
            links: 8,
            mass: 0.125,
            axial_stiffness: Some(1e4),
            pivot: Pivot {
                release: Some(0.0),
                ..Pivot::default()
            },
            floor: Some(Floor {
                height,
                angle: 0.0,
                stiffness: 5e6,
                damping: 1000.0,
                friction: 0.0,
                slip_speed: 1e-3,
                law: FloorLaw::Penalty,
                restitution: 0.0,
            }),
            ..ChainParams::default()
        })
        .unwrap();
        let angles = (0..8)
            .map(|i| -std::f64::consts::FRAC_PI_2 + if i % 2 == 0 { 0.02 } else { -0.02 })
            .collect();
        let s = Start::Angles {
            p0: [0.0, 0.0],
            angles,
            rates: None,
        }
        .state(&chain)
        .unwrap();
        let tr = solve(
            &chain,
            &s,
            Method::Dopri5,
            &crate::tolerances(1.0, 1e-8, 1e-11),
        )
        .unwrap();
        assert_eq!(tr.status, Status::Ok, "{height:?}");
        let floor = tr.summary.peak(PeakForce::Floor).unwrap().value;
        assert_eq!(floor > 0.0, landed, "{height:?}: {floor}");
        assert_eq!(tr.summary.forces_resolved, !landed, "{height:?}");
    }
}
