//! `report-scenes-accuracy`: is each report figure drawn from a converged
//! run? The report scenes with dynamics (and the folded chain), each at its
//! own settings and by RK4 at a ladder of steps, against DOP853 at rtol
//! 1e-12 (`fc_paper_figures::accuracy` makes the table, its `plot`
//! the drawing).

use fc_paper_figures::{accuracy, plot};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The report's scenes (those of the rigid limit), and after Fig. 5's the
/// settling run at the report's effective damping (Fig. 5b).
fn scenes() -> Vec<&'static str> {
    let mut out = Vec::new();
    for &s in crate::study::elastic_rigid_limit::SCENES {
        out.push(s);
        if s == "horizontal-settling" {
            out.push("horizontal-settling-report-damping");
        }
    }
    out
}

pub struct ReportAccuracy;

impl Make for ReportAccuracy {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let prepare = |scene: &str, set: &[String]| ctx.prepare(scene, set);
        let csv = (ctx.pool()?)
            .install(|| accuracy::scenes_table(&scenes(), &prepare))
            .map_err(|e| format!("{}: {e}", fig.id))?;
        Ok(vec![ctx.write(fig.data[0], &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::accuracy::draw)
    }
}
