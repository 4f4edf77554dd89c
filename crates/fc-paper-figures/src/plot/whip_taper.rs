//! The drawing of the tapered whip's table (`crate::whip_taper`):
//! the largest tip speed against the taper, a line per `n`, and its gain
//! over the uniform chain.

use std::path::Path;

use figures::{palette, LinePlot, Output, Series, Style};

use super::Reader;
use fc_csv::table::distinct;

pub fn whip_taper(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (links, taper, v, gain) = (
        t.strs("links")?,
        t.nums("taper")?,
        t.nums("v_max_over_sqrt_gL")?,
        t.nums("gain")?,
    );
    let converged = t.nums("converged_links")?;
    let worst = converged.iter().copied().fold(0.0, f64::max);
    let mut left = LinePlot::new(
        "largest tip speed, span d = 3 released",
        "taper: mass per length at the pivot / at the tip",
        "max |v_tip| / sqrt(g L)",
    );
    let mut right = LinePlot::new(
        "gain over the uniform chain",
        "taper: mass per length at the pivot / at the tip",
        "max |v_tip| / max |v_tip|(taper 1)",
    );
    for (i, n) in distinct(&links).into_iter().enumerate() {
        let pick = |y: &[f64]| -> Vec<(f64, f64)> {
            (0..t.len())
                .filter(|&k| links[k] == n)
                .map(|k| (taper[k], y[k]))
                .collect()
        };
        left.series.push(
            Series::new(format!("n = {n}"), pick(&v), Style::LinePoints).with_color(palette(i)),
        );
        right.series.push(
            Series::new(format!("n = {n}"), pick(&gain), Style::LinePoints).with_color(palette(i)),
        );
    }
    left.log_x = true;
    right.log_x = true;
    figures::line_plot_pair(
        &left,
        &right,
        &format!("Tapered whip, span d = 3: converged in n from n = {worst} (1% in max speed)"),
        stem,
    )
    .map_err(|e| e.to_string())
}
