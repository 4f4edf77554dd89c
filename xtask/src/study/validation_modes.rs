//! `normal-modes`: the lowest five frequencies of the linearised hanging
//! chain of n rods against the continuum's `omega_k = (j_{0,k}/2) sqrt(g/L)`,
//! and the convergence order fitted to the relative errors (least squares
//! in log-log over n >= 40).

use fc_paper_figures::plot;
use fc_paper_figures::validation;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

const LINKS: [usize; 12] = [10, 14, 20, 28, 40, 57, 80, 100, 160, 226, 320, 400];
const MODES: usize = 5;
const FIT_FROM: usize = 40;

pub struct NormalModes;

impl Make for NormalModes {
    /// `normal-modes.csv` (every n and mode, also in units of `sqrt(g/L)`)
    /// and `normal-modes-fit.csv` (the fitted order of each mode).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let (csv, fit, notes) = validation::normal_modes(&LINKS, MODES, FIT_FROM)?;
        for n in notes {
            println!("  {}: {n}", fig.id);
        }
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &csv)?,
            ctx.write(&format!("{}-fit.csv", fig.id), &fit)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::validation::normal_modes)
    }
}
