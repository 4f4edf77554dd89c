//! The drawings of the energy budget and the normal modes
//! (`crate::study::validation`).

use std::path::Path;

use figures::{palette, LinePlot, Output, Series, Style};

use super::Reader;
use crate::study::table::distinct;

/// Draws `energy`'s tables to `<stem>.png` and `.svg`.
pub fn energy_budget(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
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
        if crate::study::table::parse_num(r)? > 0.0 {
            let w = rows
                .iter()
                .map(|&k| (time[k], dissipated[k] / scale[k]))
                .collect();
            left.series
                .push(Series::new(format!("W, r = {r}"), w, Style::Dashed).with_color(palette(i)));
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
    let out = figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())?;
    Ok(out)
}

/// Draws `modes`'s tables to `<stem>.png` and `.svg`.
pub fn normal_modes(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (links, mode, rel) = (t.nums("links")?, t.strs("mode")?, t.nums("relative_error")?);
    let (omega, bessel) = (
        t.nums("omega_sqrt_L_over_g")?,
        t.nums("omega_bessel_sqrt_L_over_g")?,
    );
    let f = read("-fit")?;
    let (fit_mode, order, coefficient) =
        (f.strs("mode")?, f.nums("order")?, f.nums("coefficient")?);
    let fit_from = f.strs("fit_from_links")?.first().copied().unwrap_or("?");
    let mut left = LinePlot::new(
        "frequencies against the continuum",
        "n (rods)",
        "omega sqrt(L/g)",
    );
    left.log_x = true;
    let mut right = LinePlot::new(
        "relative error (all positive: the chain is stiffer)",
        "n (rods)",
        "omega_n / omega_Bessel - 1",
    );
    right.log_x = true;
    right.log_y = true;
    let mut notes = vec![format!("fit over n >= {fit_from}: error = C / n^p")];
    for (k, m) in distinct(&mode).into_iter().enumerate() {
        let rows: Vec<usize> = (0..t.len()).filter(|&j| mode[j] == m).collect();
        if let Some(j) = fit_mode.iter().position(|x| *x == m) {
            notes.push(format!(
                "mode {m}: p = {:.3}, C = {:.4}",
                order[j], coefficient[j]
            ));
        }
        left.series.push(
            Series::new(
                format!("mode {m}"),
                rows.iter().map(|&j| (links[j], omega[j])).collect(),
                Style::LinePoints,
            )
            .with_color(palette(k)),
        );
        let b = bessel[rows[0]];
        left.series.push(
            Series::new(
                if k == 0 { "j_0k / 2 (continuum)" } else { "" },
                vec![(8.0, b), (500.0, b)],
                Style::Dashed,
            )
            .with_color(palette(k)),
        );
        right.series.push(
            Series::new(
                format!("mode {m}"),
                rows.iter().map(|&j| (links[j], rel[j])).collect(),
                Style::LinePoints,
            )
            .with_color(palette(k)),
        );
    }
    left.x_range = Some((8.0, 500.0));
    left.y_range = Some((0.0, 15.0));
    right.x_range = Some((8.0, 500.0));
    right.y_range = Some((1e-8, 1e5));
    right.annotations = notes;
    let title = "Small oscillations of the hanging chain: n rods against the Bessel zeros";
    let out = figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())?;
    Ok(out)
}
