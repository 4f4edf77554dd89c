//! Every method on the same scenes: they agree at tight tolerances, `auto`
//! agrees with both, and all complete the report's overflowing folded scene.

use chain_ode::{solve, Accuracy, Chain, Method, SolveOptions, Start, State, Status, Trajectory};

use crate::{dist, folded, run_ok, scene, span3, tolerances};

fn report_scene(which: &str) -> (Chain, State, f64) {
    match which {
        // Report Fig. 7b: span d = 3, n = 50, r = 5e-4, t = 4.157.
        "span-d3" => {
            let (c, s) = span3(50, 5e-4);
            (c, s, 4.157)
        }
        // Report Fig. 6: catenary to (5, 1), n = 25, r = 1e-3, t = 7.348.
        "catenary-fall" => {
            let start = Start::Catenary {
                p0: [0.0, 0.0],
                p1: [5.0, 1.0],
            };
            let (c, s) = scene(25, 1e-3, start);
            (c, s, 7.348)
        }
        // Report Fig. 12: folded, n = 50, r = 1e-3, t = 4.157.
        _ => {
            let (c, s) = folded(50, 1e-3);
            (c, s, 4.157)
        }
    }
}

fn run(chain: &Chain, s: &State, method: Method, t_end: f64, rtol: f64) -> Trajectory {
    run_ok(chain, s, method, &tolerances(t_end, rtol, rtol * 1e-2))
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
    let (chain, s) = span3(400, 5e-4);
    let dp = run(&chain, &s, Method::Dopri5, 4.157, 1e-4);
    assert!(dp.stats.stiffness_detections > 0);
    let auto = run(&chain, &s, Method::Auto, 4.157, 1e-4);
    assert_eq!(auto.segments.len(), 1);
    assert_eq!(auto.stats, dp.stats);
    // ... while the stiff rope (n = 100, r = 1, gamma = 1389) runs BDF from
    // the start.
    let (chain, s) = span3(100, 1.0);
    let auto = run(&chain, &s, Method::Auto, 1.0, 1e-6);
    assert_eq!(auto.segments.len(), 1);
    assert_eq!(auto.segments[0].method, Method::Bdf);
    assert_eq!(auto.segments[0].t_start, 0.0);
}

#[test]
fn names_are_the_user_contract_and_a_bad_one_lists_them_all() {
    let names: Vec<&str> = Method::ALL.iter().map(|m| m.as_str()).collect();
    assert_eq!(
        names,
        ["rk4", "dopri5", "dop853", "bdf", "bdf-dense", "auto"]
    );
    for m in Method::ALL {
        assert_eq!(m.to_string().parse::<Method>(), Ok(m));
    }
    let e = "rk5".parse::<Method>().unwrap_err();
    assert_eq!(
        e.to_string(),
        "run.method: must be one of rk4, dopri5, dop853, bdf, bdf-dense, auto (got rk5)"
    );
}

#[test]
fn the_accuracy_parameter_is_dt_for_rk4_and_rtol_for_the_others() {
    let base = SolveOptions {
        t_end: 2.0,
        ..Default::default()
    };
    for m in Method::ALL {
        let o = base.clone().at_accuracy(m, 1e-6);
        if m == Method::Rk4 {
            assert!(!m.adaptive());
            assert_eq!((m.accuracy(), m.accuracy_name()), (Accuracy::Step, "dt"));
            assert_eq!(
                o,
                SolveOptions {
                    dt: 1e-6,
                    ..base.clone()
                }
            );
        } else {
            assert!(m.adaptive(), "{m}");
            assert_eq!(
                (m.accuracy(), m.accuracy_name()),
                (Accuracy::Tolerance, "rtol")
            );
            assert_eq!(o, tolerances(2.0, 1e-6, 1e-6 * 1e-2));
        }
    }
}
