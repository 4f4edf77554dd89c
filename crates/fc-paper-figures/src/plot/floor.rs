//! The drawings of the floor's figures: the U onto a floor
//! (`crate::floor_u`: the chain at a few times over the floor's line, and
//! the released end's speed with and without the floor) and the floor's
//! closed forms (`crate::floor_checks`: one rod's impact against the
//! contact stiffness, a chain on a slope against the friction angle) and
//! Cayley's scale on both floor laws (`crate::cayley_single`: the
//! windows' force against time beside the ideal `3 mu g x`).

use std::path::Path;

use figures::{cool, palette, LinePlot, Marker, Output, RGBColor, Series, Style};

use super::Reader;

pub fn floor_span_d3(read: Reader, stem: &Path) -> Result<Output, String> {
    let snaps = read("")?;
    let (t, x, y) = (snaps.nums("t")?, snaps.nums("x")?, snaps.nums("y")?);
    let mut left = LinePlot::new("the chain at t = 0 .. 4.157 over the floor", "x", "y");
    left.equal_aspect = true;
    let mut times: Vec<f64> = t.iter().copied().filter(|&s| s >= 0.0).collect();
    times.dedup();
    let last = times.last().copied().unwrap_or(1.0);
    for &s in &times {
        let pts = (0..snaps.len())
            .filter(|&j| t[j] == s)
            .map(|j| (x[j], y[j]))
            .collect();
        // Every snapshot keyed by its time (only the first and last were).
        let label = format!("t = {s:.2}");
        left.series
            .push(Series::new(label, pts, Style::Line).with_color(cool(s / last)));
    }
    let floor = (0..snaps.len())
        .filter(|&j| t[j] < 0.0)
        .map(|j| (x[j], y[j]))
        .collect();
    left.series
        .push(Series::new("floor", floor, Style::Dashed).with_color(palette(7)));

    let series = read("-series")?;
    let (scene, st, v) = (
        series.strs("scene")?,
        series.nums("t")?,
        series.nums("tip_speed")?,
    );
    let mut right = LinePlot::new("the released end's speed", "t", "tip speed |v|");
    for (i, (name, label)) in [
        ("span-d3", "no floor (the whip)"),
        ("span-d3-floor", "floor at y = -3"),
    ]
    .into_iter()
    .enumerate()
    {
        let pts = (0..series.len())
            .filter(|&j| scene[j] == name)
            .map(|j| (st[j], v[j]))
            .collect();
        right
            .series
            .push(Series::new(label, pts, Style::Line).with_color(palette(i)));
    }
    figures::line_plot_pair(
        &left,
        &right,
        "The report's U (span d = 3, n = 50) onto a floor: the whip does not form",
        stem,
    )
    .map_err(|e| e.to_string())
}

pub fn floor_checks(read: Reader, stem: &Path) -> Result<Output, String> {
    let rod = read("")?;
    let (theta, k, err) = (
        rod.nums("theta")?,
        rod.nums("stiffness")?,
        rod.nums("relative_error")?,
    );
    let mut left = LinePlot::new(
        "one rod's plastic impact: far end against the closed form",
        "contact stiffness k (m g / l units)",
        "|v_far / (6 v cos^2 th / (1 + 3 cos^2 th)) - 1|",
    );
    let mut thetas = theta.clone();
    thetas.dedup();
    let markers = [
        Marker::Circle,
        Marker::Square,
        Marker::Triangle,
        Marker::Diamond,
    ];
    for (i, &th) in thetas.iter().enumerate() {
        let pts = (0..rod.len())
            .filter(|&j| theta[j] == th)
            .map(|j| (k[j], err[j]))
            .collect();
        left.series.push(
            Series::new(format!("theta = {th} rad"), pts, Style::LinePoints)
                .with_color(palette(i))
                .with_marker(markers[i % markers.len()]),
        );
    }
    left.log_x = true;
    left.log_y = true;

    let sl = read("-slope")?;
    let (a, mu, t, v, law) = (
        sl.nums("slope")?,
        sl.nums("friction")?,
        sl.nums("t")?,
        sl.nums("speed")?,
        sl.nums("closed_form")?,
    );
    let normal = sl.nums("normal_over_weight")?;
    let mut right = LinePlot::new(
        "a chain laid on a slope a, friction mu = 0.5",
        "t",
        "centre of mass |v| (along it)",
    );
    right.log_y = true;
    let mut cases: Vec<(f64, f64)> = (0..sl.len()).map(|j| (a[j], mu[j])).collect();
    cases.dedup();
    for (i, &(s, m)) in cases.iter().enumerate() {
        let rows: Vec<usize> = (0..sl.len())
            .filter(|&j| a[j] == s && mu[j] == m && t[j] > 0.0)
            .collect();
        if s == 0.0 {
            // At rest: far below the others' scale, so said in numbers.
            let fastest = rows.iter().map(|&j| v[j].abs()).fold(0.0, f64::max);
            // Once it has sunk to its static deflection.
            let carried = rows
                .iter()
                .filter(|&&j| t[j] >= 0.5)
                .map(|&j| (normal[j] - 1.0).abs())
                .fold(0.0, f64::max);
            right.annotations = vec![
                format!("level floor: |speed| <= {fastest:.0e};"),
                format!("from t = 0.5 the floor carries its weight to {carried:.0e}"),
            ];
            continue;
        }
        let side = if s.tan() < m {
            "below the friction angle"
        } else {
            "above it"
        };
        // How far the run is from its closed form, said in its label.
        let gap = rows
            .iter()
            .filter(|&&j| law[j] != 0.0)
            .map(|&j| ((v[j].abs() - law[j].abs()) / law[j].abs()).abs())
            .fold(0.0, f64::max);
        right.series.push(
            Series::new(
                format!("a = {s} ({side}): law to {gap:.0e}"),
                rows.iter().map(|&j| (t[j], v[j].abs())).collect(),
                Style::Line,
            )
            .with_color(palette(i)),
        );
        // The closed form as open marks at about 12 times: a line on the
        // run's line would hide under it.
        let every = (rows.len() / 12).max(1);
        right.series.push(
            Series::new(
                "",
                rows.iter()
                    .step_by(every)
                    .map(|&j| (t[j], law[j].abs()))
                    .collect(),
                Style::Points,
            )
            .with_color(palette(i))
            .hollow(),
        );
    }
    right.series.push(
        Series::legend_only("open marks: the laws (creep, slide)", Style::Points)
            .with_color(RGBColor(60, 60, 60))
            .hollow(),
    );
    figures::line_plot_pair(&left, &right, "The floor against its closed forms", stem)
        .map_err(|e| e.to_string())
}

/// Cayley's scale at one `n` on both floors (`crate::cayley_single`):
/// left, the floor's force over the weight averaged over each window
/// against time, each law's run beside the ideal `3 mu g x`; right, the
/// same windows as readings (force over the ideal's), with each run's
/// mean and scatter in the legend.
pub fn cayley_floors(read: Reader, stem: &Path) -> Result<Output, String> {
    let w = read("")?;
    let sum = read("-summary")?;
    let (law, t, reading, force) = (
        w.strs("law")?,
        w.nums("t")?,
        w.nums("reading")?,
        w.nums("force_over_weight")?,
    );
    let (s_law, s_method, s_acc, s_mean, s_scatter, s_links) = (
        sum.strs("law")?,
        sum.strs("method")?,
        sum.strs("accuracy")?,
        sum.nums("reading")?,
        sum.nums("scatter")?,
        sum.nums("links")?,
    );
    let links = s_links.first().copied().unwrap_or(0.0);
    let mut left = LinePlot::new(
        "the floor's force averaged over windows of 0.05",
        "t (units of sqrt(L/g))",
        "force / (M g)",
    );
    let mut right = LinePlot::new(
        "the reading: force over the ideal's, per window",
        "t (units of sqrt(L/g))",
        "force / (3 mu g x)",
    );
    let markers = [Marker::Circle, Marker::Square];
    for (i, ((l, m), a)) in s_law.iter().zip(&s_method).zip(&s_acc).enumerate() {
        let rows: Vec<usize> = (0..w.len()).filter(|&j| &law[j] == l).collect();
        let step = if *m == "moreau-jean" { "dt" } else { "rtol" };
        let name = format!("{l} floor ({m}, {step} {a})");
        left.series.push(
            Series::new(
                name.clone(),
                rows.iter().map(|&j| (t[j], force[j])).collect(),
                Style::LinePoints,
            )
            .with_color(palette(i))
            .with_marker(markers[i % markers.len()]),
        );
        right.series.push(
            Series::new(
                format!("{name}: {:.3} +- {:.3}", s_mean[i], s_scatter[i]),
                rows.iter().map(|&j| (t[j], reading[j])).collect(),
                Style::LinePoints,
            )
            .with_color(palette(i))
            .with_marker(markers[i % markers.len()]),
        );
    }
    let (t0, t1) = (0.275, 1.225);
    let ideal: Vec<(f64, f64)> = (0..=100)
        .map(|k| {
            let s = t0 + (t1 - t0) * k as f64 / 100.0;
            (s, 1.5 * s * s)
        })
        .collect();
    left.series.push(
        Series::new("ideal 3 mu g x, x = g t^2 / 2", ideal, Style::Dashed).with_color(palette(7)),
    );
    right.series.push(
        Series::new("ideal", vec![(t0, 1.0), (t1, 1.0)], Style::Dashed).with_color(palette(7)),
    );
    figures::line_plot_pair(
        &left,
        &right,
        &format!(
            "Cayley's scale, n = {links}: the constraint floor, the penalty floor and the ideal"
        ),
        stem,
    )
    .map_err(|e| e.to_string())
}
