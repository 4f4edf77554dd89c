//! `snap-tension`: the tension along the chain around the snap, the wave
//! running up from the tip (`fc_study::snap`). Span d = 3
//! refined to n = 100 at fixed total mass `M = 10` (the continuum
//! convention), elastic links `EA = 1e4`, `eta = 1.549`; DOPRI5 at rtol
//! 1e-8, samples every 1e-3. The profiles are at the time of the tip's
//! maximum speed `t_v` (the tip is arrested), at four equal steps from it
//! to the peak of the support force `t_p`, and at `t_p + 0.05`; beside
//! them, the support force against time (`study::snap_tension` makes the
//! tables, `study::plot::elastic::snap_tension` the drawing).

use fc_paper_figures::{plot, snap_tension};
use fc_study::converge::refined_scene;
use fc_study::snap::{self, Options};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

const LINKS: usize = 100;
/// `EA` (force units).
const EA: f64 = 1e4;
/// As `snap-force`'s: 5% damping of a joint at n = 50.
const SET: [&str; 2] = [
    "chain.axial_stiffness=1e4",
    "chain.axial_damping=1.5491933384829668",
];

pub struct SnapTension;

impl Make for SnapTension {
    /// `snap-tension.csv` (tension at every joint at six times),
    /// `snap-tension-force.csv` (the support force against time around the
    /// snap) and `snap-tension-summary.csv` (the run's peak and times).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scene =
            refined_scene(&ctx.scene("span-d3", &SET)?, LINKS).map_err(|e| e.to_string())?;
        let opts = Options {
            t_end: Some(3.2),
            ..Options::default()
        };
        let (r, traj) = snap::measure(&scene, &opts).map_err(|e| e.to_string())?;
        if r.status != "ok" {
            return Err(format!("{}: the run ended {}", fig.id, r.status));
        }
        let (csv, force, summary) = snap_tension::tables(&r, &traj, LINKS, EA);
        println!(
            "  {}: t_v = {:.4}, t_p = {:.4}, peak {:.3} M g",
            fig.id, r.t_tip_speed_max, r.t_peak_force, r.peak_force
        );
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &csv)?,
            ctx.write(&format!("{}-force.csv", fig.id), &force)?,
            ctx.write(&format!("{}-summary.csv", fig.id), &summary)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::elastic::snap_tension)
    }
}
