//! The drawings of the report's own model (`crate::report_model`):
//! its snapshots, titled with how the run ended, and its Fig. 9 beside
//! the published one, each erratum undone, and the corrected model's.

use std::path::Path;

use fc_csv::table::distinct;
use figures::{palette, ChainSnapshots, LinePlot, Marker, Output, RGBColor, Series, Style};

use super::Reader;

/// The snapshots of `<id>.csv` (`point,t,x,y` and a last status row),
/// titled `title (<status> at t = <t_reached>)`, the time to 3 decimals.
pub fn snapshots(read: Reader, stem: &Path, title: &str) -> Result<Output, String> {
    let t = read("")?;
    let (point, time, x, y) = (t.strs("point")?, t.strs("t")?, t.strs("x")?, t.strs("y")?);
    let parse = |s: &str| s.parse::<f64>().map_err(|e| e.to_string());
    let mut p0 = [0.0, 0.0];
    let mut status = String::new();
    let mut frames: Vec<(f64, Vec<[f64; 2]>)> = vec![];
    for k in 0..t.len() {
        match point[k] {
            "P0" => p0 = [parse(x[k])?, parse(y[k])?],
            "0" => frames.push((parse(time[k])?, vec![[parse(x[k])?, parse(y[k])?]])),
            p if p.parse::<usize>().is_ok() => frames
                .last_mut()
                .ok_or_else(|| format!("{}: a joint before joint 0", t.name))?
                .1
                .push([parse(x[k])?, parse(y[k])?]),
            // The time as a reader needs it (3 decimals), not the 16
            // digits of the data file.
            s => status = format!("{s} at t = {:.3}", parse(time[k])?),
        }
    }
    let title = format!("{title} ({status})");
    let f = ChainSnapshots::new(&title, frames, p0);
    figures::chain_snapshots(&f, stem).map_err(|e| e.to_string())
}

/// The maximum tip speed against the span of `<id>.csv`, in two panels
/// on linear axes: left, in the report's clock, the published Fig. 9 read
/// off its page (open marks, over everything) beside the report's model by
/// its own speed measure and by the tip's exact speed; right, in our
/// units, the report's model as coded and with each erratum undone in turn
/// (`<id>-errata-spans.csv`; a case that diverges at every span named in
/// the note), and the corrected model.
pub fn vmax(read: Reader, stem: &Path, title: &str) -> Result<Output, String> {
    let t = read("")?;
    let d = t.nums("d")?;
    let col = |name: &str| -> Result<Vec<(f64, f64)>, String> {
        let v = t.nums(name)?;
        Ok(d.iter()
            .zip(v.iter())
            .filter(|(_, v)| v.is_finite())
            .map(|(&d, &v)| (d, v))
            .collect())
    };
    let mut left = LinePlot::new(
        "in its clock, as its code measures",
        "span d",
        "maximum tip speed (its units)",
    );
    let mut right = LinePlot::new(
        "in our units: each erratum undone",
        "span d",
        "max tip speed (g = 1, L = 6)",
    );
    for p in [&mut left, &mut right] {
        p.x_tick_step = Some(1.0);
    }
    left.series.push(
        Series::new(
            "its own speed (rod 1 left out, last rod's middle)",
            col("vmax_fd")?,
            Style::LinePoints,
        )
        .with_color(palette(1)),
    );
    left.series.push(
        Series::new(
            "the tip's exact speed",
            col("vmax_report")?,
            Style::LinePoints,
        )
        .with_color(palette(2)),
    );
    left.series.push(
        Series::points("the report's Fig. 9, read off its page", col("read_off")?)
            .with_color(RGBColor(0, 0, 0))
            .hollow(),
    );
    let e = read("-errata-spans")?;
    let (ed, case, ev, status) = (
        e.nums("d")?,
        e.strs("case")?,
        e.nums("vmax")?,
        e.strs("status")?,
    );
    let marks = [
        Marker::Circle,
        Marker::Square,
        Marker::Diamond,
        Marker::Triangle,
    ];
    let mut failed = vec![];
    // The first case (as coded) by span, so that a case that stays close
    // to it says how close and is drawn in open marks over it, not hidden
    // under it.
    let mut first: Vec<(f64, f64)> = vec![];
    for (k, c) in distinct(&case).into_iter().enumerate() {
        let rows: Vec<usize> = (0..e.len()).filter(|&j| case[j] == c).collect();
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|&&j| status[j] == "ok")
            .map(|&j| (ed[j], ev[j]))
            .collect();
        if pts.is_empty() {
            let how = rows.first().map_or("failed", |&j| status[j]);
            failed.push(format!("{c}: {how} at every span"));
            continue;
        }
        let style = if k == 0 {
            Style::LinePoints
        } else {
            Style::DashedPoints
        };
        let apart = largest_relative_gap(&first, &pts);
        let close = k > 0 && apart.is_some_and(|a| a < CLOSE);
        let label = match apart {
            Some(a) if close => format!("{c}: within {:.1}% of {}", 100.0 * a, case[0]),
            _ => c.to_string(),
        };
        let mut series = Series::new(label, pts.clone(), style)
            .with_color(palette(3 + k))
            .with_marker(marks[k % marks.len()]);
        if close {
            series = series.hollow();
        }
        right.series.push(series);
        if k == 0 {
            first = pts;
        }
    }
    right.series.push(
        Series::new(
            "corrected model (DOPRI5, rtol 1e-8)",
            col("corrected")?,
            Style::Line,
        )
        .with_color(RGBColor(0, 0, 0)),
    );
    right.annotations = failed;
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}

/// A case this close to the first (largest relative gap at a common
/// span) is drawn in open marks and says how close it is.
const CLOSE: f64 = 0.02;

/// The largest `|b - a| / |a|` over the spans `a` and `b` share; `None`
/// if they share none.
fn largest_relative_gap(a: &[(f64, f64)], b: &[(f64, f64)]) -> Option<f64> {
    b.iter()
        .filter_map(|&(d, v)| a.iter().find(|p| p.0 == d).map(|p| ((v - p.1) / p.1).abs()))
        .reduce(f64::max)
}

/// The report's Fig. 8 or 11 in its model, from `<id>.csv`
/// (`scene,t,speed,v_x,v_y`) and `<id>-cases.csv`: its own tip speed
/// against time (left) and velocity (right), one line per scene, each
/// labelled with how its run as coded ended and with the largest of its
/// speeds when its stepper is RK4 instead; the axes span the speeds of the
/// runs that ended ok (a diverging run leaves them).
pub fn tip(read: Reader, stem: &Path, title: &str) -> Result<Output, String> {
    let t = read("")?;
    let c = read("-cases")?;
    let (scene, time, speed) = (t.strs("scene")?, t.nums("t")?, t.nums("speed")?);
    let (vx, vy) = (t.nums("v_x")?, t.nums("v_y")?);
    let (cs, status, reached) = (c.strs("scene")?, c.strs("status")?, c.nums("t_reached")?);
    let vmax = c.nums("vmax_fd")?;
    let mut left = LinePlot::new(
        "its own tip speed, its clock",
        "t (report's clock)",
        "tip speed",
    );
    let mut right = LinePlot::new("its own tip velocity", "v_x", "v_y");
    right.equal_aspect = true;
    // The ranges of the runs that ended ok: a diverging run's last
    // differences (hundreds) would flatten every curve.
    let top = (0..c.len())
        .filter(|&k| status[k] == "ok")
        .map(|k| vmax[k])
        .fold(0.0, f64::max);
    // A quarter above, to the next half unit.
    let top = (2.5 * top).ceil() / 2.0;
    if top > 0.0 {
        left.y_range = Some((0.0, top));
    }
    // The velocities of the runs that ended ok, padded by 4%.
    let ok: Vec<&str> = (0..c.len())
        .filter(|&k| status[k] == "ok")
        .map(|k| cs[k])
        .collect();
    let bounds = (0..t.len())
        .filter(|&i| ok.contains(&scene[i]) && vx[i].is_finite() && vy[i].is_finite())
        .fold(None, |b: Option<(f64, f64, f64, f64)>, i| {
            let (x, y) = (vx[i], vy[i]);
            Some(b.map_or((x, x, y, y), |b| {
                (b.0.min(x), b.1.max(x), b.2.min(y), b.3.max(y))
            }))
        });
    if let Some((x0, x1, y0, y1)) = bounds {
        let pad = 0.04 * (x1 - x0).max(y1 - y0);
        right.x_range = Some((x0 - pad, x1 + pad));
        right.y_range = Some((y0 - pad, y1 + pad));
    }
    // The cases come in pairs, as coded then with RK4 for the stepper.
    for k in (0..c.len()).step_by(2) {
        let name = cs[k];
        let rows: Vec<usize> = (0..t.len()).filter(|&i| scene[i] == name).collect();
        let label = format!(
            "{name}: {} at t = {:.2}; RK4 stepper: max {:.2}",
            status[k],
            reached[k],
            vmax.get(k + 1).copied().unwrap_or(f64::NAN)
        );
        left.series.push(Series::line(
            label.clone(),
            rows.iter().map(|&i| (time[i], speed[i])).collect(),
        ));
        right.series.push(Series::line(
            name.to_string(),
            rows.iter().map(|&i| (vx[i], vy[i])).collect(),
        ));
    }
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}
