//! `rhs-cost`: the cost of one right-hand side against n, the O(n)
//! recursion (a whole `ChainSystem::rhs`) against the dense reference
//! (assemble `A` and `b`, faer's Cholesky), timed here with
//! `std::time::Instant` over many calls, median of repeats. All of it is
//! wall times: computed only by `--timings`, into `rhs-cost-timing.csv` and
//! `rhs-cost-fit-timing.csv`.

use fc_paper_figures::plot;
use fc_paper_figures::rhs_cost;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

pub struct RhsCost;

impl Make for RhsCost {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let (rows, fits) = rhs_cost::tables()?;
        Ok(vec![
            ctx.write(&format!("{}-timing.csv", fig.id), &rows)?,
            ctx.write(&format!("{}-fit-timing.csv", fig.id), &fits)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::timing::rhs_cost)
    }
}
