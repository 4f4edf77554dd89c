//! diffsol's BDF against RK4, the energy balance, the stiff regime, and the
//! statuses it ends with.

use chain_ode::{solve, Chain, Method, SolveOptions, State, Status, Trajectory};

use crate::{all_finite, dist, fixed, span3, tolerances};

fn run(chain: &Chain, s: &State, method: Method, opts: SolveOptions) -> Trajectory {
    solve(chain, s, method, &opts).unwrap()
}

#[test]
fn agrees_with_rk4_at_tight_settings() {
    let (chain, s) = span3(25, 5e-4);
    let b = run(&chain, &s, Method::Bdf, tolerances(2.0, 1e-10, 1e-12));
    let r = run(&chain, &s, Method::Rk4, fixed(2.0, 1e-3));
    assert_eq!(b.status, Status::Ok);
    assert_eq!(r.status, Status::Ok);
    assert_eq!(b.t_reached, 2.0);
    let d = dist(b.summary.tip_end, r.summary.tip_end);
    assert!(d < 1e-6, "tip differs by {d:e}");
    // The tip-speed maximum is located with BDF's own dense output.
    let dv = (b.summary.tip_speed_max - r.summary.tip_speed_max).abs();
    assert!(
        dv < 1e-6 * r.summary.tip_speed_max,
        "max speed differs by {dv:e}"
    );
    // E + W = E(0) along the run, to the tolerance.
    let scale = chain.energy_scale();
    assert!(
        b.summary.energy_balance_error < 1e-6 * scale,
        "balance error {:e}",
        b.summary.energy_balance_error
    );
    assert!(b.summary.dissipated > 0.0);
    // Work counters: an implicit method with the exact Jacobian.
    assert!(b.stats.steps > 0);
    assert!(b.stats.jacobian_evals >= 1);
    assert!(b.stats.lu_factorizations >= b.stats.jacobian_evals);
    assert!(b.stats.rhs_evals > b.stats.steps);
    // Rejections by cause add up, and every accepted step took at least
    // one Newton iteration; an explicit method counts none of these.
    let st = b.stats;
    assert_eq!(
        st.error_test_failures + st.newton_failures,
        st.rejected_steps,
        "{st:?}"
    );
    assert!(st.newton_iterations >= st.steps, "{st:?}");
    let d = run(&chain, &s, Method::Dopri5, tolerances(0.2, 1e-6, 1e-8)).stats;
    assert_eq!(
        (
            d.error_test_failures,
            d.newton_failures,
            d.newton_iterations
        ),
        (0, 0, 0)
    );
}

#[test]
fn undamped_energy_is_conserved_to_the_tolerance() {
    let (chain, s) = span3(20, 0.0);
    let scale = chain.energy_scale();
    let loose = run(&chain, &s, Method::Bdf, tolerances(2.0, 1e-6, 1e-8));
    let tight = run(&chain, &s, Method::Bdf, tolerances(2.0, 1e-9, 1e-11));
    for (tr, rtol) in [(&loose, 1e-6), (&tight, 1e-9)] {
        assert_eq!(tr.status, Status::Ok);
        // Nothing is dissipated without friction, not even by rounding.
        assert_eq!(tr.summary.dissipated, 0.0);
        // Conserved to the tolerance, relative to the energy scale.
        assert!(
            tr.summary.energy_balance_error < rtol * scale,
            "rtol {rtol:e}: balance error {:e}",
            tr.summary.energy_balance_error
        );
    }
    // Three decades tighter: the error follows the tolerance down, in
    // proportion.
    let ratio = loose.summary.energy_balance_error / tight.summary.energy_balance_error;
    // Tolerance proportionality: 1000 for an error proportional to rtol;
    // measured 774 (3.9e-6 and 5.1e-9, scale 24). A method whose error
    // fell like rtol^(1/2) would give 32.
    assert!((300.0..=3000.0).contains(&ratio), "ratio {ratio}");
}

#[test]
fn stiff_chain_completes_in_far_fewer_steps_than_rk4_can_take() {
    // gamma = r / (m l^2) ~ 35: the spectral radius at rest is ~48 gamma
    // (docs/model.md), so RK4 (real stability interval ~2.785) needs
    // dt < 2.785 / (48 gamma) ~ 1.7e-3, i.e. more than ~1200 steps to t = 2.
    let (chain, s) = span3(50, 0.1);
    let t_end = 2.0;
    let rk4_min_steps = t_end * 48.0 * chain.damping_rate() / 2.785;
    assert!(rk4_min_steps > 1000.0);

    let b = run(&chain, &s, Method::Bdf, tolerances(t_end, 1e-6, 1e-8));
    assert_eq!(b.status, Status::Ok);
    assert_eq!(b.t_reached, t_end);
    let attempts = (b.stats.steps + b.stats.rejected_steps) as f64;
    assert!(
        attempts < rk4_min_steps / 3.0,
        "{attempts} BDF attempts vs RK4's {rk4_min_steps:.0}"
    );

    // RK4 at dt = 0.01, ~6x its stability limit, diverges ...
    let unstable = run(&chain, &s, Method::Rk4, fixed(t_end, 0.01));
    assert_eq!(unstable.status, Status::Diverged);
    assert!(unstable.t_reached < t_end);
    // ... while below the limit it agrees with BDF to BDF's tolerance
    // (rtol 1e-6 on a chain of length 6).
    let stable = run(&chain, &s, Method::Rk4, fixed(t_end, 1e-3));
    assert_eq!(stable.status, Status::Ok);
    let d = dist(b.summary.tip_end, stable.summary.tip_end);
    assert!(d < 1e-5, "tip differs by {d:e}");
    let scale = chain.energy_scale();
    assert!(
        b.summary.energy_balance_error < 1e-5 * scale,
        "balance error {:e}",
        b.summary.energy_balance_error
    );
    assert!(b.summary.dissipated > 0.0);
}

/// `auto` runs the method that the `stiffness` study measured to be faster:
/// DOPRI5 (DOP853 at tight tolerances) below the crossover damping rate, BDF
/// past it, with the same result as that method run alone.
#[test]
fn auto_picks_the_side_of_the_crossover_it_is_on() {
    for n in [25, 50, 400] {
        let unit = Chain::report(n, 0.0).unwrap();
        let m_l2 = unit.mass() * unit.rod_length().powi(2);
        let cross = chain_ode::bdf_crossover_gamma(&unit);
        for (factor, rtol, expect) in [
            (0.25, 1e-6, Method::Dopri5),
            (0.25, 1e-10, Method::Dop853),
            (4.0, 1e-6, Method::Bdf),
            (4.0, 1e-10, Method::Bdf),
        ] {
            let (chain, s) = span3(n, factor * cross * m_l2);
            let o = tolerances(0.5, rtol, rtol * 1e-2);
            let a = run(&chain, &s, Method::Auto, o.clone());
            let alone = run(&chain, &s, expect, o);
            assert_eq!(a.status, Status::Ok);
            let methods: Vec<Method> = a.segments.iter().map(|g| g.method).collect();
            assert_eq!(
                methods,
                vec![expect],
                "n = {n}, gamma = {factor} x crossover, rtol {rtol:e}"
            );
            assert_eq!(a.final_state, alone.final_state);
            assert_eq!(a.stats, alone.stats);
        }
    }
}

#[test]
fn the_step_budget_ends_the_run_with_max_steps() {
    let (chain, s) = span3(25, 5e-4);
    let o = SolveOptions {
        max_steps: 5,
        ..tolerances(2.0, 1e-8, 1e-10)
    };
    let tr = run(&chain, &s, Method::Bdf, o);
    assert_eq!(tr.status, Status::MaxSteps);
    assert!(tr.t_reached > 0.0 && tr.t_reached < 2.0);
    // Every attempt, accepted or rejected, counts against the budget.
    assert_eq!(tr.stats.steps + tr.stats.rejected_steps, 5);
    assert!(all_finite(&tr.final_state));
    assert!(tr.summary.energy_end.is_finite());
}

#[test]
fn a_step_floor_above_the_needed_step_ends_with_step_size_too_small() {
    let (chain, s) = span3(25, 5e-4);
    let o = SolveOptions {
        h_min: 0.5,
        ..tolerances(2.0, 1e-8, 1e-10)
    };
    let tr = run(&chain, &s, Method::Bdf, o);
    assert_eq!(tr.status, Status::StepSizeTooSmall);
    assert!(tr.t_reached < 2.0);
    let t_failed = tr.t_failed.expect("a failed run says when");
    assert!(t_failed > tr.t_reached);
    assert!(all_finite(&tr.final_state));
    // A floor below every step the run needs changes nothing.
    let free = run(&chain, &s, Method::Bdf, tolerances(2.0, 1e-8, 1e-10));
    let floored = run(
        &chain,
        &s,
        Method::Bdf,
        SolveOptions {
            h_min: 1e-9,
            ..tolerances(2.0, 1e-8, 1e-10)
        },
    );
    assert_eq!(floored.status, Status::Ok);
    assert_eq!(floored.final_state, free.final_state);
}

#[test]
fn output_samples_land_on_the_grid_and_match_rk4() {
    let (chain, s) = span3(25, 5e-4);
    let out = |o: SolveOptions| SolveOptions {
        output_dt: Some(0.1),
        ..o
    };
    let b = run(&chain, &s, Method::Bdf, out(tolerances(2.0, 1e-10, 1e-12)));
    let r = run(&chain, &s, Method::Rk4, out(fixed(2.0, 1e-3)));
    assert_eq!(b.status, Status::Ok);
    assert_eq!(b.len(), 21);
    assert_eq!(r.len(), 21);
    for (k, (sb, sr)) in b.samples().zip(r.samples()).enumerate() {
        let tk = 0.1 * k as f64;
        assert!((sb.t - tk).abs() < 1e-12, "sample {k} at t = {}", sb.t);
        let worst = sb
            .angles
            .iter()
            .zip(sr.angles)
            .chain(sb.rates.iter().zip(sr.rates))
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-6, "sample {k} (t = {tk}) differs by {worst:e}");
    }
}
