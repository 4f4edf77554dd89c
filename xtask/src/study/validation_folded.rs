//! `folded-vs-analytic` and `support-force`: the folded chain with r = 0
//! against the energy-conserving law (Calkin & March 1989), and the force on
//! the pivot during the fall.
//!
//! Convention: the fall distance `x` is measured from the free end's own
//! start height. The discrete folded start has its free end at
//! `P0 + (l, -l)`, released at rest, as the law's free end is at `x = 0`;
//! measured from the pivot's height instead, the chain would start at
//! `x = l` with `v = 0`, where the law already has `v ~ sqrt(2 g l)`: a time
//! offset of about `sqrt(2 l / g)`. Both are `O(1/n)` apart; the data carry
//! both, the figures use the first.

use std::sync::OnceLock;

use chain_ode::analysis::{first_time_below, folded_law, pivot_forces, refined, tip_track};
use chain_ode::{solve, Method, SolveOptions, Start, Trajectory, Vec2};
use figures::{palette, LinePlot, RGBColor, Series, Style};
use rayon::prelude::*;

use super::{figure_files, num, pool, scene, short, stem, write_data};
use crate::study::Ctx;

const LINKS: [usize; 4] = [50, 100, 200, 400];
const XIS: [f64; 2] = [0.5, 0.9];

/// A folded run and its tip at every sample.
struct FoldedRun {
    traj: Trajectory,
    /// `(t, tip, v_tip)`.
    track: Vec<(f64, Vec2, Vec2)>,
    /// Samples up to the tip's lowest point (the end of the fall).
    fall: usize,
}

impl FoldedRun {
    fn length(&self) -> f64 {
        self.traj.chain.length
    }
    fn gravity(&self) -> f64 {
        self.traj.chain.gravity
    }
    /// `(t, x, |v|)` during the fall, `x` from the free end's start height.
    fn fall_curve(&self) -> Vec<(f64, f64, f64)> {
        let y0 = self.track[0].1[1];
        self.track[..self.fall]
            .iter()
            .map(|(t, p, v)| (*t, y0 - p[1], v[0].hypot(v[1])))
            .collect()
    }
}

static FOLDED: OnceLock<Result<Vec<FoldedRun>, String>> = OnceLock::new();

/// The folded runs with r = 0, n = 50 .. 400, made once per process.
fn folded_runs(ctx: &Ctx) -> Result<&'static [FoldedRun], String> {
    FOLDED
        .get_or_init(|| {
            let base = scene(ctx, "folded")?
                .with_overrides(&["chain.damping=0"])
                .map_err(|e| e.to_string())?;
            let chain = base.chain().map_err(|e| e.to_string())?;
            let p0 = base.start().anchor();
            let tau = (chain.length / chain.gravity).sqrt();
            pool(ctx)?
                .install(|| {
                    LINKS
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
                            let traj = solve(&c, &start, Method::Dopri5, &options)
                                .map_err(|e| e.to_string())?;
                            if !traj.status.is_ok() {
                                return Err(format!("folded n = {n}: status {}", traj.status));
                            }
                            let track = tip_track(&traj);
                            // The fall ends where the tip first moves up again.
                            let fall = track
                                .iter()
                                .position(|(t, _, v)| *t > 0.5 * tau && v[1] >= 0.0)
                                .unwrap_or(track.len());
                            println!(
                                "  folded n = {n}: vmax {:.4} at t = {:.4}, {} steps, {:.2} s",
                                traj.summary.tip_speed_max,
                                traj.summary.t_tip_speed_max,
                                traj.stats.steps,
                                traj.summary.wall_seconds
                            );
                            Ok(FoldedRun { traj, track, fall })
                        })
                        .collect::<Result<Vec<_>, String>>()
                })
                .map(|mut v| {
                    v.sort_by_key(|r| r.traj.chain.links);
                    v
                })
        })
        .as_ref()
        .map(|v| v.as_slice())
        .map_err(|e| e.clone())
}

/// `|v|` at fall distance `x`, linear in `x` between samples.
fn speed_at(curve: &[(f64, f64, f64)], x: f64) -> Option<f64> {
    curve.windows(2).find_map(|w| {
        let (a, b) = (w[0], w[1]);
        (a.1 <= x && x <= b.1 && b.1 > a.1).then(|| a.2 + (b.2 - a.2) * (x - a.1) / (b.1 - a.1))
    })
}

pub fn make_folded(ctx: &Ctx) -> Result<Vec<String>, String> {
    const ID: &str = "folded-vs-analytic";
    let runs = folded_runs(ctx)?;
    let (length, g) = (runs[0].length(), runs[0].gravity());
    let vs = (g * length).sqrt();
    let tau = (length / g).sqrt();

    let mut curve_csv = String::from("links,t,x_over_L,v_over_sqrt_gL,v_law_over_sqrt_gL\n");
    let mut times_csv = String::from(
        "links,xi,t_from_start_height,t_from_pivot_height,t_law,rel_from_start_height,\
         rel_from_pivot_height,speed_rel_at_xi,max_speed_rel_from_0.05L_to_xi\n",
    );
    let mut left = LinePlot::new(
        "tip speed against fall distance",
        "x / L (fall of the free end from its start)",
        "|v| / sqrt(g L)",
    );
    let mut right = LinePlot::new(
        "time to fall x: chain against the law",
        "n (rods)",
        "t(x) / t_law(x) - 1  (%)",
    );
    let mut rel: Vec<Vec<(f64, f64, f64)>> = vec![vec![]; XIS.len()];
    let mut notes = vec![];
    for (i, run) in runs.iter().enumerate() {
        let n = run.traj.chain.links;
        let curve = run.fall_curve();
        for &(t, x, v) in &curve {
            let law = if x < length {
                short(folded_law::speed(x.max(0.0), length, g) / vs)
            } else {
                String::new()
            };
            curve_csv.push_str(&format!(
                "{n},{},{},{},{law}\n",
                short(t),
                short(x / length),
                short(v / vs)
            ));
        }
        left.series.push(
            Series::line(
                format!("n = {n}"),
                curve
                    .iter()
                    .map(|&(_, x, v)| (x / length, v / vs))
                    .collect(),
            )
            .with_color(palette(i)),
        );
        let y0 = run.track[0].1[1];
        for (k, &xi) in XIS.iter().enumerate() {
            let x = xi * length;
            let from_start = first_time_below(&run.track, y0 - x)
                .ok_or_else(|| format!("{ID}: n = {n} never fell {xi} L"))?;
            let from_pivot = first_time_below(&run.track, run.traj.anchor[1] - x)
                .ok_or_else(|| format!("{ID}: n = {n} never fell below {xi} L"))?;
            let law = folded_law::time(x, length, g);
            let speed = speed_at(&curve, x).unwrap_or(f64::NAN);
            let law_v = folded_law::speed(x, length, g);
            let worst = curve
                .iter()
                .filter(|c| c.1 >= 0.05 * length && c.1 <= x)
                .map(|c| (c.2 / folded_law::speed(c.1, length, g) - 1.0).abs())
                .fold(0.0, f64::max);
            times_csv.push_str(&format!(
                "{n},{xi},{},{},{},{},{},{},{}\n",
                num(from_start),
                num(from_pivot),
                num(law),
                num(from_start / law - 1.0),
                num(from_pivot / law - 1.0),
                num(speed / law_v - 1.0),
                num(worst)
            ));
            rel[k].push((n as f64, from_start / law - 1.0, from_pivot / law - 1.0));
            if xi == 0.5 {
                notes.push(format!(
                    "n = {n}: t(L/2) {:+.3}%, |v/v_law - 1| <= {:.2}% to L/2",
                    100.0 * (from_start / law - 1.0),
                    100.0 * worst
                ));
            }
        }
    }
    let black = RGBColor(0, 0, 0);
    let gray = RGBColor(120, 120, 120);
    let law_curve: Vec<(f64, f64)> = (0..=2000)
        .map(|k| {
            let xi = 0.9999 * k as f64 / 2000.0;
            (xi, folded_law::speed(xi * length, length, g) / vs)
        })
        .collect();
    left.series.push(
        Series::new("law: v^2 = g x (2L - x)/(L - x)", law_curve, Style::Dashed).with_color(black),
    );
    left.series.push(
        Series::new(
            "free fall: v^2 = 2 g x",
            (0..=100)
                .map(|k| {
                    let xi = k as f64 / 100.0;
                    (xi, folded_law::free_fall_speed(xi * length, g) / vs)
                })
                .collect(),
            Style::Dashed,
        )
        .with_color(gray),
    );
    let top = runs
        .iter()
        .flat_map(|r| r.fall_curve())
        .map(|c| c.2 / vs)
        .fold(0.0, f64::max);
    left.y_range = Some((0.0, 1.05 * top));
    left.x_range = Some((0.0, 1.0));
    for (k, &xi) in XIS.iter().enumerate() {
        let label = if xi == 0.5 { "L/2" } else { "0.9 L" };
        right.series.push(
            Series::new(
                format!("{label}, x from the free end's start"),
                rel[k].iter().map(|r| (r.0, 100.0 * r.1)).collect(),
                Style::LinePoints,
            )
            .with_color(palette(k)),
        );
        right.series.push(
            Series::new(
                format!("{label}, x from the pivot's height"),
                rel[k].iter().map(|r| (r.0, 100.0 * r.2)).collect(),
                Style::Dashed,
            )
            .with_color(palette(k)),
        );
    }
    right.series.push(
        Series::new("+-0.5%", vec![(0.0, 0.5), (420.0, 0.5)], Style::Dashed).with_color(gray),
    );
    right
        .series
        .push(Series::new("", vec![(0.0, -0.5), (420.0, -0.5)], Style::Dashed).with_color(gray));
    right
        .series
        .push(Series::new("", vec![(0.0, 0.0), (420.0, 0.0)], Style::Line).with_color(black));
    right.x_range = Some((0.0, 420.0));
    right.y_range = Some((-2.0, 4.0));
    let mut files = vec![
        write_data(ctx, &format!("{ID}.csv"), &curve_csv)?,
        write_data(ctx, &format!("{ID}-times.csv"), &times_csv)?,
    ];
    let title = format!(
        "Folded chain, r = 0: the law's t(L/2) = {:.4} sqrt(L/g), t(0.9 L) = {:.4} sqrt(L/g)",
        folded_law::time(0.5 * length, length, g) / tau,
        folded_law::time(0.9 * length, length, g) / tau
    );
    figures::line_plot_pair(&left, &right, &title, &stem(ctx, ID))
        .map_err(|e| format!("{ID}: {e}"))?;
    for n in &notes {
        println!("  {ID}: {n}");
    }
    files.extend(figure_files(ID));
    Ok(files)
}

/// Width (time units) of the centred window of the running mean of the
/// pivot force: several rods turn through the fold in it (about 2.5 at
/// n = 100 and L/2), so the rods' clicks average out.
const WINDOW: f64 = 0.1;

/// The running means drawn (all are in the data).
const SHOWN: [usize; 2] = [100, 400];

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

pub fn make_support(ctx: &Ctx) -> Result<Vec<String>, String> {
    const ID: &str = "support-force";
    let runs = folded_runs(ctx)?;
    // The catenary scene for comparison, as the scene runs it (adaptive).
    let span = scene(ctx, "span-d3")?
        .with_overrides(&[
            "run.method=\"dopri5\"",
            "run.rtol=1e-9",
            "run.atol=1e-11",
            "run.output_dt=0.002",
        ])
        .map_err(|e| e.to_string())?;
    let span_traj = span
        .prepare()
        .and_then(|p| p.solve())
        .map_err(|e| e.to_string())?;
    if !span_traj.status.is_ok() {
        return Err(format!("{ID}: span-d3 status {}", span_traj.status));
    }

    // Columns: the pivot's force on rod 1 (= minus the chain's pull on P0),
    // its running mean, the law's value and running mean at the measured xi,
    // and the chain's vertical momentum from the force's impulse,
    // P_y(t) = integral (F_y - M g) dt, against the law's -rho v (L - x)/2.
    let mut csv = String::from(
        "scene,links,t,xi,pivot_force_x_over_Mg,pivot_force_y_over_Mg,\
         running_mean_y_over_Mg,law_over_Mg,law_running_mean_over_Mg,\
         momentum_y_over_M_sqrt_gL,law_momentum_y_over_M_sqrt_gL\n",
    );
    let mut left = LinePlot::new(
        "folded chain, r = 0",
        "xi = x / L (fall of the free end from its start)",
        "pull on P0, downward / (M g)",
    );
    let mut right = LinePlot::new("against time", "t", "pull on P0 / (M g)");
    let light = RGBColor(190, 190, 190);
    let mut momentum_notes = vec![];
    let mut printed = vec![];
    for (i, run) in runs.iter().enumerate() {
        let chain = &run.traj.chain;
        let (weight, length, g) = (chain.weight(), chain.length, chain.gravity);
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
        let mut pts = vec![];
        for k in 0..fy.len() {
            if k > 0 {
                impulse += 0.5 * (fy[k].0 - fy[k - 1].0) * (fy[k].1 + fy[k - 1].1 - 2.0);
            }
            // Momentum over M sqrt(g L): g * impulse(in units of M g) / sqrt(g L).
            let p = impulse * g / vs;
            let law_p = -0.5
                * folded_law::speed((xi[k] * length).clamp(0.0, 0.999_999 * length), length, g)
                / vs
                * (1.0 - xi[k]);
            let cell = |x: Option<f64>| x.map_or(String::new(), short);
            csv.push_str(&format!(
                "folded,{},{},{},{},{},{},{},{},{},{}\n",
                chain.links,
                short(fy[k].0),
                short(xi[k]),
                short(forces[k].1[0] / weight),
                short(fy[k].1),
                cell(mean[k]),
                short(law[k].1),
                cell(law_mean[k]),
                short(p),
                short(law_p)
            ));
            if let (Some(m), Some(lm)) = (mean[k], law_mean[k]) {
                if (0.05..=0.75).contains(&xi[k]) {
                    worst_mean = worst_mean.max((m / lm - 1.0).abs());
                }
                if xi[k] <= 0.95 {
                    pts.push((xi[k], m));
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
        momentum_notes.push(format!(
            "{:+.1}% (n = {})",
            100.0 * (p_half / law_half - 1.0),
            chain.links
        ));
        let (lo, hi) = fy
            .iter()
            .zip(&xi)
            .filter(|(_, &x)| (0.4..=0.6).contains(&x))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, (p, _)| {
                (a.0.min(p.1), a.1.max(p.1))
            });
        printed.push(format!(
            "n = {}: running mean within {:.1}% of the law's for 0.05 <= xi <= 0.75; \
             momentum from the impulse at xi = 0.5: {:+.2}% of the law's, within {:.4} \
             M sqrt(g L) of it to xi = 0.75; raw force in [{lo:.2}, {hi:.2}] M g for \
             0.4 <= xi <= 0.6",
            chain.links,
            100.0 * worst_mean,
            100.0 * (p_half / law_half - 1.0),
            worst_p,
        ));
        if chain.links == 100 {
            // The raw force of one n, to show the clicks the means smooth.
            left.series.insert(
                0,
                Series::line(
                    "n = 100, raw",
                    fy.iter()
                        .zip(&xi)
                        .filter(|(_, &x)| x <= 0.85)
                        .map(|(p, &x)| (x, p.1))
                        .collect(),
                )
                .with_color(light),
            );
        }
        if SHOWN.contains(&chain.links) {
            left.series.push(
                Series::line(format!("n = {}, mean", chain.links), pts).with_color(palette(i)),
            );
        }
        if i + 1 == runs.len() {
            right.series.push(
                Series::line(
                    format!("folded, n = {} (mean)", chain.links),
                    fy.iter()
                        .zip(&mean)
                        .zip(&xi)
                        .filter(|(_, &x)| x <= 0.95)
                        .filter_map(|((p, m), _)| m.map(|m| (p.0, m)))
                        .collect(),
                )
                .with_color(palette(i)),
            );
        }
    }
    let black = RGBColor(0, 0, 0);
    left.series.push(
        Series::new(
            "law",
            (0..=1000)
                .map(|k| {
                    let xi = 0.97 * k as f64 / 1000.0;
                    (xi, folded_law::support_force(xi))
                })
                .collect(),
            Style::Dashed,
        )
        .with_color(black),
    );
    left.x_range = Some((0.0, 1.0));
    left.y_range = Some((0.0, 8.0));
    left.annotations = vec![
        format!("mean: over {WINDOW} time units"),
        "momentum at xi = 0.5".to_string(),
        "against the law's:".to_string(),
    ];
    left.annotations.extend(momentum_notes);

    let chain = &span_traj.chain;
    let weight = chain.weight();
    let forces = pivot_forces(&span_traj);
    for (t, f) in &forces {
        csv.push_str(&format!(
            "span-d3,{},{},,{},{},,,,,\n",
            chain.links,
            short(*t),
            short(f[0] / weight),
            short(f[1] / weight)
        ));
    }
    right.series.push(
        Series::line(
            "span-d3: vertical",
            forces.iter().map(|(t, f)| (*t, f[1] / weight)).collect(),
        )
        .with_color(palette(5)),
    );
    right.series.push(
        Series::new(
            "span-d3: horizontal",
            forces.iter().map(|(t, f)| (*t, -f[0] / weight)).collect(),
            Style::Dashed,
        )
        .with_color(palette(5)),
    );
    let peak = forces
        .iter()
        .map(|(t, f)| (*t, f[0].hypot(f[1]) / weight))
        .fold((0.0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
    right.annotations = vec![format!("span-d3: peak |F| = {:.2} M g", peak.1)];
    right.y_range = Some((-0.2, 6.5));
    printed.push(format!(
        "span-d3: peak |F| = {:.3} M g at t = {:.4}",
        peak.1, peak.0
    ));
    printed.push(format!(
        "span-d3 at t = 0+: pull ({:.4}, {:.4}) M g",
        -forces[0].1[0] / weight,
        forces[0].1[1] / weight
    ));
    let mut files = vec![write_data(ctx, &format!("{ID}.csv"), &csv)?];
    let title = "Force on the pivot P0 from the O(n) recursion, in units of the weight M g";
    figures::line_plot_pair(&left, &right, title, &stem(ctx, ID))
        .map_err(|e| format!("{ID}: {e}"))?;
    for n in printed.iter().chain(&right.annotations) {
        println!("  {ID}: {n}");
    }
    files.extend(figure_files(ID));
    Ok(files)
}
