//! Is a scene's run converged? The table behind `report-scenes-accuracy`:
//! each scene run at its own settings and by RK4 at a ladder of steps,
//! against a reference by DOP853 at rtol 1e-12 (atol 1e-14).
//!
//! The error of a run is the largest of three relative deviations from the
//! reference: the maximum tip speed; the dissipated work `W(t_end)` (over
//! the reference's `W` when it is above `1e-6 M g L`, else over `M g L`);
//! and the tip's end position (over `L`). The time of the maximum is kept
//! beside it, since a spurious late whip moves it far. A failed run keeps
//! its status and where it stopped, and no errors.

use std::fmt::Write as _;

use fc_csv::format::num;
use fc_scene::scene::Prepared;
use fc_scene::RunSummary;

/// RK4's steps: `0.01` halved three times, and `0.0035`, the report's step
/// `0.01` in its clock converted to ours at `n = 50` (`docs/model.md`,
/// erratum 3).
pub const RK4_STEPS: [f64; 5] = [0.01, 0.005, 0.0035, 0.0025, 0.00125];

/// The runs of one scene: a label and its overrides (`--set` form). The
/// scene's own settings first, the reference last.
pub fn settings() -> Vec<(String, Vec<String>)> {
    let mut out = vec![("scene".to_string(), vec![])];
    for dt in RK4_STEPS {
        out.push((
            format!("rk4 dt={dt}"),
            vec!["run.method=\"rk4\"".into(), format!("run.dt={dt}")],
        ));
    }
    out.push((
        "reference".into(),
        vec![
            "run.method=\"dop853\"".into(),
            "run.rtol=1e-12".into(),
            "run.atol=1e-14".into(),
        ],
    ));
    out
}

/// One run of [`settings`] on one scene.
pub struct Run {
    pub scene: String,
    /// The setting's label.
    pub label: String,
    pub summary: RunSummary,
    /// The chain's length `L`.
    pub length: f64,
    /// `run.dt` for a fixed-step method, else empty.
    pub dt: String,
    /// `run.rtol` for an adaptive method, else empty.
    pub rtol: String,
}

impl Run {
    /// Runs `prepared`, the setting `label` of scene `scene`.
    pub fn of(scene: &str, label: &str, prepared: &Prepared) -> Result<Run, String> {
        let traj = prepared.solve().map_err(|e| e.to_string())?;
        let fixed = prepared.method.accuracy_name() == "dt";
        let o = &prepared.options;
        Ok(Run {
            scene: scene.to_string(),
            label: label.to_string(),
            summary: RunSummary::from_trajectory(scene, &traj),
            length: traj.chain().length(),
            dt: if fixed { num(o.dt) } else { String::new() },
            rtol: if fixed { String::new() } else { num(o.rtol) },
        })
    }
}

/// Every setting of [`settings`] of every scene of `scenes`, run on the
/// current rayon pool (`prepare` gives a scene with overrides, ready to
/// run), and their [`table`].
pub fn scenes_table<F>(scenes: &[&str], prepare: &F) -> Result<String, String>
where
    F: Fn(&str, &[String]) -> Result<Prepared, String> + Sync,
{
    use rayon::prelude::*;
    let jobs: Vec<(&str, String, Vec<String>)> = (scenes.iter())
        .flat_map(|&s| settings().into_iter().map(move |(l, o)| (s, l, o)))
        .collect();
    let runs = (jobs.par_iter())
        .map(|(scene, label, set)| Run::of(scene, label, &prepare(scene, set)?))
        .collect::<Result<Vec<_>, String>>()?;
    table(&runs)
}

/// The CSV table of `runs`, which hold every setting of [`settings`] for
/// each scene in that order. Errs if a reference run failed.
pub fn table(runs: &[Run]) -> Result<String, String> {
    let per_scene = settings().len();
    let mut csv = String::from(
        "scene,setting,method,dt,rtol,status,t_reached,energy_balance_over_MgL,\
         tip_speed_max,t_tip_speed_max,dissipated,tip_end_x,tip_end_y,\
         error_tip_speed_max,error_dissipated,error_tip_end,error\n",
    );
    for group in runs.chunks(per_scene) {
        let reference = &group[group.len() - 1];
        let r = &reference.summary;
        if r.status != "ok" {
            return Err(format!(
                "{}: the reference run failed: {}",
                reference.scene, r.status
            ));
        }
        for run in group {
            let s = &run.summary;
            let head = format!(
                "{},{},{},{},{},{},{}",
                run.scene,
                run.label,
                s.method,
                run.dt,
                run.rtol,
                s.status,
                num(s.t_reached)
            );
            if s.status != "ok" {
                let _ = writeln!(csv, "{head},,,,,,,,,,");
                continue;
            }
            let e_v = (s.tip_speed_max - r.tip_speed_max).abs() / r.tip_speed_max;
            let w_scale = if r.dissipated > 1e-6 * r.energy_scale {
                r.dissipated
            } else {
                r.energy_scale
            };
            let e_w = (s.dissipated - r.dissipated).abs() / w_scale;
            let e_x =
                (s.tip_end[0] - r.tip_end[0]).hypot(s.tip_end[1] - r.tip_end[1]) / reference.length;
            let _ = writeln!(
                csv,
                "{head},{},{},{},{},{},{},{},{},{},{}",
                num(s.energy_balance_error / s.energy_scale),
                num(s.tip_speed_max),
                num(s.t_tip_speed_max),
                num(s.dissipated),
                num(s.tip_end[0]),
                num(s.tip_end[1]),
                num(e_v),
                num(e_w),
                num(e_x),
                num(e_v.max(e_w).max(e_x)),
            );
        }
    }
    Ok(csv)
}
