//! Speed against accuracy: work-precision diagrams, the stability map and
//! the cost of one right-hand side.
//!
//! Every timed run here runs alone (never beside another timed run of this
//! module) and its time is the median of repeats; the untimed runs of the
//! stability map run in parallel.

#[path = "precision_cost.rs"]
mod cost;
#[path = "precision_map.rs"]
mod map;
#[path = "precision_stiffness.rs"]
mod stiffness;
#[path = "precision_wp.rs"]
mod wp;

use std::io::Write;
use std::path::Path;

use falling_chain::{Prepared, Scene};

use super::{Ctx, Study};

pub const STUDIES: &[Study] = &[
    Study {
        id: "wp-span-d3",
        what: "work-precision of the span d = 3 scene: tip position and maximum tip speed error \
               vs wall time and vs RHS evaluations, RK4 over dt, DOPRI5 / BDF / auto over rtol, \
               against a DOPRI5 rtol 1e-13 reference checked by RK4 and BDF",
        make: wp::span_d3,
    },
    Study {
        id: "wp-folded",
        what: "work-precision of the folded scene (r = 0.001), evaluated at the last time before \
               two runs 1e-10 apart separate 1000-fold: its end, as they never do (its r = 0 \
               variant does after the whip; `data/wp-folded-divergence.csv`)",
        make: wp::folded,
    },
    Study {
        id: "wp-stiff-rope",
        what: "work-precision of the stiff rope (n = 100, r = 1): explicit methods held at their \
               stability limit, BDF not",
        make: wp::stiff_rope,
    },
    Study {
        id: "stability-map",
        what: "where each method fails: method x dt / rtol x scene -> completed, energy-balance \
               error above 1% of M g L, diverged, step size too small, step budget exhausted",
        make: map::make,
    },
    Study {
        id: "stiffness",
        what: "where BDF pays: DOPRI5's wall time over the O(n) BDF's against the damping rate \
               gamma for n = 25 to 3200 (span d = 3, t = 1, rtol 1e-6), and the crossover gamma \
               for each n",
        make: stiffness::make,
    },
    Study {
        id: "rhs-cost",
        what: "cost of one right-hand side vs n: the O(n) recursion against the dense Cholesky \
               solve, measured slopes against n and n^3",
        make: cost::make,
    },
];

/// A scene of `scenes/` with `overrides` applied, ready to run, recording
/// no samples (summaries only).
fn prepare(ctx: &Ctx, name: &str, overrides: &[String]) -> Result<Prepared, String> {
    let path = ctx.root.join("scenes").join(format!("{name}.toml"));
    let scene = Scene::load(&path).map_err(|e| e.to_string())?;
    let scene = scene
        .with_overrides(overrides)
        .map_err(|e| format!("{name}: {e}"))?;
    let mut p = scene.prepare().map_err(|e| format!("{name}: {e}"))?;
    p.options.output_dt = None;
    Ok(p)
}

/// Writes `text` to `path` atomically; returns the path relative to the root.
fn write_text(ctx: &Ctx, path: &Path, text: &str) -> Result<String, String> {
    falling_chain::atomic::write_atomic("study data", path, |w: &mut dyn Write| {
        w.write_all(text.as_bytes())
    })
    .map_err(|e| e.to_string())?;
    Ok(relative(ctx, path))
}

/// `path` relative to the workspace root, for the list of written files.
fn relative(ctx: &Ctx, path: &Path) -> String {
    path.strip_prefix(&ctx.root)
        .unwrap_or(path)
        .display()
        .to_string()
}

/// The files a figure was written to, relative to the root.
fn written(ctx: &Ctx, out: &figures::Output) -> Vec<String> {
    vec![relative(ctx, &out.png), relative(ctx, &out.svg)]
}

/// The median of `v` (which must not be empty).
fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let k = v.len();
    if k % 2 == 1 {
        v[k / 2]
    } else {
        0.5 * (v[k / 2 - 1] + v[k / 2])
    }
}

/// `1e-3`-style text of a step or a tolerance.
fn short(v: f64) -> String {
    format!("{v:e}")
}

/// Least-squares slope of `log y` against `log x`.
fn log_slope(pts: &[(f64, f64)]) -> f64 {
    let k = pts.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = pts.iter().map(|&(x, y)| (x.ln(), y.ln())).unzip();
    let mx = lx.iter().sum::<f64>() / k;
    let my = ly.iter().sum::<f64>() / k;
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_names_powers_of_ten() {
        assert_eq!(short(1e-3), "1e-3");
        assert_eq!(short(0.02), "2e-2");
        assert_eq!(short(5e-4), "5e-4");
        assert_eq!(short(3e-5), "3e-5");
    }

    #[test]
    fn slope_of_a_power_law() {
        let pts: Vec<(f64, f64)> = [10.0, 100.0, 1000.0]
            .iter()
            .map(|&n: &f64| (n, 2.0 * n.powi(3)))
            .collect();
        assert!((log_slope(&pts) - 3.0).abs() < 1e-12);
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
    }
}
