//! The drawings of the report's figures from their tables
//! (`crate::report`): catenaries, chain snapshots, tip speed and
//! velocity against time, and the maximum tip speed against the span.

use std::path::Path;

use figures::{palette, ChainSnapshots, LinePlot, Marker, Output, Series, Style};

use super::Reader;
use fc_csv::table::{distinct, Table};

/// The legend entry of a scene: its name and where it was released.
fn scene_label(scene: &str, p1: (f64, f64)) -> String {
    format!("{scene} (P1 = ({:.3}, {:.3}))", p1.0, p1.1).replace(".000", "")
}

/// A scene of a tip figure: (name, legend label, (t_max, v_max)).
type SceneRow = (String, String, (f64, f64));

/// The scenes of `<id>-scenes.csv`.
fn read_scenes(read: Reader) -> Result<Vec<SceneRow>, String> {
    let t = read("-scenes")?;
    let (name, x, y) = (t.strs("scene")?, t.nums("p1_x")?, t.nums("p1_y")?);
    let (tm, vm) = (t.nums("t_tip_speed_max")?, t.nums("tip_speed_max")?);
    Ok((0..t.len())
        .map(|k| {
            (
                name[k].to_string(),
                scene_label(name[k], (x[k], y[k])),
                (tm[k], vm[k]),
            )
        })
        .collect())
}

/// The samples of column pair `(a, b)` of `t` for each scene in `scenes`.
fn per_scene(
    t: &Table,
    scenes: &[SceneRow],
    a: &str,
    b: &str,
) -> Result<Vec<Vec<(f64, f64)>>, String> {
    let (scene, a, b) = (t.strs("scene")?, t.nums(a)?, t.nums(b)?);
    let names = distinct(&scene);
    if names.len() != scenes.len() || names.iter().zip(scenes).any(|(n, s)| *n != s.0) {
        return Err(format!("{}: its scenes differ from the legend's", t.name));
    }
    Ok(names
        .iter()
        .map(|n| {
            (0..t.len())
                .filter(|&k| scene[k] == *n)
                .map(|k| (a[k], b[k]))
                .collect()
        })
        .collect())
}

pub fn catenaries(read: Reader, stem: &Path, title: &str) -> Result<Output, String> {
    let t = read("")?;
    let (kind, length, x, y) = (
        t.strs("kind")?,
        t.nums("length")?,
        t.nums("x")?,
        t.nums("y")?,
    );
    let mut p1 = None;
    let mut curves: Vec<(f64, Vec<(f64, f64)>)> = vec![];
    let mut lows = vec![];
    for k in 0..t.len() {
        match kind[k] {
            "p1" => p1 = Some([x[k], y[k]]),
            "lowest" => lows.push((x[k], y[k])),
            _ => match curves.last_mut() {
                Some((l, pts)) if *l == length[k] => pts.push((x[k], y[k])),
                _ => curves.push((length[k], vec![(x[k], y[k])])),
            },
        }
    }
    let mut f = figures::ColoredCurves::new(title, curves, [0.0, 0.0]);
    f.p1 = p1;
    f.markers = lows;
    f.markers_label = "lowest point";
    f.colorbar_label = "L";
    figures::colored_curves(&f, stem).map_err(|e| e.to_string())
}

/// Draws a snapshot table: every `every`-th frame and the last. With
/// `shift > 0`, the `k`-th frame drawn is moved right by `k shift` (offset
/// panels: the frames do not cover each other), the x axis is stretched
/// to them, and `P0`, `P1` are those of the first frame.
pub fn snapshots(
    read: Reader,
    stem: &Path,
    title: &str,
    every: usize,
    shift: f64,
    p1_label: Option<&str>,
) -> Result<Output, String> {
    let t = read("")?;
    let (point, time, x, y) = (t.strs("point")?, t.nums("t")?, t.nums("x")?, t.nums("y")?);
    let (mut p0, mut p1) = ([0.0, 0.0], None);
    let mut frames: Vec<(f64, Vec<[f64; 2]>)> = vec![];
    for k in 0..t.len() {
        match point[k] {
            "P0" => p0 = [x[k], y[k]],
            "P1" => p1 = Some([x[k], y[k]]),
            "0" => frames.push((time[k], vec![[x[k], y[k]]])),
            _ => frames
                .last_mut()
                .ok_or_else(|| format!("{}: a joint before joint 0", t.name))?
                .1
                .push([x[k], y[k]]),
        }
    }
    let every = every.max(1);
    let last = frames.len().saturating_sub(1);
    let frames = frames
        .into_iter()
        .enumerate()
        .filter(|(k, _)| k % every == 0 || *k == last)
        .map(|(_, f)| f)
        .collect::<Vec<_>>();
    let shown = frames.len();
    // Side by side, each snapshot's tick sits under its P0 and is
    // labelled by its time: the x numbers of shifted frames mean nothing.
    let ticks: Vec<(f64, String)> = frames
        .iter()
        .enumerate()
        .map(|(k, (t, _))| (p0[0] + k as f64 * shift, format!("{t:.2}")))
        .collect();
    let frames = frames
        .into_iter()
        .enumerate()
        .map(|(k, (t, joints))| {
            let dx = k as f64 * shift;
            (t, joints.into_iter().map(|p| [p[0] + dx, p[1]]).collect())
        })
        .collect();
    let x_label = format!("time t of each snapshot (drawn side by side, {shift} apart in x)");
    let mut f = ChainSnapshots::new(title, frames, p0);
    f.p1 = p1;
    if shift > 0.0 {
        f.equal_aspect = false;
        f.x_range = Some((-0.5 * shift, (shown as f64 - 0.5) * shift));
        f.x_label = &x_label;
        f.x_ticks = Some(ticks);
    }
    if let Some(label) = p1_label {
        f.p1_label = label;
    }
    figures::chain_snapshots(&f, stem).map_err(|e| e.to_string())
}

pub fn tip_speed(read: Reader, stem: &Path, title: &str) -> Result<Output, String> {
    let scenes = read_scenes(read)?;
    let t = read("")?;
    let lines = per_scene(&t, &scenes, "t", "tip_speed")?;
    let mut p = LinePlot::new(title, "t", "tip speed |v|");
    for (s, pts) in scenes.iter().zip(lines) {
        p.series.push(Series::line(s.1.clone(), pts));
    }
    // The continuous maxima, located between steps.
    p.series.push(
        Series::new(
            "maximum (continuous)",
            scenes.iter().map(|s| s.2).collect(),
            Style::Points,
        )
        .with_color(figures::RGBColor(0, 0, 0)),
    );
    figures::line_plot(&p, stem).map_err(|e| e.to_string())
}

pub fn tip_velocity(read: Reader, stem: &Path, title: &str) -> Result<Output, String> {
    let scenes = read_scenes(read)?;
    let t = read("")?;
    let lines = per_scene(&t, &scenes, "v_x", "v_y")?;
    let mut p = LinePlot::new(title, "v_x", "v_y");
    p.equal_aspect = true;
    for (s, pts) in scenes.iter().zip(lines) {
        p.series.push(Series::line(s.1.clone(), pts));
    }
    figures::line_plot(&p, stem).map_err(|e| e.to_string())
}

/// Fig. 9: the maximum tip speed against the span, at n = 50 (a dense
/// sweep, the report's spans) and refined (`links`, continuum fixed), the
/// narrow-span peak on finer spans, the whip switches (short dashed marks
/// at the foot of the curves), and, from `-agreement`, the spans where
/// n = 50 is within 1% of the refined chain, marked on its curve (the
/// ranges they make are the paper's, from the same table).
pub fn vmax_vs_span(
    read: Reader,
    stem: &Path,
    title: &str,
    links: usize,
) -> Result<Output, String> {
    let t = read("")?;
    let (set, d, v, status) = (
        t.strs("set")?,
        t.nums("d")?,
        t.nums("tip_speed_max")?,
        t.strs("status")?,
    );
    let ok = |which: &str| -> Vec<(f64, f64)> {
        (0..t.len())
            .filter(|&k| set[k] == which && status[k] == "ok")
            .map(|k| (d[k], v[k]))
            .collect()
    };
    let dense_count = set.iter().filter(|s| **s == "dense").count();
    let fine = format!("n{links}");
    let fine_count = set.iter().filter(|s| **s == fine).count();
    let mut p = LinePlot::new(title, "span d", "maximum tip speed");
    p.x_tick_step = Some(0.5);
    p.series.push(
        Series::line(
            format!("n = 50: {dense_count} spans (DOPRI5, rtol 1e-8)"),
            ok("dense"),
        )
        .with_color(palette(0)),
    );
    p.series.push(
        Series::new(
            format!("n = {links} (continuum fixed): {fine_count} spans (auto)"),
            ok(&fine),
            Style::LinePoints,
        )
        .with_color(palette(1)),
    );
    p.series.push(
        Series::points("n = 50 at the report's 14 spans", ok("report"))
            .with_color(palette(2))
            .with_marker(Marker::Square),
    );
    // The chain stretched straight (d = L), one diamond per chain, each
    // labelled with its chain and in its curve's colour: the two sit
    // apart at d = L and must not read as one series.
    for (which, who, colour) in [
        ("stretched".to_string(), "n = 50".to_string(), palette(0)),
        (
            format!("stretched-{fine}"),
            format!("n = {links}"),
            palette(1),
        ),
    ] {
        let pts = ok(&which);
        let at = pts
            .first()
            .map_or(String::new(), |&(_, v)| format!(": {v:.1}"));
        p.series.push(
            Series::points(format!("stretched straight, d = L, {who}{at}"), pts)
                .with_color(colour)
                .with_marker(Marker::Diamond),
        );
    }
    // The narrow-span peak on finer spans (n = links and 2 links): the
    // first as open marks over the second's line.
    let pk = read("-peak")?;
    let (pn, pd, pv, pst) = (
        pk.strs("links")?,
        pk.nums("d")?,
        pk.nums("tip_speed_max")?,
        pk.strs("status")?,
    );
    for (k, n) in distinct(&pn).into_iter().enumerate() {
        let pts: Vec<(f64, f64)> = (0..pk.len())
            .filter(|&j| pn[j] == n && pst[j] == "ok")
            .map(|j| (pd[j], pv[j]))
            .collect();
        let series = if k == 0 {
            Series::points(format!("n = {n}, finer spans near the peak"), pts).hollow()
        } else {
            Series::new(
                format!("n = {n}, finer spans near the peak"),
                pts,
                Style::LinePoints,
            )
        };
        p.series.push(series.with_color(figures::palette(4 + k)));
    }
    // The whip switch of each curve: a short dashed mark at the foot of
    // the curves, between the two spans where the time of the maximum
    // jumps.
    let (lo, hi) = v
        .iter()
        .copied()
        .filter(|x| x.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
    let times = t.nums("t_tip_speed_max")?;
    let row = |k: &str| (0..t.len()).find(|&i| set[i] == k);
    for (suffix, who, grey) in [
        ("", "n = 50", 90),
        (&format!("-{fine}")[..], &format!("n = {links}")[..], 160),
    ] {
        let (Some(a), Some(b)) = (
            row(&format!("switch-before{suffix}")),
            row(&format!("switch-after{suffix}")),
        ) else {
            continue;
        };
        let at = 0.5 * (d[a] + d[b]);
        p.series.push(
            Series::new(
                format!(
                    "whip switch, {who} (t of max {:.2} → {:.2})",
                    times[a], times[b]
                ),
                vec![(at, lo), (at, lo + 0.3 * (hi - lo))],
                Style::Dashed,
            )
            .with_color(figures::RGBColor(grey, grey, grey)),
        );
    }
    // Where n = 50 is within 1% of the refined chain, from the data: each
    // such span marked on the n = 50 curve (the ranges are the text's).
    let ag = read("-agreement")?;
    let (kind, from) = (ag.strs("kind")?, ag.nums("d")?);
    let (v50, rel) = (ag.nums("vmax_n50")?, ag.nums("rel_diff")?);
    let within: Vec<(f64, f64)> = (0..ag.len())
        .filter(|&j| kind[j] == "span" && rel[j].abs() <= 0.01)
        .map(|j| (from[j], v50[j]))
        .collect();
    p.series.push(
        Series::points(format!("n = 50 within 1% of n = {links}"), within)
            .with_color(figures::RGBColor(0, 0, 0))
            .with_marker(Marker::Diamond)
            .hollow(),
    );
    figures::line_plot(&p, stem).map_err(|e| e.to_string())
}
