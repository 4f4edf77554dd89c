//! `stiffness`: where the implicit method pays. DOPRI5 against the O(n) BDF
//! over rods `n` and the damping rate `gamma = r / (m l^2)`, on the span
//! d = 3 start (report chain, `r` set from `gamma`), `t_end = 1`, rtol 1e-6,
//! atol 1e-8. The cell is DOPRI5's wall time over BDF's (median of 3 where a
//! run is short).
//!
//! An explicit method on a stiff chain is held at its stability limit: its
//! steps are all alike, and its cost is proportional to the time it covers.
//! Where DOPRI5 would take far more than [`EXPLICIT_BUDGET`] seconds, it is
//! stopped by a step budget and its wall time is extrapolated to `t_end`
//! from the time it reached (`dopri5_extrapolated = 1` in the CSV).
//!
//! Also written: the crossover `gamma` for each `n` (where the ratio first
//! exceeds 1, interpolated in `log gamma`) beside the rule `auto` uses
//! ([`chain_ode::bdf_crossover_gamma`]), and BDF's wall time per step.
//!
//! All of it is wall times: computed only by `--timings`, into
//! `stiffness-timing.csv` and `stiffness-crossover-timing.csv`.

use falling_chain::study::stiffness::{self, EXPLICIT_BUDGET};
use figures::{palette, LinePlot, RGBColor, Series, Style};

use crate::ctx::Ctx;
use crate::data::distinct;
use crate::registry::{Figure, Make};

/// Rods.
const RODS: [usize; 8] = [25, 50, 100, 200, 400, 800, 1600, 3200];
/// Damping rates `gamma` (1/time).
const GAMMAS: [f64; 8] = [1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3, 1e4, 1e5];

pub struct Stiffness;

impl Make for Stiffness {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let (cells, cross) = stiffness::tables(&RODS, &GAMMAS)?;
        Ok(vec![
            ctx.write(&format!("{}-timing.csv", fig.id), &cells)?,
            ctx.write(&format!("{}-crossover-timing.csv", fig.id), &cross)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}-timing.csv", fig.id))?;
        let (n, gamma, ratio) = (
            t.strs("n")?,
            t.nums("gamma")?,
            t.nums("ratio_dopri5_over_bdf")?,
        );
        let c = ctx.read(&format!("{}-crossover-timing.csv", fig.id))?;
        let crossings: Vec<f64> = c
            .nums("gamma_crossover")?
            .into_iter()
            .filter(|g| g.is_finite())
            .collect();
        let rods = distinct(&n);
        let mut plot = LinePlot::new(
            "Where BDF pays: DOPRI5 wall time over BDF's (span d = 3, t = 1, rtol 1e-6)",
            "damping rate γ = r / (m l²)",
            "DOPRI5 time / BDF time",
        );
        plot.log_x = true;
        plot.log_y = true;
        for (k, rods_n) in rods.iter().enumerate() {
            let pts = (0..t.len())
                .filter(|&j| n[j] == *rods_n)
                .map(|j| (gamma[j], ratio[j]))
                .collect();
            plot.series.push(
                Series::new(format!("n = {rods_n}"), pts, Style::LinePoints).with_color(palette(k)),
            );
        }
        let (g0, g1) = gamma
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, &g| {
                (a.0.min(g), a.1.max(g))
            });
        plot.series.push(
            Series::new("equal cost", vec![(g0, 1.0), (g1, 1.0)], Style::Dashed)
                .with_color(RGBColor(0, 0, 0)),
        );
        if let (Some(lo), Some(hi), [first, .., last]) = (
            crossings.iter().copied().reduce(f64::min),
            crossings.iter().copied().reduce(f64::max),
            &rods[..],
        ) {
            plot.annotations.push(format!(
                "crossover γ from {lo:.3} to {hi:.3} (×{:.1}) over n = {first}..{last}",
                hi / lo,
            ));
        }
        plot.annotations.push(format!(
            "DOPRI5 beyond {EXPLICIT_BUDGET} s: extrapolated from the time reached"
        ));
        let out = figures::line_plot(&plot, &ctx.stem(fig.id)).map_err(|e| e.to_string())?;
        Ok(ctx.drawn(&out))
    }
}
