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

/// The axial angular frequencies (rad/time) of an elastic `chain` hanging
/// straight down at rest, lowest first (all `n`): the rods' vertical motion
/// linearised from the right-hand side itself (the exact Jacobian's
/// vertical block `B = -M^-1 K`, one JVP per rod), symmetrised with the
/// rods' vertical masses (`M^1/2 (-B) M^-1/2`; the last rod carries the tip
/// mass) and solved as a symmetric eigenproblem. Dense: O(n^2) memory,
/// O(n^3) time, for studies of the layout (`docs/model.md`, "Where the
/// compliance sits"). `None` for rigid links; NaN entries if the
/// eigenvalue iteration does not converge.
pub fn axial_frequencies(chain: &Chain) -> Option<Vec<f64>> {
    chain.axial_stiffness()?;
    let n = chain.links();
    let hanging = crate::state::State {
        anchor: [0.0, 0.0],
        angles: vec![-std::f64::consts::FRAC_PI_2; n],
        rates: vec![0.0; n],
    };
    let y = crate::elastic::start_state(chain, &hanging);
    let mut sys = crate::elastic::ElasticSystem::new(chain);
    let (oy, ovy) = (3 * n + 1, 5 * n + 1);
    let mass = |i: usize| {
        crate::elastic::rod_mass(chain, i) + if i + 1 == n { chain.tip_mass() } else { 0.0 }
    };
    let root: Vec<f64> = (0..n).map(|i| mass(i).sqrt()).collect();
    let (mut e, mut jv) = (vec![0.0; y.len()], vec![0.0; y.len()]);
    let mut s = Mat::<f64>::zeros(n, n);
    for j in 0..n {
        e[oy + j] = 1.0;
        sys.jvp(0.0, &y, &e, &mut jv);
        e[oy + j] = 0.0;
        for i in 0..n {
            s[(i, j)] = -jv[ovy + i] * root[i] / root[j];
        }
    }
    let Ok(mut omega2) = s.self_adjoint_eigenvalues(Side::Lower) else {
        return Some(vec![f64::NAN; n]);
    };
    omega2.sort_by(f64::total_cmp);
    Some(omega2.iter().map(|w| w.max(0.0).sqrt()).collect())
}
