//! How much the maximum tip speed depends on the joint friction `r`: each
//! scene over a range of `r` bracketing its own, at its own `n` (the
//! report's convention: `r` per joint) and on the refined chain with the
//! continuum held fixed (`r = eta n / L`: the same bending viscosity, so the
//! refined chain's `r` is the scene's times `links / n`).
//!
//! Every run is converged in its tolerance: the scene's own `n` by DOPRI5
//! at [`RTOL`], the refined chain by `auto` at rtol 1e-8 as Fig. 9's refined
//! curve (`span_check::refined`).

use std::fmt::Write as _;

use super::span_check::refined;
use fc_batch::sweep::{self, Vary};
use fc_csv::format::{exp, num};
use fc_scene::scene::Scene;

/// DOPRI5's `rtol` at the scene's own `n` (`atol = rtol / 100`).
pub const RTOL: f64 = 1e-10;

/// The header of [`table`].
pub const HEADER: &str = "scene,links,r,r_over_scene,tip_speed_max,t_tip_speed_max,status\n";
/// The header of [`summary`].
pub const SUMMARY_HEADER: &str = "scene,links,r_scene,vmax_r0,vmax_scene,change_r0_to_scene,\
                                  vmax_lo,vmax_hi,change_lo_to_hi,log_slope_at_scene\n";

/// One run: `r` in the scene's own units (at its own `n`), and its result.
pub struct Point {
    pub r: f64,
    pub vmax: f64,
    pub t_vmax: f64,
    pub status: String,
}

/// One scene at one `n` over `rs` (in the scene's own `r`, at its own `n`).
pub struct Line {
    pub scene: String,
    pub links: usize,
    /// The scene's own `r`.
    pub r_scene: f64,
    pub points: Vec<Point>,
}

/// Runs `scene` over `rs` (its own `n`, `r` in its units) and, if `fine` is
/// given, the refined chain of `fine` rods over the same bending
/// viscosities.
pub fn lines(
    scene: &Scene,
    rs: &[f64],
    fine: Option<usize>,
    jobs: usize,
) -> Result<Vec<Line>, String> {
    let p = scene.chain_params();
    let (n, r_scene) = (p.links, p.damping);
    let coarse = scene
        .with_overrides(&[
            "run.method=dopri5".to_string(),
            format!("run.rtol={RTOL:e}"),
            format!("run.atol={:e}", RTOL * 1e-2),
        ])
        .map_err(|e| e.to_string())?;
    let run = |s: &Scene, links: usize| -> Result<Line, String> {
        let rows = sweep::run(
            s,
            &[Vary::floats("chain.damping", rs)],
            None,
            jobs,
            &|_, _| {},
        )
        .map_err(|e| e.to_string())?;
        Ok(Line {
            scene: scene.name().to_string(),
            links,
            r_scene,
            points: rows
                .iter()
                .zip(rs)
                .map(|(row, &r)| Point {
                    r,
                    vmax: row.summary.tip_speed_max,
                    t_vmax: row.summary.t_tip_speed_max,
                    status: row.summary.status.clone(),
                })
                .collect(),
        })
    };
    let mut out = vec![run(&coarse, n)?];
    if let Some(links) = fine {
        // The refined chain: each r of the scene, refined (r scaled with n).
        let mut points = vec![];
        for &r in rs {
            let s = coarse
                .with_value("chain.damping", toml::Value::Float(r))
                .map_err(|e| e.to_string())?;
            let mut prepared = refined(&s, links)?.prepare().map_err(|e| e.to_string())?;
            prepared.options.output_dt = None;
            let traj = prepared.solve().map_err(|e| e.to_string())?;
            points.push(Point {
                r,
                vmax: traj.summary.tip_speed_max,
                t_vmax: traj.summary.t_tip_speed_max,
                status: traj.status.to_string(),
            });
        }
        out.push(Line {
            scene: scene.name().to_string(),
            links,
            r_scene,
            points,
        });
    }
    Ok(out)
}

/// The rows of `lines` (under [`HEADER`]); `r` is given in the scene's own
/// units (at its own `n`) for every line.
pub fn table(lines: &[Line]) -> String {
    let mut csv = String::new();
    for l in lines {
        for p in &l.points {
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{}",
                l.scene,
                l.links,
                exp(p.r),
                num(p.r / l.r_scene),
                num(p.vmax),
                num(p.t_vmax),
                p.status
            );
        }
    }
    csv
}

/// A line's summary (under [`SUMMARY_HEADER`]): the maximum at `r = 0` and
/// at the scene's `r`, the relative change between them, the maxima at
/// `lo` and `hi` and the change between them, and the log-log slope
/// `d log vmax / d log r` at the scene's `r` (central, from its
/// neighbours in the grid).
pub fn summary(l: &Line, (lo, hi): (f64, f64)) -> String {
    let at = |r: f64| {
        l.points
            .iter()
            .find(|p| p.r == r && p.status == "ok")
            .map_or(f64::NAN, |p| p.vmax)
    };
    let (v0, vs, vlo, vhi) = (at(0.0), at(l.r_scene), at(lo), at(hi));
    let k = l.points.iter().position(|p| p.r == l.r_scene);
    let slope = k
        .and_then(|k| Some((l.points.get(k.checked_sub(1)?)?, l.points.get(k + 1)?)))
        .filter(|(a, b)| a.r > 0.0 && b.r > 0.0)
        .map_or(f64::NAN, |(a, b)| (b.vmax / a.vmax).ln() / (b.r / a.r).ln());
    format!(
        "{},{},{},{},{},{},{},{},{},{}\n",
        l.scene,
        l.links,
        exp(l.r_scene),
        num(v0),
        num(vs),
        num(vs / v0 - 1.0),
        num(vlo),
        num(vhi),
        num(vhi / vlo - 1.0),
        num(slope)
    )
}
