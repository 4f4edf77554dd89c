//! `convergence-n`: how many rods the span scenes need.
//!
//! Each scene is refined at fixed continuum properties (total mass
//! `M = n m` and bending viscosity `eta = r l`, see
//! `falling_chain::converge`) over the ladder n = 25 .. 1600, and to n = 3200
//! where the last doubling (800 -> 1600) still moved the maximum tip speed by
//! more than 0.05% (half the finest tolerance asked for). The finest n is
//! the reference. All runs: `auto`, rtol 1e-9, atol 1e-11, tip sampled every
//! 0.01 for the path comparison. At fixed bending viscosity the damping rate
//! grows like n^4, so `auto` runs DOP853 on the coarse levels and the O(n)
//! BDF on the fine ones.

use falling_chain::study::convergence;
use figures::{palette, LinePlot, RGBColor, Series, Style};

use crate::ctx::Ctx;
use crate::data::distinct;
use crate::registry::{Figure, Make};

const SCENES: [&str; 3] = ["span-d1", "span-d3", "span-d5"];
const LADDER: [usize; 7] = [25, 50, 100, 200, 400, 800, 1600];
const FINEST: usize = 3200;
const METHOD: &str = "auto";
/// Go on to `FINEST` if the last doubling changed the max tip speed by more.
const GO_ON: f64 = 5e-4;
const RTOL: f64 = 1e-9;
const OUTPUT_DT: f64 = 0.01;
const TOLS: [f64; 2] = [1e-2, 1e-3];

pub struct Convergence;

impl Make for Convergence {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes = SCENES
            .iter()
            .map(|&name| {
                Ok((
                    name,
                    ctx.scene(name, &[format!("run.output_dt={OUTPUT_DT}")])?,
                ))
            })
            .collect::<Result<Vec<_>, String>>()?;
        let options = convergence::LadderOptions {
            ladder: &LADDER,
            finest: FINEST,
            go_on: GO_ON,
            method: METHOD,
            rtol: RTOL,
            tols: TOLS,
        };
        let (csv, summary, notes) = ctx
            .pool()?
            .install(|| convergence::ladders(&scenes, &options))?;
        for n in notes {
            println!("  {}: {n}", fig.id);
        }
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &csv)?,
            ctx.write(&format!("{}-summary.csv", fig.id), &summary)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let (scene, links, vmax) = (t.strs("scene")?, t.nums("links")?, t.nums("tip_speed_max")?);
        let reference = t.nums("reference_links")?;
        let (dev_v, dev_path) = (t.nums("dev_tip_speed_max")?, t.nums("dev_tip_path")?);
        let sm = ctx.read(&format!("{}-summary.csv", fig.id))?;
        let (sm_scene, n1, n01) = (
            sm.strs("scene")?,
            sm.strs("n_vmax_1pct")?,
            sm.strs("n_vmax_0.1pct")?,
        );
        let (mass, eta) = (sm.nums("total_mass")?, sm.nums("bending_viscosity")?);
        let scenes = distinct(&scene);
        let ladder = |s: &str| -> Vec<usize> { (0..t.len()).filter(|&k| scene[k] == s).collect() };
        let longest = scenes
            .iter()
            .map(|s| ladder(s))
            .max_by_key(Vec::len)
            .unwrap_or_default();
        let x_label = format!(
            "n (rods: {})",
            longest
                .iter()
                .map(|&k| links[k].to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
        let mut left = LinePlot::new("maximum tip speed", &x_label, "max tip speed |v|");
        left.log_x = true;
        let mut right = LinePlot::new(
            "relative deviation from the reference n",
            &x_label,
            "relative deviation",
        );
        right.log_x = true;
        right.log_y = true;
        let gray = RGBColor(120, 120, 120);
        let top = vmax.iter().copied().fold(0.0, f64::max);
        let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
        for (s, name) in scenes.iter().enumerate() {
            let rows = ladder(name);
            let reference_n = rows.first().map_or(0.0, |&k| reference[k]);
            left.series.push(
                Series::new(
                    *name,
                    rows.iter().map(|&k| (links[k], vmax[k])).collect(),
                    Style::LinePoints,
                )
                .with_color(palette(s)),
            );
            let below: Vec<usize> = rows
                .into_iter()
                .filter(|&k| links[k] != reference[k])
                .collect();
            for &k in &below {
                for v in [dev_v[k], dev_path[k]] {
                    if v > 0.0 && v.is_finite() {
                        lo = lo.min(v);
                        hi = hi.max(v);
                    }
                }
            }
            right.series.push(
                Series::new(
                    format!("{name}: max tip speed (reference: n = {reference_n})"),
                    below.iter().map(|&k| (links[k], dev_v[k])).collect(),
                    Style::LinePoints,
                )
                .with_color(palette(s)),
            );
            right.series.push(
                Series::new(
                    format!("{name}: tip path / L"),
                    below.iter().map(|&k| (links[k], dev_path[k])).collect(),
                    Style::Dashed,
                )
                .with_color(palette(s)),
            );
        }
        for (tol, label) in [(TOLS[0], "1% and 0.1%"), (TOLS[1], "")] {
            right.series.push(
                Series::new(label, vec![(20.0, tol), (4000.0, tol)], Style::Dashed)
                    .with_color(gray),
            );
        }
        right.x_range = Some((20.0, 4000.0));
        left.x_range = Some((20.0, 4000.0));
        left.annotations = vec!["n for max tip speed within 1% / 0.1%:".to_string()];
        for k in 0..sm.len() {
            left.annotations
                .push(format!("{}: {} / {}", sm_scene[k], n1[k], n01[k]));
        }
        if !sm.is_empty() {
            left.annotations.push(format!(
                "m = M/n, r = eta n/L: M = {}, eta = {:.1e}",
                mass[0], eta[0]
            ));
        }
        // Room above the data for the boxes; on the right, half a decade
        // below the smallest deviation and room above for the legend.
        left.y_range = Some((0.0, 1.75 * top));
        if lo.is_finite() {
            let (a, b) = ((lo / 10f64.sqrt()).log10().floor(), (hi * 3.0).log10());
            right.y_range = Some((10f64.powf(a), 10f64.powf(b + 0.75 * (b - a))));
        }
        let title = "Convergence in n at fixed total mass and bending viscosity (auto, rtol 1e-9)";
        let out = figures::line_plot_pair(&left, &right, title, &ctx.stem(fig.id))
            .map_err(|e| format!("{}: {e}", fig.id))?;
        Ok(ctx.drawn(&out))
    }
}
