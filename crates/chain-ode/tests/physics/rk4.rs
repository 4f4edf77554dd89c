//! RK4 against the conservation laws, its convergence order, and its statuses.

use chain_ode::{solve, Chain, Method, SolveOptions, State, Status, Trajectory};

use crate::{fixed, span3};

fn rk4(chain: &Chain, s: &State, t_end: f64, dt: f64) -> Trajectory {
    solve(chain, s, Method::Rk4, &fixed(t_end, dt)).unwrap()
}

#[test]
fn undamped_energy_error_falls_like_dt_to_the_fourth() {
    let (chain, s) = span3(20, 0.0);
    let dts = [0.02, 0.01, 0.005];
    let errs: Vec<f64> = dts
        .iter()
        .map(|&dt| {
            let tr = rk4(&chain, &s, 2.0, dt);
            assert_eq!(tr.status, Status::Ok);
            tr.summary.energy_balance_error
        })
        .collect();
    for w in errs.windows(2) {
        let order = (w[0] / w[1]).log2();
        // Measured 4.05 and 4.03; a third-order method gives 3 and fails.
        assert!(
            (3.7..=4.3).contains(&order),
            "order {order}, errors {errs:?}"
        );
    }
}

#[test]
fn damped_energy_balance_holds_and_energy_never_rises() {
    let (chain, s) = span3(25, 1e-3);
    let coarse = rk4(&chain, &s, 4.0, 0.005);
    let fine = rk4(&chain, &s, 4.0, 0.0025);
    let scale = chain.energy_scale();
    for tr in [&coarse, &fine] {
        assert_eq!(tr.status, Status::Ok);
        assert!(tr.summary.dissipated > 0.0);
        // E + W = E(0) to the method's error ...
        assert!(
            tr.summary.energy_balance_error < 1e-6 * scale,
            "{:e}",
            tr.summary.energy_balance_error
        );
        // ... and, with friction, E falls at every step: what rises is
        // rounding (measured 0).
        assert!(tr.summary.max_energy_rise <= 1e-12 * scale);
    }
    // The balance error is the method's: it shrinks at fourth order.
    let ratio = coarse.summary.energy_balance_error / fine.summary.energy_balance_error;
    // Measured order 4.04 (errors 4.1e-6 and 2.5e-7); a third-order
    // method gives 3 and fails.
    let order = ratio.log2();
    assert!((3.7..=4.3).contains(&order), "order {order}");
}

#[test]
fn a_step_far_too_large_diverges_with_a_status_not_a_nan() {
    // gamma = r/(m l^2) ~ 35 for n = 50, r = 0.1: dt = 0.01 is ~6x RK4's stability limit.
    let (chain, s) = span3(50, 0.1);
    let opts = SolveOptions {
        t_end: 20.0,
        dt: 0.01,
        output_dt: Some(0.05),
        ..Default::default()
    };
    let tr = solve(&chain, &s, Method::Rk4, &opts).unwrap();
    assert_eq!(tr.status, Status::Diverged);
    assert!(tr.t_reached < 20.0);
    let tf = tr.t_failed.expect("failure time");
    assert!(tf > tr.t_reached && tf <= tr.t_reached + 0.01 + 1e-12);
    assert!(tr.final_state.iter().all(|v| v.is_finite()));
    assert!(tr.samples().all(|s| s.angles.iter().all(|v| v.is_finite())));
    assert!(tr.summary.energy_end.is_finite() && tr.summary.tip_speed_max.is_finite());
}

#[test]
fn a_step_budget_too_small_for_the_fixed_steps_is_refused_before_the_run() {
    // RK4 knows its step count before the first step: a budget of 10 for
    // 100 steps is a bad input (naming run.dt and the smallest step the
    // budget allows), not a run that ends max_steps. The integrator's own
    // max_steps path is tested in rk4.rs.
    let (chain, s) = span3(10, 0.0);
    let opts = SolveOptions {
        t_end: 1.0,
        dt: 0.01,
        max_steps: 10,
        ..Default::default()
    };
    let e = solve(&chain, &s, Method::Rk4, &opts).unwrap_err();
    assert_eq!(e.field, "run.dt");
    assert!(e.to_string().contains("= 1e-1 for rk4"), "{e}");
}

#[test]
fn tip_speed_maximum_is_continuous_not_sampled() {
    let (chain, s) = span3(25, 5e-4);
    let opts = |dt: f64| SolveOptions {
        t_end: 4.0,
        dt,
        output_dt: Some(0.25),
        ..Default::default()
    };
    let coarse = solve(&chain, &s, Method::Rk4, &opts(0.005)).unwrap();
    let fine = solve(&chain, &s, Method::Rk4, &opts(0.0005)).unwrap();
    let (vc, vf) = (coarse.summary.tip_speed_max, fine.summary.tip_speed_max);
    // Both within RK4's own error of each other (~1e-6 here), far below the
    // step-to-step change of the speed near its peak.
    assert!((vc - vf).abs() < 5e-6 * vf, "{vc} vs {vf}");
    assert!((coarse.summary.t_tip_speed_max - fine.summary.t_tip_speed_max).abs() < 1e-4);
    // The maximum over the output samples alone (every 0.25) misses the
    // peak; over samples every 1e-4 (the dense output) it comes within the
    // parabola's miss, (0.5e-4)^2 |v''| / 2, below the continuous maximum.
    let sampled_max = |tr: &Trajectory| {
        tr.samples()
            .map(|s| {
                let v = chain_ode::kinematics::tip_velocity(&chain, s.angles, s.rates);
                v[0].hypot(v[1])
            })
            .fold(0.0, f64::max)
    };
    let sparse = sampled_max(&coarse);
    let fine_samples = SolveOptions {
        output_dt: Some(1e-4),
        ..opts(0.005)
    };
    let dense = sampled_max(&solve(&chain, &s, Method::Rk4, &fine_samples).unwrap());
    // Measured: 3.7e-3 below with samples every 0.25, 4.3e-9 below with
    // samples every 1e-4.
    assert!(sparse < vc * (1.0 - 1e-3), "{sparse} vs {vc}");
    assert!(
        dense <= vc * (1.0 + 1e-12) && dense > vc * (1.0 - 2e-8),
        "{dense} vs {vc}"
    );
}

#[test]
fn samples_land_on_the_output_grid_and_the_end() {
    let (chain, s) = span3(8, 0.0);
    let opts = SolveOptions {
        t_end: 1.03,
        dt: 0.007,
        output_dt: Some(0.25),
        ..Default::default()
    };
    let tr = solve(&chain, &s, Method::Rk4, &opts).unwrap();
    let expect = [0.0, 0.25, 0.5, 0.75, 1.0, 1.03];
    assert_eq!(tr.times.len(), expect.len(), "{:?}", tr.times);
    for (t, e) in tr.times.iter().zip(expect) {
        assert!((t - e).abs() < 1e-12);
    }
}

#[test]
fn four_right_hand_sides_per_step_and_one_at_the_start() {
    // Counted by the wrapper around the system, not by the method.
    let (chain, s) = span3(10, 1e-3);
    let tr = rk4(&chain, &s, 1.0, 0.01);
    assert_eq!(tr.status, Status::Ok);
    assert_eq!((tr.stats.steps, tr.stats.rejected_steps), (100, 0));
    assert_eq!(tr.stats.rhs_evals, 1 + 4 * tr.stats.steps);
}
