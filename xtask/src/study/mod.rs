//! The study's figures (`docs/figures.md`, "The study's figures"), one file
//! per subject: speed against accuracy (`precision_*`: work-precision,
//! stability map, stiffness, right-hand-side cost) and validation against
//! physics (`validation_*`: convergence in n, the folded chain against its
//! law and the support force, the energy budget, normal modes). Each is a
//! [`crate::registry::Make`] listed in the registry.
//!
//! Timed runs run alone, never beside another timed run, and only with
//! `--timings`; untimed runs run in parallel on [`crate::ctx::Ctx::pool`].
//!
//! Its files:
//! * `cayley_floors.rs`: `cayley-floors`: Cayley's scale at n = 160 as single runs on both floor laws (`scenes/cayley-scale.toml` at 160 rods), read over 19 windows beside the ideal `3 mu g x` ...
//! * `cayley_scale.rs`: `cayley-scale` and `cayley-top`: Cayley's scale as an ensemble (`scenes/cayley-scale.toml`, a chain hanging straight down onto a floor, let go at the top) ...
//! * `elastic_layout_order.rs`: `elastic-layout-order`: the elastic chain's axial frequencies and self-weight stretch against the continuum rope's as `n` grows (`fc_paper_figures::layout_order`; `docs/model.md` ...
//! * `elastic_rigid_limit.rs`: `elastic-rigid-limit`: "when can I use the rigid model".
//! * `elastic_rigid_order.rs`: `elastic-rigid-order`: an independent check of the dynamics.
//! * `elastic_snap_force.rs`: `snap-force`: the snap's peak support force and impulse against `n` (`fc_paper_figures::snap_sweep`), for span d = 3, span d = 1 and the folded chain ...
//! * `elastic_snap_precision.rs`: `snap-precision` and `snap-damping`: the folded elastic snap's work-precision across `EA` and across the damping (`fc_paper_figures::snap_precision`).
//! * `elastic_snap_tension.rs`: `snap-tension`: the tension along the chain around the snap, the wave running up from the tip (`fc_study::snap`).
//! * `force_precision.rs`: `force-precision`: the work-precision of the snap's forces beside the tip's, on issue 49's steel rope cut short (`fc_paper_figures::force_precision`).
//! * `floor_checks.rs`: `floor-checks`: the floor against two closed forms (the tests' `floor::` in chain-ode's physics suite check the same) ...
//! * `floor_span_d3.rs`: `floor-span-d3`: the report's U of span d = 3 (n = 50) released over a floor (`scenes/span-d3-floor.toml`), drawn at a few times with the floor ...
//! * `precision_beam.rs`: `beam-precision`: work-precision of BEAM, the IVP test set's stiff beam (`chain_ode::beam`), every method against the published reference at t = 5.
//! * `precision_cost.rs`: `rhs-cost`: the cost of one right-hand side against n, the O(n) recursion (a whole `ChainSystem::rhs`) against the dense reference (assemble `A` and `b`, faer's Cholesky) ...
//! * `precision_map.rs`: `stability-map`: where each method fails.
//! * `precision_matched.rs`: `wp-matched`: speed-ups at matched accuracy, derived from the work-precision data (no run of its own).
//! * `precision_stiffness.rs`: `stiffness`: where the implicit method pays, at matched accuracy (`fc_paper_figures::stiffness` says how).
//! * `precision_wp.rs`: Work-precision diagrams, `wp-<scene>`: the error of two well-conditioned quantities (the tip position at an evaluation time ...
//! * `span_friction.rs`: `span-friction`: the sensitivity of the maximum tip speed to the joint friction `r` for the span scenes ...
//! * `tip_mass_fall.rs`: `tip-mass-fall`: the folded chain with a point mass `M` at its free end (n = 400, r = 0) against the energy-conserving law, for `M / m_c` from 0.1 to 10 ...
//! * `validation_convergence.rs`: `convergence-n`: how many rods the span scenes need.
//! * `validation_energy.rs`: `energy-budget`: the energy `E = T + V`, the work `W` dissipated by joint friction (integrated alongside the state, `W' = 2R`) and their sum along the span d = 3 scene, for r = 0 ...
//! * `validation_folded.rs`: `folded-vs-analytic`, `support-force` and `folded-tip-acceleration`: the folded chain with r = 0 against the energy-conserving law (Calkin & March 1989) ...
//! * `validation_modes.rs`: `normal-modes`: the lowest five frequencies of the linearised hanging chain of n rods against the continuum's `omega_k = (j_{0,k}/2) sqrt(g/L)` ...
//! * `whip_taper.rs`: `whip-taper`: the tapered whip (`scenes/tapered-whip.toml`, span d = 3 released) with its mass per length tapered, base to tip.

pub mod cayley_floors;
pub mod cayley_scale;
pub mod elastic_layout_order;
pub mod elastic_rigid_limit;
pub mod elastic_rigid_order;
pub mod elastic_snap_force;
pub mod elastic_snap_precision;
pub mod elastic_snap_tension;
pub mod floor_checks;
pub mod floor_span_d3;
pub mod force_precision;
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
