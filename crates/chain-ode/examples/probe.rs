//! Quick look at one scene under every method: `cargo run --release -p chain-ode --example probe -- N R START D T_END RTOL [DT [METHODS]]`
//! START is `catenary` (P1 = (D, 0)) or `folded`.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]
use chain_ode::{solve, Chain, Method, SolveOptions, Start};
fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = a[0].parse().unwrap();
    let r: f64 = a[1].parse().unwrap();
    let d: f64 = a[3].parse().unwrap();
    let t_end: f64 = a[4].parse().unwrap();
    let rtol: f64 = a[5].parse().unwrap();
    let dt: f64 = a.get(6).map_or(0.01, |s| s.parse().unwrap());
    let chain = Chain::report(n, r).unwrap();
    let start = match a[2].as_str() {
        "folded" => Start::Folded {
            p0: [0.0, 0.0],
            down: None,
        },
        _ => Start::Catenary {
            p0: [0.0, 0.0],
            p1: [d, 0.0],
        },
    };
    let s = start.state(&chain).unwrap();
    let methods: Vec<Method> = match a.get(7) {
        Some(list) => list.split(',').map(|m| m.parse().unwrap()).collect(),
        None => Method::ALL.to_vec(),
    };
    for m in methods {
        let o = SolveOptions {
            t_end,
            dt,
            rtol,
            atol: rtol * 1e-2,
            ..Default::default()
        };
        let mut walls = vec![];
        let mut tr = None;
        for _ in 0..5 {
            let t = solve(&chain, &s, m, &o).unwrap();
            walls.push(t.summary.wall_seconds);
            tr = Some(t);
        }
        walls.sort_by(f64::total_cmp);
        let tr = tr.unwrap();
        println!(
            "{m:7} {:9} t {:.4} steps {:6} rej {:4} rhs {:7} jac {:4} lu {:4} stiff {:3} wall_med {:.3e} bal {:.2e} vmax {:.9} tip [{:.9}, {:.9}] segs {:?}",
            tr.status.as_str(), tr.t_reached, tr.stats.steps, tr.stats.rejected_steps, tr.stats.rhs_evals,
            tr.stats.jacobian_evals, tr.stats.lu_factorizations, tr.stats.stiffness_detections, walls[2],
            tr.summary.energy_balance_error, tr.summary.tip_speed_max, tr.summary.tip_end[0], tr.summary.tip_end[1],
            tr.segments.iter().map(|s| format!("{}:{:.3}-{:.3}", s.method, s.t_start, s.t_end)).collect::<Vec<_>>()
        );
    }
}
