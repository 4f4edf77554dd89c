//! The drawings of the wall-time studies: speed-ups at matched accuracy
//! (`crate::matched`), the cost of a right-hand side
//! (`crate::rhs_cost`); where BDF pays is [`super::stiffness`].

use std::path::Path;

use figures::{palette, LinePlot, Marker, Output, RGBColor, Series, Style};

use super::Reader;
use crate::rhs_cost::FIT_FROM;
use fc_csv::table::distinct;

/// The slope guides run this factor below the measured points.
const GUIDE_OFFSET: f64 = 3.0;

/// Draws `matched`'s tables to `<stem>.png` and `.svg`: for each pair
/// `a/b` (a colour) and scene (a line style), how many times faster `a` is
/// than `b` at matched error (`wall_b / wall_a`), with the line of equal
/// times, below which `a` is the slower.
pub fn matched(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("-timing")?;
    let (scene, pair, err, ratio) = (
        t.strs("scene")?,
        t.strs("pair")?,
        t.nums("error")?,
        t.nums("b_over_a")?,
    );
    let mut p = LinePlot::new(
        "Speed-up of a over b at matched error",
        "error max(err_tip, err_vmax)",
        "speed-up of a over b (b's time / a's)",
    );
    p.log_x = true;
    p.log_y = true;
    let styles = [Style::LinePoints, Style::DashedPoints, Style::Line];
    let marks = [Marker::Circle, Marker::Square, Marker::Circle];
    let (mut e_lo, mut e_hi) = (f64::INFINITY, 0.0f64);
    for (i, pr) in distinct(&pair).into_iter().enumerate() {
        let (a, b) = pr.split_once('/').unwrap_or((pr, ""));
        for (j, sc) in distinct(&scene).into_iter().enumerate() {
            let pts: Vec<(f64, f64)> = (0..t.len())
                .filter(|&k| pair[k] == pr && scene[k] == sc)
                .map(|k| (err[k], ratio[k]))
                .collect();
            if pts.is_empty() {
                continue;
            }
            for q in &pts {
                e_lo = e_lo.min(q.0);
                e_hi = e_hi.max(q.0);
            }
            let mut series = Series::new(
                format!("a = {a}, b = {b}: {}", sc.trim_start_matches("wp-")),
                pts,
                styles[j % styles.len()],
            )
            .with_color(palette(i))
            .with_marker(marks[j % marks.len()]);
            if j % styles.len() == 1 {
                series = series.hollow();
            }
            p.series.push(series);
        }
    }
    if e_lo.is_finite() {
        p.series.push(
            Series::new(
                "equal times: below it, a is the slower",
                vec![(e_lo, 1.0), (e_hi, 1.0)],
                Style::Dashed,
            )
            .with_color(RGBColor(0, 0, 0)),
        );
    }
    figures::line_plot(&p, stem).map_err(|e| e.to_string())
}

/// Draws `cost`'s tables to `<stem>.png` and `.svg`.
pub fn rhs_cost(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("-timing")?;
    let (solver, n, secs) = (t.strs("solver")?, t.nums("n")?, t.nums("seconds_per_call")?);
    let f = read("-fit-timing")?;
    let (fit_solver, fit_slope) = (f.strs("solver")?, f.nums("slope")?);
    let slope = |kind: &str| {
        fit_solver
            .iter()
            .position(|s| *s == kind)
            .map_or(f64::NAN, |k| fit_slope[k])
    };
    let (slope_fast, slope_dense) = (slope("recursion"), slope("dense"));
    let (slope_assembly, slope_factor) = (slope("dense-assembly"), slope("dense-minus-assembly"));
    let pts = |kind: &str| -> Vec<(f64, f64)> {
        (0..t.len())
            .filter(|&k| solver[k] == kind)
            .map(|k| (n[k], secs[k]))
            .collect()
    };
    let (fast, dense_pts, assembly) = (pts("recursion"), pts("dense"), pts("dense-assembly"));
    if fast.is_empty() || dense_pts.is_empty() {
        return Err(format!("{}: no recursion or dense rows", t.name));
    }

    // The figure: measured points, and reference slopes n and n^3
    // through the last measured point of each, a factor GUIDE_OFFSET below.
    let guide = |p: &[(f64, f64)], k: i32, ns: &[f64]| -> Vec<(f64, f64)> {
        let (n1, t1) = p[p.len() - 1];
        ns.iter()
            .map(|&n| (n, t1 / GUIDE_OFFSET * (n / n1).powi(k)))
            .collect()
    };
    let mut plot = LinePlot::new(
        "Cost of one right-hand side",
        "rods n",
        "seconds per evaluation (median)",
    );
    plot.log_x = true;
    plot.log_y = true;
    plot.series.push(
        Series::new(
            format!("O(n) recursion (ChainSystem::rhs): slope {slope_fast:.2}"),
            fast.clone(),
            Style::LinePoints,
        )
        .with_color(palette(0)),
    );
    plot.series.push(
        Series::new(
            format!("dense: assemble A, b + Cholesky (faer): slope {slope_dense:.2}"),
            dense_pts.clone(),
            Style::LinePoints,
        )
        .with_color(palette(3)),
    );
    plot.series.push(
        Series::new(
            format!("dense, assembly of A and b only: slope {slope_assembly:.2}"),
            assembly,
            Style::LinePoints,
        )
        .with_color(palette(1)),
    );
    plot.series.push(
        Series::new("∝ n", guide(&fast, 1, &[25.0, 10000.0]), Style::Dashed).with_color(palette(0)),
    );
    plot.series.push(
        Series::new(
            "∝ n³",
            guide(&dense_pts, 3, &[100.0, 1000.0]),
            Style::Dashed,
        )
        .with_color(palette(3)),
    );
    // The fit's range and the factorisation's own slope in the note box,
    // not as swatchless legend lines (which made the legend as tall as the
    // plot). The dense/O(n) ratio is not drawn: the dense baseline is
    // unoptimised, so its ratio overstates (the slopes are the result).
    plot.annotations = vec![
        format!("slopes fitted for n ≥ {FIT_FROM}; guides offset ×1/{GUIDE_OFFSET}"),
        format!("dense less assembly (Cholesky + solve): slope {slope_factor:.2}"),
    ];
    let out = figures::line_plot(&plot, stem).map_err(|e| e.to_string())?;
    Ok(out)
}
