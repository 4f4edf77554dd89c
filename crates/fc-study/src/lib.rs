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
//! `stability`, `needs`, `ensemble`, `converge` and `merge`, Python's functions of the
//! same names and fc-paper-figures (the paper's figures) call these.
//!
//! Its files:
//! * `converge.rs`: Convergence in the number of rods: one scene run at several `n` with the continuum held fixed, and the smallest `n` that agrees with the finest.
//! * `ensemble_series.rs`: An ensemble's time series: the mean, standard error, standard deviation and range over the members of every per-sample output.
//! * `ensemble.rs`: `ensemble`: a scene run from `members` starts whose rod angles are moved by a few `spread` rad, and the statistics of its summary over them (`docs/model.md` ...
//! * `measure.rs`: What a study measures (`--measure`): the tip, the largest tip speed, the peak forces, the floor's reading, the work dissipated; their values and relative errors.
//! * `needs.rs`: "Model no more than this scene needs": the smallest number of rods, the fastest method and tolerance at that number ...
//! * `plot.rs`: The one drawing of the study's tables, used by the CLI's `--plot` and by `cargo xtask figures` alike: the work-precision pair (error against wall time and against work ...
//! * `precision/`: Work-precision: every method across tolerances (RK4 across steps), the error of two well-conditioned quantities (the tip position at the end ...
//! * `render.rs`: From finished trajectories to the figures crate's plain data: chain frames, tip speed and tip velocity series.
//! * `rigid_limit.rs`: "When can I use the rigid model": the axial stiffness `EA` above which a scene's elastic chain agrees with its rigid one within `tol`.
//! * `snap.rs`: The snap at full extension: the force and the impulse on the support, and the tension along the chain around it.
//! * `stability.rs`: Where each method fails: every method at every step or tolerance, each run to the scene's end under a step budget ...
//! * `subject.rs`: What a work-precision study runs: a `Subject` is a model with its start and its run's options ...
//! * `work_cost.rs`: The work of a run in one currency: right-hand-side equivalents, with BDF's residuals (each followed by a Newton solve) ...

pub mod converge;
pub mod ensemble;
pub mod ensemble_series;
pub mod measure;
pub mod needs;
#[cfg(feature = "plot")]
pub mod plot;
pub mod precision;
#[cfg(feature = "plot")]
pub mod render;
pub mod rigid_limit;
pub mod snap;
pub mod stability;
pub mod subject;
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
/// `Method::ALL` order); `None` (the flag not given): every method of
/// smooth problems (all but `moreau-jean`, which runs a chain on a
/// constraint floor alone: name it to study one). An
/// empty list (`--methods ""`, Python's `methods=[]`) is refused: it names
/// no method to run.
pub fn parse_methods(what: &str, text: Option<&str>) -> Result<Vec<Method>, Error> {
    let Some(text) = text else {
        return Ok(Method::ALL
            .into_iter()
            .filter(|m| !m.is_nonsmooth())
            .collect());
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

    /// The tables' headers are the declared columns' names (the bytes of
    /// `figures/data/` and of `--out`), and a column name has one type in
    /// every table that has it (so that a merged shard reads the same).
    #[test]
    fn declared_columns_are_the_headers_and_agree() {
        assert_eq!(
            fc_csv::header(&precision::COLUMNS),
            "scene,t_eval,method,param_name,param,status,t_reached,steps,rejected_steps,\
             rhs_evals,jacobian_evals,lu_factorizations,rhs_equiv,switched,err_tip,err_vmax,\
             tip_ref_x,tip_ref_y,vmax_ref,note"
        );
        assert_eq!(
            fc_csv::header(&stability::COLUMNS),
            "scene,label,links,damping,damping_rate,t_end,method,param_name,param,outcome,\
             status,t_reached,t_failed,steps,rejected_steps,rhs_evals,energy_balance_error,\
             energy_scale_mgl,energy_error_rel,bdf_from,note"
        );
        let all: [&[(&str, fc_csv::Column)]; 6] = [
            &precision::COLUMNS,
            &precision::CLI_COLUMNS,
            &stability::COLUMNS,
            &stability::CLI_COLUMNS,
            &fc_scene::SUMMARY_CSV_COLUMNS,
            &fc_batch::shard::COLUMNS,
        ];
        for cols in all {
            for &(name, kind) in cols {
                assert_eq!(fc_csv::column_type(&all, name), Some(kind), "{name}");
            }
        }
    }
}
