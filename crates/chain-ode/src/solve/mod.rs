//! One way to run any method on any chain: [`solve`].

mod adaptive;
mod bdf;
mod bdf_dense;
mod diffsol_driver;
mod dop853;
mod dopri5;
mod observer;
mod rk4;
mod sparse_lu;

use std::fmt;
use std::str::FromStr;
use std::time::Instant;

use crate::chain::{check, Chain, InvalidParameter};
use crate::kinematics::{tip, tip_velocity, Vec2};
use crate::ode::{Observer, Outcome};
use crate::ode::{Stats, Status};
use crate::state::State;
use crate::system::ChainSystem;
use adaptive::AdaptiveOptions;
use observer::ChainObserver;

/// An integration method.
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
    /// Every method, in the order figures list them.
    pub const ALL: [Method; 6] = [
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
        Method::Bdf,
        Method::BdfDense,
        Method::Auto,
    ];

    /// The name used on the command line, in scenes and in output.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Rk4 => "rk4",
            Self::Dopri5 => "dopri5",
            Self::Dop853 => "dop853",
            Self::Bdf => "bdf",
            Self::BdfDense => "bdf-dense",
            Self::Auto => "auto",
        }
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
        Self::ALL
            .into_iter()
            .find(|m| m.as_str() == s)
            .ok_or_else(|| InvalidParameter {
                field: "run.method",
                accepted: "one of rk4, dopri5, dop853, bdf, bdf-dense, auto",
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
        }
    }
}

impl SolveOptions {
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
/// Never panics on a failing run and never returns a NaN: a run that hits a
/// non-finite value stops with `Status::Diverged` at the last finite state.
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
    let adaptive = AdaptiveOptions {
        rtol: options.rtol,
        atol: options.atol,
        h_min: options.h_min,
        max_steps: options.max_steps,
        h0: None,
        stop_when_stiff: false,
        switch_lambda: 0.0,
    };
    let (outcome, segments) = run(&mut sys, &y0, method, options, &adaptive, &mut obs);
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
    Ok(Trajectory {
        chain: chain.clone(),
        anchor: start.anchor,
        method,
        status: outcome.status,
        t_end: options.t_end,
        t_reached: outcome.t_reached,
        t_failed: outcome.t_failed,
        stats: outcome.stats,
        segments,
        summary,
        times: std::mem::take(&mut obs.times),
        states: std::mem::take(&mut obs.states),
        final_state: outcome.y_end,
    })
}

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
    let (g, big_l) = (chain.gravity, chain.length);
    27.0 * (g / big_l).sqrt() + 0.12 * (g * big_l).sqrt() / chain.rod_length()
}

/// Relative tolerance at and below which `auto`'s explicit method is DOP853
/// rather than DOPRI5 (measured on the work-precision diagrams).
pub const AUTO_DOP853_RTOL: f64 = 1e-8;

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

/// Dispatches to the method; `auto` follows [`Method::auto_plan`]: BDF from
/// the start past the crossover, else the explicit method until its
/// stiffness detector keeps firing with `|lambda|` past the crossover's
/// `48 gamma`, then BDF from that state.
fn run<O: Observer>(
    sys: &mut ChainSystem,
    y0: &[f64],
    method: Method,
    options: &SolveOptions,
    adaptive: &AdaptiveOptions,
    obs: &mut O,
) -> (Outcome, Vec<Segment>) {
    let t_end = options.t_end;
    let segment = |method, t_start, out: &Outcome| Segment {
        method,
        t_start,
        t_end: out.t_reached,
    };
    let single = |method, out: Outcome| {
        let seg = vec![segment(method, 0.0, &out)];
        (out, seg)
    };
    match method {
        Method::Rk4 => single(
            method,
            rk4::integrate(sys, 0.0, y0, t_end, options.dt, options.max_steps, obs),
        ),
        Method::Dopri5 => single(
            method,
            dopri5::integrate(sys, 0.0, y0, t_end, adaptive, obs),
        ),
        Method::Dop853 => single(
            method,
            dop853::integrate(sys, 0.0, y0, t_end, adaptive, obs),
        ),
        Method::Bdf => single(
            method,
            bdf::integrate(sys.chain(), 0.0, y0, t_end, adaptive, obs),
        ),
        Method::BdfDense => single(
            method,
            bdf_dense::integrate(sys, 0.0, y0, t_end, adaptive, obs),
        ),
        Method::Auto => {
            let chain = sys.chain().clone();
            let Some(explicit) = Method::auto_plan(&chain, adaptive.rtol) else {
                return single(
                    Method::Bdf,
                    bdf::integrate(&chain, 0.0, y0, t_end, adaptive, obs),
                );
            };
            let watch = AdaptiveOptions {
                stop_when_stiff: true,
                switch_lambda: 48.0 * bdf_crossover_gamma(&chain),
                ..*adaptive
            };
            let first = if explicit == Method::Dop853 {
                dop853::integrate(sys, 0.0, y0, t_end, &watch, obs)
            } else {
                dopri5::integrate(sys, 0.0, y0, t_end, &watch, obs)
            };
            let mut segments = vec![segment(explicit, 0.0, &first)];
            let Some(t_switch) = first.stiff_at.filter(|_| first.status.is_ok()) else {
                return (first, segments);
            };
            let budget = AdaptiveOptions {
                max_steps: adaptive
                    .max_steps
                    .saturating_sub(first.stats.steps + first.stats.rejected_steps)
                    .max(1),
                ..*adaptive
            };
            let mut second = bdf::integrate(&chain, t_switch, &first.y_end, t_end, &budget, obs);
            segments.push(segment(Method::Bdf, t_switch, &second));
            second.stats += first.stats;
            (second, segments)
        }
    }
}
