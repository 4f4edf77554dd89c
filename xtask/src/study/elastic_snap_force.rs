//! `snap-force`: the snap's peak support force and impulse against `n`
//! (`fc_paper_figures::snap_sweep`), for span d = 3, span d = 1 and the
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
//! by `--timings`; its file carries each run's wall time too. The stiffer
//! links of span d = 3, `EA = 1e6` and `1e7` to n = 100 (the rigid limit
//! of its peak), are run by every `cargo xtask figures` into
//! `snap-force-stiff.csv`, without wall times. The drawing is
//! `fc_paper_figures::plot::elastic::snap_force`.

use fc_paper_figures::plot;
use fc_paper_figures::snap_sweep::{self, Case};

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
const VARIANTS: &[Case] = &[
    ("rigid", None, 0.0, true, 400),
    ("EA 1e4", Some(1e4), 0.0, true, 400),
    ("EA 1e4 EI 0.1", Some(1e4), 0.1, true, 200),
    ("EA 1e4 r 0", Some(1e4), 0.0, false, 200),
    ("EA 1e5", Some(1e5), 0.0, true, 100),
];

/// The stiffer links, on span d = 3 alone: `EA = 1e6` and `1e7` to n = 100
/// (at n = 100, `EA = 1e7`: about 11 s), where the elastic peak meets the
/// rigid one.
const STIFF: &[Case] = &[
    ("EA 1e6", Some(1e6), 0.0, true, 100),
    ("EA 1e7", Some(1e7), 0.0, true, 100),
];

pub struct SnapForce;

impl Make for SnapForce {
    /// `snap-force-stiff.csv`: span d = 3 with the [`STIFF`] links, one
    /// row per case and n, no wall times; with `--timings`,
    /// `snap-force-timing.csv`: one row per scene, case and n.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes = (SCENES.iter())
            .map(|&(s, _, t_end)| ctx.scene::<&str>(s, &[]).map(|scene| (s, scene, t_end)))
            .collect::<Result<Vec<_>, String>>()?;
        let scenes: Vec<_> = scenes.iter().map(|(s, sc, t)| (*s, sc, *t)).collect();
        let tick = |note: String| println!("  {}: {note}", fig.id);
        let pool = ctx.pool()?;
        let stiff = pool.install(|| snap_sweep::sweep(&scenes[..1], STIFF, &LINKS, ETA, &tick))?;
        let mut files = vec![ctx.write(
            &format!("{}-stiff.csv", fig.id),
            &snap_sweep::untimed(&stiff),
        )?];
        if ctx.timings {
            let csv = pool.install(|| snap_sweep::sweep(&scenes, VARIANTS, &LINKS, ETA, &tick))?;
            files.push(ctx.write(&format!("{}-timing.csv", fig.id), &csv)?);
        }
        Ok(files)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes: Vec<(&str, &str)> = SCENES.iter().map(|&(s, l, _)| (s, l)).collect();
        ctx.draw(fig, |r, s| plot::elastic::snap_force(r, s, &scenes))
    }
}
