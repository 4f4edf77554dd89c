//! The falling chain of `n` rigid rods: its dynamics in O(n), its energy,
//! its models (the rigid and the elastic chain, the report's model, BEAM),
//! and the run layer that runs the integrators on them. The integrators
//! themselves, and the interface they see ([`Problem`], [`OdeSystem`],
//! [`SemiExplicitDae`]), live in `fc-methods`, which knows no chain; this
//! crate re-exports what its callers name ([`Method`], [`Stats`],
//! [`Status`], ...).
//!
//! Data flows one way: a [`Chain`] and a [`Start`] give a [`State`]; [`solve`]
//! runs a [`Method`] on it and returns a [`Trajectory`] with its samples, its
//! [`Summary`], its work [`Stats`] and a [`Status`]. This crate knows nothing
//! of files, scene formats or plotting.
//!
//! Conventions (see `docs/model.md`): angles `phi_i` from the horizontal,
//! counter-clockwise; rod 1 pinned at `P0`; `mass` is per rod; gravity along -y.
//!
//! `contact/` ([`contact`]): the rigid chain on a constraint floor as a
//! nonsmooth problem for `moreau-jean` (issue 50).

//! # What is public
//!
//! The API is what a scene, a study or a test needs, and nothing of how the
//! methods work inside:
//!
//! * running: [`solve`], [`Chain`] (from [`ChainParams`]), [`Start`] ->
//!   [`State`], [`Method`] (with its [`Accuracy`] parameter),
//!   [`SolveOptions`] -> [`Trajectory`] with its
//!   [`Summary`], [`Segment`]s, [`Stats`] and [`Status`];
//!   [`bdf_crossover_gamma`], the damping rate past which `auto` runs BDF;
//! * the physics the studies and the tests check the runs against:
//!   [`kinematics`] (joints, tip, energies), [`analysis`] (quantities of
//!   finished runs and closed forms), [`modes`] (the linearised hanging
//!   chain), [`dense`] (the O(n^3) reference solve), [`dynamics`] (the O(n)
//!   [`accelerations`](dynamics::accelerations)), [`dae`] (the banded DAE the
//!   O(n) BDF runs on) and [`ChainSystem`] (the right-hand side `y' = f(y)`
//!   and its Jacobian-vector product, as inherent methods);
//! * the report's own model, as a control: [`report`] ([`report::ReportModel`],
//!   its errata as switches), whose model [`ReportChain`] runs by [`solve`];
//! * errors with their fields: [`InvalidParameter`], [`StartError`].
//!
//! * the interface a model's problem implements, from fc-methods:
//!   [`OdeSystem`], [`Problem`], [`SemiExplicitDae`], [`BandedDae`].
//!
//! Everything else is internal: the observers of a run, the methods'
//! insides (fc-methods'), the scalar type of the recursion (`f64` or a dual
//! number).
//!
//! # Its files
//!
//! * the chain: `chain.rs` (its parameters, validated once), `profile.rs`
//!   (per-rod masses and lengths), `profile_refine.rs` (a list profile cut
//!   again for any `n`), `pivot.rs` (how `P0` moves or is let go),
//!   `floor.rs` (the floor's line and contact law), `state.rs` (states and
//!   the starts that make them), `load/` (the forces every path sums);
//! * the dynamics: `scalar.rs` (`f64` or a dual number), `dynamics.rs` (the
//!   O(n) recursion), `system.rs` (the rigid chain as `y' = f(y)`),
//!   `dae.rs` and `dae_frame.rs` (the banded index-1 DAE, in the rods'
//!   frames for `bdf`), `dense.rs` (the O(n^3) reference), `elastic.rs`
//!   (the elastic chain), `report.rs` (the report's own equations);
//! * the models and the run: `model/` (the [`Model`] trait and each model),
//!   `solve/` (the run layer);
//! * checks and closed forms: `kinematics.rs`, `analysis.rs`, `modes.rs`
//!   (the hanging chain's small oscillations), `tip_mass_law.rs` (the folded
//!   chain with a tip mass), `beam.rs` (the BEAM benchmark),
//!   `methods_on_chains.rs` (the integrators' tests that need a chain).

pub mod analysis;
pub mod beam;
mod chain;
pub mod contact;
pub mod dae;
pub mod dae_frame;
pub mod dense;
pub mod dynamics;
pub mod elastic;
pub mod floor;
pub mod kinematics;
pub mod load;
#[cfg(test)]
mod methods_on_chains;
pub mod model;
pub mod modes;
pub mod pivot;
pub mod profile;
mod profile_refine;
pub mod report;
mod scalar;
mod solve;
mod state;
mod system;
pub mod tip_mass_law;

pub use chain::{Chain, ChainParams, MAX_LINKS};
pub use elastic::ElasticSystem;
#[doc(hidden)]
pub use fc_methods::with_general_sparse_lu;
pub use fc_methods::{
    Accuracy, AutoPlan, BandedDae, Cancel, Integrator, Interpolant, InvalidParameter, Method,
    Nonsmooth, OdeSystem, Problem, Row, RowKind, Segment, SemiExplicitDae, Stats, Status,
    StepRecord, StepView,
};
pub use floor::{Floor, FloorLaw};
pub use kinematics::Vec2;
pub use model::beam::BEAM_MAX_STEPS;
pub use model::{
    bdf_crossover_gamma, BeamModel, ContactModel, ContactView, ElasticModel, ForceScratch,
    IntoModel, Layout, LinkView, Model, ModelKind, Observed, Peak, PeakForce, PeakValue,
    ReportChain, RigidModel, RigidView, StateView,
};
pub use pivot::{Pivot, PivotPath, TimeScales, STEPS_PER_TIME_SCALE};
pub use profile::{Profile, Rods};
pub use solve::auto_elastic::{
    axial_stiffness_ratio, floor_damping_ratio, joint_damping_ratio, AUTO_ELASTIC_ZETA,
    AUTO_GEN_ALPHA_MAX_STIFFNESS, AUTO_GEN_ALPHA_MIN_ATOL, AUTO_GEN_ALPHA_RHO_INF,
    AUTO_GEN_ALPHA_RTOL, AUTO_GEN_ALPHA_STIFFNESS, AUTO_GEN_ALPHA_TOLERANCE,
};
pub use solve::memory;
pub use solve::{
    solve, Sample, Solve, SolveOptions, Summary, Trajectory, Watch, ATOL_RANGE,
    BALANCE_PER_TOLERANCE, BDF_DENSE_MAX_ELASTIC_LINKS, BDF_DENSE_MAX_LINKS,
    DRIVE_BALANCE_FRACTION, GEN_ALPHA_MIN_RTOL, MAX_OUTPUT_BYTES, REPORT_METHODS, RTOL_RANGE,
};
#[doc(hidden)]
pub use solve::{unit_costs, UnitCosts};
pub use state::{Start, StartError, State, MAX_START_ANGLE};
pub use system::ChainSystem;
