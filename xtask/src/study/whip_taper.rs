//! `whip-taper`: the tapered whip (`scenes/tapered-whip.toml`, span d = 3
//! released) with its mass per length tapered 1:1 .. 100:1, on the ladder
//! n = 50, 100, 200 refined by the profile; the largest tip speed and its
//! gain over the uniform chain. The table and drawing are the library's
//! (`fc_paper_figures::whip_taper`, `study::plot::whip_taper`); this
//! file keeps the tapers, the ladder and the tolerance. The whip's
//! animation is made beside it.

use fc_paper_figures::{plot, whip_taper};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The tapers run (the first, 1, is the uniform chain).
const TAPERS: [f64; 7] = [1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0];
/// The ladder of n; the last is the reference.
const LADDER: [usize; 3] = [50, 100, 200];
/// The converge logic's tolerance on the largest tip speed.
const TOL: f64 = 0.01;

pub struct WhipTaper;

impl Make for WhipTaper {
    fn animation(&self) -> Option<&'static str> {
        Some("tapered-whip")
    }

    /// `whip-taper.csv`: one row per taper and n.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let base = ctx.scene("tapered-whip", &[] as &[&str])?;
        let rows = ctx
            .pool()?
            .install(|| whip_taper::rows(&base, &TAPERS, &LADDER, TOL))?;
        for r in rows.iter().filter(|r| r.links == LADDER[LADDER.len() - 1]) {
            println!(
                "  {id}: taper {}: max tip speed {:.4} sqrt(gL), gain {:.4}, converged from n = {}",
                r.taper, r.v_max, r.gain, r.converged_links
            );
        }
        Ok(vec![ctx.write(
            &format!("{id}.csv"),
            &whip_taper::csv_text(&rows),
        )?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::whip_taper::whip_taper)
    }
}
