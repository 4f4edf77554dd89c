//! `bdf`'s wall time per step with the block-tridiagonal LU and with the
//! general sparse LU (faer, COLAMD) in the same run, on the stiffness
//! study's cell: the span d = 3 catenary start of the report chain, `r` set
//! from the damping rate `gamma = r / (m l^2)`, `t_end = 1`, rtol 1e-6,
//! atol 1e-8. Runs alternate between the two solvers; the median of `RUNS`
//! is printed with the work counters and the tip difference between them.
//!
//! `cargo run --release -p chain-ode --example bdf_per_step -- GAMMA N1[,N2..] [RUNS] [block|sparse]`
//!
//! With `block` or `sparse` only that solver runs (for `perf stat`, whose
//! cycle counts a loaded machine disturbs less than wall times).

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]
use chain_ode::{solve, with_general_sparse_lu, Chain, Method, SolveOptions, Start, Trajectory};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let gamma: f64 = a[0].parse().unwrap();
    let ns: Vec<usize> = a[1].split(',').map(|s| s.parse().unwrap()).collect();
    let runs: usize = a.get(2).map_or(5, |s| s.parse().unwrap());
    let only = a.get(3).map(String::as_str);
    for n in ns {
        let base = Chain::report(n, 0.0).unwrap();
        let r = gamma * base.mass() * base.rod_length().powi(2);
        let chain = Chain::report(n, r).unwrap();
        let s = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [3.0, 0.0],
        }
        .state(&chain)
        .unwrap();
        let o = SolveOptions {
            t_end: 1.0,
            rtol: 1e-6,
            atol: 1e-8,
            ..Default::default()
        };
        let run = || solve(&chain, &s, Method::Bdf, &o).unwrap();
        if let Some(which) = only {
            for _ in 0..runs {
                let t = match which {
                    "block" => run(),
                    "sparse" => with_general_sparse_lu(run),
                    _ => panic!("block or sparse, not {which}"),
                };
                let st = &t.stats;
                println!(
                    "n {n} {which}: {} steps {} per step {:.3e} s | rejected {} newton {} rhs {} \
                     jacobians {} lu {}",
                    t.status,
                    st.steps,
                    t.summary.wall_seconds / st.steps as f64,
                    st.rejected_steps,
                    st.newton_iterations,
                    st.rhs_evals,
                    st.jacobian_evals,
                    st.lu_factorizations,
                );
            }
            continue;
        }
        let (mut block, mut sparse) = (Vec::new(), Vec::new());
        let (mut last_b, mut last_s): (Option<Trajectory>, Option<Trajectory>) = (None, None);
        for _ in 0..runs {
            let tb = run();
            block.push(tb.summary.wall_seconds / tb.stats.steps as f64);
            last_b = Some(tb);
            let ts = with_general_sparse_lu(run);
            sparse.push(ts.summary.wall_seconds / ts.stats.steps as f64);
            last_s = Some(ts);
        }
        block.sort_by(f64::total_cmp);
        sparse.sort_by(f64::total_cmp);
        let (tb, ts) = (last_b.unwrap(), last_s.unwrap());
        let (p, q) = (tb.summary.tip_end, ts.summary.tip_end);
        println!(
            "n {n} gamma {:.3e} | block: {} steps {} rej {} lu {} per step {:.3e} s | \
             sparse: {} steps {} rej {} lu {} per step {:.3e} s | sparse/block {:.2} | tip diff {:.2e}",
            chain.damping_rate(),
            tb.status,
            tb.stats.steps,
            tb.stats.rejected_steps,
            tb.stats.lu_factorizations,
            block[runs / 2],
            ts.status,
            ts.stats.steps,
            ts.stats.rejected_steps,
            ts.stats.lu_factorizations,
            sparse[runs / 2],
            sparse[runs / 2] / block[runs / 2],
            (p[0] - q[0]).hypot(p[1] - q[1]),
        );
    }
}
