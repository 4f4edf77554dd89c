//! `moreau-jean`: Moreau–Jean time stepping for a [`Nonsmooth`] problem,
//! stepping over impacts at a fixed step `dt` (Moreau 1988, Jean 1999;
//! Acary & Brogliato, *Numerical Methods for Nonsmooth Dynamical Systems*,
//! 2008, §10.1; Siconos' `MoreauJeanOSI`, Chrono's NSC), with a position
//! projection after every step (Acary 2013, the "direct projection").
//!
//! One step from `(t, q, v)` by `h`:
//!
//! ```text
//! q_m  = q + h/2 v                               the midpoint
//! v̂    = v + h M⁻¹ f(t + h/2, q_m, v)            the free motion
//! v⁺   = v̂ + M⁻¹ J(q_m)ᵀ P                       the impulses P of the rows at q_m:
//!         bilateral  J v⁺ = 0
//!         contact    0 <= P_N ⊥ u_N⁺ + e min(û_N, 0) >= 0
//!                    (active when g(q_m) + h/2 û_N <= 0)
//!         friction   |P_T| <= mu P_N, Coulomb on u_T⁺
//! q⁺   = q_m + h/2 v⁺
//! ```
//!
//! (`u = J v`, `û = J v̂` the free motion's, which the impulses act on),
//! the impulses from
//! [`Complementarity`], O(n) per Newton iteration. With a constant force
//! the free motion is exact (uniform acceleration), and with the contacts
//! the velocity jump is the impulse law's exactly: a plastic impact of a
//! rigid body is its closed form at any step. The joints hold at the
//! velocity level only, so `q⁺` drifts off them by `O(h³)` per step; the
//! projection then finds the nearest `q` (in the metric `M`) with every
//! bilateral row `g = 0` and every contact `g >= 0`, linearised at `q⁺`:
//! the same complementarity problem, with the gaps for `b` and no
//! friction. It moves positions, not velocities. The step's record
//! ([`StepRecord`]) carries the impulses and the work the contacts took
//! (`−Σ P (u⁺ + û)/2`, exactly the kinetic energy they removed from the
//! free motion, Kelvin's theorem), from
//! which the problem keeps its forces and its dissipated work.
//!
//! A step whose contact solve does not converge is tried again at half
//! the step (a rejected step), down to the step floor; the steps then go
//! on to the next point of the grid `t0 + k dt`, so that a run's steps end
//! on that grid.

use super::complementarity::Complementarity;
use super::integrator::{Integrator, Run, Span};
use crate::nonsmooth::{Nonsmooth, Row, RowKind, StepRecord, MAX_BODY, MAX_ROWS};
use crate::ode::{all_finite, Interpolant, Observer, Outcome, Problem, Stats, Status, StepView};

/// The most Newton passes of a step's projection.
pub const MAX_PROJECTIONS: usize = 6;

/// The violation of the rows at which a projection stops, relative to the
/// largest coordinate (and at least 1): far below any step's accuracy.
pub const PROJECTION_TOLERANCE: f64 = 1e-10;

/// `moreau-jean`: fixed step `dt`; runs a problem that states itself as
/// [`Nonsmooth`] ([`Problem::nonsmooth`]), and ends any other at its start
/// with `diverged`.
pub(crate) const MOREAU_JEAN: Integrator = Integrator {
    name: "moreau-jean",
    adaptive: false,
    nonsmooth: true,
    run,
};

/// The linear interpolant between a step's two ends.
struct Linear<'a> {
    t0: f64,
    h: f64,
    y0: &'a [f64],
    y1: &'a [f64],
}

impl Interpolant for Linear<'_> {
    fn eval(&self, t: f64, out: &mut [f64]) {
        let s = ((t - self.t0) / self.h).clamp(0.0, 1.0);
        for ((o, a), b) in out.iter_mut().zip(self.y0).zip(self.y1) {
            *o = a + s * (b - a);
        }
    }
}

fn run(problem: &mut dyn Problem, span: &Span<'_>, obs: &mut dyn Observer) -> Run {
    let (t0, y0) = (span.t0, span.y0);
    let stats = Stats::default();
    let d = problem.dim();
    let mut f0 = vec![0.0; d];
    if !all_finite(y0) || problem.nonsmooth().is_none() {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y0.to_vec()).into();
    }
    problem.rhs(t0, y0, &mut f0);
    let Some(sys) = problem.nonsmooth() else {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y0.to_vec()).into();
    };
    let (n, b, s) = (sys.bodies(), sys.body_dim(), sys.block_rows());
    if n == 0 || !(1..=MAX_BODY).contains(&b) || !(1..=MAX_ROWS).contains(&s) {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y0.to_vec()).into();
    }
    let mut stepper = Stepper::new(sys, n, b, s);
    let mut out = stepper.steps(span, &f0, obs);
    out.stats.rhs_evals += 1;
    out.into()
}

/// One run's state and scratch.
struct Stepper<'p> {
    sys: &'p mut dyn Nonsmooth,
    minv: Vec<f64>,
    q: Vec<f64>,
    v: Vec<f64>,
    qm: Vec<f64>,
    v1: Vec<f64>,
    q1: Vec<f64>,
    force: Vec<f64>,
    rows: Vec<Row>,
    kinds: Vec<RowKind>,
    /// The rows at the step's end, for the projection.
    projected: Vec<Row>,
    projected_kinds: Vec<RowKind>,
    projected_gaps: Vec<f64>,
    before: Vec<f64>,
    after: Vec<f64>,
    bias: Vec<f64>,
    /// The step's contact problem and the projection's (each keeps its own
    /// warm start).
    velocity: Complementarity,
    position: Complementarity,
    stats: Stats,
}

impl<'p> Stepper<'p> {
    fn new(sys: &'p mut dyn Nonsmooth, n: usize, b: usize, s: usize) -> Self {
        let dim = n * b;
        let rows = (n + 1) * s;
        let mut minv = vec![0.0; dim];
        sys.inverse_mass(&mut minv);
        Self {
            velocity: Complementarity::new(n, b, s, minv.clone()),
            position: Complementarity::new(n, b, s, minv.clone()),
            sys,
            minv,
            q: vec![0.0; dim],
            v: vec![0.0; dim],
            qm: vec![0.0; dim],
            v1: vec![0.0; dim],
            q1: vec![0.0; dim],
            force: vec![0.0; dim],
            rows: vec![Row::OFF; rows],
            kinds: vec![RowKind::Off; rows],
            projected: vec![Row::OFF; rows],
            projected_kinds: vec![RowKind::Off; rows],
            projected_gaps: vec![0.0; rows],
            before: vec![0.0; rows],
            after: vec![0.0; rows],
            bias: vec![0.0; rows],
            stats: Stats::default(),
        }
    }

    /// The steps over `span`, shown to `obs`.
    fn steps(&mut self, span: &Span<'_>, f0: &[f64], obs: &mut dyn Observer) -> Outcome {
        let (t0, t_end, dt) = (span.t0, span.t_end, span.settings.dt);
        let mut y = span.y0.to_vec();
        let mut y1 = y.clone();
        let mut f1 = vec![0.0; y.len()];
        if !(self.minv.iter().all(|m| m.is_finite() && *m > 0.0)) {
            return Outcome::ended(Status::Diverged, t0, Some(t0), self.stats, y);
        }
        self.sys.coordinates(&y, &mut self.q, &mut self.v);
        obs.start(t0, &y, f0);
        let mut t = t0;
        let mut k: u64 = 0;
        while t < t_end {
            // The next point of the grid, landing on t_end (absorbing a
            // sliver below 1e-9 dt).
            let mut target = t0 + (k + 1) as f64 * dt;
            if target > t_end - 1e-9 * dt {
                target = t_end;
            }
            let mut h = target - t;
            while t < target {
                if self.stats.steps + self.stats.rejected_steps >= span.settings.max_steps {
                    return Outcome::ended(Status::MaxSteps, t, Some(t), self.stats, y);
                }
                if obs.stop() {
                    return Outcome::ended(Status::Interrupted, t, Some(t), self.stats, y);
                }
                let t1 = if t + h >= target - 1e-9 * h {
                    target
                } else {
                    t + h
                };
                match self.attempt(t, t1 - t) {
                    Attempt::Done(work) => {
                        let hh = t1 - t;
                        y1.copy_from_slice(&y);
                        let record = StepRecord {
                            t0: t,
                            h: hh,
                            q: &self.q1,
                            v: &self.v1,
                            v0: &self.v,
                            rows: &self.rows,
                            impulses: &self.velocity.impulses,
                            contact_work: work,
                        };
                        self.sys.state(&record, &mut y1);
                        if !all_finite(&y1) {
                            return Outcome::ended(Status::Diverged, t, Some(t1), self.stats, y);
                        }
                        for ((f, a), b) in f1.iter_mut().zip(&y).zip(&y1) {
                            *f = (b - a) / hh;
                        }
                        self.stats.steps += 1;
                        obs.step(&StepView {
                            t0: t,
                            t1,
                            y0: &y,
                            y1: &y1,
                            f1: &f1,
                            interpolant: &Linear {
                                t0: t,
                                h: hh,
                                y0: &y,
                                y1: &y1,
                            },
                        });
                        std::mem::swap(&mut y, &mut y1);
                        std::mem::swap(&mut self.q, &mut self.q1);
                        std::mem::swap(&mut self.v, &mut self.v1);
                        t = t1;
                    }
                    Attempt::Unsolved => {
                        self.stats.rejected_steps += 1;
                        h *= 0.5;
                        if h < span.settings.floor_towards(t, target) {
                            return Outcome::ended(
                                Status::StepSizeTooSmall,
                                t,
                                Some(t + h),
                                self.stats,
                                y,
                            );
                        }
                    }
                    Attempt::NonFinite => {
                        return Outcome::ended(Status::Diverged, t, Some(t + h), self.stats, y);
                    }
                }
            }
            k += 1;
        }
        Outcome::ended(Status::Ok, t, None, self.stats, y)
    }

    /// One step from `(t, q, v)` by `h` into `q1`, `v1`, the impulses in
    /// the velocity solver: the contacts' work, or why it failed.
    fn attempt(&mut self, t: f64, h: f64) -> Attempt {
        let half = 0.5 * h;
        for ((m, q), v) in self.qm.iter_mut().zip(&self.q).zip(&self.v) {
            *m = q + half * v;
        }
        self.sys
            .forces(t + half, &self.qm, &self.v, &mut self.force);
        self.stats.rhs_evals += 1;
        for (((w, v), f), mi) in self
            .v1
            .iter_mut()
            .zip(&self.v)
            .zip(&self.force)
            .zip(&self.minv)
        {
            *w = v + h * mi * f;
        }
        self.sys.rows(t + half, &self.qm, &mut self.rows);
        // A contact takes part when the free motion would close its gap by
        // the step's end, `g(q_m) + h/2 J v̂ <= 0`; its friction with it.
        self.velocity
            .velocities(&self.rows, &self.v1, &mut self.before);
        let mut active = 0u64;
        for g in 0..self.rows.len() {
            let row = &self.rows[g];
            self.kinds[g] = match row.kind {
                RowKind::Normal { .. } if row.gap + half * self.before[g] > 0.0 => RowKind::Off,
                RowKind::Normal { .. } => {
                    active += 1;
                    row.kind
                }
                RowKind::Tangent { .. }
                    if g == 0 || !matches!(self.kinds[g - 1], RowKind::Normal { .. }) =>
                {
                    RowKind::Off
                }
                other => other,
            };
        }
        self.stats.contacts_max = self.stats.contacts_max.max(active);
        self.velocity.delassus(&self.rows);
        self.stats.jacobian_evals += 1;
        // Newton's law on the velocity the impulse acts on, the free
        // motion's at the step's end `û = J v̂`: `u⁺ + e min(û, 0) >= 0`.
        for ((b, kind), u0) in self.bias.iter_mut().zip(&self.kinds).zip(&self.before) {
            *b = *u0;
            if let RowKind::Normal { restitution } = kind {
                *b += restitution * u0.min(0.0);
            }
        }
        let solved = self.velocity.solve(&self.kinds, &self.bias);
        self.note(solved);
        if !solved.converged {
            return if solved.residual.is_finite() {
                Attempt::Unsolved
            } else {
                Attempt::NonFinite
            };
        }
        self.velocity
            .add_impulses(&self.rows, &self.velocity.impulses, &mut self.v1);
        // The contacts' work, from their impulses and the velocities
        // either side of them (Kelvin's theorem: the kinetic energy the
        // impulses took from the free motion).
        self.velocity
            .velocities(&self.rows, &self.v1, &mut self.after);
        let mut work = 0.0;
        for (((kind, p), u0), u1) in self
            .kinds
            .iter()
            .zip(&self.velocity.impulses)
            .zip(&self.before)
            .zip(&self.after)
        {
            if matches!(kind, RowKind::Normal { .. } | RowKind::Tangent { .. }) {
                work -= p * 0.5 * (u0 + u1);
            }
        }
        // The rows as the step used them (an inactive contact `Off`).
        for (row, kind) in self.rows.iter_mut().zip(&self.kinds) {
            row.kind = *kind;
        }
        for ((q1, m), v) in self.q1.iter_mut().zip(&self.qm).zip(&self.v1) {
            *q1 = m + half * v;
        }
        if !(all_finite(&self.q1) && all_finite(&self.v1)) {
            return Attempt::NonFinite;
        }
        if self.project(t + h) {
            Attempt::Done(work)
        } else {
            Attempt::Unsolved
        }
    }

    /// Moves `q1` to the nearest coordinates (metric `M`) where the joints
    /// hold and no contact of the step (or closed at `q1`) is inside its
    /// gap: Newton's iteration on that projection, each pass linearised at
    /// the last `q1` (a complementarity problem on the same band), until
    /// the rows hold to rounding or [`MAX_PROJECTIONS`] passes. `false`
    /// when a pass was not solved.
    fn project(&mut self, t1: f64) -> bool {
        let scale = self.q1.iter().fold(1.0f64, |a, q| a.max(q.abs()));
        let tolerance = PROJECTION_TOLERANCE * scale;
        for pass in 0..=MAX_PROJECTIONS {
            self.sys.rows(t1, &self.q1, &mut self.projected);
            let mut violation = 0.0f64;
            let mut drift = 0.0f64;
            for (g, row) in self.projected.iter().enumerate() {
                let (kind, b) = match row.kind {
                    RowKind::Bilateral => {
                        drift = drift.max(row.gap.abs());
                        (RowKind::Bilateral, row.gap)
                    }
                    RowKind::Normal { .. }
                        if row.gap < 0.0 || matches!(self.kinds[g], RowKind::Normal { .. }) =>
                    {
                        violation = violation.max(-row.gap);
                        (RowKind::Normal { restitution: 0.0 }, row.gap)
                    }
                    _ => (RowKind::Off, 0.0),
                };
                self.projected_kinds[g] = kind;
                self.projected_gaps[g] = b;
            }
            violation = violation.max(drift);
            if violation <= tolerance || pass == MAX_PROJECTIONS || violation.is_nan() {
                if drift > self.stats.constraint_drift || drift.is_nan() {
                    self.stats.constraint_drift = drift;
                }
                return violation.is_finite();
            }
            self.position.delassus(&self.projected);
            self.stats.jacobian_evals += 1;
            let solved = self
                .position
                .solve(&self.projected_kinds, &self.projected_gaps);
            self.note(solved);
            if !solved.converged {
                return false;
            }
            self.position
                .add_impulses(&self.projected, &self.position.impulses, &mut self.q1);
        }
        true
    }

    fn note(&mut self, solved: crate::complementarity::Solved) {
        self.stats.newton_iterations += solved.iterations;
        self.stats.lu_factorizations += solved.iterations;
        if solved.residual > self.stats.complementarity_residual || solved.residual.is_nan() {
            self.stats.complementarity_residual = solved.residual;
        }
    }
}

/// How an attempted step ended.
enum Attempt {
    /// Done, with the contacts' work.
    Done(f64),
    /// Its contact problem was not solved: try a shorter step.
    Unsolved,
    /// A non-finite value.
    NonFinite,
}
