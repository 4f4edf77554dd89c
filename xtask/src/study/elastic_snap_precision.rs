//! `snap-precision` and `snap-damping`: the folded elastic snap's
//! work-precision across `EA` and across the damping
//! (`fc_paper_figures::snap_precision`). Timing only: their rows hold wall
//! times, so they run with `--timings` and are drawn from their committed
//! data otherwise.

use fc_paper_figures::plot::elastic::{snap_work, SnapAxis};
use fc_paper_figures::snap_precision;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

pub struct SnapWork {
    pub axis: SnapAxis,
}

pub const BY_STIFFNESS: SnapWork = SnapWork {
    axis: SnapAxis::Stiffness,
};
pub const BY_DAMPING: SnapWork = SnapWork {
    axis: SnapAxis::Damping,
};

impl Make for SnapWork {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let prepare = |set: &[String]| ctx.prepare("folded", set);
        let cases: &[(f64, f64)] = match self.axis {
            SnapAxis::Stiffness => &snap_precision::EAS,
            SnapAxis::Damping => &snap_precision::ZETAS,
        };
        let [rows, best] = snap_precision::tables(&prepare, cases)?;
        Ok(vec![
            ctx.write(&format!("{}-timing.csv", fig.id), &rows)?,
            ctx.write(&format!("{}-best-timing.csv", fig.id), &best)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let axis = self.axis;
        ctx.draw(fig, move |r, s| snap_work(r, s, axis))
    }
}
