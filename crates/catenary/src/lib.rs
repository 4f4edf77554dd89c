//! Hanging-chain equilibria between two anchors `p0`, `p1`.
//!
//! * [`Catenary`]: the continuous catenary `y = a cosh((x - x0)/a) + c` of
//!   given arc length (parameter `a` found with argmin's `BrentRoot`).
//! * [`discrete_equilibrium`]: the exact static equilibrium of `n` equal
//!   rigid rods pinned at both ends, `tan(phi_i) = alpha + (i - 1/2) beta`.
//! * [`discrete_equilibrium_rods`]: the same for rods of unequal mass and
//!   length, `tan(phi_i) = (V - W_i) / H`, the minimum of a convex function.
//!
//! Conventions: `y` points up, gravity acts along `-y`; angles in radians
//! from the horizontal, counter-clockwise; lengths in the caller's unit.
//!
//! Bounds: coordinates and lengths up to [`MAX_MAGNITUDE`] (`1e150`), lengths
//! from [`MIN_LENGTH`] (`1e-150`), at most [`MAX_LINKS`] (`10^6`) rods; every
//! iteration is capped, and a cap that is hit is an error
//! ([`CatenaryError::NoConvergence`]), never a panic or a silent answer.
//!
//! Its files:
//! * `continuous.rs`: The continuous catenary `y = a cosh((x - x0)/a) + c` through two anchors.
//! * `discrete.rs`: The exact static equilibrium of `n` equal rigid rods pinned at both ends.
//! * `error.rs`: Why a catenary could not be built.
//! * `profiled.rs`: The exact static equilibrium of rods of unequal mass and length pinned at both ends (the tapered chain's catenary start).
//! * `profiled_kink.rs`: The equilibrium of unequal rods with one rod in compression (or in tension next to that configuration), for `crate::discrete_equilibrium_rods`.
//! * `rods.rs`: Statics of `n` equal rods pinned at both ends, for a chain running towards `+x`, in rod units (lengths in `l`, forces in rod weights `W = m g`).

mod continuous;
mod discrete;
mod error;
mod profiled;
mod profiled_kink;
mod rods;

pub use continuous::Catenary;
pub use discrete::{discrete_equilibrium, joints, DiscreteCatenary};
pub use error::{CatenaryError, Input, MAX_LINKS, MAX_MAGNITUDE, MIN_LENGTH};
pub use profiled::{discrete_equilibrium_rods, joints_rods, ProfiledCatenary};

/// A point `[x, y]` in the plane (length units, `y` up).
pub type Point = [f64; 2];
