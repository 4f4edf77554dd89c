//! gen-alpha's policy: every constant of its step control and of its
//! Newton matrix's reuse in one value, each measured on the folded elastic
//! snap (docs/model.md, "The generalized-alpha method"), and a way to run
//! the method with another policy (the measurements' own ablations; never
//! a user's setting).

use std::cell::Cell;

/// The step controller's constants ([`super::control`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ControlPolicy {
    /// The safety factor on the proposed step.
    pub safety: f64,
    /// The exponent of `1 / err` (`1/3` would be the elementary
    /// controller of a local error `O(h^3)`).
    pub k_err: f64,
    /// The exponent of the previous accepted step's `err` (the PI
    /// filter's proportional part; 0: the elementary controller).
    pub k_prev: f64,
    /// After an accepted step, a proposed factor in `[dead_lo, dead_hi]`
    /// keeps `h` as it is.
    pub dead_lo: f64,
    pub dead_hi: f64,
    /// The largest factor per step.
    pub grow_max: f64,
    /// The smallest factor after an accepted step.
    pub shrink_accepted: f64,
    /// The smallest factor after a failed error test.
    pub shrink_min: f64,
}

/// When the kept Jacobian is evaluated again ([`super::newton`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReusePolicy {
    /// A step whose Newton corrections contracted by more than this per
    /// iteration (`theta`) leaves the Jacobian stale for the next step.
    pub theta_refresh: f64,
    /// Within an attempt, a contraction at least this with an older
    /// Jacobian evaluates it again at the iterate.
    pub theta_slow: f64,
    /// Within an attempt, the iterations an older Jacobian gets to
    /// converge (at its measured rate) before it is evaluated again.
    pub stale_iters: u32,
    /// The most accepted steps a Jacobian is kept.
    pub max_age: u64,
}

/// Every constant of gen-alpha's step and Newton policy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GenAlphaPolicy {
    pub control: ControlPolicy,
    pub reuse: ReusePolicy,
    /// Move the derivative sequence to the new step's time at each change
    /// of the step (`v + c (h' - h) d''`).
    pub shift: bool,
    /// A fixed step instead of the controller (a measurement's baseline;
    /// a failed Newton iteration still retries smaller).
    pub fixed_step: Option<f64>,
    /// Measure the local error on every differential unknown whatever the
    /// problem's configuration (a measurement's variant).
    pub measure_all: bool,
    /// Bound the errors of the problem's measured quantities
    /// ([`crate::Problem::measured`]). Off by default: on issue 49's steel
    /// rope (the elastic chain's pivot force measured) it took 30 to 130
    /// times the steps and still left the snap's tension 29% high at rtol
    /// 1e-3 (the filtered error estimate does not see the stepped-over
    /// modes that carry it); `rho_inf = 0` recovers it (docs/model.md).
    pub measured: bool,
    /// The quadratic dense output (else linear, and `f1` the model's
    /// derivative).
    pub quadratic: bool,
    /// Filter the local error estimate by the Newton matrix (`(E - beta
    /// J)^-1 e`; else the raw estimate: a measurement's variant; on the
    /// undamped chain it changed the energy's drift by 30%, not its
    /// sign).
    pub filter: bool,
    /// Newton's stopping tolerance as a fraction of RADAU5's
    /// (`max(10 eps / rtol, min(sqrt(rtol), 0.03))` in the error norm).
    /// At RADAU5's own (1) the iterate, stopped short of the implicit
    /// solution towards the explicit predictor with a kept Jacobian,
    /// pumped energy into the undamped chain at every whip (issue 49.5:
    /// `scenes/horizontal-undamped.toml` at a fixed step `1e-4`, rtol
    /// `1e-6`, `+1.6e-6 M g L` by t = 30; at `0.01`, `-7e-9`, and the
    /// adaptive run's gain to t = 120 from `8.0e-5` to `6.9e-5`,
    /// docs/model.md). Only where the local error is measured on every
    /// unknown (the problem names no configuration: the rigid chain
    /// without bending springs, whose modes the step resolves); where the
    /// step damps modes it does not resolve (the elastic chain) the
    /// tighter tolerance is not reachable and RADAU5's is kept (issue
    /// 49's steel rope cut to 10 rods at rtol 1e-8: 1,805,178 steps
    /// against 45,498).
    pub newton_tol: f64,
}

impl GenAlphaPolicy {
    /// The method's policy (docs/model.md gives the measurement behind
    /// each value).
    pub const DEFAULT: Self = Self {
        control: ControlPolicy {
            safety: 0.9,
            // Gustafsson's PI controller (k_I = 0.3 / k, k_P = 0.4 / k,
            // k = 3).
            k_err: 0.7 / 3.0,
            k_prev: 0.4 / 3.0,
            dead_lo: 1.0,
            dead_hi: 1.5,
            grow_max: 2.0,
            shrink_accepted: 0.2,
            shrink_min: 0.2,
        },
        reuse: ReusePolicy {
            theta_refresh: 0.3,
            theta_slow: 0.5,
            stale_iters: 5,
            max_age: 50,
        },
        shift: true,
        fixed_step: None,
        quadratic: true,
        filter: true,
        newton_tol: 0.01,
        measure_all: false,
        measured: false,
    };
}

impl Default for GenAlphaPolicy {
    fn default() -> Self {
        Self::DEFAULT
    }
}

thread_local! {
    static POLICY: Cell<GenAlphaPolicy> = const { Cell::new(GenAlphaPolicy::DEFAULT) };
}

/// The policy gen-alpha runs with on this thread.
pub(crate) fn current() -> GenAlphaPolicy {
    POLICY.with(Cell::get)
}

/// Runs `f` with gen-alpha's `policy` on this thread (then the default
/// again): the measurements behind the policy's constants vary them one at
/// a time (docs/model.md).
pub fn with_gen_alpha_policy<R>(policy: GenAlphaPolicy, f: impl FnOnce() -> R) -> R {
    struct Restore(GenAlphaPolicy);
    impl Drop for Restore {
        fn drop(&mut self) {
            POLICY.with(|p| p.set(self.0));
        }
    }
    let _restore = Restore(POLICY.with(|p| p.replace(policy)));
    f()
}
