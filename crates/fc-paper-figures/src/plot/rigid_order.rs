//! The drawing of the rigid limit's order (`crate::rigid_order`):
//! the elastic chain's distance from the rigid one against `EA`, log-log,
//! the tip path (left) and the tip at the end (right), a line per scene,
//! with a `1/EA` guide and the fitted orders.

use std::path::Path;

use figures::{palette, LinePlot, Output, RGBColor, Series, Style};

use super::Reader;
use fc_csv::table::distinct;

/// Draws `elastic-rigid-order`'s tables to `<stem>.png` and `.svg`.
pub fn rigid_order(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (scene, ea) = (t.strs("scene")?, t.nums("axial_stiffness")?);
    let (path, speed) = (t.nums("tip_path")?, t.nums("tip_end")?);
    let f = read("-fit")?;
    let (f_scene, f_path, f_speed) = (
        f.strs("scene")?,
        f.nums("order_tip_path")?,
        f.nums("order_tip_end")?,
    );
    let mut left = LinePlot::new("tip path: max |tip − tip_rigid| / L", "EA", "distance");
    let mut right = LinePlot::new("tip at t_end: |tip − tip_rigid| / L", "EA", "distance");
    for p in [&mut left, &mut right] {
        p.log_x = true;
        p.log_y = true;
    }
    let (mut notes_l, mut notes_r) = (
        vec!["fitted order in 1/EA:".to_string()],
        vec!["fitted order in 1/EA:".to_string()],
    );
    for (k, s) in distinct(&scene).into_iter().enumerate() {
        let rows: Vec<usize> = (0..t.len()).filter(|&j| scene[j] == s).collect();
        let pts = |col: &[f64]| -> Vec<(f64, f64)> {
            rows.iter()
                .filter(|&&j| col[j].is_finite() && col[j] > 0.0)
                .map(|&j| (ea[j], col[j]))
                .collect()
        };
        let (pp, ps) = (pts(&path), pts(&speed));
        // A 1/EA guide through each line's last point, a factor 3 below.
        for (p, line) in [(&mut left, &pp), (&mut right, &ps)] {
            if let (Some(first), Some(last)) = (line.first(), line.last()) {
                let at = |x: f64| last.1 / 3.0 * last.0 / x;
                let label = if k == 0 { "∝ 1/EA" } else { "" };
                p.series.push(
                    Series::new(
                        label,
                        vec![(first.0, at(first.0)), (last.0, at(last.0))],
                        Style::Dashed,
                    )
                    .with_color(RGBColor(0, 0, 0)),
                );
            }
        }
        left.series
            .push(Series::new(s, pp, Style::LinePoints).with_color(palette(k)));
        right
            .series
            .push(Series::new(s, ps, Style::LinePoints).with_color(palette(k)));
        if let Some(j) = f_scene.iter().position(|x| *x == s) {
            notes_l.push(format!("{s}: {:.2}", f_path[j]));
            notes_r.push(format!("{s}: {:.2}", f_speed[j]));
        }
    }
    left.annotations = notes_l;
    right.annotations = notes_r;
    let title = "The rigid limit of the elastic chain, before the whip";
    figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())
}
