//! The one step loop of the explicit adaptive pairs (DOPRI5, DOP853), after
//! argmin's split of a solver from its executor: a method makes one attempt
//! ([`Pair::attempt`]: its stages, its solution and its error norm) and
//! shows an accepted step with its interpolant ([`Pair::show`]); [`run`]
//! owns everything else:
//!
//! * the step budget (accepted + rejected attempts, `max_steps`) and the
//!   step floor ([`Settings::floor_towards`]: never above the distance
//!   left, so that a span shorter than the rounding floor still runs);
//! * landing on `t_end` exactly;
//! * the step caps of a prescribed pivot motion ([`Settings::scales`]:
//!   at most `tau / 16` through a smooth jerk, landing on its end, and
//!   `T / 16` on a harmonic drive);
//! * retrying a non-finite trial [`NONFINITE_SHRINK`] times smaller (ending
//!   `diverged` at the floor);
//! * the PI step-size controller, with each method's [`Control`];
//! * Hairer's stiffness counter, which tells the observer
//!   ([`Observer::stiff`]: `auto` hands over from there);
//! * the cancel check ([`Observer::stop`]) before every attempt.
//!
//! The arithmetic is the methods' own loops', operation for operation.

use super::integrator::{Integrator, Run, Settings, Span};
use super::step_size::initial_step;
use crate::ode::{
    all_finite, Counted, Interpolant, Observer, OdeSystem, Outcome, Problem, Stats, Status,
    StepView,
};

/// A non-finite trial is retried this much smaller (not in Hairer's codes).
pub(crate) const NONFINITE_SHRINK: f64 = 0.2;

/// Stiffness test: `h |lambda|` past the method's bound on this many
/// accepted steps ...
const STIFF_COUNT: u32 = 15;
/// ... without this many clean ones between.
const NONSTIFF_RESET: u32 = 6;

/// A method's step-size control (Hairer's PI controller) and stiffness bound.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Control {
    /// Safety factor on the new step.
    pub safety: f64,
    /// The controller's exponent on the previous error (0: plain I control).
    pub beta: f64,
    /// The exponent on the current error.
    pub expo1: f64,
    /// The new step is at least `fac_min` times the old one ...
    pub fac_min: f64,
    /// ... and at most `fac_max` times.
    pub fac_max: f64,
    /// The stability bound `h |lambda|` of the method's stiffness test.
    pub stiff_hlambda: f64,
}

/// An explicit embedded Runge–Kutta pair, as the step loop sees it. The
/// pair holds its stages; slot `k1` holds `f(t, y)` at the current state.
pub(crate) trait Pair {
    /// The order `p` of the local error `O(h^p)` that sets the starting step.
    const ORDER: u32;
    /// Its controller and stiffness bound.
    const CONTROL: Control;

    /// The pair's buffers for a state of `dim` numbers.
    fn new(dim: usize) -> Self;

    /// `k1` (to be set to `f(t0, y0)` at the start) and two scratch
    /// vectors for the starting step's trial.
    fn parts(&mut self) -> Parts<'_>;

    /// One attempt of the step `s`: its solution in `s.y1` and its error
    /// norm (accepted when at most 1), or `None` when the trial is not
    /// finite (the loop retries smaller). An attempt that passes has every
    /// value the next step and the interpolant need (`f(t1, y1)` among them).
    fn attempt<S: OdeSystem>(&mut self, sys: &mut S, s: &mut Step<'_>) -> Option<f64>;

    /// The stiffness estimate `|lambda|` (1/time) of the step just accepted.
    fn lambda(&self, y1: &[f64]) -> f64;

    /// Shows the accepted step `s` to `obs`, with its interpolant, then makes
    /// `f(t1, y1)` the next step's `k1` (FSAL).
    fn show<S: OdeSystem>(&mut self, sys: &mut S, s: &Step<'_>, obs: &mut dyn Observer);
}

/// `k1` and two scratch vectors, as [`Pair::parts`] gives them.
pub(crate) type Parts<'a> = (&'a mut [f64], (&'a mut [f64], &'a mut [f64]));

/// One step as the loop hands it to a pair: from `(t, y)` by `h` to `t1`
/// (`t + h`, or `t_end` exactly; time units of the problem), the solution
/// going to `y1`, measured against the run's tolerances `o`.
pub(crate) struct Step<'a> {
    pub t: f64,
    pub t1: f64,
    pub h: f64,
    pub y: &'a [f64],
    pub y1: &'a mut [f64],
    pub o: &'a Settings,
}

impl Step<'_> {
    /// The accepted step as observers see it, with `f1 = f(t1, y1)` and the
    /// pair's interpolant.
    pub(crate) fn view<'v>(&'v self, f1: &'v [f64], dense: &'v dyn Interpolant) -> StepView<'v> {
        StepView {
            t0: self.t,
            t1: self.t1,
            y0: self.y,
            y1: self.y1,
            f1,
            interpolant: dense,
        }
    }
}

/// A pair's working storage for a state of `d` numbers: its stages `k` (in
/// the pair's own layout, `k1` first), a stage's state `ys`, a vector `aux`
/// of the pair's own (DOPRI5: the error estimate; DOP853: `f1`) and `rows`
/// vectors of dense-output coefficients `rcont`. `ys` and `aux` are the
/// starting step's scratch.
pub(crate) struct Stages<K> {
    pub k: K,
    pub ys: Vec<f64>,
    pub aux: Vec<f64>,
    pub rcont: Vec<f64>,
}

impl<K> Stages<K> {
    /// The stages `k` and zeroed buffers for a state of `d` numbers with
    /// `rows` rows of dense output.
    pub(crate) fn with(k: K, d: usize, rows: usize) -> Self {
        Self {
            k,
            ys: vec![0.0; d],
            aux: vec![0.0; d],
            rcont: vec![0.0; rows * d],
        }
    }
}

/// `sqrt(|ka - kb|^2 / |y1 - ys|^2)`: Hairer's estimate of `|lambda|` from
/// two stages `ka = f(ys)`, `kb = f(y1)` at the same time (0 if `ys = y1`).
pub(crate) fn lambda_estimate(ka: &[f64], kb: &[f64], y1: &[f64], ys: &[f64]) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for i in 0..y1.len() {
        num += (kb[i] - ka[i]).powi(2);
        den += (y1[i] - ys[i]).powi(2);
    }
    if den > 0.0 {
        (num / den).sqrt()
    } else {
        0.0
    }
}

/// Integrates `sys` over `s` (from `(t0, y0)` to `t_end > t0`, with
/// `settings`) with the pair `P`: observers see every accepted step with `f1 = f(t1, y1)` and the pair's
/// interpolant; the run ends on `t_end` or with a status, at the last
/// finite state. Every right-hand side is counted.
pub(crate) fn run<P, S>(sys: &mut S, s: &Span<'_>, obs: &mut dyn Observer) -> Outcome
where
    P: Pair,
    S: OdeSystem + ?Sized,
{
    Counted::run(sys, |sys| steps::<P, _>(sys, s, obs))
}

/// The registry's entry of the adaptive pair `P`, named `name`: it runs
/// any problem through [`run`].
pub(crate) const fn integrator<P: Pair>(name: &'static str) -> Integrator {
    Integrator {
        name,
        adaptive: true,
        nonsmooth: false,
        run: run_span::<P>,
    }
}

fn run_span<P: Pair>(p: &mut dyn Problem, s: &Span<'_>, obs: &mut dyn Observer) -> Run {
    run::<P, _>(p, s, obs).into()
}

fn steps<P: Pair, S: OdeSystem>(sys: &mut S, asked: &Span<'_>, obs: &mut dyn Observer) -> Outcome {
    let Span {
        t0,
        y0,
        t_end,
        settings: o,
    } = *asked;
    let c = P::CONTROL;
    let d = sys.dim();
    let mut stats = Stats::default();
    let mut pair = P::new(d);
    let mut y = y0.to_vec();
    let mut y1 = vec![0.0; d];

    let (f0, _) = pair.parts();
    sys.rhs(t0, &y, f0);
    if !all_finite(f0) {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y);
    }
    obs.start(t0, &y, f0);

    let span = t_end - t0;
    let mut h = match o.h0 {
        Some(h) => h.min(span),
        None => {
            let (f0, scratch) = pair.parts();
            initial_step(sys, t0, &y, f0, span, o, P::ORDER, scratch)
        }
    };
    let mut t = t0;
    let mut fac_old: f64 = 1e-4;
    let mut last_rejected = false;
    let mut last_nonfinite = false;
    let (mut stiff_steps, mut nonstiff_steps) = (0u32, 0u32);

    while t < t_end {
        if stats.steps + stats.rejected_steps >= o.max_steps {
            return Outcome::ended(Status::MaxSteps, t, Some(t), stats, y);
        }
        if obs.stop() {
            return Outcome::ended(Status::Interrupted, t, Some(t), stats, y);
        }
        // A prescribed pivot motion's time scale: no step longer than its
        // cap, and a step that lands on the end of its first phase.
        h = h.min(o.scales.max_step_at(t));
        let until = o.scales.until;
        let land = if t < until && until < t_end {
            until
        } else {
            t_end
        };
        let floor = o.floor_towards(t, land);
        if h < floor {
            let status = if last_nonfinite {
                Status::Diverged
            } else {
                Status::StepSizeTooSmall
            };
            return Outcome::ended(status, t, Some(t + h), stats, y);
        }
        // Land on t_end (or the time scale's end) exactly; stretch a step
        // that would leave a sliver.
        let mut t1 = t + h;
        if t1 > land - 1e-10 * h {
            t1 = land;
            h = land - t;
        }

        let mut s = Step {
            t,
            t1,
            h,
            y: &y,
            y1: &mut y1,
            o,
        };
        let Some(e) = pair.attempt(sys, &mut s) else {
            // A non-finite trial: retry much smaller; give up at the floor.
            stats.rejected_steps += 1;
            last_rejected = true;
            last_nonfinite = true;
            h *= NONFINITE_SHRINK;
            continue;
        };
        last_nonfinite = false;

        let fac11 = e.powf(c.expo1);
        if e <= 1.0 {
            // Accepted.
            let fac =
                (fac11 / fac_old.powf(c.beta) / c.safety).clamp(1.0 / c.fac_max, 1.0 / c.fac_min);
            let mut h_new = h / fac;
            fac_old = e.max(1e-4);
            stats.steps += 1;

            // Stiffness detection: h |lambda| past the bound, often enough.
            let lambda = pair.lambda(s.y1);
            let mut stiff_now = false;
            if h * lambda > c.stiff_hlambda {
                nonstiff_steps = 0;
                stiff_steps += 1;
                if stiff_steps == STIFF_COUNT {
                    stats.stiffness_detections += 1;
                    stiff_steps = 0;
                    stiff_now = true;
                }
            } else {
                nonstiff_steps += 1;
                if nonstiff_steps == NONSTIFF_RESET {
                    stiff_steps = 0;
                }
            }

            pair.show(sys, &s, obs);
            std::mem::swap(&mut y, &mut y1);
            t = t1;
            if last_rejected {
                h_new = h_new.min(h);
            }
            last_rejected = false;
            h = h_new;
            if stiff_now {
                obs.stiff(t, lambda);
            }
        } else {
            stats.rejected_steps += 1;
            last_rejected = true;
            h /= (fac11 / c.safety).min(1.0 / c.fac_min);
        }
    }
    Outcome::ended(Status::Ok, t, None, stats, y)
}
