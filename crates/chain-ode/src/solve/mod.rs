//! The run layer: one way to run any method on any model, [`solve`].
//!
//! The methods are fc-methods' (one [`Integrator`] per [`Method`], in its
//! registry); they see only the [`Problem`] a model gives. This layer
//! checks a run's options against its model ([`Model::validate`], on
//! [`SolveOptions::validate_common`]), hands the model's problem to the
//! method with the run's settings, cuts the run at the model's event, and
//! watches it: the recorder (samples, the first non-finite time, cancel
//! and progress), the summary's tally (which asks the model) and the
//! caller's [`Watch`]es. Work counters come from what the methods called
//! (a [`Counted`](fc_methods::Counted) system), never from counting by
//! hand.
//!
//! Its files: `options.rs` (a run's options and their bounds),
//! `trajectory.rs` (what a run returns: its summary and trajectory),
//! `run.rs` (the pieces of one run: observers, segments, the cut at an
//! event, the finished trajectory), `recorder.rs` (the samples),
//! `tally.rs` (the summary's running quantities), `peaks.rs` (the forces'
//! peaks inside steps), `auto_elastic.rs` (`auto`'s plan on elastic
//! chains), `report_stepper.rs` (the report's own fixed-step stepping) and
//! `unit_costs.rs` (the measured cost of one evaluation of each kind).

pub mod auto_elastic;
<<<<<<< HEAD
mod options;
=======
mod forces;
>>>>>>> i53
pub(crate) mod peaks;
mod recorder;
mod report_stepper;
mod run;
mod tally;
mod trajectory;
mod unit_costs;

use std::time::Instant;

use fc_methods::{InvalidParameter, Method, Settings, Span, StepView};

use crate::model::{IntoModel, Model};
use crate::state::State;
pub use options::{
    SolveOptions, ATOL_RANGE, BDF_DENSE_MAX_ELASTIC_LINKS, BDF_DENSE_MAX_LINKS, MAX_OUTPUT_BYTES,
    RTOL_RANGE,
};
use recorder::Recorder;
pub use report_stepper::{REPORT_METHODS, REPORT_RK4};
use run::{run_cut, segment, trajectory, Parts};
use tally::Tally;
pub use tally::{BALANCE_PER_TOLERANCE, DRIVE_BALANCE_FRACTION};
pub use trajectory::{Sample, Summary, Trajectory};
#[doc(hidden)]
pub use unit_costs::{unit_costs, UnitCosts};

<<<<<<< HEAD
=======
/// Options of a run. Defaults: `t_end = 1`, `dt = 0.01`, `rtol = 1e-8`, `rho_inf = 0.9`,
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
    /// `gen-alpha`'s spectral radius at infinity (`run.rho_inf`, in
    /// [0, 1]): how much of a mode its step does not resolve survives a
    /// step (1: all of it, the trapezoidal rule; 0: none). The other
    /// methods ignore it.
    pub rho_inf: f64,
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
            rho_inf: fc_methods::DEFAULT_RHO_INF,
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

    /// These options as the integrators read them: no starting step, no
    /// step caps (the run adds its model's, [`Model::time_scales`]).
    pub(crate) fn settings(&self) -> Settings {
        Settings {
            dt: self.dt,
            rtol: self.rtol,
            atol: self.atol,
            h_min: self.h_min,
            max_steps: self.max_steps,
            h0: None,
            scales: TimeScales::NONE,
            rho_inf: self.rho_inf,
        }
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
        let (lo, hi) = fc_methods::RHO_INF_RANGE;
        check(
            (lo..=hi).contains(&self.rho_inf),
            "run.rho_inf",
            "a number in [0, 1]",
            self.rho_inf,
        )?;
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
        ModelKind::of(chain).validate(method, self)
    }

    /// The bounds every model shares, for a model laid out as `layout`
    /// whose support moves as `pivot` (if it has one): [`SolveOptions::validate`];
    /// RK4's step within the span, the budget and the pivot's time scales;
    /// the samples' memory. A model's [`Model::validate`] adds its own.
    pub fn validate_common(
        &self,
        pivot: Option<&Pivot>,
        method: Method,
        layout: &Layout,
    ) -> Result<(), InvalidParameter> {
        self.validate()?;
        if method == Method::GenAlpha {
            check(
                self.rtol >= GEN_ALPHA_MIN_RTOL,
                "run.rtol",
                "a number in [1e-10, 0.1] for gen-alpha (below 1e-10 its error \
                 stops following the tolerance: docs/model.md)",
                self.rtol,
            )?;
        }
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
            if let Some(pivot) = pivot {
                let cap = pivot.time_scales().smallest();
                if cap.is_finite() {
                    let (key, scale) = if pivot.jerk != [0.0, 0.0]
                        && cap == pivot.jerk_time / crate::pivot::STEPS_PER_TIME_SCALE
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
        }
        if let Some(o) = self.output_dt {
            let o_min = Self::min_output_dt_of(self.t_end, layout.sample_numbers);
            check(
                o >= o_min,
                "run.output_dt",
                format!(
                    "at least {o_min:e} for t_end = {} and chain.links = {}: the samples \
                     ({} numbers each) must fit in {} MiB",
                    number_text(self.t_end),
                    layout.links,
                    layout.sample_numbers,
                    MAX_OUTPUT_BYTES >> 20
                ),
                o,
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
        ModelKind::of(chain).layout().sample_numbers
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

/// The tightest `rtol` gen-alpha accepts (issue 47 W2): on
/// `scenes/span-d3.toml` its tip error over `L` is 4.1e-8, 2.4e-8, 7.7e-9
/// at rtol 1e-8, 1e-9, 1e-10, and then 6.3e-9, 5.5e-9, 1.4e-9 at 1e-11,
/// 1e-12, 1e-14 (against DOP853 at 1e-13): below 1e-10 a decade of
/// tolerance buys a fraction of a decade, with ever more steps, so the
/// tolerance would be a number the run does not meet (docs/model.md, "The
/// generalized-alpha method").
pub const GEN_ALPHA_MIN_RTOL: f64 = 1e-10;

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
    /// False when the run's forces (`pivot_force_max`, the joints' and the
    /// pivot's forces of its samples) are not right to its tolerance
    /// although everything else is: gen-alpha stepped over the axial modes
    /// that carry them ([`forces::resolved`]). True for every other run.
    pub forces_resolved: bool,
    /// The largest value of each force the model tracks
    /// ([`Model::peak_forces`]: the floor's normal force), at the start,
    /// every accepted step's end and inside the steps where it turns: a
    /// property of the run, whatever its output samples.
    pub peaks: Vec<crate::model::Peak>,
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
            && self
                .peaks
                .iter()
                .all(|p| p.value.is_finite() && p.t.is_finite() && p.reference.is_finite())
    }
}

/// A finished run: the model as it was at the end, the samples, the
/// summary, the work counters and how it ended. Every accessor of a sample
/// asks the model.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory<M = ModelKind> {
    /// The model run (with its pivot's path as the run left it).
    pub model: M,
    /// The pivot `P0` at `t = 0`.
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
    /// Samples, [`Layout::dim`] numbers each, laid out as the model says.
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
    /// The work accumulator `W` (0 for a model without one).
    pub dissipated: f64,
}

impl<M: Model> Trajectory<M> {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// True when no sample was recorded.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Rods (or segments) of the model.
    pub fn links(&self) -> usize {
        self.model.layout().links
    }

    /// Sample `k`.
    pub fn sample(&self, k: usize) -> Sample<'_> {
        let layout = self.model.layout();
        let y = self.state(k);
        Sample {
            t: self.times[k],
            angles: &y[layout.angles],
            rates: &y[layout.rates],
            dissipated: layout.work.map_or(0.0, |i| y[i]),
        }
    }

    /// Every sample, in time order.
    pub fn samples(&self) -> impl Iterator<Item = Sample<'_>> + '_ {
        (0..self.len()).map(|k| self.sample(k))
    }

    /// The state vector of sample `k`.
    pub fn state(&self, k: usize) -> &[f64] {
        let d = self.model.layout().dim;
        &self.states[k * d..(k + 1) * d]
    }

    /// The pivot's position and velocity at sample `k`.
    pub fn pivot_at(&self, k: usize) -> [Vec2; 2] {
        self.model.support(self.times[k], self.state(k))
    }

    /// The joints `P_0..P_n` at sample `k`.
    pub fn joints(&self, k: usize) -> Vec<Vec2> {
        self.model.joints(self.times[k], self.state(k))
    }

    /// The tip at sample `k`.
    pub fn tip(&self, k: usize) -> Vec2 {
        self.model.tip(self.times[k], self.state(k))
    }

    /// The tip's velocity at sample `k` (inertial frame).
    pub fn tip_velocity(&self, k: usize) -> Vec2 {
        self.model.tip_velocity(self.times[k], self.state(k))
    }

    /// The energy at sample `k`, the run's own ([`Model::energy`]).
    pub fn energy(&self, k: usize) -> f64 {
        self.model.energy(self.times[k], self.state(k))
    }

    /// The joint forces `[tension, shear]` at joints `0..=n` at sample `k`.
    pub fn joint_forces(&self, k: usize) -> Vec<Vec2> {
        self.model.joint_forces(self.times[k], self.state(k))
    }

    /// The support's force on the first rod at sample `k`.
    pub fn support_force(&self, k: usize) -> Vec2 {
        self.model.support_force(self.times[k], self.state(k))
    }

    /// The momentum relative to the support at sample `k`.
    pub fn momentum(&self, k: usize) -> Vec2 {
        self.model.momentum(self.times[k], self.state(k))
    }

    /// The floor's force on each contact point at sample `k`
    /// ([`Model::floor_forces`]), `None` without a floor.
    pub fn floor_forces(&self, k: usize) -> Option<Vec<Vec2>> {
        self.model.floor_forces(self.times[k], self.state(k))
    }

    /// The floor's force gathered at each joint at sample `k`, `n + 1` of
    /// them (joint 0 the pivot, joint `n` the tip): joint `j` carries the
    /// contact at rod `j − 1`'s end and at rod `j`'s start, which the
    /// rigid chain's joint would be (physical units; `None` without a
    /// floor). They sum to [`Trajectory::floor_force`].
    pub fn floor_joint_forces(&self, k: usize) -> Option<Vec<Vec2>> {
        let f = self.floor_forces(k)?;
        let mut joints = vec![[0.0, 0.0]; f.len() / 2 + 1];
        for (j, p) in f.iter().enumerate() {
            // Point 2i is rod i's start (joint i), 2i + 1 its end (i + 1).
            let joint = &mut joints[j.div_ceil(2)];
            joint[0] += p[0];
            joint[1] += p[1];
        }
        Some(joints)
    }

    /// The floor's total force on the chain at sample `k` (what a scale
    /// under it reads, upward positive), `None` without a floor.
    pub fn floor_force(&self, k: usize) -> Option<Vec2> {
        let f = self.floor_forces(k)?;
        Some(f.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]))
    }

    /// The weight of what has landed at sample `k`: `g m_i / 2` for each
    /// contact point the floor pushes (each end of rod `i` stands for half
    /// of it; the tip's point also for the tip mass), `None` without a floor.
    pub fn floor_landed_weight(&self, k: usize) -> Option<f64> {
        let f = self.floor_forces(k)?;
        let chain = self.model.chain()?;
        let g = chain.gravity();
        let last = f.len().saturating_sub(1);
        Some(
            f.iter()
                .enumerate()
                .filter(|(_, p)| p[0] != 0.0 || p[1] != 0.0)
                .map(|(j, _)| {
                    let tip = if j == last { chain.tip_mass() } else { 0.0 };
                    g * (0.5 * crate::elastic::rod_mass(chain, j / 2) + tip)
                })
                .sum(),
        )
    }

    /// The length of chain that has landed at sample `k`: `l_i / 2` for
    /// each end of rod `i` at most [`LANDED_HEIGHT`]` l_i` (one rod) above
    /// the floor line or inside it, `None` without a floor: the part of the
    /// chain that lies on the floor or has piled up on it, to about a rod.
    /// It is read off the rods' ends, not off the contact forces: a landed
    /// rod rests at a deflection `m g / 2k` far below the run's tolerance
    /// (3e-9 of `L` on `scenes/cayley-scale.toml`), and on a plastic floor
    /// the landed rods tumble a fraction of a rod above it, so at a sample
    /// most of what has landed is pushed by nothing (the floor pushes at
    /// 37 of the 321 samples of that scene's run, `falling-chain simulate
    /// scenes/cayley-scale.toml --out`). Landed rods thrown higher than a
    /// rod are not counted: on that chain it follows `g t^2 / 2` to 1.5
    /// rods up to `x = L / 2`, and falls behind as the pile is thrown up to
    /// four rods high (0.54 against 0.72 at `t = 1.2`).
    pub fn floor_landed_length(&self, k: usize) -> Option<f64> {
        let (h, a) = self.model.floor_line()?;
        let chain = self.model.chain()?;
        let joints = self.joints(k);
        let (sin, cos) = a.sin_cos();
        let above = |p: Vec2| -sin * p[0] + cos * (p[1] - h);
        Some(
            (0..chain.links())
                .map(|i| {
                    let half = crate::elastic::rod_half_length(chain, i);
                    let ends = [joints[i], joints[i + 1]];
                    let down = ends
                        .iter()
                        .filter(|&&p| above(p) <= LANDED_HEIGHT * 2.0 * half)
                        .count();
                    half * down as f64
                })
                .sum(),
        )
    }
}

/// How high above the floor a rod's end still counts as landed, in its
/// rod's lengths ([`Trajectory::floor_landed_length`]): the rods landed on
/// a plastic floor tumble up to 0.9 of a rod above it (measured on the
/// 40-rod Cayley chain of `tests/physics/floor.rs`).
pub const LANDED_HEIGHT: f64 = 1.0;

impl Trajectory<ModelKind> {
    /// The chain run.
    pub fn chain(&self) -> &Chain {
        self.model.chain()
    }
}

>>>>>>> i53
/// An observer a caller attaches to a run ([`Solve::watch`]), beside the
/// run's own recorder and summary: it sees the model and every accepted
/// step (its end state, its derivative and its continuous extension), so a
/// study can track a quantity at every step instead of reading it off the
/// samples.
pub trait Watch<M> {
    /// The run's start at `t0` in `y0`.
    fn start(&mut self, _model: &M, _t0: f64, _y0: &[f64]) {}
    /// An accepted step.
    fn step(&mut self, model: &M, step: &StepView<'_>);
    /// True to stop the run (it ends `interrupted`).
    fn stop(&self) -> bool {
        false
    }
}

/// Runs `method` on `model` (a [`Model`], or a [`Chain`] whose model
/// [`ModelKind::of`] chooses) from `start` over `[0, options.t_end]`.
///
/// Never panics on a failing run and never returns a NaN in its state: a run
/// that hits a non-finite value stops with `Status::Diverged` at the last
/// finite state. A run whose every state is finite but whose summary is not
/// (an energy that overflows, say) also ends `Status::Diverged`, with
/// `t_failed` the first time a non-finite value was recorded: a NaN or an
/// infinity in the summary never comes with `Status::Ok`. A finite run whose
/// energy balance error `max |E + W - E(0)|` exceeds the model's energy
/// scale ([`Model::energy_scale`]), or with a prescribed pivot motion
/// [`DRIVE_BALANCE_FRACTION`] of that scale plus the work done, ends
/// `Status::Inaccurate`, with `t_failed` the first step end where it did. A
/// run whose `options.cancel` is set ends `Status::Interrupted` at its last
/// accepted step (`t_failed = t_reached`).
///
/// Every option is checked first ([`Model::validate`]): nothing is
/// allocated for a run out of bounds, and a method the model cannot run is
/// an error, not a failed run.
pub fn solve<I: IntoModel>(
    model: I,
    start: &State,
    method: Method,
    options: &SolveOptions,
) -> Result<Trajectory<I::Model>, InvalidParameter> {
    Solve::new(model, start, method, options).run()
}

/// A run being set up: [`solve`] with observers attached ([`Solve::watch`]).
pub struct Solve<'a, M: Model> {
    model: M,
    start: &'a State,
    method: Method,
    options: &'a SolveOptions,
    watches: Vec<&'a mut dyn Watch<M>>,
}

impl<'a, M: Model> Solve<'a, M> {
    /// The run of `method` on `model` from `start` with `options`.
    pub fn new<I: IntoModel<Model = M>>(
        model: I,
        start: &'a State,
        method: Method,
        options: &'a SolveOptions,
    ) -> Self {
        Self {
            model: model.into_model(),
            start,
            method,
            options,
            watches: Vec::new(),
        }
    }

    /// Attaches `watch`: it sees the start and every accepted step.
    pub fn watch(mut self, watch: &'a mut dyn Watch<M>) -> Self {
        self.watches.push(watch);
        self
    }

    /// Runs it.
    pub fn run(self) -> Result<Trajectory<M>, InvalidParameter> {
        let Solve {
            mut model,
            start,
            method,
            options,
            mut watches,
        } = self;
        model.validate(method, options)?;
        let y0 = model.initial_state(start)?;
        let layout = model.layout();
        let settings = Settings {
            scales: model.time_scales(),
            ..options.settings()
        };
        let span = Span {
            t0: 0.0,
            y0: &y0,
            t_end: options.t_end,
            settings: &settings,
        };
        let mut parts = Parts {
            rec: Recorder::new(
                layout.dim,
                options.t_end,
                options.output_dt,
                options.cancel.clone(),
            ),
            tally: Tally::new(&model, tally::run_tolerance(method, options)),
            watches: &mut watches,
        };
        let clock = Instant::now();
        let run = match model.event_time() {
            Some(te) if te > span.t0 && te < span.t_end => {
                run_cut(&mut model, method, &span, te, &mut parts)
            }
            _ => segment(&model, method, &span, &mut parts),
        };
        let Parts { rec, tally, .. } = parts;
        Ok(trajectory(
            model,
            start.anchor,
            method,
            options,
            run,
            (rec, tally),
            clock,
        ))
    }
}
<<<<<<< HEAD
=======

/// A run's observers: the recorder, the summary's tally, the caller's.
struct Parts<'w, 'a, M> {
    rec: Recorder,
    tally: Tally,
    watches: &'w mut Vec<&'a mut dyn Watch<M>>,
}

/// [`Parts`] with the model they ask, as one [`Observer`] for one segment.
struct Observers<'p, 'w, 'a, M> {
    model: &'p M,
    parts: &'p mut Parts<'w, 'a, M>,
}

impl<M: Model> Observer for Observers<'_, '_, '_, M> {
    fn start(&mut self, t0: f64, y0: &[f64], f0: &[f64]) {
        let p = &mut *self.parts;
        p.tally.start(self.model, &mut p.rec, t0, y0, f0);
        p.rec.start(t0, y0);
        for w in p.watches.iter_mut() {
            w.start(self.model, t0, y0);
        }
    }

    fn step(&mut self, step: &StepView<'_>) {
        let p = &mut *self.parts;
        p.tally.step(self.model, &mut p.rec, step);
        p.rec.step(step);
        for w in p.watches.iter_mut() {
            w.step(self.model, step);
        }
    }

    fn stop(&self) -> bool {
        self.parts.rec.cancelled() || self.parts.watches.iter().any(|w| w.stop())
    }
}

/// The model's problem with the model's plan for `auto`: what the
/// integrators see.
struct Planned<'m> {
    inner: Box<dyn Problem + 'm>,
    plan: AutoPlan,
    /// The layout's angles and positions ([`Problem::configuration`]).
    configuration: Vec<std::ops::Range<usize>>,
}

impl OdeSystem for Planned<'_> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.inner.rhs(t, y, dy)
    }
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        self.inner.jvp(t, y, v, jv)
    }
}

impl Problem for Planned<'_> {
    fn banded_dae(&self, t0: f64, y0: &[f64]) -> Option<BandedDae> {
        self.inner.banded_dae(t0, y0)
    }
    fn auto_plan(&self) -> Option<AutoPlan> {
        Some(self.plan)
    }
    fn configuration(&self) -> Vec<std::ops::Range<usize>> {
        self.configuration.clone()
    }
    fn measured(&self) -> Option<Box<dyn fc_methods::Measured>> {
        self.inner.measured()
    }
}

/// The unknowns `gen-alpha` measures its local error on
/// ([`Problem::configuration`]): the configuration alone (the angles, and
/// the elastic chain's positions) where the model oscillates stiffly and
/// the step damps those modes unresolved (elastic links, bending springs,
/// BEAM), so that their rates do not hold the step; every unknown (empty)
/// on a rigid chain without bending springs, whose modes the step
/// resolves: measured on the angles alone, the rates' errors went
/// unchecked and its energy drifted (docs/model.md, "The
/// generalized-alpha method").
fn error_configuration<M: Model>(model: &M, layout: Layout) -> Vec<std::ops::Range<usize>> {
    if model
        .chain()
        .is_some_and(|c| !c.is_elastic() && c.bending_stiffness() == 0.0)
    {
        return Vec::new();
    }
    std::iter::once(layout.angles)
        .chain(layout.positions)
        .filter(|r| !r.is_empty())
        .collect()
}

/// One segment of a run: `method` on the model's problem over `span`.
fn segment<M: Model>(
    model: &M,
    method: Method,
    span: &Span<'_>,
    parts: &mut Parts<'_, '_, M>,
) -> Run {
    let layout = model.layout();
    let mut problem = Planned {
        inner: model.problem(),
        plan: model.auto_plan(span.settings.rtol),
        configuration: error_configuration(model, layout),
    };
    let mut obs = Observers { model, parts };
    registry::run_with(
        model.integrator(method),
        method,
        &mut problem,
        span,
        &mut obs,
    )
}

/// Runs `method` over `span` in two pieces cut at the model's event
/// `t_cut` (inside the span), from one set of observers (as `auto`'s
/// handover): the first piece up to `t_cut`, then [`Model::at_event`] with
/// the state reached there, then the rest, with the steps left of the
/// budget. The two pieces' work adds up. A first piece that fails or is
/// stopped ends the whole run there.
fn run_cut<M: Model>(
    model: &mut M,
    method: Method,
    span: &Span<'_>,
    t_cut: f64,
    parts: &mut Parts<'_, '_, M>,
) -> Run {
    let held = Span {
        t_end: t_cut,
        ..*span
    };
    let first = segment(model, method, &held, parts);
    if !first.outcome.status.is_ok() || first.outcome.t_reached < t_cut {
        return first;
    }
    let mut y = first.outcome.y_end.clone();
    model.at_event(t_cut, &mut y);
    let done = first.outcome.stats;
    let settings = span.settings.after(&done);
    let rest = Span {
        t0: t_cut,
        y0: &y,
        t_end: span.t_end,
        settings: &settings,
    };
    let mut second = segment(model, method, &rest, parts);
    second.outcome.stats += done;
    second.segments.splice(0..0, first.segments);
    second
}

/// The trajectory of a finished run of `method` on `model`: its summary
/// from the tally (finished here) and the final state, and its status: a
/// run that ended `ok` becomes `diverged` if its summary is not finite and
/// `inaccurate` if its energy balance error exceeds the model's energy
/// scale (or, driven, the tally's limit). `clock` started before the run.
fn trajectory<M: Model>(
    model: M,
    anchor: Vec2,
    method: Method,
    options: &SolveOptions,
    run: Run,
    (mut rec, mut tally): (Recorder, Tally),
    clock: Instant,
) -> Trajectory<M> {
    let Run { outcome, segments } = run;
    let wall_seconds = clock.elapsed().as_secs_f64();
    tally.finish(&model, &mut rec, outcome.t_reached, &outcome.y_end);
    rec.finish(outcome.t_reached, &outcome.y_end);
    let y = &outcome.y_end;
    let summary = Summary {
        energy_start: tally.energy_start,
        energy_end: tally.energy_end,
        dissipated: tally.work_of(y),
        energy_balance_error: tally.energy_balance_error,
        max_energy_rise: tally.max_energy_rise,
        tip_end: model.tip(outcome.t_reached, y),
        tip_velocity_end: model.tip_velocity(outcome.t_reached, y),
        tip_speed_max: tally.tip_speed.value,
        t_tip_speed_max: tally.tip_speed.t,
        pivot_force_max: model
            .tracks_support_force()
            .then_some((tally.support_force_max, tally.t_support_force_max)),
        peaks: tally.peaks(),
        forces_resolved: forces::resolved(
            model.chain(),
            method,
            &segments.iter().map(|g| g.method).collect::<Vec<_>>(),
            options,
            tally.h_max,
        ),
        wall_seconds,
    };
    // A non-finite value in the summary (an energy that overflowed, a NaN
    // from the observer) is a run that went wrong, even when every state
    // stayed finite: it must not pass as `ok`.
    // A finite run whose energy balance error exceeds the model's energy
    // scale is not a solution of the model (a step far too large, a
    // tolerance far too loose): it must not pass as `ok` either; with a
    // driven pivot, nor one whose error is a percent of the work done
    // (`Tally::balance_limit`).
    let (status, t_failed) = if outcome.status.is_ok() && !summary.all_finite() {
        let t = rec.t_nonfinite.unwrap_or(outcome.t_reached);
        (Status::Diverged, Some(t))
    } else if outcome.status.is_ok()
        && summary.energy_balance_error > model.energy_scale().min(tally.balance_limit())
    {
        let t = tally.t_inaccurate.unwrap_or(outcome.t_reached);
        (Status::Inaccurate, Some(t))
    } else {
        (outcome.status, outcome.t_failed)
    };
    Trajectory {
        model,
        anchor,
        method,
        status,
        t_end: options.t_end,
        t_reached: outcome.t_reached,
        t_failed,
        stats: outcome.stats,
        segments,
        summary,
        times: std::mem::take(&mut rec.times),
        states: std::mem::take(&mut rec.states),
        final_state: outcome.y_end,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::state::Start;
    use crate::system::ChainSystem;
    use fc_methods::all_finite;

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
    /// one after the other: the first held, the second let go from the
    /// state the first reached, with the same end state and the work of
    /// both counted, for an explicit and an implicit method.
    #[test]
    fn a_run_cut_in_two_is_its_two_pieces_with_both_pieces_work() {
        let (chain, start, y0) = eight_rods_on_span_3();
        let mut params = chain.params().clone();
        params.pivot.release = Some(1.0);
        let chain = Chain::new(params).unwrap();
        let options = SolveOptions {
            t_end: 2.0,
            ..Default::default()
        };
        let settings = options.settings();
        let span = Span {
            t0: 0.0,
            y0: &y0,
            t_end: 2.0,
            settings: &settings,
        };
        let mut watches = Vec::new();
        for method in [Method::Dopri5, Method::Bdf] {
            let mut model = ModelKind::of(&chain);
            model.initial_state(&start).unwrap();
            let mut parts = Parts {
                rec: Recorder::new(y0.len(), 2.0, None, None),
                tally: Tally::new(&model, None),
                watches: &mut watches,
            };
            let held = Span { t_end: 1.0, ..span };
            let first = segment(&model, method, &held, &mut parts).outcome;
            let mut y1 = first.y_end.clone();
            model.at_event(1.0, &mut y1);
            let after = settings.after(&first.stats);
            let rest = Span {
                t0: 1.0,
                y0: &y1,
                t_end: 2.0,
                settings: &after,
            };
            let second = segment(&model, method, &rest, &mut parts).outcome;

            let mut model = ModelKind::of(&chain);
            model.initial_state(&start).unwrap();
            let mut parts = Parts {
                rec: Recorder::new(y0.len(), 2.0, None, None),
                tally: Tally::new(&model, None),
                watches: &mut watches,
            };
            let cut = run_cut(&mut model, method, &span, 1.0, &mut parts).outcome;
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
        let settings = SolveOptions {
            t_end: 4.0,
            ..Default::default()
        }
        .settings();
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
>>>>>>> i53
