//! `elastic-rigid-limit`: "when can I use the rigid model". For each report
//! scene, at its own `n` and mass per rod (the report's convention), the
//! elastic chain's distance from the rigid one (tip path and maximum tip
//! speed) against `EA`, and the `EA` above which it stays within 1e-3
//! (`falling_chain::study::rigid_limit`; 5% damping of one joint, DOPRI5 at
//! rtol 1e-8 for every run). Its ladders take about 5 min on two cores
//! (DOPRI5's steps grow like `sqrt(EA)`, to 5.6 million at `EA = 1e9`), so
//! it is computed only by `--timings` and its files, which carry each run's
//! wall time too, are timing files; without `--timings` it is drawn from
//! them as committed.

use falling_chain::study::rigid_limit::{self, Options, RUNGS_HEADER, THRESHOLD_HEADER};
use figures::{palette, LinePlot, Series, Style};
use rayon::prelude::*;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};
use falling_chain::study::table::distinct;

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
        let opts = Options::default();
        let results: Vec<Result<rigid_limit::RigidLimit, String>> = ctx.pool()?.install(|| {
            SCENES
                .par_iter()
                .map(|name| {
                    let scene = ctx.scene::<&str>(name, &[])?;
                    rigid_limit::rigid_limit(&scene, &opts).map_err(|e| format!("{name}: {e}"))
                })
                .collect()
        });
        let (mut rungs, mut answers) = (RUNGS_HEADER.to_string(), THRESHOLD_HEADER.to_string());
        for r in results {
            let r = r?;
            rungs.push_str(&rigid_limit::rungs_csv(&r));
            answers.push_str(&rigid_limit::threshold_csv(&r));
            println!(
                "  {}: {}: EA above {}",
                fig.id,
                r.scene,
                r.threshold
                    .map_or("none in the ladder".into(), |t| format!("{t:.3e}"))
            );
        }
        Ok(vec![
            ctx.write(&format!("{}-timing.csv", fig.id), &rungs)?,
            ctx.write(&format!("{}-threshold-timing.csv", fig.id), &answers)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}-timing.csv", fig.id))?;
        let (scene, ea) = (t.strs("scene")?, t.nums("axial_stiffness")?);
        let (path, speed) = (t.nums("tip_path")?, t.nums("tip_speed_max")?);
        let a = ctx.read(&format!("{}-threshold-timing.csv", fig.id))?;
        let (a_scene, a_thr, a_tol) = (a.strs("scene")?, a.nums("threshold")?, a.nums("tol")?);
        let tol = a_tol.first().copied().unwrap_or(1e-3);
        let mut left = LinePlot::new("tip path: max |tip - tip_rigid| / L", "EA", "deviation");
        let mut right = LinePlot::new(
            "maximum tip speed: |v_max / v_max_rigid - 1|",
            "EA",
            "deviation",
        );
        for p in [&mut left, &mut right] {
            p.log_x = true;
            p.log_y = true;
            p.x_range = Some((5e2, 2e9));
            p.y_range = Some((1e-8, 1e8));
        }
        let mut notes = vec![format!("EA above which both stay below {tol:e}:")];
        for (k, s) in distinct(&scene).into_iter().enumerate() {
            let rows: Vec<usize> = (0..t.len()).filter(|&j| scene[j] == s).collect();
            let pts = |col: &[f64]| -> Vec<(f64, f64)> {
                rows.iter()
                    .filter(|&&j| col[j].is_finite() && col[j] > 0.0)
                    .map(|&j| (ea[j], col[j]))
                    .collect()
            };
            let style = if k < 10 {
                Style::LinePoints
            } else {
                Style::Dashed
            };
            left.series
                .push(Series::new(s, pts(&path), style).with_color(palette(k)));
            right
                .series
                .push(Series::new("", pts(&speed), style).with_color(palette(k)));
            if let Some(j) = a_scene.iter().position(|x| *x == s) {
                let thr = a_thr[j];
                notes.push(if thr.is_finite() {
                    format!("{s}: {thr:.1e}")
                } else {
                    format!("{s}: none up to 1e9")
                });
            }
        }
        for p in [&mut left, &mut right] {
            p.series.push(
                Series::new(
                    format!("tol = {tol:e}"),
                    vec![(5e2, tol), (2e9, tol)],
                    Style::Dashed,
                )
                .with_color(figures::RGBColor(0, 0, 0)),
            );
        }
        right.annotations = notes;
        let title = "When the rigid model will do: elastic against rigid links (report scenes)";
        let out = figures::line_plot_pair(&left, &right, title, &ctx.stem(fig.id))
            .map_err(|e| format!("{}: {e}", fig.id))?;
        Ok(ctx.drawn(&out))
    }
}
