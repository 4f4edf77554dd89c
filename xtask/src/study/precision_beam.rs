//! `beam-precision`: work-precision of BEAM, the IVP test set's stiff beam
//! (`chain_ode::beam`), every method against the published reference at
//! t = 5. The runs and the tables are the library's
//! (`fc_paper_figures::beam`), the drawing too
//! (`fc_paper_figures::plot::beam`); the wall times go to
//! `beam-precision-timing.csv`, written only by `--timings`, beside the
//! machine they were measured on (`beam-precision-machine-timing.csv`, as
//! `machine-timing.csv`): BEAM's times may come from a run of their own.

use fc_paper_figures::{beam, plot};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

pub struct BeamPrecision;

impl Make for BeamPrecision {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let grid = beam::grid();
        let rows = if ctx.timings {
            beam::rows(&grid, true)?
        } else {
            ctx.pool()?.install(|| beam::rows(&grid, false))?
        };
        let mut files = vec![ctx.write(&format!("{id}.csv"), &beam::csv_text(&rows))?];
        if ctx.timings {
            files.push(ctx.write(&format!("{id}-timing.csv"), &beam::timing_text(&rows))?);
            files.push(ctx.write(
                &format!("{id}-machine-timing.csv"),
                &crate::timing::machine_csv(),
            )?);
        }
        Ok(files)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::beam::precision)
    }
}
