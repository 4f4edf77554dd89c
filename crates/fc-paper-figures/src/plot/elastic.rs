//! The drawings of the elastic chain's study: the snap's support force and
//! impulse against `n` (`fc_study::snap`), its tension wave
//! (`crate::snap_tension`), and when the rigid model will do
//! (`fc_study::rigid_limit`).

use std::path::Path;

use figures::{palette, LinePlot, Marker, Output, RGBColor, Series, Style};

use super::Reader;
use fc_csv::table::distinct;

/// How each scene of `snap-force` is drawn: line style, mark, hollow.
const SCENE_STYLES: [(Style, Marker, bool); 3] = [
    (Style::LinePoints, Marker::Circle, false),
    (Style::DashedPoints, Marker::Square, true),
    (Style::Points, Marker::Triangle, false),
];

/// `snap-force`: from `-timing` and `-stiff` (`snap::SNAP_HEADER` rows,
/// the second without wall times), the peak support force over `M g` and
/// the impulse over `M sqrt(g L)` against `n`, a line per `(scene, label)`
/// of `scenes` and variant: a colour per variant (the left panel's
/// legend), a line style and mark per scene (the right panel's).
pub fn snap_force(read: Reader, stem: &Path, scenes: &[(&str, &str)]) -> Result<Output, String> {
    // (scene, variant, n, peak, impulse) of both tables.
    let mut rows: Vec<(String, String, f64, f64, f64)> = vec![];
    for t in [read("-timing")?, read("-stiff")?] {
        let (scene, variant, links) = (t.strs("scene")?, t.strs("variant")?, t.nums("links")?);
        let (peak, impulse) = (t.nums("peak_force_mg")?, t.nums("impulse")?);
        for j in 0..t.len() {
            rows.push((
                scene[j].to_string(),
                variant[j].to_string(),
                links[j],
                peak[j],
                impulse[j],
            ));
        }
    }
    let variants = distinct(&rows.iter().map(|r| r.1.as_str()).collect::<Vec<_>>())
        .into_iter()
        .map(str::to_string)
        .collect::<Vec<_>>();
    let mut left = LinePlot::new(
        "peak support force (rigid: at the 1e-3 samples)",
        "n (rods, M = 10 fixed)",
        "max |F_pivot| / (M g)",
    );
    let mut right = LinePlot::new(
        "impulse of the snap, ±0.2 around the peak",
        "n (rods, M = 10 fixed)",
        "|J| / (M sqrt(g L))",
    );
    let mut ns: Vec<f64> = rows.iter().map(|r| r.2).collect();
    ns.sort_by(f64::total_cmp);
    ns.dedup();
    for p in [&mut left, &mut right] {
        p.log_x = true;
        p.log_y = true;
        p.x_ticks = Some(ns.clone());
    }
    for (si, &(sc, _)) in scenes.iter().enumerate() {
        let (style, marker, hollow) = SCENE_STYLES[si % SCENE_STYLES.len()];
        for (vi, v) in variants.iter().enumerate() {
            let mine: Vec<&(String, String, f64, f64, f64)> =
                rows.iter().filter(|r| r.0 == sc && r.1 == *v).collect();
            if mine.is_empty() {
                continue;
            }
            let pts = |col: fn(&(String, String, f64, f64, f64)) -> f64| -> Vec<(f64, f64)> {
                mine.iter()
                    .filter(|r| col(r).is_finite() && col(r) > 0.0)
                    .map(|r| (r.2, col(r)))
                    .collect()
            };
            for (p, col) in [
                (
                    &mut left,
                    (|r: &(String, String, f64, f64, f64)| r.3) as fn(&_) -> f64,
                ),
                (&mut right, |r: &(String, String, f64, f64, f64)| r.4),
            ] {
                let mut series = Series::new("", pts(col), style)
                    .with_color(palette(vi))
                    .with_marker(marker);
                if hollow {
                    series = series.hollow();
                }
                p.series.push(series);
            }
        }
    }
    // The legends: the variants' colours on the left, the scenes' styles
    // on the right.
    for (vi, v) in variants.iter().enumerate() {
        left.series
            .push(Series::legend_only(v.clone(), Style::Line).with_color(palette(vi)));
    }
    for (si, &(_, label)) in scenes.iter().enumerate() {
        let (style, marker, hollow) = SCENE_STYLES[si % SCENE_STYLES.len()];
        let mut entry = Series::legend_only(label, style)
            .with_color(RGBColor(60, 60, 60))
            .with_marker(marker);
        if hollow {
            entry = entry.hollow();
        }
        right.series.push(entry);
    }
    let title = "The snap: support force and impulse against n (total mass fixed)";
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}

/// `snap-tension`: the tension profiles of the main table, a colour each
/// (five from the tip's arrest to the support's peak, solid; the last,
/// after the peak, dashed), beside the support force of `-force` with each
/// profile's time marked on it in its colour; the peak's time from
/// `-summary`.
pub fn snap_tension(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (time, s, tension) = (t.strs("t")?, t.nums("s_over_L")?, t.nums("tension_mg")?);
    let f = read("-force")?;
    let (ft, ff) = (f.nums("t")?, f.nums("pivot_force_mg")?);
    let t_peak = read("-summary")?
        .nums("t_peak_force")?
        .first()
        .copied()
        .unwrap_or(f64::INFINITY);
    let mut left = LinePlot::new(
        "tension along the chain (pivot at 0, tip at 1)",
        "s / L",
        "tension / (M g)",
    );
    let mut right = LinePlot::new("support force", "t", "|F_pivot| / (M g)");
    right.series.push(
        Series::new(
            "n = 100, EA = 1e4",
            ft.iter().copied().zip(ff.iter().copied()).collect(),
            Style::Line,
        )
        .with_color(RGBColor(0, 0, 0)),
    );
    for (k, tk) in distinct(&time).iter().enumerate() {
        let pts: Vec<(f64, f64)> = (0..t.len())
            .filter(|&j| time[j] == *tk)
            .map(|j| (s[j], tension[j]))
            .collect();
        let tv: f64 = tk.parse().unwrap_or(f64::NAN);
        // A profile after the peak (the table's times are rounded; the
        // last comes 0.05 after it).
        let after = tv > t_peak + 0.01;
        let (label, style) = if after {
            (format!("t = {tv:.3}, after the peak"), Style::Dashed)
        } else {
            (format!("t = {tv:.3}"), Style::Line)
        };
        left.series
            .push(Series::new(label, pts, style).with_color(palette(k)));
        let at = ft
            .iter()
            .zip(&ff)
            .min_by(|a, b| (a.0 - tv).abs().total_cmp(&(b.0 - tv).abs()))
            .map(|(a, b)| (*a, *b));
        if let Some(p) = at {
            right
                .series
                .push(Series::new("", vec![p], Style::Points).with_color(palette(k)));
        }
    }
    left.x_range = Some((0.0, 1.0));
    let title = "The snap's wave: tension from the tip's arrest to the support's peak and after \
                 (d = 3, n = 100, M = 10, EA = 1e4)";
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}

/// `elastic-rigid-limit`: from `-timing` (`rigid_limit::RUNGS_HEADER`
/// rows) each scene's tip-path and maximum-speed deviations against `EA`,
/// the tolerance, and from `-threshold-timing` each scene's answer.
pub fn rigid_limit(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("-timing")?;
    let (scene, ea) = (t.strs("scene")?, t.nums("axial_stiffness")?);
    let (path, speed) = (t.nums("tip_path")?, t.nums("tip_speed_max")?);
    let a = read("-threshold-timing")?;
    let (a_scene, a_thr, a_tol) = (a.strs("scene")?, a.nums("threshold")?, a.nums("tol")?);
    let tol = a_tol.first().copied().unwrap_or(1e-3);
    let mut left = LinePlot::new("tip path: max |tip - tip_rigid| / L", "EA", "deviation");
    let mut right = LinePlot::new(
        "maximum tip speed: |v_max / v_max_rigid - 1|",
        "EA",
        "deviation",
    );
    for p in [&mut left, &mut right] {
        p.log_x = true;
        p.log_y = true;
    }
    // The tolerance across the ladder of EA.
    let (ea_lo, ea_hi) = ea
        .iter()
        .filter(|v| v.is_finite() && **v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
    // Each scene's answer as a mark on the tolerance line of the right
    // panel (the numbers are the paper's, from the same table); the scenes
    // with none are named in the note.
    let mut none = vec![];
    let mut thresholds = vec![];
    for (k, s) in distinct(&scene).into_iter().enumerate() {
        let rows: Vec<usize> = (0..t.len()).filter(|&j| scene[j] == s).collect();
        let pts = |col: &[f64]| -> Vec<(f64, f64)> {
            rows.iter()
                .filter(|&&j| col[j].is_finite() && col[j] > 0.0)
                .map(|&j| (ea[j], col[j]))
                .collect()
        };
        let (style, marker) = if k < 10 {
            (Style::LinePoints, Marker::Circle)
        } else {
            (Style::DashedPoints, Marker::Square)
        };
        left.series.push(
            Series::new(s, pts(&path), style)
                .with_color(palette(k))
                .with_marker(marker),
        );
        right.series.push(
            Series::new("", pts(&speed), style)
                .with_color(palette(k))
                .with_marker(marker),
        );
        if let Some(j) = a_scene.iter().position(|x| *x == s) {
            if a_thr[j].is_finite() {
                thresholds.push(
                    Series::new("", vec![(a_thr[j], tol)], Style::Points)
                        .with_color(palette(k))
                        .with_marker(Marker::Triangle)
                        .hollow(),
                );
            } else {
                none.push(s);
            }
        }
    }
    let black = figures::RGBColor(0, 0, 0);
    for (p, label) in [
        (&mut left, format!("tol = {tol:e}")),
        (&mut right, String::new()),
    ] {
        p.series.push(
            Series::new(label, vec![(ea_lo, tol), (ea_hi, tol)], Style::Dashed).with_color(black),
        );
    }
    right.series.extend(thresholds);
    right.series.push(
        Series::legend_only(
            format!("EA above which both stay below {tol:e}"),
            Style::Points,
        )
        .with_color(black)
        .with_marker(Marker::Triangle)
        .hollow(),
    );
    if !none.is_empty() {
        right.annotations = vec![format!("none up to {ea_hi:.0e}: {}", none.join(", "))];
    }
    let title = "When the rigid model will do: elastic against rigid links (report scenes)";
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}
