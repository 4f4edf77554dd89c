//! The study's figures (`docs/figures.md`, "The study's figures"), one file
//! per subject: speed against accuracy (`precision_*`: work-precision,
//! stability map, stiffness, right-hand-side cost) and validation against
//! physics (`validation_*`: convergence in n, the folded chain against its
//! law and the support force, the energy budget, normal modes). Each is a
//! [`crate::registry::Make`] listed in the registry.
//!
//! Timed runs run alone, never beside another timed run, and only with
//! `--timings`; untimed runs run in parallel on [`crate::ctx::Ctx::pool`].

pub mod cayley_scale;
pub mod elastic_layout_order;
pub mod elastic_rigid_limit;
pub mod elastic_rigid_order;
pub mod elastic_snap_force;
pub mod elastic_snap_precision;
pub mod elastic_snap_tension;
pub mod floor_checks;
pub mod floor_span_d3;
pub mod precision_beam;
pub mod precision_cost;
pub mod precision_map;
pub mod precision_matched;
pub mod precision_stiffness;
pub mod precision_wp;
pub mod span_friction;
pub mod tip_mass_fall;
pub mod validation_convergence;
pub mod validation_energy;
pub mod validation_folded;
pub mod validation_modes;
pub mod whip_taper;

/// Least-squares fits for the figure files (the library's).
#[allow(unused_imports, reason = "for the figure files that fit slopes")]
pub use fc_study::{linear_fit, log_slope};
