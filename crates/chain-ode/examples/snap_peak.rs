//! The tip speed near the snap's peak from DOP853 at rtol 1e-10, sampled
//! finely: the peak's curvature (what sampling the peak at step ends
//! costs a method whose dense output is linear).
//!
//! `cargo run --release -p chain-ode --example snap_peak -- N EA`
#![allow(clippy::unwrap_used, reason = "a developer's tool")]
use chain_ode::{solve, Chain, ChainParams, Method, SolveOptions, Start};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = a[0].parse().unwrap();
    let ea: f64 = a[1].parse().unwrap();
    let (len, m) = (6.0, 4.0 / n as f64);
    let l = len / n as f64;
    let chain = Chain::new(ChainParams {
        length: len,
        links: n,
        mass: m,
        damping: 0.001,
        axial_stiffness: Some(ea),
        axial_damping: 2.0 * 0.05 * (ea * m * l).sqrt(),
        ..ChainParams::default()
    })
    .unwrap();
    let start = Start::Folded {
        p0: [0.0, 0.0],
        down: Some(n / 2),
    }
    .state(&chain)
    .unwrap();
    let (t_from, t_to): (f64, f64) = (
        a.get(2).map_or(2.8795, |s| s.parse().unwrap()),
        a.get(3).map_or(2.8815, |s| s.parse().unwrap()),
    );
    let o = SolveOptions {
        t_end: t_to,
        rtol: 1e-10,
        atol: 1e-12,
        output_dt: Some(5e-5),
        ..Default::default()
    };
    let tr = solve(&chain, &start, Method::Dop853, &o).unwrap();
    for k in 0..tr.len() {
        let t = tr.times[k];
        if t > t_from {
            let v = tr.tip_velocity(k);
            let p = tr.tip(k);
            println!("{t:.5} {:.8} {:.10} {:.10}", v[0].hypot(v[1]), p[0], p[1]);
        }
    }
    println!(
        "max {:.8} at {:.6}",
        tr.summary.tip_speed_max, tr.summary.t_tip_speed_max
    );
}
