//! `force-precision`: the work-precision of the snap's forces beside the
//! tip's, on issue 49's steel rope cut short
//! (`fc_paper_figures::force_precision` says how and why).

use fc_paper_figures::force_precision;
use fc_paper_figures::plot::elastic::force_precision as draw;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

pub struct ForcePrecision;

impl Make for ForcePrecision {
    /// `force-precision.csv` (every method at every rtol) and
    /// `force-precision-reference.csv` (the reference and its
    /// confirmation).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let prepare = |set: &[String]| ctx.prepare("span-d3", set);
        let [rows, reference] = force_precision::tables(&prepare)?;
        ctx.write_tables(fig.id, &[("", rows), ("-reference", reference)])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, draw)
    }
}
