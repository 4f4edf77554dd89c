//! The drawings of the paper's own tables, one module per study module,
//! each reading its tables through a [`Reader`], and the paper's
//! work-precision figure ([`wp_figure`]). They build on the drawings of
//! any scene's tables (fc-study's `plot`), of which the stability map
//! ([`stability_figure`]) is re-exported for xtask.

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
