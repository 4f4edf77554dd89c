//! gen-alpha (or any method) on the rigid chain's two checks of issues 47
//! and 49: span d = 3 (`scenes/span-d3.toml`: n = 50, r = 0.0005, the
//! catenary to (3, 0), t = 4.157), its tip at the end against DOP853 at
//! rtol 1e-12; and the undamped horizontal start
//! (`scenes/horizontal-undamped.toml`: n = 25, r = 0, from (6, 0)) to
//! `T_END`, its energy balance `max |E - E(0)|` and `E(T) - E(0)` in units
//! of `M g L`.
//!
//! `cargo run --release -p chain-ode --example rigid_probe -- span|horiz METHOD RTOL[,..] RHO[,..] [T_END]`

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]
use chain_ode::{solve, Chain, Method, SolveOptions, Start};
use fc_methods::{with_gen_alpha_policy, GenAlphaPolicy};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let which = a[0].as_str();
    let method: Method = a[1].parse().unwrap();
    let rtols: Vec<f64> = a[2].split(',').map(|s| s.parse().unwrap()).collect();
    let rhos: Vec<f64> = a[3].split(',').map(|s| s.parse().unwrap()).collect();
    // A fixed step for gen-alpha (its policy's `fixed_step`), from FIXED.
    let policy = GenAlphaPolicy {
        fixed_step: std::env::var("FIXED").ok().map(|s| s.parse().unwrap()),
        ..GenAlphaPolicy::DEFAULT
    };
    let (chain, start, t_end) = match which {
        "span" => (
            Chain::report(50, 0.0005).unwrap(),
            Start::Catenary {
                p0: [0.0, 0.0],
                p1: [3.0, 0.0],
            },
            4.157,
        ),
        _ => (
            Chain::report(25, 0.0).unwrap(),
            Start::Stretched {
                p0: [0.0, 0.0],
                p1: [6.0, 0.0],
            },
            a.get(4).map_or(120.0, |s| s.parse().unwrap()),
        ),
    };
    let t_end = a.get(4).map_or(t_end, |s| s.parse().unwrap());
    let s = start.state(&chain).unwrap();
    let mgl = chain.total_mass() * chain.gravity() * chain.length();
    let base = SolveOptions {
        t_end,
        ..Default::default()
    };
    let reference = solve(
        &chain,
        &s,
        Method::Dop853,
        &SolveOptions {
            rtol: 1e-12,
            atol: 1e-14,
            ..base.clone()
        },
    )
    .unwrap();
    let tip0 = reference.summary.tip_end;
    println!(
        "{which}: t_end {t_end}, reference DOP853 1e-12 {} steps {}, energy drift {:.2e} MgL",
        reference.status,
        reference.stats.steps,
        (reference.summary.energy_end + reference.summary.dissipated
            - reference.summary.energy_start)
            / mgl
    );
    println!("method rho rtol status steps rejected etf nf jac lu newton err_tip dE_end/MgL balance/MgL wall");
    for &rho in &rhos {
        for &rtol in &rtols {
            let o = SolveOptions {
                rtol,
                atol: rtol * 1e-2,
                rho_inf: rho,
                ..base.clone()
            };
            let tr = with_gen_alpha_policy(policy, || solve(&chain, &s, method, &o)).unwrap();
            let sm = &tr.summary;
            let st = &tr.stats;
            let et = (sm.tip_end[0] - tip0[0]).hypot(sm.tip_end[1] - tip0[1]) / chain.length();
            println!(
                "{method} {rho} {rtol:.0e} {} {} {} {} {} {} {} {} {et:.2e} {:+.3e} {:.3e} {:.3}",
                tr.status,
                st.steps,
                st.rejected_steps,
                st.error_test_failures,
                st.newton_failures,
                st.jacobian_evals,
                st.lu_factorizations,
                st.newton_iterations,
                (sm.energy_end + sm.dissipated - sm.energy_start) / mgl,
                sm.energy_balance_error / mgl,
                sm.wall_seconds
            );
        }
    }
}
