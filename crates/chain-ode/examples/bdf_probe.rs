//! BDF against RK4 (and DOPRI5) on the span-d3 catenary start: median wall
//! time of `RUNS` runs, work counters, and the tip error against a tight
//! reference run.
//!
//! `cargo run --release -p chain-ode --example bdf_probe -- N R T_END RTOL DT1[,DT2..] [RUNS]`
//!
//! Setting `BDF_PROBE_SPARSE_LU=1` runs `bdf` on the general sparse LU
//! (faer, COLAMD) instead of the block-tridiagonal one, for the old-new
//! ratio.
//! (atol = rtol / 100; the reference is BDF at rtol 1e-12, atol 1e-14.)

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]
use chain_ode::{solve, with_general_sparse_lu, Chain, Method, SolveOptions, Start, Trajectory};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = a[0].parse().unwrap();
    let r: f64 = a[1].parse().unwrap();
    let t_end: f64 = a[2].parse().unwrap();
    let rtol: f64 = a[3].parse().unwrap();
    let dts: Vec<f64> = a[4].split(',').map(|s| s.parse().unwrap()).collect();
    let runs: usize = a.get(5).map_or(5, |s| s.parse().unwrap());
    let chain = Chain::report(n, r).unwrap();
    let start = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    };
    let s = start.state(&chain).unwrap();
    let base = SolveOptions {
        t_end,
        rtol,
        atol: rtol * 1e-2,
        ..Default::default()
    };
    let reference = solve(
        &chain,
        &s,
        Method::Bdf,
        &SolveOptions {
            rtol: 1e-12,
            atol: 1e-14,
            ..base.clone()
        },
    )
    .unwrap();
    println!(
        "n {n} r {r} t_end {t_end} gamma {:.3} reference: {} steps {}",
        chain.damping_rate(),
        reference.status,
        reference.stats.steps
    );
    let timed = |m: Method, o: &SolveOptions| -> (Trajectory, f64) {
        let mut walls = Vec::new();
        let mut last = None;
        for _ in 0..runs {
            let tr = if std::env::var_os("BDF_PROBE_SPARSE_LU").is_some() {
                with_general_sparse_lu(|| solve(&chain, &s, m, o))
            } else {
                solve(&chain, &s, m, o)
            }
            .unwrap();
            walls.push(tr.summary.wall_seconds);
            last = Some(tr);
        }
        walls.sort_by(f64::total_cmp);
        (last.unwrap(), walls[runs / 2])
    };
    let mut cases = vec![
        (Method::Bdf, base.clone(), format!("rtol {rtol:.0e}")),
        (Method::Dopri5, base.clone(), format!("rtol {rtol:.0e}")),
    ];
    for &dt in &dts {
        cases.push((
            Method::Rk4,
            SolveOptions { dt, ..base.clone() },
            format!("dt {dt:e}"),
        ));
    }
    for (m, o, label) in cases {
        let (tr, wall) = timed(m, &o);
        let tip_err = if tr.status.is_ok() {
            let (p, q) = (tr.summary.tip_end, reference.summary.tip_end);
            (p[0] - q[0]).hypot(p[1] - q[1])
        } else {
            f64::NAN
        };
        println!(
            "{m:6} {label:10} {:18} wall_med {:9.3e} s  steps {:7} rej {:5} rhs {:8} jac {:5} lu {:5}  tip_err {:8.1e}  bal {:8.1e}",
            tr.status.as_str(),
            wall,
            tr.stats.steps,
            tr.stats.rejected_steps,
            tr.stats.rhs_evals,
            tr.stats.jacobian_evals,
            tr.stats.lu_factorizations,
            tip_err,
            tr.summary.energy_balance_error,
        );
    }
}
