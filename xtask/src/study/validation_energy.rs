//! `energy-budget`: the energy `E = T + V`, the work `W` dissipated by joint
//! friction (integrated alongside the state, `W' = 2R`) and their sum along
//! the span d = 3 scene, for r = 0, the scene's r and a larger r. With the
//! scene's n = 50 and m = 0.2 per rod, only r changes.

use falling_chain::study::validation;
use figures::{palette, LinePlot, Series, Style};
use rayon::prelude::*;

use crate::ctx::Ctx;
use crate::data::distinct;
use crate::registry::{Figure, Make};

const DAMPINGS: [f64; 3] = [0.0, 5e-4, 1e-2];

pub struct EnergyBudget;

impl Make for EnergyBudget {
    /// `energy-budget.csv`: every sample of the three runs.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let runs = ctx.pool()?.install(|| {
            DAMPINGS
                .par_iter()
                .map(|&r| {
                    let s = ctx.scene(
                        "span-d3",
                        &[
                            format!("chain.damping={r}"),
                            "run.method=\"dopri5\"".to_string(),
                            "run.rtol=1e-10".to_string(),
                            "run.atol=1e-12".to_string(),
                            "run.output_dt=0.01".to_string(),
                        ],
                    )?;
                    let traj = s
                        .prepare()
                        .and_then(|p| p.solve())
                        .map_err(|e| e.to_string())?;
                    if !traj.status.is_ok() {
                        return Err(format!("{}: r = {r}: status {}", fig.id, traj.status));
                    }
                    Ok(traj)
                })
                .collect::<Result<Vec<_>, String>>()
        })?;

        let (csv, notes) = validation::energy_budget(&runs);
        for n in notes {
            println!("  {}: {n}", fig.id);
        }
        Ok(vec![ctx.write(&format!("{}.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let damping = t.strs("damping")?;
        let (scale, time) = (t.nums("energy_scale")?, t.nums("t")?);
        let (energy, dissipated, balance) = (
            t.nums("energy")?,
            t.nums("dissipated")?,
            t.nums("balance_over_MgL")?,
        );
        let mut left = LinePlot::new("energy change and dissipated work", "t", "energy / (M g L)");
        let mut right = LinePlot::new("energy balance", "t", "|E(t) + W(t) - E(0)| / (M g L)");
        right.log_y = true;
        let mut notes = vec![];
        for (i, r) in distinct(&damping).into_iter().enumerate() {
            let rows: Vec<usize> = (0..t.len()).filter(|&k| damping[k] == r).collect();
            let e0 = energy[rows[0]];
            let de = rows
                .iter()
                .map(|&k| (time[k], (energy[k] - e0) / scale[k]))
                .collect();
            left.series
                .push(Series::line(format!("E - E(0), r = {r}"), de).with_color(palette(i)));
            if crate::data::parse_num(r)? > 0.0 {
                let w = rows
                    .iter()
                    .map(|&k| (time[k], dissipated[k] / scale[k]))
                    .collect();
                left.series.push(
                    Series::new(format!("W, r = {r}"), w, Style::Dashed).with_color(palette(i)),
                );
            }
            let bal: Vec<(f64, f64)> = rows.iter().map(|&k| (time[k], balance[k].abs())).collect();
            let worst = bal.iter().map(|b| b.1).fold(0.0, f64::max);
            notes.push(format!("r = {r}: {worst:.1e}"));
            right
                .series
                .push(Series::line(format!("r = {r}"), bal).with_color(palette(i)));
        }
        right.annotations = vec!["max over the samples:".to_string()];
        right.annotations.extend(notes);
        right.y_range = Some((1e-17, 1e-9));
        let title = "Energy budget, span d = 3 (n = 50): dE/dt = -2R, W' = 2R (DOPRI5, rtol 1e-10)";
        let out = figures::line_plot_pair(&left, &right, title, &ctx.stem(fig.id))
            .map_err(|e| format!("{}: {e}", fig.id))?;
        Ok(ctx.drawn(&out))
    }
}
