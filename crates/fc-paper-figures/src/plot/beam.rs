//! The drawing of BEAM's work-precision table (`crate::beam`):
//! the error at `t = 5` against the wall time (from `-timing`) and against
//! the accepted steps, a line per method.

use std::path::Path;

use chain_ode::Method;
use figures::{palette, LinePlot, Output, Series, Style};

use super::{Reader, DRAW_FLOOR};
use fc_csv::format::exp;

/// `beam-precision`: from the main table and `-timing`, the larger of the
/// angle and rate errors against the reference at `t = 5` vs wall time
/// (left) and vs accepted steps (right); failed runs named in the legend.
pub fn precision(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let w = read("-timing")?;
    let (method, param, status) = (t.strs("method")?, t.strs("param")?, t.strs("status")?);
    let (steps, ea, er) = (
        t.nums("steps")?,
        t.nums("err_angles")?,
        t.nums("err_rates")?,
    );
    let (wm, wp, wall) = (w.strs("method")?, w.strs("param")?, w.nums("wall_seconds")?);
    let y_label = "max error of y1, y40, y41, y80 at t = 5";
    let mut left = LinePlot::new("error vs wall time", "wall time (s)", y_label);
    let mut right = LinePlot::new("error vs work", "accepted steps", y_label);
    for (i, m) in Method::ALL.into_iter().enumerate() {
        let mine: Vec<usize> = (0..t.len()).filter(|&k| method[k] == m.as_str()).collect();
        if mine.is_empty() {
            continue;
        }
        let ok: Vec<usize> = mine
            .iter()
            .copied()
            .filter(|&k| status[k] == "ok")
            .collect();
        let failed: Vec<&str> = mine
            .iter()
            .filter(|&&k| status[k] != "ok")
            .map(|&k| param[k])
            .collect();
        let err = |k: usize| ea[k].max(er[k]).max(DRAW_FLOOR);
        let wall_of = |k: usize| {
            (0..w.len())
                .find(|&j| wm[j] == method[k] && wp[j] == param[k])
                .map_or(f64::NAN, |j| wall[j])
        };
        let mut label = format!("{} ({})", m.as_str().to_uppercase(), m.accuracy_name());
        if let (Some(&a), Some(&b)) = (ok.first(), ok.last()) {
            label.push_str(&format!(" {} … {}", param[a], param[b]));
        }
        if !failed.is_empty() {
            label.push_str(&format!("; fails at {}", failed.join(", ")));
        }
        let style = if m == Method::Auto {
            Style::Dashed
        } else {
            Style::LinePoints
        };
        let by_wall: Vec<(f64, f64)> = ok
            .iter()
            .map(|&k| (wall_of(k), err(k)))
            .filter(|p| p.0.is_finite())
            .collect();
        let by_steps: Vec<(f64, f64)> = ok.iter().map(|&k| (steps[k], err(k))).collect();
        left.series
            .push(Series::new(label, by_wall, style).with_color(palette(i)));
        right
            .series
            .push(Series::new("", by_steps, style).with_color(palette(i)));
    }
    for p in [&mut left, &mut right] {
        p.log_x = true;
        p.log_y = true;
    }
    right.annotations = vec![
        format!("rtol = atol; reference: the IVP test set's at t = 5"),
        format!("the rates y41, y80 set the error (floor {})", exp(1e-8)),
    ];
    figures::line_plot_pair(
        &left,
        &right,
        "Work-precision: BEAM (IVP test set; 40 segments, t = 0 … 5)",
        stem,
    )
    .map_err(|e| e.to_string())
}
