//! The drawing of Cayley's scale as an ensemble (`crate::cayley`): the
//! ensemble's mean reading over the ideal's against time, a line per `n`,
//! and the mid-fall reading against `n` with its two standard errors, the
//! other floors and tilts at `n = 40` beside it.

use std::path::Path;

use figures::{palette, LinePlot, Marker, Output, Series, Style};

use super::Reader;

/// The ladder in `n` is the cases at this floor and tilt.
const LADDER_STIFFNESS: f64 = 1e5;
const LADDER_TILT: f64 = 0.2;
const LADDER_SPREAD: f64 = 1e-3;

pub fn cayley(read: Reader, stem: &Path) -> Result<Output, String> {
    let s = read("")?;
    let m = read("-midfall")?;
    let on_ladder = |k: f64, tilt: f64, spread: f64| {
        k == LADDER_STIFFNESS && tilt == LADDER_TILT && spread == LADDER_SPREAD
    };
    let (links, k, tilt, spread, t) = (
        s.nums("links")?,
        s.nums("stiffness")?,
        s.nums("tilt")?,
        s.nums("spread")?,
        s.nums("t")?,
    );
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
        .filter(|&j| on_ladder(k[j], tilt[j], spread[j]))
        .map(|j| links[j])
        .collect();
    ns.dedup();
    for (i, &n) in ns.iter().enumerate() {
        let pts = (0..s.len())
            .filter(|&j| links[j] == n && on_ladder(k[j], tilt[j], spread[j]))
            .filter_map(|j| Some((t[j], wide[j]?)))
            .collect();
        left.series
            .push(Series::new(format!("n = {n}"), pts, Style::Line).with_color(palette(i)));
    }
    left.series.push(
        Series::new(
            "ideal (Cayley): 1",
            vec![(0.2, 1.0), (1.2, 1.0)],
            Style::Dashed,
        )
        .with_color(palette(7)),
    );
    left.y_range = Some((0.0, 2.0));

    let (ml, mk, mt, msp) = (
        m.nums("links")?,
        m.nums("stiffness")?,
        m.nums("tilt")?,
        m.nums("spread")?,
    );
    let (mm, msem) = (m.nums("reading_mean")?, m.nums("reading_sem")?);
    let (wm, wsem) = (m.nums("reading_wide_mean")?, m.nums("reading_wide_sem")?);
    let mut right = LinePlot::new(
        "at mid-fall (x = L / 2)",
        "rods n",
        "ensemble mean of F / (3 mu g x)",
    );
    let ladder: Vec<usize> = (0..m.len())
        .filter(|&j| on_ladder(mk[j], mt[j], msp[j]))
        .collect();
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
    let others: Vec<usize> = (0..m.len())
        .filter(|&j| !on_ladder(mk[j], mt[j], msp[j]))
        .collect();
    let markers = [Marker::Square, Marker::Triangle, Marker::Diamond];
    for (i, &j) in others.iter().enumerate() {
        let label = if msp[j] != LADDER_SPREAD {
            format!("spread {:e}", msp[j])
        } else if mt[j] != LADDER_TILT {
            format!("tilt {}", mt[j])
        } else {
            format!("k = {:e}", mk[j])
        };
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
