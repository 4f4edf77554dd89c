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

/// One row per scene run: what the paper quotes about the report's scenes.
/// Deterministic (no wall times).
pub fn summary_csv(runs: &BTreeMap<&'static str, SceneRun>) -> String {
    let mut s = String::from(
        "scene,method,links,damping,t_end,status,steps,rejected_steps,rhs_evals,\
         energy_start,energy_end,dissipated,energy_balance_error,energy_scale,\
         tip_speed_max,t_tip_speed_max,tip_end_x,tip_end_y\n",
    );
    for (name, r) in runs {
        let (t, m) = (&r.traj, &r.traj.summary);
        s.push_str(&format!(
            "{name},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
            t.method,
            t.chain.links,
            t.chain.damping,
            t.t_end,
            t.status,
            t.stats.steps,
            t.stats.rejected_steps,
            t.stats.rhs_evals,
            m.energy_start,
            m.energy_end,
            m.dissipated,
            m.energy_balance_error,
            t.chain.energy_scale(),
            m.tip_speed_max,
            m.t_tip_speed_max,
            m.tip_end[0],
            m.tip_end[1],
        ));
    }
    s
}
