//! `cayley-scale` and `cayley-top`: Cayley's scale as an ensemble
//! (`scenes/cayley-scale.toml`, a chain hanging straight down onto a
//! floor, let go at the top), each ensemble 16 starts whose rod angles are
//! perturbed by up to 1e-3 rad. `cayley-scale` draws the mean reading over
//! the ideal's against time on the ladder n = 10, 20, 40, 80 and at
//! mid-fall against n, the floor's stiffness, the start's tilt and the
//! perturbation's size; `cayley-top` the top's fall over the free fall's
//! on the ladder and, at n = 40, over the contact law (plastic, elastic),
//! the joints' friction and the floor's. Both figures draw the one set of
//! ensembles, run once ([`ensembles`]). The tables and drawings are the
//! library's (`fc_paper_figures::cayley`, `plot::cayley`); this file keeps
//! the cases.

use std::sync::OnceLock;

use chain_ode::Method;
use fc_paper_figures::cayley::{self, Ensemble};
use fc_paper_figures::plot;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// Members of every ensemble.
const MEMBERS: usize = 16;
/// The method and tolerance of every member (the cheapest on this scene
/// at matched statistical accuracy, `docs/model.md`, "Speed on Cayley's
/// scene, at matched (statistical) accuracy").
const METHOD: Method = Method::Dop853;
const RTOL: f64 = 1e-6;

/// `(links, stiffness, damping, floor friction, joint friction, tilt,
/// spread)`: the ladder in n first (k = 1e5 with its plastic damping,
/// tilt 0.2 rad, spread 1e-3 rad), then at n = 40 the other floors
/// (damping with the square root of the stiffness, the same damping
/// ratio), the other tilts, a perturbation a thousand times smaller, an
/// elastic floor, the joints' friction (r / (m l^2) = 0.64 and 6.4) and
/// the floor's.
const CASES: [(usize, f64, f64, f64, f64, f64, f64); 13] = [
    (10, 1e5, 100.0, 0.0, 0.0, 0.2, 1e-3),
    (20, 1e5, 100.0, 0.0, 0.0, 0.2, 1e-3),
    (40, 1e5, 100.0, 0.0, 0.0, 0.2, 1e-3),
    (80, 1e5, 100.0, 0.0, 0.0, 0.2, 1e-3),
    (40, 1e4, 30.0, 0.0, 0.0, 0.2, 1e-3),
    (40, 1e6, 300.0, 0.0, 0.0, 0.2, 1e-3),
    (40, 1e5, 100.0, 0.0, 0.0, 0.02, 1e-3),
    (40, 1e5, 100.0, 0.0, 0.0, 0.5, 1e-3),
    (40, 1e5, 100.0, 0.0, 0.0, 0.2, 1e-6),
    (40, 1e5, 0.0, 0.0, 0.0, 0.2, 1e-3),
    (40, 1e5, 100.0, 0.0, 1e-5, 0.2, 1e-3),
    (40, 1e5, 100.0, 0.0, 1e-4, 0.2, 1e-3),
    (40, 1e5, 100.0, 0.3, 0.0, 0.2, 1e-3),
];

/// Every case's ensemble, run once for both figures (the first figure to
/// ask runs them; a failed member is an error).
fn ensembles(ctx: &Ctx) -> Result<&'static [Ensemble], String> {
    static DONE: OnceLock<Result<Vec<Ensemble>, String>> = OnceLock::new();
    let done = DONE.get_or_init(|| {
        let base = ctx.scene("cayley-scale", &[] as &[&str])?;
        let cases: Vec<cayley::Case> = (CASES.iter())
            .map(
                |&(links, stiffness, damping, friction, joint_friction, tilt, spread)| {
                    cayley::Case {
                        links,
                        stiffness,
                        damping,
                        friction,
                        joint_friction,
                        tilt,
                        spread,
                        members: MEMBERS,
                        method: METHOD,
                        rtol: RTOL,
                    }
                },
            )
            .collect();
        // Every member of every case in one parallel loop.
        let all = ctx.pool()?.install(|| cayley::run_all(&base, &cases))?;
        for e in &all {
            let c = &e.case;
            let (links, stiffness) = (c.links, c.stiffness);
            if let Some((j, why)) = e.failed.first() {
                return Err(format!(
                    "cayley: n = {links}, k = {stiffness:e}: member {j} {why}"
                ));
            }
            let p = e.midfall();
            println!(
                "  cayley: n = {links}, k = {stiffness:e}, c = {}, mu_f = {}, r = {:e}, tilt {}, \
                 spread {:e}: mid-fall reading {:.3} +- {:.3} (sem), momentum {:.3}, top {:.4}",
                c.damping,
                c.friction,
                c.joint_friction,
                c.tilt,
                c.spread,
                p.reading.mean,
                p.reading.sem,
                p.momentum.mean,
                p.top.mean
            );
        }
        Ok(all)
    });
    done.as_deref().map_err(Clone::clone)
}

pub struct CayleyScale;

impl Make for CayleyScale {
    /// `cayley-scale.csv` (every ensemble at every time) and
    /// `cayley-scale-midfall.csv` (at mid-fall).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let all = ensembles(ctx)?;
        Ok(vec![
            ctx.write(&format!("{id}.csv"), &cayley::series_csv(all))?,
            ctx.write(&format!("{id}-midfall.csv"), &cayley::midfall_csv(all))?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::cayley::cayley)
    }
}

pub struct CayleyTop;

impl Make for CayleyTop {
    /// `cayley-top.csv`: the top's fall over the free fall's, every
    /// ensemble at every time.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let all = ensembles(ctx)?;
        Ok(vec![ctx.write(
            &format!("{}.csv", fig.id),
            &cayley::top_csv(all),
        )?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::cayley::cayley_top)
    }
}
