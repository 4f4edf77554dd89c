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
    let rtol = 1e-8;
    let scale = chain.energy_scale();
    for method in [
        Method::Dopri5,
        Method::Dop853,
        Method::Bdf,
        Method::BdfDense,
        Method::Auto,
    ] {
        let tr = run(&chain, &s, method, t_end, rtol);
        // Measured |E + W - E0| / (rtol scale): DOPRI5 0.15, DOP853 (and
        // auto, which runs it) 0.07; bdf 29, bdf-dense 11 (at equal rtol
        // BDF's global error through the whip is far larger). Bounds 5x to
        // 7x above.
        let bound = match method {
            Method::Bdf | Method::BdfDense => 150.0,
            _ => 1.0,
        } * rtol
            * scale;
        assert!(
            tr.summary.energy_balance_error < bound,
            "{method}: |E + W - E0| = {:e} > {bound:e}",
            tr.summary.energy_balance_error
        );
        // With friction E falls at every step; what rises is rounding
        // (measured 0 for the explicit methods, 4e-14 for the BDFs).
        assert!(
            tr.summary.max_energy_rise <= 1e-12 * scale,
            "{method}: E rose by {:e}",
            tr.summary.max_energy_rise
        );
        assert!(tr.summary.dissipated > 0.0);
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
    //! The design's energy invariants, along runs of every method.
    //!
    //! Rod length needs no test here: in angle coordinates it is exact by
    //! construction (`dynamics.rs` keeps the one test of `joints`). What a
    //! bug can break is the energy: `E + W` must stay at `E(0)` to the
    //! method's error, the dissipated work `W` (a state variable, integrated
    //! from `W' = 2R(w) >= 0`) must never decrease, and hence `E` never rises
    //! by more than the balance error. A friction sign error, a `W` that
    //! misses a term, or an energy that drifts all fail these.

    use super::*;
    use chain_ode::kinematics::energy;
    use proptest::prelude::*;

    /// Accuracy of each method in this test: `dt` for RK4, `rtol` (with
    /// `atol = rtol / 100`) for the others.
    fn accuracy(method: Method) -> f64 {
        match method {
            Method::Rk4 => 2.5e-4,
            _ => 1e-8,
        }
    }

    /// The bound on `|E + W - E(0)| / energy_scale` for `method` at
    /// [`accuracy`]: set 5 to 10x above the worst seen over 48 cases
    /// (`cargo test --release -p chain-ode --test physics invariants --
    /// --nocapture` prints every run's ratio). A friction term of the wrong
    /// sign fails it at once (E rises by 4e-7 of the scale in 0.08).
    fn balance_bound(method: Method) -> f64 {
        match method {
            Method::Rk4 => BOUND_RK4,
            Method::Dopri5 | Method::Dop853 | Method::Auto => BOUND_EXPLICIT,
            Method::Bdf | Method::BdfDense => BOUND_BDF,
            Method::GenAlpha => BOUND_GEN_ALPHA,
            // Runs a chain on a constraint floor only (tests/physics/contact.rs).
            Method::MoreauJean => f64::NAN,
        }
    }
    /// RK4 at `dt = 2.5e-4` (a quarter of its stability limit at the
    /// stiffest friction here): worst seen WORST_RK4.
    const BOUND_RK4: f64 = 1e-8;
    /// DOPRI5, DOP853 and `auto` at `rtol = 1e-8`: worst seen 8.6e-9 over
    /// 48 cases, in DOPRI5's dense output without friction; 5 rtol.
    const BOUND_EXPLICIT: f64 = 5e-8;
    /// Both BDFs at `rtol = 1e-8`: worst seen 4.7e-8 over 48 cases (`bdf`,
    /// no friction); at equal `rtol` BDF's global error is larger than the
    /// explicit pairs'. 30 rtol.
    const BOUND_BDF: f64 = 3e-7;
    /// `gen-alpha` at `rtol = 1e-8`: second order, its error measured on
    /// the angles alone, so its balance error is the largest at equal
    /// `rtol`: worst seen 4.3e-7 over 48 cases (a sample's balance, no
    /// friction), 2.6e-7 at the run's end; 7x above it.
    const BOUND_GEN_ALPHA: f64 = 3e-6;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// From any state of a chain of 30 to 48 rods, without friction, with
        /// mild friction and with stiff friction (damping rate up to ~100,
        /// spectral radius ~5000), every method keeps `E + W = E(0)` within
        /// a bound set by its accuracy, never lets `W` decrease, and never
        /// lets `E` rise by more than that bound.
        #[test]
        fn energy_balance_holds_and_dissipated_work_never_decreases(
            n in 30usize..=48,
            friction in 0usize..3,
            r in 0.0f64..1.0,
            angles in prop::collection::vec(-3.1f64..3.1, 48),
            rates in prop::collection::vec(-1.0f64..1.0, 48),
        ) {
            let damping = match friction {
                0 => 0.0,
                1 => 1e-4 + 1e-2 * r,
                _ => 0.05 + 0.15 * r,
            };
            let chain = Chain::report(n, damping).unwrap();
            let s = Start::Angles {
                p0: [0.0, 0.0],
                angles: angles[..n].to_vec(),
                rates: Some(rates[..n].to_vec()),
            }
            .state(&chain)
            .unwrap();
            let scale = chain.energy_scale();
            for method in Method::ALL.into_iter().filter(|m| !m.is_nonsmooth()) {
                let opts = SolveOptions {
                    t_end: 0.5,
                    output_dt: Some(0.01),
                    ..Default::default()
                }
                .at_accuracy(method, accuracy(method));
                let tr = solve(&chain, &s, method, &opts).unwrap();
                prop_assert_eq!(tr.status, Status::Ok, "{}", method);
                let e0 = energy(&chain, &s.angles, &s.rates);
                let bound = balance_bound(method) * scale;
                let (mut worst, mut e_prev, mut w_prev) = (0.0f64, e0, 0.0);
                for sample in tr.samples() {
                    let e = energy(&chain, sample.angles, sample.rates);
                    let w = sample.dissipated;
                    worst = worst.max((e + w - e0).abs());
                    if damping == 0.0 {
                        // Nothing is dissipated without friction, not even by rounding.
                        prop_assert_eq!(w, 0.0, "{}", method);
                    }
                    prop_assert!(w >= w_prev, "{}: W fell from {:e} to {:e} at t = {}",
                        method, w_prev, w, sample.t);
                    prop_assert!(e <= e_prev + bound, "{}: E rose by {:e} at t = {}",
                        method, e - e_prev, sample.t);
                    (e_prev, w_prev) = (e, w);
                }
                // Between steps (the samples, from the dense output) and at
                // every step's end (the summary's own measure).
                prop_assert!(worst <= bound, "{}: samples' |E + W - E0| = {:e} > {:e}",
                    method, worst, bound);
                prop_assert!(tr.summary.energy_balance_error <= bound,
                    "{}: |E + W - E0| = {:e} > {:e} (n = {}, r = {})",
                    method, tr.summary.energy_balance_error, bound, n, damping);
                eprintln!("invariants: {method} n {n} r {damping:.3e} balance/scale {:.3e} samples {:.3e}",
                    tr.summary.energy_balance_error / scale, worst / scale);
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
        [
            "rk4",
            "dopri5",
            "dop853",
            "bdf",
            "bdf-dense",
            "auto",
            "gen-alpha",
            "moreau-jean"
        ]
    );
    for m in Method::ALL {
        assert_eq!(m.to_string().parse::<Method>(), Ok(m));
    }
    let e = "rk5".parse::<Method>().unwrap_err();
    assert_eq!(
        e.to_string(),
        "run.method: must be one of rk4, dopri5, dop853, bdf, bdf-dense, auto, gen-alpha, moreau-jean \
         (got rk5)"
    );
}

#[test]
fn the_accuracy_parameter_is_dt_for_rk4_and_moreau_jean_and_rtol_for_the_others() {
    let base = SolveOptions {
        t_end: 2.0,
        ..Default::default()
    };
    for m in Method::ALL {
        let o = base.clone().at_accuracy(m, 1e-6);
        if matches!(m, Method::Rk4 | Method::MoreauJean) {
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

#[test]
fn auto_hands_over_to_bdf_mid_run_and_keeps_the_state() {
    // An elastic chain (20 rods, EA = 1e6) whose joints are critically
    // damped (eta = 500: zeta = eta / (2 sqrt(EA m l)) = 1.02, past
    // AUTO_ELASTIC_ZETA): DOPRI5's stiffness detector fires on the springs,
    // and auto hands the rest of the run to BDF.
    let (rigid, s) = span3(20, 5e-4);
    let chain = Chain::new(chain_ode::ChainParams {
        axial_stiffness: Some(1e6),
        axial_damping: 500.0,
        ..rigid.params().clone()
    })
    .unwrap();
    let (t_end, rtol) = (0.5, 1e-6);
    // Samples 2e-5 apart: the damped springs make the detector fire within
    // the first millisecond.
    let opts = SolveOptions {
        output_dt: Some(2e-5),
        ..tolerances(t_end, rtol, rtol * 1e-2)
    };
    let auto = run_ok(&chain, &s, Method::Auto, &opts);
    let dp = run_ok(&chain, &s, Method::Dopri5, &opts);
    assert!(dp.stats.stiffness_detections > 0);
    let [first, second] = &auto.segments[..] else {
        panic!("one handover expected: {:?}", auto.segments);
    };
    assert_eq!((first.method, second.method), (Method::Dopri5, Method::Bdf));
    assert_eq!((first.t_start, second.t_end), (0.0, t_end));
    assert_eq!(first.t_end, second.t_start);
    let t_switch = first.t_end;
    assert!(t_switch > 2e-4 && t_switch < t_end - 0.05, "{t_switch}");
    // Up to the handover auto is DOPRI5 alone, bit for bit.
    let mut before = 0;
    for (a, d) in auto.samples().zip(dp.samples()) {
        if a.t > t_switch {
            break;
        }
        assert_eq!((a.t, a.angles, a.rates), (d.t, d.angles, d.rates));
        before += 1;
    }
    assert!(before > 10, "{before} samples before t = {t_switch}");
    // After it, BDF carries on from DOPRI5's state: the result is the
    // chain's to the tolerance. Measured against DOP853 at 1e-10 (handover
    // at t = 0.00101, 51 samples before it): tip 7.7e-8, |E + W - E0|
    // 1.4e-8 of the scale.
    let reference = run(&chain, &s, Method::Dop853, t_end, 1e-10);
    let d = dist(auto.summary.tip_end, reference.summary.tip_end);
    let balance = auto.summary.energy_balance_error / chain.energy_scale();
    assert!(d < 1e-6, "tip off by {d:e}");
    assert!(balance < 1e-6, "balance {balance:e}");
    let w: Vec<f64> = auto.samples().map(|x| x.dissipated).collect();
    assert!(w.windows(2).all(|p| p[1] >= p[0]), "W fell");
}

#[test]
fn auto_keeps_the_accuracy_of_the_better_method_where_dopri5_is_held_by_stability() {
    // 400 rods, span d = 3, r = 5e-4: DOPRI5 is held at its stability limit
    // (its stiffness detector fires through the whip) and far more accurate
    // than asked; BDF at the same rtol is not, and no faster. auto stays
    // with DOPRI5 (no handover on a chain) and must be within 10x of the
    // better method's energy-balance error (the stability map's rule).
    // Measured: DOPRI5 2.4e-3 and 2.4e-5, BDF 2.2 and 0.29 at rtol 1e-2
    // and 1e-3; auto handing over gave 2.41 and 6.6e-2.
    let (chain, s) = span3(400, 5e-4);
    for rtol in [1e-2, 1e-3] {
        let opts = tolerances(4.157, rtol, rtol * 1e-2);
        let err = |m| run_ok(&chain, &s, m, &opts).summary.energy_balance_error;
        let auto = run_ok(&chain, &s, Method::Auto, &opts);
        assert_eq!(auto.segments.len(), 1, "rtol {rtol:e}: {:?}", auto.segments);
        let better = err(Method::Dopri5).min(err(Method::Bdf));
        let e = auto.summary.energy_balance_error;
        assert!(
            e <= 10.0 * better,
            "rtol {rtol:e}: auto {e:e}, better {better:e}"
        );
    }
}
