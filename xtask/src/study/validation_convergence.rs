//! `convergence-n`: how many rods the span scenes need.
//!
//! Each scene is refined at fixed continuum properties (total mass
//! `M = n m` and bending viscosity `eta = r l`, see
//! `fc_study::converge`) over the ladder n = 25 .. 1600, and to n = 3200
//! where the last doubling (800 -> 1600) still moved the maximum tip speed by
//! more than 0.05% (half the finest tolerance asked for). The finest n is
//! the reference. All runs: `auto`, rtol 1e-9, atol 1e-11, tip sampled every
//! 0.01 for the path comparison. At fixed bending viscosity the damping rate
//! grows like n^4, so `auto` runs DOP853 on the coarse levels and the O(n)
//! BDF on the fine ones.

use fc_paper_figures::convergence;
use fc_paper_figures::plot;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

const SCENES: [&str; 3] = ["span-d1", "span-d3", "span-d5"];
const LADDER: [usize; 7] = [25, 50, 100, 200, 400, 800, 1600];
const FINEST: usize = 3200;
const METHOD: &str = "auto";
/// Go on to `FINEST` if the last doubling changed the max tip speed by more.
const GO_ON: f64 = 5e-4;
const RTOL: f64 = 1e-9;
const OUTPUT_DT: f64 = 0.01;

pub struct Convergence;

impl Make for Convergence {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes = SCENES
            .iter()
            .map(|&name| {
                Ok((
                    name,
                    ctx.scene(name, &[format!("run.output_dt={OUTPUT_DT}")])?,
                ))
            })
            .collect::<Result<Vec<_>, String>>()?;
        let options = convergence::LadderOptions {
            ladder: &LADDER,
            finest: FINEST,
            go_on: GO_ON,
            method: METHOD,
            rtol: RTOL,
            tols: convergence::TOLS,
        };
        let (csv, summary, notes) = ctx
            .pool()?
            .install(|| convergence::ladders(&scenes, &options))?;
        for n in notes {
            println!("  {}: {n}", fig.id);
        }
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &csv)?,
            ctx.write(&format!("{}-summary.csv", fig.id), &summary)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::convergence::convergence_n)
    }
}
