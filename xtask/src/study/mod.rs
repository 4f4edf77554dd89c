//! The study's figures (`docs/figures.md`, "The study's figures"), one file
//! per subject: speed against accuracy (`precision_*`: work-precision,
//! stability map, stiffness, right-hand-side cost) and validation against
//! physics (`validation_*`: convergence in n, the folded chain against its
//! law and the support force, the energy budget, normal modes). Each is a
//! [`crate::registry::Make`] listed in the registry.
//!
//! Timed runs run alone, never beside another timed run, and only with
//! `--timings`; untimed runs run in parallel on [`crate::ctx::Ctx::pool`].

pub mod precision_cost;
pub mod precision_map;
pub mod precision_matched;
pub mod precision_stiffness;
pub mod precision_wp;
pub mod tip_mass_fall;
pub mod validation_convergence;
pub mod validation_energy;
pub mod validation_folded;
pub mod validation_modes;

/// Least-squares intercept and slope of `y = a + b x`.
pub fn linear_fit(pts: &[(f64, f64)]) -> (f64, f64) {
    let k = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mx, my) = (sx / k, sy / k);
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let b = sxy / sxx;
    (my - b * mx, b)
}

/// Least-squares slope of `log y` against `log x`.
pub fn log_slope(pts: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = pts.iter().map(|&(x, y)| (x.ln(), y.ln())).collect();
    linear_fit(&logs).1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slope_of_a_power_law() {
        let pts: Vec<(f64, f64)> = [10.0, 100.0, 1000.0]
            .iter()
            .map(|&n: &f64| (n, 2.0 * n.powi(3)))
            .collect();
        assert!((log_slope(&pts) - 3.0).abs() < 1e-12);
        let (a, b) = linear_fit(&[(0.0, 1.0), (1.0, 3.0), (2.0, 5.0)]);
        assert!((a - 1.0).abs() < 1e-12 && (b - 2.0).abs() < 1e-12);
    }
}
