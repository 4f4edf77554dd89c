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
pub mod validation_convergence;
pub mod validation_energy;
pub mod validation_folded;
pub mod validation_modes;

use chain_ode::{Method, SolveOptions};

/// The name of the accuracy parameter of `method`: RK4's step `dt`, the
/// adaptive methods' `rtol`.
pub fn accuracy_name(method: Method) -> &'static str {
    method.accuracy_name()
}

/// `options` with the accuracy of `method` set to `x`: RK4's step, or the
/// adaptive methods' `rtol` (with `atol = rtol / 100`).
pub fn at_accuracy(options: &SolveOptions, method: Method, x: f64) -> SolveOptions {
    options.clone().at_accuracy(method, x)
}

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

    #[test]
    fn accuracy_is_dt_or_rtol() {
        let o = SolveOptions::default();
        assert_eq!(at_accuracy(&o, Method::Rk4, 1e-3).dt, 1e-3);
        let a = at_accuracy(&o, Method::Dopri5, 1e-6);
        assert_eq!((a.rtol, a.atol), (1e-6, 1e-6 * 1e-2));
        assert_eq!(accuracy_name(Method::Rk4), "dt");
        assert_eq!(accuracy_name(Method::Bdf), "rtol");
    }
}
