//! The studies of any scene, as plain data: work-precision ([`precision`]),
//! where each method fails ([`stability`]), and what a scene needs
//! ([`needs`]: rods, method and tolerance, physical terms), sharded and
//! budgeted by fc-batch; the convergence in n ([`converge`]); the `EA`
//! above which a scene may use rigid links ([`rigid_limit`]); the snap's
//! force, impulse and tension ([`snap`]); the measured unit costs that
//! weight the implicit methods' work ([`work_cost`]).
//!
//! Each takes a prepared scene (or a scene) and options and returns typed
//! rows, with the text of its CSV table (the CSV layer, fc-csv); it knows
//! nothing of figure files or of the paper. The drawings of its tables
//! ([`plot`], and a run's snapshots, [`render`]) are behind the `plot`
//! feature, so that Python builds without plotters. The CLI's `precision`,
//! `stability`, `needs`, `converge` and `merge`, Python's functions of the
//! same names and fc-paper-figures (the paper's figures) call these.

pub mod converge;
pub mod needs;
#[cfg(feature = "plot")]
pub mod plot;
pub mod precision;
#[cfg(feature = "plot")]
pub mod render;
pub mod rigid_limit;
pub mod snap;
pub mod stability;
pub mod work_cost;

use chain_ode::Method;

use fc_scene::error::{echo, Error};

/// The median of `xs` (NaN if empty).
pub fn median(xs: &[f64]) -> f64 {
    let mut v = xs.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        k if k % 2 == 1 => v[k / 2],
        k => 0.5 * (v[k / 2 - 1] + v[k / 2]),
    }
}

/// Parses `--methods rk4,dop853`: method names (each at most once, in
/// `Method::ALL` order); `None` (the flag not given): every method. An
/// empty list (`--methods ""`, Python's `methods=[]`) is refused: it names
/// no method to run.
pub fn parse_methods(what: &str, text: Option<&str>) -> Result<Vec<Method>, Error> {
    let Some(text) = text else {
        return Ok(Method::ALL.to_vec());
    };
    let names: Vec<&str> = Method::ALL.iter().map(|m| m.as_str()).collect();
    if text.trim().is_empty() {
        return Err(Error::field(
            what,
            format!(
                "names no method: give one or more of {}, separated by commas",
                names.join(", ")
            ),
        ));
    }
    let mut chosen = vec![];
    for name in text.split(',').map(str::trim) {
        let m = Method::ALL
            .into_iter()
            .find(|m| m.as_str() == name)
            .ok_or_else(|| {
                Error::field(
                    what,
                    format!("'{}' is not one of {}", echo(name), names.join(", ")),
                )
            })?;
        if !chosen.contains(&m) {
            chosen.push(m);
        }
    }
    Ok(Method::ALL
        .into_iter()
        .filter(|m| chosen.contains(m))
        .collect())
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
}
