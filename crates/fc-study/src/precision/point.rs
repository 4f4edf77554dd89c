//! The study's rows: a [`Point`] (a run, or a point not run, and its
//! errors) and its [`Plan`] (whether it ran, and if not, why).

use super::*;
use chain_ode::{Method, Model, SolveOptions, Stats, Trajectory};

use crate::measure::{self, Measures, Values, COUNT};
use crate::subject::Subject;
use fc_csv::format::exp;

/// Whether a point runs, and if not, why.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plan {
    Run,
    /// Predicted too costly when timed (see [`MAX_RUN`], [`LINE_BUDGET`]).
    Cost,
    /// Thinned: the timed line's first run took more than [`THIN_ABOVE`].
    Thinned,
    /// RK4 only: a coarser step already reached [`ERR_FLOOR`].
    Floor,
    /// Not run, or stopped, within the time budget (`--budget`).
    Budget,
    /// Not run: the reference run failed, so no error could be measured.
    NoReference,
    /// Not run: the point's options break a bound of its method (RK4's
    /// steps past `run.max_steps`); the note gives it.
    Bound,
}

impl Plan {
    pub const ALL: [Plan; 7] = [
        Plan::Run,
        Plan::Cost,
        Plan::Thinned,
        Plan::Floor,
        Plan::Budget,
        Plan::NoReference,
        Plan::Bound,
    ];

    pub fn as_str(self) -> &'static str {
        match self {
            Plan::Run => "run",
            Plan::Cost => "cost",
            Plan::Thinned => "thinned",
            Plan::Floor => "floor",
            Plan::Budget => "budget",
            Plan::NoReference => "no_reference",
            Plan::Bound => "bound",
        }
    }

    pub fn parse(s: &str) -> Result<Plan, String> {
        Plan::ALL
            .into_iter()
            .find(|p| p.as_str() == s)
            .ok_or_else(|| format!("unknown plan '{s}'"))
    }

    /// Why the point was not run, without wall times.
    pub fn note(self) -> String {
        match self {
            Plan::Run => String::new(),
            Plan::Cost => format!(
                "cost: predicted above {MAX_RUN} s per run or {LINE_BUDGET} s per line when timed"
            ),
            Plan::Thinned => format!("thinned: a run took > {THIN_ABOVE} s when timed"),
            Plan::Floor => format!(
                "a coarser dt is already at the reference's level (< {})",
                exp(ERR_FLOOR)
            ),
            Plan::Budget => "budget: not run within --budget".into(),
            Plan::NoReference => {
                "not run: the reference run failed (no error can be measured)".into()
            }
            Plan::Bound => "not run: out of its method's bounds".into(),
        }
    }
}

/// One row of the table: a run (or a point not run) and its errors.
#[derive(Clone, Debug)]
pub struct Point {
    /// A method's name, or `reference-dopri5`, `check-rk4`,
    /// `check-rk4-richardson`, `check-bdf`.
    pub method: String,
    /// `dt` or `rtol`.
    pub param_name: &'static str,
    pub param: f64,
    pub plan: Plan,
    pub status: String,
    pub t_reached: f64,
    pub stats: Stats,
    /// The size of the state (`2 n + 1`).
    pub dim: usize,
    pub err_tip: f64,
    pub err_vmax: f64,
    /// What the study measures (`tip` by default: then [`Point::err`] is
    /// the larger of `err_tip` and `err_vmax`, as it always was).
    pub measures: Measures,
    /// Each measure's relative error (indexed as [`measure::Measure::ALL`],
    /// NaN where not measured or not run).
    pub err_each: [f64; COUNT],
    /// The largest of them (the point's error when it measures more than
    /// the tip).
    pub err_measured: f64,
    /// For `auto`: whether it switched to BDF.
    pub switched: bool,
    /// Why it failed or was not run (no wall times).
    pub note: String,
    /// Wall times (s) of its runs (one, or the repeats when timed).
    pub walls: Vec<f64>,
    /// A timed point's note with wall times (for the timing file).
    pub timing_note: String,
    /// How to run it again (completed, timed points only).
    pub rerun: Option<(Method, SolveOptions)>,
    /// Its number in the ladder (`None` for the reference and its checks).
    pub run: Option<usize>,
}

impl Point {
    /// RHS evaluations plus one per Jacobian-vector product.
    pub fn rhs_equiv(&self) -> u64 {
        self.stats.rhs_evals + self.stats.jacobian_evals * self.dim as u64
    }

    /// Its error (NaN if not run or failed): the larger of the tip's two
    /// for `tip` alone, else the largest over its measures.
    pub fn err(&self) -> f64 {
        if self.measures.is_tip() {
            self.err_tip.max(self.err_vmax)
        } else {
            self.err_measured
        }
    }

    /// The error of measure `m` (NaN if not measured).
    pub fn err_of(&self, m: measure::Measure) -> f64 {
        if self.measures.is_tip() && m == measure::Measure::Tip {
            return self.err();
        }
        self.err_each[m as usize]
    }

    /// Whether it completed with finite errors.
    pub fn ok(&self) -> bool {
        self.status == "ok"
            && self.err_tip.is_finite()
            && self.err_vmax.is_finite()
            && self.err().is_finite()
    }

    /// A point of `method` at accuracy `param` that was not run.
    pub fn not_run(method: Method, param: f64, plan: Plan, timing_note: String) -> Point {
        Point {
            method: method.as_str().into(),
            param_name: method.accuracy_name(),
            param,
            plan,
            status: "not_run".into(),
            t_reached: f64::NAN,
            stats: Stats::default(),
            dim: 0,
            err_tip: f64::NAN,
            err_vmax: f64::NAN,
            measures: Measures::TIP,
            err_each: [f64::NAN; COUNT],
            err_measured: f64::NAN,
            switched: false,
            note: plan.note(),
            walls: vec![],
            timing_note,
            rerun: None,
            run: None,
        }
    }

    /// The row of a finished run of `subject`, its errors measured
    /// against `reference` ([`Subject::errors`]).
    pub fn from_run<S: Subject>(
        method: String,
        param_name: &'static str,
        param: f64,
        t: &Trajectory<S::Model>,
        subject: &S,
        reference: &Reference,
    ) -> Point {
        let (err_tip, err_vmax) = if t.status.is_ok() {
            subject.errors(reference, t)
        } else {
            (f64::NAN, f64::NAN)
        };
        let measures = subject.measures();
        let (err_each, err_measured) = if t.status.is_ok() && !measures.is_tip() {
            let values = Values::of(t, measures);
            measure::errors(measures, err_tip.max(err_vmax), &reference.values, &values)
        } else {
            ([f64::NAN; COUNT], f64::NAN)
        };
        let note = match t.t_failed {
            Some(tf) => format!("failed at t = {tf:.4}"),
            None => String::new(),
        };
        Point {
            method,
            param_name,
            param,
            plan: Plan::Run,
            status: t.status.as_str().into(),
            t_reached: t.t_reached,
            stats: t.stats,
            dim: 2 * t.model.layout().links + 1,
            err_tip,
            err_vmax,
            measures,
            err_each,
            err_measured,
            switched: t.segments.len() > 1,
            note,
            walls: vec![t.summary.wall_seconds],
            timing_note: String::new(),
            rerun: None,
            run: None,
        }
    }
}
