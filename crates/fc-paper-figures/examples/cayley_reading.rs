//! Cayley's scale as single runs (issue 50), with their wall times:
//! `cargo run --release -p fc-paper-figures --example cayley_reading --
//! SCENE N LAW METHOD ACCURACY [REPEATS]`, where `SCENE` is
//! `scenes/cayley-scale.toml`, `LAW` `constraint` or `penalty`, `ACCURACY`
//! `run.dt` for a fixed-step method and `run.rtol` for an adaptive one.
//! Prints the reading over `t = 0.3 .. 1.2` (19 windows of 0.05; the
//! mean, the scatter over the windows and the error
//! `sqrt(mean (r_j − 1)²)`), the steps, and the wall time of each repeat
//! with their median (`fc_paper_figures::cayley_single`).

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]

use chain_ode::Method;
use fc_paper_figures::cayley_single::{self, Single};
use fc_scene::scene::Scene;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    assert!(
        (5..=6).contains(&a.len()),
        "usage: SCENE N LAW METHOD ACCURACY [REPEATS]"
    );
    let base = Scene::load(&a[0]).unwrap();
    let law: &'static str = match a[2].as_str() {
        "constraint" => "constraint",
        "penalty" => "penalty",
        other => panic!("LAW is constraint or penalty, not {other}"),
    };
    let single = Single {
        links: a[1].parse().unwrap(),
        law,
        method: a[3].parse::<Method>().unwrap(),
        accuracy: a[4].parse().unwrap(),
    };
    let repeats: usize = a.get(5).map_or(1, |s| s.parse().unwrap());
    let mut walls = Vec::new();
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let (_, read) = cayley_single::run(&base, &single).unwrap();
        walls.push(read.wall_seconds);
        last = Some(read);
    }
    let r = last.unwrap();
    walls.sort_by(f64::total_cmp);
    let median = walls[walls.len() / 2];
    println!(
        "n={} law={} {} accuracy={:e}: status {} reading {:.4} scatter {:.4} error {:.4} \
         steps {} wall median {:.3} s of {:?}",
        single.links,
        single.law,
        single.method,
        single.accuracy,
        r.status,
        r.reading.mean,
        r.reading.scatter,
        r.error,
        r.steps,
        median,
        walls
    );
    let windows: Vec<String> = r
        .reading
        .windows
        .iter()
        .map(|w| format!("{:.3}", w.1))
        .collect();
    println!("  windows: {}", windows.join(" "));
}
