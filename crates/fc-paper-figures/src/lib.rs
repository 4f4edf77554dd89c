//! The study modules that only the paper's figures use: `cargo xtask
//! figures` (xtask) chooses the scenes and calls these, and nothing else
//! does. Each computes the rows of one or more of the paper's tables
//! (`figures/data/*.csv`: the accuracy of the methods, BEAM's
//! work-precision, the convergence in n, the folded chain, friction, the
//! report's scenes and model, the stiffness crossovers, the timing tables,
//! the tip mass, the tapered whip, Cayley's scale, the viewer's peak, ...), with the
//! drawings of those tables in [`plot`].
//!
//! It builds on the studies of any scene (fc-study, with its drawings),
//! fc-batch, fc-viewer and fc-scene; neither the CLI nor Python depends on
//! it.

pub mod accuracy;
pub mod beam;
pub mod cayley;
pub mod cayley_single;
pub mod convergence;
pub mod divergence;
pub mod floor_checks;
pub mod floor_u;
pub mod folded;
pub mod friction;
pub mod layout_order;
pub mod machine;
pub mod matched;
pub mod plan;
pub mod plot;
pub mod report;
pub mod report_model;
pub mod report_model_tip;
pub mod rhs_cost;
pub mod rigid_order;
pub mod scene_run;
pub mod snap_precision;
pub mod snap_sweep;
pub mod snap_tension;
pub mod span_check;
pub mod stiffness;
pub mod tip_mass;
pub mod validation;
pub mod viewer_peak;
pub mod whip_taper;

/// The methods the paper's work-precision, stability and BEAM figures
/// compare, in their order: every method but `gen-alpha`, whose figures
/// are the elastic snap's (`precision` on that scene with every method).
/// A figure's tables keep their rows when a method is added to the
/// registry; a new method joins a figure by joining this list.
pub const PAPER_METHODS: [chain_ode::Method; 6] = [
    chain_ode::Method::Rk4,
    chain_ode::Method::Dopri5,
    chain_ode::Method::Dop853,
    chain_ode::Method::Bdf,
    chain_ode::Method::BdfDense,
    chain_ode::Method::Auto,
];
