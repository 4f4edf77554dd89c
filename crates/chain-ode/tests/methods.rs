//! Every method on the same scenes: they agree at tight tolerances, `auto`
//! agrees with both, and all complete the report's overflowing folded scene.

use chain_ode::{solve, Chain, Method, SolveOptions, Start, State, Status, Trajectory};

fn report_scene(which: &str) -> (Chain, State, f64) {
    match which {
        // Report Fig. 7b: span d = 3, n = 50, r = 5e-4, t = 4.157.
        "span-d3" => {
            let c = Chain::report(50, 5e-4).unwrap();
            let s = Start::Catenary {
                p0: [0.0, 0.0],
                p1: [3.0, 0.0],
            };
            (c.clone(), s.state(&c).unwrap(), 4.157)
        }
        // Report Fig. 6: catenary to (5, 1), n = 25, r = 1e-3, t = 7.348.
        "catenary-fall" => {
            let c = Chain::report(25, 1e-3).unwrap();
            let s = Start::Catenary {
                p0: [0.0, 0.0],
                p1: [5.0, 1.0],
            };
            (c.clone(), s.state(&c).unwrap(), 7.348)
        }
        // Report Fig. 12: folded, n = 50, r = 1e-3, t = 4.157.
        _ => {
            let c = Chain::report(50, 1e-3).unwrap();
            let s = Start::Folded {
                p0: [0.0, 0.0],
                down: None,
            };
            (c.clone(), s.state(&c).unwrap(), 4.157)
        }
    }
}

fn run(chain: &Chain, s: &State, method: Method, t_end: f64, rtol: f64) -> Trajectory {
    let opts = SolveOptions {
        t_end,
        rtol,
        atol: rtol * 1e-2,
        ..Default::default()
    };
    let tr = solve(chain, s, method, &opts).unwrap();
    assert_eq!(tr.status, Status::Ok, "{method}");
    tr
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

#[test]
fn every_adaptive_method_agrees_at_tight_tolerances_on_two_report_scenes() {
    for scene in ["span-d3", "catenary-fall"] {
        let (chain, s, t_end) = report_scene(scene);
        let dp = run(&chain, &s, Method::Dopri5, t_end, 1e-11);
        for method in [Method::Dop853, Method::Bdf, Method::BdfDense, Method::Auto] {
            let other = run(&chain, &s, method, t_end, 1e-11);
            let d = dist(dp.summary.tip_end, other.summary.tip_end);
            assert!(
                d < 1e-7,
                "{scene}: DOPRI5 and {method} tips differ by {d:e}"
            );
            let dv = (dp.summary.tip_speed_max - other.summary.tip_speed_max).abs();
            assert!(
                dv < 1e-6 * dp.summary.tip_speed_max,
                "{scene}: {method} vmax {dv:e}"
            );
        }
    }
}

#[test]
fn every_adaptive_method_completes_the_folded_scene_with_energy_balance() {
    let (chain, s, t_end) = report_scene("folded");
    let bound = 1e-6 * chain.weight() * chain.length;
    for method in [
        Method::Dopri5,
        Method::Dop853,
        Method::Bdf,
        Method::BdfDense,
        Method::Auto,
    ] {
        let tr = run(&chain, &s, method, t_end, 1e-8);
        assert!(
            tr.summary.energy_balance_error < bound,
            "{method}: |E + W - E0| = {:e} > {bound:e}",
            tr.summary.energy_balance_error
        );
        assert!(tr.summary.max_energy_rise <= tr.summary.energy_balance_error);
    }
}

#[test]
fn auto_runs_explicit_where_nothing_is_stiff() {
    let (chain, s, t_end) = report_scene("span-d3");
    for (rtol, explicit) in [(1e-6, Method::Dopri5), (1e-10, Method::Dop853)] {
        let auto = run(&chain, &s, Method::Auto, t_end, rtol);
        let alone = run(&chain, &s, explicit, t_end, rtol);
        assert_eq!(auto.segments.len(), 1);
        assert_eq!(auto.segments[0].method, explicit);
        assert_eq!(auto.stats, alone.stats);
    }
}

mod invariants {
    use super::*;
    use chain_ode::kinematics::joints;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// Along any damped run: rods keep their length, and the energy never
        /// rises by more than the integration error of the energy balance.
        #[test]
        fn rods_keep_their_length_and_energy_never_rises(
            n in 2usize..30,
            damping in 1e-4f64..1e-2,
            angles in prop::collection::vec(-3.1f64..3.1, 30),
        ) {
            let chain = Chain::report(n, damping).unwrap();
            let s = Start::Angles { p0: [0.0, 0.0], angles: angles[..n].to_vec(), rates: None }
                .state(&chain)
                .unwrap();
            let opts = SolveOptions {
                t_end: 1.0,
                rtol: 1e-9,
                atol: 1e-11,
                output_dt: Some(0.1),
                ..Default::default()
            };
            let tr = solve(&chain, &s, Method::Dopri5, &opts).unwrap();
            prop_assert_eq!(tr.status, Status::Ok);
            let scale = chain.energy_scale();
            prop_assert!(tr.summary.dissipated >= 0.0);
            prop_assert!(tr.summary.energy_balance_error < 1e-6 * scale);
            prop_assert!(
                tr.summary.max_energy_rise <= tr.summary.energy_balance_error + 1e-13 * scale,
                "E rose by {:e} (balance error {:e})",
                tr.summary.max_energy_rise,
                tr.summary.energy_balance_error
            );
            let l = chain.rod_length();
            for sample in tr.samples() {
                let r = joints(&chain, tr.anchor, sample.angles);
                for p in r.windows(2) {
                    let d = (p[1][0] - p[0][0]).hypot(p[1][1] - p[0][1]);
                    prop_assert!((d - l).abs() < 1e-12 * chain.length);
                }
            }
        }
    }
}

#[test]
fn auto_runs_bdf_only_where_it_pays() {
    // n = 400, r = 5e-4 (gamma = 11): DOPRI5's detector fires on the
    // chain's fastest undamped mode, but that mode (omega ~ 555) is below
    // the crossover: auto stays explicit.
    let chain = Chain::report(400, 5e-4).unwrap();
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    let dp = run(&chain, &s, Method::Dopri5, 4.157, 1e-4);
    assert!(dp.stats.stiffness_detections > 0);
    let auto = run(&chain, &s, Method::Auto, 4.157, 1e-4);
    assert_eq!(auto.segments.len(), 1);
    assert_eq!(auto.stats, dp.stats);
    // ... while the stiff rope (n = 100, r = 1, gamma = 1389) runs BDF from
    // the start.
    let chain = Chain::report(100, 1.0).unwrap();
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    let auto = run(&chain, &s, Method::Auto, 1.0, 1e-6);
    assert_eq!(auto.segments.len(), 1);
    assert_eq!(auto.segments[0].method, Method::Bdf);
    assert_eq!(auto.segments[0].t_start, 0.0);
}
