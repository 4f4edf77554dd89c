//! `cayley-scale`: Cayley's scale as an ensemble (`scenes/cayley-scale.toml`,
//! a chain hanging straight down onto a plastic floor, let go at the top),
//! each ensemble 16 starts whose rod angles are perturbed by up to 1e-3 rad:
//! the mean reading over the ideal's against time on the ladder n = 10, 20,
//! 40, 80, and at mid-fall against n, the floor's stiffness, the start's
//! tilt and the perturbation's size. The tables and drawing are the
//! library's (`fc_paper_figures::cayley`, `plot::cayley`); this file keeps
//! the cases.

use chain_ode::Method;
use fc_paper_figures::{cayley, plot};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// Members of every ensemble.
const MEMBERS: usize = 16;
/// The method and tolerance of every member (the cheapest on this scene,
/// `docs/model.md`, "Speed on Cayley's scene").
const METHOD: Method = Method::Dop853;
const RTOL: f64 = 1e-6;

/// `(links, stiffness, damping, tilt, spread)`: the ladder in n first
/// (k = 1e5 with its plastic damping, tilt 0.2 rad, spread 1e-3 rad), then
/// at n = 40 the other floors (damping with the square root of the
/// stiffness, the same damping ratio), the other tilts and a perturbation a
/// thousand times smaller.
const CASES: [(usize, f64, f64, f64, f64); 9] = [
    (10, 1e5, 100.0, 0.2, 1e-3),
    (20, 1e5, 100.0, 0.2, 1e-3),
    (40, 1e5, 100.0, 0.2, 1e-3),
    (80, 1e5, 100.0, 0.2, 1e-3),
    (40, 1e4, 30.0, 0.2, 1e-3),
    (40, 1e6, 300.0, 0.2, 1e-3),
    (40, 1e5, 100.0, 0.02, 1e-3),
    (40, 1e5, 100.0, 0.5, 1e-3),
    (40, 1e5, 100.0, 0.2, 1e-6),
];

pub struct CayleyScale;

impl Make for CayleyScale {
    /// `cayley-scale.csv` (every ensemble at every time) and
    /// `cayley-scale-midfall.csv` (at mid-fall).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let base = ctx.scene("cayley-scale", &[] as &[&str])?;
        let pool = ctx.pool()?;
        let mut ensembles = Vec::with_capacity(CASES.len());
        for (links, stiffness, damping, tilt, spread) in CASES {
            let case = cayley::Case {
                links,
                stiffness,
                damping,
                tilt,
                spread,
                members: MEMBERS,
                method: METHOD,
                rtol: RTOL,
            };
            let e = pool.install(|| cayley::run(&base, &case))?;
            if let Some((j, why)) = e.failed.first() {
                return Err(format!(
                    "{id}: n = {links}, k = {stiffness:e}: member {j} {why}"
                ));
            }
            let p = e.midfall();
            println!(
                "  {id}: n = {links}, k = {stiffness:e}, tilt {tilt}, spread {spread:e}: \
                 mid-fall reading {:.3} +- {:.3} (sem), momentum {:.3}, top {:.4}",
                p.reading.mean, p.reading.sem, p.momentum.mean, p.top.mean
            );
            ensembles.push(e);
        }
        Ok(vec![
            ctx.write(&format!("{id}.csv"), &cayley::series_csv(&ensembles))?,
            ctx.write(
                &format!("{id}-midfall.csv"),
                &cayley::midfall_csv(&ensembles),
            )?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::cayley::cayley)
    }
}
