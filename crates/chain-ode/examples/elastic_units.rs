//! The elastic chain's units of implicit work at the folded start, in
//! right-hand sides: a Jacobian (`jacobian_values`), an LU of its Newton
//! matrix (block tridiagonal), a solve; the fastest of a few batches.
//!
//! `cargo run --release -p chain-ode --example elastic_units -- N [EA]`

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument stops it with the message"
)]
use std::hint::black_box;
use std::rc::Rc;
use std::time::Instant;

use chain_ode::elastic::{start_state, ElasticDae};
use chain_ode::{Chain, ChainParams, Start};
use diffsol::{FaerVec, Vector};
use diffsol_la::LinearSolver;
use fc_methods::{BlockLu, LuLog, NewtonMatrix, SemiExplicitDae};

fn per_call(mut f: impl FnMut()) -> f64 {
    let mut calls = 1;
    loop {
        let t = Instant::now();
        for _ in 0..calls {
            f();
        }
        if t.elapsed().as_secs_f64() >= 5e-3 || calls >= 1 << 20 {
            break;
        }
        calls *= 2;
    }
    (0..7)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..calls {
                f();
            }
            t.elapsed().as_secs_f64() / calls as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = a[0].parse().unwrap();
    let ea: f64 = a.get(1).map_or(1e8, |s| s.parse().unwrap());
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
    let state = Start::Folded {
        p0: [0.0, 0.0],
        down: Some(n / 2),
    }
    .state(&chain)
    .unwrap();
    let y = start_state(&chain, &state);
    let dae = ElasticDae::new(&chain);
    let mut out = vec![0.0; y.len()];
    let rhs = per_call(|| dae.rhs(black_box(&y), &mut out));
    let mut count = 0;
    dae.jacobian_entries(&y, &mut |_, _, _| count += 1);
    let mut vals = vec![0.0; count];
    let jac = per_call(|| SemiExplicitDae::jacobian_values(&dae, 0.0, black_box(&y), &mut vals));
    let mut sink = 0.0;
    let jac_dyn = per_call(|| dae.jacobian_entries(black_box(&y), &mut |_, _, v| sink += v));
    black_box(sink);
    let newton = NewtonMatrix::of(&dae, 0.0, &y, 1e-3).unwrap();
    let log = Rc::new(LuLog::default());
    let mut lu = BlockLu::new(SemiExplicitDae::blocks(&dae).unwrap(), log.clone());
    lu.set_sparsity(&newton);
    let lu_t = per_call(|| lu.set_linearisation(black_box(&newton)));
    let mut x = FaerVec::from_vec(out.clone(), newton.ctx);
    let solve = per_call(|| {
        let _ = lu.solve_in_place(black_box(&mut x));
    });
    println!(
        "n {n}: rhs {:.3e} s; in rhs: jacobian {:.2} (through the callback {:.2}), lu {:.2}, solve {:.2}",
        rhs,
        jac / rhs,
        jac_dyn / rhs,
        lu_t / rhs,
        solve / rhs
    );
}
