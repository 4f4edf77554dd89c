//! `elastic-rigid-limit`: "when can I use the rigid model". For each report
//! scene, at its own `n` and mass per rod (the report's convention), the
//! elastic chain's distance from the rigid one (tip path and maximum tip
//! speed) against `EA`, and the `EA` above which it stays within 1e-3
//! (`fc_study::rigid_limit`; 5% damping of one joint, DOPRI5 at
//! rtol 1e-8 for every run). Its ladders take about 5 min on two cores
//! (DOPRI5's steps grow like `sqrt(EA)`, to 5.6 million at `EA = 1e9`), so
//! it is computed only by `--timings` and its files, which carry each run's
//! wall time too, are timing files; without `--timings` it is drawn from
//! them as committed (`fc_paper_figures::plot::elastic::rigid_limit`).

use fc_paper_figures::plot;
use fc_study::rigid_limit::{self, Options};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The scenes of the report's figures, in the order of `docs/figures.md`.
pub const SCENES: &[&str] = &[
    "horizontal-undamped",
    "horizontal-damped",
    "horizontal-settling",
    "catenary-fall",
    "span-d1",
    "span-d3",
    "span-d5",
    "span-d6",
    "height-hm2",
    "height-h0",
    "height-h2",
    "height-h4",
    "folded",
];

pub struct RigidLimit;

impl Make for RigidLimit {
    /// `elastic-rigid-limit-timing.csv` (every rung) and
    /// `elastic-rigid-limit-threshold-timing.csv` (each scene's answer).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes = (SCENES.iter())
            .map(|&name| Ok((name, ctx.scene::<&str>(name, &[])?)))
            .collect::<Result<Vec<_>, String>>()?;
        let tick = |note: String| println!("  {}: {note}", fig.id);
        let tables =
            (ctx.pool()?).install(|| rigid_limit::tables(&scenes, &Options::default(), &tick))?;
        ctx.write_tables(fig.id, &tables)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::elastic::rigid_limit)
    }
}
