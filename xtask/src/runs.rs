//! The scene runs the figures need, each made once, in parallel.

use std::collections::BTreeMap;
use std::path::Path;

use chain_ode::{Trajectory, Vec2};
use falling_chain::Scene;
use rayon::prelude::*;

/// A finished scene run and what the figures need to know about it.
pub struct SceneRun {
    pub scene: Scene,
    pub traj: Trajectory,
    /// The scene's own sample spacing (the report's snapshot spacing).
    pub snapshot_dt: f64,
    /// Where the free end was held (P1).
    pub release: Vec2,
}

/// Samples are recorded this many times finer than the scene's `output_dt`,
/// so that speed curves are smooth; snapshots keep the scene's spacing.
pub const FINE: f64 = 32.0;

/// Runs one scene file of `scenes/`.
pub fn run_scene(scenes: &Path, name: &str) -> Result<SceneRun, String> {
    let path = scenes.join(format!("{name}.toml"));
    let scene = Scene::load(&path).map_err(|e| e.to_string())?;
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
    scenes: &Path,
    names: &[&'static str],
    tick: &(dyn Fn(&str) + Sync),
) -> Result<BTreeMap<&'static str, SceneRun>, String> {
    names
        .par_iter()
        .map(|&name| {
            let r = run_scene(scenes, name)?;
            tick(name);
            Ok((name, r))
        })
        .collect()
}
