//! A point mass at the free end (`chain.tip_mass`, issue 18): the O(n)
//! recursion against the dense reference, the banded DAE's residual and
//! Jacobian, the energy along a run, the one-rod physical pendulum, and the
//! folded chain's fall against the energy-conserving law derived below.

use chain_ode::analysis::{first_time_below, tip_track};
use chain_ode::dae::ChainDae;
use chain_ode::dynamics::{accelerations, Workspace};
use chain_ode::{dense, solve, Chain, ChainParams, Method, SolveOptions, Start};

fn chain(n: usize, m_total: f64, tip: f64, damping: f64) -> Chain {
    Chain::new(ChainParams {
        links: n,
        mass: m_total / n as f64,
        damping,
        gravity: 1.3,
        tip_mass: tip,
        ..ChainParams::default()
    })
    .unwrap()
}

/// A deterministic, irregular state of `n` rods.
fn state(n: usize, seed: f64) -> (Vec<f64>, Vec<f64>) {
    let phi = (0..n)
        .map(|i| (1.7 * i as f64 + seed).sin() * 2.0 - 1.0)
        .collect();
    let w = (0..n)
        .map(|i| (0.9 * i as f64 + 2.0 * seed).cos() * 1.5)
        .collect();
    (phi, w)
}

#[test]
fn recursion_with_a_tip_mass_matches_the_dense_reference() {
    for (n, tip) in [(1, 0.3), (2, 0.05), (7, 2.0), (30, 0.5)] {
        let chain = chain(n, 2.0, tip, 0.01);
        let (phi, w) = state(n, 0.3 + tip);
        let mut acc = vec![0.0; n];
        accelerations(&chain, &phi, &w, &mut acc, &mut Workspace::new(n));
        let reference = dense::accelerations(&chain, &phi, &w);
        let scale = reference.iter().fold(1.0f64, |a, x| a.max(x.abs()));
        for (a, b) in acc.iter().zip(&reference) {
            assert!(
                (a - b).abs() < 1e-11 * scale,
                "n = {n}, M = {tip}: {a} vs {b}"
            );
        }
        // And the tip mass matters: without it the answer differs.
        let bare = dense::accelerations(&self::chain(n, 2.0, 0.0, 0.01), &phi, &w);
        assert!(bare
            .iter()
            .zip(&reference)
            .any(|(a, b)| (a - b).abs() > 1e-3 * scale));
        // The energy's kinetic part is the dense quadratic form.
        let t = chain_ode::kinematics::kinetic_energy(&chain, &phi, &w);
        let td = dense::kinetic_energy(&chain, &phi, &w);
        assert!((t - td).abs() < 1e-12 * td.abs().max(1.0), "{t} vs {td}");
    }
}

#[test]
fn banded_dae_with_a_tip_mass_is_consistent_and_its_jacobian_is_exact() {
    for (n, tip) in [(1, 0.7), (5, 0.4)] {
        let chain = chain(n, 1.0, tip, 0.02);
        let dae = ChainDae::new(&chain);
        let (phi, w) = state(n, 1.1);
        let mut y = vec![0.0; dae.dim()];
        y[..n].copy_from_slice(&phi);
        y[n..2 * n].copy_from_slice(&w);
        dae.make_consistent(&mut y, &mut Workspace::new(n));
        let mut out = vec![0.0; dae.dim()];
        dae.rhs(&y, &mut out);
        let d = dae.differential_dim();
        for (k, r) in out[d..].iter().enumerate() {
            assert!(r.abs() < 1e-12, "n = {n}: residual {k} = {r}");
        }
        // The recursion's accelerations are the DAE's alpha.
        let mut acc = vec![0.0; n];
        accelerations(&chain, &phi, &w, &mut acc, &mut Workspace::new(n));
        for i in 0..n {
            assert!((y[d + i] - acc[i]).abs() < 1e-12);
        }
        // The Jacobian against central differences, every column but W's row.
        let mut jac = vec![0.0; dae.dim() * dae.dim()];
        dae.jacobian_entries(&y, |r, c, v| jac[r * dae.dim() + c] += v);
        let h = 1e-6;
        for c in 0..dae.dim() {
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[c] += h;
            ym[c] -= h;
            let (mut fp, mut fm) = (vec![0.0; dae.dim()], vec![0.0; dae.dim()]);
            dae.rhs(&yp, &mut fp);
            dae.rhs(&ym, &mut fm);
            for r in (0..dae.dim()).filter(|&r| r != 2 * n) {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                let an = jac[r * dae.dim() + c];
                assert!(
                    (fd - an).abs() < 1e-6,
                    "n = {n}: J[{r}][{c}] = {an} vs {fd}"
                );
            }
        }
    }
}

#[test]
fn energy_is_conserved_with_a_tip_mass_under_every_method() {
    let chain = chain(12, 1.0, 0.6, 0.0);
    let start = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    for method in [Method::Dopri5, Method::Bdf] {
        let options = SolveOptions {
            t_end: 2.0,
            rtol: 1e-9,
            atol: 1e-11,
            output_dt: Some(0.5),
            ..Default::default()
        };
        let traj = solve(&chain, &start, method, &options).unwrap();
        assert!(traj.status.is_ok(), "{method:?}: {}", traj.status);
        let (e0, e1) = (traj.energy(0), traj.energy(traj.len() - 1));
        // The tip mass's share of the energy is large: a run that ignored it
        // in the dynamics or in the energy would drift by O(1).
        assert!(
            (e1 - e0).abs() < 1e-5 * chain.energy_scale(),
            "{method:?}: {e0} -> {e1}"
        );
        // The observer's balance too (its own one-pass energy).
        let err = traj.summary.energy_balance_error;
        assert!(err < 1e-5 * chain.energy_scale(), "{method:?}: {err:e}");
    }
}

#[test]
fn one_rod_with_a_tip_mass_is_a_physical_pendulum() {
    // I phi'' = -(m/2 + M) g l cos phi, I = m l^2 / 3 + M l^2: the
    // small-oscillation frequency about the hanging state is
    // omega^2 = g (m/2 + M) / (l (m/3 + M)).
    for tip in [0.0, 0.25, 3.0] {
        let chain = Chain::new(ChainParams {
            length: 1.7,
            links: 1,
            mass: 0.8,
            gravity: 9.81,
            tip_mass: tip,
            ..ChainParams::default()
        })
        .unwrap();
        let omega2 = 9.81 * (0.4 + tip) / (1.7 * (0.8 / 3.0 + tip));
        for phi in [-1.5, -0.3, 0.9] {
            let mut acc = [0.0];
            accelerations(&chain, &[phi], &[0.7], &mut acc, &mut Workspace::new(1));
            let expect = -omega2 * f64::cos(phi);
            assert!(
                (acc[0] - expect).abs() < 1e-13 * omega2,
                "M = {tip}: {} vs {expect}",
                acc[0]
            );
        }
        // And a run oscillates at that frequency: the period of a small
        // swing about phi = -pi/2 from the first two upward crossings.
        let amp = 1e-3;
        let start = Start::Angles {
            p0: [0.0, 0.0],
            angles: vec![-std::f64::consts::FRAC_PI_2 + amp],
            rates: None,
        }
        .state(&chain)
        .unwrap();
        let period = 2.0 * std::f64::consts::PI / omega2.sqrt();
        let options = SolveOptions {
            t_end: 2.2 * period,
            rtol: 1e-11,
            atol: 1e-13,
            output_dt: Some(period / 2000.0),
            ..Default::default()
        };
        let traj = solve(&chain, &start, Method::Dopri5, &options).unwrap();
        assert!(traj.status.is_ok());
        // Maxima of phi: a swing of amplitude 1e-3 has its period within
        // amp^2/16 of the small-oscillation one.
        let phis: Vec<f64> = (0..traj.len()).map(|k| traj.state(k)[0]).collect();
        let crossings: Vec<f64> = (1..phis.len())
            .filter(|&k| {
                let c = -std::f64::consts::FRAC_PI_2;
                phis[k - 1] < c && phis[k] >= c
            })
            .map(|k| {
                let c = -std::f64::consts::FRAC_PI_2;
                let (t0, t1) = (traj.times[k - 1], traj.times[k]);
                t0 + (t1 - t0) * (c - phis[k - 1]) / (phis[k] - phis[k - 1])
            })
            .collect();
        assert!(
            crossings.len() >= 2,
            "M = {tip}: {} crossings",
            crossings.len()
        );
        let measured = crossings[1] - crossings[0];
        assert!(
            (measured / period - 1.0).abs() < 1e-5,
            "M = {tip}: period {measured} vs {period}"
        );
    }
}

/// The folded chain with a tip mass `M`, energy-conserving (derived here).
/// The law's fall time, `chain_ode::tip_mass_law::time` (derived in
/// `docs/model.md`, "A tip mass").
fn tip_law_time(k: f64, xi: f64) -> f64 {
    chain_ode::tip_mass_law::time(xi, k)
}

#[test]
fn the_tip_law_reproduces_the_issues_table_and_its_limits() {
    // Fall time over the free-fall time sqrt(2 L / g), issue 18's table.
    for (k, stated) in [
        (0.1, 0.893),
        (0.5, 0.948),
        (1.0, 0.968),
        (2.0, 0.982),
        (10.0, 0.996),
    ] {
        let ratio = tip_law_time(k, 1.0) / 2f64.sqrt();
        assert!(
            (ratio - stated).abs() < 6e-4,
            "k = {k}: {ratio} vs {stated}"
        );
    }
    // A heavy tip is free fall.
    assert!((tip_law_time(1e9, 1.0) / 2f64.sqrt() - 1.0).abs() < 1e-6);
}

#[test]
fn folded_chain_with_a_tip_mass_falls_as_the_law_says_at_n_400() {
    let n = 400;
    for k in [0.5, 1.0] {
        let chain = Chain::new(ChainParams {
            links: n,
            mass: 10.0 / n as f64,
            tip_mass: 10.0 * k,
            ..ChainParams::default()
        })
        .unwrap();
        let start = Start::Folded {
            p0: [0.0, 0.0],
            down: None,
        }
        .state(&chain)
        .unwrap();
        let (length, g) = (chain.length(), chain.gravity());
        let tau = (length / g).sqrt();
        // The free end starts one rod below the pivot and can fall L - l:
        // the fall time is the law's at x = L - l (see validation.rs).
        let x_end = length - chain.rod_length();
        let options = SolveOptions {
            t_end: tip_law_time(k, 1.0) * tau * 1.01,
            rtol: 1e-9,
            atol: 1e-11,
            output_dt: Some(1e-3),
            ..Default::default()
        };
        let traj = solve(&chain, &start, Method::Dopri5, &options).unwrap();
        assert!(traj.status.is_ok(), "k = {k}: {}", traj.status);
        let track = tip_track(&traj);
        let y_start = track[0].1[1];
        // The fall time: the tip within 0.1% of full extension (the discrete
        // chain never straightens exactly; measured at n = 400: +0.12% at
        // M/m_c = 0.5 and +0.05% at 1, earlier crossings closer still).
        for xi in [0.5, 0.9, 0.999] {
            let x = xi * x_end;
            let law = tip_law_time(k, x / length) * tau;
            let t = first_time_below(&track, y_start - x)
                .unwrap_or_else(|| panic!("k = {k}: the tip never fell {x}"));
            let rel = t / law - 1.0;
            assert!(
                rel.abs() < 2e-3,
                "k = {k}, xi = {xi}: t = {t} vs the law's {law} ({:+.3}%)",
                100.0 * rel
            );
        }
    }
}
