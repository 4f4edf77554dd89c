//! The run layer: one way to run any method on any model, [`solve`].
//!
//! The methods are fc-methods' (one [`Integrator`] per [`Method`], in its
//! registry); they see only the [`Problem`] a model gives. This layer
//! checks a run's options against its model ([`Model::validate`], on
//! [`SolveOptions::validate_common`]), hands the model's problem to the
//! method with the run's settings, cuts the run at the model's event, and
//! watches it: the recorder (samples, the first non-finite time, cancel
//! and progress), the summary's tally (which asks the model) and the
//! caller's [`Watch`]es. Work counters come from what the methods called
//! (a [`Counted`](fc_methods::Counted) system), never from counting by
//! hand.
//!
//! Its files: `options.rs` (a run's options and their bounds),
//! `trajectory.rs` (what a run returns: its summary and trajectory),
//! `run.rs` (the pieces of one run: observers, segments, the cut at an
//! event, the finished trajectory), `recorder.rs` (the samples),
//! `tally.rs` (the summary's running quantities), `forces.rs` (whether
//! a run's forces are resolved), `peaks.rs` (the forces'
//! peaks inside steps), `auto_elastic.rs` (`auto`'s plan on elastic
//! chains), `report_stepper.rs` (the report's own fixed-step stepping),
//! `unit_costs.rs` (the measured cost of one evaluation of each kind) and
//! `memory.rs` (a run's memory, estimated and checked before it allocates).

pub mod auto_elastic;
mod forces;
pub mod memory;
mod options;
pub(crate) mod peaks;
mod recorder;
mod report_stepper;
mod run;
mod tally;
mod trajectory;
mod unit_costs;

use std::time::Instant;

use fc_methods::{InvalidParameter, Method, Settings, Span, StepView};

use crate::model::{IntoModel, Model};
use crate::state::State;
pub use options::{
    SolveOptions, ATOL_RANGE, BDF_DENSE_MAX_ELASTIC_LINKS, BDF_DENSE_MAX_LINKS, GEN_ALPHA_MIN_RTOL,
    MAX_OUTPUT_BYTES, RTOL_RANGE,
};
use recorder::Recorder;
pub use report_stepper::{REPORT_METHODS, REPORT_RK4};
use run::{run_cut, segment, trajectory, Parts};
use tally::Tally;
pub use tally::{BALANCE_PER_TOLERANCE, DRIVE_BALANCE_FRACTION};
pub use trajectory::{Sample, Summary, Trajectory};
#[doc(hidden)]
pub use unit_costs::{unit_costs, UnitCosts};

/// An observer a caller attaches to a run ([`Solve::watch`]), beside the
/// run's own recorder and summary: it sees the model and every accepted
/// step (its end state, its derivative and its continuous extension), so a
/// study can track a quantity at every step instead of reading it off the
/// samples.
pub trait Watch<M> {
    /// The run's start at `t0` in `y0`.
    fn start(&mut self, _model: &M, _t0: f64, _y0: &[f64]) {}
    /// An accepted step.
    fn step(&mut self, model: &M, step: &StepView<'_>);
    /// True to stop the run (it ends `interrupted`).
    fn stop(&self) -> bool {
        false
    }
}

/// The method whose accuracy a run of `method` has: `auto` on a model
/// whose plan is a method of nonsmooth problems from the start (the
/// constraint floor's `moreau-jean`) runs that method at its fixed step,
/// and its energy balance is judged as that method's; any other method is
/// itself.
fn method_run<M: Model>(model: &M, method: Method, options: &SolveOptions) -> Method {
    if method == Method::Auto {
        let plan =
            auto_elastic::within_reach(model.auto_plan(options.rtol), options.rtol, options.atol);
        if plan.explicit.is_none() && plan.implicit.is_nonsmooth() {
            return plan.implicit;
        }
    }
    method
}

/// Runs `method` on `model` (a [`Model`], or a [`Chain`] whose model
/// [`ModelKind::of`] chooses) from `start` over `[0, options.t_end]`.
///
/// Never panics on a failing run and never returns a NaN in its state: a run
/// that hits a non-finite value stops with `Status::Diverged` at the last
/// finite state. A run whose every state is finite but whose summary is not
/// (an energy that overflows, say) also ends `Status::Diverged`, with
/// `t_failed` the first time a non-finite value was recorded: a NaN or an
/// infinity in the summary never comes with `Status::Ok`. A finite run whose
/// energy balance error `max |E + W - E(0)|` exceeds the model's energy
/// scale ([`Model::energy_scale`]), or with a prescribed pivot motion
/// [`DRIVE_BALANCE_FRACTION`] of that scale plus the work done, ends
/// `Status::Inaccurate`, with `t_failed` the first step end where it did. A
/// run whose `options.cancel` is set ends `Status::Interrupted` at its last
/// accepted step (`t_failed = t_reached`).
///
/// Every option is checked first ([`Model::validate`]): nothing is
/// allocated for a run out of bounds, and a method the model cannot run is
/// an error, not a failed run.
pub fn solve<I: IntoModel>(
    model: I,
    start: &State,
    method: Method,
    options: &SolveOptions,
) -> Result<Trajectory<I::Model>, InvalidParameter> {
    Solve::new(model, start, method, options).run()
}

/// A run being set up: [`solve`] with observers attached ([`Solve::watch`]).
pub struct Solve<'a, M: Model> {
    model: M,
    start: &'a State,
    method: Method,
    options: &'a SolveOptions,
    watches: Vec<&'a mut dyn Watch<M>>,
    /// Track the pivot's force and the tensions ([`Solve::without_force_peaks`]).
    force_peaks: bool,
}

impl<'a, M: Model> Solve<'a, M> {
    /// The run of `method` on `model` from `start` with `options`.
    pub fn new<I: IntoModel<Model = M>>(
        model: I,
        start: &'a State,
        method: Method,
        options: &'a SolveOptions,
    ) -> Self {
        Self {
            model: model.into_model(),
            start,
            method,
            options,
            watches: Vec::new(),
            force_peaks: true,
        }
    }

    /// A run that does not track the peaks of the pivot's force and the
    /// tensions (`Summary::pivot_force_max` and the
    /// [`PeakForce::Pivot`](crate::PeakForce::Pivot) and
    /// [`PeakForce::Tension`](crate::PeakForce::Tension) peaks are then
    /// absent; the floor's stays): for a caller that reads neither and
    /// times the integrator (a benchmark). Their tracking costs the rigid
    /// chain two recursions per step where they are near their peak, one
    /// elsewhere: on `scenes/span-d3.toml` (DOPRI5 at rtol 1e-10, 1,352
    /// steps, 8,114 right-hand sides either way) the median wall time
    /// went from 0.033 s to 0.055 s (1.67x, 9 runs each at load 10-12;
    /// docs/model.md, "Forces as results"); the elastic chain's are one
    /// pass over its links, no recursion.
    pub fn without_force_peaks(mut self) -> Self {
        self.force_peaks = false;
        self
    }

    /// Attaches `watch`: it sees the start and every accepted step.
    pub fn watch(mut self, watch: &'a mut dyn Watch<M>) -> Self {
        self.watches.push(watch);
        self
    }

    /// Runs it.
    pub fn run(self) -> Result<Trajectory<M>, InvalidParameter> {
        let Solve {
            mut model,
            start,
            method,
            options,
            mut watches,
            force_peaks,
        } = self;
        model.validate(method, options)?;
        let y0 = model.initial_state(start)?;
        let layout = model.layout();
        let settings = Settings {
            scales: model.time_scales(),
            ..options.settings()
        };
        let span = Span {
            t0: 0.0,
            y0: &y0,
            t_end: options.t_end,
            settings: &settings,
        };
        let mut parts = Parts {
            rec: Recorder::new(
                layout.dim,
                options.t_end,
                options.output_dt,
                options.cancel.clone(),
            ),
            tally: Tally::new(
                &model,
                tally::run_tolerance(method_run(&model, method, options), options),
            )
            .with_force_peaks(force_peaks),
            watches: &mut watches,
        };
        let clock = Instant::now();
        let run = match model.event_time() {
            Some(te) if te > span.t0 && te < span.t_end => {
                run_cut(&mut model, method, &span, te, &mut parts)
            }
            _ => segment(&model, method, &span, &mut parts),
        };
        let Parts { rec, tally, .. } = parts;
        Ok(trajectory(
            model,
            start.anchor,
            method,
            options,
            run,
            (rec, tally),
            clock,
        ))
    }
}
