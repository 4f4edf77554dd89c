//! The stiff rope (n = 100, r = 1, span d = 3, t_end = 4) at matched
//! accuracy, as `wp-stiff-rope` and `wp-matched` measure it, in one quick
//! run: each method over an rtol ladder (atol = rtol / 100, no samples), the
//! median wall and CPU time of `RUNS` runs (CPU time from
//! `/proc/thread-self/schedstat` where there is one: less moved by other
//! processes on a loaded machine), its work counters and its error
//! `max(|tip - tip_ref| / L, |vmax - vmax_ref| / vmax_ref)` against the
//! study's reference (DOPRI5 at rtol 1e-13, atol 1e-15). Then, per method,
//! its time at the error `LEVEL` (default: DOPRI5's at rtol 1e-3 on this
//! scene, 3.57e-8), interpolated as `wp-matched` does (log-log between the
//! first bracketing pair of runs, loosest first).
//!
//! `cargo run --release -p chain-ode --example rope_ladder -- METHODS RTOLS [RUNS [LEVEL]]`
//! (comma-separated lists, e.g. `bdf,dopri5 1e-3,1e-8,1e-9 5`).
//! `ROPE_NO_REF=1` skips the reference run (1.6 s) and uses its values as
//! this example printed them.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]
use chain_ode::{solve, Chain, Method, SolveOptions, Start};

/// CPU time of this thread so far (seconds), if the kernel reports it.
fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

/// Time at error `level` of `runs` (`(error, time)`, loosest first): log-log
/// between the first bracketing pair, as `falling_chain::study::matched`.
fn time_at(runs: &[(f64, f64)], level: f64) -> Option<f64> {
    runs.windows(2).find_map(|w| {
        let ((e0, t0), (e1, t1)) = (w[0], w[1]);
        if !(e0.min(e1) <= level && level <= e0.max(e1)) {
            return None;
        }
        if e0 == e1 {
            return Some(t0.min(t1));
        }
        let s = (level.ln() - e0.ln()) / (e1.ln() - e0.ln());
        Some((t0.ln() + s * (t1.ln() - t0.ln())).exp())
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let methods: Vec<Method> = a[0].split(',').map(|m| m.parse().unwrap()).collect();
    let rtols: Vec<f64> = a[1].split(',').map(|s| s.parse().unwrap()).collect();
    let runs: usize = a.get(2).map_or(5, |s| s.parse().unwrap());
    let level: f64 = a.get(3).map_or(3.57e-8, |s| s.parse().unwrap());
    let chain = Chain::report(100, 1.0).unwrap();
    let start = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    };
    let s = start.state(&chain).unwrap();
    let t_end = 4.0;
    let (tip_ref, vmax_ref) = if std::env::var("ROPE_NO_REF").is_ok() {
        ([-2.083815145972657, -3.7080228752246596], 7.756909186849636)
    } else {
        let o = SolveOptions {
            t_end,
            rtol: 1e-13,
            atol: 1e-15,
            ..Default::default()
        };
        let r = solve(&chain, &s, Method::Dopri5, &o).unwrap();
        (r.summary.tip_end, r.summary.tip_speed_max)
    };
    println!("reference tip {tip_ref:?} vmax {vmax_ref}");
    for m in methods {
        let (mut by_wall, mut by_cpu) = (vec![], vec![]);
        for &rtol in &rtols {
            let o = SolveOptions {
                t_end,
                rtol,
                atol: rtol * 1e-2,
                ..Default::default()
            };
            let (mut walls, mut cpus) = (vec![], vec![]);
            let mut tr = None;
            for _ in 0..runs {
                let c0 = cpu_seconds();
                let t = solve(&chain, &s, m, &o).unwrap();
                if let (Some(c0), Some(c1)) = (c0, cpu_seconds()) {
                    cpus.push(c1 - c0);
                }
                walls.push(t.summary.wall_seconds);
                tr = Some(t);
            }
            let (wall, cpu) = (
                median(walls),
                if cpus.is_empty() {
                    f64::NAN
                } else {
                    median(cpus)
                },
            );
            let tr = tr.unwrap();
            let sm = &tr.summary;
            let e_tip =
                (sm.tip_end[0] - tip_ref[0]).hypot(sm.tip_end[1] - tip_ref[1]) / chain.length();
            let e_v = (sm.tip_speed_max - vmax_ref).abs() / vmax_ref;
            let err = e_tip.max(e_v);
            let st = &tr.stats;
            println!(
                "{m:7} rtol {rtol:.0e} {:8} steps {:6} rej {:4} etf {:3} nf {:3} nit {:6} rhs {:7} jac {:4} lu {:4} wall {:.3e} cpu {:.3e} us/step {:.1} e_tip {:.2e} e_v {:.2e} err {:.2e}",
                tr.status.as_str(),
                st.steps,
                st.rejected_steps,
                st.error_test_failures,
                st.newton_failures,
                st.newton_iterations,
                st.rhs_evals,
                st.jacobian_evals,
                st.lu_factorizations,
                wall,
                cpu,
                cpu * 1e6 / st.steps.max(1) as f64,
                e_tip,
                e_v,
                err,
            );
            if tr.status.is_ok() && err > 0.0 {
                by_wall.push((err, wall));
                by_cpu.push((err, cpu));
            }
        }
        let show = |t: Option<f64>| t.map_or("none".to_string(), |t| format!("{t:.3e}"));
        println!(
            "{m:7} at error {level:.2e}: wall {} s, cpu {} s",
            show(time_at(&by_wall, level)),
            show(time_at(&by_cpu, level))
        );
    }
}
