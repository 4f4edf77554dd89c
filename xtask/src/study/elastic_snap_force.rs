//! `snap-force`: the snap's peak support force and impulse against `n`
//! (`falling_chain::study::snap`), for span d = 3, span d = 1 and the
//! folded chain, each refined from its n = 50 scene at fixed total mass
//! `M = 10` and bending viscosity (`converge::refined_scene`: the continuum
//! convention), with rigid links and with elastic links: `EA = 1e4` to
//! n = 400, with `EI = 0.1` and without joint friction to n = 200, and
//! `EA = 1e5` to n = 100 (fewer n for the machine's time). The axial
//! viscosity `eta = 1.549` (5% damping of a joint at n = 50) is kept under
//! refinement too. Every run DOPRI5 at rtol 1e-8 (to t = 3.5; the folded
//! chain to 4.157), samples every 1e-3, impulse window ±0.2 around the peak.
//!
//! The sweep took 161 s on two shared cores (the folded chain at n = 400,
//! `EA = 1e4`: 151 130 steps and 34 s for one run), so it is computed only
//! by `--timings`; its file carries each run's wall time too. The drawing
//! is `falling_chain::study::plot::elastic::snap_force`.

use falling_chain::converge::refined_scene;
use falling_chain::study::plot;
use falling_chain::study::snap::{self, Options, SNAP_HEADER};
use rayon::prelude::*;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The scenes, as `(scene, label, end time)`: the spans snap before
/// t = 3.1 at every n; the folded chain's fold, whose friction grows with n
/// at fixed bending viscosity, is slower at large n (at n = 400 it has not
/// snapped by t = 3.5), so it runs to its scene's end, 4.157.
const SCENES: &[(&str, &str, f64)] = &[
    ("span-d3", "d = 3", 3.5),
    ("span-d1", "d = 1", 3.5),
    ("folded", "folded", 4.157),
];

/// The numbers of rods.
const LINKS: [usize; 5] = [25, 50, 100, 200, 400];

/// `eta` for 5% damping of one joint at n = 50, `EA = 1e4` (`m = 0.2`,
/// `l = 0.12`): `2 * 0.05 * sqrt(1e4 * 0.2 * 0.12)`.
const ETA: f64 = 1.549_193_338_482_966_8;

/// The cases: `(label, EA, EI, friction kept, largest n)`.
const VARIANTS: &[(&str, Option<f64>, f64, bool, usize)] = &[
    ("rigid", None, 0.0, true, 400),
    ("EA 1e4", Some(1e4), 0.0, true, 400),
    ("EA 1e4 EI 0.1", Some(1e4), 0.1, true, 200),
    ("EA 1e4 r 0", Some(1e4), 0.0, false, 200),
    ("EA 1e5", Some(1e5), 0.0, true, 100),
];

pub struct SnapForce;

impl Make for SnapForce {
    /// `snap-force-timing.csv`: one row per scene, case and n.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let mut jobs = vec![];
        for &(scene, _, _) in SCENES {
            for &(variant, ea, ei, friction, top) in VARIANTS {
                for n in LINKS.into_iter().filter(|&n| n <= top) {
                    jobs.push((scene, variant, ea, ei, friction, n));
                }
            }
        }
        // The largest first, so that the pool ends together.
        jobs.sort_by_key(|j| std::cmp::Reverse(j.5));
        let rows: Vec<Result<(usize, String), String>> = ctx.pool()?.install(|| {
            jobs.par_iter()
                .enumerate()
                .map(|(k, &(scene, variant, ea, ei, friction, n))| {
                    let err = |e: falling_chain::Error| format!("{scene} {variant} n = {n}: {e}");
                    let mut set = vec![format!("chain.bending_stiffness={ei}")];
                    if let Some(ea) = ea {
                        set.push(format!("chain.axial_stiffness={ea:e}"));
                        set.push(format!("chain.axial_damping={ETA}"));
                    }
                    if !friction {
                        set.push("chain.damping=0.0".into());
                    }
                    let s = ctx.scene(scene, &set)?;
                    let s = refined_scene(&s, n).map_err(err)?;
                    let t_end = SCENES.iter().find(|x| x.0 == scene).map(|x| x.2);
                    let opts = Options {
                        t_end,
                        ..Options::default()
                    };
                    let (r, _) = snap::measure(&s, &opts).map_err(err)?;
                    println!(
                        "  {}: {scene} {variant} n = {n}: peak {:.3} Mg at {:.4}, impulse {:.4}, \
                         v_max {:.3}, {} steps, {:.1} s",
                        fig.id,
                        r.peak_force,
                        r.t_peak_force,
                        r.impulse,
                        r.tip_speed_max,
                        r.steps,
                        r.wall_seconds
                    );
                    Ok((k, snap::snap_row(variant, &r)))
                })
                .collect()
        });
        let mut rows = rows.into_iter().collect::<Result<Vec<_>, String>>()?;
        // Back in the order of the scenes, cases and n.
        rows.sort_by_key(|r| {
            let j = jobs[r.0];
            let sc = SCENES.iter().position(|s| s.0 == j.0);
            let va = VARIANTS.iter().position(|v| v.0 == j.1);
            (sc, va, j.5)
        });
        let mut csv = SNAP_HEADER.to_string();
        for (_, row) in rows {
            csv.push_str(&row);
        }
        Ok(vec![ctx.write(&format!("{}-timing.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes: Vec<(&str, &str)> = SCENES.iter().map(|&(s, l, _)| (s, l)).collect();
        ctx.draw(fig, |r, s| plot::elastic::snap_force(r, s, &scenes))
    }
}
