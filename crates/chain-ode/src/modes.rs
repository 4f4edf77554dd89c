//! Small oscillations about the vertical hanging chain.
//!
//! With `phi_i = -pi/2 + theta_i`, the linearised equations are
//! `mt theta'' + (g/l) Q theta = 0`, `Q = diag(q_i)`, `q_i = n - i + 1/2`.
//! With `u = Q^{1/2} theta` this is the symmetric eigenproblem
//! `Q^{-1/2} mt Q^{-1/2} u = ((g/l)/omega^2) u`.

use faer::{Mat, Side};

use crate::chain::Chain;
use crate::dense::mt;
use crate::kinematics::lever_arm;

/// The angular frequencies `omega_k` (rad/time) of the linearised hanging
/// chain, lowest first (all `n` of them). Dense: O(n^2) memory, O(n^3)
/// time. If the symmetric eigenvalue iteration does not converge (never
/// seen: the matrix is finite and symmetric), every entry is NaN.
pub fn hanging_frequencies(chain: &Chain) -> Vec<f64> {
    let n = chain.links();
    let qs: Vec<f64> = (0..n).map(|i| 1.0 / lever_arm(n, i).sqrt()).collect();
    let s = Mat::from_fn(n, n, |i, j| qs[i] * mt(n, i, j) * qs[j]);
    let Ok(lambda) = s.self_adjoint_eigenvalues(Side::Lower) else {
        return vec![f64::NAN; n];
    };
    let g = chain.gravity_rate();
    // Largest lambda <-> lowest frequency.
    lambda.iter().rev().map(|&x| (g / x).sqrt()).collect()
}
