//! One right-hand-side evaluation of equal rods against rods of unequal
//! mass and length (`chain.taper`, `chain.rod_lengths`), same shape and
//! motion: the cost of the per-rod terms; and both with a tip mass and
//! bending springs.
//! `cargo bench -p chain-ode --bench rhs_profile`.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]

use chain_ode::{Chain, ChainParams, ChainSystem, Profile, Start};
use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};

/// The report's chain of `n` rods with `profile` (and, `with_terms`, a tip
/// mass `M_t = n m / 10` and bending `EI = 0.01`), on the catenary of span
/// 3, with some motion so that every term is exercised.
fn state(n: usize, profile: Profile, with_terms: bool) -> (Chain, Vec<f64>) {
    let chain = Chain::new(ChainParams {
        links: n,
        damping: 5e-4,
        tip_mass: if with_terms { 0.02 * n as f64 } else { 0.0 },
        bending_stiffness: if with_terms { 0.01 } else { 0.0 },
        profile,
        ..ChainParams::default()
    })
    .unwrap();
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    let rates: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    (chain, ChainSystem::pack(&s.angles, &rates, 0.0))
}

fn rhs_profile(c: &mut Criterion) {
    let mut group = c.benchmark_group("rhs_profile");
    for n in [50usize, 2000] {
        let lengths = || Some((0..n).map(|i| 2.0 - i as f64 / n as f64).collect());
        let profiles = [
            ("uniform", Profile::default(), false),
            (
                "taper",
                Profile {
                    taper: 10.0,
                    ..Profile::default()
                },
                false,
            ),
            (
                "taper+lengths",
                Profile {
                    taper: 10.0,
                    lengths: lengths(),
                    ..Profile::default()
                },
                false,
            ),
            ("uniform+tip+bending", Profile::default(), true),
            (
                "taper+lengths+tip+bending",
                Profile {
                    taper: 10.0,
                    lengths: lengths(),
                    ..Profile::default()
                },
                true,
            ),
        ];
        for (name, profile, with_terms) in profiles {
            let (chain, y) = state(n, profile, with_terms);
            let mut sys = ChainSystem::new(&chain);
            let mut dy = vec![0.0; y.len()];
            group.bench_with_input(BenchmarkId::new(name, n), &n, |b, _| {
                b.iter(|| sys.rhs(0.0, black_box(&y), black_box(&mut dy)))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, rhs_profile);
criterion_main!(benches);
