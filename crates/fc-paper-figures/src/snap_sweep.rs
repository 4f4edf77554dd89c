//! The snap against `n`: [`snap::measure`] of a few scenes, each refined
//! at fixed total mass and bending viscosity (`converge::refined_scene`,
//! the continuum convention) to several numbers of rods, with rigid links
//! and with elastic ones ([`Case`]), one CSV row per run ([`snap::snap_row`]).

use rayon::prelude::*;

use fc_scene::scene::Scene;
use fc_study::converge::refined_scene;
use fc_study::snap::{self, Options, Snap, SNAP_HEADER};

/// One case of links: its label, `EA` (`None`: rigid links), `EI`, whether
/// the joint friction is kept (else `chain.damping = 0`), and the largest
/// number of rods it runs to.
pub type Case = (&'static str, Option<f64>, f64, bool, usize);

/// A scene of the sweep: its name, the scene, and the end time of its runs.
pub type SweepScene<'a> = (&'a str, &'a Scene, f64);

/// One line on a finished run, for progress.
pub fn note(scene: &str, variant: &str, n: usize, r: &Snap) -> String {
    format!(
        "{scene} {variant} n = {n}: peak {:.3} Mg at {:.4}, impulse {:.4}, v_max {:.3}, \
         {} steps, {:.1} s",
        r.peak_force, r.t_peak_force, r.impulse, r.tip_speed_max, r.steps, r.wall_seconds
    )
}

/// `snap_row`s ([`SNAP_HEADER`]) of every scene, case and `n` of `links`
/// up to the case's largest, in that order, each run with DOPRI5 at rtol
/// 1e-8 to its scene's end time ([`Options`]'s defaults). An elastic case
/// sets the axial viscosity `eta`, kept under refinement. The runs go on
/// the current rayon pool, the largest `n` first so that the pool ends
/// together; `tick` is called with [`note`] after each.
pub fn sweep(
    scenes: &[SweepScene],
    cases: &[Case],
    links: &[usize],
    eta: f64,
    tick: &(dyn Fn(String) + Sync),
) -> Result<String, String> {
    let mut jobs = vec![];
    for (sc, &(_, _, t_end)) in scenes.iter().enumerate() {
        for (va, &(_, _, _, _, top)) in cases.iter().enumerate() {
            for &n in links.iter().filter(|&&n| n <= top) {
                jobs.push((sc, va, n, t_end));
            }
        }
    }
    jobs.sort_by_key(|j| std::cmp::Reverse(j.2));
    let mut rows = jobs
        .par_iter()
        .map(|&(sc, va, n, t_end)| {
            let (scene, base, _) = scenes[sc];
            let (variant, ea, ei, friction, _) = cases[va];
            let err = |e: fc_scene::Error| format!("{scene} {variant} n = {n}: {e}");
            let mut set = vec![format!("chain.bending_stiffness={ei}")];
            if let Some(ea) = ea {
                set.push(format!("chain.axial_stiffness={ea:e}"));
                set.push(format!("chain.axial_damping={eta}"));
            }
            if !friction {
                set.push("chain.damping=0.0".into());
            }
            let s = base
                .with_overrides(&set)
                .map_err(|e| format!("{scene}: {e}"))?;
            let s = refined_scene(&s, n).map_err(err)?;
            let opts = Options {
                t_end: Some(t_end),
                ..Options::default()
            };
            let (r, _) = snap::measure(&s, &opts).map_err(err)?;
            tick(note(scene, variant, n, &r));
            Ok(((sc, va, n), snap::snap_row(variant, &r)))
        })
        .collect::<Result<Vec<_>, String>>()?;
    // Back in the order of the scenes, cases and n.
    rows.sort_by_key(|r| r.0);
    let mut csv = SNAP_HEADER.to_string();
    for (_, row) in rows {
        csv.push_str(&row);
    }
    Ok(csv)
}

/// A [`sweep`]'s table without its last column, the runs' wall times
/// (`wall_seconds`): the rows that reproduce to the byte.
pub fn untimed(csv: &str) -> String {
    csv.lines()
        .map(|line| line.rsplit_once(',').map_or(line, |(kept, _)| kept))
        .fold(String::new(), |mut out, line| {
            out.push_str(line);
            out.push('\n');
            out
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_untimed_table_drops_the_wall_times_alone() {
        let csv = format!(
            "{SNAP_HEADER}span-d3,EA 1e6,100,10,1e6,1.5,0,0.001,ok,10.8,2.76,5.02,2.77,0.48,2.57,2.97,0.16,900,5400,4.012e0\n"
        );
        let t = untimed(&csv);
        let mut lines = t.lines();
        assert!(lines.next().unwrap().ends_with(",steps,rhs_evals"));
        assert_eq!(
            lines.next(),
            Some("span-d3,EA 1e6,100,10,1e6,1.5,0,0.001,ok,10.8,2.76,5.02,2.77,0.48,2.57,2.97,0.16,900,5400")
        );
        assert_eq!(lines.next(), None);
    }
}
