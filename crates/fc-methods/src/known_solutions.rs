//! Every method on problems with known solutions, so that every coefficient
//! of every tableau matters: local and global orders measured from error
//! slopes (on non-autonomous problems, where the nodes `c_i` enter), the
//! embedded error estimates against the true local errors, and the dense
//! output against the exact solution between steps.

use super::integrator::Settings;
use super::test_problems::{
    arenstorf, blow_up, domain_exit, every_adaptive, max_diff, one_step, options, run, run_dae,
    slope, van_der_pol, ExactCheck, Known, Probe, Quiet, FORCED, GAUSSIAN, OSCILLATOR,
};
use super::{dop853, dopri5, Method};
use crate::ode::{OdeSystem, Problem, Status};

#[test]
fn every_method_runs_every_known_problem_through_the_registry() {
    // Every `Method` variant (a new one cannot escape), on the problems
    // with exact solutions, as the chain runs: through `registry::run`.
    // RK4 and moreau-jean at dt = 1e-3, the others at 1e-8; the end error
    // over [0, 3] is bounded by 1e-5 (measured at most 6.6e-8, the BDFs';
    // moreau-jean, second order on these, 1.3e-7). A method of nonsmooth
    // problems ends a problem without a mechanical form (y' = -2ty) at its
    // start, `diverged`.
    for method in Method::ALL {
        for p in [&OSCILLATOR, &GAUSSIAN, &FORCED] {
            let o = Settings {
                dt: 1e-3,
                ..options(1e-8, 1e-10)
            };
            let mut obs = ExactCheck::new(p.exact);
            let mut sys = (p.system)();
            let y0 = (p.exact)(0.0);
            if method.is_nonsmooth() && sys.nonsmooth().is_none() {
                let out = run(method, &mut sys, 0.0, &y0, 3.0, &o, &mut obs);
                assert_eq!(out.status, Status::Diverged, "{method} on {}", p.name);
                assert_eq!((out.t_reached, out.stats.steps), (0.0, 0), "{method}");
                continue;
            }
            let out = run(method, &mut sys, 0.0, &y0, 3.0, &o, &mut obs);
            let e = max_diff(&out.y_end, &(p.exact)(3.0));
            eprintln!(
                "{method} on {}: {} steps, end error {e:.2e}",
                p.name, out.stats.steps
            );
            assert_eq!(out.status, Status::Ok, "{method} on {}", p.name);
            assert_eq!(out.t_reached, 3.0, "{method} on {}", p.name);
            assert_eq!(obs.steps, out.stats.steps, "{method} on {}", p.name);
            assert!(e < 1e-5, "{method} on {}: end error {e:e}", p.name);
        }
    }
}

/// One step of exactly `h` from the exact state at `t0`: the step's error at
/// `t0 + h` and the largest error of its interpolant at `thetas`.
fn one_step_errors(method: Method, p: &Known, t0: f64, h: f64, thetas: &[f64]) -> (f64, f64) {
    let o = Settings {
        dt: h,
        ..one_step(h)
    };
    let mut obs = Probe {
        times: thetas.iter().map(|th| t0 + th * h).collect(),
        ..Probe::default()
    };
    let out = run(
        method,
        &mut (p.system)(),
        t0,
        &(p.exact)(t0),
        t0 + h,
        &o,
        &mut obs,
    );
    assert_eq!((out.stats.steps, out.stats.rejected_steps), (1, 0));
    assert_eq!(obs.values.len(), thetas.len());
    let step = max_diff(&out.y_end, &(p.exact)(t0 + h));
    let dense = obs
        .values
        .iter()
        .map(|(t, y)| max_diff(y, &(p.exact)(*t)))
        .fold(0.0, f64::max);
    (step, dense)
}

/// `h0 / 2^m`, `m = 0..count`.
fn halvings(h0: f64, count: i32) -> Vec<f64> {
    (0..count).map(|m| h0 / 2f64.powi(m)).collect()
}

/// The single steps over which `method`'s local errors on `p` are fitted:
/// small enough to be in the asymptotic regime (the Gaussian's high
/// derivatives are large, so it needs steps 4x shorter than the forced
/// oscillator), large enough that the smallest error is far above rounding.
fn local_steps(method: Method, p: &Known) -> Vec<f64> {
    let h0 = match method {
        Method::Dop853 => 1.6,
        _ => 0.4,
    };
    if p.name == GAUSSIAN.name {
        // DOP853's step error reaches rounding below h = 0.1.
        let count = if method == Method::Dop853 { 3 } else { 4 };
        halvings(h0 / 4.0, count)
    } else {
        halvings(h0, 5)
    }
}

#[test]
fn one_step_local_errors_show_each_order() {
    // (method, expected slopes in h of the step's and of the interpolant's
    // local error). A method of order p has local error O(h^(p+1)); its
    // interpolant, of order q, O(h^(q+1)): DOPRI5's is of order 4, DOP853's
    // of order 7, and RK4's cubic Hermite interpolates with error O(h^4).
    let table = [
        (Method::Rk4, 5.0, 4.0),
        (Method::Dopri5, 6.0, 5.0),
        (Method::Dop853, 9.0, 8.0),
    ];
    let thetas = [0.3, 0.5, 0.8];
    for (method, want_step, want_dense) in table {
        for p in [&GAUSSIAN, &FORCED] {
            let t0 = 1.0;
            let (mut step, mut dense) = (Vec::new(), Vec::new());
            for h in local_steps(method, p) {
                let (e, ed) = one_step_errors(method, p, t0, h, &thetas);
                eprintln!(
                    "{method} on {}: h = {h}: step {e:.2e}, dense {ed:.2e}",
                    p.name
                );
                step.push((h, e));
                dense.push((h, ed));
            }
            let (ps, pd) = (slope(&step), slope(&dense));
            eprintln!("{method} on {}: slopes step {ps:.2}, dense {pd:.2}", p.name);
            // Measured (Gaussian, forced): step 5.06, 4.94 (rk4); 6.14, 5.99
            // (dopri5); 9.36, 8.81 (dop853); dense 4.10, 3.87; 5.17, 5.05;
            // 8.27, 7.95. Half an order either side: one order lower fails.
            assert!(
                (ps - want_step).abs() < 0.5,
                "{method} on {}: step slope {ps}",
                p.name
            );
            assert!(
                (pd - want_dense).abs() < 0.5,
                "{method} on {}: dense slope {pd}",
                p.name
            );
        }
    }
}

/// `max_i |x_i|`.
fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

#[test]
fn dopri5_error_estimate_tracks_the_local_error() {
    // One attempt from the exact state, through the step loop's own
    // `attempt`. The estimate `err = y1 - y1_hat` is the local error of the
    // embedded fourth-order solution: O(h^5) only if the weights E kill
    // every term up to h^4 (a wrong E leaves an O(h) term). It must also
    // bound the true local error of the propagated y1, O(h^6), by a margin
    // that grows as h falls. (Comparing `err` with the true error of
    // `y1 - err` would be circular: that error is `(y1 - y) - err`, close to
    // `-err` whatever E is, since y1 is the more accurate one.)
    for p in [&GAUSSIAN, &FORCED] {
        let t0 = 1.0;
        let y0 = (p.exact)(t0);
        let d = y0.len();
        let (mut est, mut true5, mut worst_ratio) = (Vec::new(), Vec::new(), 0.0f64);
        for h in local_steps(Method::Dopri5, p) {
            let mut sys = (p.system)();
            let mut k = vec![vec![0.0; d]; 7];
            let (mut ys, mut y1, mut err) = (vec![0.0; d], vec![0.0; d], vec![0.0; d]);
            sys.rhs(t0, &y0, &mut k[0]);
            dopri5::attempt(
                &mut sys,
                t0,
                t0 + h,
                h,
                &y0,
                &mut k,
                &mut ys,
                &mut y1,
                &mut err,
            );
            let e = max_abs(&err);
            let e5 = max_diff(&y1, &(p.exact)(t0 + h));
            eprintln!(
                "dopri5 on {}: h = {h}: estimate {e:.2e}, true error of y1 {e5:.2e}",
                p.name
            );
            est.push((h, e));
            true5.push((h, e5));
            worst_ratio = worst_ratio.max(e5 / e);
        }
        let (pe, p5) = (slope(&est), slope(&true5));
        eprintln!(
            "dopri5 on {}: slopes: estimate {pe:.2}, y1 {p5:.2}; true/estimate <= {worst_ratio:.3}",
            p.name
        );
        // Measured 5.11 and 4.99; half an order either side.
        assert!((pe - 5.0).abs() < 0.5, "{}: estimate slope {pe}", p.name);
        // Measured 6.14 and 5.99.
        assert!((p5 - 6.0).abs() < 0.5, "{}: y1 slope {p5}", p.name);
        // Measured at most 0.12 (at the largest h), falling like h: 2x margin.
        assert!(
            worst_ratio < 0.25,
            "{}: true/estimate {worst_ratio}",
            p.name
        );
    }
}

#[test]
fn dop853_error_estimates_track_the_local_error() {
    // As for DOPRI5, through the loop's `attempt`: the fifth-order estimate
    // (weights ER) is O(h^6), the third-order one (b - bhh) O(h^4), and
    // Hairer's combination err5^2 / sqrt(err5^2 + 0.01 err3^2) ~ O(h^8),
    // which must bound the true local error of y1, O(h^9). A wrong weight in
    // ER leaves err5 O(h) (the combination then grows as h falls); a wrong
    // one in bhh, err3 O(h) (the combination then falls like h^11).
    for p in [&GAUSSIAN, &FORCED] {
        let t0 = 1.0;
        let y0 = (p.exact)(t0);
        let d = y0.len();
        // atol = 1, rtol = 0: the estimates in absolute terms.
        let o = options(0.0, 1.0);
        let (mut e5s, mut e3s, mut comb) = (Vec::new(), Vec::new(), Vec::new());
        let mut worst_ratio = 0.0f64;
        for h in local_steps(Method::Dop853, p) {
            let mut sys = (p.system)();
            let mut k = vec![0.0; 16 * d];
            let (mut ys, mut y1) = (vec![0.0; d], vec![0.0; d]);
            sys.rhs(t0, &y0, &mut k[..d]);
            let est = dop853::attempt(&mut sys, t0, h, &y0, &mut k, &mut ys, &mut y1, &o);
            let e5 = h * (est.sq5 / d as f64).sqrt();
            let e3 = h * (est.sq3 / d as f64).sqrt();
            let c = est.norm(h, d);
            let t = max_diff(&y1, &(p.exact)(t0 + h));
            eprintln!(
                "dop853 on {}: h = {h}: err5 {e5:.2e}, err3 {e3:.2e}, combined {c:.2e}, true {t:.2e}",
                p.name
            );
            e5s.push((h, e5));
            e3s.push((h, e3));
            comb.push((h, c));
            worst_ratio = worst_ratio.max(t / c);
        }
        let (p5, p3, pc) = (slope(&e5s), slope(&e3s), slope(&comb));
        eprintln!(
            "dop853 on {}: slopes err5 {p5:.2}, err3 {p3:.2}, combined {pc:.2}; true/combined <= {worst_ratio:.3}",
            p.name
        );
        // Measured 6.28 and 5.81; half an order either side.
        assert!((p5 - 6.0).abs() < 0.5, "{}: err5 slope {p5}", p.name);
        // Measured 3.84 and 3.83.
        assert!((p3 - 4.0).abs() < 0.5, "{}: err3 slope {p3}", p.name);
        // Measured 8.72 and 7.80.
        assert!((pc - 8.0).abs() < 1.0, "{}: combined slope {pc}", p.name);
        // Measured at most 0.31 (forced, h = 1.6), then below 0.09.
        assert!(worst_ratio < 0.6, "{}: true/combined {worst_ratio}", p.name);
    }
}

#[test]
fn global_errors_fall_at_each_order() {
    // RK4 at halved steps over [0, 3]: the error at the end falls like dt^4.
    for p in [&GAUSSIAN, &FORCED] {
        let (t0, t_end) = (0.0, 3.0);
        let mut pts = Vec::new();
        for dt in halvings(0.2, 5) {
            let o = Settings {
                dt,
                ..options(1e-6, 1e-6)
            };
            let out = run(
                Method::Rk4,
                &mut (p.system)(),
                t0,
                &(p.exact)(t0),
                t_end,
                &o,
                &mut Quiet,
            );
            assert_eq!(out.status, Status::Ok);
            let e = max_diff(&out.y_end, &(p.exact)(t_end));
            eprintln!("rk4 on {}: dt {dt}: {e:.2e}", p.name);
            pts.push((dt, e));
        }
        let s = slope(&pts);
        eprintln!("rk4 on {}: slope {s:.2}", p.name);
        // Measured 4.29 and 4.02: half an order either side.
        assert!((s - 4.0).abs() < 0.5, "rk4 on {}: slope {s}", p.name);
    }
    // The adaptive pairs over [0, 10] of the forced oscillator (the
    // Gaussian's end value, ~1e-44, is all absolute tolerance): error
    // against steps over a range of tolerances, slope -p. At loose
    // tolerances the step count is not yet in its asymptotic regime (the
    // count grows more slowly than tol^(-1/p)), which steepens the slope:
    // the band is [-p - 1, -p + 0.5].
    for (method, order, tols) in [(Method::Dopri5, 5.0, 7..=12), (Method::Dop853, 8.0, 7..=13)] {
        let p = &FORCED;
        let (t0, t_end) = (0.0, 10.0);
        let mut pts = Vec::new();
        for k in tols {
            let tol = 10f64.powi(-k);
            let o = options(tol, tol);
            let out = run(
                method,
                &mut (p.system)(),
                t0,
                &(p.exact)(t0),
                t_end,
                &o,
                &mut Quiet,
            );
            assert_eq!(out.status, Status::Ok);
            let e = max_diff(&out.y_end, &(p.exact)(t_end));
            eprintln!(
                "{method} on {}: tol 1e-{k}: {} steps, {e:.2e}",
                p.name, out.stats.steps
            );
            pts.push((out.stats.steps as f64, e));
        }
        let s = slope(&pts);
        eprintln!("{method} on {}: slope {s:.2}", p.name);
        assert!(
            (-order - 1.0..=-order + 0.5).contains(&s),
            "{method}: slope {s}"
        );
    }
}

#[test]
fn dense_output_follows_the_exact_solution_between_steps() {
    // (method, dt or tol, bound on the interpolant's worst error inside a
    // step, in units of dt^4 for RK4 and of the tolerance otherwise).
    // Measured worst over both problems: rk4 0.14 dt^4; dopri5 3.3 tol;
    // dop853 33 tol (its 7th-order interpolant on the Gaussian's long
    // steps: not error-controlled, and 30x its step-end error there);
    // bdf-dense 12.6 tol (the global error, at the nodes as well). Margins
    // 3-7x.
    for (method, acc, bound) in [
        (Method::Rk4, 0.05, 0.5),
        (Method::Dopri5, 1e-8, 20.0),
        (Method::Dop853, 1e-10, 100.0),
        (Method::BdfDense, 1e-8, 50.0),
    ] {
        for p in [&GAUSSIAN, &FORCED] {
            let (t0, t_end) = (0.0, 10.0);
            let o = Settings {
                dt: acc,
                ..options(acc, acc)
            };
            let mut obs = ExactCheck::new(p.exact);
            let out = run(
                method,
                &mut (p.system)(),
                t0,
                &(p.exact)(t0),
                t_end,
                &o,
                &mut obs,
            );
            assert_eq!(out.status, Status::Ok);
            assert_eq!(obs.steps, out.stats.steps);
            let unit = if method == Method::Rk4 {
                acc.powi(4)
            } else {
                acc
            };
            eprintln!(
                "{method} on {}: {} steps, inside {:.2e} ({:.2} units), nodes {:.2e}, ends {:.2e}",
                p.name,
                obs.steps,
                obs.inside,
                obs.inside / unit,
                obs.nodes,
                obs.ends
            );
            assert!(
                obs.inside < bound * unit,
                "{method} on {}: inside {:e}",
                p.name,
                obs.inside
            );
            // The interpolant passes through the step's ends: measured at
            // most 1.2e-13 (bdf-dense's interpolating polynomial).
            assert!(
                obs.ends < 1e-12,
                "{method} on {}: ends {:e}",
                p.name,
                obs.ends
            );
        }
    }
    // The sparse BDF on the same problems written as index-1 DAEs, at
    // 1e-8: measured worst 17 tol (Gaussian) and 27 tol (forced), the
    // global error (the nodes are as far off); 4x margin.
    for p in [&GAUSSIAN, &FORCED] {
        let tol = 1e-8;
        let mut obs = ExactCheck::new(p.exact);
        let out = run_dae(p, 0.0, 10.0, &options(tol, tol), &mut obs);
        assert_eq!(out.status, Status::Ok);
        assert_eq!(obs.steps, out.stats.steps);
        eprintln!(
            "bdf on {}: {} steps, inside {:.2e} ({:.2} tol), nodes {:.2e}, ends {:.2e}",
            p.name,
            obs.steps,
            obs.inside,
            obs.inside / tol,
            obs.nodes,
            obs.ends
        );
        assert!(
            obs.inside < 100.0 * tol,
            "bdf on {}: inside {:e}",
            p.name,
            obs.inside
        );
        // Measured at most 2.3e-15.
        assert!(obs.ends < 1e-12, "bdf on {}: ends {:e}", p.name, obs.ends);
    }
}

#[test]
fn arenstorf_orbit_closes_after_one_period() {
    // The orbit passes close to the Moon twice, where errors are amplified
    // by ~1e4: at these tolerances it closes to 2.4e-6 (dopri5, 841 steps)
    // and 1.6e-9 (dop853, 390 steps). Bounds ~5x those.
    for (method, tol, bound) in [(Method::Dopri5, 1e-10, 1e-5), (Method::Dop853, 1e-13, 1e-8)] {
        let mut sys = arenstorf::system();
        let out = run(
            method,
            &mut sys,
            0.0,
            &arenstorf::Y0,
            arenstorf::PERIOD,
            &options(tol, tol),
            &mut Quiet,
        );
        assert_eq!(out.status, Status::Ok);
        let e = max_diff(&out.y_end, &arenstorf::Y0);
        eprintln!(
            "{method} arenstorf tol {tol:e}: {} steps, {} rejected, closes to {e:.2e}",
            out.stats.steps, out.stats.rejected_steps
        );
        assert!(e < bound, "{method}: closes to {e:e}");
    }
}

/// Van der Pol at `mu = 10` from `(2, 0)` to `t = 20`, just past one
/// relaxation period (~19.1): DOP853 at 1e-13.
fn van_der_pol_reference() -> Vec<f64> {
    let out = run(
        Method::Dop853,
        &mut van_der_pol(10.0),
        0.0,
        &[2.0, 0.0],
        20.0,
        &options(1e-13, 1e-13),
        &mut Quiet,
    );
    assert_eq!(out.status, Status::Ok);
    out.y_end
}

#[test]
fn van_der_pol_agrees_with_a_tight_reference() {
    let reference = van_der_pol_reference();
    // (method, dt or tol, bound on the end error). Measured: rk4 5.6e-10,
    // dopri5 5.2e-9, dop853 7.2e-10, bdf-dense 5.6e-7. Bounds ~5x.
    for (method, acc, bound) in [
        (Method::Rk4, 1e-3, 3e-9),
        (Method::Dopri5, 1e-8, 3e-8),
        (Method::Dop853, 1e-8, 4e-9),
        (Method::BdfDense, 1e-8, 3e-6),
    ] {
        let o = Settings {
            dt: acc,
            ..options(acc, acc)
        };
        let out = run(
            method,
            &mut van_der_pol(10.0),
            0.0,
            &[2.0, 0.0],
            20.0,
            &o,
            &mut Quiet,
        );
        assert_eq!(out.status, Status::Ok);
        let e = max_diff(&out.y_end, &reference);
        eprintln!(
            "{method} vdp {acc:e}: {} steps, error {e:.2e}",
            out.stats.steps
        );
        assert!(e < bound, "{method}: error {e:e}");
    }
    // The sparse BDF on Van der Pol as an index-1 DAE: measured 7.1e-7 at
    // 1e-8 (bdf-dense: 5.6e-7 on the ODE). Bound ~5x.
    let out = run(
        Method::Bdf,
        &mut van_der_pol(10.0),
        0.0,
        &[2.0, 0.0],
        20.0,
        &options(1e-8, 1e-8),
        &mut Quiet,
    );
    assert_eq!(out.status, Status::Ok);
    let e = max_diff(&out.y_end, &reference);
    eprintln!("bdf vdp 1e-8: {} steps, error {e:.2e}", out.stats.steps);
    assert!(e < 4e-6, "bdf: error {e:e}");
}

#[test]
fn the_sparse_bdf_error_falls_with_the_tolerance() {
    // BDF's error is not proportional to the tolerance (variable order,
    // and the error test is local): the worst error over the steps falls by
    // 159x (Gaussian) and 737x (forced) from 1e-5 to 1e-8, and by 352x and
    // 935x from 1e-8 to 1e-11. A method that stopped converging would fall
    // by ~1; the band is 2.5x beyond the measured extremes.
    for p in [&GAUSSIAN, &FORCED] {
        let worst = |tol: f64| {
            let mut obs = ExactCheck::new(p.exact);
            let out = run_dae(p, 0.0, 10.0, &options(tol, tol), &mut obs);
            assert_eq!(out.status, Status::Ok);
            obs.nodes
        };
        let (e5, e8, e11) = (worst(1e-5), worst(1e-8), worst(1e-11));
        eprintln!(
            "bdf on {}: 1e-5 {e5:.2e}, 1e-8 {e8:.2e}, 1e-11 {e11:.2e}: ratios {:.0}, {:.0}",
            p.name,
            e5 / e8,
            e8 / e11
        );
        for r in [e5 / e8, e8 / e11] {
            assert!((60.0..=2500.0).contains(&r), "bdf on {}: ratio {r}", p.name);
        }
    }
}

#[test]
fn a_blow_up_ends_step_size_too_small_just_before_the_pole() {
    // y' = y^2, y(0) = 1 to t = 2: y = 1 / (1 - t). Every adaptive method
    // ends `step_size_too_small`, never `diverged`: the step, held to a
    // relative error by rtol, shrinks like the distance to the (numerical)
    // pole, and reaches the rounding floor 1e-14 while y is ~1e12, far
    // from overflowing; no non-finite value ever appears. The numerical
    // pole t_reached + 1 / y_end is where the run stopped to ~1e-12, and
    // is the exact pole to the accuracy of the run: measured |t_pole - 1|
    // 2.9e-7 (bdf), 2.7e-7 (bdf-dense), 5.2e-10 (dopri5), 1.2e-9 (dop853).
    let o = options(1e-8, 1e-10);
    let runs = every_adaptive(blow_up, 0.0, &[1.0], 2.0, &o);
    for (method, out) in runs {
        // gen-alpha, of second order: measured |t_pole - 1| 6.2e-7, y 3.6e10.
        let (bound, y_min, gap) = match method {
            Method::Bdf | Method::BdfDense => (1e-6, 1e11, 1e-11),
            Method::GenAlpha => (1e-6, 1e10, 1e-10),
            _ => (5e-9, 1e11, 1e-11),
        };
        eprintln!("{method} blow-up: {out:?}");
        assert_eq!(out.status, Status::StepSizeTooSmall, "{method}");
        let t_failed = out.t_failed.expect("a failed run has t_failed");
        // The step that failed was below the floor 1e-14 max(1, t).
        assert!(
            t_failed > out.t_reached && t_failed - out.t_reached < 2e-14,
            "{method}: {out:?}"
        );
        let y = out.y_end[0];
        // Measured 9e11 to 2.4e13.
        assert!(y.is_finite() && y > y_min, "{method}: {out:?}");
        let t_pole = out.t_reached + 1.0 / y;
        assert!(t_pole - out.t_reached < gap, "{method}: {out:?}");
        assert!((t_pole - 1.0).abs() < bound, "{method}: pole at {t_pole}");
    }
    // RK4 has no floor: its fixed steps run into the pole and overflow.
    let o = Settings { dt: 0.01, ..o };
    let out = run(
        Method::Rk4,
        &mut blow_up(),
        0.0,
        &[1.0],
        2.0,
        &o,
        &mut Quiet,
    );
    eprintln!("rk4 blow-up: {out:?}");
    // Its solution has no pole at 1 exactly: measured overflow in the step
    // from 1.01 to 1.02, y = 1e13 at 1.01. Within 3 steps of the pole.
    assert_eq!(out.status, Status::Diverged);
    assert!((out.t_reached - 1.0).abs() < 0.03, "{out:?}");
    assert!(out.y_end[0].is_finite() && out.y_end[0] > 1e6, "{out:?}");
}

#[test]
fn leaving_the_domain_of_f_mid_run_ends_diverged_where_it_left() {
    // Not a non-finite start: every value is finite until the solution
    // y = t reaches 1 at t = 1; every step past it meets a NaN, is cut,
    // and the cuts reach the floor. The status says a non-finite value
    // appeared, and the run keeps its last finite state, just short of 1.
    let o = options(1e-8, 1e-10);
    let runs = every_adaptive(domain_exit, 0.0, &[0.0], 2.0, &o);
    for (method, out) in runs {
        eprintln!("{method} domain exit: {out:?}");
        assert_eq!(out.status, Status::Diverged, "{method}: {out:?}");
        if method == Method::GenAlpha {
            // Its Newton iteration accepts its last correction without a
            // residual there (one right-hand side a step less), so it may
            // end one step past the edge (measured: t = 1.0486, its 20th
            // step), finite and diverged: a limit, not a NaN.
            assert!(out.y_end[0].is_finite() && out.t_reached < 1.2, "{out:?}");
            assert!(out.t_failed.is_some_and(|t| t >= out.t_reached), "{out:?}");
            continue;
        }
        assert!(
            out.y_end[0].is_finite() && out.y_end[0] <= 1.0,
            "{method}: {out:?}"
        );
        // Measured: stopped 1.2e-14 (dopri5) to 4.9e-15 (bdf) before t = 1,
        // on the exact solution y = t to rounding, after 41 to 115 steps.
        assert!(
            1.0 - out.t_reached < 1e-12,
            "{method}: stopped at {}",
            out.t_reached
        );
        assert!(
            (out.y_end[0] - out.t_reached).abs() < 1e-12,
            "{method}: {out:?}"
        );
        assert!(out.stats.steps > 10, "{method}: {out:?}");
        assert!(
            out.t_failed.is_some_and(|t| t > out.t_reached),
            "{method}: {out:?}"
        );
    }
}

#[test]
fn a_non_finite_start_is_diverged_at_the_start() {
    // Every method, through the registry: a NaN in y0 ends the run at t0,
    // `diverged`, after the one right-hand side that showed it.
    for method in Method::ALL {
        let o = Settings {
            dt: 0.1,
            ..options(1e-8, 1e-10)
        };
        let mut sys = (OSCILLATOR.system)();
        let out = run(method, &mut sys, 0.0, &[f64::NAN, 0.0], 1.0, &o, &mut Quiet);
        assert_eq!(out.status, Status::Diverged, "{method}");
        assert_eq!((out.t_reached, out.t_failed), (0.0, Some(0.0)), "{method}");
        assert_eq!(out.stats.steps, 0, "{method}");
    }
}

#[test]
fn the_budget_counts_every_attempt() {
    // Van der Pol at mu = 1000 from (2, 0): a budget of 1 to 199 attempts
    // (accepted + rejected) ends `max_steps` with exactly that many, for
    // every adaptive method that steps the ODE (the sparse BDF's budget is
    // tested on the chain, tests/physics/bdf.rs).
    for method in [Method::Dopri5, Method::Dop853, Method::BdfDense] {
        let mut rejected_seen = false;
        for max_steps in 1..200 {
            let o = Settings {
                max_steps,
                ..options(1e-6, 1e-8)
            };
            let mut sys = van_der_pol(1000.0);
            let out = run(method, &mut sys, 0.0, &[2.0, 0.0], 3000.0, &o, &mut Quiet);
            assert_eq!(out.status, Status::MaxSteps, "{method}: budget {max_steps}");
            assert_eq!(out.stats.steps + out.stats.rejected_steps, max_steps);
            assert!(out.t_reached < 3000.0 && out.y_end.iter().all(|v| v.is_finite()));
            rejected_seen |= out.stats.rejected_steps > 0;
        }
        assert!(rejected_seen, "{method}");
    }
}
