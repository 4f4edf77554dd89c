//! The drawings of the energy budget and the normal modes
//! (`crate::validation`).

use std::path::Path;

use figures::{palette, LinePlot, Output, Series, Style};

use super::Reader;
use fc_csv::table::distinct;

/// Draws `energy`'s tables to `<stem>.png` and `.svg`.
pub fn energy_budget(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let damping = t.strs("damping")?;
    let (scale, time) = (t.nums("energy_scale")?, t.nums("t")?);
    let (energy, dissipated, balance) = (
        t.nums("energy")?,
        t.nums("dissipated")?,
        t.nums("balance_over_MgL")?,
    );
    let mut left = LinePlot::new("energy change and dissipated work", "t", "energy / (M g L)");
    let mut right = LinePlot::new("energy balance", "t", "|E(t) + W(t) - E(0)| / (M g L)");
    right.log_y = true;
    let mut notes = vec![];
    for (i, r) in distinct(&damping).into_iter().enumerate() {
        let rows: Vec<usize> = (0..t.len()).filter(|&k| damping[k] == r).collect();
        let e0 = energy[rows[0]];
        let de = rows
            .iter()
            .map(|&k| (time[k], (energy[k] - e0) / scale[k]))
            .collect();
        left.series
            .push(Series::line(format!("E - E(0), r = {r}"), de).with_color(palette(i)));
        if fc_csv::table::parse_num(r)? > 0.0 {
            let w = rows
                .iter()
                .map(|&k| (time[k], dissipated[k] / scale[k]))
                .collect();
            left.series
                .push(Series::new(format!("W, r = {r}"), w, Style::Dashed).with_color(palette(i)));
        }
        let bal: Vec<(f64, f64)> = rows.iter().map(|&k| (time[k], balance[k].abs())).collect();
        let worst = bal.iter().map(|b| b.1).fold(0.0, f64::max);
        notes.push(format!("r = {r}: {worst:.1e}"));
        right
            .series
            .push(Series::line(format!("r = {r}"), bal).with_color(palette(i)));
    }
    right.annotations = vec!["max over the samples:".to_string()];
    right.annotations.extend(notes);
    right.y_range = Some((1e-17, 1e-9));
    let title = "Energy budget, span d = 3 (n = 50): dE/dt = -2R, W' = 2R (DOPRI5, rtol 1e-10)";
    let out = figures::line_plot_pair(&left, &right, title, stem).map_err(|e| e.to_string())?;
    Ok(out)
}

/// Two significant digits: what a fit over n = 40 .. 400 determines of
/// `C` (its fitted order moves in the second decimal).
fn two_digits(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return format!("{x}");
    }
    let decimals = (1 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

/// Draws `modes`'s tables to `<stem>.png` and `.svg`: the relative error
/// of each mode against n (the frequencies themselves, on the scale of
/// the continuum's, are indistinguishable from it: their values go to the
/// legend).
pub fn normal_modes(read: Reader, stem: &Path) -> Result<Output, String> {
    let t = read("")?;
    let (links, mode, rel) = (t.nums("links")?, t.strs("mode")?, t.nums("relative_error")?);
    let bessel = t.nums("omega_bessel_sqrt_L_over_g")?;
    let f = read("-fit")?;
    let (fit_mode, order, coefficient) =
        (f.strs("mode")?, f.nums("order")?, f.nums("coefficient")?);
    let fit_from = f.strs("fit_from_links")?.first().copied().unwrap_or("?");
    let mut p = LinePlot::new(
        "Hanging chain: n rods against the continuum (j_0k / 2)",
        "n (rods)",
        "ω_n / ω_Bessel - 1 (positive: the chain is stiffer)",
    );
    p.log_x = true;
    p.log_y = true;
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for (k, m) in distinct(&mode).into_iter().enumerate() {
        let rows: Vec<usize> = (0..t.len()).filter(|&j| mode[j] == m).collect();
        let fit = fit_mode
            .iter()
            .position(|x| *x == m)
            .map_or(String::new(), |j| {
                format!(": p = {:.2}, C = {}", order[j], two_digits(coefficient[j]))
            });
        let pts: Vec<(f64, f64)> = rows.iter().map(|&j| (links[j], rel[j])).collect();
        for q in &pts {
            lo = lo.min(q.1);
            hi = hi.max(q.1);
        }
        p.series.push(
            Series::new(
                format!("mode {m} (ω √(L/g) → {:.3}){fit}", bessel[rows[0]]),
                pts,
                Style::LinePoints,
            )
            .with_color(palette(k)),
        );
    }
    p.x_range = Some((8.0, 500.0));
    if lo.is_finite() && hi > 0.0 {
        // Half a decade below; above, room for the legend.
        p.y_range = Some((lo / 3.0, hi * 300.0));
    }
    p.annotations = vec![format!("fit over n ≥ {fit_from}: error = C / n^p")];
    figures::line_plot(&p, stem).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::two_digits;

    /// The fitted coefficients as the legend prints them: two significant
    /// digits, whatever their size.
    #[test]
    fn coefficients_keep_two_significant_digits() {
        assert_eq!(two_digits(0.030617790075241774), "0.031");
        assert_eq!(two_digits(1.0170717309734207), "1.0");
        assert_eq!(two_digits(4.2081903440732376), "4.2");
        assert_eq!(two_digits(10.022663429386704), "10");
        assert_eq!(two_digits(17.53523819368095), "18");
    }
}
