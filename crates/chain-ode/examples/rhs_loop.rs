//! Calls the RHS in a loop, for profilers: `rhs_loop N CALLS`.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]
use chain_ode::{Chain, ChainSystem, Start};
fn main() {
    let a: Vec<usize> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    let (n, calls) = (a[0], a[1]);
    let chain = Chain::report(n, 5e-4).unwrap();
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    let rates: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    let mut y = ChainSystem::pack(&s.angles, &rates, 0.0);
    let mut sys = ChainSystem::new(&chain);
    let mut dy = vec![0.0; y.len()];
    let t = std::time::Instant::now();
    for k in 0..calls {
        y[0] += 1e-12 * (k & 1) as f64;
        sys.rhs(0.0, std::hint::black_box(&y), &mut dy);
    }
    let el = t.elapsed().as_secs_f64();
    println!(
        "n {n}: {:.3} us per call, {:.2} ns per rod ({})",
        el / calls as f64 * 1e6,
        el / calls as f64 / n as f64 * 1e9,
        dy[n]
    );
}
