//! The drawings of the elastic chain's study: the snap's support force and
//! impulse against `n` (`fc_study::snap`), its tension wave
//! (`crate::snap_tension`), when the rigid model will do
//! (`fc_study::rigid_limit`), and the work-precision of its forces
//! (`crate::force_precision`).

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
/// of `scenes` and variant: a colour per variant, a line style and mark
/// per scene, both keyed in the one legend of the left panel.
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
    // One legend, on the left: the variants' colours, then the scenes'
    // line styles and marks (both panels draw the same series, so two
    // half-legends made a reader look in two places).
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
        left.series.push(entry);
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

/// `elastic-layout-order`: the relative errors of the lowest axial
/// frequencies (left) and of the self-weight stretch (right) against `n`,
/// log-log, from `crate::layout_order`'s tables, with the layout before
/// (every joint carrying a whole rod) as its closed forms, dashed, and a
/// `1/n^2` guide.
pub fn layout_order(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (links, mode, rel) = (t.nums("links")?, t.nums("mode")?, t.nums("relative_error")?);
    let s = read("-stretch")?;
    let (s_links, ratio, s_rel) = (
        s.nums("links")?,
        s.nums("tip_mass_over_M")?,
        s.nums("relative_error")?,
    );
    let f = read("-fit")?;
    let (quantity, order) = (f.strs("quantity")?, f.strs("order")?);
    let mut left = LinePlot::new(
        "axial frequencies against the rope's",
        "n",
        "|relative error|",
    );
    let mut right = LinePlot::new(
        "self-weight stretch against the rope's",
        "n",
        "|relative error|",
    );
    for p in [&mut left, &mut right] {
        p.log_x = true;
        p.log_y = true;
    }
    let ns: Vec<f64> = {
        let mut v = links.clone();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    };
    let (first, last) = (
        ns.first().copied().unwrap_or(1.0),
        ns.last().copied().unwrap_or(1.0),
    );
    let modes: Vec<f64> = {
        let mut m = mode.clone();
        m.sort_by(f64::total_cmp);
        m.dedup();
        m
    };
    let mut at_first = f64::INFINITY;
    for (k, &j) in modes.iter().enumerate() {
        let pts: Vec<(f64, f64)> = (0..t.len())
            .filter(|&r| mode[r] == j && rel[r] != 0.0)
            .map(|r| (links[r], rel[r].abs()))
            .collect();
        at_first = at_first.min(pts.first().map_or(f64::INFINITY, |p| p.1));
        left.series
            .push(Series::new(format!("mode {j}"), pts, Style::LinePoints).with_color(palette(k)));
    }
    // The layout before, mode 1: (4n / pi) sin(pi / (4n + 2)) - 1.
    let before: Vec<(f64, f64)> = ns
        .iter()
        .map(|&n| {
            let x = std::f64::consts::PI / (4.0 * n + 2.0);
            (n, (4.0 * n / std::f64::consts::PI * x.sin() - 1.0).abs())
        })
        .collect();
    left.series.push(
        Series::new("mode 1, a rod per joint (before)", before, Style::Dashed)
            .with_color(RGBColor(0, 0, 0)),
    );
    // A 1/n^2 guide a factor 3 below mode 1's first point.
    let guide = |n: f64| at_first / 3.0 * (first / n).powi(2);
    left.series.push(
        Series::new(
            "∝ 1/n²",
            vec![(first, guide(first)), (last, guide(last))],
            Style::Line,
        )
        .with_color(RGBColor(120, 120, 120)),
    );
    for (k, (r, label)) in [(0.0, "uniform"), (1.0, "tip mass M_t = M")]
        .into_iter()
        .enumerate()
    {
        let pts: Vec<(f64, f64)> = (0..s.len())
            .filter(|&q| ratio[q] == r && s_rel[q].abs() > crate::layout_order::ROUNDING)
            .map(|q| (s_links[q], s_rel[q].abs()))
            .collect();
        if !pts.is_empty() {
            right
                .series
                .push(Series::new(label, pts, Style::LinePoints).with_color(palette(k + 3)));
        }
    }
    right.series.push(
        Series::new(
            "uniform, a rod per joint (before): 1/n",
            ns.iter().map(|&n| (n, 1.0 / n)).collect(),
            Style::Dashed,
        )
        .with_color(RGBColor(0, 0, 0)),
    );
    let mut notes = vec!["fitted order in 1/n:".to_string()];
    for (q, o) in quantity.iter().zip(&order) {
        let o = match o.parse::<f64>() {
            Ok(o) => format!("{o:.3}"),
            Err(_) => "exact".to_string(),
        };
        notes.push(format!("{q}: {o}"));
    }
    notes.push(format!(
        "uniform stretch: the rope's to {:.0e}",
        crate::layout_order::ROUNDING
    ));
    right.annotations = notes;
    let title = "The elastic chain against the continuum rope, EA = 1e4 M g";
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}

/// What `snap_work` draws against: the axial stiffness (`snap-precision`)
/// or the damping ratio (`snap-damping`).
#[derive(Clone, Copy, PartialEq)]
pub enum SnapAxis {
    Stiffness,
    Damping,
}

/// `snap-precision` and `snap-damping`: from `crate::snap_precision`'s
/// tables (`-timing`, `-best-timing`), the error against the wall time in
/// the hardest case (the stiffest `EA`, the most damped `zeta`; left, a
/// line per method along its tolerances) and, against `EA` or `zeta`, the
/// speed-up of the implicit methods over the faster explicit pair at
/// matched error, from the least wall time to each error level (right;
/// above 1: the implicit method is faster). Against `EA`: gen-alpha at each
/// level; against `zeta`: gen-alpha and BDF at `1e-4`.
pub fn snap_work(read: Reader, stem: &Path, axis: SnapAxis) -> Result<Output, String> {
    let t = read("-timing")?;
    let x_col = match axis {
        SnapAxis::Stiffness => "axial_stiffness",
        SnapAxis::Damping => "zeta",
    };
    let (x, method) = (t.nums(x_col)?, t.strs("method")?);
    let (error, wall) = (t.nums("error")?, t.nums("wall_seconds")?);
    let b = read("-best-timing")?;
    let (level, b_method, b_x, b_wall) = (
        b.nums("error_level")?,
        b.strs("method")?,
        b.nums(x_col)?,
        b.nums("wall_seconds")?,
    );
    let hardest = x.iter().copied().fold(0.0, f64::max);
    let left_title = match axis {
        SnapAxis::Stiffness => format!("EA = {hardest:.0e}: error against wall time"),
        SnapAxis::Damping => format!("zeta = {hardest}: error against wall time"),
    };
    let mut left = LinePlot::new(&left_title, "wall time (s)", "error");
    let (right_title, x_label) = match axis {
        SnapAxis::Stiffness => ("speed-up of gen-alpha over DOPRI5/DOP853", "EA"),
        SnapAxis::Damping => ("speed-up over DOPRI5/DOP853 at error 1e-4", "zeta"),
    };
    let mut right = LinePlot::new(right_title, x_label, "explicit time / implicit time");
    for p in [&mut left, &mut right] {
        p.log_x = true;
        p.log_y = true;
    }
    const STYLES: [(Style, Marker, bool); 5] = [
        (Style::LinePoints, Marker::Circle, false),
        (Style::DashedPoints, Marker::Square, true),
        (Style::LinePoints, Marker::Triangle, false),
        (Style::LinePoints, Marker::Diamond, true),
        (Style::DashedPoints, Marker::Circle, true),
    ];
    let styled = |s: Series, k: usize| {
        let (style, marker, hollow) = STYLES[k % STYLES.len()];
        let s = Series { style, ..s }
            .with_color(palette(k))
            .with_marker(marker);
        if hollow {
            s.hollow()
        } else {
            s
        }
    };
    for (k, m) in distinct(&method).into_iter().enumerate() {
        let pts: Vec<(f64, f64)> = (0..t.len())
            .filter(|&j| {
                method[j] == m && x[j] == hardest && error[j].is_finite() && error[j] > 0.0
            })
            .map(|j| (wall[j], error[j]))
            .collect();
        left.series
            .push(styled(Series::new(m, pts, Style::Line), k));
    }
    let best = |lv: f64, m: &str, at: f64| {
        (0..b.len())
            .find(|&j| level[j] == lv && b_method[j] == m && b_x[j] == at)
            .map(|j| b_wall[j])
    };
    let explicit = |lv: f64, at: f64| match (best(lv, "dopri5", at), best(lv, "dop853", at)) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (Some(a), None) | (None, Some(a)) => Some(a),
        _ => None,
    };
    let mut xs = b_x.clone();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let speed_up = |lv: f64, m: &str| -> Vec<(f64, f64)> {
        xs.iter()
            .filter_map(|&at| Some((at, explicit(lv, at)? / best(lv, m, at)?)))
            .collect()
    };
    match axis {
        SnapAxis::Stiffness => {
            let mut levels = level.clone();
            levels.sort_by(f64::total_cmp);
            levels.dedup();
            for (k, &lv) in levels.iter().rev().enumerate() {
                let label = format!("gen-alpha, error {lv:.0e}");
                right.series.push(styled(
                    Series::new(label, speed_up(lv, "gen-alpha"), Style::Line),
                    k,
                ));
            }
        }
        SnapAxis::Damping => {
            for (k, m) in ["gen-alpha", "bdf"].into_iter().enumerate() {
                right
                    .series
                    .push(styled(Series::new(m, speed_up(1e-4, m), Style::Line), k));
            }
        }
    }
    if let (Some(&a), Some(&z)) = (xs.first(), xs.last()) {
        right.series.push(
            Series::new("equal times", vec![(a, 1.0), (z, 1.0)], Style::Dashed)
                .with_color(RGBColor(0, 0, 0)),
        );
    }
    let title = match axis {
        SnapAxis::Stiffness => "The folded elastic snap (n = 20, 5% damping, t = 3.2)",
        SnapAxis::Damping => "The folded elastic snap (n = 20, EA = 1e7, t = 3.2)",
    };
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}

/// The least tip error `force_precision` draws (the reference and its
/// confirmation put the tip 1e-14 L apart).
const TIP_FLOOR: f64 = 1e-12;

/// `force-precision`: from `crate::force_precision`'s rows and reference,
/// against rtol, the relative errors of each method's largest pivot force
/// (solid) and largest joint tension (dashed) (left) and of its tip at the
/// end over `L` (right), a colour per method; the runs that say
/// `forces_resolved = false` ringed in black on the left. An error below
/// the reference's agreement is drawn at it (the reference cannot tell
/// it from zero).
pub fn force_precision(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (method, rtol) = (t.strs("method")?, t.nums("rtol")?);
    let (pivot, tension, tip) = (
        t.nums("pivot_error")?,
        t.nums("tension_error")?,
        t.nums("tip_error")?,
    );
    let resolved = t.strs("forces_resolved")?;
    let r = read("-reference")?;
    let peaks = (r.nums("pivot_force_max")?, r.nums("tension_max")?);
    let floor = crate::force_precision::AGREEMENT;
    let agree = (peaks.0[1] / peaks.0[0] - 1.0)
        .abs()
        .max((peaks.1[1] / peaks.1[0] - 1.0).abs());
    let at_least = |e: f64, floor: f64| {
        if e.is_finite() {
            e.max(floor)
        } else {
            f64::NAN
        }
    };
    let shown = |e: f64| at_least(e, floor);
    let mut left = LinePlot::new(
        "largest pivot force (solid) and tension (dashed)",
        "rtol",
        "relative error",
    );
    let mut right = LinePlot::new(
        "tip at the end (below 1e-12 drawn at it)",
        "rtol",
        "|tip - tip_ref| / L",
    );
    for p in [&mut left, &mut right] {
        p.log_x = true;
        p.log_y = true;
    }
    let mut ringed = vec![];
    for (k, m) in distinct(&method).into_iter().enumerate() {
        let rows: Vec<usize> = (0..t.len()).filter(|&j| method[j] == m).collect();
        let line = |e: &[f64], floor: f64| {
            rows.iter()
                .map(|&j| (rtol[j], at_least(e[j], floor)))
                .collect()
        };
        left.series.push(
            Series::new(m, line(&pivot, floor), Style::LinePoints)
                .with_color(palette(k))
                .with_marker(Marker::Circle),
        );
        left.series.push(
            Series::new("", line(&tension, floor), Style::DashedPoints)
                .with_color(palette(k))
                .with_marker(Marker::Square),
        );
        right.series.push(
            Series::new(m, line(&tip, TIP_FLOOR), Style::LinePoints)
                .with_color(palette(k))
                .with_marker(Marker::Circle),
        );
        for &j in &rows {
            if resolved[j] == "false" {
                ringed.push((rtol[j], shown(pivot[j])));
                ringed.push((rtol[j], shown(tension[j])));
            }
        }
    }
    left.series.push(
        Series::new("forces_resolved = false", ringed, Style::Points)
            .with_color(RGBColor(0, 0, 0))
            .with_marker(Marker::Diamond)
            .hollow(),
    );
    let a = rtol.iter().copied().fold(f64::INFINITY, f64::min);
    let z = rtol.iter().copied().fold(0.0, f64::max);
    left.series.push(
        Series::new("10 rtol", vec![(a, 10.0 * a), (z, 10.0 * z)], Style::Dashed)
            .with_color(RGBColor(120, 120, 120)),
    );
    left.annotations = vec![
        format!("reference: peak pivot force {:.7}", peaks.0[0]),
        format!("DOP853 1e-8 against DOPRI5 1e-9: {agree:.0e}"),
        format!("errors below {floor:.0e} (rounding) drawn at it"),
    ];
    let title = format!(
        "The steel rope's snap cut to n = {} (EA = 1e8, 5% damping, t = 3.2)",
        crate::force_precision::LINKS
    );
    figures::line_plot_pair(&left, &right, &title, stem).map_err(|e| e.to_string())
}
