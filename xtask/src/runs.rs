//! The scene runs the report's figures share, each made once, in parallel;
//! the summary of them the paper quotes (`scenes.csv`); and the animations,
//! which are made from the runs directly (they are not redrawn from data).

use std::collections::BTreeMap;
use std::path::Path;

use chain_ode::{Trajectory, Vec2};
use falling_chain::study::report;
use falling_chain::{render, Scene};
use rayon::prelude::*;

use crate::ctx::Ctx;

/// A finished scene run and what the figures need to know about it.
pub struct SceneRun {
    pub scene: Scene,
    pub traj: Trajectory,
    /// The scene's own sample spacing (the report's snapshot spacing).
    pub snapshot_dt: f64,
    /// Where the free end was held (P1).
    pub release: Vec2,
}

impl SceneRun {
    /// The run as the report's tables take it.
    pub fn as_run(&self) -> falling_chain::study::report::Run<'_> {
        falling_chain::study::report::Run {
            name: self.scene.name(),
            traj: &self.traj,
            release: self.release,
        }
    }
}

/// Samples are recorded this many times finer than the scene's `output_dt`,
/// so that speed curves are smooth; snapshots keep the scene's spacing.
pub const FINE: f64 = 32.0;

/// Runs one scene file of `scenes/`.
pub fn run_scene(ctx: &Ctx, name: &str) -> Result<SceneRun, String> {
    let scene = ctx.scene::<&str>(name, &[])?;
    let mut prepared = scene.prepare().map_err(|e| e.to_string())?;
    let snapshot_dt = prepared
        .options
        .output_dt
        .unwrap_or(prepared.options.t_end / 50.0);
    prepared.options.output_dt = Some(snapshot_dt / FINE);
    let release = scene
        .start()
        .release_point(&prepared.chain)
        .map_err(|e| e.to_string())?;
    let traj = prepared.solve().map_err(|e| e.to_string())?;
    if !traj.status.is_ok() {
        return Err(format!(
            "{name}: the run ended with status {} at t = {} (method {})",
            traj.status, traj.t_reached, traj.method
        ));
    }
    Ok(SceneRun {
        scene,
        traj,
        snapshot_dt,
        release,
    })
}

/// Runs every named scene once (in parallel), calling `tick` after each.
pub fn run_all(
    ctx: &Ctx,
    names: &[&'static str],
    tick: &(dyn Fn(&str) + Sync),
) -> Result<BTreeMap<&'static str, SceneRun>, String> {
    names
        .par_iter()
        .map(|&name| {
            let r = run_scene(ctx, name)?;
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

/// The animation of one scene run, `<dir>/<name>.gif`: about 60 frames at
/// 20 per second.
pub fn animation(name: &str, run: &SceneRun, dir: &Path) -> Result<(), String> {
    let fine = run.snapshot_dt / FINE;
    let spacing = fine * (run.traj.t_end / fine / 60.0).round().max(1.0);
    let title = format!("{} (t = {:.3})", name, run.traj.t_end);
    let f = render::snapshots(&title, &run.traj, Some(spacing), Some(run.release));
    figures::chain_animation(&f, &dir.join(format!("{name}.gif")), 20)
        .map_err(|e| format!("anim {name}: {e}"))
}
