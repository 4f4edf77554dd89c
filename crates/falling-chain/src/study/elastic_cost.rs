//! Where BDF pays, in `EA`: each method's wall time at matched accuracy on
//! an elastic scene, across axial stiffnesses and damping ratios.
//!
//! For each `EA` and joint damping ratio `zeta` (`eta = 2 zeta sqrt(EA m
//! l)`, as [`super::rigid_limit::elastic`] sets it), a reference run (DOP853
//! at `ref_rtol`, `atol = rtol / 100`) and every method at every `rtol` of
//! the line, each run's error `max(|tip_end - tip_ref| / L, |v_max /
//! v_max_ref - 1|)` and wall time; then, as `wp-matched` does
//! ([`super::matched::time_at`]), each method's wall time at an error level,
//! log-log interpolated between the first two runs of its line that bracket
//! it, never extrapolated. The runs are timed one at a time.

use chain_ode::Method;
use serde::Serialize;

use super::format::{exp, num};
use super::matched;
use super::rigid_limit;
use crate::error::Error;
use crate::scene::Scene;

/// What to run.
#[derive(Clone, Debug)]
pub struct Options {
    pub axial_stiffness: Vec<f64>,
    pub zeta: Vec<f64>,
    pub methods: Vec<Method>,
    /// The line's tolerances, loosest first.
    pub rtols: Vec<f64>,
    /// The reference's tolerance (DOP853).
    pub ref_rtol: f64,
    /// End time of every run (time units).
    pub t_end: f64,
}

/// One run.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    pub axial_stiffness: f64,
    pub zeta: f64,
    /// `"reference"` for the reference run, else the method's name.
    pub method: String,
    pub rtol: f64,
    pub status: String,
    /// Against the reference (0 for the reference itself).
    pub error: f64,
    pub steps: u64,
    pub rhs_evals: u64,
    pub wall_seconds: f64,
    /// `auto`'s segments, e.g. `dopri5>bdf`.
    pub segments: String,
}

fn run_one(
    scene: &Scene,
    method: &str,
    rtol: f64,
    t_end: f64,
) -> Result<chain_ode::Trajectory, Error> {
    let s = scene
        .with_value("run.method", toml::Value::String(method.to_string()))?
        .with_value("run.rtol", toml::Value::Float(rtol))?
        .with_value("run.atol", toml::Value::Float(rtol * 1e-2))?
        .with_value("run.t_end", toml::Value::Float(t_end))?;
    let mut p = s.prepare()?;
    p.options.output_dt = None;
    p.solve()
}

/// Runs every case of `opts` on `scene`, one run at a time; `progress`
/// hears of each row as it is done.
pub fn run(scene: &Scene, opts: &Options, progress: &dyn Fn(&Row)) -> Result<Vec<Row>, Error> {
    let mut rows = vec![];
    let length = scene.chain_params().length;
    for &ea in &opts.axial_stiffness {
        for &zeta in &opts.zeta {
            let (s, _) = rigid_limit::elastic(scene, ea, zeta)?;
            let r = run_one(&s, Method::Dop853.as_str(), opts.ref_rtol, opts.t_end)?;
            let (tip_ref, v_ref) = (r.summary.tip_end, r.summary.tip_speed_max);
            let row = |method: &str, rtol: f64, t: &chain_ode::Trajectory, error: f64| Row {
                axial_stiffness: ea,
                zeta,
                method: method.to_string(),
                rtol,
                status: t.status.as_str().to_string(),
                error,
                steps: t.stats.steps,
                rhs_evals: t.stats.rhs_evals,
                wall_seconds: t.summary.wall_seconds,
                segments: t
                    .segments
                    .iter()
                    .map(|g| g.method.as_str())
                    .collect::<Vec<_>>()
                    .join(">"),
            };
            let reference = row("reference", opts.ref_rtol, &r, 0.0);
            progress(&reference);
            rows.push(reference);
            for &m in &opts.methods {
                for &rtol in &opts.rtols {
                    let t = run_one(&s, m.as_str(), rtol, opts.t_end)?;
                    let tip = t.summary.tip_end;
                    let error = ((tip[0] - tip_ref[0]).hypot(tip[1] - tip_ref[1]) / length)
                        .max((t.summary.tip_speed_max / v_ref - 1.0).abs());
                    let error = if t.status.is_ok() { error } else { f64::NAN };
                    let r = row(m.as_str(), rtol, &t, error);
                    progress(&r);
                    rows.push(r);
                }
            }
        }
    }
    Ok(rows)
}

/// Each method's wall time at error `level` for `(ea, zeta)`, from `rows`
/// (its runs loosest first): `None` where its line does not bracket it.
pub fn wall_at(rows: &[Row], ea: f64, zeta: f64, method: &str, level: f64) -> Option<f64> {
    let line: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.axial_stiffness == ea && r.zeta == zeta && r.method == method)
        .filter(|r| r.error.is_finite())
        .map(|r| (r.error.max(1e-300), r.wall_seconds))
        .collect();
    matched::time_at(&line, level)
}

/// The header of [`rows_csv`].
pub const HEADER: &str =
    "axial_stiffness,zeta,method,rtol,status,error,steps,rhs_evals,wall_seconds,segments\n";

/// `rows` as CSV lines (after [`HEADER`]).
pub fn rows_csv(rows: &[Row]) -> String {
    rows.iter()
        .map(|r| {
            format!(
                "{},{},{},{},{},{},{},{},{:.4e},{}\n",
                exp(r.axial_stiffness),
                num(r.zeta),
                r.method,
                exp(r.rtol),
                r.status,
                exp(r.error),
                r.steps,
                r.rhs_evals,
                r.wall_seconds,
                r.segments
            )
        })
        .collect()
}
