//! The integration methods and the narrow interface they run on, knowing
//! no model: a problem is a [`Problem`] (an [`OdeSystem`] `y' = f(t, y)`,
//! which may also state itself as a banded index-1 [`SemiExplicitDae`] for
//! the O(n) BDF), and a method, named by a [`Method`] and run by its
//! [`Integrator`], advances it, showing every accepted step and its
//! continuous extension to an [`Observer`], and returns an [`Outcome`]
//! with its work [`Stats`] and a [`Status`]. The methods: fixed-step RK4,
//! the explicit pairs DOPRI5 and DOP853 (one step loop), diffsol's BDF on
//! the banded DAE (its Newton matrices by a block-tridiagonal or a general
//! sparse LU) and on the dense explicit form, and `auto`, a policy over
//! them ([`AutoPlan`]).
//!
//! Its caller is chain-ode's run layer (`chain_ode::solve`), which builds
//! each model's problem, hands it to a method with the run's [`Settings`]
//! and watches it through its observers; chain-ode re-exports what its own
//! callers name ([`Method`], [`Stats`], [`Status`], ...). Work counters
//! come from what was called ([`Counted`], the DAE's counters, diffsol's
//! statistics), never from counting by hand; a run never panics and never
//! returns a NaN state.
//!
//! Adding a method: one file with its [`Integrator`] constant, its
//! [`Method`] variant and its line in the registry (`registry.rs`); see
//! ARCHITECTURE.md, "How to add a method".

mod auto;
mod bdf;
mod bdf_dense;
mod block_lu;
mod diffsol_driver;
mod dop853;
mod dop853_tableau;
mod dopri5;
mod error;
mod explicit;
mod genalpha;
mod integrator;
#[cfg(test)]
mod known_solutions;
mod method;
mod newton_matrix;
mod ode;
#[doc(hidden)]
pub mod registry;
#[doc(hidden)]
pub mod rk4;
mod sparse_lu;
mod step_size;
#[cfg(test)]
mod test_problems;
#[cfg(any(test, feature = "test-support"))]
#[doc(hidden)]
pub mod testing;

pub use auto::AutoPlan;
pub use error::InvalidParameter;
pub use genalpha::{DEFAULT_RHO_INF, RHO_INF_RANGE};
pub use integrator::{Accuracy, Integrator, TimeScales};
pub use method::{Method, Segment};
pub use ode::{
    all_finite, BandedDae, Cancel, Counted, Interpolant, Measured, Observer, OdeSystem, Outcome,
    Problem, SemiExplicitDae, Stats, Status, StepView,
};

// The run layer's side of the interface: what it hands a method and gets
// back, and the pieces of the methods it measures or reuses (its unit
// costs, the report's stepper on the fixed-step loop).
#[doc(hidden)]
pub use auto::AUTO_DOP853_RTOL;
#[doc(hidden)]
pub use bdf::with_general_sparse_lu;
#[doc(hidden)]
pub use block_lu::BlockLu;
#[doc(hidden)]
pub use genalpha::{with_gen_alpha_policy, ControlPolicy, GenAlphaPolicy, ReusePolicy};
#[doc(hidden)]
pub use integrator::{Run, Settings, Span};
#[doc(hidden)]
pub use newton_matrix::NewtonMatrix;
#[doc(hidden)]
pub use sparse_lu::LuLog;
