//! The derivatives the sparse BDF's observer reads after an accepted step
//! (`ChainDae::derivatives_at`, the chain's
//! `SemiExplicitDae::derivatives`, computed without the rods'
//! residuals): bit for bit the first `2n + 1` entries of the full
//! right-hand side, and what the model says they are (`phi' = w`,
//! `w' = alpha`, `W' = r sum (w_i - w_{i-1})^2` less a driven pivot's power
//! `m l F_0 . v_0`), for any chain, with a driven and with a free pivot.

use chain_ode::dae::ChainDae;
use chain_ode::{Chain, ChainParams, Pivot};
use proptest::prelude::*;

use crate::chain_and_state;

/// Checks `dae` at `(t, y)`; `power` is the driven pivot's `F_0 . v_0` in
/// rod units (0 for a fixed or free pivot).
fn check(chain: &Chain, dae: &ChainDae, t: f64, y: &[f64], power: f64) {
    let n = chain.links();
    let (d, dim) = (dae.differential_dim(), dae.dim());
    let mut full = vec![0.0; dim];
    dae.rhs_at(t, y, &mut full);
    // `out` starts as NaN, so that a derivative not written shows.
    let mut part = vec![f64::NAN; dim];
    dae.derivatives_at(t, y, &mut part);
    for k in 0..d {
        assert_eq!(
            part[k].to_bits(),
            full[k].to_bits(),
            "n = {n}, entry {k}: {} against {}",
            part[k],
            full[k]
        );
    }
    // The model's derivatives, summed independently.
    let w = &y[n..2 * n];
    for i in 0..n {
        assert_eq!(part[i], w[i]);
        assert_eq!(part[n + i], y[d + i]);
    }
    let mut two_r: f64 = 0.0;
    for i in 1..n {
        two_r += (w[i] - w[i - 1]).powi(2);
    }
    let want = chain.damping() * two_r - chain.mass() * chain.rod_length() * power;
    let scale = 1.0 + want.abs();
    assert!(
        (part[2 * n] - want).abs() < 1e-13 * scale,
        "n = {n}: W' = {} against {want}",
        part[2 * n]
    );
}

/// A state of `dae` with every unknown set (the algebraic ones need not be
/// consistent): angles and rates from `phi`, `w`, the rest from a sine.
fn state(dae: &ChainDae, phi: &[f64], w: &[f64]) -> Vec<f64> {
    let n = phi.len();
    (0..dae.dim())
        .map(|u| match u {
            _ if u < n => phi[u],
            _ if u < 2 * n => w[u - n],
            _ => (0.37 * u as f64).sin() * 3.0,
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Any chain (profiles, bending, friction) with a fixed pivot.
    #[test]
    fn the_observed_derivatives_are_the_right_hand_sides((chain, phi, w) in chain_and_state(40)) {
        let dae = ChainDae::new(&chain);
        let y = state(&dae, &phi, &w);
        check(&chain, &dae, 0.0, &y, 0.0);
    }
}

#[test]
fn the_observed_derivatives_hold_with_a_driven_or_a_free_pivot() {
    let driven = Pivot {
        acceleration: [0.2, -0.3],
        amplitude: [0.05, 0.1],
        frequency: 3.0,
        jerk: [0.4, 0.0],
        jerk_time: 0.7,
        release: None,
    };
    let free = Pivot {
        release: Some(0.0),
        ..Pivot::default()
    };
    for (n, tip, pivot, released) in [
        (1, 0.0, driven, false),
        (7, 0.4, driven, false),
        (1, 0.7, free, true),
        (6, 0.0, free, true),
    ] {
        let chain = Chain::new(ChainParams {
            links: n,
            length: 3.0,
            mass: 0.6 / n as f64,
            gravity: 1.3,
            damping: 0.02,
            tip_mass: tip,
            pivot,
            ..ChainParams::default()
        })
        .unwrap();
        let dae = ChainDae::new(&chain).released(released);
        let phi: Vec<f64> = (0..n).map(|i| (1.7 * i as f64 + 0.4).sin() * 2.0).collect();
        let w: Vec<f64> = (0..n).map(|i| (0.9 * i as f64 + 0.8).cos() * 1.5).collect();
        let y = state(&dae, &phi, &w);
        let t = 0.37;
        let power = if released {
            0.0
        } else {
            let f0 = dae.pivot_force(&y);
            let v0 = pivot.drive(t)[1];
            f0[0] * v0[0] + f0[1] * v0[1]
        };
        check(&chain, &dae, t, &y, power);
    }
}
