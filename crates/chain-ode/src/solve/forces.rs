//! Whether a run's forces are right to its tolerance: a method that steps
//! over the axial modes of elastic links does not resolve the tensions
//! they carry unless it annihilates them (issue 49: gen-alpha at
//! `rho_inf = 0.9` put the steel rope's snap tension 3 to 25 times too
//! high with every other number right).

use fc_methods::Method;

use super::auto_elastic::AUTO_GEN_ALPHA_RHO_INF;
use super::SolveOptions;
use crate::chain::Chain;

/// Below this `rtol`, gen-alpha at `rho_inf = 0`, stepping over the axial
/// modes, does not claim its forces: they are the modes' quasi-static
/// values, whose error does not follow the tolerance (measured on issue
/// 49's steel rope against BDF at rtol 1e-8, 48.0780: 1.2e-3 at rtol
/// 1e-3, 5e-5 at 1e-4, 1e-4 at 1e-5, 3e-5 at 1e-6; docs/model.md, "The
/// generalized-alpha method").
pub const QUASI_STATIC_FORCE_RTOL: f64 = 1e-4;

/// A step longer than this over the fastest axial period's `1 / (2 pi)`
/// (`h omega_max > 1`) steps over the mode.
const RESOLVED_H_OMEGA: f64 = 1.0;

/// True unless a `gen-alpha` segment of a run of `method` (one of
/// `ran`, the methods of its segments) on `chain` stepped over its axial
/// modes (its largest step `h_max` longer than `1 / omega_max`,
/// `omega_max = 2 sqrt(K / m)` the spring chain's highest frequency)
/// without annihilating them (`rho_inf > 0`), or annihilated them at a
/// tolerance below [`QUASI_STATIC_FORCE_RTOL`]. Rigid links (no axial
/// modes) and every other method: true (the explicit methods are held to
/// the modes' stability limit, BDF resolves what its error control sees).
pub(crate) fn resolved(
    chain: Option<&Chain>,
    method: Method,
    ran: &[Method],
    options: &SolveOptions,
    h_max: f64,
) -> bool {
    let Some(chain) = chain else { return true };
    let Some(k) = chain.joint_stiffness() else {
        return true;
    };
    if !ran.contains(&Method::GenAlpha) {
        return true;
    }
    let omega = 2.0 * (k / chain.mass()).sqrt();
    if h_max * omega <= RESOLVED_H_OMEGA {
        return true;
    }
    let rho = if method == Method::Auto {
        AUTO_GEN_ALPHA_RHO_INF
    } else {
        options.rho_inf
    };
    rho == 0.0 && options.rtol >= QUASI_STATIC_FORCE_RTOL
}
