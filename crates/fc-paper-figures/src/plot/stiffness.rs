//! The drawing of where BDF pays (`crate::stiffness`): left, DOPRI5's
//! cost over BDF's at matched error against the damping rate, a line per
//! `n`, with the equal-cost line and, on it, the rate past which `auto`
//! runs BDF for each `n`; right, the measured crossover against `n` beside
//! `auto`'s rule.

use std::path::Path;

use figures::{palette, LinePlot, Output, RGBColor, Series, Style};

use super::Reader;
use crate::stiffness::{TARGET, T_END};
use fc_csv::format::exp;
use fc_csv::table::distinct;

/// A crossover's label: one decimal below 10 (`3.2`), the nearest whole
/// number from there (`16`, `106`), so that the figure prints the number
/// the text quotes from the same table.
fn crossover_label(x: f64) -> String {
    if x.abs() < 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.0}")
    }
}

/// Draws `stiffness`'s tables to `<stem>.png` and `.svg`.
pub fn stiffness(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("-timing")?;
    let (n, gamma, ratio) = (
        t.strs("n")?,
        t.nums("gamma")?,
        t.nums("ratio_dopri5_over_bdf")?,
    );
    let c = read("-crossover-timing")?;
    let (cn, measured, rule) = (
        c.nums("n")?,
        c.nums("gamma_crossover")?,
        c.nums("gamma_crossover_rule")?,
    );
    let rods = distinct(&n);
    let shown: Vec<usize> = (0..t.len()).filter(|&j| ratio[j].is_finite()).collect();
    let (lo, hi) = shown
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, &j| {
            (a.0.min(ratio[j]), a.1.max(ratio[j]))
        });
    let (g0, g1) = shown
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |a, &j| {
            (a.0.min(gamma[j]), a.1.max(gamma[j]))
        });

    let mut left = LinePlot::new(
        "",
        "damping rate γ = r / (m l²)",
        "DOPRI5 cost / BDF cost at equal error",
    );
    left.log_x = true;
    left.log_y = true;
    if lo.is_finite() && hi.is_finite() {
        left.y_range = Some((lo.min(1.0) / 2.0, hi.max(1.0) * 4.0));
    }
    for (k, rods_n) in rods.iter().enumerate() {
        let pts = shown
            .iter()
            .filter(|&&j| n[j] == *rods_n)
            .map(|&j| (gamma[j], ratio[j]))
            .collect();
        left.series.push(
            Series::new(format!("n = {rods_n}"), pts, Style::LinePoints).with_color(palette(k)),
        );
    }
    if g0.is_finite() && g1.is_finite() {
        left.series.push(
            Series::new("equal cost", vec![(g0, 1.0), (g1, 1.0)], Style::Dashed)
                .with_color(RGBColor(0, 0, 0)),
        );
    }
    // auto's rule for each n, on the equal-cost line in that n's colour.
    for (k, rods_n) in rods.iter().enumerate() {
        let at: Vec<(f64, f64)> = (0..c.len())
            .filter(|&j| format!("{}", cn[j]) == *rods_n && rule[j].is_finite())
            .map(|j| (rule[j], 1.0))
            .collect();
        let label = if k == 0 { "auto's rule γc(n)" } else { "" };
        left.series
            .push(Series::new(label, at, Style::Points).with_color(palette(k)));
    }

    let mut right = LinePlot::new("", "rods n", "crossover damping rate γ");
    right.log_x = true;
    right.log_y = true;
    let pts: Vec<(f64, f64)> = (0..c.len())
        .filter(|&j| measured[j].is_finite())
        .map(|j| (cn[j], measured[j]))
        .collect();
    right
        .series
        .push(Series::new("measured, equal error", pts, Style::Points).with_color(palette(0)));
    let rule_pts: Vec<(f64, f64)> = (0..c.len()).map(|j| (cn[j], rule[j])).collect();
    right
        .series
        .push(Series::new("auto's rule", rule_pts, Style::Line).with_color(palette(1)));
    for j in 0..c.len() {
        if measured[j].is_finite() {
            right.annotations.push(format!(
                "n = {}: {} (rule {})",
                cn[j],
                crossover_label(measured[j]),
                crossover_label(rule[j])
            ));
        }
    }
    let title = format!(
        "Where BDF pays, at matched error {} (span d = 3, t = 0 .. {T_END}, whip included)",
        exp(TARGET)
    );
    let out = figures::line_plot_pair(&left, &right, &title, stem).map_err(|e| e.to_string())?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::crossover_label;

    #[test]
    fn crossover_labels_are_the_tables_numbers_rounded() {
        assert_eq!(crossover_label(15.543), "16");
        assert_eq!(crossover_label(105.9), "106");
        assert_eq!(crossover_label(1055.0), "1055");
        assert_eq!(crossover_label(3.24), "3.2");
    }
}
