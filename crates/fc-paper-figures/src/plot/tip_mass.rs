//! The drawing of the `tip-mass-fall` figure (`crate::tip_mass`):
//! the folded chain with a tip mass against the energy-conserving law, the
//! fall time over free fall and the tip speed at the end of the fall.

use std::path::Path;

use figures::{palette, LinePlot, Marker, Output, RGBColor, Series, Style};

use super::Reader;

/// The runs of `<id>.csv` (`ratio,t_fall,v_fall,t_law,v_law`, `links` rods)
/// against the law's curves of `<id>-law.csv` (`ratio,t_law,v_final`).
pub fn fall(read: Reader, stem: &Path, links: usize) -> Result<Output, String> {
    let runs = read("")?;
    let (k, t, v) = (
        runs.nums("ratio")?,
        runs.nums("t_fall")?,
        runs.nums("v_fall")?,
    );
    let (t_law, v_law) = (runs.nums("t_law")?, runs.nums("v_law")?);
    let law = read("-law")?;
    let (lk, lt, lv) = (law.nums("ratio")?, law.nums("t_law")?, law.nums("v_final")?);
    let black = RGBColor(0, 0, 0);
    let zip = |a: &[f64], b: &[f64]| a.iter().copied().zip(b.iter().copied()).collect();
    let mut left = LinePlot::new(
        "fall time over free fall sqrt(2L/g)",
        "M / m_c",
        "t_fall / sqrt(2 L / g)",
    );
    left.series
        .push(Series::new("law (full extension)", zip(&lk, &lt), Style::Dashed).with_color(black));
    // The law where the runs are measured: open marks over the runs' line.
    left.series.push(
        Series::new("law at 0.99 (L - l)", zip(&k, &t_law), Style::Points)
            .with_color(palette(1))
            .with_marker(Marker::Diamond)
            .hollow(),
    );
    left.series.push(
        Series::new(
            format!("n = {links}, r = 0"),
            zip(&k, &t),
            Style::LinePoints,
        )
        .with_color(palette(0)),
    );
    left.log_x = true;
    let mut right = LinePlot::new(
        "tip speed at the end of the fall",
        "M / m_c",
        "|v| / sqrt(g L)",
    );
    right.series.push(
        Series::new(
            "law at full extension: sqrt(2 (1 + m_c / 4M))",
            zip(&lk, &lv),
            Style::Dashed,
        )
        .with_color(black),
    );
    right.series.push(
        Series::new("law at 0.99 (L - l)", zip(&k, &v_law), Style::Points)
            .with_color(palette(1))
            .with_marker(Marker::Diamond)
            .hollow(),
    );
    right.series.push(
        Series::new(
            format!("n = {links}, r = 0"),
            zip(&k, &v),
            Style::LinePoints,
        )
        .with_color(palette(0)),
    );
    right.log_x = true;
    right.log_y = true;
    figures::line_plot_pair(
        &left,
        &right,
        "Folded chain with a tip mass M: runs against the energy-conserving law",
        stem,
    )
    .map_err(|e| e.to_string())
}
