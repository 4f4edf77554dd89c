//! `energy-budget`: the energy `E = T + V`, the work `W` dissipated by joint
//! friction (integrated alongside the state, `W' = 2R`) and their sum along
//! the span d = 3 scene, for r = 0, the scene's r and a larger r. With the
//! scene's n = 50 and m = 0.2 per rod, only r changes.

use chain_ode::kinematics::{kinetic_energy, potential_energy};
use figures::{palette, LinePlot, Series, Style};
use rayon::prelude::*;

use super::{figure_files, num, pool, scene, stem, write_data};
use crate::study::Ctx;

const ID: &str = "energy-budget";
const DAMPINGS: [f64; 3] = [0.0, 5e-4, 1e-2];

pub fn make(ctx: &Ctx) -> Result<Vec<String>, String> {
    let runs = pool(ctx)?.install(|| {
        DAMPINGS
            .par_iter()
            .map(|&r| {
                let s = scene(ctx, "span-d3")?
                    .with_overrides(&[
                        format!("chain.damping={r}"),
                        "run.method=\"dopri5\"".to_string(),
                        "run.rtol=1e-10".to_string(),
                        "run.atol=1e-12".to_string(),
                        "run.output_dt=0.01".to_string(),
                    ])
                    .map_err(|e| e.to_string())?;
                let traj = s
                    .prepare()
                    .and_then(|p| p.solve())
                    .map_err(|e| e.to_string())?;
                if !traj.status.is_ok() {
                    return Err(format!("{ID}: r = {r}: status {}", traj.status));
                }
                Ok(traj)
            })
            .collect::<Result<Vec<_>, String>>()
    })?;

    let mut csv = String::from(
        "damping,damping_rate,t,kinetic,potential,energy,dissipated,balance_over_MgL\n",
    );
    let mut left = LinePlot::new("energy change and dissipated work", "t", "energy / (M g L)");
    let mut right = LinePlot::new("energy balance", "t", "|E(t) + W(t) - E(0)| / (M g L)");
    right.log_y = true;
    let mut notes = vec![];
    for (i, traj) in runs.iter().enumerate() {
        let chain = &traj.chain;
        let scale = chain.energy_scale();
        let mut e0 = None;
        let (mut de, mut w, mut bal) = (vec![], vec![], vec![]);
        for s in traj.samples() {
            let t = kinetic_energy(chain, s.angles, s.rates);
            let v = potential_energy(chain, s.angles);
            let e = t + v;
            let e0 = *e0.get_or_insert(e);
            let b = (e + s.dissipated - e0) / scale;
            csv.push_str(&format!(
                "{},{},{},{},{},{},{},{}\n",
                num(chain.damping),
                num(chain.damping_rate()),
                num(s.t),
                num(t),
                num(v),
                num(e),
                num(s.dissipated),
                num(b)
            ));
            de.push((s.t, (e - e0) / scale));
            w.push((s.t, s.dissipated / scale));
            bal.push((s.t, b.abs()));
        }
        let r = chain.damping;
        left.series
            .push(Series::line(format!("E - E(0), r = {r}"), de).with_color(palette(i)));
        if r > 0.0 {
            left.series.push(
                Series::new(format!("W, r = {r}"), w.clone(), Style::Dashed).with_color(palette(i)),
            );
        }
        let worst = bal.iter().map(|b| b.1).fold(0.0, f64::max);
        let w_end = w.last().map_or(0.0, |p| p.1);
        notes.push(format!("r = {r}: {worst:.1e}"));
        println!(
            "  {ID}: r = {r} (r/(m l^2) = {:.3}): W(t_end) = {w_end:.3e} M g L, \
             max |E + W - E(0)| = {worst:.2e} M g L",
            chain.damping_rate()
        );
        right
            .series
            .push(Series::line(format!("r = {r}"), bal).with_color(palette(i)));
    }
    right.annotations = vec!["max over the samples:".to_string()];
    right.annotations.extend(notes);
    right.y_range = Some((1e-17, 1e-9));
    let mut files = vec![write_data(ctx, &format!("{ID}.csv"), &csv)?];
    let title = "Energy budget, span d = 3 (n = 50): dE/dt = -2R, W' = 2R (DOPRI5, rtol 1e-10)";
    figures::line_plot_pair(&left, &right, title, &stem(ctx, ID))
        .map_err(|e| format!("{ID}: {e}"))?;
    files.extend(figure_files(ID));
    Ok(files)
}
