//! The one interface every method implements ([`Integrator`]), what it is
//! told ([`Settings`]) and which parameter sets its accuracy ([`Accuracy`]).

use super::SolveOptions;
use crate::ode::{Observer, Outcome};
use crate::system::ChainSystem;

/// The parameter that sets a method's accuracy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Accuracy {
    /// The fixed step `dt` (`run.dt`).
    Step,
    /// The relative tolerance `rtol` (`run.rtol`), with `atol = rtol / 100`
    /// when set through [`SolveOptions::at_accuracy`].
    Tolerance,
}

impl Accuracy {
    /// The parameter's name: `"dt"` or `"rtol"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Step => "dt",
            Self::Tolerance => "rtol",
        }
    }
}

/// A method: its name, what kind it is, and how it runs a chain.
///
/// Every method is one file with one implementation of this trait, listed by
/// one line in [`super::registry`]. Its work counters come from the system it
/// is handed wrapped in a [`Counted`](crate::ode::Counted), never from
/// counting by hand.
pub(crate) trait Integrator {
    /// The name on the command line, in scenes and in output. A contract:
    /// never renamed.
    fn name(&self) -> &'static str;

    /// True if the step adapts to `rtol`/`atol`.
    fn adaptive(&self) -> bool;

    /// The parameter that sets the accuracy: `rtol` for adaptive methods,
    /// `dt` for fixed-step ones.
    fn accuracy(&self) -> Accuracy {
        if self.adaptive() {
            Accuracy::Tolerance
        } else {
            Accuracy::Step
        }
    }

    /// Integrates from `(t0, y0)` to `t_end`, showing `obs` every accepted
    /// step. Never panics and never returns a NaN: a failure is a status with
    /// the last finite state. Leaves `segments` empty unless the method runs
    /// others (then it lists theirs).
    fn integrate(
        &self,
        sys: &mut ChainSystem,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        settings: &Settings,
        obs: &mut dyn Observer,
    ) -> Outcome;
}

/// A run's options as the integrators read them: [`SolveOptions`], plus
/// what `auto` sets when it runs another method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Settings {
    /// Fixed step (RK4).
    pub dt: f64,
    pub rtol: f64,
    pub atol: f64,
    /// Smallest step allowed before `step_size_too_small`; the effective
    /// floor is never below the rounding limit `1e-14 * max(1, |t|)`.
    pub h_min: f64,
    /// Budget of step attempts (accepted + rejected).
    pub max_steps: u64,
    /// Initial step; `None` picks one (Hairer's algorithm for DOPRI5).
    pub h0: Option<f64>,
    /// Explicit adaptive methods only: return as soon as the stiffness
    /// detector fires (for `auto`).
    pub stop_when_stiff: bool,
    /// With `stop_when_stiff`: the stiffness estimate `|lambda|` must also
    /// exceed this (1/time) before the method stops.
    pub switch_lambda: f64,
}

impl Settings {
    /// The settings of a run with these options.
    pub fn of(options: &SolveOptions) -> Self {
        Self {
            dt: options.dt,
            rtol: options.rtol,
            atol: options.atol,
            h_min: options.h_min,
            max_steps: options.max_steps,
            h0: None,
            stop_when_stiff: false,
            switch_lambda: 0.0,
        }
    }

    /// The step floor at time `t`.
    pub fn floor(&self, t: f64) -> f64 {
        self.h_min.max(1e-14 * t.abs().max(1.0))
    }
}
