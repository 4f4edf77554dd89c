//! One way to run any method on any chain: [`solve`].
//!
//! Every method is one file with one [`Integrator`](integrator::Integrator)
//! (its name, whether it is adaptive, its accuracy parameter, how it runs),
//! listed by one line in [`registry`] next to its [`Method`] variant.
//! `auto` is a policy over the registry (`auto.rs`). Work counters come from
//! a [`Counted`](crate::ode::Counted) system, never from counting by hand.

mod auto;
pub mod auto_elastic;
mod bdf;
mod bdf_dense;
mod beam_run;
mod block_lu;
mod diffsol_driver;
mod dop853;
mod dop853_tableau;
mod dopri5;
mod elastic_run;
mod explicit;
mod integrator;
#[cfg(test)]
mod known_solutions;
mod newton_matrix;
mod observer;
mod registry;
mod report_run;
mod rk4;
mod sparse_lu;
mod step_size;
#[cfg(test)]
mod test_problems;
mod unit_costs;

use std::fmt;
use std::str::FromStr;
use std::time::Instant;

use crate::chain::{check, number_text, Chain, InvalidParameter};
use crate::elastic;
use crate::kinematics::{energy, joints, tip, tip_velocity, Vec2};
use crate::ode::{Cancel, Stats, Status};
use crate::pivot::PivotPath;
use crate::state::State;
use crate::system::ChainSystem;
pub use auto::bdf_crossover_gamma;
#[doc(hidden)]
pub use bdf::with_general_sparse_lu;
pub use beam_run::{solve_beam, BeamRun, BEAM_MAX_STEPS};
pub use integrator::Accuracy;
use integrator::{Run, Settings, Span};
use observer::ChainObserver;
pub use observer::DRIVE_BALANCE_FRACTION;
pub use report_run::{solve_report, REPORT_METHODS};
#[doc(hidden)]
pub use unit_costs::{unit_costs, UnitCosts};

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
    /// DOPRI5 (DOP853 at tight tolerances) to the end on a chain, and on a
    /// problem that names no chain (the elastic chain) handing over to BDF
    /// when the stiffness detector fires.
    Auto,
}

impl Method {
    /// Every method, in the order figures list them (the registry's).
    pub const ALL: [Method; registry::REGISTRY.len()] = registry::methods();

    /// The name used on the command line, in scenes and in output.
    pub fn as_str(self) -> &'static str {
        registry::integrator(self).name
    }

    /// True if the method adapts its step to `rtol`/`atol`.
    pub fn adaptive(self) -> bool {
        registry::integrator(self).adaptive
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
            accepted: registry::accepted_names().into(),
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

    /// Checks every field on its own; the error names the first one out of
    /// range. [`SolveOptions::validate_for`] adds the bounds that depend on
    /// the method and the chain; [`solve`] checks both before it allocates.
    pub fn validate(&self) -> Result<(), InvalidParameter> {
        let pos = |x: f64| x.is_finite() && x > 0.0;
        check(
            pos(self.t_end),
            "run.t_end",
            "a finite number > 0",
            self.t_end,
        )?;
        check(pos(self.dt), "run.dt", "a finite number > 0", self.dt)?;
        let (lo, hi) = RTOL_RANGE;
        check(
            (lo..=hi).contains(&self.rtol),
            "run.rtol",
            "a number in [1e-14, 0.1]",
            self.rtol,
        )?;
        let (lo, hi) = ATOL_RANGE;
        check(
            (lo..=hi).contains(&self.atol),
            "run.atol",
            "a number in [1e-20, 1]",
            self.atol,
        )?;
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

    /// [`SolveOptions::validate`], then the bounds that depend on `method`
    /// and `chain`, each stated with the numbers of this run:
    /// * RK4: `run.dt <= run.t_end`, and `ceil(t_end / dt) <= run.max_steps`
    ///   (the smallest step accepted is `t_end / max_steps`);
    /// * the recorded samples, `t_end / output_dt` of
    ///   [`SolveOptions::sample_numbers`] numbers
    ///   each, within [`MAX_OUTPUT_BYTES`] (the smallest `run.output_dt`
    ///   accepted is [`SolveOptions::min_output_dt`]);
    /// * `bdf-dense`: at most [`BDF_DENSE_MAX_LINKS`] rods (`bdf` runs any).
    /// * RK4 with a prescribed pivot motion: `run.dt` at most the motion's
    ///   time scale over [`crate::STEPS_PER_TIME_SCALE`]
    ///   ([`crate::Pivot::time_scales`]).
    ///
    /// `chain` itself is checked by [`Chain::validate`].
    pub fn validate_for(&self, chain: &Chain, method: Method) -> Result<(), InvalidParameter> {
        self.validate()?;
        if method == Method::Rk4 {
            check(
                self.dt <= self.t_end,
                "run.dt",
                format!("at most run.t_end = {} for rk4", number_text(self.t_end)),
                self.dt,
            )?;
            let dt_min = self.t_end / self.max_steps as f64;
            check(
                self.dt >= dt_min,
                "run.dt",
                format!(
                    "at least run.t_end / run.max_steps = {dt_min:e} for rk4 (t_end = {}, \
                     max_steps = {})",
                    number_text(self.t_end),
                    self.max_steps
                ),
                self.dt,
            )?;
            // A fixed step must resolve the pivot's prescribed motion, as
            // the adaptive methods' caps do (`Pivot::time_scales`).
            let cap = chain.pivot().time_scales().smallest();
            if cap.is_finite() {
                let (key, scale) = if chain.pivot().jerk != [0.0, 0.0]
                    && cap == chain.pivot().jerk_time / crate::pivot::STEPS_PER_TIME_SCALE
                {
                    ("pivot.jerk_time", "the smooth jerk's duration")
                } else {
                    (
                        "pivot.frequency",
                        "the harmonic motion's period 2 pi / frequency",
                    )
                };
                check(
                    self.dt <= cap,
                    "run.dt",
                    format!(
                        "at most {cap:e} for rk4 with this pivot: {} of {scale} ({key})",
                        format_args!("1/{}", crate::pivot::STEPS_PER_TIME_SCALE)
                    ),
                    self.dt,
                )?;
            }
        }
        if let Some(o) = self.output_dt {
            let o_min = Self::min_output_dt_for(self.t_end, chain);
            check(
                o >= o_min,
                "run.output_dt",
                format!(
                    "at least {o_min:e} for t_end = {} and chain.links = {}: the samples \
                     ({} numbers each) must fit in {} MiB",
                    number_text(self.t_end),
                    chain.links(),
                    Self::sample_numbers(chain),
                    MAX_OUTPUT_BYTES >> 20
                ),
                o,
            )?;
        }
        if method == Method::BdfDense && chain.is_elastic() {
            check(
                chain.links() <= BDF_DENSE_MAX_ELASTIC_LINKS,
                "chain.links",
                format!(
                    "at most {BDF_DENSE_MAX_ELASTIC_LINKS} for bdf-dense with chain.axial_stiffness \
                     (its dense Jacobian of 6 n + 1 unknowns grows like n^2 in memory and n^3 in \
                     time); run.method = \"bdf\" is the same method in O(n)"
                ),
                chain.links(),
            )?;
        }
        if method == Method::BdfDense {
            check(
                chain.links() <= BDF_DENSE_MAX_LINKS,
                "chain.links",
                format!(
                    "at most {BDF_DENSE_MAX_LINKS} for bdf-dense (its dense Jacobian and LU \
                     grow like n^2 in memory and n^3 in time); run.method = \"bdf\" is the \
                     same method in O(n)"
                ),
                chain.links(),
            )?;
        }
        Ok(())
    }

    /// The smallest `output_dt` (time units) whose samples over `t_end` fit
    /// in [`MAX_OUTPUT_BYTES`] for a chain of `links` rigid rods: each
    /// sample holds its time and the `2 n + 1` state values (`f64`), and
    /// the `2 (n + 1)` joint forces an output may derive from it
    /// ([`SolveOptions::sample_numbers`]); a run records
    /// `t_end / output_dt + 2` samples at most (the start, and the end when
    /// it is not on the grid).
    pub fn min_output_dt(t_end: f64, links: usize) -> f64 {
        Self::min_output_dt_of(t_end, 4 * links as u64 + 4)
    }

    /// Numbers a recorded sample of `chain` may take in memory: its time,
    /// its state (`2 n + 1` rigid, `6 n + 1` elastic), the joint forces an
    /// output may derive from it (`2 (n + 1)`) and, for an elastic chain,
    /// its joints (`2 (n + 1)`, which Python keeps).
    pub fn sample_numbers(chain: &Chain) -> u64 {
        let n = chain.links() as u64;
        if chain.is_elastic() {
            (6 * n + 2) + 4 * (n + 1)
        } else {
            (2 * n + 2) + 2 * (n + 1)
        }
    }

    /// [`SolveOptions::min_output_dt`] for `chain`'s model
    /// ([`SolveOptions::sample_numbers`] each).
    pub fn min_output_dt_for(t_end: f64, chain: &Chain) -> f64 {
        Self::min_output_dt_of(t_end, Self::sample_numbers(chain))
    }

    fn min_output_dt_of(t_end: f64, numbers: u64) -> f64 {
        let per_sample = 8 * numbers;
        let samples = MAX_OUTPUT_BYTES / per_sample;
        t_end / samples.saturating_sub(2).max(1) as f64
    }
}

/// The accepted range of `run.rtol`, `[min, max]`: below `1e-14` a relative
/// error test asks for less than the rounding of `f64` states (the BDFs then
/// crawl at steps of `1e-13` for hours), above `0.1` it allows errors as
/// large as the state.
pub const RTOL_RANGE: (f64, f64) = (1e-14, 0.1);

/// The accepted range of `run.atol` (units of the state: rad, rad per time
/// unit, energy), `[min, max]`.
pub const ATOL_RANGE: (f64, f64) = (1e-20, 1.0);

/// The most memory a run's recorded samples may take (bytes): 1 GiB.
pub const MAX_OUTPUT_BYTES: u64 = 1 << 30;

/// The largest chain `bdf-dense` runs: its Jacobian and LU are dense
/// `(2n + 1)^2` matrices, factorised in O(n^3).
pub const BDF_DENSE_MAX_LINKS: usize = 500;

/// The largest elastic chain `bdf-dense` runs: `6 n + 1` unknowns, so
/// about the same dense matrices as [`BDF_DENSE_MAX_LINKS`] rigid rods.
pub const BDF_DENSE_MAX_ELASTIC_LINKS: usize = 160;

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
    /// Elastic links only: the largest pivot force `|F_1|` (force units)
    /// at the start and at any accepted step's end, and when: `(force, t)`.
    /// `None` for rigid links (their pivot force is the DAE's, from the
    /// samples: `analysis::pivot_forces`).
    pub pivot_force_max: Option<(f64, f64)>,
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
            self.pivot_force_max.map_or(0.0, |p| p.0),
            self.pivot_force_max.map_or(0.0, |p| p.1),
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
    /// The pivot `P0` at `t = 0`.
    pub anchor: Vec2,
    /// Where the pivot is at any time (the anchor, for a fixed pivot).
    pub pivot: PivotPath,
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
    /// Samples, `2 n + 1` numbers each (angles, rates, dissipated work), or
    /// `6 n + 1` for elastic links ([`crate::elastic`]).
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
        let n = self.chain.links();
        let y = self.state(k);
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

    /// The whole state of sample `k`: `[phi, w, W]` for rigid links,
    /// `[theta, w, W, x, y, vx, vy]` for elastic ones ([`crate::elastic`]).
    pub fn state(&self, k: usize) -> &[f64] {
        let d = state_len(&self.chain);
        &self.states[k * d..(k + 1) * d]
    }

    /// The pivot's position and velocity at sample `k`.
    pub fn pivot_at(&self, k: usize) -> [Vec2; 2] {
        let n = self.chain.links();
        let y = self.state(k);
        self.pivot
            .at(&self.chain, self.times[k], &y[..n], &y[n..2 * n])
    }

    /// The joints `r_0 = P0, .., r_n` of sample `k`, for either model (for
    /// rigid links, `kinematics::joints` of its angles from the pivot there).
    pub fn joints(&self, k: usize) -> Vec<Vec2> {
        if self.chain.is_elastic() {
            let p0 = self.pivot_at(k)[0];
            return elastic::joints_at(&self.chain, self.times[k], p0, self.state(k));
        }
        state_joints(&self.chain, self.pivot_at(k)[0], self.state(k))
    }

    /// The tip of sample `k` (for rigid links, `kinematics::tip`).
    pub fn tip(&self, k: usize) -> Vec2 {
        state_tip(&self.chain, self.pivot_at(k)[0], self.state(k))
    }

    /// The tip velocity of sample `k` (for rigid links,
    /// `kinematics::tip_velocity`, plus the pivot's velocity).
    pub fn tip_velocity(&self, k: usize) -> Vec2 {
        let v = state_tip_velocity(&self.chain, self.state(k));
        if self.pivot.is_fixed() {
            return v;
        }
        let v0 = self.pivot_at(k)[1];
        [v[0] + v0[0], v[1] + v0[1]]
    }

    /// The energy of sample `k`: `T + V (+ U_b)` for rigid links
    /// (`kinematics::energy`, in the inertial frame for a moving pivot),
    /// `T + V + U_el + U_b` for elastic ones.
    pub fn energy(&self, k: usize) -> f64 {
        if self.chain.is_elastic() {
            return elastic_energy_at(&self.chain, self.times[k], self.state(k));
        }
        let e = state_energy(&self.chain, self.state(k));
        if self.pivot.is_fixed() {
            return e;
        }
        let n = self.chain.links();
        let y = self.state(k);
        e + self
            .pivot
            .frame(&self.chain, self.times[k], &y[..n], &y[n..2 * n])
            .energy
    }

    /// The joint forces of sample `k`, joints `0..=n` (the pivot first, the
    /// free tip's zero last), each `[tension, shear]` in the frame of the
    /// rod after the joint: tension `-F_k . u_k`, positive when the joint
    /// pulls the rod back toward the pivot; shear `F_k . v_k` with `v_k`
    /// the rod's direction turned by +90 degrees (force units). Rigid
    /// links: the banded DAE's joint forces, consistent with the sample's
    /// state (and the pivot's motion at its time); elastic links: the
    /// springs' and dashpots' forces.
    pub fn joint_forces(&self, k: usize) -> Vec<Vec2> {
        let t = self.times[k];
        state_joint_forces(&self.chain, t, self.pivot.is_free_at(t), self.state(k))
    }
}

/// Refuses a start whose angles or rates are not one per rod.
pub(crate) fn check_start(chain: &Chain, start: &State) -> Result<(), InvalidParameter> {
    let n = chain.links();
    check(
        start.angles.len() == n && start.rates.len() == n,
        "start",
        "a state with chain.links angles and rates",
        start.angles.len(),
    )
}

/// Numbers in a state of `chain`'s model: `2 n + 1` for rigid links
/// (`[phi, w, W]`), `6 n + 1` for elastic ones (see [`crate::elastic`]).
pub(crate) fn state_len(chain: &Chain) -> usize {
    if chain.is_elastic() {
        6 * chain.links() + 1
    } else {
        2 * chain.links() + 1
    }
}

/// The energy of a state of either model (the rigid one's as
/// `kinematics::energy` computes it).
pub(crate) fn state_energy(chain: &Chain, y: &[f64]) -> f64 {
    if chain.is_elastic() {
        elastic::energy(chain, y)
    } else {
        let n = chain.links();
        energy(chain, &y[..n], &y[n..2 * n])
    }
}

/// The energy of an elastic state at `t` in the inertial frame: the
/// chain's own ([`elastic::energy_at`], relative to the pivot) plus, for a
/// driven pivot, the frame's terms ([`elastic::frame_energy`]).
pub(crate) fn elastic_energy_at(chain: &Chain, t: f64, y: &[f64]) -> f64 {
    let e = elastic::energy_at(chain, t, y);
    if !chain.pivot().is_driven() {
        return e;
    }
    let [d, v0, _] = chain.pivot().drive(t);
    e + elastic::frame_energy(chain, d, v0, y)
}

/// The tip velocity of a state of either model.
pub(crate) fn state_tip_velocity(chain: &Chain, y: &[f64]) -> Vec2 {
    if chain.is_elastic() {
        elastic::tip_velocity(chain, y)
    } else {
        let n = chain.links();
        tip_velocity(chain, &y[..n], &y[n..2 * n])
    }
}

/// The tip of a state of either model, the pivot at `p0`.
pub(crate) fn state_tip(chain: &Chain, p0: Vec2, y: &[f64]) -> Vec2 {
    if chain.is_elastic() {
        elastic::tip(chain, p0, y)
    } else {
        tip(chain, p0, &y[..chain.links()])
    }
}

/// The joints `r_0 .. r_n` of a state of either model, the pivot at `p0`.
pub(crate) fn state_joints(chain: &Chain, p0: Vec2, y: &[f64]) -> Vec<Vec2> {
    if chain.is_elastic() {
        elastic::joints(chain, p0, y)
    } else {
        joints(chain, p0, &y[..chain.links()])
    }
}

/// The joint forces `[tension, shear]` of a state of either model, joints
/// `0..=n` (see [`elastic::tension_shear`] for the frame and signs).
pub(crate) fn state_joint_forces(chain: &Chain, t: f64, free: bool, y: &[f64]) -> Vec<Vec2> {
    let n = chain.links();
    let forces = if chain.is_elastic() {
        elastic::joint_forces_at(chain, t, y)
    } else {
        elastic::rigid_joint_forces_at(chain, t, free, y)
    };
    elastic::tension_shear(&y[..n], &forces)
}

/// Runs `method` on `chain` from `start` over `[0, options.t_end]`.
///
/// Never panics on a failing run and never returns a NaN in its state: a run
/// that hits a non-finite value stops with `Status::Diverged` at the last
/// finite state. A run whose every state is finite but whose summary is not
/// (an energy that overflows, say) also ends `Status::Diverged`, with
/// `t_failed` the first time a non-finite value was recorded: a NaN or an
/// infinity in the summary never comes with `Status::Ok`. A finite run whose
/// energy balance error `max |E + W - E(0)|` exceeds the chain's energy
/// scale ([`Chain::energy_scale`]), or with a prescribed pivot motion
/// [`DRIVE_BALANCE_FRACTION`] of that scale plus the work done, ends
/// `Status::Inaccurate`, with
/// `t_failed` the first step end where it did. A run whose
/// `options.cancel` is set ends `Status::Interrupted` at its last accepted
/// step (`t_failed = t_reached`).
///
/// Every option is checked first ([`SolveOptions::validate_for`]): nothing
/// is allocated for a run out of bounds.
pub fn solve(
    chain: &Chain,
    start: &State,
    method: Method,
    options: &SolveOptions,
) -> Result<Trajectory, InvalidParameter> {
    options.validate_for(chain, method)?;
    check_start(chain, start)?;
    let y0 = if chain.is_elastic() {
        elastic::start_state(chain, start)
    } else {
        ChainSystem::pack(&start.angles, &start.rates, 0.0)
    };
    let mut path = PivotPath::new(chain, start.anchor);
    let settings = Settings {
        scales: chain.pivot().time_scales(),
        ..Settings::of(options)
    };
    let span = Span {
        t0: 0.0,
        y0: &y0,
        t_end: options.t_end,
        settings: &settings,
    };
    let clock = Instant::now();
    // A rigid chain with a fixed pivot takes exactly the path it always took.
    let (run, obs) = if chain.is_elastic() {
        elastic_run::run(chain, method, options, &span, &path)
    } else if chain.pivot().release.is_some() {
        run_with_release(chain, start, method, options, &span, &mut path)
    } else {
        let mut obs = ChainObserver::for_run(chain, path.clone(), options);
        let run = registry::run(method, &mut ChainSystem::new(chain), &span, &mut obs);
        (run, obs)
    };
    Ok(trajectory(
        chain,
        start,
        method,
        options,
        (run, obs, path),
        chain.energy_scale(),
        clock,
    ))
}

/// The trajectory of a finished run of `method` on `chain` from `start`:
/// its summary from the observer `obs` (finished here) and the final
/// state, and its status: a run that ended `ok` becomes `diverged` if its
/// summary is not finite and `inaccurate` if its energy balance error
/// exceeds `energy_scale`. `clock` started before the run (its wall time);
/// `path` is the pivot's.
fn trajectory(
    chain: &Chain,
    start: &State,
    method: Method,
    options: &SolveOptions,
    (run, mut obs, path): (Run, ChainObserver, PivotPath),
    energy_scale: f64,
    clock: Instant,
) -> Trajectory {
    let Run { outcome, segments } = run;
    let n = chain.links();
    let wall_seconds = clock.elapsed().as_secs_f64();
    obs.finish(outcome.t_reached, &outcome.y_end);
    let y = &outcome.y_end;
    let (tip_end, tip_velocity_end) = if path.is_fixed() {
        (
            state_tip(chain, start.anchor, y),
            state_tip_velocity(chain, y),
        )
    } else {
        let [p0, v0] = path.at(chain, outcome.t_reached, &y[..n], &y[n..2 * n]);
        let v = state_tip_velocity(chain, y);
        (state_tip(chain, p0, y), [v[0] + v0[0], v[1] + v0[1]])
    };
    let summary = Summary {
        energy_start: obs.energy_start,
        energy_end: obs.energy_end,
        dissipated: y[2 * n],
        energy_balance_error: obs.energy_balance_error,
        max_energy_rise: obs.max_energy_rise,
        tip_end,
        tip_velocity_end,
        tip_speed_max: obs.tip_speed_max,
        t_tip_speed_max: obs.t_tip_speed_max,
        pivot_force_max: chain
            .is_elastic()
            .then_some((obs.pivot_force_max, obs.t_pivot_force_max)),
        wall_seconds,
    };
    // A non-finite value in the summary (an energy that overflowed, a NaN
    // from the observer) is a run that went wrong, even when every state
    // stayed finite: it must not pass as `ok`.
    // A finite run whose energy balance error exceeds the chain's energy
    // scale is not a solution of the model (a step far too large, a
    // tolerance far too loose): it must not pass as `ok` either; with a
    // driven pivot, nor one whose error is a percent of the work done
    // (`ChainObserver::balance_limit`).
    let (status, t_failed) = if outcome.status.is_ok() && !summary.all_finite() {
        let t = obs.t_nonfinite.unwrap_or(outcome.t_reached);
        (Status::Diverged, Some(t))
    } else if outcome.status.is_ok()
        && summary.energy_balance_error > energy_scale.min(obs.balance_limit())
    {
        let t = obs.t_inaccurate.unwrap_or(outcome.t_reached);
        (Status::Inaccurate, Some(t))
    } else {
        (outcome.status, outcome.t_failed)
    };
    Trajectory {
        chain: chain.clone(),
        anchor: start.anchor,
        pivot: path,
        method,
        status,
        t_end: options.t_end,
        t_reached: outcome.t_reached,
        t_failed,
        stats: outcome.stats,
        segments,
        summary,
        times: std::mem::take(&mut obs.times),
        states: std::mem::take(&mut obs.states),
        final_state: outcome.y_end,
    }
}

/// A rigid chain whose pivot is let go at `t_r` (`pivot.release`): held
/// (fixed or driven) up to `t_r`, then free, in two runs of `method` from
/// one observer (as `auto`'s handover). The release is noted in `path` from
/// the state reached at `t_r` exactly; a first run that fails or is
/// stopped ends the whole run there.
fn run_with_release(
    chain: &Chain,
    start: &State,
    method: Method,
    options: &SolveOptions,
    span: &Span<'_>,
    path: &mut PivotPath,
) -> (Run, ChainObserver) {
    let n = chain.links();
    let t_release = chain.pivot().release.unwrap_or(0.0);
    let mut sys = ChainSystem::new(chain);
    let new_observer = |path: &PivotPath| ChainObserver::for_run(chain, path.clone(), options);
    if t_release <= span.t0 || t_release >= span.t_end {
        if t_release <= span.t0 {
            path.release(chain, span.t0, &start.angles, &start.rates);
            sys.set_released(true);
        }
        let mut obs = new_observer(path);
        let run = registry::run(method, &mut sys, span, &mut obs);
        return (run, obs);
    }
    let mut obs = new_observer(path);
    let run = run_cut(
        method,
        &mut sys,
        span,
        &mut obs,
        t_release,
        |sys, y, obs| {
            path.release(chain, t_release, &y[..n], &y[n..2 * n]);
            obs.path = path.clone();
            sys.set_released(true);
        },
    );
    (run, obs)
}

/// Runs `method` over `span` in two pieces cut at `t_cut` (inside the
/// span), from one observer (as `auto`'s handover): the first piece up to
/// `t_cut`, then `cut` with the system, the state reached at `t_cut` (which
/// it may change) and the observer, then the second piece from there. The
/// statistics are summed and the segments joined; a first piece that fails
/// or is stopped ends the whole run there. A pivot let go at `t_cut` is the
/// one use, for the rigid and the elastic chain.
fn run_cut<S: crate::ode::Problem>(
    method: Method,
    sys: &mut S,
    span: &Span<'_>,
    obs: &mut ChainObserver,
    t_cut: f64,
    cut: impl FnOnce(&mut S, &mut [f64], &mut ChainObserver),
) -> Run {
    let held = Span {
        t_end: t_cut,
        ..*span
    };
    let first = registry::run(method, sys, &held, obs);
    if !first.outcome.status.is_ok() || first.outcome.t_reached < t_cut {
        return first;
    }
    let mut y = first.outcome.y_end.clone();
    cut(sys, &mut y, obs);
    let done = first.outcome.stats;
    let settings = span.settings.after(&done);
    let rest = Span {
        t0: t_cut,
        y0: &y,
        t_end: span.t_end,
        settings: &settings,
    };
    let mut second = registry::run(method, sys, &rest, obs);
    second.outcome.stats += done;
    second.segments.splice(0..0, first.segments);
    second
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::{all_finite, Observer, StepView};
    use crate::state::Start;

    /// Asks every method to stop once it has seen `k` accepted steps.
    struct StopAfter {
        k: u64,
        steps: u64,
        t_last: f64,
    }

    impl Observer for StopAfter {
        fn start(&mut self, t0: f64, _: &[f64], _: &[f64]) {
            self.t_last = t0;
        }
        fn step(&mut self, s: &StepView<'_>) {
            self.steps += 1;
            self.t_last = s.t1;
        }
        fn stop(&self) -> bool {
            self.steps >= self.k
        }
    }

    /// Eight rods of the report's chain hanging on span d = 3: the chain,
    /// the start and its packed state.
    fn eight_rods_on_span_3() -> (Chain, State, Vec<f64>) {
        let chain = Chain::report(8, 5e-4).unwrap();
        let start = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [3.0, 0.0],
        }
        .state(&chain)
        .unwrap();
        let y0 = ChainSystem::pack(&start.angles, &start.rates, 0.0);
        (chain, start, y0)
    }

    /// A run cut in two (a pivot let go mid-run) is the two pieces run
    /// one after the other: the same end state, and the work of both
    /// counted, for an explicit and an implicit method.
    #[test]
    fn a_run_cut_in_two_is_its_two_pieces_with_both_pieces_work() {
        let (chain, start, y0) = eight_rods_on_span_3();
        let options = SolveOptions {
            t_end: 2.0,
            ..Default::default()
        };
        let settings = Settings::of(&options);
        let path = PivotPath::new(&chain, start.anchor);
        let observer = || ChainObserver::for_run(&chain, path.clone(), &options);
        let span = Span {
            t0: 0.0,
            y0: &y0,
            t_end: 2.0,
            settings: &settings,
        };
        for method in [Method::Dopri5, Method::Bdf] {
            let mut sys = ChainSystem::new(&chain);
            let mut obs = observer();
            let held = Span { t_end: 1.0, ..span };
            let first = registry::run(method, &mut sys, &held, &mut obs).outcome;
            let y1 = first.y_end.clone();
            let after = settings.after(&first.stats);
            let rest = Span {
                t0: 1.0,
                y0: &y1,
                t_end: 2.0,
                settings: &after,
            };
            let second = registry::run(method, &mut sys, &rest, &mut obs).outcome;

            let mut sys = ChainSystem::new(&chain);
            let mut obs = observer();
            let cut = run_cut(method, &mut sys, &span, &mut obs, 1.0, |_, _, _| {}).outcome;
            assert_eq!(cut.status, Status::Ok, "{method}");
            assert_eq!(cut.y_end, second.y_end, "{method}");
            let (a, b, c) = (first.stats, second.stats, cut.stats);
            assert!(a.steps > 0 && b.steps > 0, "{method}");
            assert_eq!(c.steps, a.steps + b.steps, "{method}");
            assert_eq!(
                c.rejected_steps,
                a.rejected_steps + b.rejected_steps,
                "{method}"
            );
            assert_eq!(c.rhs_evals, a.rhs_evals + b.rhs_evals, "{method}");
            assert_eq!(
                c.lu_factorizations,
                a.lu_factorizations + b.lu_factorizations,
                "{method}"
            );
        }
    }

    #[test]
    fn every_method_stops_at_the_step_its_observer_asks() {
        let (chain, _, y0) = eight_rods_on_span_3();
        let settings = Settings::of(&SolveOptions {
            t_end: 4.0,
            ..Default::default()
        });
        for method in Method::ALL {
            for k in [0, 1, 7] {
                let mut sys = ChainSystem::new(&chain);
                let mut obs = StopAfter {
                    k,
                    steps: 0,
                    t_last: f64::NAN,
                };
                let span = Span {
                    t0: 0.0,
                    y0: &y0,
                    t_end: 4.0,
                    settings: &settings,
                };
                let out = registry::run(method, &mut sys, &span, &mut obs).outcome;
                assert_eq!(out.status, Status::Interrupted, "{method}, k = {k}");
                assert_eq!(out.stats.steps, k, "{method}, k = {k}");
                assert_eq!(obs.steps, k, "{method}, k = {k}");
                assert_eq!(
                    out.t_reached, obs.t_last,
                    "{method}: the last accepted step"
                );
                assert!(out.t_reached < 4.0 && all_finite(&out.y_end), "{method}");
                assert_eq!(out.t_failed, Some(out.t_reached));
            }
        }
    }
}
