//! `elastic-layout-order`: the elastic chain's axial frequencies and
//! self-weight stretch against the continuum rope's as `n` grows
//! (`fc_paper_figures::layout_order`; `docs/model.md`, "Where the
//! compliance sits"). Deterministic: `elastic-layout-order.csv` (the
//! modes), `-stretch.csv` and `-fit.csv` (the fitted orders).

use fc_paper_figures::layout_order;
use fc_paper_figures::plot;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The ladder of `n`, doubling: the dense eigenproblem at 320 rods costs
/// a few tens of milliseconds.
const LINKS: [usize; 7] = [5, 10, 20, 40, 80, 160, 320];
/// The modes drawn.
const MODES: usize = 3;
/// The orders are fitted from this `n` on.
const FIT_FROM: usize = 20;

pub struct LayoutOrder;

impl Make for LayoutOrder {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let [modes, stretch, fit] = layout_order::tables(&LINKS, MODES, FIT_FROM)?;
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &modes)?,
            ctx.write(&format!("{}-stretch.csv", fig.id), &stretch)?,
            ctx.write(&format!("{}-fit.csv", fig.id), &fit)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::elastic::layout_order)
    }
}
