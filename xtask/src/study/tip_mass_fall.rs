//! `tip-mass-fall`: the folded chain with a point mass `M` at its free end
//! (n = 400, r = 0) against the energy-conserving law, for `M / m_c` from
//! 0.1 to 10: the fall time over free fall and the tip speed at the end of
//! the fall. The runs and the table are the library's
//! (`fc_paper_figures::tip_mass`), the drawing `study::plot::tip_mass`;
//! this file keeps the choice of ratios.

use fc_paper_figures::{plot, tip_mass};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The mass ratios `k = M / m_c` run.
const RATIOS: [f64; 7] = [0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0];
/// Rods: the n = 400.
const LINKS: usize = 400;

pub struct TipMassFall;

impl Make for TipMassFall {
    /// `tip-mass-fall.csv` (one run per ratio against the law) and
    /// `tip-mass-fall-law.csv` (the law's curves).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let rows = ctx.pool()?.install(|| tip_mass::rows(&RATIOS, LINKS))?;
        for r in &rows {
            println!(
                "  {id}: M/m_c = {}: fall time {:+.3}% of the law's",
                r.ratio,
                100.0 * (r.t_fall / r.t_law - 1.0)
            );
        }
        Ok(vec![
            ctx.write(&format!("{id}.csv"), &tip_mass::csv_text(&rows))?,
            ctx.write(
                &format!("{id}-law.csv"),
                &tip_mass::law_csv(0.05, 20.0, 200),
            )?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, |r, s| plot::tip_mass::fall(r, s, LINKS))
    }
}
