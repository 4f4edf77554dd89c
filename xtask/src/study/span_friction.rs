//! `span-friction`: the sensitivity of the maximum tip speed to the joint
//! friction `r` for the span scenes, at their own n = 50 (DOPRI5 at rtol
//! 1e-10) and on the refined chain of 200 rods with the continuum held
//! fixed (`auto` at rtol 1e-8), over `r` from 0 to 20 times the scenes'
//! 5e-4 (`fc_paper_figures::friction`). Deterministic:
//! `span-friction.csv` (every run) and `span-friction-summary.csv` (per
//! scene and n: the change from r = 0 to the scenes' r, across the report's
//! range 1e-4 .. 1e-3, and the log-log slope at the scenes' r).

use fc_paper_figures::friction::{self, HEADER, SUMMARY_HEADER};
use fc_paper_figures::plot;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The span scenes.
const SCENES: [&str; 4] = ["span-d1", "span-d3", "span-d5", "span-d6"];
/// Joint friction `r` at n = 50 (the scenes' units): 0, then 1e-5 to 1e-2,
/// bracketing the report's range 1e-4 .. 1e-3 and the scenes' 5e-4.
const RS: [f64; 9] = [0.0, 1e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3, 1e-2];
/// The refined chain's rods.
const FINE: usize = 200;

pub struct SpanFriction;

impl Make for SpanFriction {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let (mut rows, mut sums) = (HEADER.to_string(), SUMMARY_HEADER.to_string());
        for name in SCENES {
            let scene = ctx.scene::<&str>(name, &[])?;
            for line in friction::lines(&scene, &RS, Some(FINE), ctx.jobs)? {
                rows.push_str(&friction::table(std::slice::from_ref(&line)));
                sums.push_str(&friction::summary(&line, (1e-4, 1e-3)));
            }
        }
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &rows)?,
            ctx.write(&format!("{}-summary.csv", fig.id), &sums)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::friction::friction)
    }
}
