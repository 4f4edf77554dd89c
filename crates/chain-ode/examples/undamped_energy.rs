//! gen-alpha's energy on the undamped 25-rod chain
//! (`scenes/horizontal-undamped.toml`, issue 49.5): `E(t) - E(0)` over
//! `M g L` at twelve times and at the end, under a variant of
//! `GenAlphaPolicy` (docs/model.md, "gen-alpha's energy on the undamped
//! chain", is measured with it).
//!
//! `cargo run --release -p chain-ode --example undamped_energy -- MODES RTOL T_END RHO_INF [METHOD]`
//! with `MODES` a comma-separated list of `default`, `noshift`, `nodead`,
//! `nofilter`, `ntol=F` (Newton's tolerance as a fraction of RADAU5's),
//! `fixed=H` (a fixed step).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument stops it with the message"
)]
use chain_ode::{solve, Chain, ChainParams, Method, SolveOptions, Start};
use fc_methods::{with_gen_alpha_policy, GenAlphaPolicy};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let mode = a[0].as_str();
    let rtol: f64 = a[1].parse().unwrap();
    let t_end: f64 = a[2].parse().unwrap();
    let rho: f64 = a[3].parse().unwrap();
    let method: Method = a.get(4).map_or(Method::GenAlpha, |s| s.parse().unwrap());
    let chain = Chain::new(ChainParams {
        length: 6.0,
        links: 25,
        mass: 0.2,
        gravity: 1.0,
        damping: 0.0,
        ..ChainParams::default()
    })
    .unwrap();
    let s = Start::Stretched {
        p0: [0.0, 0.0],
        p1: [6.0, 0.0],
    }
    .state(&chain)
    .unwrap();
    let mut p = GenAlphaPolicy::DEFAULT;
    for mode in mode.split(',') {
        match mode {
            "default" => {}
            "noshift" => p.shift = false,
            "nodead" => {
                p.control.dead_lo = 1.0;
                p.control.dead_hi = 1.0;
            }
            "nofilter" => p.filter = false,
            m if m.starts_with("ntol=") => p.newton_tol = m[5..].parse().unwrap(),
            m if m.starts_with("fixed=") => p.fixed_step = Some(m[6..].parse().unwrap()),
            _ => panic!("mode"),
        }
    }
    let o = SolveOptions {
        t_end,
        rtol,
        atol: rtol * 1e-2,
        rho_inf: rho,
        output_dt: Some(t_end / 12.0),
        max_steps: 100_000_000,
        ..Default::default()
    };
    let clock = std::time::Instant::now();
    let tr = with_gen_alpha_policy(p, || solve(&chain, &s, method, &o).unwrap());
    let scale = 30.0;
    let e: Vec<String> = (0..tr.times.len())
        .map(|k| format!("{:.2e}", (tr.energy(k) - tr.energy(0)) / scale))
        .collect();
    println!("{mode} {method} rtol {rtol:e} rho {rho} T {t_end}: {} steps {} rej {} dE/MgL {:.3e} wall {:.1}s\n  E(t): {}", tr.status, tr.stats.steps, tr.stats.rejected_steps, (tr.summary.energy_end - tr.summary.energy_start)/scale, clock.elapsed().as_secs_f64(), e.join(" "));
}
