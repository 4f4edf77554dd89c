//! Air drag (`chain.air_drag = c`, [`chain_ode::load::Drag`]): a force
//! `-c l_i |v_i| v_i` at each rod's centre, against its closed forms, the
//! dense reference's virtual work, and the energy balance of every method.

use chain_ode::dae::ChainDae;
use chain_ode::dynamics::{accelerations, Workspace};
use chain_ode::{
    dense, solve, Chain, ChainParams, ChainSystem, Method, Pivot, SolveOptions, Start, State,
    Status,
};
use proptest::prelude::*;

use super::chain_and_state;

/// `params` with the drag `c`.
fn with_drag(mut params: ChainParams, c: f64) -> ChainParams {
    params.coefficients.set("chain.air_drag", c);
    params
}

/// Each method's options: RK4 at `dt`, the others at `rtol` (gen-alpha, of
/// second order, a thousand times tighter), samples every `t_end / 40`.
fn options(method: Method, t_end: f64, dt: f64, rtol: f64) -> SolveOptions {
    let x = match method {
        Method::Rk4 => dt,
        // Its tightest tolerance (issue 47 W2).
        Method::GenAlpha => (rtol * 1e-3).max(chain_ode::GEN_ALPHA_MIN_RTOL),
        _ => rtol,
    };
    SolveOptions {
        t_end,
        output_dt: Some(t_end / 40.0),
        ..SolveOptions::default()
    }
    .at_accuracy(method, x)
}

/// A chain lying flat, both ends let go at `t = 0`: every rod falls alike,
/// no joint pulls, and each one is a body of mass `m` and length `l` under
/// its weight and its drag, `m v' = -m g + c l v^2`, which reaches the
/// terminal speed `v_t = sqrt(m g / (c l))` as
/// `v(t) = -v_t tanh(g t / v_t)` after falling
/// `(v_t^2 / g) ln cosh(g t / v_t)`. The rigid chain's state does not carry
/// a free pivot's velocity and refuses the drag with it; elastic links (stiff:
/// no gap opens) run it with every method, the tip on the closed form to
/// each method's accuracy, and `E + W = E(0)` with the drag's work in `W`.
#[test]
fn a_chain_falling_flat_reaches_the_terminal_speed_with_every_method() {
    let (n, m, len, g, c) = (12, 0.2, 6.0, 1.0, 0.05);
    let l = len / n as f64;
    let params = with_drag(
        ChainParams {
            length: len,
            links: n,
            mass: m,
            gravity: g,
            pivot: Pivot {
                release: Some(0.0),
                ..Pivot::default()
            },
            ..ChainParams::default()
        },
        c,
    );
    let flat = Start::Stretched {
        p0: [0.0, 0.0],
        p1: [len, 0.0],
    };
    // Rigid links: refused by the drag's key, before any run.
    let rigid = Chain::new(params.clone()).unwrap();
    let s = flat.state(&rigid).unwrap();
    let e = solve(&rigid, &s, Method::Dopri5, &SolveOptions::default()).unwrap_err();
    assert_eq!(e.field, "chain.air_drag");

    let chain = Chain::new(ChainParams {
        axial_stiffness: Some(1e4 * n as f64 * m * g),
        ..params
    })
    .unwrap();
    let vt = (m * g / (c * l)).sqrt();
    let fall = |t: f64| (vt * vt / g) * (g * t / vt).cosh().ln();
    let speed = |t: f64| vt * (g * t / vt).tanh();
    let t_end = 4.0;
    for method in Method::ALL.into_iter().filter(|m| !m.is_nonsmooth()) {
        let tr = solve(&chain, &s, method, &options(method, t_end, 1e-3, 1e-9)).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method}");
        // Within each method's accuracy of the closed form, relative to
        // the fall (measured: RK4 2e-15, DOPRI5 8e-11, gen-alpha 7e-11,
        // DOP853 and auto 5e-10, the BDFs 1.1e-9 and 1.4e-9; the work and
        // the balance to 6e-9 of theirs).
        // gen-alpha at its tightest rtol, 1e-10: its work within 1.2e-8.
        let tol = match method {
            Method::Bdf | Method::BdfDense => 2e-8,
            Method::GenAlpha => 1e-7,
            _ => 1e-8,
        };
        let y0 = tr.tip(0)[1];
        let mut worst: f64 = 0.0;
        for k in 0..tr.len() {
            let t = tr.times[k];
            let [tx, ty] = tr.tip(k);
            let [vx, vy] = tr.tip_velocity(k);
            worst = worst.max((ty - (y0 - fall(t))).abs() / fall(t_end));
            assert!((tx - len).abs() < tol * len, "{method}: t = {t}: x {tx}");
            assert!(vx.abs() < tol * vt, "{method}: t = {t}: vx {vx}");
            assert!(
                (vy + speed(t)).abs() < tol * vt,
                "{method}: t = {t}: {vy} vs {}",
                -speed(t)
            );
        }
        assert!(worst < tol, "{method}: fall off by {worst:e} of it");
        // By t = 4 the chain is at 89 % of the terminal speed, so the drag
        // did most of the work: W is most of the weight's loss.
        let w = tr.summary.dissipated;
        let lost = m * n as f64 * g * fall(t_end) - 0.5 * m * n as f64 * speed(t_end).powi(2);
        assert!((w - lost).abs() < tol * lost, "{method}: W {w} vs {lost}");
        assert!(
            tr.summary.energy_balance_error < tol * chain.energy_scale(),
            "{method}: balance {:e}",
            tr.summary.energy_balance_error
        );
    }
}

/// One rod spinning about its fixed end without gravity: the drag at its
/// centre, `c l (w l / 2)^2` across it, slows it as
/// `(m l^2 / 3) w' = -c l^4 w |w| / 8`, so `w(t) = w0 / (1 + k w0 t)` and
/// `phi(t) = ln(1 + k w0 t) / k`, `k = 3 c l^2 / (8 m)`, and the work the
/// drag took is the kinetic energy lost. Every method, on the rigid model's
/// recursion, banded DAE and dense Jacobian alike.
#[test]
fn the_drag_on_a_spinning_rod_takes_its_closed_form_work_with_every_method() {
    let (m, l, c, w0) = (0.3, 1.5, 0.2, 2.0);
    let chain = Chain::new(with_drag(
        ChainParams {
            length: l,
            links: 1,
            mass: m,
            gravity: 0.0,
            ..ChainParams::default()
        },
        c,
    ))
    .unwrap();
    let s = State {
        anchor: [0.0, 0.0],
        angles: vec![0.0],
        rates: vec![w0],
    };
    let k = 3.0 * c * l * l / (8.0 * m);
    let t_end = 3.0;
    let rate = |t: f64| w0 / (1.0 + k * w0 * t);
    let angle = |t: f64| (1.0 + k * w0 * t).ln() / k;
    let inertia = m * l * l / 3.0;
    for method in Method::ALL.into_iter().filter(|m| !m.is_nonsmooth()) {
        let tr = solve(&chain, &s, method, &options(method, t_end, 1e-3, 1e-10)).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method}");
        // Measured: the angle within 4e-14 (RK4), 3e-11 (the explicit
        // pairs, gen-alpha), 9e-10 (the BDFs; auto runs BDF without gravity).
        // gen-alpha at its tightest rtol, 1e-10: the angle within 1.1e-9.
        let tol = match method {
            Method::Bdf | Method::BdfDense | Method::Auto | Method::GenAlpha => 1e-8,
            _ => 1e-9,
        };
        for smp in tr.samples() {
            let t = smp.t;
            assert!(
                (smp.angles[0] - angle(t)).abs() < tol,
                "{method}: t = {t}: {} vs {}",
                smp.angles[0],
                angle(t)
            );
            assert!(
                (smp.rates[0] - rate(t)).abs() < tol * w0,
                "{method}: t = {t}"
            );
            let lost = 0.5 * inertia * (w0 * w0 - rate(t).powi(2));
            assert!(
                (smp.dissipated - lost).abs() < tol * inertia * w0 * w0,
                "{method}: t = {t}: W {} vs {lost}",
                smp.dissipated
            );
        }
    }
}

/// Random chains of every term, with a drag: the recursion's
/// `phi''` is the dense reference's, whose loads enter by virtual work
/// (`Q_i = sum_k (dc_k / dphi_i) . F_k`) and not through articulated bodies.
#[test]
fn the_recursion_with_drag_is_the_dense_solve_of_virtual_work() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    runner
        .run(
            &(chain_and_state(9), 0.001f64..3.0),
            |((chain, phi, w), c)| {
                let chain = Chain::new(with_drag(chain.params().clone(), c)).unwrap();
                let n = chain.links();
                let mut acc = vec![0.0; n];
                accelerations(&chain, &phi, &w, &mut acc, &mut Workspace::new(n));
                let reference = dense::accelerations(&chain, &phi, &w);
                let scale = reference.iter().fold(1.0f64, |a, b| a.max(b.abs()));
                for (a, b) in acc.iter().zip(&reference) {
                    prop_assert!((a - b).abs() < 1e-8 * scale, "{a} vs {b}");
                }
                Ok(())
            },
        )
        .unwrap();
}

/// The banded DAE with a drag: made consistent by the recursion, its
/// algebraic rows vanish and its derivatives are `ChainSystem`'s (with the
/// drag's power in `W'`); every entry of its Jacobian is the residual's
/// derivative (central differences). The entries it leaves out are the
/// drag's reach past the band (a centre's velocity reads every rod above
/// it, a rod's force in the difference of two neighbours' balances): none
/// without the drag, and in proportion to it (`bdf` runs on a Newton matrix
/// without them, an inexact Newton: the balance test below).
#[test]
fn the_banded_dae_with_drag_is_consistent_and_exact_within_its_band() {
    for (tip_mass, taper) in [(0.0, 1.0), (0.4, 3.0)] {
        let mut reach = vec![];
        for c in [0.0, 0.15, 0.3] {
            reach.push(band_check(tip_mass, taper, c));
        }
        assert_eq!(
            reach[0], 0.0,
            "taper {taper}: nothing left out without the drag"
        );
        assert!(
            reach[1] > 0.0,
            "taper {taper}: the drag reaches past the band"
        );
        assert!(
            (reach[2] / reach[1] - 2.0).abs() < 1e-3,
            "taper {taper}: {reach:?}"
        );
    }
}

/// The largest entry the banded DAE's Jacobian leaves out, after checking
/// the DAE's consistency and its entries, for a chain with the drag `c`.
fn band_check(tip_mass: f64, taper: f64, c: f64) -> f64 {
    let mut params = with_drag(
        ChainParams {
            links: 8,
            damping: 0.01,
            bending_stiffness: 0.02,
            tip_mass,
            ..ChainParams::default()
        },
        c,
    );
    params.profile.taper = taper;
    let chain = Chain::new(params).unwrap();
    let n = chain.links();
    let phi: Vec<f64> = (0..n).map(|i| -1.2 + 0.3 * (i as f64).sin()).collect();
    let w: Vec<f64> = (0..n).map(|i| 0.8 * (1.3 * i as f64).cos()).collect();
    let dae = ChainDae::new(&chain);
    let dim = dae.dim();
    let mut y = vec![0.0; dim];
    y[..n].copy_from_slice(&phi);
    y[n..2 * n].copy_from_slice(&w);
    dae.make_consistent(&mut y, &mut Workspace::new(n));
    let mut out = vec![0.0; dim];
    dae.rhs(&y, &mut out);
    for (k, r) in out[2 * n + 1..].iter().enumerate() {
        assert!(r.abs() < 1e-10, "taper {taper}, c {c}: row {k}: {r}");
    }
    let mut sys = ChainSystem::new(&chain);
    let mut dy = vec![0.0; 2 * n + 1];
    sys.rhs(0.0, &y[..2 * n + 1], &mut dy);
    for k in 0..2 * n + 1 {
        assert!(
            (out[k] - dy[k]).abs() < 1e-10 * dy[k].abs().max(1.0),
            "taper {taper}, c {c}: {k}: {} vs {}",
            out[k],
            dy[k]
        );
    }
    let mut jac = vec![0.0; dim * dim];
    let mut seen = vec![false; dim * dim];
    dae.jacobian_entries(&y, |r, col, v| {
        assert!(!seen[r * dim + col], "({r}, {col}) twice");
        seen[r * dim + col] = true;
        jac[r * dim + col] = v;
    });
    let (mut up, mut down) = (vec![0.0; dim], vec![0.0; dim]);
    let mut left_out: f64 = 0.0;
    for col in 0..dim {
        let h = 1e-6 * (1.0 + y[col].abs());
        let (mut yp, mut ym) = (y.clone(), y.clone());
        yp[col] += h;
        ym[col] -= h;
        dae.rhs(&yp, &mut up);
        dae.rhs(&ym, &mut down);
        for r in (0..dim).filter(|&r| r != 2 * n) {
            let fd = (up[r] - down[r]) / (2.0 * h);
            if seen[r * dim + col] {
                assert!(
                    (jac[r * dim + col] - fd).abs() < 1e-6 * fd.abs().max(1.0),
                    "taper {taper}, c {c}: ({r}, {col}): {} vs {fd}",
                    jac[r * dim + col]
                );
            } else if fd.abs() > 1e-7 {
                left_out = left_out.max(fd.abs());
            }
        }
    }
    left_out
}

/// The drag's work in the balance: a span of 20 rods, rigid and elastic,
/// with a drag of the size of its weight at the speed of a fall over its
/// length, run by every method: `E + W = E(0)` to each method's accuracy,
/// `W` never falls, and the drag slows the fall (the tip's largest speed
/// below the drag-free run's).
#[test]
fn every_method_closes_the_energy_balance_with_the_drag_in_it() {
    for ea in [None, Some(2e4)] {
        let base = ChainParams {
            links: 20,
            damping: 5e-4,
            axial_stiffness: ea,
            ..ChainParams::default()
        };
        let chain = Chain::new(with_drag(base.clone(), 0.05)).unwrap();
        let free = Chain::new(base).unwrap();
        let s = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [3.0, 0.0],
        }
        .state(&chain)
        .unwrap();
        let t_end = 3.0;
        let vmax_free = solve(
            &free,
            &s,
            Method::Dop853,
            &options(Method::Dop853, t_end, 1e-3, 1e-10),
        )
        .unwrap()
        .summary
        .tip_speed_max;
        for method in Method::ALL.into_iter().filter(|m| !m.is_nonsmooth()) {
            // gen-alpha at rtol 1e-9 (of second order, it crawls at the
            // 1e-11 the other tests give it).
            let opts = match method {
                Method::GenAlpha => options(method, t_end, 2e-4, 1e-6),
                _ => options(method, t_end, 2e-4, 1e-8),
            };
            let tr = solve(&chain, &s, method, &opts).unwrap();
            assert_eq!(tr.status, Status::Ok, "{ea:?} {method}");
            // Measured (of the energy scale): RK4 6e-14 rigid and 1.2e-9
            // elastic at dt = 2e-4, the explicit pairs 8e-11 at most, the
            // BDFs 7e-9, gen-alpha 1.4e-8 at rtol 1e-9.
            let bound = match method {
                Method::Bdf | Method::BdfDense | Method::GenAlpha => 1e-7,
                _ => 1e-8,
            } * chain.energy_scale();
            assert!(
                tr.summary.energy_balance_error < bound,
                "{ea:?} {method}: {:e}",
                tr.summary.energy_balance_error
            );
            let work: Vec<f64> = tr.samples().map(|s| s.dissipated).collect();
            assert!(work.windows(2).all(|p| p[1] >= p[0] - 1e-12), "{method}");
            assert!(tr.summary.dissipated > 0.0);
            assert!(
                tr.summary.tip_speed_max < vmax_free,
                "{ea:?} {method}: {} vs {vmax_free}",
                tr.summary.tip_speed_max
            );
        }
    }
}
