//! The drawing of the accuracy table (`crate::accuracy`): per
//! scene, RK4's error against its step and the scene's own run's error.

use std::path::Path;

use figures::{palette, LinePlot, Output, Series, Style};

use super::Reader;
use crate::accuracy::RK4_STEPS;
use fc_csv::table::distinct;

/// Errors below this are drawn at it (a log axis cannot show 0).
const FLOOR: f64 = 1e-13;

/// Draws the table in two panels (so that each keeps its colours
/// distinct): the horizontal and catenary starts, then the spans, heights
/// and the folded chain.
pub fn draw(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (scene, setting, status) = (t.strs("scene")?, t.strs("setting")?, t.strs("status")?);
    let (dt, error) = (t.nums("dt")?, t.nums("error")?);
    let y_label = "largest relative error";
    let mut panels = [
        LinePlot::new("Figs. 3-6", "RK4 step dt", y_label),
        LinePlot::new("Figs. 7-12", "RK4 step dt", y_label),
    ];
    for p in &mut panels {
        p.log_x = true;
        p.log_y = true;
        // A tick at each of RK4's steps.
        p.x_ticks = Some(RK4_STEPS.to_vec());
    }
    let mut counts = [0usize; 2];
    let mut floored = false;
    for name in distinct(&scene) {
        let panel =
            usize::from(name.starts_with("span") || name.starts_with("height") || name == "folded");
        let colour = palette(counts[panel]);
        counts[panel] += 1;
        let rows: Vec<usize> = (0..t.len()).filter(|&k| scene[k] == name).collect();
        let rk4: Vec<(f64, f64)> = rows
            .iter()
            .filter(|&&k| setting[k].starts_with("rk4") && status[k] == "ok")
            .map(|&k| (dt[k], error[k].max(FLOOR)))
            .collect();
        panels[panel]
            .series
            .push(Series::new(name, rk4, Style::LinePoints).with_color(colour));
        if let Some(&k) = rows
            .iter()
            .find(|&&k| setting[k] == "scene" && status[k] == "ok")
        {
            let own = vec![
                (RK4_STEPS[RK4_STEPS.len() - 1], error[k].max(FLOOR)),
                (RK4_STEPS[0], error[k].max(FLOOR)),
            ];
            panels[panel]
                .series
                .push(Series::new("", own, Style::Dashed).with_color(colour));
            if error[k] < FLOOR {
                floored = true;
            }
        }
    }
    for p in &mut panels {
        p.annotations = vec!["dashed: the scene's own settings".to_string()];
        if floored {
            p.annotations
                .push(format!("errors below {FLOOR:.0e} drawn at {FLOOR:.0e}"));
        }
    }
    for k in (0..t.len()).filter(|&k| status[k] != "ok") {
        panels[1]
            .annotations
            .push(format!("{} {}: {}", scene[k], setting[k], status[k]));
    }
    let title = "Report scenes against DOP853 at rtol 1e-12: the largest relative error of v_max, W and the tip's end";
    figures::line_plot_pair(&panels[0], &panels[1], title, stem).map_err(|e| e.to_string())
}
