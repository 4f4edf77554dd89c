//! The drawings of the folded chain's tables (`crate::folded`):
//! its fall against the law, the force on the pivot, the tip's
//! acceleration.

use std::path::Path;

use figures::{palette, LinePlot, Marker, Output, RGBColor, Series, Style};

use super::Reader;
use crate::folded::{FORCE_LAW_TO, WINDOW};
use fc_csv::table::distinct;

/// The running means drawn (all are in the data): the finest run's, whose
/// comparison with the law a coarser mean's pulses would hide.
const SHOWN: [usize; 1] = [400];
/// The run whose raw force is drawn (light, under the means).
const RAW: &str = "400";

pub fn vs_law(read: Reader, stem: &Path) -> Result<Output, String> {
    let c = read("")?;
    let (links, x, v) = (
        c.strs("links")?,
        c.nums("x_over_L")?,
        c.nums("v_over_sqrt_gL")?,
    );
    let tm = read("-times")?;
    let (t_links, t_xi) = (tm.nums("links")?, tm.strs("xi")?);
    let (rel_start, rel_pivot) = (
        tm.nums("rel_from_start_height")?,
        tm.nums("rel_from_pivot_height")?,
    );
    let t_law = tm.nums("t_law_over_sqrt_L_over_g")?;
    let law = read("-law")?;
    let (law_xi, law_v, free_v) = (
        law.nums("xi")?,
        law.nums("v_law_over_sqrt_gL")?,
        law.nums("v_free_fall_over_sqrt_gL")?,
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
    for (i, n) in distinct(&links).into_iter().enumerate() {
        left.series.push(
            Series::line(
                format!("n = {n}"),
                (0..c.len())
                    .filter(|&k| links[k] == n)
                    .map(|k| (x[k], v[k]))
                    .collect(),
            )
            .with_color(palette(i)),
        );
    }
    let black = RGBColor(0, 0, 0);
    let gray = RGBColor(120, 120, 120);
    let pairs = |ys: &[f64]| law_xi.iter().copied().zip(ys.iter().copied()).collect();
    left.series.push(
        Series::new(
            "law: v^2 = g x (2L - x)/(L - x)",
            pairs(&law_v),
            Style::Dashed,
        )
        .with_color(black),
    );
    left.series.push(
        Series::new("free fall: v^2 = 2 g x", pairs(&free_v), Style::Dashed).with_color(gray),
    );
    let top = v.iter().copied().fold(0.0, f64::max);
    left.y_range = Some((0.0, 1.05 * top));
    left.x_range = Some((0.0, 1.0));
    let mut title_law = vec![];
    for (k, xi) in distinct(&t_xi).into_iter().enumerate() {
        let rows: Vec<usize> = (0..tm.len()).filter(|&j| t_xi[j] == xi).collect();
        title_law.push(t_law[rows[0]]);
        let label = if xi == "0.5" { "L/2" } else { "0.9 L" };
        right.series.push(
            Series::new(
                format!("{label}, x from the free end's start"),
                rows.iter()
                    .map(|&j| (t_links[j], 100.0 * rel_start[j]))
                    .collect(),
                Style::LinePoints,
            )
            .with_color(palette(k)),
        );
        right.series.push(
            Series::new(
                format!("{label}, x from the pivot's height"),
                rows.iter()
                    .map(|&j| (t_links[j], 100.0 * rel_pivot[j]))
                    .collect(),
                Style::DashedPoints,
            )
            .with_color(palette(k))
            .with_marker(Marker::Square)
            .hollow(),
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
    let [half, most] = title_law[..] else {
        return Err("the times table: expected two fall distances".to_string());
    };
    let title = format!(
        "Folded chain, r = 0: the law's t(L/2) = {half:.4} sqrt(L/g), t(0.9 L) = {most:.4} sqrt(L/g)"
    );
    let out = figures::line_plot_pair(&left, &right, &title, stem).map_err(|e| e.to_string())?;
    Ok(out)
}

pub fn support_force(read: Reader, stem: &Path) -> Result<Output, String> {
    let d = read("")?;
    let (scene, links, t, xi) = (
        d.strs("scene")?,
        d.strs("links")?,
        d.nums("t")?,
        d.nums("xi")?,
    );
    let (fx, fy) = (
        d.nums("pivot_force_x_over_Mg")?,
        d.nums("pivot_force_y_over_Mg")?,
    );
    let (mean, law_mean) = (
        d.nums("running_mean_y_over_Mg")?,
        d.nums("law_running_mean_over_Mg")?,
    );
    let (p, law_p) = (
        d.nums("momentum_y_over_M_sqrt_gL")?,
        d.nums("law_momentum_y_over_M_sqrt_gL")?,
    );
    let law = read("-law")?;
    let (law_xi, law_f) = (law.nums("xi")?, law.nums("law_over_Mg")?);

    let mut left = LinePlot::new(
        "folded chain, r = 0: vertical pull against ξ",
        "ξ = x / L (fall x of the free end from its start, chain length L)",
        "vertical pull on P₀, downward / (M g)",
    );
    let mut right = LinePlot::new(
        "span d = 3 (n = 50, r = 5e-4): pull against time t",
        "t",
        "pull on P₀ / (M g)",
    );
    let light = RGBColor(200, 200, 200);
    let mut momentum_notes = vec![];
    let folded: Vec<usize> = (0..d.len()).filter(|&k| scene[k] == "folded").collect();
    let ns = distinct(&folded.iter().map(|&k| links[k]).collect::<Vec<_>>());
    for (i, n) in ns.iter().enumerate() {
        let rows: Vec<usize> = folded.iter().copied().filter(|&k| links[k] == *n).collect();
        // The momentum from the impulse against the law's at xi = 0.5.
        if let Some(&h) = rows.iter().find(|&&k| xi[k] >= 0.5).or(rows.last()) {
            momentum_notes.push(format!(
                "{:+.1}% (n = {n})",
                100.0 * (p[h] / law_p[h] - 1.0)
            ));
        }
        if *n == RAW {
            // The raw force of one n, to show the clicks the means smooth.
            left.series.insert(
                0,
                Series::line(
                    format!("n = {n}, raw"),
                    rows.iter().map(|&k| (xi[k], fy[k])).collect(),
                )
                .with_color(light),
            );
        }
        let averaged: Vec<usize> = rows
            .iter()
            .copied()
            .filter(|&k| mean[k].is_finite() && law_mean[k].is_finite() && xi[k] <= 0.95)
            .collect();
        if SHOWN.iter().any(|s| s.to_string() == *n) {
            left.series.push(
                Series::line(
                    format!("n = {n}, mean"),
                    averaged.iter().map(|&k| (xi[k], mean[k])).collect(),
                )
                .with_color(palette(i)),
            );
        }
    }
    let black = RGBColor(0, 0, 0);
    left.series.push(
        Series::new(
            format!("law (drawn to ξ = {FORCE_LAW_TO}; → ∞ as ξ → 1)"),
            law_xi.iter().copied().zip(law_f.iter().copied()).collect(),
            Style::Dashed,
        )
        .with_color(black),
    );
    // A log axis: the raw pulses (up to some 300 M g near the end of the
    // fall) and the law's rise stay in the frame.
    left.x_range = Some((0.0, 1.0));
    left.log_y = true;
    // Above the raw force's peak, a decade and a half for the legend and
    // the note: on a log axis that costs a third of the height, where
    // beside the plot they would take two thirds of it.
    let raw_top = folded
        .iter()
        .filter(|&&k| links[k] == RAW)
        .map(|&k| fy[k])
        .fold(1.0, f64::max);
    left.y_range = Some((0.3, 30.0 * raw_top));

    left.annotations = vec![
        format!("mean: over {WINDOW} time units"),
        "momentum at ξ = 0.5".to_string(),
        "against the law's:".to_string(),
    ];
    left.annotations.extend(momentum_notes);

    let span: Vec<usize> = (0..d.len()).filter(|&k| scene[k] == "span-d3").collect();
    right.series.push(
        Series::line(
            "vertical (downward)",
            span.iter().map(|&k| (t[k], fy[k])).collect(),
        )
        .with_color(palette(5)),
    );
    right.series.push(
        Series::new(
            "horizontal",
            span.iter().map(|&k| (t[k], -fx[k])).collect(),
            Style::Dashed,
        )
        .with_color(palette(5)),
    );
    let peak = |f: &dyn Fn(usize) -> f64| span.iter().map(|&k| f(k)).fold(0.0, f64::max);
    let top = peak(&|k| fy[k]);
    right.annotations = vec![
        format!("peak vertical pull {top:.2} M g"),
        format!(
            "(peak magnitude |F| {:.2} M g)",
            peak(&|k| fx[k].hypot(fy[k]))
        ),
    ];

    let title = "Force F on the pivot P₀ / weight M g of the chain (mass M): two experiments";
    let out = figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())?;
    Ok(out)
}

/// Where the left panel of the tip's acceleration ends: beyond it the
/// accelerations of the whip swing by thousands of g either way.
const LINEAR_TO: f64 = 0.8;
/// Where the right panel (the ratio to the law) begins.
const RATIO_FROM: f64 = 0.7;

/// Draws `tip_acceleration`'s tables: on linear axes (the accelerations
/// change sign), the acceleration itself up to `xi = LINEAR_TO`, and from
/// `xi = RATIO_FROM` to the end the means of the `-at` table over the
/// law's (marks, on a range fitted to them), over every sample's ratio
/// drawn light behind them (clipped to that range; its extremes named).
pub fn tip_acceleration(read: Reader, stem: &Path) -> Result<Output, String> {
    let c = read("")?;
    let (links, xi, a, law) = (
        c.strs("links")?,
        c.nums("xi")?,
        c.nums("accel_over_g")?,
        c.nums("law_over_g")?,
    );
    let at = read("-at")?;
    let (at_links, at_xi, at_mean, at_law_mean) = (
        at.strs("links")?,
        at.nums("xi")?,
        at.nums("accel_mean_over_g")?,
        at.nums("law_mean_over_g")?,
    );
    let mut left = LinePlot::new(
        "downward tip acceleration, ξ ≤ 0.8",
        "ξ = x / L (fall of the free end from its start)",
        "downward tip acceleration / g",
    );
    let mut right = LinePlot::new(
        "ξ ≥ 0.7: window means over the law's",
        "ξ = x / L",
        "tip acceleration / the law's",
    );
    let names = distinct(&links);
    let marks = [Marker::Circle, Marker::Square, Marker::Diamond];
    // The range of the means and of the samples' ratio on the right.
    let (mut m_lo, mut m_hi) = (0.0f64, 1.0f64);
    let (mut s_lo, mut s_hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut means_series = vec![];
    for (i, n) in names.iter().enumerate() {
        let rows: Vec<usize> = (0..c.len()).filter(|&k| links[k] == *n).collect();
        let near: Vec<(f64, f64)> = rows
            .iter()
            .filter(|&&k| xi[k] <= LINEAR_TO)
            .map(|&k| (xi[k], a[k]))
            .collect();
        left.series.push(
            Series::line(format!("n = {n} (from the dynamics at each sample)"), near)
                .with_color(palette(i)),
        );
        let ratio: Vec<(f64, f64)> = rows
            .iter()
            .filter(|&&k| xi[k] >= RATIO_FROM && law[k].is_finite() && law[k] > 0.0)
            .map(|&k| (xi[k], a[k] / law[k]))
            .collect();
        for p in &ratio {
            s_lo = s_lo.min(p.1);
            s_hi = s_hi.max(p.1);
        }
        right
            .series
            .push(Series::line(format!("n = {n}, samples"), ratio).with_color(light(palette(i))));
        let means: Vec<(f64, f64)> = (0..at.len())
            .filter(|&k| at_links[k] == *n && at_xi[k] >= RATIO_FROM && at_law_mean[k] > 0.0)
            .map(|k| (at_xi[k], at_mean[k] / at_law_mean[k]))
            .collect();
        for p in &means {
            m_lo = m_lo.min(p.1);
            m_hi = m_hi.max(p.1);
        }
        means_series.push(
            // The table's means: over the samples with |xi' - xi| <= the
            // study's window (not the support force's running mean).
            Series::points(
                format!(
                    "n = {n}, means (|ξ' − ξ| ≤ {})",
                    crate::folded::ACCEL_WINDOW
                ),
                means,
            )
            .with_color(palette(i))
            .with_marker(marks[i % marks.len()])
            .hollow(),
        );
    }
    // The law at the finest run's samples.
    let finest = names.last().copied().unwrap_or_default();
    let law_pts: Vec<(f64, f64)> = (0..c.len())
        .filter(|&k| links[k] == finest && xi[k] <= LINEAR_TO)
        .map(|k| (xi[k], law[k]))
        .collect();
    let black = RGBColor(0, 0, 0);
    let gray = RGBColor(120, 120, 120);
    left.series.push(
        Series::new(
            "law: a = g [1 + ξ (2 - ξ) / (2 (1 - ξ)²)]",
            law_pts,
            Style::Dashed,
        )
        .with_color(black),
    );
    left.series.push(
        Series::new(
            "free fall: a = g",
            vec![(0.0, 1.0), (LINEAR_TO, 1.0)],
            Style::Dashed,
        )
        .with_color(gray),
    );
    left.x_range = Some((0.0, LINEAR_TO));
    right.series.push(
        Series::new(
            "the law",
            vec![(RATIO_FROM, 1.0), (1.0, 1.0)],
            Style::Dashed,
        )
        .with_color(black),
    );
    right
        .series
        .push(Series::new("", vec![(RATIO_FROM, 0.0), (1.0, 0.0)], Style::Line).with_color(gray));
    right.series.extend(means_series);
    right.x_range = Some((RATIO_FROM, 1.0));
    let pad = 0.08 * (m_hi - m_lo);
    right.y_range = Some((m_lo - pad, m_hi + pad));
    if s_lo.is_finite() {
        right.annotations = vec![format!(
            "light: every sample's ratio, {s_lo:.0} to {s_hi:.0} (clipped)"
        )];
    }
    let title =
        "Folded chain, r = 0: why the tip beats g (linear axes: the acceleration changes sign)";
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}

/// `c` two thirds of the way to white.
fn light(c: RGBColor) -> RGBColor {
    let f = |v: u8| ((u16::from(v) + 2 * 255) / 3) as u8;
    RGBColor(f(c.0), f(c.1), f(c.2))
}
