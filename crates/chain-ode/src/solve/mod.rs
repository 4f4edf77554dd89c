//! One way to run any method on any chain: [`solve`].
//!
//! Every method is one file with one [`Integrator`](integrator::Integrator)
//! (its name, whether it is adaptive, its accuracy parameter, how it runs),
//! listed by one line in [`registry`] next to its [`Method`] variant.
//! `auto` is a policy over the registry (`auto.rs`). Work counters come from
//! a [`Counted`](crate::ode::Counted) system, never from counting by hand.

mod auto;
mod bdf;
mod bdf_dense;
mod diffsol_driver;
mod dop853;
mod dopri5;
mod integrator;
#[cfg(test)]
mod known_solutions;
mod observer;
mod registry;
mod rk4;
mod sparse_lu;
mod step_size;
#[cfg(test)]
mod test_problems;

use std::fmt;
use std::str::FromStr;
use std::time::Instant;

use crate::chain::{check, Chain, InvalidParameter};
use crate::kinematics::{tip, tip_velocity, Vec2};
use crate::ode::{Cancel, Stats, Status};
use crate::state::State;
use crate::system::ChainSystem;
pub use auto::bdf_crossover_gamma;
pub use integrator::Accuracy;
use integrator::Settings;
use observer::ChainObserver;

/// An integration method. The variant is the public handle; its name and
/// kind come from its integrator in the registry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Classical fixed-step Runge–Kutta 4 (`dt`).
    Rk4,
    /// Adaptive Dormand–Prince 5(4) with dense output (`rtol`, `atol`).
    Dopri5,
    /// Adaptive Dormand–Prince 8(5,3) with 7th-order dense output, for tight
    /// tolerances (`rtol`, `atol`).
    Dop853,
    /// Implicit variable-order BDF from diffsol on the banded DAE, sparse LU:
    /// O(n) per step (`rtol`, `atol`).
    Bdf,
    /// diffsol's BDF on the explicit form with a dense Jacobian and dense LU:
    /// O(n^3) per factorisation, kept as the reference for `bdf` (`rtol`, `atol`).
    BdfDense,
    /// BDF where the damping rate is past the measured crossover; otherwise
    /// DOPRI5 (DOP853 at tight tolerances), handing over to BDF when the
    /// stiffness detector keeps firing with an eigenvalue past the crossover.
    Auto,
}

impl Method {
    /// Every method, in the order figures list them (the registry's).
    pub const ALL: [Method; registry::REGISTRY.len()] = registry::methods();

    /// The name used on the command line, in scenes and in output.
    pub fn as_str(self) -> &'static str {
        registry::integrator(self).name()
    }

    /// True if the method adapts its step to `rtol`/`atol`.
    pub fn adaptive(self) -> bool {
        registry::integrator(self).adaptive()
    }

    /// The parameter that sets the method's accuracy.
    pub fn accuracy(self) -> Accuracy {
        registry::integrator(self).accuracy()
    }

    /// The name of that parameter: `"dt"` or `"rtol"`.
    pub fn accuracy_name(self) -> &'static str {
        self.accuracy().name()
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for Method {
    type Err = InvalidParameter;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        registry::named(s).ok_or_else(|| InvalidParameter {
            field: "run.method",
            accepted: registry::accepted_names(),
            got: s.to_string(),
        })
    }
}

/// Options of a run. Defaults: `t_end = 1`, `dt = 0.01`, `rtol = 1e-8`,
/// `atol = 1e-10`, no output samples, at most 10^8 steps.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveOptions {
    /// End time (time units of the chain's `g`).
    pub t_end: f64,
    /// Fixed step of RK4.
    pub dt: f64,
    /// Relative tolerance of adaptive methods.
    pub rtol: f64,
    /// Absolute tolerance of adaptive methods.
    pub atol: f64,
    /// Spacing of recorded samples; `None` keeps only the summary.
    pub output_dt: Option<f64>,
    /// Step budget; a run that needs more ends with `max_steps`.
    pub max_steps: u64,
    /// Smallest adaptive step before `step_size_too_small` (0: the rounding limit).
    pub h_min: f64,
    /// A flag that stops the run from outside (`Status::Interrupted`);
    /// `None` runs to the end.
    pub cancel: Option<Cancel>,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            t_end: 1.0,
            dt: 0.01,
            rtol: 1e-8,
            atol: 1e-10,
            output_dt: None,
            max_steps: 100_000_000,
            h_min: 0.0,
            cancel: None,
        }
    }
}

impl SolveOptions {
    /// These options with `method`'s accuracy parameter set to `x`: `dt = x`
    /// for a fixed-step method, `rtol = x` and `atol = x / 100` for an
    /// adaptive one.
    pub fn at_accuracy(mut self, method: Method, x: f64) -> Self {
        match method.accuracy() {
            Accuracy::Step => self.dt = x,
            Accuracy::Tolerance => {
                self.rtol = x;
                self.atol = x * 1e-2;
            }
        }
        self
    }

    /// Checks every field; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), InvalidParameter> {
        let pos = |x: f64| x.is_finite() && x > 0.0;
        check(
            pos(self.t_end),
            "run.t_end",
            "a finite number > 0",
            self.t_end,
        )?;
        check(pos(self.dt), "run.dt", "a finite number > 0", self.dt)?;
        check(
            pos(self.rtol) && self.rtol < 1.0,
            "run.rtol",
            "a number in (0, 1)",
            self.rtol,
        )?;
        check(pos(self.atol), "run.atol", "a finite number > 0", self.atol)?;
        if let Some(o) = self.output_dt {
            check(pos(o), "run.output_dt", "a finite number > 0", o)?;
        }
        check(
            self.h_min.is_finite() && self.h_min >= 0.0,
            "run.h_min",
            "a finite number >= 0",
            self.h_min,
        )?;
        check(
            self.max_steps > 0,
            "run.max_steps",
            "an integer > 0",
            self.max_steps,
        )
    }
}

/// The scalar results of a run: what `simulate --json` prints.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// `E(0) = T + V` at the start.
    pub energy_start: f64,
    /// `E` at `t_reached`.
    pub energy_end: f64,
    /// Work `W` dissipated by joint friction up to `t_reached`.
    pub dissipated: f64,
    /// `max |E + W - E(0)|` over every step.
    pub energy_balance_error: f64,
    /// Largest rise of `E` from one step to the next (0 if it never rose).
    pub max_energy_rise: f64,
    /// Tip position at `t_reached`.
    pub tip_end: Vec2,
    /// Tip velocity at `t_reached`.
    pub tip_velocity_end: Vec2,
    /// Continuous maximum of the exact tip speed over the run.
    pub tip_speed_max: f64,
    /// When it happened.
    pub t_tip_speed_max: f64,
    /// Wall time of the integration (s).
    pub wall_seconds: f64,
}

impl Summary {
    /// True if every field is finite. `solve` never reports a run as `ok`
    /// when this is false: such a run ends `diverged`.
    pub fn all_finite(&self) -> bool {
        [
            self.energy_start,
            self.energy_end,
            self.dissipated,
            self.energy_balance_error,
            self.max_energy_rise,
            self.tip_end[0],
            self.tip_end[1],
            self.tip_velocity_end[0],
            self.tip_velocity_end[1],
            self.tip_speed_max,
            self.t_tip_speed_max,
            self.wall_seconds,
        ]
        .iter()
        .all(|v| v.is_finite())
    }
}

/// The time span over which one method ran (several for `auto`).
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    pub method: Method,
    pub t_start: f64,
    pub t_end: f64,
}

/// A finished run: samples, summary, work counters and how it ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory {
    pub chain: Chain,
    /// The pivot `P0`.
    pub anchor: Vec2,
    pub method: Method,
    pub status: Status,
    /// The requested end time.
    pub t_end: f64,
    /// The last time with a finite state.
    pub t_reached: f64,
    /// When the run failed, if it did.
    pub t_failed: Option<f64>,
    pub stats: Stats,
    pub segments: Vec<Segment>,
    pub summary: Summary,
    /// Sample times (`output_dt` apart, plus the final time).
    pub times: Vec<f64>,
    /// Samples, `2 n + 1` numbers each: angles, rates, dissipated work.
    states: Vec<f64>,
    /// The state at `t_reached`.
    pub final_state: Vec<f64>,
}

/// One recorded sample of a trajectory.
#[derive(Clone, Copy, Debug)]
pub struct Sample<'a> {
    pub t: f64,
    pub angles: &'a [f64],
    pub rates: &'a [f64],
    pub dissipated: f64,
}

impl Trajectory {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// True if no samples were recorded.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Sample `k`.
    pub fn sample(&self, k: usize) -> Sample<'_> {
        let n = self.chain.links;
        let y = &self.states[k * (2 * n + 1)..(k + 1) * (2 * n + 1)];
        Sample {
            t: self.times[k],
            angles: &y[..n],
            rates: &y[n..2 * n],
            dissipated: y[2 * n],
        }
    }

    /// All samples in time order.
    pub fn samples(&self) -> impl Iterator<Item = Sample<'_>> + '_ {
        (0..self.len()).map(|k| self.sample(k))
    }
}

/// Runs `method` on `chain` from `start` over `[0, options.t_end]`.
///
/// Never panics on a failing run and never returns a NaN in its state: a run
/// that hits a non-finite value stops with `Status::Diverged` at the last
/// finite state. A run whose every state is finite but whose summary is not
/// (an energy that overflows, say) also ends `Status::Diverged`, with
/// `t_failed` the first time a non-finite value was recorded: a NaN or an
/// infinity in the summary never comes with `Status::Ok`.
pub fn solve(
    chain: &Chain,
    start: &State,
    method: Method,
    options: &SolveOptions,
) -> Result<Trajectory, InvalidParameter> {
    chain.validate()?;
    options.validate()?;
    let n = chain.links;
    check(
        start.angles.len() == n && start.rates.len() == n,
        "start",
        "a state with chain.links angles and rates",
        start.angles.len(),
    )?;
    let mut sys = ChainSystem::new(chain);
    let y0 = ChainSystem::pack(&start.angles, &start.rates, 0.0);
    let mut obs = ChainObserver::new(chain, options.output_dt);
    let clock = Instant::now();
    let settings = Settings::of(options);
    let outcome = registry::run(
        method,
        &mut sys,
        0.0,
        &y0,
        options.t_end,
        &settings,
        &mut obs,
    );
    let wall_seconds = clock.elapsed().as_secs_f64();
    obs.finish(outcome.t_reached, &outcome.y_end);
    let y = &outcome.y_end;
    let summary = Summary {
        energy_start: obs.energy_start,
        energy_end: obs.energy_end,
        dissipated: y[2 * n],
        energy_balance_error: obs.energy_balance_error,
        max_energy_rise: obs.max_energy_rise,
        tip_end: tip(chain, start.anchor, &y[..n]),
        tip_velocity_end: tip_velocity(chain, &y[..n], &y[n..2 * n]),
        tip_speed_max: obs.tip_speed_max,
        t_tip_speed_max: obs.t_tip_speed_max,
        wall_seconds,
    };
    // A non-finite value in the summary (an energy that overflowed, a NaN
    // from the observer) is a run that went wrong, even when every state
    // stayed finite: it must not pass as `ok`.
    let (status, t_failed) = if outcome.status.is_ok() && !summary.all_finite() {
        let t = obs.t_nonfinite.unwrap_or(outcome.t_reached);
        (Status::Diverged, Some(t))
    } else {
        (outcome.status, outcome.t_failed)
    };
    Ok(Trajectory {
        chain: chain.clone(),
        anchor: start.anchor,
        method,
        status,
        t_end: options.t_end,
        t_reached: outcome.t_reached,
        t_failed,
        stats: outcome.stats,
        segments: outcome.segments,
        summary,
        times: std::mem::take(&mut obs.times),
        states: std::mem::take(&mut obs.states),
        final_state: outcome.y_end,
    })
}
