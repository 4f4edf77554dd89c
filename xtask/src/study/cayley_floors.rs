//! `cayley-floors`: Cayley's scale at n = 160 as single runs on both floor
//! laws (`scenes/cayley-scale.toml` at 160 rods, its zigzag kept), read
//! over the 19 windows of 0.05 in t = 0.3 .. 1.2 beside the ideal
//! `3 mu g x` (`fc_paper_figures::cayley_single`, `plot::floor`).
//!
//! What it runs: the constraint floor by Moreau–Jean at dt = 2.5e-3 (500
//! steps, ~0.3 s of CPU), and the penalty floor by DOP853 at rtol 1e-4
//! (atol 1e-6; 41 610 steps, ~4 s of CPU; the whole figure 9 s of wall
//! time, 4.4 s of CPU). A single penalty run is one sample of the landing
//! sequence (`docs/model.md`), and its reading does not move with the
//! tolerance beyond its window scatter: 1.020 +- 0.41 at rtol 1e-3,
//! 1.039 +- 0.23 at 1e-4, 1.017 +- 0.23 at 1e-5, 1.030 +- 0.34 at 1e-6
//! (mean +- scatter over the 19 windows; 2.8, 4.2, 5.5 and 7.5 s of CPU):
//! rtol 1e-4 is the cheapest tolerance whose scatter is not above the
//! tighter ones'. Both runs are deterministic: the data reproduce to the
//! byte.
use chain_ode::Method;
use fc_paper_figures::cayley_single::{self, Single};
use fc_paper_figures::plot;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The rods.
const LINKS: usize = 160;

/// The two runs: the constraint floor's step and the penalty floor's
/// tolerance.
const RUNS: [Single; 2] = [
    Single {
        links: LINKS,
        law: "constraint",
        method: Method::MoreauJean,
        accuracy: 2.5e-3,
    },
    Single {
        links: LINKS,
        law: "penalty",
        method: Method::Dop853,
        accuracy: 1e-4,
    },
];

pub struct CayleyFloors;

impl Make for CayleyFloors {
    /// `cayley-floors.csv` (every window of both runs) and
    /// `cayley-floors-summary.csv` (each run's mean, scatter, error,
    /// steps).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let base = ctx.scene("cayley-scale", &[] as &[&str])?;
        let reads = ctx.pool()?.install(|| {
            use rayon::prelude::*;
            RUNS.par_iter()
                .map(|single| cayley_single::run(&base, single).map(|(_, read)| read))
                .collect::<Result<Vec<_>, String>>()
        })?;
        for r in &reads {
            if r.status != "ok" {
                return Err(format!(
                    "{id}: the {} floor's run ended {}",
                    r.single.law, r.status
                ));
            }
            println!(
                "  {id}: {} floor, {} at {:e}: reading {:.4} scatter {:.4} error {:.4}, {} steps",
                r.single.law,
                r.single.method,
                r.single.accuracy,
                r.reading.mean,
                r.reading.scatter,
                r.error,
                r.steps
            );
        }
        Ok(vec![
            ctx.write(&format!("{id}.csv"), &cayley_single::windows_csv(&reads))?,
            ctx.write(
                &format!("{id}-summary.csv"),
                &cayley_single::readings_csv(&reads),
            )?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::floor::cayley_floors)
    }
}
