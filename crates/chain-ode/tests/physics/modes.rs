//! Linearised hanging chain against the continuum: omega_k = (j_{0,k}/2) sqrt(g/L).

use chain_ode::modes::hanging_frequencies;
use chain_ode::Chain;

const J0_ZEROS: [f64; 3] = [2.404825558, 5.520078110, 8.653727913];

fn relative_errors(n: usize) -> Vec<f64> {
    let chain = Chain::report(n, 0.0).unwrap();
    let w = hanging_frequencies(&chain);
    let scale = (chain.gravity() / chain.length()).sqrt();
    J0_ZEROS
        .iter()
        .enumerate()
        .map(|(k, j)| (w[k] / (0.5 * j * scale) - 1.0).abs())
        .collect()
}

#[test]
fn lowest_three_modes_converge_like_one_over_n_squared() {
    let ns = [25usize, 50, 100, 200];
    let errs: Vec<Vec<f64>> = ns.iter().map(|&n| relative_errors(n)).collect();
    for (k, _) in J0_ZEROS.iter().enumerate() {
        for w in 0..ns.len() - 1 {
            let (coarse, fine) = (errs[w][k], errs[w + 1][k]);
            let order = (coarse / fine).log2();
            assert!(
                (1.8..=2.2).contains(&order),
                "mode {}: order {order} between n = {} and {} (errors {:e}, {:e})",
                k + 1,
                ns[w],
                ns[w + 1],
                coarse,
                fine
            );
        }
    }
    // And they converge to the Bessel values themselves.
    assert!(errs[3].iter().all(|e| *e < 1e-3), "{:?}", errs[3]);
}
