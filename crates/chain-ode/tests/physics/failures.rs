//! Chain runs that fail: each failure status of the adaptive methods and
//! `auto` on a chain, where the physics says the run must stop, and the
//! rule that a non-finite summary is never `ok`.

use chain_ode::analysis::folded_law;
use chain_ode::kinematics::{energy, tip};
use chain_ode::{solve, ChainSystem, Method, SolveOptions, Start, Status, Trajectory};

use super::{all_finite, folded, span3, tolerances};

/// Every field of the summary is finite, and so is the final state.
fn finite_end(tr: &Trajectory) {
    assert!(all_finite(&tr.final_state), "{}: final state", tr.method);
    assert!(tr.summary.all_finite(), "{}: {:?}", tr.method, tr.summary);
}

/// The report's folded chain (n = 50, r = 0.001) to the scene's t_end.
fn folded_run(method: Method, options: SolveOptions) -> Trajectory {
    let (chain, s) = folded(50, 0.001);
    solve(&chain, &s, method, &options).unwrap()
}

/// How far the free end has fallen below its start height `P0.y - l` in the
/// state `angles` (the folded law's `x`).
fn fall(tr: &Trajectory, angles: &[f64]) -> f64 {
    let start_y = -tr.chain().rod_length();
    start_y - tip(tr.chain(), tr.anchor, angles)[1]
}

#[test]
fn a_step_floor_stops_dopri5_and_auto_in_the_folded_whip() {
    // The folded chain's free end speeds up like 1/sqrt(L - x) as its fall x
    // approaches L (the law v^2 = g x (2L - x) / (L - x)): an adaptive step
    // must shrink without bound there. A floor of 3e-3 is passed by the
    // smooth fall (the complete run's steps are longer until the whip) and
    // must stop the run in the whip's last tenth of the fall.
    let h_min = 3e-3;
    let opts = SolveOptions {
        h_min,
        ..tolerances(4.157, 1e-4, 1e-6)
    };
    let complete = folded_run(Method::Dopri5, tolerances(4.157, 1e-4, 1e-6));
    assert_eq!(complete.status, Status::Ok);
    let (l, length) = (complete.chain().rod_length(), complete.chain().length());
    for method in [Method::Dopri5, Method::Auto] {
        let tr = folded_run(method, opts.clone());
        let t_failed = tr.t_failed.expect("a failed run has t_failed");
        let x = fall(&tr, &tr.final_state[..50]);
        println!(
            "{method}: {} at t_reached = {}, t_failed = {t_failed}, x/L = {}, vmax = {} at {}, complete run's peak at {}",
            tr.status,
            tr.t_reached,
            x / length,
            tr.summary.tip_speed_max,
            tr.summary.t_tip_speed_max,
            complete.summary.t_tip_speed_max
        );
        assert_eq!(tr.status, Status::StepSizeTooSmall, "{method}");
        // auto at rtol 1e-4 on this undamped-ish chain is DOPRI5.
        assert_eq!(tr.segments.len(), 1);
        assert_eq!(tr.segments[0].method, Method::Dopri5, "{method}");
        finite_end(&tr);
        // The step it could not make was shorter than the floor.
        assert!(
            tr.t_reached < t_failed && t_failed - tr.t_reached < h_min,
            "{method}: {} .. {t_failed}",
            tr.t_reached
        );
        // Stopped in the last 15% of the fall (measured: x = 0.883 L at
        // t = 2.919), after the law's time for it (2.85) and before the
        // whip's peak in the complete run (2.971).
        assert!(
            x > 0.85 * length && x < length - l,
            "{method}: x = {x} at t = {}",
            tr.t_reached
        );
        assert!(
            tr.t_reached > folded_law::time(0.85 * length, length, 1.0)
                && tr.t_reached < complete.summary.t_tip_speed_max,
            "{method}: t = {}",
            tr.t_reached
        );
        // Still accelerating when it stopped, faster than a free fall over
        // the whole length could make it: the whip.
        assert_eq!(tr.summary.t_tip_speed_max, tr.t_reached, "{method}");
        assert!(
            tr.summary.tip_speed_max > (2.0 * length).sqrt(),
            "{method}: {}",
            tr.summary.tip_speed_max
        );
    }
}

/// The spectral radius of the chain's Jacobian at its start, by power
/// iteration on the exact Jacobian-vector product.
fn spectral_radius(sys: &mut ChainSystem, y: &[f64]) -> f64 {
    let mut v: Vec<f64> = (0..y.len()).map(|i| 1.0 + (i % 7) as f64).collect();
    let mut jv = vec![0.0; y.len()];
    let mut rho = 0.0;
    for _ in 0..500 {
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        v.iter_mut().for_each(|x| *x /= norm);
        sys.jvp(0.0, y, &v, &mut jv);
        rho = jv.iter().map(|x| x * x).sum::<f64>().sqrt();
        std::mem::swap(&mut v, &mut jv);
    }
    rho
}

#[test]
fn a_step_budget_stops_dopri5_on_a_stiff_chain_at_its_stability_limit() {
    // Joint friction r = 1e6 on the report's span d = 3 (gamma = r/(m l^2)
    // = 3.5e8): the Jacobian's largest eigenvalue lambda is real and
    // negative, and DOPRI5 is held at its real stability boundary, h =
    // 3.3066 / |lambda|, whatever its tolerance. A budget of N steps then
    // reaches t = N h; `auto` sees the damping rate past the crossover and
    // runs BDF to the end.
    let (chain, s) = span3(50, 1e6);
    let mut sys = ChainSystem::new(&chain);
    let y0 = ChainSystem::pack(&s.angles, &s.rates, 0.0);
    let lambda = spectral_radius(&mut sys, &y0);
    let h_stable = 3.3066 / lambda;
    let budget = 10_000;
    let opts = SolveOptions {
        max_steps: budget,
        ..tolerances(1.0, 1e-6, 1e-8)
    };
    let tr = solve(&chain, &s, Method::Dopri5, &opts).unwrap();
    println!(
        "lambda = {lambda} (48 gamma = {}), h_stable = {h_stable}; {} at t = {} after {} steps + {} rejected: t / (N h) = {}",
        48.0 * chain.damping_rate(),
        tr.status,
        tr.t_reached,
        tr.stats.steps,
        tr.stats.rejected_steps,
        tr.t_reached / (budget as f64 * h_stable)
    );
    assert_eq!(tr.status, Status::MaxSteps);
    assert_eq!(tr.stats.steps + tr.stats.rejected_steps, budget);
    assert_eq!(tr.t_failed, Some(tr.t_reached));
    finite_end(&tr);
    let ratio = tr.t_reached / (budget as f64 * h_stable);
    // Measured: |lambda| = 1.650e10 (48 gamma = 1.667e10), t = 2.0026e-6
    // after 9991 steps and 9 rejections, t / (N h) = 0.9995.
    assert!((ratio - 1.0).abs() < 0.02, "t / (N h_stable) = {ratio}");

    let auto = solve(&chain, &s, Method::Auto, &opts).unwrap();
    assert_eq!(auto.status, Status::Ok, "{:?}", auto.segments);
    assert_eq!(auto.segments[0].method, Method::Bdf);
}

#[test]
fn a_step_budget_stops_bdf_and_auto_mid_fall_where_the_folded_law_puts_the_tip() {
    // Cut short by a step budget before the whip, a run stops with the
    // chain where the folded law says it is at that time: the free end has
    // fallen the x with t(x) = t_reached, and
    // the energy still balances. Measured: BDF stops at t = 2.023 (0.97%
    // after the law's t(x)), auto (DOPRI5 here) at 1.778 (0.82% after): the
    // discrete chain lags the continuum law by about 1% at n = 50.
    for (method, budget) in [(Method::Bdf, 1000), (Method::Auto, 150)] {
        let opts = SolveOptions {
            max_steps: budget,
            ..tolerances(4.157, 1e-6, 1e-8)
        };
        let tr = folded_run(method, opts);
        let (length, n) = (tr.chain().length(), tr.chain().links());
        let x = fall(&tr, &tr.final_state[..n]);
        let t_law = folded_law::time(x, length, 1.0);
        println!(
            "{method}: {} at t = {} after {} + {} attempts, x/L = {}, law's t(x) = {t_law}: {}",
            tr.status,
            tr.t_reached,
            tr.stats.steps,
            tr.stats.rejected_steps,
            x / length,
            tr.t_reached / t_law - 1.0
        );
        assert_eq!(tr.status, Status::MaxSteps, "{method}");
        assert_eq!(tr.stats.steps + tr.stats.rejected_steps, budget, "{method}");
        finite_end(&tr);
        assert!(tr.t_reached > 0.5 && tr.t_reached < 4.157, "{method}");
        assert!(
            (tr.t_reached / t_law - 1.0).abs() < 0.02,
            "{method}: t = {} but the law's t(x = {x}) = {t_law}",
            tr.t_reached
        );
        let (phi, w) = (&tr.final_state[..n], &tr.final_state[n..2 * n]);
        let e = energy(tr.chain(), phi, w);
        let w_diss = tr.final_state[2 * n];
        assert!(
            (e + w_diss - tr.summary.energy_start).abs() <= tr.summary.energy_balance_error + 1e-12,
            "{method}"
        );
    }
}

#[test]
fn stages_that_overflow_end_dopri5_diverged_at_the_start_with_the_start_kept() {
    // r = 1e250: gamma = 3.5e252, so any representable step h >= 1e-14 has
    // h |lambda| > 1e238 and DOPRI5's stages overflow; every trial is
    // non-finite until the step falls below the rounding floor. The run
    // must say `diverged` at t = 0 and keep the start.
    let (chain, s) = span3(50, 1e250);
    let tr = solve(&chain, &s, Method::Dopri5, &tolerances(1.0, 1e-6, 1e-8)).unwrap();
    assert_eq!(tr.status, Status::Diverged);
    assert_eq!(tr.t_reached, 0.0);
    assert!(tr.t_failed.unwrap() > 0.0 && tr.t_failed.unwrap() < 1e-13);
    assert_eq!(tr.stats.steps, 0);
    assert_eq!(&tr.final_state[..50], &s.angles[..]);
    finite_end(&tr);
}

#[test]
fn an_energy_that_overflows_is_diverged_not_ok() {
    // Every rod spinning at w = 1e152 with the chain straight: the state is
    // finite and one RK4 step keeps it finite (the rigid rotation's angular
    // accelerations are only gravity's), but the kinetic energy
    // sum (i l w)^2 m / 2 exceeds f64's range. The summary cannot be
    // finite, so the run must not be `ok`.
    let n = 50;
    let chain = chain_ode::Chain::report(n, 0.0).unwrap();
    let s = Start::Angles {
        p0: [0.0, 0.0],
        angles: vec![-0.5; n],
        rates: Some(vec![1e152; n]),
    }
    .state(&chain)
    .unwrap();
    let opts = SolveOptions {
        t_end: 1e-152,
        dt: 1e-152,
        ..Default::default()
    };
    let tr = solve(&chain, &s, Method::Rk4, &opts).unwrap();
    // The integrator got to the end with a finite state ...
    assert_eq!(tr.t_reached, opts.t_end);
    assert!(all_finite(&tr.final_state));
    // ... but the energy it recorded at the start is not finite, and the
    // balance built on it is NaN: not `ok`, failed where it appeared.
    assert_eq!(tr.summary.energy_start, f64::INFINITY);
    assert!(tr.summary.energy_balance_error.is_nan());
    assert_eq!(tr.status, Status::Diverged);
    assert_eq!(tr.t_failed, Some(0.0));
}

/// `bdf` holds the energy balance of a lightly damped chain to the
/// tolerance: `|E + W - E(0)| <= rtol |E(0)|` over every step at rtol 1e-6
/// and 1e-8. diffsol's default Newton tolerance (0.2) let unconverged steps
/// through on the DAE: 1.6e-7 at rtol 1e-8, past `rtol |E(0)| = 1.4e-7`
/// (docs/model.md, "The Newton matrix in the rods' frames").
#[test]
fn bdf_holds_the_energy_balance_to_the_tolerance() {
    let (chain, s) = span3(50, 0.0005);
    for rtol in [1e-6, 1e-8] {
        let opts = SolveOptions {
            t_end: 2.0,
            rtol,
            atol: rtol / 100.0,
            output_dt: Some(0.05),
            ..Default::default()
        };
        let tr = solve(&chain, &s, Method::Bdf, &opts).unwrap();
        assert_eq!(tr.status, Status::Ok);
        let (bound, e0) = (tr.summary.energy_balance_error, tr.summary.energy_start);
        assert!(
            bound <= rtol * e0.abs(),
            "rtol {rtol}: {bound} > {}",
            rtol * e0.abs()
        );
    }
}

#[test]
fn a_complete_run_has_a_finite_summary_whose_balance_bounds_every_sample() {
    // The observer's energy balance is max |E + W - E(0)| over every step:
    // at least what the samples show, computed here from the public
    // kinematics. A NaN anywhere (a broken energy at one step) would make
    // the run `diverged` and the summary non-finite.
    let (chain, s) = span3(50, 0.0005);
    for method in [Method::Rk4, Method::Dopri5, Method::Bdf, Method::Auto] {
        let opts = SolveOptions {
            t_end: 2.0,
            dt: 0.01,
            rtol: 1e-6,
            atol: 1e-8,
            output_dt: Some(0.05),
            ..Default::default()
        };
        let tr = solve(&chain, &s, method, &opts).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method}: {:?}", tr.summary);
        assert_eq!(tr.t_failed, None);
        finite_end(&tr);
        let e0 = tr.summary.energy_start;
        let worst = tr
            .samples()
            .map(|p| (energy(&chain, p.angles, p.rates) + p.dissipated - e0).abs())
            .fold(0.0, f64::max);
        let bound = tr.summary.energy_balance_error;
        println!("{method}: worst sample {worst}, balance {bound}");
        assert!(
            worst <= bound * (1.0 + 1e-9) + 1e-13,
            "{method}: {worst} > {bound}"
        );
        assert!(bound < 1e-3 * chain.energy_scale(), "{method}: {bound}");
    }
}

#[test]
fn a_start_whose_first_derivative_overflows_reports_the_start_not_zeros() {
    // Rates of 1e154: the accelerations (~w^2 / l) overflow, so no method
    // takes a step. The summary still describes the start: its energy
    // (~1e309, infinite in f64) and its finite tip speed (6e154), not the
    // zeros of an observer that never started.
    let (chain, _) = span3(10, 0.0);
    let s = Start::Angles {
        p0: [0.0, 0.0],
        angles: vec![-0.5; 10],
        rates: Some(vec![1e154; 10]),
    }
    .state(&chain)
    .unwrap();
    let e0 = energy(&chain, &s.angles, &s.rates);
    assert_eq!(e0, f64::INFINITY);
    for method in [Method::Rk4, Method::Dopri5, Method::Bdf] {
        let tr = solve(&chain, &s, method, &tolerances(1.0, 1e-6, 1e-8)).unwrap();
        assert_eq!(tr.status, Status::Diverged, "{method}");
        assert_eq!((tr.t_reached, tr.t_failed), (0.0, Some(0.0)), "{method}");
        assert_eq!(tr.summary.energy_start, e0, "{method}");
        assert_eq!(tr.summary.energy_end, e0, "{method}");
        let v = chain_ode::kinematics::tip_velocity(&chain, &s.angles, &s.rates);
        assert!(v[0].hypot(v[1]) > 1e154);
        assert_eq!(tr.summary.tip_speed_max, v[0].hypot(v[1]), "{method}");
    }
}
