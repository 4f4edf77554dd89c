//! `energy-budget`: the energy `E = T + V`, the work `W` dissipated by joint
//! friction (integrated alongside the state, `W' = 2R`) and their sum along
//! the span d = 3 scene, for r = 0, the scene's r and a larger r. With the
//! scene's n = 50 and m = 0.2 per rod, only r changes.

use fc_paper_figures::plot;
use fc_paper_figures::validation;
use rayon::prelude::*;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

const DAMPINGS: [f64; 3] = [0.0, 5e-4, 1e-2];

pub struct EnergyBudget;

impl Make for EnergyBudget {
    /// `energy-budget.csv`: every sample of the three runs.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let runs = ctx.pool()?.install(|| {
            DAMPINGS
                .par_iter()
                .map(|&r| {
                    let s = ctx.scene(
                        "span-d3",
                        &[
                            format!("chain.damping={r}"),
                            "run.method=\"dopri5\"".to_string(),
                            "run.rtol=1e-10".to_string(),
                            "run.atol=1e-12".to_string(),
                            "run.output_dt=0.01".to_string(),
                        ],
                    )?;
                    let traj = s
                        .prepare()
                        .and_then(|p| p.solve())
                        .map_err(|e| e.to_string())?;
                    if !traj.status.is_ok() {
                        return Err(format!("{}: r = {r}: status {}", fig.id, traj.status));
                    }
                    Ok(traj)
                })
                .collect::<Result<Vec<_>, String>>()
        })?;

        let (csv, notes) = validation::energy_budget(&runs);
        for n in notes {
            println!("  {}: {n}", fig.id);
        }
        Ok(vec![ctx.write(&format!("{}.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::validation::energy_budget)
    }
}
