//! Cayley's scale, one run: `cargo run --release -p chain-ode --example cayley -- N K C METHOD RTOL [EPS [R [MU]]]`.
//! A chain of `N` rods (`L = 1`, mass per length 1, `g = 1`) hangs straight
//! down, its rods zigzagging by `EPS` rad (default 0.02), its lower end
//! touching a floor of stiffness `K`, damping `C` and friction `MU`
//! (default 0, regularised at 1e-3), the joints' friction `R` (default 0,
//! `ChainParams::damping`); the top is let go at
//! `t = 0`. Prints the scale's reading over `3 mu g x` (`x = g t^2 / 2`,
//! the ideal free fall) at `t = 0.5, 0.75, 1 (mid-fall), 1.25`, the fall
//! of the top against free fall at those times, the steps and wall time.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]
use std::f64::consts::FRAC_PI_2;

use chain_ode::{solve, Chain, ChainParams, Floor, FloorLaw, Method, Pivot, SolveOptions, Start};

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = a[0].parse().unwrap();
    let k: f64 = a[1].parse().unwrap();
    let c: f64 = a[2].parse().unwrap();
    let method: Method = a[3].parse().unwrap();
    let rtol: f64 = a[4].parse().unwrap();
    let eps: f64 = a.get(5).map_or(0.02, |s| s.parse().unwrap());
    let r: f64 = a.get(6).map_or(0.0, |s| s.parse().unwrap());
    let mu: f64 = a.get(7).map_or(0.0, |s| s.parse().unwrap());
    let chain = Chain::new(ChainParams {
        length: 1.0,
        links: n,
        mass: 1.0 / n as f64,
        gravity: 1.0,
        pivot: Pivot {
            release: Some(0.0),
            ..Pivot::default()
        },
        floor: Some(Floor {
            height: None,
            angle: 0.0,
            stiffness: k,
            damping: c,
            friction: mu,
            slip_speed: 1e-3,
            law: FloorLaw::Penalty,
            restitution: 0.0,
        }),
        damping: r,
        ..ChainParams::default()
    })
    .unwrap();
    let angles = (0..n)
        .map(|i| -FRAC_PI_2 + if i % 2 == 0 { eps } else { -eps })
        .collect();
    let s = Start::Angles {
        p0: [0.0, 0.0],
        angles,
        rates: None,
    }
    .state(&chain)
    .unwrap();
    let times = [0.5, 0.75, 1.0, 1.25];
    let d = 0.05;
    let o = SolveOptions {
        t_end: 1.3,
        rtol,
        atol: rtol * 1e-2,
        output_dt: Some(d),
        max_steps: 200_000_000,
        ..SolveOptions::default()
    };
    let tr = solve(&chain, &s, method, &o).unwrap();
    print!(
        "n={n} k={k:e} c={c} {method} rtol={rtol:e}: {} steps {} rhs {:.3} s {:?};",
        tr.stats.steps, tr.stats.rhs_evals, tr.summary.wall_seconds, tr.status
    );
    for &t in &times {
        let Some(j) = tr.times.iter().position(|&s| (s - t).abs() < 1e-9) else {
            continue;
        };
        let x = 0.5 * t * t;
        // The scale's reading averaged over [t - d, t + d], from the
        // chain's momentum (the floor and gravity are the only forces on
        // it once let go): F = dP/dt + M g; the ideal's average is
        // 3 (g / 2) (t^2 + d^2 / 3).
        let dp = tr.momentum(j + 1)[1] - tr.momentum(j - 1)[1];
        let f = dp / (2.0 * d) + 1.0;
        let ideal = 1.5 * (t * t + d * d / 3.0);
        // The top: the first rod's start (joint 0, once let go).
        let top = tr.joints(j)[0][1];
        print!(
            " t={t}: F/(3 mu g x)={:.4} top/free={:.4}",
            f / ideal,
            -top / x
        );
    }
    println!();
    if std::env::var_os("CAYLEY_SERIES").is_some() {
        let o = SolveOptions {
            output_dt: Some(0.05),
            ..o
        };
        let tr = solve(&chain, &s, method, &o).unwrap();
        for j in 0..tr.len() {
            let js = tr.joints(j);
            let lo = js.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
            let hi = js.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
            let f = tr.floor_force(j).unwrap();
            let (h, _) = chain_ode::Model::view(&tr.model).floor_line().unwrap();
            println!(
                "t={:.3} F=({:.4},{:.4}) lowest-floor={:.3e} top={:.4} tipy={:.4}",
                tr.times[j],
                f[0],
                f[1],
                lo - h,
                hi,
                js[n][1]
            );
        }
    }
}
