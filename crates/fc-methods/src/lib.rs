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
//!
//! Its files:
//! * `auto.rs`: `auto`: a policy over the registered methods, run by the problem's `AutoPlan`: its implicit method (BDF, or gen-alpha) from the start ...
//! * `bdf.rs`: `bdf`: diffsol's BDF (variable order 1-5) on a problem's banded, index-1 DAE (the chain's is `ChainDae`), with sparse linear algebra: every step of the chain costs O(n).
//! * `bdf_dense.rs`: `bdf-dense`: diffsol's BDF (variable order 1-5) on the explicit form `y' = f(y)` with the exact Jacobian-vector product of the system.
//! * `block_lu.rs`: A block-tridiagonal LU for diffsol's Newton matrices: the chain's unknowns grouped rod by rod, each rod coupled only to its two neighbours ...
//! * `diffsol_driver.rs`: The step loop around diffsol's BDF, shared by `bdf` (the sparse DAE) and `bdf-dense` (the explicit form): the step budget, the step floor ...
//! * `dop853.rs`: Dormand–Prince 8(5,3) (Hairer & Wanner's DOP853): 12 stages, the combined fifth/third-order error estimate, a PI step-size controller, Hairer's initial step ...
//! * `dop853_tableau.rs`: The coefficients of Hairer's DOP853 (Dormand–Prince 8(5,3)), rounded to f64: the nodes and rows of the stages `k2..k12`, the eighth-order weights, the two error estimates ...
//! * `dopri5.rs`: Dormand–Prince 5(4) (Hairer & Wanner's DOPRI5): FSAL, the error norm over `rtol`/`atol`, a PI step-size controller, Hairer's initial step, the fourth-order dense output ...
//! * `error.rs`: A parameter outside its range, with its fields (`InvalidParameter`): the error of a method's name that is not one (`crate::Method`'s `FromStr`) ...
//! * `explicit.rs`: The one step loop of the explicit adaptive pairs (DOPRI5, DOP853), after argmin's split of a solver from its executor: a method makes one attempt (`Pair::attempt`: its stages ...
//! * `genalpha.rs`: `gen-alpha`: the generalized-alpha method of Chung & Hulbert (1993), in the first-order form of Jansen, Whiting & Hulbert (2000) ...
//! * `integrator.rs`: The one interface every method implements (`Integrator`), what it is told (`Settings`) and which parameter sets its accuracy (`Accuracy`).
//! * `known_solutions.rs`: Every method on problems with known solutions, so that every coefficient of every tableau matters: local and global orders measured from error slopes (on non-autonomous problems ...
//! * `method.rs`: The methods' public handle, `Method` (its name, kind and accuracy parameter come from its integrator in the registry), and the `Segment` of a run that one method covered.
//! * `newton_matrix.rs`: The Newton matrix `M - c J` of a semi-explicit DAE at a state, held dense on its sparsity pattern, as diffsol hands it to a linear solver ...
//! * `ode.rs`: The narrow interface between a problem and the integrators.
//! * `registry.rs`: The one list of methods: each `Method` and the `Integrator` that runs it.
//! * `rk4.rs`: Classical fixed-step RK4 on the whole state (angles and rates together), with the cubic Hermite interpolant as its continuous extension ...
//! * `sparse_lu.rs`: A sparse LU for diffsol's Newton matrices that fails with an error, not a panic.
//! * `step_size.rs`: Step-size helpers shared by the explicit adaptive pairs (DOPRI5, DOP853).
//! * `test_problems.rs`: What the integrators' tests share: a system made of closures with exact call counters (`Toy`), problems with known solutions (as ODEs, and as index-1 DAEs for the sparse BDF) ...
//! * `testing.rs`: Test support: what the integrators' own tests share with the tests of problems defined elsewhere (the chains, whose banded DAEs the sparse BDF and its block LU are checked on) ...
//!
//! The nonsmooth side: `nonsmooth.rs` (the [`Nonsmooth`] interface a
//! problem with impacts gives), `complementarity.rs` (the Alart–Curnier
//! semismooth Newton on the block-tridiagonal Delassus matrix) and
//! `moreau_jean.rs` (Moreau–Jean time stepping).

mod auto;
mod bdf;
mod bdf_dense;
mod block_lu;
mod complementarity;
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
mod moreau_jean;
mod newton_matrix;
mod nonsmooth;
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
pub use nonsmooth::{Nonsmooth, Row, RowKind, StepRecord, MAX_BODY, MAX_ROWS};
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
