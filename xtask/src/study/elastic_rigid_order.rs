//! `elastic-rigid-order`: an independent check of the dynamics. The
//! elastic chain (maximal coordinates) against the rigid one (the angles)
//! on three report scenes stopped before their whip, over a ladder of `EA`:
//! the distance must fall like `1/EA` (`fc_paper_figures::rigid_order`).
//! Deterministic: `elastic-rigid-order.csv` (every rung) and
//! `elastic-rigid-order-fit.csv` (the fitted order of each scene).

use fc_paper_figures::plot;
use fc_paper_figures::rigid_order::{self, FIT_HEADER, HEADER};
use rayon::prelude::*;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The scenes and the time each runs to, before its whip (the maximum tip
/// speed comes at t = 2.76, 2.97 and 3.03 in `figures/data/scenes.csv`).
const SCENES: [(&str, f64); 3] = [("span-d3", 1.5), ("folded", 1.5), ("catenary-fall", 2.0)];
/// The ladder of `EA` (force units), two rungs a decade (DOP853's steps grow
/// like `sqrt(EA)`: 1e6 would triple the figure's cost for a rung that
/// says nothing new).
const LADDER: [f64; 5] = [1e3, 3.2e3, 1e4, 3.2e4, 1e5];

pub struct RigidOrder;

impl Make for RigidOrder {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let ladders: Vec<Result<rigid_order::Ladder, String>> = ctx.pool()?.install(|| {
            SCENES
                .par_iter()
                .map(|&(name, t_end)| {
                    let scene = ctx.scene::<&str>(name, &[])?;
                    rigid_order::ladder(&scene, t_end, &LADDER).map_err(|e| format!("{name}: {e}"))
                })
                .collect()
        });
        let (mut rungs, mut fits) = (HEADER.to_string(), FIT_HEADER.to_string());
        for l in ladders {
            let l = l?;
            rungs.push_str(&rigid_order::rungs_csv(&l));
            fits.push_str(&rigid_order::fit_csv(&l));
        }
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &rungs)?,
            ctx.write(&format!("{}-fit.csv", fig.id), &fits)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::rigid_order::rigid_order)
    }
}
