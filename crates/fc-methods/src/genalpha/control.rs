//! gen-alpha's step controller, built for a method that steps over modes:
//! it changes `h` rarely and smoothly (each change costs an LU and
//! disturbs the method's derivative sequence), by a PI filter of the error
//! estimates, a dead band inside which the step is kept, and a growth
//! limit. docs/model.md, "The generalized-alpha method", has the
//! measurements behind each part.

use super::policy::ControlPolicy;

/// The controller's memory: the last accepted step's error, and whether
/// the last attempt failed.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Controller {
    policy: ControlPolicy,
    err_prev: Option<f64>,
    after_reject: bool,
}

impl Controller {
    pub fn new(policy: ControlPolicy) -> Self {
        Self {
            policy,
            err_prev: None,
            after_reject: false,
        }
    }

    /// The factor on `h` after an accepted step of error `err` (in the
    /// tolerance's units, at most 1): 1 inside the dead band, at most
    /// `grow_max`, and at most 1 right after a rejection.
    pub fn accepted(&mut self, err: f64) -> f64 {
        let p = &self.policy;
        let e = err.max(1e-10);
        let mut fac = p.safety * e.powf(-p.k_err);
        if let Some(prev) = self.err_prev {
            fac *= prev.max(1e-10).powf(p.k_prev);
        }
        self.err_prev = Some(e);
        if self.after_reject {
            fac = fac.min(1.0);
        }
        self.after_reject = false;
        if (p.dead_lo..=p.dead_hi).contains(&fac) {
            1.0
        } else {
            fac.clamp(p.shrink_accepted, p.grow_max)
        }
    }

    /// The factor on `h` after a failed error test of error `err` (> 1, or
    /// not finite).
    pub fn rejected(&mut self, err: f64) -> f64 {
        let p = &self.policy;
        self.after_reject = true;
        if err.is_finite() {
            (p.safety * err.powf(-1.0 / 3.0)).clamp(p.shrink_min, 1.0)
        } else {
            p.shrink_min
        }
    }

    /// After a failed Newton iteration: the next accepted step does not grow.
    pub fn newton_failed(&mut self) {
        self.after_reject = true;
    }
}
