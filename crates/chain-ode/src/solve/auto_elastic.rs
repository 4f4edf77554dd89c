//! `auto`'s rule for elastic links: hand over to BDF only where the
//! fastest axial modes are damped enough that BDF need not follow them.
//!
//! DOPRI5's stiffness detector fires on an elastic chain whatever its
//! axial damping: the joint springs put eigenvalues near the imaginary axis
//! at `|lambda| ~ 2 sqrt(K / m)`, and the explicit step sits at that
//! stability limit. When those modes are lightly damped, though, the
//! release of the tip rings them above any tight tolerance, and BDF must
//! resolve them too: it then takes as many steps as DOPRI5, each dearer.
//! (Before this rule, an elastic chain named no chain to `auto`, which
//! handed over at the first detection whatever the damping.)
//! Measured (`docs/elastic-measurements.md`, "auto on elastic chains":
//! span d = 3, n = 50, `EA = 1e6`, rtol 1e-7, t = 1.5), BDF against DOPRI5
//! in wall time: 5.5 times slower at a joint damping ratio `zeta = 0.05`,
//! 1.6 times slower at `0.3`, 6.3 times faster at `1`. The rule: hand over
//! at the first detection only at `zeta >=` [`AUTO_ELASTIC_ZETA`]; below
//! it, stay explicit throughout.

use crate::chain::Chain;
use fc_methods::{AutoPlan, Method, AUTO_DOP853_RTOL};

/// The joint damping ratio `zeta = C / (2 sqrt(K m))` from which `auto`
/// may hand an elastic chain over to BDF: placed between the measured 0.3
/// (BDF still slower) and 1 (BDF faster).
pub const AUTO_ELASTIC_ZETA: f64 = 0.5;

/// The damping ratio `C / (2 sqrt(K m))` of one joint of an elastic
/// chain (`K = EA / l`, `C = eta / l`, `m` a rod's mass); `None` for rigid
/// links.
pub fn joint_damping_ratio(chain: &Chain) -> Option<f64> {
    let k = chain.joint_stiffness()?;
    Some(chain.joint_damping() / (2.0 * (k * chain.mass()).sqrt()))
}

/// `auto`'s plan for an elastic `chain` at `rtol`: the explicit method it
/// starts with (DOPRI5, or DOP853 at `rtol <= 1e-8`, as for a problem that
/// names no chain) and the `|lambda|` past which it hands over to BDF: the
/// first stiffness detection (0) for joints damped at least
/// [`AUTO_ELASTIC_ZETA`], never (infinity) below it.
pub(crate) fn plan(chain: &Chain, rtol: f64) -> AutoPlan {
    let explicit = if rtol <= AUTO_DOP853_RTOL {
        Method::Dop853
    } else {
        Method::Dopri5
    };
    let damped = joint_damping_ratio(chain).is_some_and(|z| z >= AUTO_ELASTIC_ZETA);
    AutoPlan {
        explicit: Some(explicit),
        hand_over_above: if damped { 0.0 } else { f64::INFINITY },
    }
}
