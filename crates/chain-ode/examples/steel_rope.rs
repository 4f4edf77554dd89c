//! Issue 49's steel rope: `scenes/span-d3.toml` with `EA = 1e8` and 5%
//! axial damping of one joint's mode, to `t = 3.2` past the snap: a
//! method's peak pivot force (`Summary::pivot_force_max`) and its work,
//! over a ladder of tolerances.
//!
//! `cargo run --release -p chain-ode --example steel_rope -- METHOD RTOL[,RTOL..] [EA] [RHO_INF]`
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    reason = "a developer's tool: a bad argument stops it with the message"
)]
use chain_ode::{solve, Chain, ChainParams, Method, SolveOptions, Start};
use fc_methods::{with_gen_alpha_policy, GenAlphaPolicy};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let method: Method = a[0].parse().unwrap();
    let rtols: Vec<f64> = a[1].split(',').map(|s| s.parse().unwrap()).collect();
    let ea: f64 = a.get(2).map_or(1e8, |s| s.parse().unwrap());
    let rho: f64 = a
        .get(3)
        .map_or(SolveOptions::default().rho_inf, |s| s.parse().unwrap());
    // `FC_MEASURED=1`: gen-alpha bounds the pivot force's error too
    // (`Problem::measured`; off by default).
    let policy = GenAlphaPolicy {
        measured: std::env::var_os("FC_MEASURED").is_some(),
        ..GenAlphaPolicy::DEFAULT
    };
    let (n, len, mass) = (50, 6.0, 0.2);
    // `chain.mass` is each rod's mass: 5% of one joint's axial mode is
    // `eta = 0.1 sqrt(EA m l)` = 154.9 at EA = 1e8 (issue 49).
    let (m, l) = (mass, len / n as f64);
    let chain = Chain::new(ChainParams {
        length: len,
        links: n,
        mass,
        gravity: 1.0,
        damping: 0.0005,
        axial_stiffness: Some(ea),
        axial_damping: 2.0 * 0.05 * (ea * m * l).sqrt(),
        ..ChainParams::default()
    })
    .unwrap();
    let start = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    for rtol in rtols {
        let o = SolveOptions {
            t_end: 3.2,
            rtol,
            atol: rtol * 1e-2,
            rho_inf: rho,
            output_dt: Some(0.08),
            max_steps: 50_000_000,
            ..Default::default()
        };
        let tr = with_gen_alpha_policy(policy, || solve(&chain, &start, method, &o)).unwrap();
        let (f, t) = tr.summary.pivot_force_max.unwrap();
        let s = &tr.stats;
        println!(
            "{method} rtol {rtol:e} EA {ea:e} rho {rho}: {} pivot_force_max {f:.6} at {t:.5}, tip_speed_max {:.8}, steps {} rejected {} jac {} lu {} rhs {} wall {:.2} s segments {:?}",
            tr.status.as_str(),
            tr.summary.tip_speed_max,
            s.steps,
            s.rejected_steps,
            s.jacobian_evals,
            s.lu_factorizations,
            s.rhs_evals,
            tr.summary.wall_seconds,
            tr.segments.iter().map(|g| g.method).collect::<Vec<_>>()
        );
    }
}
