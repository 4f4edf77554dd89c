//! The narrow interface between a problem and the integrators.
//!
//! A problem is a [`Problem`]: an [`OdeSystem`] `y' = f(t, y)` that may
//! also state itself as a banded [`SemiExplicitDae`] (for the O(n) BDF) and
//! carry its model's plan for `auto` ([`Problem::auto_plan`]). An
//! integrator advances it and hands every accepted step, with its
//! continuous extension, to an [`Observer`]. Integrators never look inside
//! the state; observers never step. This module depends on no method (only
//! on `auto`'s plan, plain data): the methods depend on it, never the other
//! way.

use std::ops::Range;

use crate::auto::AutoPlan;
use crate::nonsmooth::Nonsmooth;

/// `y' = f(t, y)` on `R^dim`.
pub trait OdeSystem {
    /// Length of the state vector.
    fn dim(&self) -> usize;
    /// `dy = f(t, y)`. Must not allocate: it is the hot path.
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]);
    /// The exact Jacobian-vector product `jv = (df/dy)(t, y) v`.
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]);
}

impl<S: OdeSystem + ?Sized> OdeSystem for &mut S {
    fn dim(&self) -> usize {
        (**self).dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        (**self).rhs(t, y, dy)
    }
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        (**self).jvp(t, y, v, jv)
    }
}

/// A semi-explicit DAE `M y' = f(t, y)` with the constant mass matrix
/// `M = diag(1 (differential_dim), 0 (the rest))`: the differential unknowns
/// come first, then the algebraic ones. The sparse BDF runs any of them;
/// it must be of index 1 (the algebraic block of the Jacobian nonsingular).
pub trait SemiExplicitDae {
    /// Number of unknowns.
    fn dim(&self) -> usize;
    /// Number of differential unknowns: the first rows and columns.
    fn differential_dim(&self) -> usize;
    /// `out = f(t, y)`: the derivatives of the differential unknowns, then
    /// the residuals of the algebraic equations.
    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]);
    /// The derivatives of the differential unknowns alone, bit for bit the
    /// first `differential_dim` entries of [`SemiExplicitDae::rhs`], into
    /// `out[..differential_dim]` (`out` has `dim` entries; the rest are
    /// left as they are), when the DAE can give them without its algebraic
    /// residuals (the chain's: `w` and `alpha` are unknowns): `true`. The
    /// default writes nothing and returns `false`; the caller then
    /// evaluates `rhs`. The BDF's loop uses it for the observer's `f1`.
    fn derivatives(&self, _t: f64, _y: &[f64], _out: &mut [f64]) -> bool {
        false
    }
    /// Entries of `df/dy` at `(t, y)` as `emit(row, column, value)`. The
    /// entries and their order must not depend on `t` or `y`: the pattern
    /// is built once, from the start.
    fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64));
    /// The values of [`SemiExplicitDae::jacobian_entries`] at `(t, y)`, in
    /// its order, into `out` (one per entry; extra entries of `out` are
    /// left as they are): what a method that keeps the pattern reads. The
    /// default collects them through `jacobian_entries`; a DAE that can
    /// write them without a call per entry overrides it (the elastic
    /// chain's).
    fn jacobian_values(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let mut k = 0;
        self.jacobian_entries(t, y, &mut |_, _, v| {
            if let Some(o) = out.get_mut(k) {
                *o = v;
            }
            k += 1;
        });
    }
    /// The unknowns as a chain of blocks: `Some(block)` with `block[u]` the
    /// block (`0..K`, none empty, in the chain's order) of unknown `u`, such
    /// that every Jacobian entry couples an unknown to its own block or a
    /// neighbouring one (for a chain of rods: a block per rod). The sparse
    /// BDF then factorises its Newton matrices block-tridiagonally (and
    /// checks the claim against the pattern first). `None` (the default):
    /// no such grouping is known, and the general sparse LU runs.
    fn blocks(&self) -> Option<Vec<usize>> {
        None
    }
}

impl<D: SemiExplicitDae + ?Sized> SemiExplicitDae for Box<D> {
    fn dim(&self) -> usize {
        (**self).dim()
    }
    fn differential_dim(&self) -> usize {
        (**self).differential_dim()
    }
    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) {
        (**self).rhs(t, y, out)
    }
    fn derivatives(&self, t: f64, y: &[f64], out: &mut [f64]) -> bool {
        (**self).derivatives(t, y, out)
    }
    fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        (**self).jacobian_entries(t, y, emit)
    }
    fn jacobian_values(&self, t: f64, y: &[f64], out: &mut [f64]) {
        (**self).jacobian_values(t, y, out)
    }
    fn blocks(&self) -> Option<Vec<usize>> {
        (**self).blocks()
    }
}

/// A problem as a banded DAE: the equations, and the consistent start whose
/// first `differential_dim` unknowns are the [`OdeSystem`]'s state.
pub struct BandedDae {
    pub dae: Box<dyn SemiExplicitDae>,
    /// Every unknown at the start, the algebraic equations holding.
    pub y0: Vec<f64>,
}

/// What every method runs: the [`OdeSystem`], and what some methods need
/// besides. A new model implements this once and every method runs it.
pub trait Problem: OdeSystem {
    /// The problem as a banded index-1 DAE from the state `y0` at `t0`,
    /// whose differential unknowns are this system's state (the O(n) BDF
    /// runs it). `None` (the default): the problem has no such form, and
    /// `bdf` ends at the start with `diverged`.
    fn banded_dae(&self, _t0: f64, _y0: &[f64]) -> Option<BandedDae> {
        None
    }

    /// `auto`'s plan for this problem, when its model gave one (the run
    /// layer does); `None`: the generic plan ([`AutoPlan::generic`]).
    fn auto_plan(&self) -> Option<AutoPlan> {
        None
    }

    /// The unknowns of the state that are a configuration (angles,
    /// positions) whose rates are unknowns too: the second-order
    /// structure. `gen-alpha` measures its local error on these alone, as
    /// structural dynamics controls the displacements, so that the rates
    /// of modes it damps unresolved do not hold its step (the run layer
    /// gives the model's: its layout's angles and positions). Empty (the
    /// default): every unknown.
    fn configuration(&self) -> Vec<Range<usize>> {
        Vec::new()
    }

    /// The problem as a mechanical system with constraints in maximal
    /// coordinates ([`Nonsmooth`]), for a method that steps over impacts
    /// (`moreau-jean`). `None` (the default): it has no such form, and
    /// `moreau-jean` ends at the start with `diverged`.
    fn nonsmooth(&mut self) -> Option<&mut dyn Nonsmooth> {
        None
    }
    /// Quantities of the state that a study measures (a tip's position or
    /// speed, a force), whose local errors `gen-alpha` bounds by the
    /// tolerance besides the configuration's. `None` (the default): the
    /// configuration alone.
    fn measured(&self) -> Option<Box<dyn Measured>> {
        None
    }
}

/// Scalar quantities of a problem's state, `q(t, y)`: what a study
/// measures, handed to the error control ([`Problem::measured`]). A step's
/// local error `e` moves each by `q(t, y + e) - q(t, y)`.
pub trait Measured {
    /// How many quantities.
    fn count(&self) -> usize;
    /// Their values at `(t, y)` into `out` (`count` entries). Called twice
    /// per step attempt: it must not allocate.
    fn values(&self, t: f64, y: &[f64], out: &mut [f64]);
}

/// A system that counts the calls made to it: the work counters of every
/// method that steps through an [`OdeSystem`] come from here, never from
/// counting by hand.
pub struct Counted<S> {
    inner: S,
    rhs_calls: u64,
    jvp_calls: u64,
}

impl<S: OdeSystem> Counted<S> {
    /// `inner`, with both counters at zero.
    pub fn new(inner: S) -> Self {
        Self {
            inner,
            rhs_calls: 0,
            jvp_calls: 0,
        }
    }

    /// Right-hand sides evaluated so far.
    pub fn rhs_calls(&self) -> u64 {
        self.rhs_calls
    }

    /// Jacobian-vector products evaluated so far.
    pub fn jvp_calls(&self) -> u64 {
        self.jvp_calls
    }

    /// Runs `method` on `inner` through a counter: the outcome's
    /// `rhs_evals` is the number of right-hand sides it asked for.
    pub fn run(inner: S, method: impl FnOnce(&mut Self) -> Outcome) -> Outcome {
        let mut counted = Self::new(inner);
        let mut out = method(&mut counted);
        out.stats.rhs_evals = counted.rhs_calls();
        out
    }
}

impl<S: OdeSystem> OdeSystem for Counted<S> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.rhs_calls += 1;
        self.inner.rhs(t, y, dy)
    }
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        self.jvp_calls += 1;
        self.inner.jvp(t, y, v, jv)
    }
}

/// A continuous extension of one accepted step over `[t0, t1]`.
pub trait Interpolant {
    /// The interpolated state at `t` in `[t0, t1]`.
    fn eval(&self, t: f64, out: &mut [f64]);
}

/// One accepted step as observers see it: end points, their derivatives, and
/// the method's interpolant between them.
pub struct StepView<'a> {
    pub t0: f64,
    pub t1: f64,
    /// The state at `t0`. The chain's observer needs only `y1`; the methods'
    /// tests check the interpolant against both ends.
    #[allow(dead_code)]
    pub y0: &'a [f64],
    pub y1: &'a [f64],
    /// `f(t1, y1)`.
    pub f1: &'a [f64],
    pub interpolant: &'a dyn Interpolant,
}

/// Watches a run: sampling, maxima, invariants. Never changes it.
pub trait Observer {
    /// Called once with the initial state and its derivative.
    fn start(&mut self, t0: f64, y0: &[f64], f0: &[f64]);
    /// Called after every accepted step.
    fn step(&mut self, step: &StepView<'_>);
    /// Called when an explicit method's stiffness detector fires on the
    /// accepted step ending at `t` (just shown), with its estimate
    /// `|lambda|` (1/time). `auto` watches it to hand over.
    fn stiff(&mut self, _t: f64, _lambda: f64) {}
    /// True once the run should stop (its [`Cancel`] was set). Every method
    /// asks before each step attempt and then ends with
    /// [`Status::Interrupted`] at its last accepted step. Called once per
    /// attempt: it must be cheap (one relaxed atomic load).
    fn stop(&self) -> bool {
        false
    }
}

/// Cubic Hermite interpolation between `(y0, f0)` and `(y1, f1)`: fourth-order
/// accurate, the continuous extension used for RK4.
pub struct Hermite<'a> {
    pub t0: f64,
    pub h: f64,
    pub y0: &'a [f64],
    pub f0: &'a [f64],
    pub y1: &'a [f64],
    pub f1: &'a [f64],
}

impl Interpolant for Hermite<'_> {
    fn eval(&self, t: f64, out: &mut [f64]) {
        let s = (t - self.t0) / self.h;
        let s2 = s * s;
        let s3 = s2 * s;
        let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
        let h10 = (s3 - 2.0 * s2 + s) * self.h;
        let h01 = -2.0 * s3 + 3.0 * s2;
        let h11 = (s3 - s2) * self.h;
        for (i, o) in out.iter_mut().enumerate() {
            *o = h00 * self.y0[i] + h10 * self.f0[i] + h01 * self.y1[i] + h11 * self.f1[i];
        }
    }
}

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Reached `t_end`.
    Ok,
    /// A non-finite value appeared; the run stopped at the last finite state
    /// (or, with every state finite, a summary value such as the energy was
    /// not: see `solve`).
    Diverged,
    /// The adaptive step fell below the minimum.
    StepSizeTooSmall,
    /// The step budget ran out.
    MaxSteps,
    /// An implicit method's Newton matrix could not be factorised, even
    /// after the step was cut.
    LinearSolveFailed,
    /// The run reached `t_end` with every value finite, but its energy
    /// balance error `max |E + W - E(0)|` exceeds the model's energy scale
    /// (chain-ode's `Model::energy_scale`; the run layer decides it): the
    /// numbers are not a solution of the model.
    Inaccurate,
    /// The run was stopped from outside (a [`Cancel`] was set: Ctrl-C in
    /// Python, a signal in the CLI) at the last accepted step.
    Interrupted,
}

impl Status {
    /// The name used in `--json` and CSV output.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Ok => "ok",
            Self::Diverged => "diverged",
            Self::StepSizeTooSmall => "step_size_too_small",
            Self::MaxSteps => "max_steps",
            Self::LinearSolveFailed => "linear_solve_failed",
            Self::Inaccurate => "inaccurate",
            Self::Interrupted => "interrupted",
        }
    }

    /// True for `Ok`.
    pub fn is_ok(self) -> bool {
        self == Self::Ok
    }
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A flag that stops a run from outside, shared between the caller and the
/// run (clones share it). The run checks it after every accepted step and
/// ends with [`Status::Interrupted`] once it is set. It also carries the
/// time the run last recorded a sample ([`Cancel::reached`]), for a caller
/// that shows progress from another thread.
#[derive(Clone, Debug, Default)]
pub struct Cancel(std::sync::Arc<Shared>);

/// What a [`Cancel`]'s clones share.
#[derive(Debug, Default)]
struct Shared {
    stop: std::sync::atomic::AtomicBool,
    /// The bits of the last recorded sample's time (0.0 before any).
    time: std::sync::atomic::AtomicU64,
}

impl Cancel {
    /// A flag that is not set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets the flag: every run holding a clone stops at its next step.
    pub fn cancel(&self) {
        self.0
            .stop
            .store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// True once [`Cancel::cancel`] was called on this flag or a clone.
    pub fn is_cancelled(&self) -> bool {
        self.0.stop.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// Notes `t` (time units) as the time the run has reached: called by
    /// the run at each sample it records (never inside a step).
    pub fn report(&self, t: f64) {
        self.0
            .time
            .store(t.to_bits(), std::sync::atomic::Ordering::Relaxed);
    }

    /// The time of the last sample a run holding this flag recorded (0
    /// before the first; the latest of any of them when several share it).
    pub fn reached(&self) -> f64 {
        f64::from_bits(self.0.time.load(std::sync::atomic::Ordering::Relaxed))
    }
}
/// Two flags are equal when they are the same flag.
impl PartialEq for Cancel {
    fn eq(&self, other: &Self) -> bool {
        std::sync::Arc::ptr_eq(&self.0, &other.0)
    }
}

/// Work counters of a run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts (error test or nonlinear solver failure).
    pub rejected_steps: u64,
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Jacobian evaluations (dense Jacobians built).
    pub jacobian_evals: u64,
    /// LU factorisations (implicit methods).
    pub lu_factorizations: u64,
    /// Times the stiffness detector fired (DOPRI5).
    pub stiffness_detections: u64,
    /// Implicit methods (diffsol's BDFs): attempts rejected by the local
    /// error test. With [`Stats::newton_failures`] they make up
    /// `rejected_steps` (less a step accepted below the step floor, which
    /// counts as rejected). 0 for the explicit methods, whose rejections
    /// are all error-test failures and are counted in `rejected_steps`.
    pub error_test_failures: u64,
    /// Implicit methods: attempts rejected because the Newton iteration
    /// did not converge (or its linear solve failed).
    pub newton_failures: u64,
    /// Implicit methods: Newton iterations over the run, rejected
    /// attempts included (`moreau-jean`: those of its contact solves and
    /// projections, one factorisation each).
    pub newton_iterations: u64,
    /// `moreau-jean`: the most contacts active in one step (0 for the
    /// other methods).
    pub contacts_max: u64,
    /// `moreau-jean`: the largest residual of a contact solve's laws at
    /// its end over the run (velocity units for the velocity solves,
    /// length for the projections): how far from exact the impulses are.
    pub complementarity_residual: f64,
    /// `moreau-jean`: the largest violation of a bilateral row (a joint)
    /// left at a step's end after its projection (length): what the
    /// states carry (the drift one step makes is taken out by the
    /// projection's Newton passes).
    pub constraint_drift: f64,
    /// Times the step size was changed after an accepted step (`gen-alpha`,
    /// whose controller keeps it inside a dead band: each change costs an
    /// LU); 0 for the methods that do not count them.
    pub step_size_changes: u64,
}

impl std::ops::AddAssign for Stats {
    fn add_assign(&mut self, o: Self) {
        self.steps += o.steps;
        self.rejected_steps += o.rejected_steps;
        self.rhs_evals += o.rhs_evals;
        self.jacobian_evals += o.jacobian_evals;
        self.lu_factorizations += o.lu_factorizations;
        self.stiffness_detections += o.stiffness_detections;
        self.error_test_failures += o.error_test_failures;
        self.newton_failures += o.newton_failures;
        self.newton_iterations += o.newton_iterations;
        self.step_size_changes += o.step_size_changes;
        self.contacts_max = self.contacts_max.max(o.contacts_max);
        self.complementarity_residual =
            max_nan(self.complementarity_residual, o.complementarity_residual);
        self.constraint_drift = max_nan(self.constraint_drift, o.constraint_drift);
    }
}

/// The larger of two values, NaN if either is.
fn max_nan(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// What an integrator returns: where it got, how, and at what cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    pub status: Status,
    /// The last time with a finite state (== t_end when `status` is `Ok`).
    pub t_reached: f64,
    /// The time at which the run failed (the attempted step's end), if it did.
    pub t_failed: Option<f64>,
    pub stats: Stats,
    /// The state at `t_reached`.
    pub y_end: Vec<f64>,
}

impl Outcome {
    /// A run that ended at `t` in state `y`.
    pub fn ended(status: Status, t: f64, t_failed: Option<f64>, stats: Stats, y: Vec<f64>) -> Self {
        Self {
            status,
            t_reached: t,
            t_failed,
            stats,
            y_end: y,
        }
    }
}

/// True if every entry is finite.
pub fn all_finite(y: &[f64]) -> bool {
    y.iter().all(|v| v.is_finite())
}
