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
use chain_ode::{Accuracy, BeamModel, InvalidParameter, Method, SolveOptions, State, Trajectory};
use fc_study::precision::{self, Point, Reference};
use fc_study::subject::Subject;
use rayon::prelude::*;

use fc_csv::format::{exp, exp_digits, num};

/// The adaptive methods' tolerances (`rtol = atol`, the test set's way).
pub const RTOLS: [f64; 6] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];

/// RK4's steps: its stability limit lies between the last two.
pub const RK4_DTS: [f64; 5] = [1e-4, 2e-4, 3e-4, 4e-4, 5e-4];

/// Every point of the figure: each of the paper's methods
/// ([`crate::PAPER_METHODS`]) at each of its parameters, in that order.
pub fn grid() -> Vec<(Method, f64)> {
    crate::PAPER_METHODS
        .into_iter()
        .flat_map(|m| {
            let xs: &[f64] = if m.adaptive() { &RTOLS } else { &RK4_DTS };
            xs.iter().map(move |&x| (m, x))
        })
        .collect()
}

/// BEAM as the precision study's subject ([`fc_study::subject`]): the test
/// set's options per point ([`BeamModel::options`]: `rtol = atol`, to
/// `t = 5` within [`chain_ode::BEAM_MAX_STEPS`]) and its errors against
/// the test set's published solution at `t = 5`: `max(|y1 - ref|, |y40 -
/// ref|)` in the angles (rad) and `max(|y41 - ref|, |y80 - ref|)` in the
/// rates (rad per time unit), in the study's two error columns. The study's
/// reference run is not what BEAM's errors are measured against; run, it
/// is measured against the published solution as every other run is.
#[derive(Clone, Debug)]
pub struct Beam {
    model: BeamModel,
    state: State,
    options: SolveOptions,
}

impl Beam {
    /// The test set's BEAM (40 segments on `[0, 5]`).
    pub fn new() -> Result<Self, InvalidParameter> {
        let model = BeamModel::new();
        let state = model.start();
        Ok(Self {
            model,
            state,
            // The options every point shares; `options_for` sets the accuracy.
            options: BeamModel::options(Method::Dopri5, 1e-6)?,
        })
    }
}

impl Subject for Beam {
    type Model = BeamModel;

    fn model(&self) -> BeamModel {
        self.model.clone()
    }

    fn state(&self) -> &State {
        &self.state
    }

    fn options(&self) -> &SolveOptions {
        &self.options
    }

    fn options_mut(&mut self) -> &mut SolveOptions {
        &mut self.options
    }

    /// The beam's length is 1 (the test set's units).
    fn length(&self) -> f64 {
        1.0
    }

    /// `dt` for RK4; `rtol = atol` for the others (the test set's way), no
    /// samples. The bounds are [`Subject::validate`]'s.
    fn options_for(&self, method: Method, param: f64) -> SolveOptions {
        let mut o = self.options.clone();
        match method.accuracy() {
            Accuracy::Step => o.dt = param,
            Accuracy::Tolerance => {
                o.rtol = param;
                o.atol = param;
            }
        }
        o.output_dt = None;
        o
    }

    /// Against the published solution (`_reference` is not read).
    fn errors(&self, _reference: &Reference, t: &Trajectory<BeamModel>) -> (f64, f64) {
        let e = |k: usize| {
            let (i, r) = REFERENCE[k];
            (BeamModel::component(&t.final_state, i) - r).abs()
        };
        (e(0).max(e(1)), e(2).max(e(3)))
    }
}

/// Runs every point of `points` as the precision study runs a point
/// ([`precision::run_point`] on [`Beam`]): one at a time when `timed`
/// (their wall times mean something then), else in parallel. A row's
/// `err_tip` and `err_vmax` are BEAM's angle and rate errors.
pub fn rows(points: &[(Method, f64)], timed: bool) -> Result<Vec<Point>, String> {
    let beam = Beam::new().map_err(|e| format!("beam: {e}"))?;
    // BEAM's errors do not read the study's reference run.
    let published = Reference {
        tip: [f64::NAN; 2],
        vmax: f64::NAN,
        length: beam.length(),
        values: fc_study::measure::Values::NONE,
    };
    let one = |&(m, x): &(Method, f64)| {
        if let Some(e) = precision::bound_of(&beam, m, x) {
            return Err(format!("beam {m} {x:e}: {e}"));
        }
        precision::run_point(&beam, m, x, &published).map_err(|e| format!("beam {m} {x:e}: {e}"))
    };
    if timed {
        points.iter().map(one).collect()
    } else {
        points.par_iter().map(one).collect()
    }
}

/// The table (no wall times: it reproduces to the byte).
pub fn csv_text(rows: &[Point]) -> String {
    let mut s = String::from(
        "method,param_name,param,status,t_reached,steps,rejected_steps,rhs_evals,\
         jacobian_evals,lu_factorizations,err_angles,err_rates\n",
    );
    for r in rows {
        let st = &r.stats;
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{}",
            r.method,
            r.param_name,
            exp(r.param),
            r.status,
            num(r.t_reached),
            st.steps,
            st.rejected_steps,
            st.rhs_evals,
            st.jacobian_evals,
            st.lu_factorizations,
            exp(r.err_tip),
            exp(r.err_vmax),
        );
    }
    s
}

/// The wall times of the same runs: `method,param,wall_seconds`.
pub fn timing_text(rows: &[Point]) -> String {
    let mut s = String::from("method,param,wall_seconds\n");
    for r in rows {
        let wall = r.walls.first().copied().unwrap_or(f64::NAN);
        let _ = writeln!(s, "{},{},{}", r.method, exp(r.param), exp_digits(wall, 3));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc_batch::shard::Provenance;
    use fc_csv::table::Table;

    /// BEAM runs through the whole precision study ([`precision::study_of`],
    /// the same as any scene's): its reference run and both checks land on
    /// the test set's published solution (an independent one: a wrong
    /// right-hand side or a wrong component read fails it), the study is
    /// confirmed, and DOP853's errors fall as its tolerance tightens.
    #[test]
    fn the_precision_study_runs_on_beam() {
        let options = precision::Options {
            methods: vec![Method::Dop853],
            checks: precision::Checks::default(),
            budget: None,
            shard: None,
            jobs: 2,
            measures: fc_study::measure::Measures::TIP,
        };
        let provenance = Provenance {
            runs: precision::ladder(&options.methods).len(),
            hash: "0".repeat(16),
        };
        let beam = Beam::new().expect("valid");
        let s =
            precision::study_of(beam, "beam", provenance, &options, None, &|| {}).expect("runs");
        assert!(s.failures.is_empty(), "{:?}", s.failures);
        assert_eq!(s.links, 40);
        for name in ["reference-dopri5", "check-rk4", "check-bdf"] {
            let r = s.rows.iter().find(|r| r.method == name).expect("row");
            assert!(r.ok() && r.err() < 1e-6, "{name}: {r:?}");
        }
        let dop853: Vec<&Point> = s.rows.iter().filter(|r| r.method == "dop853").collect();
        assert_eq!(dop853.len(), precision::RTOLS.len());
        let (loose, tight) = (dop853[0].err(), dop853[dop853.len() - 1].err());
        assert!(tight < 1e-3 * loose, "{loose:e} -> {tight:e}");
        // The table's csv and the figure's table hold the same errors.
        let fig = csv_text(&rows(&[(Method::Dop853, 1e-3)], false).expect("runs"));
        let t = Table::parse("beam", &fig).expect("parses");
        assert_eq!(t.nums("err_angles").expect("column")[0], dop853[0].err_tip);
    }

    /// The grid holds every method, and the table reads back with one row
    /// per run and NaN errors for a failed one.
    #[test]
    fn the_table_reads_back() {
        let g = grid();
        for m in crate::PAPER_METHODS {
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
