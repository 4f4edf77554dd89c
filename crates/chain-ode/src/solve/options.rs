//! A run's options ([`SolveOptions`]) and their checks, and the bounds on
//! them: the tolerances' ranges, the samples' memory, the dense BDF's sizes.

use fc_methods::{Accuracy, Cancel, InvalidParameter, Method, Settings, TimeScales};

use crate::chain::{check, number_text, Chain};
use crate::model::{Layout, Model, ModelKind};
use crate::pivot::Pivot;

/// Options of a run. Defaults: `t_end = 1`, `dt = 0.01`, `rtol = 1e-8`, `rho_inf = 0.9`,
/// `atol = 1e-10`, no output samples, at most 10^8 steps.
#[derive(Clone, Debug, PartialEq)]
pub struct SolveOptions {
    /// End time (time units of the chain's `g`).
    pub t_end: f64,
    /// Fixed step of RK4.
    pub dt: f64,
    /// Relative tolerance of adaptive methods.
    pub rtol: f64,
    /// Absolute tolerance of adaptive methods.
    pub atol: f64,
    /// Spacing of recorded samples; `None` keeps only the summary.
    pub output_dt: Option<f64>,
    /// Step budget; a run that needs more ends with `max_steps`.
    pub max_steps: u64,
    /// Smallest adaptive step before `step_size_too_small` (0: the rounding limit).
    pub h_min: f64,
    /// A flag that stops the run from outside (`Status::Interrupted`);
    /// `None` runs to the end.
    pub cancel: Option<Cancel>,
    /// `gen-alpha`'s spectral radius at infinity (`run.rho_inf`, in
    /// [0, 1]): how much of a mode its step does not resolve survives a
    /// step (1: all of it, the trapezoidal rule; 0: none). The other
    /// methods ignore it.
    pub rho_inf: f64,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            t_end: 1.0,
            dt: 0.01,
            rtol: 1e-8,
            atol: 1e-10,
            output_dt: None,
            max_steps: 100_000_000,
            h_min: 0.0,
            cancel: None,
            rho_inf: fc_methods::DEFAULT_RHO_INF,
        }
    }
}

impl SolveOptions {
    /// These options with `method`'s accuracy parameter set to `x`: `dt = x`
    /// for a fixed-step method, `rtol = x` and `atol = x / 100` for an
    /// adaptive one.
    pub fn at_accuracy(mut self, method: Method, x: f64) -> Self {
        match method.accuracy() {
            Accuracy::Step => self.dt = x,
            Accuracy::Tolerance => {
                self.rtol = x;
                self.atol = x * 1e-2;
            }
        }
        self
    }

    /// These options as the integrators read them: no starting step, no
    /// step caps (the run adds its model's, [`Model::time_scales`]).
    pub(crate) fn settings(&self) -> Settings {
        Settings {
            dt: self.dt,
            rtol: self.rtol,
            atol: self.atol,
            h_min: self.h_min,
            max_steps: self.max_steps,
            h0: None,
            scales: TimeScales::NONE,
            rho_inf: self.rho_inf,
        }
    }

    /// Checks every field on its own; the error names the first one out of
    /// range. [`SolveOptions::validate_for`] adds the bounds that depend on
    /// the method and the chain; [`solve`] checks both before it allocates.
    pub fn validate(&self) -> Result<(), InvalidParameter> {
        let pos = |x: f64| x.is_finite() && x > 0.0;
        check(
            pos(self.t_end),
            "run.t_end",
            "a finite number > 0",
            self.t_end,
        )?;
        check(pos(self.dt), "run.dt", "a finite number > 0", self.dt)?;
        let (lo, hi) = RTOL_RANGE;
        check(
            (lo..=hi).contains(&self.rtol),
            "run.rtol",
            "a number in [1e-14, 0.1]",
            self.rtol,
        )?;
        let (lo, hi) = ATOL_RANGE;
        check(
            (lo..=hi).contains(&self.atol),
            "run.atol",
            "a number in [1e-20, 1]",
            self.atol,
        )?;
        if let Some(o) = self.output_dt {
            check(pos(o), "run.output_dt", "a finite number > 0", o)?;
        }
        let (lo, hi) = fc_methods::RHO_INF_RANGE;
        check(
            (lo..=hi).contains(&self.rho_inf),
            "run.rho_inf",
            "a number in [0, 1]",
            self.rho_inf,
        )?;
        check(
            self.h_min.is_finite() && self.h_min >= 0.0,
            "run.h_min",
            "a finite number >= 0",
            self.h_min,
        )?;
        check(
            self.max_steps > 0,
            "run.max_steps",
            "an integer > 0",
            self.max_steps,
        )
    }

    /// [`SolveOptions::validate`], then the bounds that depend on `method`
    /// and `chain`, each stated with the numbers of this run:
    /// * RK4: `run.dt <= run.t_end`, and `ceil(t_end / dt) <= run.max_steps`
    ///   (the smallest step accepted is `t_end / max_steps`);
    /// * the recorded samples, `t_end / output_dt` of
    ///   [`SolveOptions::sample_numbers`] numbers
    ///   each, within [`MAX_OUTPUT_BYTES`] (the smallest `run.output_dt`
    ///   accepted is [`SolveOptions::min_output_dt`]);
    /// * `bdf-dense`: at most [`BDF_DENSE_MAX_LINKS`] rods (`bdf` runs any).
    /// * RK4 with a prescribed pivot motion: `run.dt` at most the motion's
    ///   time scale over [`crate::STEPS_PER_TIME_SCALE`]
    ///   ([`crate::Pivot::time_scales`]).
    ///
    /// `chain` itself is checked by [`Chain::validate`].
    ///
    /// Then the run's memory ([`SolveOptions::check_memory`], one run).
    pub fn validate_for(&self, chain: &Chain, method: Method) -> Result<(), InvalidParameter> {
        ModelKind::of(chain).validate(method, self)?;
        self.check_memory(chain, method, 1)
    }

    /// Refuses `concurrent` runs of `chain` with `method` at once whose
    /// estimated memory (its working memory a rod, measured, and its
    /// recorded samples) exceeds what the machine can give, naming
    /// `chain.links` ([`crate::memory`]; issue 47 A2). A study that runs
    /// `--jobs` runs at once checks them together.
    pub fn check_memory(
        &self,
        chain: &Chain,
        method: Method,
        concurrent: usize,
    ) -> Result<(), InvalidParameter> {
        let model = ModelKind::of(chain);
        let layout = model.layout();
        let samples = self.output_dt.map_or(0, |o| {
            let count = (self.t_end / o).floor().min(u64::MAX as f64) as u64;
            count
                .saturating_add(2)
                .saturating_mul(8)
                .saturating_mul(layout.sample_numbers)
        });
        super::memory::check(model.name(), method, layout.links, samples, concurrent)
    }

    /// The bounds every model shares, for a model laid out as `layout`
    /// whose support moves as `pivot` (if it has one): [`SolveOptions::validate`];
    /// RK4's step within the span, the budget and the pivot's time scales;
    /// the samples' memory. A model's [`Model::validate`] adds its own.
    pub fn validate_common(
        &self,
        pivot: Option<&Pivot>,
        method: Method,
        layout: &Layout,
    ) -> Result<(), InvalidParameter> {
        self.validate()?;
        check(
            !method.is_nonsmooth(),
            "run.method",
            format!(
                "a method of smooth problems here ({} runs a chain on a floor with floor.law = \
                 \"constraint\")",
                method
            ),
            method,
        )?;
        if method == Method::GenAlpha {
            check(
                self.rtol >= GEN_ALPHA_MIN_RTOL,
                "run.rtol",
                "a number in [1e-10, 0.1] for gen-alpha (below 1e-10 its error \
                 stops following the tolerance: docs/model.md)",
                self.rtol,
            )?;
        }
        if method == Method::Rk4 {
            self.validate_fixed_step(method)?;
            // A fixed step must resolve the pivot's prescribed motion, as
            // the adaptive methods' caps do (`Pivot::time_scales`).
            if let Some(pivot) = pivot {
                let cap = pivot.time_scales().smallest();
                if cap.is_finite() {
                    let (key, scale) = if pivot.jerk != [0.0, 0.0]
                        && cap == pivot.jerk_time / crate::pivot::STEPS_PER_TIME_SCALE
                    {
                        ("pivot.jerk_time", "the smooth jerk's duration")
                    } else {
                        (
                            "pivot.frequency",
                            "the harmonic motion's period 2 pi / frequency",
                        )
                    };
                    check(
                        self.dt <= cap,
                        "run.dt",
                        format!(
                            "at most {cap:e} for rk4 with this pivot: {} of {scale} ({key})",
                            format_args!("1/{}", crate::pivot::STEPS_PER_TIME_SCALE)
                        ),
                        self.dt,
                    )?;
                }
            }
        }
        self.validate_samples(layout)
    }

    /// A fixed step `run.dt` of `method` within the span and the budget:
    /// `dt <= t_end` and `dt >= t_end / max_steps`.
    pub(crate) fn validate_fixed_step(&self, method: Method) -> Result<(), InvalidParameter> {
        check(
            self.dt <= self.t_end,
            "run.dt",
            format!(
                "at most run.t_end = {} for {method}",
                number_text(self.t_end)
            ),
            self.dt,
        )?;
        let dt_min = self.t_end / self.max_steps as f64;
        check(
            self.dt >= dt_min,
            "run.dt",
            format!(
                "at least run.t_end / run.max_steps = {dt_min:e} for {method} (t_end = {}, \
                 max_steps = {})",
                number_text(self.t_end),
                self.max_steps
            ),
            self.dt,
        )
    }

    /// The recorded samples of a model laid out as `layout` within
    /// [`MAX_OUTPUT_BYTES`].
    pub(crate) fn validate_samples(&self, layout: &Layout) -> Result<(), InvalidParameter> {
        if let Some(o) = self.output_dt {
            let o_min = Self::min_output_dt_of(self.t_end, layout.sample_numbers);
            check(
                o >= o_min,
                "run.output_dt",
                format!(
                    "at least {o_min:e} for t_end = {} and chain.links = {}: the samples \
                     ({} numbers each) must fit in {} MiB",
                    number_text(self.t_end),
                    layout.links,
                    layout.sample_numbers,
                    MAX_OUTPUT_BYTES >> 20
                ),
                o,
            )?;
        }
        Ok(())
    }

    /// The smallest `output_dt` (time units) whose samples over `t_end` fit
    /// in [`MAX_OUTPUT_BYTES`] for a chain of `links` rigid rods: each
    /// sample holds its time and the `2 n + 1` state values (`f64`), and
    /// the `2 (n + 1)` joint forces an output may derive from it
    /// ([`SolveOptions::sample_numbers`]); a run records
    /// `t_end / output_dt + 2` samples at most (the start, and the end when
    /// it is not on the grid).
    pub fn min_output_dt(t_end: f64, links: usize) -> f64 {
        Self::min_output_dt_of(t_end, 4 * links as u64 + 4)
    }

    /// Numbers a recorded sample of `chain` may take in memory: its time,
    /// its state (`2 n + 1` rigid, `6 n + 1` elastic), the joint forces an
    /// output may derive from it (`2 (n + 1)`) and, for an elastic chain,
    /// its joints (`2 (n + 1)`, which Python keeps).
    pub fn sample_numbers(chain: &Chain) -> u64 {
        ModelKind::of(chain).layout().sample_numbers
    }

    /// [`SolveOptions::min_output_dt`] for `chain`'s model
    /// ([`SolveOptions::sample_numbers`] each).
    pub fn min_output_dt_for(t_end: f64, chain: &Chain) -> f64 {
        Self::min_output_dt_of(t_end, Self::sample_numbers(chain))
    }

    fn min_output_dt_of(t_end: f64, numbers: u64) -> f64 {
        let per_sample = 8 * numbers;
        let samples = MAX_OUTPUT_BYTES / per_sample;
        t_end / samples.saturating_sub(2).max(1) as f64
    }
}

/// The accepted range of `run.rtol`, `[min, max]`: below `1e-14` a relative
/// error test asks for less than the rounding of `f64` states (the BDFs then
/// crawl at steps of `1e-13` for hours), above `0.1` it allows errors as
/// large as the state.
pub const RTOL_RANGE: (f64, f64) = (1e-14, 0.1);

/// The tightest `rtol` gen-alpha accepts (issue 47 W2): on
/// `scenes/span-d3.toml` its tip error over `L` is 4.1e-8, 2.4e-8, 7.7e-9
/// at rtol 1e-8, 1e-9, 1e-10, and then 6.3e-9, 5.5e-9, 1.4e-9 at 1e-11,
/// 1e-12, 1e-14 (against DOP853 at 1e-13): below 1e-10 a decade of
/// tolerance buys a fraction of a decade, with ever more steps, so the
/// tolerance would be a number the run does not meet (docs/model.md, "The
/// generalized-alpha method").
pub const GEN_ALPHA_MIN_RTOL: f64 = 1e-10;

/// The accepted range of `run.atol` (units of the state: rad, rad per time
/// unit, energy), `[min, max]`.
pub const ATOL_RANGE: (f64, f64) = (1e-20, 1.0);

/// The most memory a run's recorded samples may take (bytes): 1 GiB.
pub const MAX_OUTPUT_BYTES: u64 = 1 << 30;

/// The largest chain `bdf-dense` runs: its Jacobian and LU are dense
/// `(2n + 1)^2` matrices, factorised in O(n^3).
pub const BDF_DENSE_MAX_LINKS: usize = 500;

/// The largest elastic chain `bdf-dense` runs: `6 n + 1` unknowns, so
/// about the same dense matrices as [`BDF_DENSE_MAX_LINKS`] rigid rods.
pub const BDF_DENSE_MAX_ELASTIC_LINKS: usize = 160;
