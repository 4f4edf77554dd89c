//! `rhs-cost`: the cost of one right-hand side against n, the O(n)
//! recursion (a whole `ChainSystem::rhs`) against the dense reference
//! (assemble `A` and `b`, faer's Cholesky), timed here with
//! `std::time::Instant` over many calls, median of repeats. All of it is
//! wall times: computed only by `--timings`, into `rhs-cost-timing.csv` and
//! `rhs-cost-fit-timing.csv`.

use falling_chain::study::rhs_cost::{self, FIT_FROM};
use figures::{palette, LinePlot, RGBColor, Series, Style};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The slope guides run this factor below the measured points.
const GUIDE_OFFSET: f64 = 3.0;

pub struct RhsCost;

impl Make for RhsCost {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let (rows, fits) = rhs_cost::tables()?;
        Ok(vec![
            ctx.write(&format!("{}-timing.csv", fig.id), &rows)?,
            ctx.write(&format!("{}-fit-timing.csv", fig.id), &fits)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}-timing.csv", fig.id))?;
        let (solver, n, secs) = (t.strs("solver")?, t.nums("n")?, t.nums("seconds_per_call")?);
        let f = ctx.read(&format!("{}-fit-timing.csv", fig.id))?;
        let (fit_solver, fit_slope) = (f.strs("solver")?, f.nums("slope")?);
        let slope = |kind: &str| {
            fit_solver
                .iter()
                .position(|s| *s == kind)
                .map_or(f64::NAN, |k| fit_slope[k])
        };
        let (slope_fast, slope_dense) = (slope("recursion"), slope("dense"));
        let (slope_assembly, slope_factor) =
            (slope("dense-assembly"), slope("dense-minus-assembly"));
        let pts = |kind: &str| -> Vec<(f64, f64)> {
            (0..t.len())
                .filter(|&k| solver[k] == kind)
                .map(|k| (n[k], secs[k]))
                .collect()
        };
        let (fast, dense_pts, assembly) = (pts("recursion"), pts("dense"), pts("dense-assembly"));
        if fast.is_empty() || dense_pts.is_empty() {
            return Err(format!("{}: no recursion or dense rows", t.name));
        }

        // The figure: measured points, and reference slopes n and n^3
        // through the last measured point of each, a factor GUIDE_OFFSET below.
        let guide = |p: &[(f64, f64)], k: i32, ns: &[f64]| -> Vec<(f64, f64)> {
            let (n1, t1) = p[p.len() - 1];
            ns.iter()
                .map(|&n| (n, t1 / GUIDE_OFFSET * (n / n1).powi(k)))
                .collect()
        };
        let mut plot = LinePlot::new(
            "Cost of one right-hand side",
            "rods n",
            "seconds per evaluation (median)",
        );
        plot.log_x = true;
        plot.log_y = true;
        plot.series.push(
            Series::new(
                format!("O(n) recursion (ChainSystem::rhs): slope {slope_fast:.2}"),
                fast.clone(),
                Style::LinePoints,
            )
            .with_color(palette(0)),
        );
        plot.series.push(
            Series::new(
                format!("dense: assemble A, b + Cholesky (faer): slope {slope_dense:.2}"),
                dense_pts.clone(),
                Style::LinePoints,
            )
            .with_color(palette(3)),
        );
        plot.series.push(
            Series::new(
                format!("dense, assembly of A and b only: slope {slope_assembly:.2}"),
                assembly,
                Style::LinePoints,
            )
            .with_color(palette(1)),
        );
        plot.series.push(
            Series::new("∝ n", guide(&fast, 1, &[25.0, 10000.0]), Style::Dashed)
                .with_color(palette(0)),
        );
        plot.series.push(
            Series::new(
                "∝ n³",
                guide(&dense_pts, 3, &[100.0, 1000.0]),
                Style::Dashed,
            )
            .with_color(palette(3)),
        );
        let at = |kind: &str, rods: f64| {
            (0..t.len())
                .find(|&k| solver[k] == kind && n[k] == rods)
                .map(|k| secs[k])
        };
        let ratio = |rods: f64| Some(at("dense", rods)? / at("recursion", rods)?);
        // Lines of text in the legend (invisible swatches), which gets room of
        // its own above the data.
        for line in [
            format!("slopes fitted for n ≥ {FIT_FROM}; guides offset ×1/{GUIDE_OFFSET}"),
            format!("dense less assembly (Cholesky + solve): slope {slope_factor:.2}"),
            format!(
                "dense / O(n): {:.0}× at n = 50, {:.0}× at n = 1000",
                ratio(50.0).unwrap_or(f64::NAN),
                ratio(1000.0).unwrap_or(f64::NAN)
            ),
        ] {
            plot.series
                .push(Series::new(line, vec![], Style::Points).with_color(RGBColor(255, 255, 255)));
        }
        let out = figures::line_plot(&plot, &ctx.stem(fig.id)).map_err(|e| e.to_string())?;
        Ok(ctx.drawn(&out))
    }
}
