use chain_ode::{solve, Chain, Method, SolveOptions, Start};
fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let (n, r, d, t_end) = (args[0] as usize, args[1], args[2], args[3]);
    let chain = Chain::report(n, r).unwrap();
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [d, 0.0],
    }
    .state(&chain)
    .unwrap();
    for dt in [0.02, 0.01, 0.005, 0.0025, 0.00125] {
        let o = SolveOptions {
            t_end,
            dt,
            ..Default::default()
        };
        let tr = solve(&chain, &s, Method::Rk4, &o).unwrap();
        println!(
            "dt {dt}: {} bal {:e} rise {:e} vmax {:.10} t {:.6} tip {:?} scale {}",
            tr.status,
            tr.summary.energy_balance_error,
            tr.summary.max_energy_rise,
            tr.summary.tip_speed_max,
            tr.summary.t_tip_speed_max,
            tr.summary.tip_end,
            chain.energy_scale()
        );
    }
}
