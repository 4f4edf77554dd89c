//! The drawings of the paper's own tables, one module per study module,
//! each reading its tables through a [`Reader`], and the paper's
//! work-precision figure ([`wp_figure`]). They build on the drawings of
//! any scene's tables (fc-study's `plot`), of which the stability map
//! ([`stability_figure`]) is re-exported for xtask.
//!
//! Its files:
//! * `accuracy.rs`: The drawing of the accuracy table (`crate::accuracy`): per scene, RK4's error against its step and the scene's own run's error.
//! * `beam.rs`: The drawing of BEAM's work-precision table (`crate::beam`): the error at `t = 5` against the wall time (from `-timing`) and against the accepted steps, a line per method.
//! * `cayley.rs`: The drawing of Cayley's scale as an ensemble (`crate::cayley`): the ensemble's mean reading over the ideal's against time, a line per `n` ...
//! * `convergence.rs`: The drawing of the convergence in n (`crate::convergence::ladders`).
//! * `elastic.rs`: The drawings of the elastic chain's study: the snap's support force and impulse against `n` (`fc_study::snap`), its tension wave (`crate::snap_tension`) ...
//! * `floor.rs`: The drawings of the floor's figures: the U onto a floor (`crate::floor_u`: the chain at a few times over the floor's line ...
//! * `folded.rs`: The drawings of the folded chain's tables (`crate::folded`): its fall against the law, the force on the pivot, the tip's acceleration.
//! * `friction.rs`: The drawing of the friction sensitivity (`crate::friction`): the maximum tip speed over its value without friction ...
//! * `report.rs`: The drawings of the report's figures from their tables (`crate::report`): catenaries, chain snapshots, tip speed and velocity against time ...
//! * `report_model.rs`: The drawings of the report's own model (`crate::report_model`): its snapshots, titled with how the run ended, and its Fig. 9 beside the published one, each erratum undone ...
//! * `rigid_order.rs`: The drawing of the rigid limit's order (`crate::rigid_order`): the elastic chain's distance from the rigid one against `EA`, log-log ...
//! * `stiffness.rs`: The drawing of where BDF pays (`crate::stiffness`): left, DOPRI5's cost over BDF's at matched error against the damping rate, a line per `n`, with the equal-cost line and, on it ...
//! * `timing.rs`: The drawings of the wall-time studies: speed-ups at matched accuracy (`crate::matched`), the cost of a right-hand side (`crate::rhs_cost`); where BDF pays is `super::stiffness`.
//! * `tip_mass.rs`: The drawing of the `tip-mass-fall` figure (`crate::tip_mass`): the folded chain with a tip mass against the energy-conserving law ...
//! * `validation.rs`: The drawings of the energy budget and the normal modes (`crate::validation`).
//! * `whip_taper.rs`: The drawing of the tapered whip's table (`crate::whip_taper`): the largest tip speed against the taper, a line per `n`, and its gain over the uniform chain.

pub mod accuracy;
pub mod beam;
pub mod cayley;
pub mod convergence;
pub mod elastic;
pub mod floor;
pub mod folded;
pub mod friction;
pub mod report;
pub mod report_model;
pub mod rigid_order;
pub mod stiffness;
pub mod timing;
pub mod tip_mass;
pub mod validation;
pub mod whip_taper;

use std::path::Path;

use fc_study::plot::{work_precision_weighted, wp_points, DRAW_FLOOR};
use fc_study::work_cost::Weights;
use figures::Output;

pub use fc_study::plot::{stability_figure, Reader};

use crate::plan::Eval;

/// The paper's work-precision figure of the scene called `label`, from its
/// tables (`""`, `-timing`, `-cost-timing` and, with
/// [`Eval::BeforeSeparation`], `-divergence`, whose note it adds), its
/// work weighted by the measured unit costs.
pub fn wp_figure(read: Reader, stem: &Path, label: &str, eval: Eval) -> Result<Output, String> {
    let rows = wp_points(&read("")?, Some(&read("-timing")?))?;
    let weights = Weights::from_table(&read("-cost-timing")?)?;
    let notes = match eval {
        Eval::End => vec![],
        Eval::BeforeSeparation => vec![crate::divergence::note(&read("-divergence")?)?],
    };
    let pair = work_precision_weighted(label, &rows, notes, Some(weights));
    pair.save(stem).map_err(|e| e.to_string())
}
