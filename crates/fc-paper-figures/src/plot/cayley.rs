//! The drawing of Cayley's scale as an ensemble (`crate::cayley`): the
//! ensemble's mean reading over the ideal's against time, a line per `n`,
//! and the mid-fall reading against `n` with its two standard errors, the
//! other floors and tilts at `n = 40` beside it.

use std::path::Path;

use figures::{palette, LinePlot, Marker, Output, RGBColor, Series, Style};

use super::Reader;

/// The ladder in `n` is the cases at this floor, tilt and spread, with
/// no friction.
const LADDER_STIFFNESS: f64 = 1e5;
const LADDER_DAMPING: f64 = 100.0;
const LADDER_TILT: f64 = 0.2;
const LADDER_SPREAD: f64 = 1e-3;

/// The case columns of one row of a table: `(stiffness, damping, floor
/// friction, joint friction, tilt, spread)`.
type CaseKey = (f64, f64, f64, f64, f64, f64);

fn case_keys(t: &fc_csv::table::Table) -> Result<(Vec<f64>, Vec<CaseKey>), String> {
    let (n, k, c, mu, r, tilt, spread) = (
        t.nums("links")?,
        t.nums("stiffness")?,
        t.nums("damping")?,
        t.nums("friction")?,
        t.nums("joint_friction")?,
        t.nums("tilt")?,
        t.nums("spread")?,
    );
    let keys = (0..t.len())
        .map(|j| (k[j], c[j], mu[j], r[j], tilt[j], spread[j]))
        .collect();
    Ok((n, keys))
}

/// Whether a case is on the ladder in `n`.
fn on_ladder(key: &CaseKey) -> bool {
    *key == (
        LADDER_STIFFNESS,
        LADDER_DAMPING,
        0.0,
        0.0,
        LADDER_TILT,
        LADDER_SPREAD,
    )
}

/// How a case off the ladder differs from it, for a legend.
fn variant(key: &CaseKey) -> String {
    let (k, c, mu, r, tilt, spread) = *key;
    if spread != LADDER_SPREAD {
        format!("spread {spread:e}")
    } else if tilt != LADDER_TILT {
        format!("tilt {tilt}")
    } else if mu != 0.0 {
        format!("floor friction {mu}")
    } else if r != 0.0 {
        format!("joint friction r = {r:e}")
    } else if c == 0.0 {
        "elastic floor (c = 0)".to_string()
    } else {
        format!("k = {k:e}")
    }
}

pub fn cayley(read: Reader, stem: &Path) -> Result<Output, String> {
    let s = read("")?;
    let m = read("-midfall")?;
    let (links, keys) = case_keys(&s)?;
    let t = s.nums("t")?;
    // The wide window's cells are empty where it leaves the run.
    let wide: Vec<Option<f64>> = s
        .strs("reading_wide_mean")?
        .iter()
        .map(|c| c.parse().ok())
        .collect();
    let mut left = LinePlot::new(
        "ensemble mean of the scale's reading",
        "t / sqrt(L / g)",
        "F / (3 mu g x), averaged over t +- 0.2",
    );
    let mut ns: Vec<f64> = (0..s.len())
        .filter(|&j| on_ladder(&keys[j]))
        .map(|j| links[j])
        .collect();
    ns.dedup();
    for (i, &n) in ns.iter().enumerate() {
        let pts = (0..s.len())
            .filter(|&j| links[j] == n && on_ladder(&keys[j]))
            .filter_map(|j| Some((t[j], wide[j]?)))
            .collect();
        left.series
            .push(Series::new(format!("n = {n}"), pts, Style::Line).with_color(palette(i)));
    }
    left.series.push(
        // Solid black: grey dashed lines are the standard errors.
        Series::new(
            "ideal (Cayley): 1",
            vec![(0.2, 1.0), (1.2, 1.0)],
            Style::Line,
        )
        .with_color(RGBColor(0, 0, 0)),
    );
    left.y_range = Some((0.0, 2.0));

    let (ml, mkeys) = case_keys(&m)?;
    let (mm, msem) = (m.nums("reading_mean")?, m.nums("reading_sem")?);
    let (wm, wsem) = (m.nums("reading_wide_mean")?, m.nums("reading_wide_sem")?);
    let mut right = LinePlot::new(
        "ensemble mean at mid-fall (x = L / 2)",
        "rods n",
        "F / (3 mu g x)",
    );
    let ladder: Vec<usize> = (0..m.len()).filter(|&j| on_ladder(&mkeys[j])).collect();
    let pick = |rows: &[usize], y: &dyn Fn(usize) -> f64| -> Vec<(f64, f64)> {
        rows.iter().map(|&j| (ml[j], y(j))).collect()
    };
    let windows: [(&str, &[f64], &[f64], usize); 2] = [
        ("window t +- 0.2", &wm, &wsem, 0),
        ("window t +- 0.05", &mm, &msem, 1),
    ];
    for (label, mean, sem, colour) in windows {
        right.series.push(
            Series::new(label, pick(&ladder, &|j| mean[j]), Style::LinePoints)
                .with_color(palette(colour)),
        );
        for sign in [2.0, -2.0] {
            right.series.push(
                Series::new(
                    "",
                    pick(&ladder, &|j| mean[j] + sign * sem[j]),
                    Style::Dashed,
                )
                .with_color(palette(colour)),
            );
        }
    }
    right.series.push(
        Series::legend_only("dashed: +- 2 standard errors", Style::Dashed).with_color(palette(7)),
    );
    // The other floors, tilts and spread; the frictions and the elastic
    // floor are `cayley-top`'s.
    let others: Vec<usize> = (0..m.len())
        .filter(|&j| {
            let (_, c, mu, r, _, _) = mkeys[j];
            !on_ladder(&mkeys[j]) && c != 0.0 && mu == 0.0 && r == 0.0
        })
        .collect();
    let markers = [Marker::Square, Marker::Triangle, Marker::Diamond];
    for (i, &j) in others.iter().enumerate() {
        let label = variant(&mkeys[j]);
        right.series.push(
            Series::new(
                format!("n = {}, {label}, t +- 0.2", ml[j]),
                vec![(ml[j], wm[j])],
                Style::Points,
            )
            .with_color(palette(i + 2))
            .with_marker(markers[i % markers.len()])
            .hollow(),
        );
    }
    right.log_x = true;
    right.x_ticks = Some(ns.clone());
    let members = m.nums("members")?.first().copied().unwrap_or(0.0);
    figures::line_plot_pair(
        &left,
        &right,
        &format!(
            "Cayley's scale: ensembles of {members} perturbed starts (k = 1e5, tilt 0.2 rad, \
             spread 1e-3 rad unless given)"
        ),
        stem,
    )
    .map_err(|e| e.to_string())
}

/// The top's fall over the free fall's against time: the ladder in `n`
/// (left) and, at `n = 40`, the contact law and the frictions (right),
/// each the ensemble's mean with its two standard errors dashed.
pub fn cayley_top(read: Reader, stem: &Path) -> Result<Output, String> {
    let s = read("")?;
    let (links, keys) = case_keys(&s)?;
    let (t, mean, sem) = (s.nums("t")?, s.nums("top_mean")?, s.nums("top_sem")?);
    let y_label = "top's fall / (g t^2 / 2)";
    let mut left = LinePlot::new(
        "over n (plastic floor, no friction)",
        "t / sqrt(L / g)",
        y_label,
    );
    let mut right = LinePlot::new(
        "n = 40: contact law and friction",
        "t / sqrt(L / g)",
        y_label,
    );
    // Each distinct case in the order of the table.
    let mut cases: Vec<(f64, CaseKey)> = Vec::new();
    for j in 0..s.len() {
        if cases.last() != Some(&(links[j], keys[j])) {
            cases.push((links[j], keys[j]));
        }
    }
    let (mut li, mut ri) = (0, 0);
    for &(n, key) in &cases {
        let rows: Vec<usize> = (0..s.len())
            .filter(|&j| links[j] == n && keys[j] == key && t[j] >= 0.2 - 1e-9)
            .collect();
        let line = |f: &dyn Fn(usize) -> f64| rows.iter().map(|&j| (t[j], f(j))).collect();
        let (plot, colour, label) = if on_ladder(&key) {
            li += 1;
            (&mut left, li - 1, format!("n = {n}"))
        } else if n == 40.0 && (key.1 == 0.0 || key.2 != 0.0 || key.3 != 0.0) {
            ri += 1;
            (&mut right, ri, variant(&key))
        } else {
            continue;
        };
        plot.series
            .push(Series::new(label, line(&|j| mean[j]), Style::Line).with_color(palette(colour)));
        for sign in [2.0, -2.0] {
            plot.series.push(
                Series::new("", line(&|j| mean[j] + sign * sem[j]), Style::Dashed)
                    .with_color(palette(colour)),
            );
        }
        if n == 40.0 && on_ladder(&key) {
            // The plastic floor without friction, the right panel's baseline.
            right.series.push(
                Series::new(
                    "plastic floor, no friction",
                    line(&|j| mean[j]),
                    Style::Line,
                )
                .with_color(palette(0)),
            );
        }
    }
    for plot in [&mut left, &mut right] {
        plot.series.push(
            // Solid black: grey dashed lines are the standard errors.
            Series::new("free fall: 1", vec![(0.2, 1.0), (1.35, 1.0)], Style::Line)
                .with_color(RGBColor(0, 0, 0)),
        );
        plot.series.push(
            Series::legend_only("dashed: +- 2 standard errors", Style::Dashed)
                .with_color(palette(7)),
        );
    }
    right.annotations = vec![
        "Grewal, Johnson & Ruina's dowel chain led".into(),
        "free fall by 6-7 cm in 75 cm (about 1.09)".into(),
    ];
    figures::line_plot_pair(
        &left,
        &right,
        "Faster than g? The top of a chain falling onto a floor, ensembles of 16 perturbed starts",
        stem,
    )
    .map_err(|e| e.to_string())
}
