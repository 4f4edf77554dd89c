//! Drawing each figure of the catalogue from finished runs.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use catenary::Catenary;
use falling_chain::render;
use falling_chain::sweep::{self, Vary};
use figures::{LinePlot, Series, Style};

use crate::catalog::{Figure, Kind, LinspaceSlice};
use crate::runs::{SceneRun, FINE};

/// Everything a figure may draw from.
pub struct Inputs<'a> {
    pub runs: &'a BTreeMap<&'static str, SceneRun>,
    pub data_dir: &'a Path,
    pub jobs: usize,
}

fn label(run: &SceneRun) -> String {
    let p = run.release;
    format!("{} (P1 = ({:.3}, {:.3}))", run.scene.name(), p[0], p[1]).replace(".000", "")
}

/// Draws `fig` into `<out>/<id>.png` and `.svg`.
pub fn figure(fig: &Figure, inputs: &Inputs, out: &Path) -> Result<(), String> {
    let stem = out.join(fig.id);
    let title = format!("{}: {}", fig.report, fig.title);
    let res = match fig.kind {
        Kind::Sketch => figures::sketch(&stem),
        Kind::Catenaries { p1, lengths } => {
            let (l0, l1, count) = lengths;
            let mut curves = vec![];
            let mut lows = vec![];
            for k in 0..count {
                let length = l0 + (l1 - l0) * k as f64 / (count - 1) as f64;
                let c = Catenary::through([0.0, 0.0], p1, length).map_err(|e| e.to_string())?;
                let pts = (0..=200)
                    .map(|i| {
                        let x = p1[0] * i as f64 / 200.0;
                        (x, c.y(x))
                    })
                    .collect();
                curves.push((length, pts));
                let low = c.lowest_point();
                lows.push((low[0], low[1]));
            }
            let mut f = figures::ColoredCurves::new(&title, curves, [0.0, 0.0]);
            f.p1 = Some(p1);
            f.markers = lows;
            f.markers_label = "lowest point";
            f.colorbar_label = "L";
            figures::colored_curves(&f, &stem)
        }
        Kind::Snapshots { scene, x_range } => {
            let run = &inputs.runs[scene];
            let mut f =
                render::snapshots(&title, &run.traj, Some(run.snapshot_dt), Some(run.release));
            if let Some(xr) = x_range {
                f.x_range = Some(xr);
                f.equal_aspect = false;
            }
            figures::chain_snapshots(&f, &stem)
        }
        Kind::TipSpeed { scenes } => {
            let mut p = LinePlot::new(&title, "t", "tip speed |v|");
            for s in scenes {
                let run = &inputs.runs[s];
                p.series
                    .push(Series::line(label(run), render::tip_speed(&run.traj)));
            }
            // The continuous maxima, located between steps.
            let maxima = scenes
                .iter()
                .map(|s| {
                    let sm = &inputs.runs[s].traj.summary;
                    (sm.t_tip_speed_max, sm.tip_speed_max)
                })
                .collect();
            p.series.push(
                Series::new("maximum (continuous)", maxima, Style::Points)
                    .with_color(figures::RGBColor(0, 0, 0)),
            );
            figures::line_plot(&p, &stem)
        }
        Kind::TipVelocity { scenes } => {
            let mut p = LinePlot::new(&title, "v_x", "v_y");
            p.equal_aspect = true;
            for s in scenes {
                let run = &inputs.runs[s];
                p.series.push(Series::line(
                    label(run),
                    render::tip_velocity_path(&run.traj),
                ));
            }
            figures::line_plot(&p, &stem)
        }
        Kind::VmaxVsSpan {
            scene,
            stretched,
            report_spans,
            dense,
        } => {
            return vmax_vs_span(
                fig,
                &title,
                inputs,
                scene,
                stretched,
                report_spans,
                dense,
                &stem,
            )
        }
    };
    res.map(|_| ()).map_err(|e| format!("{}: {e}", fig.id))
}

/// `n` evenly spaced values from `a` to `b` (both included).
fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

#[allow(clippy::too_many_arguments)]
fn vmax_vs_span(
    fig: &Figure,
    title: &str,
    inputs: &Inputs,
    scene: &str,
    stretched: &str,
    report_spans: LinspaceSlice,
    dense: (f64, f64, usize),
    stem: &Path,
) -> Result<(), String> {
    let s = report_spans;
    let report: Vec<f64> = linspace(s.start, s.stop, s.num)[s.from..s.to].to_vec();
    let dense: Vec<f64> = linspace(dense.0, dense.1, dense.2);
    let base = &inputs.runs[scene].scene;
    // Adaptive DOPRI5 for every span: RK4 at the report's dt diverges near d = 1.
    let base = base
        .with_overrides(&["run.method=dopri5", "run.rtol=1e-8", "run.atol=1e-10"])
        .map_err(|e| e.to_string())?;
    let sweep_of = |spans: &[f64]| -> Result<Vec<(f64, f64, f64, String)>, String> {
        let vary = [Vary::floats("start.p1.0", spans)];
        let rows =
            sweep::run(&base, &vary, None, inputs.jobs, &|_, _| {}).map_err(|e| e.to_string())?;
        Ok(rows
            .into_iter()
            .zip(spans)
            .map(|(r, &d)| {
                (
                    d,
                    r.summary.tip_speed_max,
                    r.summary.t_tip_speed_max,
                    r.summary.status,
                )
            })
            .collect())
    };
    let rep = sweep_of(&report)?;
    let den = sweep_of(&dense)?;
    let full = &inputs.runs[stretched];
    let d_full = full.release[0] - full.traj.anchor[0];
    let ok = |v: &[(f64, f64, f64, String)]| -> Vec<(f64, f64)> {
        v.iter()
            .filter(|r| r.3 == "ok")
            .map(|r| (r.0, r.1))
            .collect()
    };
    let mut p = LinePlot::new(title, "span d", "maximum tip speed");
    p.series.push(Series::line(
        format!("{} spans (DOPRI5, rtol 1e-8)", dense.len()),
        ok(&den),
    ));
    p.series
        .push(Series::points("the report's 14 spans", ok(&rep)));
    p.series.push(Series::points(
        "stretched, d = L",
        vec![(d_full, full.traj.summary.tip_speed_max)],
    ));
    figures::line_plot(&p, stem).map_err(|e| format!("{}: {e}", fig.id))?;

    // The numbers behind the figure (deterministic: no wall times).
    let mut csv = String::from("set,d,tip_speed_max,t_tip_speed_max,status\n");
    for (set, rows) in [("report", &rep), ("dense", &den)] {
        for r in rows.iter() {
            csv.push_str(&format!("{set},{},{},{},{}\n", r.0, r.1, r.2, r.3));
        }
    }
    csv.push_str(&format!(
        "stretched,{d_full},{},{},{}\n",
        full.traj.summary.tip_speed_max, full.traj.summary.t_tip_speed_max, full.traj.status
    ));
    fs::create_dir_all(inputs.data_dir).map_err(|e| e.to_string())?;
    fs::write(inputs.data_dir.join(format!("{}.csv", fig.id)), csv).map_err(|e| e.to_string())
}

/// The animation of one scene run: about 60 frames at 20 per second.
pub fn animation(name: &str, run: &SceneRun, out: &Path) -> Result<(), String> {
    let fine = run.snapshot_dt / FINE;
    let spacing = fine * (run.traj.t_end / fine / 60.0).round().max(1.0);
    let title = format!("{} (t = {:.3})", name, run.traj.t_end);
    let f = render::snapshots(&title, &run.traj, Some(spacing), Some(run.release));
    figures::chain_animation(&f, &out.join(format!("{name}.gif")), 20)
        .map_err(|e| format!("anim {name}: {e}"))
}
