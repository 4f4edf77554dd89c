//! A scene run as the report's figures take it: sampled [`FINE`] times
//! finer than the scene's own `output_dt` (so that speed curves are smooth;
//! snapshots keep the scene's spacing), with where its free end was held,
//! and its animation. `cargo xtask figures` makes one per scene and shares
//! it among the figures that draw that scene.

use std::path::Path;

use chain_ode::{Trajectory, Vec2};

use super::report::Run;
use fc_scene::scene::Scene;
use fc_study::render;

/// Samples are recorded this many times finer than the scene's `output_dt`.
pub const FINE: f64 = 32.0;

/// A finished scene run and what the figures need to know about it.
pub struct SceneRun {
    pub scene: Scene,
    pub traj: Trajectory,
    /// The scene's own sample spacing (the report's snapshot spacing; a
    /// scene without `output_dt`: `t_end / 50`).
    pub snapshot_dt: f64,
    /// Where the free end was held (P1).
    pub release: Vec2,
}

impl SceneRun {
    /// Runs `scene` as its file says, sampled [`FINE`] times finer. A run
    /// that ends with a failed status is an error naming it.
    pub fn run(scene: Scene) -> Result<SceneRun, String> {
        SceneRun::run_sampled(scene, FINE)
    }

    /// As [`SceneRun::run`], sampled `fine` times finer than the scene's
    /// spacing (the tip velocity's loops, which turn fast in the whip).
    pub fn run_sampled(scene: Scene, fine: f64) -> Result<SceneRun, String> {
        let name = scene.name().to_string();
        let mut prepared = scene.prepare().map_err(|e| e.to_string())?;
        let snapshot_dt = prepared
            .options
            .output_dt
            .unwrap_or(prepared.options.t_end / 50.0);
        prepared.options.output_dt = Some(snapshot_dt / fine);
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

    /// The run as the report's tables take it.
    pub fn as_run(&self) -> Run<'_> {
        Run {
            name: self.scene.name(),
            traj: &self.traj,
            release: self.release,
        }
    }

    /// The animation of the run, `<dir>/<name>.gif`: about 60 frames at 20
    /// per second.
    pub fn animation(&self, name: &str, dir: &Path) -> Result<(), String> {
        let fine = self.snapshot_dt / FINE;
        let spacing = fine * (self.traj.t_end / fine / 60.0).round().max(1.0);
        let title = format!("{} (t = {:.3})", name, self.traj.t_end);
        let f = render::snapshots(&title, &self.traj, Some(spacing), Some(self.release));
        figures::chain_animation(&f, &dir.join(format!("{name}.gif")), 20)
            .map_err(|e| format!("anim {name}: {e}"))
    }
}
