//! The drawing of the convergence in n (`crate::convergence::ladders`).

use std::path::Path;

use figures::{palette, LinePlot, Output, RGBColor, Series, Style};

use super::Reader;
use crate::convergence::TOLS;
use fc_csv::table::distinct;

/// Draws `convergence`'s tables to `<stem>.png` and `.svg`.
pub fn convergence_n(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (scene, links, vmax) = (t.strs("scene")?, t.nums("links")?, t.nums("tip_speed_max")?);
    let reference = t.nums("reference_links")?;
    let (dev_v, dev_path) = (t.nums("dev_tip_speed_max")?, t.nums("dev_tip_path")?);
    let sm = read("-summary")?;
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
    let mut references = vec![];
    for (s, name) in scenes.iter().enumerate() {
        let rows = ladder(name);
        let reference_n = rows.first().map_or(0.0, |&k| reference[k]);
        // The scenes' names are in the right panel's legend, in the same
        // colours.
        left.series.push(
            Series::new(
                "",
                rows.iter().map(|&k| (links[k], vmax[k])).collect(),
                Style::LinePoints,
            )
            .with_color(palette(s)),
        );
        let below: Vec<usize> = rows
            .into_iter()
            .filter(|&k| links[k] != reference[k])
            .collect();
        references.push(reference_n);
        right.series.push(
            Series::new(
                *name,
                below.iter().map(|&k| (links[k], dev_v[k])).collect(),
                Style::LinePoints,
            )
            .with_color(palette(s)),
        );
        right.series.push(
            Series::new(
                "",
                below.iter().map(|&k| (links[k], dev_path[k])).collect(),
                Style::Dashed,
            )
            .with_color(palette(s)),
        );
    }
    let (x0, x1) = (20.0, 2000.0);
    right.series.push(
        Series::new("dashed: tip path / L", vec![], Style::Dashed).with_color(RGBColor(0, 0, 0)),
    );
    for (tol, label) in [(TOLS[0], "1% and 0.1%"), (TOLS[1], "")] {
        right
            .series
            .push(Series::new(label, vec![(x0, tol), (x1, tol)], Style::Dashed).with_color(gray));
    }
    let names: Vec<String> = references.iter().map(|r| r.to_string()).collect();
    let reference = distinct(&names.iter().map(String::as_str).collect::<Vec<_>>()).join(", ");
    right.annotations = vec![
        "solid: max tip speed".to_string(),
        format!("against the reference n = {reference}"),
    ];
    right.x_range = Some((x0, x1));
    left.x_range = Some((x0, x1));
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
    // The speeds from zero; the deviations fitted (the boxes go where
    // they hide no data, beside the plots if need be).
    left.y_range = Some((0.0, 1.04 * top));
    let title = "Convergence in n at fixed total mass and bending viscosity (auto, rtol 1e-9)";
    let out = figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())?;
    Ok(out)
}
