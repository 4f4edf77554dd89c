//! The scene runs the report's figures share, each made once, in parallel
//! (`fc_paper_figures::scene_run`), and the summary of them the paper
//! quotes (`scenes.csv`).

use std::collections::BTreeMap;

use chain_ode::Trajectory;
use fc_paper_figures::report;
pub use fc_paper_figures::scene_run::SceneRun;
use rayon::prelude::*;

use crate::ctx::Ctx;

/// Runs every named scene file of `scenes/` once (in parallel), calling
/// `tick` after each.
pub fn run_all(
    ctx: &Ctx,
    names: &[&'static str],
    tick: &(dyn Fn(&str) + Sync),
) -> Result<BTreeMap<&'static str, SceneRun>, String> {
    names
        .par_iter()
        .map(|&name| {
            let r = SceneRun::run(ctx.scene::<&str>(name, &[])?)?;
            tick(name);
            Ok((name, r))
        })
        .collect()
}

/// `scenes.csv`: one row per scene run, what the paper quotes about the
/// report's scenes (no wall times).
pub fn summary_csv(runs: &BTreeMap<&'static str, SceneRun>) -> String {
    let runs: Vec<(&str, &Trajectory)> = runs.iter().map(|(n, r)| (*n, &r.traj)).collect();
    report::summary(&runs)
}
