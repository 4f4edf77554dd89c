//! `floor-span-d3`: the report's U of span d = 3 (n = 50) released over a
//! floor (`scenes/span-d3-floor.toml`), drawn at a few times with the
//! floor, and its released end's speed beside the same U without a floor
//! (`scenes/span-d3.toml`, the whip). Both are the shared scene runs; the
//! tables and drawing are the library's (`fc_paper_figures::floor_u`,
//! `plot::floor`).

use fc_paper_figures::{floor_u, plot};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The snapshots' times (the scene's clock): the start, before and after
/// the bottom lands at t = 1.444, and the report's t_end.
const TIMES: [f64; 9] = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.157];

pub struct FloorSpanD3;

impl Make for FloorSpanD3 {
    fn scenes(&self) -> Vec<&'static str> {
        vec!["span-d3-floor", "span-d3"]
    }

    /// `floor-span-d3.csv` (the snapshots and the floor's line) and
    /// `floor-span-d3-series.csv` (both runs' tip speed and floor force).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let floor = ctx.run("span-d3-floor")?;
        let plain = ctx.run("span-d3")?;
        Ok(vec![
            ctx.write(
                &format!("{id}.csv"),
                &floor_u::snapshots_csv(&floor.traj, &TIMES)?,
            )?,
            ctx.write(
                &format!("{id}-series.csv"),
                &floor_u::series_csv(&[("span-d3", &plain.traj), ("span-d3-floor", &floor.traj)]),
            )?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::floor::floor_span_d3)
    }
}
