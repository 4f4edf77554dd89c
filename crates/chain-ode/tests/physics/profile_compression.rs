//! The catenary start of unequal rods with one rod in compression (the
//! free end held within that rod's length of a folded chain's end): an
//! exact equilibrium, checked as the tension case is
//! (`profile::the_catenary_start_of_a_tapered_chain_is_an_exact_equilibrium`):
//! the potential's gradient by central differences is the generalised force
//! of one end force `F` on every rod.

use chain_ode::kinematics::{joints, potential_energy};
use chain_ode::{Chain, ChainParams, Profile, Start};

#[test]
fn a_catenary_start_with_a_rod_in_compression_is_an_exact_equilibrium() {
    // Rod lengths 0.6, 1.2, 0.6, 1.8, 0.6, 1.2 (L = 6): with rods 0..2
    // down and 4..5 up, the long rod 3 reaches from (0, -2.4 + 1.8) within
    // 1.8 of (0, -0.6); P1 = (0.5, -0.3) is 0.58 from it.
    for masses in [None, Some(vec![3.0, 1.0, 2.0, 1.0, 0.5, 2.0])] {
        let n = 6;
        let chain = Chain::new(ChainParams {
            length: 6.0,
            links: n,
            profile: Profile {
                lengths: Some(vec![1.0, 2.0, 1.0, 3.0, 1.0, 2.0]),
                masses,
                ..Profile::default()
            },
            ..ChainParams::default()
        })
        .unwrap();
        let (p0, p1) = ([0.0, 0.0], [0.5, -0.3]);
        let state = Start::Catenary { p0, p1 }.state(&chain).unwrap();
        let phi = &state.angles;
        let r = joints(&chain, p0, phi);
        assert!((r[n][0] - p1[0]).hypot(r[n][1] - p1[1]) < 1e-11, "{r:?}");
        let h = 1e-6;
        let grad: Vec<f64> = (0..n)
            .map(|i| {
                let (mut a, mut b) = (phi.clone(), phi.clone());
                a[i] += h;
                b[i] -= h;
                (potential_energy(&chain, &a) - potential_energy(&chain, &b)) / (2.0 * h)
            })
            .collect();
        let lever = |i: usize| {
            let d = [r[i + 1][0] - r[i][0], r[i + 1][1] - r[i][1]];
            [-d[1], d[0]]
        };
        // F from two rods that are not parallel (rods 0 and 3), then every rod.
        let (a, b) = (lever(0), lever(3));
        let det = a[0] * b[1] - a[1] * b[0];
        assert!(det.abs() > 1e-3, "rods 0 and 3 parallel");
        let f = [
            (grad[0] * b[1] - grad[3] * a[1]) / det,
            (a[0] * grad[3] - b[0] * grad[0]) / det,
        ];
        let scale = chain.weight() * chain.length();
        for (i, g) in grad.iter().enumerate() {
            let l = lever(i);
            let res = g - (f[0] * l[0] + f[1] * l[1]);
            assert!(res.abs() < 1e-8 * scale, "rod {i}: {res:e}");
        }
        // Rod 3 in compression: the hand at P1 pushes the chain towards
        // the pivot (F_x < 0, where a chain in tension is pulled away), the
        // long rod leans within 90 degrees of +x and the rods before it
        // hang below one another.
        assert!(f[0] < 0.0, "F = {f:?}");
        assert!(phi[3].cos() > 0.0 && (0..3).all(|i| r[i + 1][1] < r[i][1]));
    }
}
