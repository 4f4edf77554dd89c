//! DOPRI5 against an independent RK4 reference, its order, energy and statuses.

use chain_ode::{solve, Chain, Method, SolveOptions, Start, State, Status, Trajectory};

use crate::{dist, folded, run_ok, span};

fn run(chain: &Chain, s: &State, method: Method, opts: SolveOptions) -> Trajectory {
    run_ok(chain, s, method, &opts)
}

#[test]
fn error_falls_at_fifth_order_in_the_number_of_steps() {
    let (chain, s) = span(10, 0.0, 3.0);
    let t_end = 1.5;
    // Independent reference: RK4 with dt = 1e-4 (error ~1e-15 here).
    let reference = run(
        &chain,
        &s,
        Method::Rk4,
        SolveOptions {
            t_end,
            dt: 1e-4,
            ..Default::default()
        },
    );
    let (mut xs, mut ys) = (vec![], vec![]);
    for rtol in [1e-5, 1e-6, 1e-7, 1e-8, 1e-9] {
        let tr = run(
            &chain,
            &s,
            Method::Dopri5,
            SolveOptions {
                t_end,
                rtol,
                atol: rtol * 1e-2,
                ..Default::default()
            },
        );
        let err = dist(tr.summary.tip_end, reference.summary.tip_end);
        xs.push((tr.stats.steps as f64).ln());
        ys.push(err.ln());
    }
    // Least-squares slope of log(error) against log(steps).
    let m = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / m, ys.iter().sum::<f64>() / m);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    let slope = sxy / sxx;
    // Measured -5.57 over 18 to 100 steps; -5 for a fifth-order method with
    // a fixed step. A fourth-order pair would give about -4 and fail.
    assert!((-6.0..=-5.0).contains(&slope), "slope {slope}");
}

#[test]
fn agrees_with_rk4_on_two_report_scenes() {
    for (chain, s, t_end) in [
        {
            let (c, s) = span(25, 5e-4, 3.0);
            (c, s, 4.157)
        },
        {
            let c = Chain::report(25, 1e-3).unwrap();
            let s = Start::Catenary {
                p0: [0.0, 0.0],
                p1: [5.0, 1.0],
            }
            .state(&c)
            .unwrap();
            (c, s, 7.348)
        },
    ] {
        let a = run(
            &chain,
            &s,
            Method::Dopri5,
            SolveOptions {
                t_end,
                rtol: 1e-11,
                atol: 1e-13,
                ..Default::default()
            },
        );
        let b = run(
            &chain,
            &s,
            Method::Rk4,
            SolveOptions {
                t_end,
                dt: 5e-4,
                ..Default::default()
            },
        );
        let d = dist(a.summary.tip_end, b.summary.tip_end);
        assert!(d < 1e-7, "tip differs by {d:e}");
        let dv = (a.summary.tip_speed_max - b.summary.tip_speed_max).abs();
        assert!(
            dv < 1e-6 * b.summary.tip_speed_max,
            "max speed differs by {dv:e}"
        );
    }
}

#[test]
fn folded_scene_completes_with_energy_balance() {
    // The report's overflowing case: n = 50 folded, r = 0.001, report t = 12.
    // (RK4 at the report scenes' dt diverging here is a documented claim,
    // tested on the shipped scene in tests/cli.)
    let (chain, s) = folded(50, 1e-3);
    let rtol = 1e-8;
    let opts = SolveOptions {
        t_end: 4.157,
        rtol,
        atol: 1e-10,
        ..Default::default()
    };
    let tr = run(&chain, &s, Method::Dopri5, opts);
    // Measured 8.8e-8 = 0.15 rtol * energy_scale through the whip.
    let bound = rtol * chain.energy_scale();
    assert!(
        tr.summary.energy_balance_error < bound,
        "{:e}",
        tr.summary.energy_balance_error
    );
}

#[test]
fn dense_output_samples_match_the_reference() {
    let (chain, s) = span(12, 1e-3, 3.0);
    let opts = |m_dt: f64| SolveOptions {
        t_end: 2.0,
        dt: m_dt,
        rtol: 1e-10,
        atol: 1e-12,
        output_dt: Some(0.1),
        ..Default::default()
    };
    let a = run(&chain, &s, Method::Dopri5, opts(0.01));
    let b = run(&chain, &s, Method::Rk4, opts(5e-4));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.samples().zip(b.samples()) {
        assert!((x.t - y.t).abs() < 1e-12);
        for (p, q) in x.angles.iter().zip(y.angles) {
            assert!((p - q).abs() < 1e-7, "t = {}: {p} vs {q}", x.t);
        }
    }
}

#[test]
fn failure_statuses_are_reported_with_their_time() {
    let (chain, s) = span(10, 0.0, 3.0);
    let base = SolveOptions {
        t_end: 2.0,
        rtol: 1e-10,
        atol: 1e-12,
        ..Default::default()
    };
    let tr = solve(
        &chain,
        &s,
        Method::Dopri5,
        &SolveOptions {
            max_steps: 20,
            ..base.clone()
        },
    )
    .unwrap();
    assert_eq!(tr.status, Status::MaxSteps);
    assert!(tr.t_reached > 0.0 && tr.t_reached < 2.0);
    assert_eq!(tr.stats.steps + tr.stats.rejected_steps, 20);

    let tr = solve(
        &chain,
        &s,
        Method::Dopri5,
        &SolveOptions {
            h_min: 0.05,
            ..base
        },
    )
    .unwrap();
    assert_eq!(tr.status, Status::StepSizeTooSmall);
    assert!(tr.t_failed.is_some() && tr.t_reached < 2.0);
}

#[test]
fn stiffness_detector_fires_only_where_damping_is_stiff() {
    let (chain, s) = span(50, 0.1, 3.0);
    let stiff = run(
        &chain,
        &s,
        Method::Dopri5,
        SolveOptions {
            t_end: 2.0,
            rtol: 1e-6,
            atol: 1e-8,
            ..Default::default()
        },
    );
    assert!(stiff.stats.stiffness_detections > 0);
    let (chain, s) = span(25, 5e-4, 3.0);
    let mild = run(
        &chain,
        &s,
        Method::Dopri5,
        SolveOptions {
            t_end: 4.157,
            rtol: 1e-6,
            atol: 1e-8,
            ..Default::default()
        },
    );
    assert_eq!(mild.stats.stiffness_detections, 0);
}

#[test]
fn six_right_hand_sides_per_attempt_and_two_at_the_start() {
    // One at the start, one for the initial step, six per attempt (FSAL):
    // counted by the wrapper around the system, not by the method.
    let (chain, s) = span(10, 1e-3, 3.0);
    let tr = run(
        &chain,
        &s,
        Method::Dopri5,
        crate::tolerances(2.0, 1e-8, 1e-10),
    );
    let st = tr.stats;
    assert!(st.steps > 0);
    assert_eq!(st.rhs_evals, 2 + 6 * (st.steps + st.rejected_steps));
}
