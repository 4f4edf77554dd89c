//! Where, if anywhere, `auto`'s handover to BDF pays on BEAM (the paper's
//! external benchmark; methods §6, claim 10 of the third review): DOP853,
//! DOPRI5, BDF and `auto` at BEAM's tolerances (`fc_paper_figures::beam`,
//! `rtol = atol`), each point run as the precision study runs it
//! (`beam::rows`, one at a time) `REPEATS` times, its wall time the median.
//! Printed: each run's errors at `t = 5` against the published solution
//! (angles, rates), steps, whether `auto` ran BDF, the median wall time;
//! then each method's wall time at matched error (log-log between the
//! bracketing runs, as `wp-matched`; `-` where no pair brackets the level),
//! by the rate error (the larger one) and by the angle error.
//!
//! `cargo run --release -p fc-paper-figures --example beam_auto [REPEATS]`
//!
//! Wall times are this machine's at the time of the run; the errors and
//! steps reproduce to the byte.

use std::process::ExitCode;

use chain_ode::Method;
use fc_paper_figures::beam::{self, RTOLS};
use fc_paper_figures::matched::time_at;

const METHODS: [Method; 4] = [Method::Dop853, Method::Dopri5, Method::Bdf, Method::Auto];

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> ExitCode {
    let repeats: usize = match std::env::args().nth(1).map(|a| a.parse()) {
        None => 3,
        Some(Ok(r)) if r > 0 => r,
        Some(_) => {
            eprintln!("REPEATS: a positive whole number");
            return ExitCode::from(2);
        }
    };
    println!("method,rtol,err_angles,err_rates,steps,ran_bdf,wall_median_s");
    // (method, [(err_angles, err_rates, wall)] loosest first)
    let mut lines = vec![];
    for m in METHODS {
        let mut line = vec![];
        for &rtol in &RTOLS {
            let mut walls = vec![];
            let mut last = None;
            for _ in 0..repeats {
                match beam::rows(&[(m, rtol)], true) {
                    Ok(mut rows) => {
                        let p = rows.remove(0);
                        walls.extend(p.walls.first().copied());
                        last = Some(p);
                    }
                    Err(e) => {
                        eprintln!("{e}");
                        return ExitCode::from(1);
                    }
                }
            }
            let Some(p) = last else { continue };
            let wall = median(walls);
            println!(
                "{m},{rtol:e},{:.3e},{:.3e},{},{},{wall:.3}",
                p.err_tip,
                p.err_vmax,
                p.stats.steps,
                u8::from(p.switched)
            );
            if p.status == "ok" {
                line.push((p.err_tip, p.err_vmax, wall));
            }
        }
        lines.push((m, line));
    }
    for (name, pick) in [
        (
            "rate error",
            (|r: &(f64, f64, f64)| r.1) as fn(&(f64, f64, f64)) -> f64,
        ),
        ("angle error", |r: &(f64, f64, f64)| r.0),
    ] {
        println!();
        let head: Vec<String> = METHODS.iter().map(|m| m.to_string()).collect();
        println!("matched {name},{}", head.join(","));
        for k in 1..=9 {
            let level = 10f64.powi(-k);
            let cells: Vec<String> = lines
                .iter()
                .map(|(_, line)| {
                    let runs: Vec<(f64, f64)> = line.iter().map(|r| (pick(r), r.2)).collect();
                    time_at(&runs, level).map_or("-".to_string(), |t| format!("{t:.3}"))
                })
                .collect();
            if cells.iter().any(|c| c != "-") {
                println!("{level:.0e},{}", cells.join(","));
            }
        }
    }
    ExitCode::SUCCESS
}
