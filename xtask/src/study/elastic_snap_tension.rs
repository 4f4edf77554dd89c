//! `snap-tension`: the tension along the chain around the snap, the wave
//! running up from the tip (`falling_chain::study::snap`). Span d = 3
//! refined to n = 100 at fixed total mass `M = 10` (the continuum
//! convention), elastic links `EA = 1e4`, `eta = 1.549`; DOPRI5 at rtol
//! 1e-8, samples every 1e-3. The profiles are at the time of the tip's
//! maximum speed `t_v` (the tip is arrested), at four equal steps from it
//! to the peak of the support force `t_p`, and at `t_p + 0.05`; beside
//! them, the support force against time.

use falling_chain::converge::refined_scene;
use falling_chain::study::snap::{self, Options};
use figures::{cool, LinePlot, Series, Style};
use std::fmt::Write as _;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};
use falling_chain::study::format::{fixed, num};
use falling_chain::study::table::distinct;

const LINKS: usize = 100;
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
        let (tv, tp) = (r.t_tip_speed_max, r.t_peak_force);
        let mut times: Vec<f64> = (0..5).map(|k| tv + (tp - tv) * k as f64 / 4.0).collect();
        times.push(tp + 0.05);
        let mut csv = String::from("t,joint,s_over_L,tension_mg\n");
        for (t, tension) in snap::tension_profiles(&traj, &times) {
            for (k, x) in tension.iter().enumerate() {
                writeln!(
                    csv,
                    "{},{k},{},{}",
                    num(t),
                    num(k as f64 / LINKS as f64),
                    fixed(*x, 5)
                )
                .map_err(|e| e.to_string())?;
            }
        }
        let weight = traj.chain.weight();
        let summary = format!(
            "links,axial_stiffness,tip_speed_max,t_tip_speed_max,peak_force_mg,t_peak_force,\
             impulse\n{LINKS},1e4,{},{},{},{},{}\n",
            num(r.tip_speed_max),
            num(tv),
            num(r.peak_force),
            num(tp),
            num(r.impulse)
        );
        let mut force = String::from("t,pivot_force_mg\n");
        for (t, f) in chain_ode::analysis::pivot_forces(&traj) {
            if (tv - 0.4..=tp + 0.3).contains(&t) {
                writeln!(
                    force,
                    "{},{}",
                    fixed(t, 4),
                    fixed(f[0].hypot(f[1]) / weight, 5)
                )
                .map_err(|e| e.to_string())?;
            }
        }
        println!(
            "  {}: t_v = {tv:.4}, t_p = {tp:.4}, peak {:.3} M g",
            fig.id, r.peak_force
        );
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &csv)?,
            ctx.write(&format!("{}-force.csv", fig.id), &force)?,
            ctx.write(&format!("{}-summary.csv", fig.id), &summary)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let (time, s, tension) = (t.strs("t")?, t.nums("s_over_L")?, t.nums("tension_mg")?);
        let f = ctx.read(&format!("{}-force.csv", fig.id))?;
        let (ft, ff) = (f.nums("t")?, f.nums("pivot_force_mg")?);
        let mut left = LinePlot::new(
            "tension along the chain (pivot at 0, tip at 1)",
            "s / L",
            "tension / (M g)",
        );
        let mut right = LinePlot::new("support force", "t", "|F_pivot| / (M g)");
        let times = distinct(&time);
        let k_max = times.len().saturating_sub(1).max(1) as f64;
        for (k, tk) in times.iter().enumerate() {
            let pts: Vec<(f64, f64)> = (0..t.len())
                .filter(|&j| time[j] == *tk)
                .map(|j| (s[j], tension[j]))
                .collect();
            let tv: f64 = tk.parse().unwrap_or(f64::NAN);
            left.series.push(
                Series::new(format!("t = {tv:.3}"), pts, Style::Line)
                    .with_color(cool(k as f64 / k_max)),
            );
            let at = ft
                .iter()
                .zip(&ff)
                .min_by(|a, b| (a.0 - tv).abs().total_cmp(&(b.0 - tv).abs()))
                .map(|(a, b)| (*a, *b));
            if let Some(p) = at {
                right.series.push(
                    Series::new("", vec![p], Style::Points).with_color(cool(k as f64 / k_max)),
                );
            }
        }
        right.series.insert(
            0,
            Series::new(
                "n = 100, EA = 1e4",
                ft.iter().copied().zip(ff.iter().copied()).collect(),
                Style::Line,
            )
            .with_color(figures::RGBColor(0, 0, 0)),
        );
        left.x_range = Some((0.0, 1.0));
        let title = "The snap's wave: tension from the tip's arrest to the support's peak \
                     (d = 3, n = 100, M = 10, EA = 1e4)";
        let out = figures::line_plot_pair(&left, &right, title, &ctx.stem(fig.id))
            .map_err(|e| format!("{}: {e}", fig.id))?;
        Ok(ctx.drawn(&out))
    }
}
