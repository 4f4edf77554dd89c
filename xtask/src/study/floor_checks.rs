//! `floor-checks`: the floor against two closed forms (the tests'
//! `floor::` in chain-ode's physics suite check the same): one rod's
//! plastic impact over the contact stiffness at three angles, and a chain
//! laid on a level floor and on slopes below and above the friction
//! angle. The tables and drawing are the library's
//! (`fc_paper_figures::floor_checks`, `plot::floor`).

use fc_paper_figures::{floor_checks, plot};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The rod's angles from the horizontal (rad).
const THETAS: [f64; 3] = [0.05, 0.5, 1.0];
/// The contact stiffnesses.
const STIFFNESSES: [f64; 4] = [1e4, 1e5, 1e6, 1e7];
/// `(slope, friction)`: level, below (tan 0.3 = 0.31 < 0.5) and above
/// (tan 0.6 = 0.68) the friction angle atan 0.5 = 0.464.
const SLOPES: [(f64, f64); 3] = [(0.0, 0.5), (0.3, 0.5), (0.6, 0.5)];
/// The slope runs' end.
const T_END: f64 = 3.0;

pub struct FloorChecks;

impl Make for FloorChecks {
    /// `floor-checks.csv` (one rod) and `floor-checks-slope.csv`.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let pool = ctx.pool()?;
        let (rod, slope) = pool.install(|| {
            Ok::<_, String>((
                floor_checks::impact_csv(&THETAS, &STIFFNESSES)?,
                floor_checks::slope_csv(&SLOPES, T_END)?,
            ))
        })?;
        Ok(vec![
            ctx.write(&format!("{id}.csv"), &rod)?,
            ctx.write(&format!("{id}-slope.csv"), &slope)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::floor::floor_checks)
    }
}
