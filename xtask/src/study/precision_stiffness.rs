//! `stiffness`: where the implicit method pays, at matched accuracy
//! (`fc_paper_figures::stiffness` says how). The grid: for each `n`, the
//! damping rates a quarter decade apart (`1, 1.8, 3.2, 5.6` times a power
//! of ten: `10^(j/4)` to two digits) for `j` in its range, placed around the
//! crossover; the cells past DOPRI5's budget are not run.
//!
//! All of it is wall times: computed only by `--timings`, into
//! `stiffness-timing.csv` and `stiffness-crossover-timing.csv`.

use fc_paper_figures::plot;
use fc_paper_figures::stiffness;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// Rods, and the range of `j` in `gamma = 10^(j/4)` (1/time, to two digits)
/// for each.
const GRID: [(usize, i32, i32); 4] = [(25, 0, 12), (100, 0, 12), (400, 2, 10), (1600, 6, 9)];

/// `10^(j/4)` to two significant digits: 1, 1.8, 3.2, 5.6, 10, 18, ...
/// (the nearest `f64` to the decimal, so that the CSV prints `1.8e1`).
fn quarter_decade(j: i32) -> f64 {
    const MANTISSA: [&str; 4] = ["1", "1.8", "3.2", "5.6"];
    let (decade, k) = (j.div_euclid(4), j.rem_euclid(4));
    let text = format!("{}e{decade}", MANTISSA[k as usize]);
    text.parse().unwrap_or(f64::NAN)
}

pub struct Stiffness;

impl Make for Stiffness {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let grid: Vec<(usize, Vec<f64>)> = GRID
            .iter()
            .map(|&(n, j0, j1)| (n, (j0..=j1).map(quarter_decade).collect()))
            .collect();
        let (cells, cross) = stiffness::tables(&grid)?;
        Ok(vec![
            ctx.write(&format!("{}-timing.csv", fig.id), &cells)?,
            ctx.write(&format!("{}-crossover-timing.csv", fig.id), &cross)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::stiffness::stiffness)
    }
}
