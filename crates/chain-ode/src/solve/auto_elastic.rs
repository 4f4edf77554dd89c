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
//! it, stay explicit throughout. A lightly damped chain whose axial modes
//! are far faster than the fall (`omega_axial sqrt(L/g) >= 1e5`) runs
//! gen-alpha from the start at loose tolerances (`rtol >= 1e-3`), where it
//! was measured to win (docs/model.md, "auto and gen-alpha").

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

/// The loosest `rtol` at which `auto` runs gen-alpha: at tighter
/// tolerances the explicit method's stability-held step already gives an
/// error far below the request, which gen-alpha (second order) can only
/// match in more time (docs/model.md, "auto and gen-alpha").
pub const AUTO_GEN_ALPHA_RTOL: f64 = 1e-3;

/// The axial stiffness, `omega_axial sqrt(L / g)` with
/// `omega_axial = 2 sqrt(K / m)` a joint's fastest axial frequency, from
/// which `auto` runs gen-alpha on a lightly damped elastic chain at
/// `rtol >=` [`AUTO_GEN_ALPHA_RTOL`] (measured: at `n = 20` gen-alpha won
/// at `EA = 1e8`, 2.0e5, not at `1e7`, 6.3e4; docs/model.md).
pub const AUTO_GEN_ALPHA_STIFFNESS: f64 = 1e5;

/// gen-alpha's tolerance under `auto`, as a factor of the asked one: its
/// global error on the folded snap at `rtol = 1e-6` was 115 to 560 times
/// that `rtol` (measured at `n = 20, 50`, `EA = 1e7, 1e8`), so that at a
/// thousandth of the request it lands below it.
pub const AUTO_GEN_ALPHA_TOLERANCE: f64 = 1e-3;

/// The spectral radius at infinity of `auto`'s gen-alpha: 0, so that the
/// axial modes it steps over are annihilated at every step and the
/// tensions they carry are their quasi-static values. At the default 0.9
/// those modes ring on, damped by 10% a step, and the snap's tension came
/// out 3.3 times too high on issue 49's steel rope (160.5 against 48.078,
/// auto at rtol 1e-3; at 0: 48.0767); docs/model.md, "The
/// generalized-alpha method", has the measurements.
pub const AUTO_GEN_ALPHA_RHO_INF: f64 = 0.0;

/// The stiffness ratio ([`axial_stiffness_ratio`]) up to which `auto`
/// starts gen-alpha: the stiffest rope on which it was measured to win
/// (issue 47 H3, remeasured with [`AUTO_GEN_ALPHA_MIN_ATOL`]: at rtol 1e-3
/// and atol 1e-5, bungee at EA = 1e12, ratio 8.9e7: gen-alpha reached t =
/// 0.53 in 100,000 step attempts, DOPRI5 t = 0.0017; the folded snap at
/// EA = 1e12, ratio 2e7, gen-alpha to the end in 51,380 steps, DOPRI5 t =
/// 0.020 in 100,000; docs/model.md, "auto and gen-alpha"). The old edge,
/// 4e5, came from runs at the scenes' atol 1e-10, where gen-alpha's
/// Newton iteration, not its stiffness, stalled it; that case is
/// [`AUTO_GEN_ALPHA_MIN_ATOL`]'s now. Past 1e8 nothing was measured.
pub const AUTO_GEN_ALPHA_MAX_STIFFNESS: f64 = 1e8;

/// The smallest absolute tolerance (`atol` times
/// [`AUTO_GEN_ALPHA_TOLERANCE`], state units) at which `auto` starts
/// gen-alpha: below it gen-alpha's Newton iteration, converged to that
/// tolerance on joints whose springs amplify a state's rounding by `EA/l`,
/// fails at a third of its attempts and the run loses to DOPRI5 (issue 47
/// H3, remeasured: the folded snap at `n = 20`, `EA = 1e8`, rtol 1e-3, 5%
/// damping: at `atol` 1e-6 and 1e-7 gen-alpha took 5,677 and 7,410 steps
/// with 1 and 2 Newton failures in 0.66 and 0.92 s, at 1e-8 26,233 steps
/// with 5,782 failures in 3.6 s, at the scene's 1e-10 162,103 steps with
/// 52,154 failures in 12.5 s, where DOPRI5 took 155,950 steps in 1.9-2.5
/// s; docs/model.md, "auto and gen-alpha").
pub const AUTO_GEN_ALPHA_MIN_ATOL: f64 = 1e-10;

/// `plan` for a run at `atol`: a plan that starts gen-alpha
/// ([`plan`]) at an absolute tolerance below [`AUTO_GEN_ALPHA_MIN_ATOL`]
/// becomes the explicit method's to the end (the plan of a lightly damped
/// chain outside the gen-alpha band); any other plan is itself.
pub(crate) fn within_reach(plan: AutoPlan, rtol: f64, atol: f64) -> AutoPlan {
    let starts_gen_alpha = plan.explicit.is_none() && plan.implicit == Method::GenAlpha;
    if !starts_gen_alpha || atol * plan.implicit_tolerance >= AUTO_GEN_ALPHA_MIN_ATOL {
        return plan;
    }
    AutoPlan {
        explicit: Some(if rtol <= AUTO_DOP853_RTOL {
            Method::Dop853
        } else {
            Method::Dopri5
        }),
        hand_over_above: f64::INFINITY,
        implicit: Method::Bdf,
        implicit_tolerance: 1.0,
        implicit_rho_inf: None,
    }
}

/// The damping ratio of the floor's contact at a rod end resting on it,
/// `zeta = c g sqrt(m_p / k) / 2` for the Hunt–Crossley law `N = k delta
/// (1 + c delta')` (a contact point carries `m_p = m / 2`; at its rest
/// deflection `delta = m_p g / k` the viscous coefficient `k c delta` is
/// `c m_p g`, against `2 sqrt(k m_p)`); `None` without a floor or gravity.
pub fn floor_damping_ratio(chain: &Chain) -> Option<f64> {
    let f = chain.floor()?;
    let g = chain.gravity();
    let m_p = 0.5 * chain.mass();
    (g > 0.0).then(|| f.damping * g * (m_p / f.stiffness).sqrt() / 2.0)
}

/// `omega_axial sqrt(L / g)`, `omega_axial = 2 sqrt(K / m)` (a joint's
/// spring `K = EA / l` and a rod's mass `m`); `None` for rigid links or
/// without gravity (no slow time scale to compare with).
pub fn axial_stiffness_ratio(chain: &Chain) -> Option<f64> {
    let k = chain.joint_stiffness()?;
    let g = chain.gravity();
    (g > 0.0).then(|| 2.0 * (k / chain.mass()).sqrt() * (chain.length() / g).sqrt())
}

/// `auto`'s plan for an elastic `chain` at `rtol`: the explicit method it
/// starts with (DOPRI5, or DOP853 at `rtol <= 1e-8`, as for a problem that
/// names no chain) and the `|lambda|` past which it hands over to BDF: the
/// first stiffness detection (0) for joints or a floor contact damped at
/// least [`AUTO_ELASTIC_ZETA`] ([`floor_damping_ratio`]), never
/// (infinity) below it; except that a lightly
/// damped chain whose axial modes are past [`AUTO_GEN_ALPHA_STIFFNESS`]
/// (and not past [`AUTO_GEN_ALPHA_MAX_STIFFNESS`]) runs gen-alpha from the start (at [`AUTO_GEN_ALPHA_TOLERANCE`] times
/// the tolerance) when `rtol >=` [`AUTO_GEN_ALPHA_RTOL`] (and, applied by
/// the run, [`within_reach`]: its absolute tolerance at least
/// [`AUTO_GEN_ALPHA_MIN_ATOL`]).
pub(crate) fn plan(chain: &Chain, rtol: f64) -> AutoPlan {
    let explicit = if rtol <= AUTO_DOP853_RTOL {
        Method::Dop853
    } else {
        Method::Dopri5
    };
    // A damped stiff contact is a damped stiff mode as the joints' are
    // (issue 47 H1: a plastic floor ran DOPRI5 to the end, 14 times
    // slower than bdf).
    let damped = joint_damping_ratio(chain).is_some_and(|z| z >= AUTO_ELASTIC_ZETA)
        || floor_damping_ratio(chain).is_some_and(|z| z >= AUTO_ELASTIC_ZETA);
    let unresolved = axial_stiffness_ratio(chain)
        .is_some_and(|s| (AUTO_GEN_ALPHA_STIFFNESS..=AUTO_GEN_ALPHA_MAX_STIFFNESS).contains(&s));
    if !damped && unresolved && rtol >= AUTO_GEN_ALPHA_RTOL {
        return AutoPlan {
            explicit: None,
            hand_over_above: f64::INFINITY,
            implicit: Method::GenAlpha,
            implicit_tolerance: AUTO_GEN_ALPHA_TOLERANCE,
            implicit_rho_inf: Some(AUTO_GEN_ALPHA_RHO_INF),
        };
    }
    AutoPlan {
        explicit: Some(explicit),
        hand_over_above: if damped { 0.0 } else { f64::INFINITY },
        implicit: Method::Bdf,
        implicit_tolerance: 1.0,
        implicit_rho_inf: None,
    }
}
