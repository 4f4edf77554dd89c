//! The folded chain with a point mass at its free end against the
//! energy-conserving law (`chain_ode::tip_mass_law`, derived in
//! `docs/model.md`, "A tip mass"): for each mass ratio `k = M / m_c`, the
//! fall time and the tip speed at the end of the fall of one run, beside
//! the law's. The figure `tip-mass-fall` draws its table.

use std::fmt::Write as _;

use chain_ode::analysis::{first_time_below, tip_track};
use chain_ode::{solve, tip_mass_law, Chain, ChainParams, Method, SolveOptions, Start, Vec2};
use rayon::prelude::*;

use fc_csv::format::num;

/// One mass ratio's run against the law.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// `k = M / m_c`.
    pub ratio: f64,
    pub links: usize,
    /// The fall distance at which the fall is timed: `0.99 (L - l)` (the
    /// free end starts one rod below the pivot; the discrete chain never
    /// straightens exactly), over `L`.
    pub xi: f64,
    /// The run's time to fall `xi L`, over the free-fall time `sqrt(2 L / g)`.
    pub t_fall: f64,
    /// The law's, in the same unit.
    pub t_law: f64,
    /// The run's tip speed there, over `sqrt(g L)` (linear between samples).
    pub v_fall: f64,
    /// The law's speed there, in the same unit.
    pub v_law: f64,
    /// The law's speed at full extension, `sqrt(2 (1 + 1/(4k)))`.
    pub v_final: f64,
}

/// The tip speed when the tip first passes `level`, linear between samples.
fn speed_below(track: &[(f64, Vec2, Vec2)], level: f64) -> Option<f64> {
    track.windows(2).find_map(|w| {
        let ((_, a, va), (_, b, vb)) = (w[0], w[1]);
        (a[1] >= level && b[1] < level).then(|| {
            let s = (a[1] - level) / (a[1] - b[1]);
            let (sa, sb) = (va[0].hypot(va[1]), vb[0].hypot(vb[1]));
            sa + s * (sb - sa)
        })
    })
}

/// The report's chain (`L = 6`, `g = 1`, total mass `m_c = 10`, `r = 0`)
/// of `links` rods, folded, with `M = k m_c` at its end, run by DOPRI5 at
/// rtol `1e-9` to 5% past the law's fall time, for each `k` (in parallel).
pub fn rows(ratios: &[f64], links: usize) -> Result<Vec<Row>, String> {
    ratios
        .par_iter()
        .map(|&k| {
            let m_c = 10.0;
            let chain = Chain::new(ChainParams {
                links,
                mass: m_c / links as f64,
                tip_mass: k * m_c,
                ..ChainParams::default()
            })
            .map_err(|e| e.to_string())?;
            let start = Start::Folded {
                p0: [0.0, 0.0],
                down: None,
            }
            .state(&chain)
            .map_err(|e| e.to_string())?;
            let (length, g) = (chain.length(), chain.gravity());
            let tau = (length / g).sqrt();
            let options = SolveOptions {
                t_end: tip_mass_law::time(1.0, k) * tau * 1.05,
                rtol: 1e-9,
                atol: 1e-11,
                output_dt: Some(1e-3),
                ..Default::default()
            };
            let traj =
                solve(&chain, &start, Method::Dopri5, &options).map_err(|e| e.to_string())?;
            if !traj.status.is_ok() {
                return Err(format!("tip mass k = {k}: status {}", traj.status));
            }
            let track = tip_track(&traj);
            let y_start = track.first().map_or(0.0, |p| p.1[1]);
            let x = 0.99 * (length - chain.rod_length());
            let t = first_time_below(&track, y_start - x)
                .ok_or_else(|| format!("tip mass k = {k}: the tip never fell {x}"))?;
            let v = speed_below(&track, y_start - x)
                .ok_or_else(|| format!("tip mass k = {k}: no speed at {x}"))?;
            let (t_ff, v_s) = ((2.0 * length / g).sqrt(), (g * length).sqrt());
            Ok(Row {
                ratio: k,
                links,
                xi: x / length,
                t_fall: t / t_ff,
                t_law: tip_mass_law::time(x / length, k) * tau / t_ff,
                v_fall: v / v_s,
                v_law: tip_mass_law::speed(x, length, g, k) / v_s,
                v_final: tip_mass_law::final_speed(length, g, k) / v_s,
            })
        })
        .collect()
}

/// The CSV of [`rows`].
pub fn csv_text(rows: &[Row]) -> String {
    let mut s = String::from("ratio,links,xi,t_fall,t_law,t_rel,v_fall,v_law,v_final\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{}",
            num(r.ratio),
            r.links,
            num(r.xi),
            num(r.t_fall),
            num(r.t_law),
            num(r.t_fall / r.t_law - 1.0),
            num(r.v_fall),
            num(r.v_law),
            num(r.v_final)
        );
    }
    s
}

/// The law's curves against `k` (log-spaced from `lo` to `hi`, `points`
/// of them): fall time over free fall and final speed over `sqrt(g L)`.
pub fn law_csv(lo: f64, hi: f64, points: usize) -> String {
    let mut s = String::from("ratio,t_law,v_final\n");
    let steps = points.max(2) - 1;
    for j in 0..=steps {
        let k = lo * (hi / lo).powf(j as f64 / steps as f64);
        let _ = writeln!(
            s,
            "{},{},{}",
            num(k),
            num(tip_mass_law::time(1.0, k) / 2f64.sqrt()),
            num(tip_mass_law::final_speed(1.0, 1.0, k))
        );
    }
    s
}
