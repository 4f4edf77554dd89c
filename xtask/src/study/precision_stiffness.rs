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

use falling_chain::study::plot;
use falling_chain::study::stiffness;

use crate::ctx::Ctx;
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
        ctx.draw(fig, plot::timing::stiffness)
    }
}
