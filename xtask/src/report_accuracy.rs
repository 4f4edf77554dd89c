//! `report-scenes-accuracy`: is each report figure drawn from a converged
//! run? Every report scene with dynamics, run by RK4 at steps from the
//! report's `dt = 0.01` down to `0.01/8` (with `0.0035`, the report's own
//! step converted to our clock at `n = 50`), and at the scene's own settings,
//! against a reference run by DOP853 at rtol 1e-12 (atol 1e-14).
//!
//! The error of a run is the largest of three relative deviations from the
//! reference: the maximum tip speed, the dissipated work `W(t_end)` (over
//! the reference's `W` when it is above `1e-6 M g L`, else over `M g L`),
//! and the tip's end position (over `L`). The time of the maximum is
//! recorded beside, since a spurious late whip moves it far.

use std::fmt::Write as _;

use falling_chain::RunSummary;
use figures::{palette, LinePlot, Series, Style};
use rayon::prelude::*;

use crate::ctx::Ctx;
use crate::data::{distinct, num};
use crate::registry::{Figure, Make};

/// The report scenes whose figures show dynamics.
const SCENES: [&str; 14] = [
    "horizontal-undamped",
    "horizontal-damped",
    "horizontal-settling",
    "horizontal-settling-report-damping",
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

/// RK4's steps: `0.01` halved three times, and `0.0035`, the report's
/// step `0.01` in its clock converted to ours at `n = 50` (erratum 3).
const STEPS: [f64; 5] = [0.01, 0.005, 0.0035, 0.0025, 0.00125];

/// One run's overrides: a label and the `--set` list.
fn settings() -> Vec<(String, Vec<String>)> {
    let mut out = vec![("scene".to_string(), vec![])];
    for dt in STEPS {
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

pub struct ReportAccuracy;

impl Make for ReportAccuracy {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let jobs: Vec<(&str, String, Vec<String>)> = SCENES
            .iter()
            .flat_map(|s| settings().into_iter().map(move |(l, o)| (*s, l, o)))
            .collect();
        let runs = ctx.pool()?.install(|| {
            jobs.par_iter()
                .map(|(scene, label, overrides)| {
                    let prepared = ctx.prepare(scene, overrides)?;
                    let traj = prepared.solve().map_err(|e| e.to_string())?;
                    if !traj.status.is_ok() && label == "reference" {
                        return Err(format!("{}: {scene} {label}: {}", fig.id, traj.status));
                    }
                    // The step for RK4, the tolerance for the adaptive methods.
                    let fixed = prepared.method.accuracy_name() == "dt";
                    let (o, length) = (&prepared.options, traj.chain.length());
                    let dt = if fixed { num(o.dt) } else { String::new() };
                    let rtol = if fixed { String::new() } else { num(o.rtol) };
                    let summary = RunSummary::from_trajectory(scene, &traj);
                    Ok((summary, length, dt, rtol))
                })
                .collect::<Result<Vec<_>, String>>()
        })?;
        let mut csv = String::from(
            "scene,setting,method,dt,rtol,status,t_reached,energy_balance_over_MgL,tip_speed_max,t_tip_speed_max,dissipated,\
             tip_end_x,tip_end_y,error_tip_speed_max,error_dissipated,error_tip_end,error\n",
        );
        for (k, scene) in SCENES.iter().enumerate() {
            let group = &runs[k * settings().len()..(k + 1) * settings().len()];
            let (reference, length, _, _) = &group[group.len() - 1];
            for ((label, _), (run, _, dt, rtol)) in settings().iter().zip(group) {
                if run.status != "ok" {
                    // A failed run (RK4 diverges on span d = 1 at dt = 0.01):
                    // its status and where it stopped, no errors.
                    writeln!(
                        csv,
                        "{scene},{label},{},{dt},{rtol},{},{},,,,,,,,,,",
                        run.method,
                        run.status,
                        num(run.t_reached)
                    )
                    .map_err(|e| e.to_string())?;
                    continue;
                }
                let e_v =
                    (run.tip_speed_max - reference.tip_speed_max).abs() / reference.tip_speed_max;
                let w_scale = if reference.dissipated > 1e-6 * reference.energy_scale {
                    reference.dissipated
                } else {
                    reference.energy_scale
                };
                let e_w = (run.dissipated - reference.dissipated).abs() / w_scale;
                let e_x = (run.tip_end[0] - reference.tip_end[0])
                    .hypot(run.tip_end[1] - reference.tip_end[1])
                    / length;
                writeln!(
                    csv,
                    "{scene},{label},{},{dt},{rtol},ok,{},{},{},{},{},{},{},{},{},{},{}",
                    run.method,
                    num(run.t_reached),
                    num(run.energy_balance_error / run.energy_scale),
                    num(run.tip_speed_max),
                    num(run.t_tip_speed_max),
                    num(run.dissipated),
                    num(run.tip_end[0]),
                    num(run.tip_end[1]),
                    num(e_v),
                    num(e_w),
                    num(e_x),
                    num(e_v.max(e_w).max(e_x)),
                )
                .map_err(|e| e.to_string())?;
            }
        }
        Ok(vec![ctx.write(fig.data[0], &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(fig.data[0])?;
        let (scene, setting, status) = (t.strs("scene")?, t.strs("setting")?, t.strs("status")?);
        let (dt, error) = (t.nums("dt")?, t.nums("error")?);
        let floor = 1e-13;
        let y_label = "largest relative error (tip speed max, W, tip end)";
        // Two panels, so that each keeps its colours distinct: the
        // horizontal and catenary starts (Figs. 3-6), then spans and heights.
        let mut panels = [
            LinePlot::new("Figs. 3-6", "RK4 step dt", y_label),
            LinePlot::new("Figs. 7-12", "RK4 step dt", y_label),
        ];
        for p in &mut panels {
            p.log_x = true;
            p.log_y = true;
            // The data sit left of dt = 0.01; the legend takes the right.
            p.x_range = Some((1e-3, 1.0));
            p.y_range = Some((1e-13, 10.0));
        }
        let names = distinct(&scene);
        for (i, name) in names.iter().enumerate() {
            let panel = usize::from(
                name.starts_with("span") || name.starts_with("height") || *name == "folded",
            );
            let colour = palette(if panel == 0 { i } else { i - 5 });
            let rows: Vec<usize> = (0..t.len()).filter(|&k| scene[k] == *name).collect();
            let rk4: Vec<(f64, f64)> = rows
                .iter()
                .filter(|&&k| setting[k].starts_with("rk4") && status[k] == "ok")
                .map(|&k| (dt[k], error[k].max(floor)))
                .collect();
            panels[panel]
                .series
                .push(Series::new(*name, rk4, Style::LinePoints).with_color(colour));
            if let Some(&k) = rows
                .iter()
                .find(|&&k| setting[k] == "scene" && status[k] == "ok")
            {
                let own = vec![
                    (STEPS[4], error[k].max(floor)),
                    (STEPS[0], error[k].max(floor)),
                ];
                panels[panel]
                    .series
                    .push(Series::new("", own, Style::Dashed).with_color(colour));
            }
        }
        for p in &mut panels {
            p.annotations = vec![
                "dashed: the scene's own settings".to_string(),
                format!("errors below {floor:.0e} drawn at {floor:.0e}"),
            ];
        }
        for k in (0..t.len()).filter(|&k| status[k] != "ok") {
            panels[1]
                .annotations
                .push(format!("{} {}: {}", scene[k], setting[k], status[k]));
        }
        let title = "Report scenes: RK4 and the scenes' own runs against DOP853 at rtol 1e-12";
        let out = figures::line_plot_pair(&panels[0], &panels[1], title, &ctx.stem(fig.id))
            .map_err(|e| format!("{}: {e}", fig.id))?;
        Ok(ctx.drawn(&out))
    }
}
