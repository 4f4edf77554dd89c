//! `auto`: a policy over the registered methods. BDF from the start past
//! the measured crossover damping rate; otherwise DOPRI5 (DOP853 at tight
//! tolerances) until its stiffness detector keeps firing with `|lambda|`
//! past the crossover's `48 gamma`, then BDF from that state. Elastic links
//! hand over only when their axial modes are damped (`auto_elastic`).

use super::integrator::{Integrator, Run, Settings, Span};
use super::{registry, Method};
use crate::chain::Chain;
use crate::ode::{Observer, Problem, Status, StepView};

/// The damping rate `gamma = r / (m l^2)` (1/time) past which the O(n) BDF
/// overtakes DOPRI5 on this chain, and from which `auto` runs BDF from the
/// start.
///
/// An explicit step is held below `~3.3 / |lambda|`, and the chain has two
/// fast rates: damping, `|lambda| ~ 48 gamma`, and its fastest undamped mode,
/// `omega_max ~ 3.4 sqrt(g L) / l` (the hanging chain's top frequency; it
/// grows like n). So the crossover grows with n once `omega_max` dominates.
/// The `stiffness` study (span d = 3, t = 1, rtol 1e-6, n = 25 to 3200)
/// measured it and fits it as `27 sqrt(g/L) + 0.12 sqrt(g L) / l`: 12 at
/// n = 25 and 168 at n = 3200 in the report's units.
pub fn bdf_crossover_gamma(chain: &Chain) -> f64 {
    let (g, big_l) = (chain.gravity(), chain.length());
    27.0 * (g / big_l).sqrt() + 0.12 * (g * big_l).sqrt() / chain.rod_length()
}

/// Relative tolerance at and below which `auto`'s explicit method is DOP853
/// rather than DOPRI5 (measured on the work-precision diagrams).
pub(crate) const AUTO_DOP853_RTOL: f64 = 1e-8;

impl Method {
    /// The methods `auto` runs for this chain and tolerance: the explicit one
    /// it starts with (none when the chain is past the crossover), and BDF.
    pub fn auto_plan(chain: &Chain, rtol: f64) -> Option<Method> {
        if chain.damping_rate() >= bdf_crossover_gamma(chain) {
            None
        } else if rtol <= AUTO_DOP853_RTOL {
            Some(Method::Dop853)
        } else {
            Some(Method::Dopri5)
        }
    }
}

/// The explicit method `auto` starts with on `problem` (none: BDF from the
/// start), and the stiffness estimate `|lambda|` (1/time) past which it
/// hands over. A rigid chain places both from its crossover, an elastic
/// one from its joint damping (`auto_elastic`); a problem that names no
/// chain starts explicit and hands over at the first detection.
fn plan(problem: &dyn Problem, rtol: f64) -> (Option<Method>, f64) {
    match problem.chain() {
        Some(chain) if chain.is_elastic() => super::auto_elastic::plan(chain, rtol),
        Some(chain) => (
            Method::auto_plan(chain, rtol),
            48.0 * bdf_crossover_gamma(chain),
        ),
        None if rtol <= AUTO_DOP853_RTOL => (Some(Method::Dop853), 0.0),
        None => (Some(Method::Dopri5), 0.0),
    }
}

/// Watches the explicit method for `auto`: passes everything on, and once
/// the stiffness detector fires with `|lambda|` past `switch_lambda` (before
/// `t_end`), asks the method to stop there: the handover.
struct Watch<'a> {
    inner: &'a mut dyn Observer,
    switch_lambda: f64,
    t_end: f64,
    stiff_at: Option<f64>,
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
        // Hand over only where the implicit method should be cheaper: its
        // LU costs grow with the problem, while the explicit cost per unit
        // time grows like dim |lambda|.
        if lambda > self.switch_lambda && t < self.t_end && self.stiff_at.is_none() {
            self.stiff_at = Some(t);
        }
    }
    fn stop(&self) -> bool {
        self.stiff_at.is_some() || self.inner.stop()
    }
}

/// `auto`: runs [`Method::auto_plan`]'s methods through the registry.
pub(crate) const AUTO: Integrator = Integrator {
    name: "auto",
    adaptive: true,
    run,
};

/// The explicit method until the watcher hands over, then BDF from there.
fn run(problem: &mut dyn Problem, span: &Span<'_>, obs: &mut dyn Observer) -> Run {
    let (explicit, switch_lambda) = plan(problem, span.settings.rtol);
    let Some(explicit) = explicit else {
        return registry::run(Method::Bdf, problem, span, obs);
    };
    let mut watch = Watch {
        inner: obs,
        switch_lambda,
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
    // What is left of the step budget.
    let settings = Settings {
        max_steps: span
            .settings
            .max_steps
            .saturating_sub(done.steps + done.rejected_steps)
            .max(1),
        ..*span.settings
    };
    let rest = Span {
        t0: t_switch,
        y0: &first.outcome.y_end,
        t_end: span.t_end,
        settings: &settings,
    };
    let mut second = registry::run(Method::Bdf, problem, &rest, obs);
    second.outcome.stats += done;
    second.segments.splice(0..0, first.segments);
    second
}
