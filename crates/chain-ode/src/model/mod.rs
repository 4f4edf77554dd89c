//! What a state is and what it means: the [`Model`] trait (the problem
//! side), the [`StateView`] trait (what a state means), and the one place
//! that decides which model a chain is ([`ModelKind::choose`]).
//!
//! The integrators see only a [`Problem`] (`y' = f(t, y)`, and maybe a
//! banded DAE); they never look inside a state. The run layer ([`solve`](crate::solve))
//! sees only a [`Model`]: it asks the model for its first state, the
//! problem to integrate, its events, and, at every accepted step, its view
//! ([`Model::view`]) for the energy and the tip's velocity of the state (one
//! pass). The trajectory keeps the model, and every accessor of a sample
//! (the tip, the joints, the joint forces, the energy) asks its view again.
//! No other code branches on the kind of model.
//!
//! The models of the crate, and the view each shares:
//! * [`RigidModel`]: the chain of rigid rods (`[phi, w, W]`, `2 n + 1`),
//!   viewed by [`RigidView`];
//! * [`ElasticModel`]: elastic links (`[phi, w, W, x, y, vx, vy]`, `6 n + 1`),
//!   viewed by [`LinkView`];
//! * [`ContactModel`]: rigid rods on a constraint floor, in maximal
//!   coordinates (`[phi, w, W, x, y, vx, vy]` and the forces of the last
//!   step, `10 n + 5`), run by `moreau-jean`, viewed by [`ContactView`];
//! * [`ReportModel`](crate::report::ReportModel)'s chain, [`ReportChain`]: the
//!   student report's equations, as a control: the rigid model's state,
//!   viewed by the same [`RigidView`] with the report's energy;
//! * [`BeamModel`]: the BEAM benchmark of Hairer & Wanner (`[z, z']`, `2 n`),
//!   its own view.
//!
//! A model of another crate implements [`Model`] (and a [`StateView`], or
//! reuses one) and runs through the same [`solve`](crate::solve)
//! (ARCHITECTURE.md, "How to add a model").
//!
//! Its files: `view.rs` (the [`StateView`] trait), `rigid.rs`, `elastic.rs`,
//! `contact.rs` (one model and its view each), `report.rs` (the report's
//! model on the rigid view) and `beam.rs`, `kind.rs` (the chain's models as
//! one type, chosen in one place: [`ModelKind::choose`]).

pub mod beam;
mod contact;
mod elastic;
mod kind;
mod report;
mod rigid;
mod view;

use std::ops::Range;

pub use beam::BeamModel;
pub use contact::{ContactModel, ContactView, START_TOLERANCE as CONTACT_START_TOLERANCE};
pub use elastic::{ElasticModel, LinkView};
pub use kind::{IntoModel, ModelKind};
pub use report::ReportChain;
pub(crate) use rigid::rigid_energy;
pub(crate) use rigid::RigidForces;
pub use rigid::{bdf_crossover_gamma, RigidModel, RigidView};
pub use view::StateView;

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

/// A model: a physical system with a state vector and the problem that
/// integrates it (the problem side); what a state means is its view
/// ([`Model::view`]).
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

    /// What a state means: the tip, the joints, the energy and the forces
    /// of a state ([`StateView`]), shared by the models of one state layout.
    fn view(&self) -> &dyn StateView;
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
