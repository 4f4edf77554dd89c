//! Issue 24: every size a user controls is bounded before the run, every
//! run ends (a hang is a test failure, through a liveness bound), and no
//! finite nonsense passes as `ok`.

use crate::{all_finite, span3};
use chain_ode::{
    solve, Cancel, Chain, InvalidParameter, Method, SolveOptions, Start, Status, ATOL_RANGE,
    BDF_DENSE_MAX_LINKS, MAX_OUTPUT_BYTES, RTOL_RANGE,
};
use std::sync::mpsc;
use std::time::Duration;

/// Runs `f` on its own thread and fails if it has not returned within
/// `secs` (a liveness bound, never a timing claim).
fn within<T: Send + 'static>(secs: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    rx.recv_timeout(Duration::from_secs(secs))
        .expect("did not finish within its liveness bound")
}

/// The next float above `x > 0`, and the one below.
fn up(x: f64) -> f64 {
    f64::from_bits(x.to_bits() + 1)
}
fn down(x: f64) -> f64 {
    f64::from_bits(x.to_bits() - 1)
}

/// The error of `options` for `method` on `chain`, which must name `field`
/// on one line.
fn refused(chain: &Chain, method: Method, options: &SolveOptions, field: &str) -> InvalidParameter {
    let e = options.validate_for(chain, method).unwrap_err();
    assert_eq!(e.field, field, "{e}");
    let text = e.to_string();
    assert!(text.starts_with(field) && !text.contains('\n'), "{text}");
    // solve refuses it the same way, before any allocation or step.
    let s = Start::Stretched {
        p0: [0.0, 0.0],
        p1: [chain.length(), 0.0],
    }
    .state(chain)
    .unwrap();
    assert_eq!(solve(chain, &s, method, options).unwrap_err(), e);
    e
}

fn accepted(chain: &Chain, method: Method, options: &SolveOptions) {
    if let Err(e) = options.validate_for(chain, method) {
        panic!("{method}: {e}");
    }
}

#[test]
fn tolerances_are_bounded_to_where_the_methods_mean_something_boundaries_included() {
    let chain = Chain::report(5, 0.0).unwrap();
    let (rlo, rhi) = RTOL_RANGE;
    let (alo, ahi) = ATOL_RANGE;
    assert_eq!((rlo, rhi, alo, ahi), (1e-14, 0.1, 1e-20, 1.0));
    let with = |rtol: f64, atol: f64| SolveOptions {
        rtol,
        atol,
        ..Default::default()
    };
    for m in crate::smooth_methods() {
        // gen-alpha's own floor (issue 47 W2): its error stops following
        // the tolerance below it.
        let lo = if m == Method::GenAlpha {
            let lo = chain_ode::GEN_ALPHA_MIN_RTOL;
            for r in [down(lo), 1e-13, rlo] {
                let e = refused(&chain, m, &with(r, alo), "run.rtol");
                assert!(e.to_string().contains("[1e-10, 0.1] for gen-alpha"), "{e}");
            }
            lo
        } else {
            accepted(&chain, m, &with(1e-13, 1e-15));
            rlo
        };
        for (r, a) in [(lo, alo), (rhi, ahi), (1e-2, 1e-4)] {
            accepted(&chain, m, &with(r, a));
        }
        for r in [down(rlo), up(rhi), 1e-20, 1e-300, 0.999999, f64::NAN, 0.0] {
            let e = refused(&chain, m, &with(r, 1e-10), "run.rtol");
            assert!(e.to_string().contains("[1e-14, 0.1]"), "{e}");
        }
        for a in [down(alo), up(ahi), 1e300, 1e-300, f64::INFINITY, -1.0] {
            let e = refused(&chain, m, &with(1e-8, a), "run.atol");
            assert!(e.to_string().contains("[1e-20, 1]"), "{e}");
        }
    }
}

#[test]
fn rk4_steps_are_bounded_by_t_end_and_by_the_step_budget_boundaries_included() {
    let chain = Chain::report(2, 0.0).unwrap();
    let (_, s) = span3(2, 0.0);
    let o = |dt: f64| SolveOptions {
        t_end: 1.0,
        dt,
        max_steps: 1000,
        ..Default::default()
    };
    // dt = t_end: one step.
    accepted(&chain, Method::Rk4, &o(1.0));
    let e = refused(&chain, Method::Rk4, &o(up(1.0)), "run.dt");
    assert!(e.to_string().contains("at most run.t_end = 1"), "{e}");
    // dt = t_end / max_steps: exactly the budget, and the run completes.
    accepted(&chain, Method::Rk4, &o(1e-3));
    let tr = solve(&chain, &s, Method::Rk4, &o(1e-3)).unwrap();
    assert_eq!((tr.status, tr.stats.steps), (Status::Ok, 1000));
    let e = refused(&chain, Method::Rk4, &o(down(1e-3)), "run.dt");
    assert!(
        e.to_string()
            .contains("at least run.t_end / run.max_steps = 1e-3"),
        "{e}"
    );
    // The issue's 1e-300 is refused at once with the default budget, and
    // its message states the smallest step accepted (t_end / 10^8).
    let issue = SolveOptions {
        t_end: 4.157,
        dt: 1e-300,
        ..Default::default()
    };
    let e = refused(&chain, Method::Rk4, &issue, "run.dt");
    assert!(e.to_string().contains("4.157e-8"), "{e}");
    // The adaptive methods do not use dt: no bound on it for them.
    for m in Method::ALL.into_iter().filter(|m| m.adaptive()) {
        accepted(&chain, m, &o(10.0));
        accepted(&chain, m, &o(1e-300));
    }
}

#[test]
fn an_elastic_chains_samples_count_its_state_forces_and_joints() {
    for (t_end, n) in [(4.157, 50), (1.0, 1_000_000)] {
        let chain = Chain::new(chain_ode::ChainParams {
            links: n,
            axial_stiffness: Some(1e4),
            ..chain_ode::ChainParams::default()
        })
        .unwrap();
        let o_min = SolveOptions::min_output_dt_for(t_end, &chain);
        // Time and state (6 n + 1), joint forces and joints (2 (n + 1) each).
        let per_sample = 8.0 * (10 * n + 6) as f64;
        let samples = (t_end / o_min).floor() + 2.0;
        assert!(samples * per_sample <= MAX_OUTPUT_BYTES as f64);
        assert!((samples + 1.0) * per_sample > MAX_OUTPUT_BYTES as f64 - per_sample);
        // One step at most: a run that the cap failed to stop ends at once
        // instead of filling the memory (as under the break in .ci/breaks).
        let o = SolveOptions {
            t_end,
            output_dt: Some(o_min * 0.999),
            max_steps: 1,
            ..Default::default()
        };
        let e = chain_ode::solve(
            &chain,
            &chain_ode::Start::Folded {
                p0: [0.0, 0.0],
                down: None,
            }
            .state(&chain)
            .unwrap(),
            Method::Dopri5,
            &o,
        )
        .unwrap_err();
        assert_eq!(e.field, "run.output_dt", "{e}");
    }
}

#[test]
fn the_samples_must_fit_in_the_memory_cap_boundary_included() {
    for (t_end, n) in [(4.157, 50), (1e6, 1), (1.0, 1_000_000), (3.0, 7)] {
        let chain = Chain::report(n, 0.0).unwrap();
        let o_min = SolveOptions::min_output_dt(t_end, n);
        // At the minimum, the samples a run can record (the start, one per
        // output_dt, the end) fit in the cap.
        // Time and state (2 n + 1), and the joint forces (2 (n + 1)).
        let per_sample = 8.0 * (4 * n + 4) as f64;
        let samples = (t_end / o_min).floor() + 2.0;
        assert!(
            samples * per_sample <= MAX_OUTPUT_BYTES as f64,
            "{t_end} {n}"
        );
        // and a minimum one sample smaller would not.
        assert!((samples + 1.0) * per_sample > MAX_OUTPUT_BYTES as f64 - per_sample);
        let o = |output_dt: f64| SolveOptions {
            t_end,
            output_dt: Some(output_dt),
            ..Default::default()
        };
        for m in crate::smooth_methods() {
            if m == Method::BdfDense && n > BDF_DENSE_MAX_LINKS {
                continue;
            }
            accepted(&chain, m, &o(o_min));
            let e = refused(&chain, m, &o(down(o_min)), "run.output_dt");
            assert!(
                e.to_string().contains(&format!("at least {o_min:e}")),
                "{e}"
            );
        }
    }
    // The issue's output_dt = 1e-9 over span-d3 (13 GB of samples).
    let chain = Chain::report(50, 5e-4).unwrap();
    let o = SolveOptions {
        t_end: 4.157,
        output_dt: Some(1e-9),
        ..Default::default()
    };
    refused(&chain, Method::Rk4, &o, "run.output_dt");
}

#[test]
fn a_run_records_no_more_samples_than_its_grid_and_its_end() {
    let (chain, s) = span3(3, 5e-4);
    for m in crate::smooth_methods() {
        let o = SolveOptions {
            t_end: 1.0,
            output_dt: Some(0.3),
            ..Default::default()
        };
        let tr = solve(&chain, &s, m, &o).unwrap();
        let t: Vec<f64> = tr.times.clone();
        assert_eq!(t.len(), 5, "{m}: {t:?}");
        assert_eq!((t[0], t[4]), (0.0, 1.0), "{m}");
    }
}

#[test]
fn bdf_dense_is_capped_where_its_dense_matrices_stop_being_sensible() {
    assert_eq!(BDF_DENSE_MAX_LINKS, 500);
    let o = SolveOptions::default();
    let at = Chain::report(BDF_DENSE_MAX_LINKS, 0.0).unwrap();
    let past = Chain::report(BDF_DENSE_MAX_LINKS + 1, 0.0).unwrap();
    accepted(&at, Method::BdfDense, &o);
    let e = refused(&past, Method::BdfDense, &o, "chain.links");
    let text = e.to_string();
    assert!(
        text.contains("at most 500") && text.contains("\"bdf\""),
        "{text}"
    );
    for m in crate::smooth_methods().filter(|&m| m != Method::BdfDense) {
        accepted(&past, m, &o);
    }
}

#[test]
fn one_step_far_too_large_is_inaccurate_not_ok() {
    // The issue's `--set run.dt=1e300` on span-d3: one RK4 step over the
    // whole run (dt = t_end, the largest step accepted now), energy from
    // -13.7 to ~2e7 against a scale M g L = 60.
    let (chain, s) = span3(50, 5e-4);
    let o = SolveOptions {
        t_end: 4.157,
        dt: 4.157,
        ..Default::default()
    };
    let tr = solve(&chain, &s, Method::Rk4, &o).unwrap();
    assert_eq!(tr.status, Status::Inaccurate);
    assert_eq!(tr.status.as_str(), "inaccurate");
    assert_eq!(tr.stats.steps, 1);
    assert_eq!(tr.t_reached, 4.157);
    assert_eq!(
        tr.t_failed,
        Some(4.157),
        "the first step end past the scale"
    );
    assert!(tr.summary.energy_balance_error > chain.energy_scale());
    assert!(tr.summary.all_finite() && all_finite(&tr.final_state));
    // The same scene converged: the balance error is far below the scale.
    let o = SolveOptions { dt: 0.01, ..o };
    let tr = solve(&chain, &s, Method::Rk4, &o).unwrap();
    assert_eq!(tr.status, Status::Ok);
    assert!(tr.summary.energy_balance_error < 1e-3 * chain.energy_scale());
    // t_failed is the first step end where the balance went past the
    // scale: two steps of 2.0785 end inaccurate, and so does the first of
    // them alone, so t_failed is its end, not the run's.
    let half = 4.157 / 2.0;
    let two = SolveOptions { dt: half, ..o };
    let tr = solve(&chain, &s, Method::Rk4, &two).unwrap();
    assert_eq!((tr.status, tr.stats.steps), (Status::Inaccurate, 2));
    let first = SolveOptions {
        t_end: half,
        ..two.clone()
    };
    let tr1 = solve(&chain, &s, Method::Rk4, &first).unwrap();
    assert_eq!((tr1.status, tr1.t_failed), (Status::Inaccurate, Some(half)));
    assert_eq!(tr.t_failed, Some(half));
}

#[test]
fn a_cancelled_run_ends_interrupted_with_a_finite_state_for_every_method() {
    for m in crate::smooth_methods() {
        let (chain, s) = span3(10, 5e-4);
        // Long enough that only the flag can end it within the bound.
        let o = SolveOptions {
            t_end: 1e5,
            dt: 0.01,
            cancel: Some(Cancel::new()),
            ..Default::default()
        };
        let flag = o.cancel.clone().unwrap();
        let setter = std::thread::spawn(move || {
            std::thread::sleep(Duration::from_millis(50));
            flag.cancel();
        });
        let tr = within(60, move || solve(&chain, &s, m, &o).unwrap());
        setter.join().unwrap();
        assert_eq!(tr.status, Status::Interrupted, "{m}");
        assert!(
            tr.t_reached > 0.0 && tr.t_reached < 1e5,
            "{m}: {}",
            tr.t_reached
        );
        assert_eq!(tr.t_failed, Some(tr.t_reached), "{m}");
        assert!(
            all_finite(&tr.final_state) && tr.summary.all_finite(),
            "{m}"
        );
    }
}

#[test]
fn a_flag_set_before_the_run_stops_it_at_the_start_and_an_unset_one_changes_nothing() {
    let (chain, s) = span3(6, 5e-4);
    for m in crate::smooth_methods() {
        let cancel = Cancel::new();
        let plain = SolveOptions {
            t_end: 2.0,
            output_dt: Some(0.25),
            ..Default::default()
        };
        let watched = SolveOptions {
            cancel: Some(cancel.clone()),
            ..plain.clone()
        };
        let (a, b) = (
            solve(&chain, &s, m, &plain).unwrap(),
            solve(&chain, &s, m, &watched).unwrap(),
        );
        // Bit for bit the same run (wall time aside).
        assert_eq!(a.status, Status::Ok, "{m}");
        assert_eq!(
            (a.stats, a.t_reached, &a.times),
            (b.stats, b.t_reached, &b.times)
        );
        assert_eq!(a.final_state, b.final_state, "{m}");
        let (mut sa, mut sb) = (a.summary.clone(), b.summary.clone());
        (sa.wall_seconds, sb.wall_seconds) = (0.0, 0.0);
        assert_eq!(sa, sb, "{m}");
        assert!(a
            .samples()
            .zip(b.samples())
            .all(|(x, y)| x.angles == y.angles));
        cancel.cancel();
        let c = solve(&chain, &s, m, &watched).unwrap();
        assert_eq!(
            (c.status, c.t_reached, c.stats.steps),
            (Status::Interrupted, 0.0, 0),
            "{m}"
        );
        assert_eq!(
            c.final_state,
            [&s.angles[..], &s.rates[..], &[0.0]].concat()
        );
    }
}

#[test]
fn both_bdfs_end_step_size_too_small_below_the_step_floor() {
    // The tightest tolerances accepted, with a floor of 1e-3 that the
    // start's first steps cannot meet: both BDFs stop at once, as the
    // explicit methods do, with the start's finite state.
    let (chain, s) = span3(20, 5e-4);
    let o = SolveOptions {
        t_end: 4.157,
        rtol: 1e-14,
        atol: 1e-20,
        h_min: 1e-3,
        ..Default::default()
    };
    for m in [
        Method::Bdf,
        Method::BdfDense,
        Method::Dopri5,
        Method::Dop853,
    ] {
        let tr = within(60, {
            let (chain, s, o) = (chain.clone(), s.clone(), o.clone());
            move || solve(&chain, &s, m, &o).unwrap()
        });
        assert_eq!(tr.status, Status::StepSizeTooSmall, "{m}");
        assert!(
            tr.stats.steps + tr.stats.rejected_steps < 100,
            "{m}: {:?}",
            tr.stats
        );
        assert!(tr.t_failed.is_some_and(|t| t > tr.t_reached), "{m}");
        assert!(all_finite(&tr.final_state), "{m}");
    }
}

#[test]
fn the_two_rod_catenary_over_a_thousand_time_units_ends() {
    // The issue's hang: rk4, dt = 1e-3, t_end = 1000; the maximum search of
    // a step near t = 1000 could not narrow below one ulp of t.
    let (chain, s) = crate::span(2, 5e-4, 3.0);
    let o = SolveOptions {
        t_end: 1000.0,
        dt: 1e-3,
        ..Default::default()
    };
    let tr = within(120, move || solve(&chain, &s, Method::Rk4, &o).unwrap());
    assert_eq!(tr.status, Status::Ok);
    assert!((0.0..=1000.0).contains(&tr.summary.t_tip_speed_max));
}
