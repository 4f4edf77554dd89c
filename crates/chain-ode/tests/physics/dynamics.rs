//! The O(n) dynamics against the dense reference and the conservation laws.

use chain_ode::dense;
use chain_ode::dynamics::{accelerations, Workspace};
use chain_ode::kinematics::{dissipation_rate, energy, joints};
use chain_ode::{Chain, ChainSystem};
use proptest::prelude::*;

use crate::{chain_and_state, max_abs};

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// In angle coordinates every rod has length `l` by construction: no
    /// run can change it. The one place it could still go wrong is
    /// `joints`, which every figure, CSV and animation draws from; this is
    /// the crate's one test of it (the design's "constant rod length").
    #[test]
    fn rod_length_is_exact_by_construction((chain, phi, _w) in chain_and_state(300)) {
        let r = joints(&chain, [0.3, -1.2], &phi);
        prop_assert_eq!(r.len(), chain.links() + 1);
        prop_assert_eq!(r[0], [0.3, -1.2]);
        // Every rod as long as the others, and together as long as the
        // chain (which a wrong `rod_length` shared by both sides would not
        // be), each pointing along its angle from the horizontal.
        // A profiled chain's rods measure lambda_i l (lambda summing to n).
        let l0 = chain.length() / chain.links() as f64;
        let lam = |i: usize| chain.rods().map_or(1.0, |r| r.length[i]);
        let total: f64 = (0..chain.links()).map(lam).sum::<f64>() * l0;
        prop_assert!((total - chain.length()).abs() <= 1e-12 * chain.length());
        for (i, (p, angle)) in r.windows(2).zip(&phi).enumerate() {
            let l = lam(i) * l0;
            let (dx, dy) = (p[1][0] - p[0][0], p[1][1] - p[0][1]);
            prop_assert!((dx.hypot(dy) - l).abs() <= 1e-12 * chain.length());
            prop_assert!((dx - l * angle.cos()).abs() <= 1e-12 * chain.length());
            prop_assert!((dy - l * angle.sin()).abs() <= 1e-12 * chain.length());
        }
    }

    #[test]
    fn fast_solve_equals_dense_cholesky((chain, phi, w) in chain_and_state(300)) {
        let n = chain.links();
        let mut acc = vec![0.0; n];
        let mut ws = Workspace::new(n);
        accelerations(&chain, &phi, &w, &mut acc, &mut ws);
        let reference = dense::accelerations(&chain, &phi, &w);
        let scale = max_abs(&reference).max(1e-300);
        for i in 0..n {
            prop_assert!((acc[i] - reference[i]).abs() <= 1e-10 * scale,
                "rod {}: {} vs {} (scale {})", i, acc[i], reference[i], scale);
        }
    }

    #[test]
    fn kinetic_energy_equals_quadratic_form((chain, phi, w) in chain_and_state(300)) {
        let fast = chain_ode::kinematics::kinetic_energy(&chain, &phi, &w);
        let dense = dense::kinetic_energy(&chain, &phi, &w);
        prop_assert!((fast - dense).abs() <= 1e-11 * dense.abs().max(1e-300));
    }

    #[test]
    fn energy_rate_is_minus_twice_rayleigh((chain, phi, w) in chain_and_state(300)) {
        // dE/dt along the exact flow, by a fourth-order central difference
        // in the flow direction. The step moves the state by at most 1e-3
        // (angles in rad, rates in rad/time): truncation ~ 1e-12 of the
        // energy, rounding ~ 1e-13 of it per unit |f|. (A second-order
        // difference moving the state by only 1e-6 was rounding-limited and
        // failed now and then on stiff random chains, gamma ~ 1e6.)
        let n = chain.links();
        let mut sys = ChainSystem::new(&chain);
        let y = ChainSystem::pack(&phi, &w, 0.0);
        let mut f = vec![0.0; y.len()];
        sys.rhs(0.0, &y, &mut f);
        let eps = 1e-3 / (1.0 + max_abs(&f[..2 * n]));
        let at = |s: f64| {
            let z: Vec<f64> = y.iter().zip(&f).map(|(a, b)| a + s * b).collect();
            energy(&chain, &z[..n], &z[n..2 * n])
        };
        let de_dt =
            (8.0 * (at(eps) - at(-eps)) - (at(2.0 * eps) - at(-2.0 * eps))) / (12.0 * eps);
        let two_r = dissipation_rate(&chain, &w);
        // Scale of the individual power terms.
        let l = chain.rod_length();
        let power: f64 = (0..n).map(|i| {
            chain.mass() * l * l * w[i].abs() * (f[n + i].abs() + w[i] * w[i]) * n as f64
                + chain.weight() * l * w[i].abs()
        }).sum::<f64>() + two_r
            // The bending springs' power, (EI / l) sum |dphi| |dw|.
            + chain.bending_stiffness() / l
                * (1..n).map(|i| (phi[i] - phi[i - 1]).abs() * (w[i] - w[i - 1]).abs()).sum::<f64>();
        // The difference quotient's rounding, `~ 2 eps |E| / eps_step` (the
        // stiff bending springs of short rods make |f| large and the step
        // small), allowed 30 times over.
        let magnitude = (chain_ode::kinematics::kinetic_energy(&chain, &phi, &w)
            + chain_ode::kinematics::potential_energy(&chain, &phi).abs()
            + chain_ode::kinematics::bending_energy(&chain, &phi)) * 1e-14 / eps;
        prop_assert!((de_dt + two_r).abs() <= 1e-6 * power.max(1e-300) + magnitude,
            "dE/dt {} vs -2R {} (power scale {})", de_dt, -two_r, power);
    }

    #[test]
    fn jacobian_vector_product_matches_central_difference(
        (chain, phi, w) in chain_and_state(300),
        seed in prop::collection::vec(-1.0f64..1.0, 601)
    ) {
        let n = chain.links();
        let mut sys = ChainSystem::new(&chain);
        let y = ChainSystem::pack(&phi, &w, 0.7);
        let v: Vec<f64> = seed[..2 * n + 1].to_vec();
        let mut jv = vec![0.0; y.len()];
        sys.jvp(0.0, &y, &v, &mut jv);
        let eps = 1e-6;
        let shifted = |s: f64, sys: &mut ChainSystem| {
            let z: Vec<f64> = y.iter().zip(&v).map(|(a, b)| a + s * b).collect();
            let mut f = vec![0.0; z.len()];
            sys.rhs(0.0, &z, &mut f);
            f
        };
        let fp = shifted(eps, &mut sys);
        let fm = shifted(-eps, &mut sys);
        let scale = max_abs(&jv).max(max_abs(&fp)).max(1e-300);
        for i in 0..y.len() {
            let fd = (fp[i] - fm[i]) / (2.0 * eps);
            prop_assert!((fd - jv[i]).abs() <= 1e-5 * scale, "entry {}: {} vs {}", i, jv[i], fd);
        }
    }
}

#[test]
fn hanging_rest_state_stays_put_and_pivot_carries_the_weight() {
    let chain = Chain::report(30, 1e-3).unwrap();
    let mut sys = ChainSystem::new(&chain);
    let y = ChainSystem::pack(&[-std::f64::consts::FRAC_PI_2; 30], &[0.0; 30], 0.0);
    let mut f = vec![1.0; y.len()];
    let r = sys.rhs_with_reactions(&y, &mut f);
    assert!(max_abs(&f) < 1e-12);
    assert!((r.pivot_force[1] - chain.weight()).abs() < 1e-12 * chain.weight());
}
