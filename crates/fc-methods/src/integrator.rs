//! The one interface every method implements ([`Integrator`]), what it is
//! told ([`Settings`]) and which parameter sets its accuracy ([`Accuracy`]).

use super::{Segment, Stats};
use crate::ode::{Observer, Outcome, Problem};

/// The parameter that sets a method's accuracy.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Accuracy {
    /// The fixed step `dt` (`run.dt`).
    Step,
    /// The relative tolerance `rtol` (`run.rtol`), with `atol = rtol / 100`
    /// when set through chain-ode's `SolveOptions::at_accuracy`.
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

/// A method: its name, what kind it is, and how it runs any [`Problem`].
///
/// Every method is one file with one constant of this type, listed by one
/// line in [`super::registry`]. Its work counters come from the system it
/// is handed wrapped in a [`Counted`](crate::ode::Counted), never from
/// counting by hand.
pub struct Integrator {
    /// The name on the command line, in scenes and in output. A contract:
    /// never renamed.
    pub name: &'static str,
    /// True if the step adapts to `rtol`/`atol`.
    pub adaptive: bool,
    /// True if it runs only a problem that states itself as a mechanical
    /// system with constraints ([`Problem::nonsmooth`]: `moreau-jean`);
    /// false if it runs any [`OdeSystem`](crate::OdeSystem).
    pub nonsmooth: bool,
    /// Integrates a problem over a span, showing the observer every
    /// accepted step. Never panics and never returns a NaN: a failure is a
    /// status with the last finite state. Leaves `segments` empty unless
    /// the method runs others (then it lists theirs).
    pub run: fn(&mut dyn Problem, &Span<'_>, &mut dyn Observer) -> Run,
}

impl Integrator {
    /// The parameter that sets the accuracy: `rtol` for adaptive methods,
    /// `dt` for fixed-step ones.
    pub fn accuracy(&self) -> Accuracy {
        if self.adaptive {
            Accuracy::Tolerance
        } else {
            Accuracy::Step
        }
    }
}

/// What a method is asked: from `(t0, y0)` to `t_end`, with `settings`.
#[derive(Clone, Copy, Debug)]
pub struct Span<'a> {
    pub t0: f64,
    pub y0: &'a [f64],
    pub t_end: f64,
    pub settings: &'a Settings,
}

/// What a method returns through the registry: its [`Outcome`] and, for a
/// method that runs others (`auto`), which ran over which spans.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    pub outcome: Outcome,
    /// Empty for a method that runs alone (the registry records it).
    pub segments: Vec<Segment>,
}

impl From<Outcome> for Run {
    fn from(outcome: Outcome) -> Self {
        Self {
            outcome,
            segments: Vec::new(),
        }
    }
}

/// A run's options as the integrators read them (the run layer builds them
/// from its own options), with the starting step the tests set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
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
    /// The step caps of a prescribed pivot motion (the adaptive explicit
    /// methods obey them; [`TimeScales::NONE`] by default).
    pub scales: TimeScales,
    /// `gen-alpha`'s spectral radius at infinity, in [`RHO_INF_RANGE`]
    /// (the others ignore it).
    ///
    /// [`RHO_INF_RANGE`]: crate::RHO_INF_RANGE
    pub rho_inf: f64,
}

impl Settings {
    /// The step floor at time `t`.
    pub fn floor(&self, t: f64) -> f64 {
        self.h_min.max(1e-14 * t.abs().max(1.0))
    }

    /// The step floor at `t` of a run that must still reach `t_land` (the
    /// span's end or a time scale's end): never above the distance left nor
    /// above the cap at `t`, so that a span or a time scale shorter than
    /// the rounding floor (`t_end = 1e-15`, a release at `1e-300`) is
    /// integrated rather than refused with `step_size_too_small`.
    pub fn floor_towards(&self, t: f64, t_land: f64) -> f64 {
        self.floor(t)
            .min(t_land - t)
            .min(self.scales.max_step_at(t))
    }

    /// These settings for the rest of a run that already spent `done`'s
    /// step attempts (a handover or a release continues from there): the
    /// budget left, at least one.
    pub fn after(&self, done: &Stats) -> Self {
        Self {
            max_steps: self
                .max_steps
                .saturating_sub(done.steps.saturating_add(done.rejected_steps))
                .max(1),
            ..*self
        }
    }
}

/// The largest steps that resolve a prescribed motion of the problem (time
/// units): at most `max_step` before `until`, a step that lands on `until`
/// exactly, and at most `max_step_after` from there on. An adaptive
/// explicit method's error estimate cannot see a drive that happens
/// between its stages (a jerk shorter than the first step is zero at both
/// the step's ends and at every stage past it); these caps make it see it.
/// The run layer gives them (for the chain: `Pivot::time_scales`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeScales {
    /// The largest step before `until`.
    pub max_step: f64,
    /// The end of the first phase (a smooth jerk's `tau`), landed on
    /// exactly; 0: one phase.
    pub until: f64,
    /// The largest step from `until` on.
    pub max_step_after: f64,
}

impl TimeScales {
    /// No cap: no prescribed motion (for the chain: a fixed, released or
    /// uniformly accelerated pivot).
    pub const NONE: Self = Self {
        max_step: f64::INFINITY,
        until: 0.0,
        max_step_after: f64::INFINITY,
    };

    /// The largest step allowed at `t`.
    pub fn max_step_at(&self, t: f64) -> f64 {
        if t < self.until {
            self.max_step
        } else {
            self.max_step_after
        }
    }

    /// The smallest cap of the run (a fixed step must obey it throughout).
    pub fn smallest(&self) -> f64 {
        if self.until > 0.0 {
            self.max_step.min(self.max_step_after)
        } else {
            self.max_step_after
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A continued run gets what is left of the step attempts, and at
    /// least one; everything else is kept.
    #[test]
    fn a_continued_run_gets_the_steps_left() {
        let s = Settings {
            dt: 0.01,
            rtol: 1e-6,
            atol: 1e-8,
            h_min: 0.0,
            max_steps: 100,
            h0: None,
            scales: TimeScales::NONE,
            rho_inf: crate::DEFAULT_RHO_INF,
        };
        let done = |steps, rejected_steps| Stats {
            steps,
            rejected_steps,
            ..Stats::default()
        };
        let rest = s.after(&done(30, 5));
        assert_eq!(rest.max_steps, 65);
        assert_eq!(
            Settings {
                max_steps: 100,
                ..rest
            },
            s
        );
        assert_eq!(s.after(&done(100, 0)).max_steps, 1);
        assert_eq!(s.after(&done(u64::MAX, 7)).max_steps, 1);
    }
}
