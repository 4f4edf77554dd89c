//! BEAM, the study's one external benchmark (`chain_ode::beam`: the IVP
//! test set's stiff beam of 40 segments on `[0, 5]`): every method over a
//! range of its accuracy parameter, each run's work counters and its
//! errors at `t = 5` against the test set's published reference, in the
//! angles (`y1`, `y40`) and in the rates (`y41`, `y80`). The figure
//! `beam-precision` draws the table ([`super::plot::beam::precision`]);
//! the wall times go to a table of their own ([`timing_text`]), so that
//! [`csv_text`] reproduces to the byte.

use std::fmt::Write as _;

use chain_ode::beam::REFERENCE;
use chain_ode::{solve, BeamModel, InvalidParameter, Method, Trajectory};
use rayon::prelude::*;

use fc_csv::format::{exp, exp_digits, num};

/// The adaptive methods' tolerances (`rtol = atol`, the test set's way).
pub const RTOLS: [f64; 6] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];

/// RK4's steps: its stability limit lies between the last two.
pub const RK4_DTS: [f64; 5] = [1e-4, 2e-4, 3e-4, 4e-4, 5e-4];

/// Every point of the figure: each method at each of its parameters, in
/// `Method::ALL` order.
pub fn grid() -> Vec<(Method, f64)> {
    Method::ALL
        .into_iter()
        .flat_map(|m| {
            let xs: &[f64] = if m.adaptive() { &RTOLS } else { &RK4_DTS };
            xs.iter().map(move |&x| (m, x))
        })
        .collect()
}

/// One run and its errors.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The run (its final state is the test set's `y` at `t = 5`).
    pub run: Trajectory<BeamModel>,
    /// Its accuracy parameter (`dt` for RK4, else `rtol = atol`).
    pub accuracy: f64,
    /// `max(|y1 - ref|, |y40 - ref|)` at `t = 5` (rad; NaN unless ok).
    pub err_angles: f64,
    /// `max(|y41 - ref|, |y80 - ref|)` (rad per time unit; NaN unless ok).
    pub err_rates: f64,
}

impl Row {
    /// The row of a finished run.
    pub fn of(run: Trajectory<BeamModel>, accuracy: f64) -> Self {
        let e = |k: usize| {
            let (i, r) = REFERENCE[k];
            if run.status.is_ok() {
                (BeamModel::component(&run.final_state, i) - r).abs()
            } else {
                f64::NAN
            }
        };
        Self {
            err_angles: e(0).max(e(1)),
            err_rates: e(2).max(e(3)),
            run,
            accuracy,
        }
    }
}

/// The test set's run of `method` at `accuracy` ([`BeamModel::options`]).
pub fn run(method: Method, accuracy: f64) -> Result<Trajectory<BeamModel>, InvalidParameter> {
    let model = BeamModel::new();
    let start = model.start();
    solve(
        model,
        &start,
        method,
        &BeamModel::options(method, accuracy)?,
    )
}

/// Runs every point of `points`: one at a time when `timed` (their wall
/// times mean something then), else in parallel.
pub fn rows(points: &[(Method, f64)], timed: bool) -> Result<Vec<Row>, String> {
    let one = |&(m, x): &(Method, f64)| {
        run(m, x)
            .map(|t| Row::of(t, x))
            .map_err(|e| format!("beam {m} {x:e}: {e}"))
    };
    if timed {
        points.iter().map(one).collect()
    } else {
        points.par_iter().map(one).collect()
    }
}

/// The table (no wall times: it reproduces to the byte).
pub fn csv_text(rows: &[Row]) -> String {
    let mut s = String::from(
        "method,param_name,param,status,t_reached,steps,rejected_steps,rhs_evals,\
         jacobian_evals,lu_factorizations,err_angles,err_rates\n",
    );
    for r in rows {
        let (run, st) = (&r.run, &r.run.stats);
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            run.method,
            run.method.accuracy_name(),
            exp(r.accuracy),
            run.status,
            num(run.t_reached),
            st.steps,
            st.rejected_steps,
            st.rhs_evals,
            st.jacobian_evals,
            st.lu_factorizations,
            exp(r.err_angles),
            exp(r.err_rates),
        );
    }
    s
}

/// The wall times of the same runs: `method,param,wall_seconds`.
pub fn timing_text(rows: &[Row]) -> String {
    let mut s = String::from("method,param,wall_seconds\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{}",
            r.run.method,
            exp(r.accuracy),
            exp_digits(r.run.summary.wall_seconds, 3)
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc_csv::table::Table;

    /// The grid holds every method, and the table reads back with one row
    /// per run and NaN errors for a failed one.
    #[test]
    fn the_table_reads_back() {
        let g = grid();
        for m in Method::ALL {
            assert!(g.iter().any(|&(k, _)| k == m), "{m}");
        }
        let rows = rows(&[(Method::Rk4, 3e-4), (Method::Rk4, 1e-3)], false).expect("valid");
        let t = Table::parse("beam", &csv_text(&rows)).expect("parses");
        assert_eq!(t.len(), 2);
        let status = t.strs("status").expect("column");
        assert_eq!(status, ["ok", "diverged"]);
        let e = t.nums("err_rates").expect("column");
        assert!(e[0] < 1e-6 && e[1].is_nan(), "{e:?}");
        let w = Table::parse("timing", &timing_text(&rows)).expect("parses");
        assert_eq!(w.len(), 2);
    }
}
