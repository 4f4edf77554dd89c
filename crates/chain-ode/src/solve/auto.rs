//! `auto`: a policy over the registered methods. BDF from the start past
//! the measured crossover damping rate; otherwise DOPRI5 (DOP853 at tight
//! tolerances) until its stiffness detector keeps firing with `|lambda|`
//! past the crossover's `48 gamma`, then BDF from that state; a rigid
//! chain, for which that stiffness is the whip and the waves, is not handed
//! over mid-run ([`hands_over`]). Elastic links hand over only when their
//! axial modes are damped (`auto_elastic`).

use super::integrator::{Integrator, Run, Span};
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
/// An earlier form of the `stiffness` study (span d = 3, t = 1, equal
/// rtol 1e-6, n = 25 to 3200) measured it and fits it as
/// `27 sqrt(g/L) + 0.12 sqrt(g L) / l`: 12 at n = 25 and 168 at n = 3200 in
/// the report's units, an empirical fit. At matched accuracy (error 1e-6)
/// over a fall past the whip (t = 3) the study now measures 11, 15, 28 and
/// 106 at n = 25, 100, 400 and 1600, 0.84 to 1.13 times this rule
/// (`cargo xtask figures --timings --only stiffness`, wall times on a
/// shared machine, known to a factor of about two).
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
    /// The chain's damping rate is its stiffest rod's
    /// ([`Chain::stiffest_damping_rate`]): a profile with one light or short
    /// rod is as stiff as that rod.
    pub fn auto_plan(chain: &Chain, rtol: f64) -> Option<Method> {
        if chain.stiffest_damping_rate() >= bdf_crossover_gamma(chain) {
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
    /// The problem names a rigid chain ([`hands_over`]).
    chain: bool,
}

/// Whether `auto` hands over to BDF at `t`, where the explicit method's
/// stiffness detector reports `|lambda|` (1/time): never for a rigid chain
/// (`chain`), and for any other problem once `lambda` is past
/// `switch_lambda` before `t_end` (an elastic chain's `switch_lambda` is
/// `auto_elastic`'s: 0 when its joints are damped, else infinite). The one
/// place the mid-run policy lives.
///
/// Why no handover on a chain: below the crossover (where `auto` starts
/// explicit) damping's `|lambda| ~ 48 gamma` stays under the handover's
/// `48 gamma_c`, so what the detector meets is the whip and the fast waves,
/// which BDF must follow too. There the explicit method, held at its
/// stability limit, is far more accurate than asked, while BDF at the same
/// tolerance is not, and is no faster. Measured on 400 rods (span d = 3,
/// r = 5e-4, rtol 1e-3, atol 1e-5; `falling-chain simulate` of the span-d3
/// scene with `chain.links=400`), energy-balance error and wall time:
///
/// | t_end | DOPRI5 | BDF | auto handing over (at t = 3.09) |
/// |---|---|---|---|
/// | 4.157 | 2.4e-5, 752 steps | 0.29, 973 steps | 6.6e-2, 623 steps |
/// | 12 | 12.4, 0.70 s | 1.93, 1.77 s | 2.74, 1.25 s |
/// | 30 | 13.5, 1.34 s | 1.93, 6.17 s | 3.37, 5.52 s |
///
/// (and at rtol 1e-2, t_end 4.157: 2.4e-3 for DOPRI5, 2.2 for BDF, 2.41
/// for auto handing over at t = 2.46). An elastic chain hands over at the
/// first detection when its axial modes are damped (`auto_elastic`), and a
/// problem that names no chain does so always.
fn hands_over(chain: bool, t: f64, t_end: f64, lambda: f64, switch_lambda: f64) -> bool {
    !chain && lambda > switch_lambda && t < t_end
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
        if self.stiff_at.is_none()
            && hands_over(self.chain, t, self.t_end, lambda, self.switch_lambda)
        {
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
        chain: problem.chain().is_some_and(|c| !c.is_elastic()),
    };
    let first = registry::run(explicit, problem, span, &mut watch);
    let handover = watch
        .stiff_at
        .filter(|_| first.outcome.status == Status::Interrupted);
    let Some(t_switch) = handover else {
        return first;
    };
    let done = first.outcome.stats;
    let settings = span.settings.after(&done);
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
