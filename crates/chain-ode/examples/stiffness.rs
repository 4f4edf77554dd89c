//! Where does the chain turn stiff? DOPRI5 against BDF over damping r and rods n
//! on the span d = 3 start (L = 6, m = 0.2 per rod, g = 1), at equal tolerance.
//!
//! `cargo run --release -p chain-ode --example stiffness -- [T_END] [RTOL]`
//! Prints one row per (n, r): the damping rate gamma = r/(m l^2), each method's
//! status, steps, RHS evaluations, median wall time (of 3 when under 0.5 s),
//! the tip distance between the two, and the wall-time ratio DOPRI5 / BDF.
use chain_ode::{solve, Chain, Method, SolveOptions, Start, Trajectory};

fn timed(chain: &Chain, s: &chain_ode::State, m: Method, o: &SolveOptions) -> (Trajectory, f64) {
    let first = solve(chain, s, m, o).unwrap();
    if first.summary.wall_seconds > 0.5 {
        let w = first.summary.wall_seconds;
        return (first, w);
    }
    let mut walls = vec![first.summary.wall_seconds];
    for _ in 0..2 {
        walls.push(solve(chain, s, m, o).unwrap().summary.wall_seconds);
    }
    walls.sort_by(f64::total_cmp);
    (first, walls[1])
}

fn main() {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    let t_end = a.first().copied().unwrap_or(1.0);
    let rtol = a.get(1).copied().unwrap_or(1e-6);
    println!("n,r,gamma,dopri5_status,dopri5_steps,dopri5_rhs,dopri5_wall,bdf_status,bdf_steps,bdf_rhs,bdf_jac,bdf_lu,bdf_wall,tip_diff,ratio_dopri5_over_bdf");
    for n in [25usize, 50, 100, 200, 400, 800] {
        for r in [1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0] {
            let chain = Chain::report(n, r).unwrap();
            let s = Start::Catenary {
                p0: [0.0, 0.0],
                p1: [3.0, 0.0],
            }
            .state(&chain)
            .unwrap();
            let o = SolveOptions {
                t_end,
                rtol,
                atol: rtol * 1e-2,
                max_steps: 300_000,
                ..Default::default()
            };
            let (dp, wd) = timed(&chain, &s, Method::Dopri5, &o);
            let (bdf, wb) = timed(&chain, &s, Method::Bdf, &o);
            let diff = (dp.summary.tip_end[0] - bdf.summary.tip_end[0])
                .hypot(dp.summary.tip_end[1] - bdf.summary.tip_end[1]);
            println!(
                "{n},{r:e},{:.4e},{},{},{},{wd:.4e},{},{},{},{},{},{wb:.4e},{diff:.2e},{:.3}",
                chain.damping_rate(),
                dp.status,
                dp.stats.steps,
                dp.stats.rhs_evals,
                bdf.status,
                bdf.stats.steps,
                bdf.stats.rhs_evals,
                bdf.stats.jacobian_evals,
                bdf.stats.lu_factorizations,
                wd / wb
            );
        }
    }
}
