//! The drawing of the friction sensitivity (`crate::friction`): the
//! maximum tip speed over its value without friction, against the joint
//! friction `r` (in the scenes' units at their own `n`), a colour per
//! scene, solid at the scene's `n` and dashed with open marks on the
//! refined chain, with the report's `r` and its range marked.

use std::path::Path;

use figures::{palette, LinePlot, Marker, Output, RGBColor, Series, Style};

use super::Reader;
use fc_csv::table::distinct;

/// The report's joint friction range (its units, n = 50) and its scenes' r.
const REPORT_RANGE: (f64, f64) = (1e-4, 1e-3);
const REPORT_R: f64 = 5e-4;

/// Draws `span-friction`'s table to `<stem>.png` and `.svg`.
pub fn friction(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (scene, links, r, v, st) = (
        t.strs("scene")?,
        t.strs("links")?,
        t.nums("r")?,
        t.nums("tip_speed_max")?,
        t.strs("status")?,
    );
    let mut p = LinePlot::new(
        "Maximum tip speed against the joint friction r (span scenes)",
        "joint friction r (the scenes' units, at n = 50)",
        "v_max(r) / v_max(r = 0)",
    );
    p.log_x = true;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let all_links = distinct(&links);
    for (k, s) in distinct(&scene).into_iter().enumerate() {
        for (j, n) in all_links.iter().enumerate() {
            let rows: Vec<usize> = (0..t.len())
                .filter(|&i| scene[i] == s && links[i] == *n && st[i] == "ok")
                .collect();
            let Some(v0) = rows.iter().find(|&&i| r[i] == 0.0).map(|&i| v[i]) else {
                continue;
            };
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|&&i| r[i] > 0.0)
                .map(|&i| (r[i], v[i] / v0))
                .collect();
            for q in &pts {
                lo = lo.min(q.1);
                hi = hi.max(q.1);
            }
            // The scene's n solid with filled marks, the refined chain
            // dashed with open squares.
            let series = if j == 0 {
                Series::new(format!("{s}, n = {n}"), pts, Style::LinePoints)
            } else {
                Series::new(format!("{s}, n = {n}"), pts, Style::DashedPoints)
                    .with_marker(Marker::Square)
                    .hollow()
            };
            p.series.push(series.with_color(palette(k)));
        }
    }
    if lo.is_finite() && hi.is_finite() {
        let grey = RGBColor(120, 120, 120);
        p.series.push(
            Series::new(
                format!("the scenes' r = {REPORT_R:e}"),
                vec![(REPORT_R, lo), (REPORT_R, hi)],
                Style::Dashed,
            )
            .with_color(RGBColor(0, 0, 0)),
        );
        for (k, x) in [REPORT_RANGE.0, REPORT_RANGE.1].into_iter().enumerate() {
            let label = if k == 0 {
                "the report's range of r"
            } else {
                ""
            };
            p.series
                .push(Series::new(label, vec![(x, lo), (x, hi)], Style::Dashed).with_color(grey));
        }
    }
    figures::line_plot(&p, stem).map_err(|e| e.to_string())
}
