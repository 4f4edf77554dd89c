//! One right-hand-side evaluation vs n: the O(n) recursion, the elastic
//! chain's springs (`chain.axial_stiffness`) and the dense Cholesky
//! reference side by side. `cargo bench -p chain-ode --bench rhs`.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]

use chain_ode::dense;
use chain_ode::elastic;
use chain_ode::{Chain, ChainParams, ChainSystem, ElasticSystem, Start, State};
use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};

fn state(n: usize) -> (Chain, Vec<f64>) {
    let chain = Chain::report(n, 5e-4).unwrap();
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    // Give it some motion so that every term is exercised.
    let rates: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    (chain, ChainSystem::pack(&s.angles, &rates, 0.0))
}

fn rhs(c: &mut Criterion) {
    let mut group = c.benchmark_group("rhs");
    for n in [25usize, 50, 100, 200, 400, 1000, 2000, 5000, 10_000] {
        let (chain, y) = state(n);
        let mut sys = ChainSystem::new(&chain);
        let mut dy = vec![0.0; y.len()];
        group.bench_with_input(BenchmarkId::new("fast", n), &n, |b, _| {
            b.iter(|| sys.rhs(0.0, black_box(&y), black_box(&mut dy)))
        });
        // The elastic chain in the same shape and motion (EA = 1e4).
        let elastic_chain = Chain::new(ChainParams {
            axial_stiffness: Some(1e4),
            ..chain.params().clone()
        })
        .unwrap();
        let start = State {
            anchor: [0.0, 0.0],
            angles: y[..n].to_vec(),
            rates: y[n..2 * n].to_vec(),
        };
        let ye = elastic::start_state(&elastic_chain, &start);
        let mut esys = ElasticSystem::new(&elastic_chain);
        let mut dye = vec![0.0; ye.len()];
        group.bench_with_input(BenchmarkId::new("elastic", n), &n, |b, _| {
            b.iter(|| esys.rhs(0.0, black_box(&ye), black_box(&mut dye)))
        });
        if n <= 1000 {
            let (phi, w) = (&y[..n], &y[n..2 * n]);
            group.bench_with_input(BenchmarkId::new("dense", n), &n, |b, _| {
                b.iter(|| dense::accelerations(&chain, black_box(phi), black_box(w)))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, rhs);
criterion_main!(benches);
