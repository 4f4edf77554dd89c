//! Issue 49's steel rope: the snap's pivot tension is a number a run
//! reports (`Summary::pivot_force_max`, the `--forces` samples), so an
//! `ok` run must have it right to its tolerance or say it did not resolve
//! it (`Summary::forces_resolved`).

use chain_ode::analysis::pivot_forces;
use chain_ode::{solve, Chain, ChainParams, Method, SolveOptions, Start, Status};

use crate::elastic::rigid_of;

/// `scenes/span-d3.toml` (n = 50, `L = 6`, `m = 0.2` a rod, `g = 1`,
/// `r = 5e-4`) with `EA = 1e8` and 5% damping of one joint's axial mode,
/// `eta = 0.1 sqrt(EA m l) = 154.9`.
fn steel_rope() -> Chain {
    let (ea, m, l) = (1e8, 0.2, 6.0 / 50.0);
    Chain::new(ChainParams {
        links: 50,
        damping: 5e-4,
        axial_stiffness: Some(ea),
        axial_damping: 0.1 * (ea * m * l).sqrt(),
        ..ChainParams::default()
    })
    .unwrap()
}

/// The steel rope's snap tension from every way `gen-alpha` can be run on
/// it, against the rigid chain's (the rope's limit, an independent
/// formulation: its pivot force from the multipliers' recursion, by DOPRI5
/// at rtol 1e-10 sampled every 2e-4; the rope's converged value, BDF at
/// rtol 1e-8 and DOP853 at 1e-9, is within 1.5e-4 of it). A run that says
/// its forces are resolved has its peak within the bound (10 rtol,
/// or 1e-2 at rtol >= 1e-3) plus that 1.5e-4; `auto` at rtol 1e-3 (which
/// runs gen-alpha at `rho_inf = 0`, the stepped-over modes annihilated)
/// resolves it; gen-alpha at the default `rho_inf = 0.9` does not (its peak
/// was 26 and 3.3 times too high at rtol 1e-3 and 1e-6) and must say so.
#[test]
fn no_run_reports_a_snap_tension_it_did_not_resolve_as_resolved() {
    let chain = steel_rope();
    let start = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    };
    let s = start.state(&chain).unwrap();
    let t_end = 3.2;
    let rigid = solve(
        &rigid_of(&chain),
        &s,
        Method::Dopri5,
        &SolveOptions {
            t_end,
            rtol: 1e-10,
            atol: 1e-12,
            output_dt: Some(2e-4),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(rigid.status, Status::Ok);
    let reference = pivot_forces(&rigid)
        .iter()
        .map(|(_, f)| f[0].hypot(f[1]))
        .fold(0.0, f64::max);
    // The snap: far above the hanging weight (n m g = 10).
    assert!(reference > 4.0 * chain.weight(), "{reference}");
    let mut resolved = vec![];
    for (method, rho_inf, rtol) in [
        (Method::Auto, 0.9, 1e-3),
        (Method::GenAlpha, 0.9, 1e-3),
        (Method::GenAlpha, 0.9, 1e-6),
        (Method::GenAlpha, 0.0, 1e-3),
        (Method::GenAlpha, 0.0, 1e-4),
    ] {
        let o = SolveOptions {
            t_end,
            rtol,
            atol: 1e-2 * rtol,
            rho_inf,
            ..Default::default()
        };
        let tr = solve(&chain, &s, method, &o).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method} {rho_inf} {rtol}");
        let (peak, _) = tr.summary.pivot_force_max.unwrap();
        let err = (peak / reference - 1.0).abs();
        let bound = if rtol >= 1e-3 { 1e-2 } else { 10.0 * rtol } + 1.5e-4;
        let ok = tr.summary.forces_resolved;
        assert!(
            !ok || err <= bound,
            "{method} rho {rho_inf} rtol {rtol}: {peak} against {reference} ({err:e}) said resolved"
        );
        resolved.push(ok);
    }
    assert_eq!(resolved, [true, false, false, true, true]);
}

/// The span-d3 chain cut to 10 rods (`m = 0.2`, `l = 0.6`, `r = 5e-4`)
/// with axial stiffness `ea` and 5% damping of a joint's axial mode, on
/// its U (`P1 = (3, 0)`), at rest.
fn ten_rod_rope(ea: f64) -> (Chain, chain_ode::State) {
    let (m, l) = (0.2, 0.6);
    let chain = Chain::new(ChainParams {
        links: 10,
        damping: 5e-4,
        axial_stiffness: Some(ea),
        axial_damping: 0.1 * (ea * m * l).sqrt(),
        ..ChainParams::default()
    })
    .unwrap();
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    (chain, s)
}

/// Issue 49.3's criterion on a cheap steel rope (10 rods of the span-d3
/// chain, `EA = 1e7`, 5% damping of a joint's axial mode): every smooth
/// method's `ok` run at rtol 1e-3 and 1e-6 has its peak pivot force
/// and its largest tension (both tracked at every step) within 10 rtol of
/// the converged values (1e-2 at rtol 1e-3), or says it did not resolve
/// them (`forces_resolved = false`). Converged: DOP853 at rtol 1e-10,
/// confirmed by DOPRI5 at 1e-9 to 1e-8. Measured: BDF and BDF-dense,
/// stepping over the lightly damped axial modes, miss at every one of
/// these tolerances (1.6 times, 1.3e-2, 4.5e-5 off) and gen-alpha at
/// `rho_inf = 0.9` by 36 to 0.2 times, and must say so; DOPRI5 at 1e-3
/// put the pivot force 16% high (DOP853 0.9%), and the explicit methods
/// do not claim forces at rtol above 1e-4; at 1e-5 and 1e-7 they resolve
/// them (4e-9).
#[test]
fn every_ok_run_has_its_peak_forces_to_its_tolerance_or_says_it_did_not() {
    use chain_ode::PeakForce;
    let (chain, s) = ten_rod_rope(1e7);
    let run = |method: Method, rtol: f64| {
        let o = SolveOptions {
            t_end: 3.2,
            rtol,
            atol: 1e-2 * rtol,
            dt: 2e-5,
            ..Default::default()
        };
        solve(&chain, &s, method, &o).unwrap()
    };
    let peaks = |tr: &chain_ode::Trajectory| {
        [PeakForce::Pivot, PeakForce::Tension].map(|f| tr.summary.peak(f).unwrap().value)
    };
    let reference = run(Method::Dop853, 1e-10);
    let confirm = run(Method::Dopri5, 1e-9);
    let (want, other) = (peaks(&reference), peaks(&confirm));
    for (a, b) in want.iter().zip(other) {
        assert!((a / b - 1.0).abs() < 1e-8, "{want:?} against {other:?}");
    }
    assert!(want[0] > 3.0 * chain.weight(), "the snap: {want:?}");
    let mut table = vec![];
    for method in crate::smooth_methods() {
        for rtol in [1e-3, 1e-6] {
            if method == Method::Rk4 && rtol != 1e-3 {
                continue;
            }
            let tr = run(method, rtol);
            let got = peaks(&tr);
            let err: Vec<f64> = got
                .iter()
                .zip(want)
                .map(|(g, w)| (g / w - 1.0).abs())
                .collect();
            let bound = if rtol >= 1e-3 { 1e-2 } else { 10.0 * rtol };
            let claimed = tr.status == Status::Ok && tr.summary.forces_resolved;
            table.push(format!(
                "{method} {rtol:e}: {:?} {got:?} errors {err:?} resolved {} steps {}",
                tr.status, tr.summary.forces_resolved, tr.stats.steps
            ));
            assert!(
                !claimed || err.iter().all(|&e| e <= bound),
                "{method} rtol {rtol:e}: {got:?} against {want:?} ({err:?}) said resolved"
            );
            if matches!(method, Method::Dopri5 | Method::Dop853 | Method::Rk4) && rtol < 1e-4 {
                assert!(claimed, "{method} {rtol:e}");
            }
        }
    }
    eprintln!("{}", table.join("\n"));
}

/// The `force-precision` figure's rope (10 rods of the span-d3 chain at
/// the steel rope's `EA = 1e8`, 5% damping): DOPRI5 at rtol 1e-4 put the
/// peak pivot force 1.3e-3 off (10.36742 against 10.35421), above 10
/// rtol, and said it resolved it. Every explicit run at 1e-4 and 1e-5 that
/// claims its forces has them within 10 rtol of DOP853 at rtol 1e-8
/// (confirmed by DOPRI5 at 1e-9 to 6e-8, the force's rounding floor `K eps
/// L` being 2e-7 of it).
#[test]
fn an_explicit_run_on_a_steel_rope_claims_its_forces_only_within_ten_tolerances() {
    use chain_ode::PeakForce;
    let (chain, s) = ten_rod_rope(1e8);
    let run = |method: Method, rtol: f64| {
        let o = SolveOptions {
            t_end: 3.2,
            rtol,
            atol: 1e-2 * rtol,
            ..Default::default()
        };
        let tr = solve(&chain, &s, method, &o).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method} {rtol:e}");
        let peak = tr.summary.peak(PeakForce::Pivot).unwrap().value;
        (peak, tr.summary.forces_resolved)
    };
    let (want, _) = run(Method::Dop853, 1e-8);
    let (other, _) = run(Method::Dopri5, 1e-9);
    assert!((other / want - 1.0).abs() < 3e-7, "{want} against {other}");
    for method in [Method::Dopri5, Method::Dop853] {
        for rtol in [1e-4, 1e-5] {
            let (peak, claimed) = run(method, rtol);
            let err = (peak / want - 1.0).abs();
            assert!(
                !claimed || err <= 10.0 * rtol,
                "{method} rtol {rtol:e}: {peak} against {want} ({err:e}) said resolved"
            );
        }
    }
}
