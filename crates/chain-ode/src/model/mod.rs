//! What a state means: the [`Model`] trait, and the one place that decides
//! which model a chain is ([`ModelKind::of`]).
//!
//! The integrators see only a [`Problem`] (`y' = f(t, y)`, and maybe a
//! banded DAE); they never look inside a state. The run layer ([`solve`](crate::solve))
//! sees only a [`Model`]: it asks the model for its first state, the
//! problem to integrate, its events, and, at every accepted step, for the
//! energy and the tip's velocity of the state (one pass). The trajectory
//! keeps the model, and every accessor of a sample (the tip, the joints,
//! the joint forces, the energy) asks it again. No other code branches on
//! the kind of model.
//!
//! The models of the crate:
//! * [`RigidModel`]: the chain of rigid rods (`[phi, w, W]`, `2 n + 1`);
//! * [`ElasticModel`]: elastic links (`[phi, w, W, x, y, vx, vy]`, `6 n + 1`);
//! * [`ContactModel`]: rigid rods on a constraint floor, in maximal
//!   coordinates (`[phi, w, W, x, y, vx, vy]` and the forces of the last
//!   step, `10 n + 5`), run by `moreau-jean`;
//! * [`ReportModel`](crate::report::ReportModel)'s chain, [`ReportChain`]: the
//!   student report's equations, as a control;
//! * [`BeamModel`]: the BEAM benchmark of Hairer & Wanner (`[z, z']`, `2 n`).
//!
//! A model of another crate implements [`Model`] and runs through the same
//! [`solve`](crate::solve) (ARCHITECTURE.md, "How to add a model").
//!
//! Its files: `rigid.rs`, `elastic.rs`, `contact.rs`, `report.rs` and
//! `beam.rs` (one model each), `kind.rs` (the chain's models as one type, chosen in one
//! place: [`ModelKind::choose`]).

pub mod beam;
mod contact;
mod elastic;
mod kind;
mod report;
mod rigid;

use std::ops::Range;

pub use beam::BeamModel;
pub use contact::{ContactModel, START_TOLERANCE as CONTACT_START_TOLERANCE};
pub use elastic::ElasticModel;
pub use kind::{IntoModel, ModelKind};
pub use report::ReportChain;
pub(crate) use rigid::rigid_energy;
pub(crate) use rigid::RigidForces;
pub use rigid::{bdf_crossover_gamma, RigidModel};

use crate::chain::Chain;
use crate::kinematics::Vec2;
pub use crate::solve::peaks::{ForceScratch, Peak, PeakForce, PeakValue};
use crate::solve::SolveOptions;
use crate::state::State;
use fc_methods::InvalidParameter;
use fc_methods::Problem;
use fc_methods::{AutoPlan, Integrator, Method, TimeScales};

/// Where the parts of a model's state vector are.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Layout {
    /// Rods (or segments) of the model.
    pub links: usize,
    /// Length of the state vector.
    pub dim: usize,
    /// The rods' angles (rad).
    pub angles: Range<usize>,
    /// Their rates (rad per time unit).
    pub rates: Range<usize>,
    /// The work accumulator `W` (energy dissipated or done on the chain),
    /// if the model keeps one.
    pub work: Option<usize>,
    /// The rod centres' positions `x` then `y`, for a model that has them
    /// as unknowns (the elastic chain).
    pub positions: Option<Range<usize>>,
    /// Their velocities `vx` then `vy`.
    pub velocities: Option<Range<usize>>,
    /// Numbers one output sample costs (the state, its time, and the joints
    /// and forces a viewer reads from it): what bounds `run.output_dt`.
    pub sample_numbers: u64,
}

impl Layout {
    /// The layout of `[angles (n), rates (n), W, rest]` with `dim` entries.
    pub(crate) fn angles_rates_work(links: usize, dim: usize, sample_numbers: u64) -> Self {
        Self {
            links,
            dim,
            angles: 0..links,
            rates: links..2 * links,
            work: Some(2 * links),
            positions: None,
            velocities: None,
            sample_numbers,
        }
    }
}

/// What the run layer reads from a state at every accepted step, in one
/// pass: the energy `E` (the balance `E + W = E(0)`), the tip's velocity and
/// its acceleration (the tip speed's slope, for its continuous maximum).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observed {
    /// `E` in the model's energy units.
    pub energy: f64,
    /// The tip's velocity in the inertial frame.
    pub tip_velocity: Vec2,
    /// The tip's acceleration (from the state and its derivative).
    pub tip_acceleration: Vec2,
}

/// A model: a physical system with a state vector, the problem that
/// integrates it, and what a state means.
///
/// Conventions: time in the model's units, energies in its units; a state
/// is the vector the model's [`Problem`] integrates, laid out as
/// [`Model::layout`] says. Every method takes `&self` except the two that
/// change the model along a run (the start and the event), so that a
/// trajectory's model is the model as it was at the end of the run.
pub trait Model: Clone + std::fmt::Debug + PartialEq {
    /// The model's name in output: `"rigid"`, `"elastic"`, `"report"`, `"beam"`.
    fn name(&self) -> &'static str;

    /// The chain this model is of, if it is a chain's.
    fn chain(&self) -> Option<&Chain> {
        None
    }

    /// Where the parts of the state are.
    fn layout(&self) -> Layout;

    /// The bounds of a run that depend on this model and `method` (the
    /// methods it can run, the sizes they allocate, the steps its time
    /// scales allow), beyond [`SolveOptions::validate`]. Checked before any
    /// allocation of the run.
    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter>;

    /// The first state from `start` (and whatever the start changes in the
    /// model, such as a pivot let go at `t = 0`).
    fn initial_state(&mut self, start: &State) -> Result<Vec<f64>, InvalidParameter>;

    /// The problem the integrators run, in the model's present phase.
    fn problem(&self) -> Box<dyn Problem + '_>;

    /// What runs `method` on this model: the registry's integrator, unless
    /// the model brings its own (the report's stepper).
    fn integrator(&self, method: Method) -> &'static Integrator {
        method.integrator()
    }

    /// The model's energy scale: a run whose balance error exceeds it is
    /// `inaccurate`.
    fn energy_scale(&self) -> f64;

    /// True when the model's support moves by a prescribed motion: the
    /// balance is then held to a fraction of the work done as well
    /// ([`DRIVE_BALANCE_FRACTION`](crate::DRIVE_BALANCE_FRACTION)).
    fn is_driven(&self) -> bool {
        false
    }

    /// The largest steps its prescribed motions allow.
    fn time_scales(&self) -> TimeScales {
        TimeScales::NONE
    }

    /// `auto`'s plan for this model at `rtol`.
    fn auto_plan(&self, rtol: f64) -> AutoPlan {
        AutoPlan::generic(rtol)
    }

    /// The time of the model's event (the release of the pivot), if any;
    /// a run cuts there when it falls inside `(0, t_end)`.
    fn event_time(&self) -> Option<f64> {
        None
    }

    /// What happens at the event, at `t` in the state `y` (which the model
    /// may change). The problem is then made anew from the model.
    fn at_event(&mut self, _t: f64, _y: &mut [f64]) {}

    /// The run's view of `y` at `t` (`f = y'` there), in one pass. `trig`
    /// is scratch the model may use (no allocation once it has grown).
    fn observe(&self, t: f64, y: &[f64], f: &[f64], trig: &mut Vec<(f64, f64)>) -> Observed;

    /// The energy of `y` at `t`, as [`Model::observe`] has it.
    fn energy(&self, t: f64, y: &[f64]) -> f64;

    /// The tip (the free end) at `t`.
    fn tip(&self, t: f64, y: &[f64]) -> Vec2;

    /// The tip's velocity at `t` in the inertial frame.
    fn tip_velocity(&self, t: f64, y: &[f64]) -> Vec2;

    /// The support's (pivot's) position and velocity at `t`.
    fn support(&self, _t: f64, _y: &[f64]) -> [Vec2; 2] {
        [[0.0, 0.0], [0.0, 0.0]]
    }

    /// The joints `P_0..P_n` at `t`.
    fn joints(&self, t: f64, y: &[f64]) -> Vec<Vec2>;

    /// The joint forces `[tension, shear]` at joints `0..=n` at `t`.
    fn joint_forces(&self, t: f64, y: &[f64]) -> Vec<Vec2>;

    /// The force of the support on the first rod at `t` (zero where the
    /// model has none).
    fn support_force(&self, _t: f64, _y: &[f64]) -> Vec2 {
        [0.0, 0.0]
    }

    /// True when the summary's tip speed maximum is refined inside the
    /// steps on the continuous extension (the chains'); false keeps the
    /// step ends' values only, so that a benchmark's work counters are its
    /// integrator's alone (a lazy dense output costs right-hand sides).
    fn refines_tip_speed(&self) -> bool {
        true
    }

    /// The momentum relative to the support.
    fn momentum(&self, _t: f64, _y: &[f64]) -> Vec2 {
        [0.0, 0.0]
    }

    /// The floor's force on each contact point at `t` (physical units; the
    /// elastic chain's: rod 0's start, rod 0's end, rod 1's start, ...), or
    /// `None` for a model without a floor.
    fn floor_forces(&self, _t: f64, _y: &[f64]) -> Option<Vec<Vec2>> {
        None
    }

    /// The floor as placed for the run, `(height at x = 0, angle)` in scene
    /// coordinates, or `None` without a floor.
    fn floor_line(&self) -> Option<(f64, f64)> {
        None
    }

    /// The forces whose peaks the run tracks at every accepted step
    /// ([`PeakForce`]; `Summary::peaks`): none by default.
    fn peak_forces(&self) -> &'static [PeakForce] {
        &[]
    }

    /// `force`'s value and reference at `(t, y)` ([`PeakValue`]), for a
    /// force of [`Model::peak_forces`]: a function of the state alone,
    /// O(n) and allocation free once `scratch` has grown at the run's
    /// first call (it runs at every step).
    fn peak_force(
        &self,
        _force: PeakForce,
        _t: f64,
        _y: &[f64],
        _scratch: &mut ForceScratch,
    ) -> PeakValue {
        [0.0, 0.0]
    }
}

/// A start for `chain` must give one angle and one rate per rod.
pub(crate) fn check_start(chain: &Chain, start: &State) -> Result<(), InvalidParameter> {
    let n = chain.links();
    crate::chain::check(
        start.angles.len() == n && start.rates.len() == n,
        "start",
        "a state with chain.links angles and rates",
        start.angles.len(),
    )
}
