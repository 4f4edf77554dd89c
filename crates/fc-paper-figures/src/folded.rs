//! The folded chain with r = 0 against the energy-conserving law (Calkin &
//! March 1989): its fall against the law's speed and times, the force on
//! the pivot, and the tip's acceleration, as tables (the figures
//! `folded-vs-analytic`, `support-force` and `folded-tip-acceleration` of
//! `cargo xtask figures` draw them).
//!
//! Convention: the fall distance `x` is measured from the free end's own
//! start height. The discrete folded start has its free end at
//! `P0 + (l, -l)`, released at rest, as the law's free end is at `x = 0`;
//! measured from the pivot's height instead, the chain would start at
//! `x = l` with `v = 0`, where the law already has `v ~ sqrt(2 g l)`: a time
//! offset of about `sqrt(2 l / g)`. Both are `O(1/n)` apart; the data carry
//! both, the figures use the first.

use std::fmt::Write as _;

use chain_ode::analysis::{first_time_below, folded_law, pivot_forces, refined, tip_track};
use chain_ode::dynamics::{accelerations, Workspace};
use chain_ode::{solve, Method, SolveOptions, Start, Trajectory, Vec2};
use rayon::prelude::*;

use fc_csv::format::{fixed, num, opt};
use fc_scene::scene::Scene;

/// The tables of [`vs_law`]: the fall of each n
/// (`links,t,x_over_L,v_over_sqrt_gL,v_law_over_sqrt_gL`), the times to
/// L/2 and 0.9 L against the law, the law's and free fall's speed against
/// `xi`, and a line per n on how close it is.
pub struct VsLaw {
    pub curve: String,
    pub times: String,
    pub law: String,
    pub notes: Vec<String>,
}

/// The tables of [`support_force`]: the pivot force at every sample of the
/// folded falls and of the span scene, the law, and a line per run.
pub struct SupportTables {
    pub force: String,
    pub law: String,
    pub notes: Vec<String>,
}

/// A long per-sample cell: six decimals (quantities of order one).
fn short(x: f64) -> String {
    fixed(x, 6)
}

pub const LINKS: [usize; 4] = [50, 100, 200, 400];
pub const XIS: [f64; 2] = [0.5, 0.9];

/// A folded run and its tip at every sample.
pub struct FoldedRun {
    pub traj: Trajectory,
    /// `(t, tip, v_tip)`.
    pub track: Vec<(f64, Vec2, Vec2)>,
    /// Samples up to the tip's lowest point (the end of the fall).
    pub fall: usize,
    /// One line on the run (vmax, its time, the steps).
    pub note: String,
}

impl FoldedRun {
    pub fn length(&self) -> f64 {
        self.traj.chain().length()
    }
    pub fn gravity(&self) -> f64 {
        self.traj.chain().gravity()
    }
    /// `(t, x, |v|)` during the fall, `x` from the free end's start height.
    pub fn fall_curve(&self) -> Vec<(f64, f64, f64)> {
        let y0 = self.track[0].1[1];
        self.track[..self.fall]
            .iter()
            .map(|(t, p, v)| (*t, y0 - p[1], v[0].hypot(v[1])))
            .collect()
    }
}

/// The folded runs of `base` (the folded scene with r = 0) at each of
/// [`LINKS`] rods, in parallel on the current rayon pool, sorted by n.
pub fn folded_runs(base: &Scene) -> Result<Vec<FoldedRun>, String> {
    let chain = base.chain().map_err(|e| e.to_string())?;
    let p0 = base.start().anchor();
    let tau = (chain.length() / chain.gravity()).sqrt();
    let mut runs = LINKS
        .par_iter()
        .rev()
        .map(|&n| {
            let c = refined(&chain, n).map_err(|e| e.to_string())?;
            let start = Start::Folded {
                p0,
                down: Some(n / 2),
            }
            .state(&c)
            .map_err(|e| e.to_string())?;
            // Past the law's total fall time 1.198 sqrt(L/g).
            let options = SolveOptions {
                t_end: 1.22 * tau,
                rtol: 1e-10,
                atol: 1e-12,
                output_dt: Some(1e-3),
                ..Default::default()
            };
            let traj = solve(&c, &start, Method::Dopri5, &options).map_err(|e| e.to_string())?;
            if !traj.status.is_ok() {
                return Err(format!("folded n = {n}: status {}", traj.status));
            }
            let track = tip_track(&traj);
            // The fall ends where the tip first moves up again.
            let fall = track
                .iter()
                .position(|(t, _, v)| *t > 0.5 * tau && v[1] >= 0.0)
                .unwrap_or(track.len());
            let note = format!(
                "folded n = {n}: vmax {:.4} at t = {:.4}, {} steps",
                traj.summary.tip_speed_max, traj.summary.t_tip_speed_max, traj.stats.steps,
            );
            Ok(FoldedRun {
                traj,
                track,
                fall,
                note,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    runs.sort_by_key(|r| r.traj.chain().links());
    Ok(runs)
}

/// `|v|` at fall distance `x`, linear in `x` between samples.
fn speed_at(curve: &[(f64, f64, f64)], x: f64) -> Option<f64> {
    curve.windows(2).find_map(|w| {
        let (a, b) = (w[0], w[1]);
        (a.1 <= x && x <= b.1 && b.1 > a.1).then(|| a.2 + (b.2 - a.2) * (x - a.1) / (b.1 - a.1))
    })
}

/// Points of the law's curves: `xi` from 0 to [`LAW_TO`].
const LAW_POINTS: usize = 2000;
const LAW_TO: f64 = 0.9999;

/// The tables of the folded runs against the law: the fall of each n, the times (times to
/// L/2 and 0.9 L against the law) and `-law.csv` (the law's and free
/// fall's speed against `xi`).
pub fn vs_law(runs: &[FoldedRun]) -> Result<VsLaw, String> {
    let (length, g) = (runs[0].length(), runs[0].gravity());
    let vs = (g * length).sqrt();
    let tau = (length / g).sqrt();
    let mut notes = vec![];

    let mut curve_csv = String::from("links,t,x_over_L,v_over_sqrt_gL,v_law_over_sqrt_gL\n");
    let mut times_csv = String::from(
        "links,xi,t_from_start_height,t_from_pivot_height,t_law,rel_from_start_height,\
         rel_from_pivot_height,speed_rel_at_xi,max_speed_rel_from_0.05L_to_xi,\
         t_law_over_sqrt_L_over_g\n",
    );
    for run in runs {
        let n = run.traj.chain().links();
        let curve = run.fall_curve();
        for &(t, x, v) in &curve {
            let law = if x < length {
                short(folded_law::speed(x.max(0.0), length, g) / vs)
            } else {
                String::new()
            };
            let _ = writeln!(
                curve_csv,
                "{n},{},{},{},{law}",
                short(t),
                short(x / length),
                short(v / vs)
            );
        }
        let y0 = run.track[0].1[1];
        for &xi in &XIS {
            let x = xi * length;
            let from_start = first_time_below(&run.track, y0 - x)
                .ok_or_else(|| format!("folded n = {n} never fell {xi} L"))?;
            let from_pivot = first_time_below(&run.track, run.traj.anchor[1] - x)
                .ok_or_else(|| format!("folded n = {n} never fell below {xi} L"))?;
            let law = folded_law::time(x, length, g);
            let speed = speed_at(&curve, x).unwrap_or(f64::NAN);
            let law_v = folded_law::speed(x, length, g);
            let worst = curve
                .iter()
                .filter(|c| c.1 >= 0.05 * length && c.1 <= x)
                .map(|c| (c.2 / folded_law::speed(c.1, length, g) - 1.0).abs())
                .fold(0.0, f64::max);
            let _ = writeln!(
                times_csv,
                "{n},{xi},{},{},{},{},{},{},{},{}",
                num(from_start),
                num(from_pivot),
                num(law),
                num(from_start / law - 1.0),
                num(from_pivot / law - 1.0),
                num(speed / law_v - 1.0),
                num(worst),
                num(law / tau)
            );
            if xi == 0.5 {
                notes.push(format!(
                    "n = {n}: t(L/2) {:+.3}%, |v/v_law - 1| <= {:.2}% to L/2",
                    100.0 * (from_start / law - 1.0),
                    100.0 * worst
                ));
            }
        }
    }
    let mut law_csv = String::from("xi,v_law_over_sqrt_gL,v_free_fall_over_sqrt_gL\n");
    for k in 0..=LAW_POINTS {
        let xi = LAW_TO * k as f64 / LAW_POINTS as f64;
        let _ = writeln!(
            law_csv,
            "{},{},{}",
            short(xi),
            short(folded_law::speed(xi * length, length, g) / vs),
            short(folded_law::free_fall_speed(xi * length, g) / vs)
        );
    }
    Ok(VsLaw {
        curve: curve_csv,
        times: times_csv,
        law: law_csv,
        notes,
    })
}

/// Width (time units) of the centred window of the running mean of the
/// pivot force: several rods turn through the fold in it (about 2.5 at
/// n = 100 and L/2), so the rods' clicks average out.
pub const WINDOW: f64 = 0.1;

/// The impulse `integral_0^{t_k} (f - 1) dt` of samples `(t, f)` (units of M g).
fn impulse_at(pts: &[(f64, f64)], k: usize) -> f64 {
    pts[..=k]
        .windows(2)
        .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[1].1 + w[0].1 - 2.0))
        .sum()
}

/// Running means over a centred window of width `WINDOW` of `(t, f)`
/// (trapezoid rule on the samples), where the window fits in the data.
fn running_mean(pts: &[(f64, f64)]) -> Vec<Option<f64>> {
    let mut cum = vec![0.0; pts.len()];
    for k in 1..pts.len() {
        cum[k] = cum[k - 1] + 0.5 * (pts[k].0 - pts[k - 1].0) * (pts[k].1 + pts[k - 1].1);
    }
    let dt = pts.get(1).map_or(1.0, |p| p.0 - pts[0].0);
    let half = (0.5 * WINDOW / dt).round() as usize;
    (0..pts.len())
        .map(|k| {
            (k >= half && k + half < pts.len())
                .then(|| (cum[k + half] - cum[k - half]) / (pts[k + half].0 - pts[k - half].0))
        })
        .collect()
}

/// Points of the law's curve of the support force: `xi` from 0 to 0.97.
const FORCE_LAW_POINTS: usize = 1000;
pub const FORCE_LAW_TO: f64 = 0.97;

/// The catenary scene `span` run as [`support_force`] compares it:
/// adaptive DOPRI5 at rtol 1e-9 (atol 1e-11), a sample every 0.002. Errs
/// unless the run completes.
pub fn span_run(span: &Scene) -> Result<Trajectory, String> {
    let set = [
        "run.method=\"dopri5\"",
        "run.rtol=1e-9",
        "run.atol=1e-11",
        "run.output_dt=0.002",
    ];
    let traj = (span.with_overrides(&set))
        .and_then(|s| s.prepare())
        .and_then(|p| p.solve())
        .map_err(|e| e.to_string())?;
    if !traj.status.is_ok() {
        return Err(format!("status {}", traj.status));
    }
    Ok(traj)
}

/// The pivot force at every sample of the folded falls `runs` and of the
/// run `span_traj` of the scene called `span` (a catenary start, for
/// comparison), and the law's.
pub fn support_force(
    runs: &[FoldedRun],
    (span, span_traj): (&str, &Trajectory),
) -> Result<SupportTables, String> {
    let mut notes = vec![];
    // Columns: the pivot's force on rod 1 (= minus the chain's pull on
    // P0), its running mean, the law's value and running mean at the
    // measured xi, and the chain's vertical momentum from the force's
    // impulse, P_y(t) = integral (F_y - M g) dt, against the law's
    // -rho v (L - x)/2.
    let mut csv = String::from(
        "scene,links,t,xi,pivot_force_x_over_Mg,pivot_force_y_over_Mg,\
         running_mean_y_over_Mg,law_over_Mg,law_running_mean_over_Mg,\
         momentum_y_over_M_sqrt_gL,law_momentum_y_over_M_sqrt_gL\n",
    );
    for run in runs {
        let chain = run.traj.chain();
        let (weight, length, g) = (chain.weight(), chain.length(), chain.gravity());
        let vs = (g * length).sqrt();
        let forces = &pivot_forces(&run.traj)[..run.fall];
        let y0 = run.track[0].1[1];
        let xi: Vec<f64> = run.track[..run.fall]
            .iter()
            .map(|p| (y0 - p.1[1]) / length)
            .collect();
        let fy: Vec<(f64, f64)> = forces.iter().map(|(t, f)| (*t, f[1] / weight)).collect();
        let law: Vec<(f64, f64)> = fy
            .iter()
            .zip(&xi)
            .map(|(p, &x)| (p.0, folded_law::support_force(x)))
            .collect();
        let mean = running_mean(&fy);
        let law_mean = running_mean(&law);
        let (mut impulse, mut worst_mean, mut worst_p): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for k in 0..fy.len() {
            if k > 0 {
                impulse += 0.5 * (fy[k].0 - fy[k - 1].0) * (fy[k].1 + fy[k - 1].1 - 2.0);
            }
            // Momentum over M sqrt(g L): g * impulse (in units of M g) / sqrt(g L).
            let p = impulse * g / vs;
            let law_p = -0.5
                * folded_law::speed((xi[k] * length).clamp(0.0, 0.999_999 * length), length, g)
                / vs
                * (1.0 - xi[k]);
            let _ = writeln!(
                csv,
                "folded,{},{},{},{},{},{},{},{},{},{}",
                chain.links(),
                short(fy[k].0),
                short(xi[k]),
                short(forces[k].1[0] / weight),
                short(fy[k].1),
                opt(mean[k], short),
                short(law[k].1),
                opt(law_mean[k], short),
                short(p),
                short(law_p)
            );
            if let (Some(m), Some(lm)) = (mean[k], law_mean[k]) {
                if (0.05..=0.75).contains(&xi[k]) {
                    worst_mean = worst_mean.max((m / lm - 1.0).abs());
                }
            }
            if xi[k] <= 0.75 {
                worst_p = worst_p.max((p - law_p).abs());
            }
        }
        // The momentum from the impulse against the law's at xi = 0.5.
        let half = xi.iter().position(|&x| x >= 0.5).unwrap_or(xi.len() - 1);
        let p_half = impulse_at(&fy, half) * g / vs;
        let law_half =
            -0.5 * folded_law::speed(xi[half] * length, length, g) / vs * (1.0 - xi[half]);
        let (lo, hi) = fy
            .iter()
            .zip(&xi)
            .filter(|(_, &x)| (0.4..=0.6).contains(&x))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, (p, _)| {
                (a.0.min(p.1), a.1.max(p.1))
            });
        notes.push(format!(
            "n = {}: running mean within {:.1}% of the law's for 0.05 <= xi <= 0.75; \
             momentum from the impulse at xi = 0.5: {:+.2}% of the law's, within {:.4} \
             M sqrt(g L) of it to xi = 0.75; raw force in [{lo:.2}, {hi:.2}] M g for \
             0.4 <= xi <= 0.6",
            chain.links(),
            100.0 * worst_mean,
            100.0 * (p_half / law_half - 1.0),
            worst_p,
        ));
    }
    let chain = span_traj.chain();
    let weight = chain.weight();
    let forces = pivot_forces(span_traj);
    for (t, f) in &forces {
        let _ = writeln!(
            csv,
            "{span},{},{},,{},{},,,,,",
            chain.links(),
            short(*t),
            short(f[0] / weight),
            short(f[1] / weight)
        );
    }
    if let Some((_, f)) = forces.first() {
        notes.push(format!(
            "{span} at t = 0+: pull ({:.4}, {:.4}) M g",
            -f[0] / weight,
            f[1] / weight
        ));
    }
    let mut law_csv = String::from("xi,law_over_Mg\n");
    for k in 0..=FORCE_LAW_POINTS {
        let xi = FORCE_LAW_TO * k as f64 / FORCE_LAW_POINTS as f64;
        let _ = writeln!(
            law_csv,
            "{},{}",
            short(xi),
            short(folded_law::support_force(xi))
        );
    }
    Ok(SupportTables {
        force: csv,
        law: law_csv,
        notes,
    })
}

/// The rods of the tip-acceleration figure (two of the folded runs).
pub const ACCEL_LINKS: [usize; 2] = [100, 400];
/// Fall distances at which `-at.csv` compares the tip with the law.
const ACCEL_XIS: [f64; 5] = [0.25, 0.5, 0.75, 0.9, 0.95];
/// Half-width in `xi` of the window `-at.csv` averages over (the discrete
/// tip's acceleration oscillates as each rod rounds the fold).
pub(crate) const ACCEL_WINDOW: f64 = 0.02;

/// The law's tip acceleration over `g`: `1 + xi (2 - xi) / (2 (1 - xi)^2)`,
/// the derivative along the fall of `v^2 = g x (2L - x)/(L - x)`
/// (`a = (1/2) d(v^2)/dx`): free fall plus the pull of the tension at the
/// fold on the falling arm.
fn accel_law(xi: f64) -> f64 {
    1.0 + xi * (2.0 - xi) / (2.0 * (1.0 - xi) * (1.0 - xi))
}

/// `folded-tip-acceleration.csv`: `links,t,xi,accel_over_g,law_over_g`
/// at every output sample of the fall (`xi = x/L`, `x` from the free
/// end's start height; `accel_over_g` = the tip's downward acceleration
/// over `g`, evaluated by `chain_ode::dynamics::accelerations` at the
/// sample's state, not differenced). `-at.csv`:
/// `links,xi,accel_over_g,law_over_g,rel_to_law` at a few `xi`, linear
/// in `xi` between samples, then `accel_mean_over_g,law_mean_over_g,
/// rel_mean_to_law`: the means over `|x/L - xi| <= 0.02` (the tip
/// velocity's change over that time, and the law's mean there).
pub fn tip_acceleration(runs: &[FoldedRun]) -> (String, String) {
    let mut csv = String::from("links,t,xi,accel_over_g,law_over_g\n");
    let mut at = String::from(
        "links,xi,accel_over_g,law_over_g,rel_to_law,\
         accel_mean_over_g,law_mean_over_g,rel_mean_to_law\n",
    );
    for run in runs
        .iter()
        .filter(|r| ACCEL_LINKS.contains(&r.traj.chain().links()))
    {
        let chain = run.traj.chain();
        let n = chain.links();
        let (length, g) = (run.length(), run.gravity());
        let mut ws = Workspace::new(n);
        let mut acc = vec![0.0; n];
        let y0 = run.track[0].1[1];
        let mut curve = vec![];
        for k in 0..run.fall {
            let s = run.traj.sample(k);
            let r = accelerations(chain, s.angles, s.rates, &mut acc, &mut ws);
            let xi = (y0 - run.track[k].1[1]) / length;
            let a = -r.tip_acceleration[1] / g;
            curve.push((xi, a, s.t, run.track[k].2[1]));
            let _ = writeln!(
                csv,
                "{n},{},{},{},{}",
                fixed(s.t, 4),
                short(xi),
                short(a),
                short(accel_law(xi))
            );
        }
        for xi in ACCEL_XIS {
            let a = curve.windows(2).find_map(|w| {
                let (p, q) = (w[0], w[1]);
                (p.0 <= xi && xi <= q.0 && q.0 > p.0)
                    .then(|| p.1 + (q.1 - p.1) * (xi - p.0) / (q.0 - p.0))
            });
            let law = accel_law(xi);
            // The mean over the samples within ACCEL_WINDOW of xi: the
            // exact tip velocity's change over the time between them,
            // against the law's mean over the same samples (equal times).
            let near: Vec<&(f64, f64, f64, f64)> = curve
                .iter()
                .filter(|c| (c.0 - xi).abs() <= ACCEL_WINDOW)
                .collect();
            let (mean, law_mean) = match (near.first(), near.last()) {
                (Some(p), Some(q)) if q.2 > p.2 => (
                    Some(-(q.3 - p.3) / (q.2 - p.2) / g),
                    Some(near.iter().map(|c| accel_law(c.0)).sum::<f64>() / near.len() as f64),
                ),
                _ => (None, None),
            };
            let _ = writeln!(
                at,
                "{n},{},{},{},{},{},{},{}",
                num(xi),
                opt(a, num),
                num(law),
                opt(a.map(|a| a / law - 1.0), num),
                opt(mean, num),
                opt(law_mean, num),
                opt(mean.zip(law_mean).map(|(m, l)| m / l - 1.0), num)
            );
        }
    }
    (csv, at)
}
