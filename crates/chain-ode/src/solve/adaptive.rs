//! Options shared by the adaptive methods (DOPRI5, BDF).

/// Step-size control of an adaptive method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AdaptiveOptions {
    pub rtol: f64,
    pub atol: f64,
    /// Smallest step allowed before `step_size_too_small`; the effective
    /// floor is never below the rounding limit `1e-14 * max(1, |t|)`.
    pub h_min: f64,
    /// Budget of step attempts (accepted + rejected).
    pub max_steps: u64,
    /// Initial step; `None` picks one (Hairer's algorithm for DOPRI5).
    pub h0: Option<f64>,
    /// DOPRI5 only: return as soon as the stiffness detector fires (for `auto`).
    pub stop_when_stiff: bool,
    /// With `stop_when_stiff`: the stiffness estimate `|lambda|` must also
    /// exceed this (1/time) before DOPRI5 stops.
    pub switch_lambda: f64,
}

impl AdaptiveOptions {
    /// The step floor at time `t`.
    pub fn floor(&self, t: f64) -> f64 {
        self.h_min.max(1e-14 * t.abs().max(1.0))
    }
}
