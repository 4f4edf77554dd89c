//! The folded elastic snap (issue 53's case): a method's work and error
//! against DOP853 at rtol 1e-10, over a ladder of tolerances, with the
//! median wall time of `RUNS` runs.
//!
//! `cargo run --release -p chain-ode --example snap_probe -- N EA METHOD RTOL[,RTOL..] [RUNS] [RHO_INF]`
//!
//! The folded start of `scenes/folded.toml` (`L = 6`, `r = 0.001`,
//! `g = 1`) on `N` rods of mass `4 / N`, `N / 2` down, the axial damping
//! `eta = 2 zeta sqrt(EA m l)` at `zeta = 0.05`, to `t = 3.2`; error: the
//! larger of the tip end's distance over `L` and the largest tip speed's
//! relative error. `METHOD` may be `gen-alpha`, `dopri5`, `bdf`, ...

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]
use chain_ode::{solve, Chain, ChainParams, Method, SolveOptions, Start};
use fc_methods::{with_gen_alpha_policy, GenAlphaPolicy};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = a[0].parse().unwrap();
    let ea: f64 = a[1].parse().unwrap();
    let method: Method = a[2].parse().unwrap();
    let rtols: Vec<f64> = a[3].split(',').map(|s| s.parse().unwrap()).collect();
    let runs: usize = a.get(4).map_or(1, |s| s.parse().unwrap());
    let rho: f64 = a
        .get(5)
        .map_or(SolveOptions::default().rho_inf, |s| s.parse().unwrap());
    let (len, m) = (6.0, 4.0 / n as f64);
    let l = len / n as f64;
    let eta = 2.0 * 0.05 * (ea * m * l).sqrt();
    let chain = Chain::new(ChainParams {
        length: len,
        links: n,
        mass: m,
        gravity: 1.0,
        damping: 0.001,
        axial_stiffness: Some(ea),
        axial_damping: eta,
        ..ChainParams::default()
    })
    .unwrap();
    let start = Start::Folded {
        p0: [0.0, 0.0],
        down: Some(n / 2),
    }
    .state(&chain)
    .unwrap();
    let base = SolveOptions {
        t_end: 3.2,
        rho_inf: rho,
        ..Default::default()
    };
    // The reference, cached (DOP853 at rtol 1e-10 takes minutes at n = 100).
    let ref_rtol: f64 = std::env::var("REF_RTOL").map_or(1e-10, |s| s.parse().unwrap());
    let cache = format!("/tmp/snapref-{n}-{ea:e}.txt");
    let (tip0, v0) = match std::fs::read_to_string(&cache) {
        Ok(text) => {
            let v: Vec<f64> = text
                .split_whitespace()
                .map(|x| x.parse().unwrap())
                .collect();
            ([v[0], v[1]], v[2])
        }
        Err(_) => {
            let reference = solve(
                &chain,
                &start,
                Method::Dop853,
                &SolveOptions {
                    rtol: ref_rtol,
                    atol: ref_rtol * 1e-2,
                    ..base.clone()
                },
            )
            .unwrap();
            let s = &reference.summary;
            std::fs::write(
                &cache,
                format!(
                    "{:e} {:e} {:e}",
                    s.tip_end[0], s.tip_end[1], s.tip_speed_max
                ),
            )
            .unwrap();
            (s.tip_end, s.tip_speed_max)
        }
    };
    println!("n {n} EA {ea:e} eta {eta:.4} reference vmax {v0:.6}");
    let configs: Vec<String> = if a.len() > 6 {
        a[6..].to_vec()
    } else {
        vec![String::new()]
    };
    for config in configs {
        let policy = policy_of(&config);
        println!("== {config}");
        println!("method rtol status steps rejected newton_fail jac lu newton rhs changes err_tip err_speed err wall_median");
        for &rtol in &rtols {
            let o = SolveOptions {
                rtol,
                atol: rtol * 1e-2,
                ..base.clone()
            };
            let mut walls = vec![];
            let mut last = None;
            for _ in 0..runs {
                let tr =
                    with_gen_alpha_policy(policy, || solve(&chain, &start, method, &o)).unwrap();
                walls.push(tr.summary.wall_seconds);
                last = Some(tr);
            }
            walls.sort_by(f64::total_cmp);
            let tr = last.unwrap();
            let s = &tr.summary;
            let et = (s.tip_end[0] - tip0[0]).hypot(s.tip_end[1] - tip0[1]) / len;
            let ev = (s.tip_speed_max - v0).abs() / v0;
            let st = &tr.stats;
            println!(
                "{method} {rtol:.0e} {} {} {} {} {} {} {} {} {} {et:.2e} {ev:.2e} {:.2e} {:.4}",
                tr.status,
                st.steps,
                st.rejected_steps,
                st.newton_failures,
                st.jacobian_evals,
                st.lu_factorizations,
                st.newton_iterations,
                st.rhs_evals,
                st.step_size_changes,
                et.max(ev),
                walls[runs / 2]
            );
        }
    }
}

/// gen-alpha's policy with the `KEY=VALUE;..` changes of `config` (keys:
/// `dead_lo`, `dead_hi`, `grow`, `k_err`, `k_prev`, `safety`,
/// `theta_refresh`, `theta_slow`, `stale_iters`, `max_age`, `shift`,
/// `fixed`).
fn policy_of(config: &str) -> GenAlphaPolicy {
    let mut p = GenAlphaPolicy::DEFAULT;
    for kv in config.split(';').filter(|x| !x.is_empty()) {
        let (k, v) = kv.split_once('=').unwrap();
        let x: f64 = v.parse().unwrap();
        match k {
            "dead_lo" => p.control.dead_lo = x,
            "dead_hi" => p.control.dead_hi = x,
            "grow" => p.control.grow_max = x,
            "k_err" => p.control.k_err = x,
            "k_prev" => p.control.k_prev = x,
            "safety" => p.control.safety = x,
            "theta_refresh" => p.reuse.theta_refresh = x,
            "theta_slow" => p.reuse.theta_slow = x,
            "stale_iters" => p.reuse.stale_iters = x as u32,
            "max_age" => p.reuse.max_age = x as u64,
            "shift" => p.shift = x != 0.0,
            "fixed" => p.fixed_step = Some(x),
            "quadratic" => p.quadratic = x != 0.0,
            "measure_all" => p.measure_all = x != 0.0,
            _ => panic!("unknown key {k}"),
        }
    }
    p
}
