//! Whether a run's forces are right to its tolerance: a method that steps
//! over the axial modes of elastic links does not resolve the tensions
//! they carry unless it annihilates them (issue 49: gen-alpha at
//! `rho_inf = 0.9` put the steel rope's snap tension 3 to 25 times too
//! high with every other number right; BDF 5e-5 to 4.9 times off at rtol
//! 1e-8 to 1e-3; DOPRI5 at rtol 1e-3 16% on a 10-rod rope).

use fc_methods::Method;

use super::auto_elastic::{joint_damping_ratio, AUTO_ELASTIC_ZETA, AUTO_GEN_ALPHA_RHO_INF};
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

/// True unless a segment of a run of `method` (`ran`, the methods of its
/// segments) on `chain`, elastic links with axial modes of highest
/// frequency `omega_max = 2 sqrt(K / m)`, does not resolve the forces
/// they carry:
/// * `dopri5` or `dop853` at [`QUASI_STATIC_FORCE_RTOL`] or looser: held
///   to the modes' stability limit,
///   they leave the ringing that their error control allows at that
///   tolerance, which the springs' stiffness multiplies into the force.
///   Measured on 10 rods of the span-d3 chain at `EA = 1e7` (`zeta =
///   0.05`): DOPRI5 at rtol 1e-3 put the peak pivot force 16% high (its
///   transverse part; the tension 1.4e-4), DOP853 0.9%; at 1e-5 both
///   within 4e-9 (on the 50-rod steel rope DOPRI5 at 1e-3 was within
///   6e-6: the rule is the cautious side of the two); at `EA = 1e8`
///   DOPRI5 at rtol 1e-4 was 1.3e-3 off, above 10 rtol (the
///   `force-precision` figure), hence 1e-4 itself;
/// * an implicit method whose largest step `h_max` is longer than `1 /
///   omega_max` (it stepped over the modes): `gen-alpha` without
///   annihilating them (`rho_inf > 0`), or annihilating them at a
///   tolerance below [`QUASI_STATIC_FORCE_RTOL`]; `bdf` and `bdf-dense`
///   on lightly damped modes (a joint damping ratio below
///   [`AUTO_ELASTIC_ZETA`]): their error estimate, of the slow motion,
///   does not hold the ringing modes' share of the force, which they damp
///   by an amount that depends on their step and order. Measured on issue
///   49's steel rope (`zeta = 0.05`, peak pivot force 48.0778 converged):
///   BDF gave 235.6, 58.3, 51.8, 49.6, 48.110, 48.0804 at rtol 1e-3 to
///   1e-8, every one `ok` and outside 10 rtol (docs/model.md, "Forces as
///   results"). Overdamped modes decay, which BDF follows.
///
/// Rigid links (no axial modes), `rk4` (no tolerance: its step is the
/// user's) and the explicit methods at tighter tolerances: true.
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
    let explicit = ran
        .iter()
        .any(|m| matches!(m, Method::Dopri5 | Method::Dop853));
    if explicit && options.rtol >= QUASI_STATIC_FORCE_RTOL {
        return false;
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
    let gen_alpha =
        !ran.contains(&Method::GenAlpha) || (rho == 0.0 && options.rtol >= QUASI_STATIC_FORCE_RTOL);
    let damped = joint_damping_ratio(chain).is_some_and(|z| z >= AUTO_ELASTIC_ZETA);
    let bdf = !ran
        .iter()
        .any(|m| matches!(m, Method::Bdf | Method::BdfDense))
        || damped;
    gen_alpha && bdf
}

/// False when the penalty floor pushed during the run (its tracked peak
/// [`PeakForce::Floor`](crate::model::PeakForce::Floor) above zero): the
/// contact law's kinks (touch-down, the clamp `N >= 0`) are where a pair's
/// error estimate does not see its error, as for the floor's energy
/// balance (`solve::tally::BALANCE_PER_TOLERANCE_FLOOR`),
/// so the forces of a run that landed are not right to its tolerance.
/// Measured on 8 rods of `scenes/cayley-scale.toml` (`chain.mass = 0.125`):
/// the largest floor force up to `t = 1` is 6568.40 converged (DOP853,
/// DOPRI5 and BDF at rtol 1e-12 within 1e-6), and 6568.43, 6568.28,
/// 6568.59 at rtol 1e-10 (4e-6 to 3e-5, far beyond 10 rtol); over the
/// whole fall (`t_end = 1.6`) the landings make the motion itself
/// sensitive (the tip's end differs by 1e-3 between methods at rtol
/// 1e-12) and the largest force was 12,364 to 15,683 over methods and rtol
/// 1e-4 to 1e-12, each run `ok` (docs/model.md, "Forces as results").
pub(crate) fn floor_resolved(peaks: &[crate::model::Peak]) -> bool {
    !peaks
        .iter()
        .any(|p| p.force == crate::model::PeakForce::Floor && p.value > 0.0)
}
