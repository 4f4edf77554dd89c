//! The tapered whip: the largest tip speed of the chain released from the
//! U of span d = 3 against the taper of its mass per length
//! (`chain.taper`, base to tip), on a ladder of `n` refined by the profile
//! ([`fc_study::converge::refined_scene`]: total mass, length, taper and
//! bending viscosity `eta = r l` held fixed). For each taper the converge
//! logic ([`converge::smallest_adequate`] on `d(vmax)`) says which `n` is
//! converged. The figure `whip-taper` draws its table.

use std::fmt::Write as _;

use rayon::prelude::*;

use fc_csv::format::num;
use fc_scene::scene::Scene;
use fc_study::converge::{self, Deviation, Level};

/// One run of the ladder.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The mass per length at the pivot over that at the tip.
    pub taper: f64,
    pub links: usize,
    /// The largest tip speed over `sqrt(g L)`.
    pub v_max: f64,
    /// When it is reached, over `sqrt(L / g)`.
    pub t_max: f64,
    /// `v_max` over the uniform chain's (`taper = 1`) at the same `n`.
    pub gain: f64,
    /// `|v_max / v_max(reference n) - 1|` (0 at the reference, the ladder's
    /// finest `n`).
    pub d_vmax: f64,
    /// The smallest adequate `n` of this taper's ladder at `tol`
    /// ([`converge::smallest_adequate`] on `d(vmax)`); the reference `n`
    /// when none below it is.
    pub converged_links: usize,
}

/// Runs `base` (a scene with a `chain.taper` key) for every taper and
/// every `n` of `ladder` (sorted ascending, at least two; the last the
/// reference; the first taper is 1, the uniform chain the gain is over;
/// in parallel), and finds each taper's converged `n` at `tol`
/// in `d(vmax)`.
pub fn rows(base: &Scene, tapers: &[f64], ladder: &[usize], tol: f64) -> Result<Vec<Row>, String> {
    if tapers.first() != Some(&1.0) || ladder.len() < 2 {
        return Err("whip-taper: the tapers start with 1 (the uniform chain) and the ladder has two n or more".into());
    }
    let jobs: Vec<(f64, usize)> = tapers
        .iter()
        .flat_map(|&k| ladder.iter().map(move |&n| (k, n)))
        .collect();
    let levels: Vec<Level> = jobs
        .par_iter()
        .map(|&(k, n)| {
            let scene = base
                .with_value("chain.taper", toml::Value::Float(k))
                .map_err(|e| e.to_string())?;
            let level = converge::run_level(&scene, n, None, None).map_err(|e| e.to_string())?;
            if level.summary.status != "ok" {
                return Err(format!(
                    "taper {k}, n = {n}: status {}",
                    level.summary.status
                ));
            }
            Ok(level)
        })
        .collect::<Result<_, String>>()?;
    let per = ladder.len();
    let mut out = Vec::with_capacity(jobs.len());
    for (t, &k) in tapers.iter().enumerate() {
        let mine = &levels[t * per..(t + 1) * per];
        let reference = &mine[per - 1];
        let converged = converge::smallest_adequate(mine, |d| d.tip_speed_max < tol)
            .unwrap_or(reference.links());
        for (j, level) in mine.iter().enumerate() {
            let chain = &level.chain;
            let (l, g) = (chain.length(), chain.gravity());
            let uniform = &levels[j].summary.tip_speed_max;
            out.push(Row {
                taper: k,
                links: level.links(),
                v_max: level.summary.tip_speed_max / (g * l).sqrt(),
                t_max: level.summary.t_tip_speed_max / (l / g).sqrt(),
                gain: level.summary.tip_speed_max / uniform,
                d_vmax: Deviation::between(level, reference).tip_speed_max,
                converged_links: converged,
            });
        }
    }
    Ok(out)
}

/// The CSV of [`rows`].
pub fn csv_text(rows: &[Row]) -> String {
    let mut s = String::from(
        "taper,links,v_max_over_sqrt_gL,t_max_over_sqrt_L_over_g,gain,d_vmax,converged_links\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{}",
            num(r.taper),
            r.links,
            num(r.v_max),
            num(r.t_max),
            num(r.gain),
            num(r.d_vmax),
            r.converged_links
        );
    }
    s
}
