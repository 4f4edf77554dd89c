//! `auto`: a policy over the registered methods, run by the problem's
//! [`AutoPlan`]: its implicit method (BDF, or gen-alpha) from the start, or
//! the plan's explicit method until its stiffness detector fires with
//! `|lambda|` past the plan's threshold, then the implicit method from that
//! state ([`hands_over`]).  The implicit method runs at the plan's
//! tolerance factor times the asked `rtol` and `atol` (1 for BDF). The plans are the run
//! layer's, from its models (chain-ode's: BDF from the start past the
//! chain's measured crossover damping rate, else DOPRI5 (DOP853 at tight
//! tolerances) to the end for a rigid chain, never handed over mid-run;
//! elastic links handed over only when their axial modes are damped); a
//! problem without a plan runs DOP853 to the end ([`AutoPlan::generic`]).

use super::integrator::{Integrator, Run, Settings, Span};
use super::{registry, Method};
use crate::ode::{Observer, Problem, Status, StepView};

/// Relative tolerance at and below which `auto`'s explicit method is DOP853
/// rather than DOPRI5 (measured on the work-precision diagrams).
pub const AUTO_DOP853_RTOL: f64 = 1e-8;

/// `auto`'s plan for one problem, from its model (the run layer gives it:
/// [`Problem::auto_plan`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoPlan {
    /// The explicit method to start with; `None`: the implicit method from
    /// the start.
    pub explicit: Option<Method>,
    /// Hand over to the implicit method at the first stiffness detection
    /// with `|lambda|` above this (`0`: at the first detection; infinite:
    /// never).
    pub hand_over_above: f64,
    /// The implicit method: [`Method::Bdf`] or [`Method::GenAlpha`].
    pub implicit: Method,
    /// The implicit method runs at this times the asked `rtol` and `atol`
    /// (in (0, 1]; 1 for BDF, whose error follows its tolerance).
    pub implicit_tolerance: f64,
    /// The spectral radius at infinity `gen-alpha` runs with as the
    /// implicit method (`None`: the run's `rho_inf`). `Some(0)` annihilates
    /// the modes it steps over at every step, so that the forces they carry
    /// are their quasi-static values (the elastic chain's: docs/model.md,
    /// "The generalized-alpha method").
    pub implicit_rho_inf: Option<f64>,
}

impl AutoPlan {
    /// The plan for a problem whose model says nothing of its stiffness:
    /// DOP853 to the end, at every `rtol`. The detector measures `|lambda|`
    /// alone, so it cannot tell damped stiffness, where BDF pays, from fast
    /// undamped modes, which BDF must follow too; on BEAM (such modes) the
    /// handover lost at every matched error and DOP853 was the fastest
    /// explicit method (`cargo run --release -p fc-paper-figures --example
    /// beam_auto`, methods §6). A model that knows its stiffness says so in
    /// its own plan (the rigid and the elastic chain do).
    pub fn generic(_rtol: f64) -> Self {
        Self {
            explicit: Some(Method::Dop853),
            hand_over_above: f64::INFINITY,
            implicit: Method::Bdf,
            implicit_tolerance: 1.0,
            implicit_rho_inf: None,
        }
    }
}

/// The explicit method's observer: passes everything on, and stops the run
/// at the first stiffness detection past the plan's threshold.
struct Watch<'a> {
    inner: &'a mut dyn Observer,
    hand_over_above: f64,
    t_end: f64,
    stiff_at: Option<f64>,
}

/// Whether `auto` hands over at a detection of `|lambda|` at `t`: above the
/// plan's threshold, and not at the end (nothing would be left to run).
fn hands_over(t: f64, t_end: f64, lambda: f64, hand_over_above: f64) -> bool {
    lambda > hand_over_above && t < t_end
}

impl Observer for Watch<'_> {
    fn start(&mut self, t0: f64, y0: &[f64], f0: &[f64]) {
        self.inner.start(t0, y0, f0)
    }
    fn step(&mut self, step: &StepView<'_>) {
        self.inner.step(step)
    }
    fn stiff(&mut self, t: f64, lambda: f64) {
        self.inner.stiff(t, lambda);
        if self.stiff_at.is_none() && hands_over(t, self.t_end, lambda, self.hand_over_above) {
            self.stiff_at = Some(t);
        }
    }
    fn stop(&self) -> bool {
        self.stiff_at.is_some() || self.inner.stop()
    }
}

/// `auto`: runs its problem's [`AutoPlan`] through the registry.
pub(crate) const AUTO: Integrator = Integrator {
    name: "auto",
    adaptive: true,
    nonsmooth: false,
    run,
};

/// The explicit method until the watcher hands over, then the implicit
/// method from there.
fn run(problem: &mut dyn Problem, span: &Span<'_>, obs: &mut dyn Observer) -> Run {
    let plan = problem
        .auto_plan()
        .unwrap_or_else(|| AutoPlan::generic(span.settings.rtol));
    // The implicit method's settings (unchanged at a factor of 1).
    let tightened = |s: &Settings| {
        let rho_inf = plan.implicit_rho_inf.unwrap_or(s.rho_inf);
        if plan.implicit_tolerance == 1.0 && rho_inf == s.rho_inf {
            *s
        } else {
            Settings {
                rtol: s.rtol * plan.implicit_tolerance,
                atol: s.atol * plan.implicit_tolerance,
                rho_inf,
                ..*s
            }
        }
    };
    let Some(explicit) = plan.explicit else {
        let settings = tightened(span.settings);
        let whole = Span {
            settings: &settings,
            ..*span
        };
        return registry::run(plan.implicit, problem, &whole, obs);
    };
    let mut watch = Watch {
        inner: obs,
        hand_over_above: plan.hand_over_above,
        t_end: span.t_end,
        stiff_at: None,
    };
    let first = registry::run(explicit, problem, span, &mut watch);
    let handover = watch
        .stiff_at
        .filter(|_| first.outcome.status == Status::Interrupted);
    let Some(t_switch) = handover else {
        return first;
    };
    let done = first.outcome.stats;
    let settings = tightened(&span.settings.after(&done));
    let rest = Span {
        t0: t_switch,
        y0: &first.outcome.y_end,
        t_end: span.t_end,
        settings: &settings,
    };
    let mut second = registry::run(plan.implicit, problem, &rest, obs);
    second.outcome.stats += done;
    second.segments.splice(0..0, first.segments);
    second
}
