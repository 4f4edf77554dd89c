//! The falling chain of `n` rigid rods: its dynamics in O(n), its energy, and
//! the integrators that run it.
//!
//! Data flows one way: a [`Chain`] and a [`Start`] give a [`State`]; [`solve`]
//! runs a [`Method`] on it and returns a [`Trajectory`] with its samples, its
//! [`Summary`], its work [`Stats`] and a [`Status`]. This crate knows nothing
//! of files, scene formats or plotting.
//!
//! Conventions (see `physics.md`): angles `phi_i` from the horizontal,
//! counter-clockwise; rod 1 pinned at `P0`; `mass` is per rod; gravity along -y.

pub mod analysis;
pub mod chain;
pub mod dae;
pub mod dense;
pub mod dynamics;
pub mod kinematics;
pub mod modes;
pub mod ode;
pub mod scalar;
pub mod solve;
pub mod state;
pub mod system;

pub use chain::{Chain, InvalidParameter};
pub use kinematics::Vec2;
pub use ode::{Stats, Status};
pub use solve::{
    bdf_crossover_gamma, solve, Accuracy, Method, Sample, Segment, SolveOptions, Summary,
    Trajectory,
};
pub use state::{Start, StartError, State};
pub use system::ChainSystem;
