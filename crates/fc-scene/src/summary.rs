//! The scalar results of one run, as printed by `simulate --json` and as one
//! CSV row per run (for sweeps).

use std::fmt;

use chain_ode::Trajectory;
use serde::{Deserialize, Serialize};

use fc_csv::Column;

use crate::csv::field as csv_field;

/// The time span over which one method ran.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SegmentSummary {
    pub method: String,
    pub t_start: f64,
    pub t_end: f64,
}

/// What a run did, in the units of its scene.
///
/// The JSON keys `status`, `method`, `links`, `t_reached`, `steps`,
/// `rejected_steps`, `rhs_evals`, `jacobian_evals`, `wall_seconds`,
/// `energy_start`, `energy_end`, `dissipated`, `energy_balance_error`,
/// `tip_end`, `tip_speed_max`, `t_tip_speed_max` are a contract (scripts
/// read them); the others are extras.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    /// The scene's name.
    pub name: String,
    /// `ok`, `diverged`, `step_size_too_small` or `max_steps`.
    pub status: String,
    /// The method asked for (`segments` says which ran when).
    pub method: String,
    /// The model that ran (`chain_ode::Model::name`: `rigid`, `elastic`,
    /// `report`). In `--json` only, not in the CSV row; absent in older
    /// JSON reads as empty.
    #[serde(default)]
    pub model: String,
    /// Number of rods `n`.
    pub links: usize,
    /// The end time asked for.
    pub t_end: f64,
    /// The last time with a finite state.
    pub t_reached: f64,
    /// When the run failed, if it did.
    pub t_failed: Option<f64>,
    pub steps: u64,
    pub rejected_steps: u64,
    pub rhs_evals: u64,
    pub jacobian_evals: u64,
    pub lu_factorizations: u64,
    pub stiffness_detections: u64,
    /// The implicit methods' rejections by cause and their Newton work
    /// (`chain_ode::Stats`; 0 for the explicit methods). In `--json` only,
    /// not in the CSV row; absent in older JSON reads as 0.
    #[serde(default)]
    pub error_test_failures: u64,
    #[serde(default)]
    pub newton_failures: u64,
    #[serde(default)]
    pub newton_iterations: u64,
    /// `moreau-jean`'s contact statistics (`chain_ode::Stats`), `None`
    /// for the other methods (and then absent from the JSON; not in the
    /// CSV row): the most contacts active in one step, the largest
    /// residual of a contact solve's laws (velocity units; length for the
    /// projections) and the largest joint drift one step made before its
    /// projection (length).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contacts_max: Option<u64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub complementarity_residual: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub constraint_drift: Option<f64>,
    /// Wall time of the integration (s).
    pub wall_seconds: f64,
    /// `E(0)`.
    pub energy_start: f64,
    /// `E(t_reached)`.
    pub energy_end: f64,
    /// Work dissipated by joint friction up to `t_reached`.
    pub dissipated: f64,
    /// `max |E + W - E(0)|` over the steps.
    pub energy_balance_error: f64,
    /// Largest step-to-step rise of `E`.
    pub max_energy_rise: f64,
    /// `M g L`, the scale for energy errors.
    pub energy_scale: f64,
    /// `r / min_i (m_i l_i^2)` (1/time), the stiffness parameter: the
    /// damping rate of the most damped rod (`r / (m l^2)` for equal rods;
    /// `Chain::stiffest_damping_rate`).
    pub damping_rate: f64,
    /// Tip position at `t_reached`.
    pub tip_end: [f64; 2],
    /// Tip velocity at `t_reached`.
    pub tip_velocity_end: [f64; 2],
    /// Continuous maximum of the tip speed over the run.
    pub tip_speed_max: f64,
    /// When it happened.
    pub t_tip_speed_max: f64,
    /// Which method ran over which span.
    pub segments: Vec<SegmentSummary>,
    /// The floor's largest total normal force over the run (force; what a
    /// scale under the chain reads): at the start, every accepted step's
    /// end and inside a step where it turns (the method's continuous
    /// extension), never read off the output samples. `None` without a
    /// floor (and then absent from the JSON). Not in the CSV row.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub floor_force_max: Option<f64>,
    /// When it happened.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_floor_force_max: Option<f64>,
    /// At the instant of `floor_force_max`, that force over the weight of
    /// the contact points the floor pushes then, `g sum m_i / 2` (each end
    /// of rod `i` stands for half of it; the tip's point also carries the
    /// tip mass): 1 for a chain resting on the floor. It counts contact
    /// points, not landed length: at an impact's peak only the few points
    /// in contact count, so it measures the impact (it can be 1e3 or
    /// more), not Cayley's scale reading `3 mu g x` (which needs the
    /// landed length and an average over time). 0 when nothing touches.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub floor_force_over_landed_weight: Option<f64>,
    /// The support's largest force `|F_1|` over the run (force units; the
    /// pivot's pull on the first rod, zero once let go), tracked like
    /// `floor_force_max` (every accepted step, refined inside a step where
    /// it turns), never read off the output samples: the elastic links'
    /// pivot spring, the rigid chain's multiplier (the report's model: the
    /// rigid chain's at its state). `None` (absent) for the contact model
    /// (`moreau-jean`), whose forces are a step's impulses over its length:
    /// their peak at an impact grows as `1 / h` and is no property of the
    /// run. Not in the CSV row.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pivot_force_max: Option<f64>,
    /// When it happened.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_pivot_force_max: Option<f64>,
    /// The largest tension over every joint and the whole run (force
    /// units; `T_k = -F_k . u_k`, the joint's force on the rod after it
    /// along that rod, positive when pulling it toward the support; joint
    /// 0 is the pivot), tracked like `pivot_force_max`, with its time and
    /// the joint `k` (0..n-1). Same models. Not in the CSV row.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_max: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t_tension_max: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tension_max_joint: Option<usize>,
    /// False when the run's forces (`pivot_force_max`, `tension_max`,
    /// `floor_force_max`, its `--forces` samples) are not right to its
    /// tolerance although its motion is (docs/cli.md; docs/model.md,
    /// "Forces as results"): on elastic links gen-alpha at `rho_inf > 0`
    /// or bdf stepped over the axial modes that carry them, or dopri5 or
    /// dop853 ran at rtol 1e-4 or looser; or the chain landed on the penalty
    /// floor. Not in the CSV row; absent in older JSON reads as true.
    #[serde(default = "resolved_default")]
    pub forces_resolved: bool,
}

/// [`RunSummary::forces_resolved`] in JSON written before it.
fn resolved_default() -> bool {
    true
}

/// The floor's peak of the run `traj` (tracked at every step, never read
/// off its samples): `(F_max, t, F_max / landed weight)` along the
/// floor's normal, `None` without a floor. The ratio is 0 where nothing
/// touches the floor at the peak (then `F_max` is 0 too).
fn floor_peak(traj: &Trajectory) -> Option<(f64, f64, f64)> {
    let p = traj
        .summary
        .peaks
        .iter()
        .find(|p| p.force == chain_ode::PeakForce::Floor)?;
    let ratio = if p.reference > 0.0 {
        p.value / p.reference
    } else {
        0.0
    };
    Some((p.value, p.t, ratio))
}

/// Columns of [`RunSummary::csv_row`], in order.
pub const SUMMARY_CSV_COLUMNS: [(&str, Column); 28] = [
    ("name", Column::Text),
    ("status", Column::Text),
    ("method", Column::Text),
    ("links", Column::Int),
    ("t_end", Column::Float),
    ("t_reached", Column::Float),
    ("t_failed", Column::Float),
    ("steps", Column::Int),
    ("rejected_steps", Column::Int),
    ("rhs_evals", Column::Int),
    ("jacobian_evals", Column::Int),
    ("lu_factorizations", Column::Int),
    ("stiffness_detections", Column::Int),
    ("wall_seconds", Column::Float),
    ("energy_start", Column::Float),
    ("energy_end", Column::Float),
    ("dissipated", Column::Float),
    ("energy_balance_error", Column::Float),
    ("max_energy_rise", Column::Float),
    ("energy_scale", Column::Float),
    ("damping_rate", Column::Float),
    ("tip_end_x", Column::Float),
    ("tip_end_y", Column::Float),
    ("tip_velocity_end_x", Column::Float),
    ("tip_velocity_end_y", Column::Float),
    ("tip_speed_max", Column::Float),
    ("t_tip_speed_max", Column::Float),
    ("segments", Column::Text),
];

/// How many stiffness detections of an explicit method (DOPRI5, DOP853)
/// make a run worth a hint. One detection is 15 accepted steps in a row at
/// the method's stability limit (`h |lambda| > 3.25`), which a transient
/// (the whip) can give a few times; 10 of them, 150 steps held at the
/// limit, mean that the step size is set by stability for a good part of
/// the run, where an implicit method takes far fewer steps.
pub const STIFFNESS_HINT_DETECTIONS: u64 = 10;

/// The explicit methods whose stiffness detector [`stiffness_hint`] reads.
const EXPLICIT_WITH_DETECTOR: [&str; 2] = ["dopri5", "dop853"];

/// Whether `summary` is an explicit method's run that detected stiffness at
/// least [`STIFFNESS_HINT_DETECTIONS`] times: one named dopri5 or dop853,
/// or an `auto` run that stayed explicit throughout (its plan did not hand
/// over, every segment dopri5 or dop853).
pub fn looks_stiff(summary: &RunSummary) -> bool {
    let explicit = EXPLICIT_WITH_DETECTOR.contains(&summary.method.as_str())
        || (summary.method == "auto"
            && !summary.segments.is_empty()
            && summary
                .segments
                .iter()
                .all(|g| EXPLICIT_WITH_DETECTOR.contains(&g.method.as_str())));
    explicit && summary.stiffness_detections >= STIFFNESS_HINT_DETECTIONS
}

/// The one-line hint for runs that [`looks_stiff`]: `stiff` of `total` runs
/// (one run: `total == 1`), by `method` with at most `detections`. Under
/// the report's model (`report`), which runs only rk4, dopri5 and dop853,
/// it names those and the way to the implicit methods.
pub fn stiffness_hint(
    method: &str,
    detections: u64,
    stiff: usize,
    total: usize,
    report: bool,
) -> String {
    let which = if total == 1 {
        format!("{method} detected stiffness {detections} times")
    } else {
        format!("{stiff} of {total} runs detected stiffness (up to {detections} times, {method})")
    };
    let advice = if method == "auto" {
        "auto stayed explicit (its plan hands over only where the damping says an implicit \
         method wins); --method bdf may need far fewer steps (the run goes on as asked)"
    } else if report {
        "the report's model runs only rk4, dopri5 and dop853; with model.report = false, \
         --method bdf or auto may need far fewer steps (the run goes on as asked)"
    } else {
        "--method bdf or auto may need far fewer steps (the run goes on as asked)"
    };
    format!("hint: {which} (each: 15 steps in a row at its stability limit); {advice}")
}

/// The hint for a set of summaries of the corrected model, if any of them
/// [`looks_stiff`]: one line for the whole command.
pub fn stiffness_hint_for<'a>(
    summaries: impl IntoIterator<Item = &'a RunSummary>,
) -> Option<String> {
    stiffness_hint_for_model(summaries, false)
}

/// [`stiffness_hint_for`], for runs of the report's model when `report`.
pub fn stiffness_hint_for_model<'a>(
    summaries: impl IntoIterator<Item = &'a RunSummary>,
    report: bool,
) -> Option<String> {
    let (mut total, mut stiff, mut most, mut method) = (0, 0, 0, "");
    for s in summaries {
        total += 1;
        if looks_stiff(s) {
            stiff += 1;
            if s.stiffness_detections >= most {
                most = s.stiffness_detections;
                method = s.method.as_str();
            }
        }
    }
    (stiff > 0).then(|| stiffness_hint(method, most, stiff, total, report))
}

impl RunSummary {
    /// The summary of `traj`, under the scene name `name`.
    pub fn from_trajectory(name: &str, traj: &Trajectory) -> Self {
        let s = &traj.summary;
        let st = &traj.stats;
        let floor = floor_peak(traj);
        let pivot = s.peak(chain_ode::PeakForce::Pivot);
        let tension = s.peak(chain_ode::PeakForce::Tension);
        let nonsmooth = traj.segments.iter().any(|g| g.method.is_nonsmooth());
        Self {
            name: name.to_string(),
            status: traj.status.as_str().to_string(),
            method: traj.method.as_str().to_string(),
            model: chain_ode::Model::name(&traj.model).to_string(),
            links: traj.chain().links(),
            t_end: traj.t_end,
            t_reached: traj.t_reached,
            t_failed: traj.t_failed,
            steps: st.steps,
            rejected_steps: st.rejected_steps,
            rhs_evals: st.rhs_evals,
            jacobian_evals: st.jacobian_evals,
            lu_factorizations: st.lu_factorizations,
            stiffness_detections: st.stiffness_detections,
            error_test_failures: st.error_test_failures,
            newton_failures: st.newton_failures,
            newton_iterations: st.newton_iterations,
            contacts_max: nonsmooth.then_some(st.contacts_max),
            complementarity_residual: nonsmooth.then_some(st.complementarity_residual),
            constraint_drift: nonsmooth.then_some(st.constraint_drift),
            wall_seconds: s.wall_seconds,
            energy_start: s.energy_start,
            energy_end: s.energy_end,
            dissipated: s.dissipated,
            energy_balance_error: s.energy_balance_error,
            max_energy_rise: s.max_energy_rise,
            energy_scale: traj.chain().energy_scale(),
            damping_rate: traj.chain().stiffest_damping_rate(),
            tip_end: s.tip_end,
            tip_velocity_end: s.tip_velocity_end,
            tip_speed_max: s.tip_speed_max,
            t_tip_speed_max: s.t_tip_speed_max,
            segments: traj
                .segments
                .iter()
                .map(|g| SegmentSummary {
                    method: g.method.as_str().to_string(),
                    t_start: g.t_start,
                    t_end: g.t_end,
                })
                .collect(),
            pivot_force_max: pivot.map(|p| p.value),
            t_pivot_force_max: pivot.map(|p| p.t),
            tension_max: tension.map(|p| p.value),
            t_tension_max: tension.map(|p| p.t),
            tension_max_joint: tension.map(|p| p.reference as usize),
            floor_force_max: floor.map(|f| f.0),
            t_floor_force_max: floor.map(|f| f.1),
            floor_force_over_landed_weight: floor.map(|f| f.2),
            forces_resolved: s.forces_resolved,
        }
    }

    /// True if the run reached its end time.
    pub fn is_ok(&self) -> bool {
        self.status == "ok"
    }

    /// One line of JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|e| {
            serde_json::json!({ "error": format!("the summary did not serialise: {e}") })
                .to_string()
        })
    }

    /// The header line of [`RunSummary::csv_row`] (no newline).
    pub fn csv_header() -> String {
        fc_csv::header(&SUMMARY_CSV_COLUMNS)
    }

    /// One CSV row (no newline) with the columns of [`SUMMARY_CSV_COLUMNS`]:
    /// full-precision numbers, empty cells for unknown values, segments as
    /// `method@t_start..t_end` joined by `;`.
    pub fn csv_row(&self) -> String {
        let opt = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
        let segments = self
            .segments
            .iter()
            .map(|g| format!("{}@{}..{}", g.method, g.t_start, g.t_end))
            .collect::<Vec<_>>()
            .join(";");
        let cells = [
            csv_field(&self.name).into_owned(),
            csv_field(&self.status).into_owned(),
            csv_field(&self.method).into_owned(),
            self.links.to_string(),
            self.t_end.to_string(),
            self.t_reached.to_string(),
            opt(self.t_failed),
            self.steps.to_string(),
            self.rejected_steps.to_string(),
            self.rhs_evals.to_string(),
            self.jacobian_evals.to_string(),
            self.lu_factorizations.to_string(),
            self.stiffness_detections.to_string(),
            self.wall_seconds.to_string(),
            self.energy_start.to_string(),
            self.energy_end.to_string(),
            self.dissipated.to_string(),
            self.energy_balance_error.to_string(),
            self.max_energy_rise.to_string(),
            self.energy_scale.to_string(),
            self.damping_rate.to_string(),
            self.tip_end[0].to_string(),
            self.tip_end[1].to_string(),
            self.tip_velocity_end[0].to_string(),
            self.tip_velocity_end[1].to_string(),
            self.tip_speed_max.to_string(),
            self.t_tip_speed_max.to_string(),
            csv_field(&segments).into_owned(),
        ];
        cells.join(",")
    }
}

impl fmt::Display for RunSummary {
    /// A readable multi-line summary.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let model = if self.model.is_empty() {
            String::new()
        } else {
            format!(", the {} model", self.model)
        };
        writeln!(
            f,
            "{}: {} ({}{model}, {} rods)",
            self.name, self.status, self.method, self.links
        )?;
        writeln!(
            f,
            "  t reached         {} of {}",
            self.t_reached, self.t_end
        )?;
        if let Some(t) = self.t_failed {
            writeln!(f, "  failed at         t = {t}")?;
        }
        if self.segments.len() > 1 {
            let spans: Vec<String> = self
                .segments
                .iter()
                .map(|g| format!("{} [{:.4}, {:.4}]", g.method, g.t_start, g.t_end))
                .collect();
            writeln!(f, "  segments          {}", spans.join(", "))?;
        }
        writeln!(
            f,
            "  work              {} steps ({} rejected), {} RHS, {} Jacobians, {} LU",
            self.steps,
            self.rejected_steps,
            self.rhs_evals,
            self.jacobian_evals,
            self.lu_factorizations
        )?;
        if let (Some(c), Some(r), Some(d)) = (
            self.contacts_max,
            self.complementarity_residual,
            self.constraint_drift,
        ) {
            writeln!(
                f,
                "  contacts          at most {c} at once, {} Newton iterations, residual \
                 {r:.3e}, joint drift per step {d:.3e}",
                self.newton_iterations
            )?;
        }
        writeln!(f, "  wall time         {:.3e} s", self.wall_seconds)?;
        writeln!(
            f,
            "  energy            {:.9} -> {:.9}, dissipated {:.3e}",
            self.energy_start, self.energy_end, self.dissipated
        )?;
        writeln!(
            f,
            "  energy balance    {:.3e} ({:.3e} of M g L = {})",
            self.energy_balance_error,
            self.energy_balance_error / self.energy_scale,
            self.energy_scale
        )?;
        writeln!(
            f,
            "  tip at end        ({:.6}, {:.6}), velocity ({:.6}, {:.6})",
            self.tip_end[0], self.tip_end[1], self.tip_velocity_end[0], self.tip_velocity_end[1]
        )?;
        write!(
            f,
            "  max tip speed     {:.6} at t = {:.6}",
            self.tip_speed_max, self.t_tip_speed_max
        )?;
        if let (Some(fm), Some(t)) = (self.pivot_force_max, self.t_pivot_force_max) {
            write!(f, "\n  max pivot force   {fm:.6} at t = {t:.6}")?;
        }
        if let (Some(tm), Some(t), Some(k)) =
            (self.tension_max, self.t_tension_max, self.tension_max_joint)
        {
            write!(f, "\n  max tension       {tm:.6} at t = {t:.6}, joint {k}")?;
        }
        if let (Some(fm), Some(t), Some(r)) = (
            self.floor_force_max,
            self.t_floor_force_max,
            self.floor_force_over_landed_weight,
        ) {
            write!(
                f,
                "\n  max floor force   {fm:.6} at t = {t:.6} ({r:.4} x the weight landed)"
            )?;
        }
        if !self.forces_resolved {
            write!(
                f,
                "\n  forces            NOT resolved to the tolerance (the motion is): the method stepped over the elastic links' axial modes, or ran explicit at rtol 1e-4 or looser, or the chain landed on the penalty floor (docs/model.md, \"Forces as results\"); dopri5 or dop853 at rtol 1e-5 or tighter resolve a rope's"
            )?;
        }
        Ok(())
    }
}
