//! The peaks of forces a run tracks as properties of the run, never of its
//! output samples: at the start, at every accepted step's end, and inside
//! a step on the method's continuous extension where the force turns from
//! rising to falling (as the tip speed's maximum is refined). A model
//! names the forces it has ([`StateView::peak_forces`](crate::StateView::peak_forces)) and gives each one's
//! value at a state ([`StateView::peak_force`](crate::StateView::peak_force)); the tally folds them
//! ([`PeakTrack`]): the floor's normal force, the support's force and the
//! largest joint tension. A model's evaluation may keep scratch across the
//! run's steps ([`ForceScratch`]: the rigid chain's multipliers), sized at
//! the run's start, so that the tracking allocates nothing per step.

use fc_methods::StepView;

use super::recorder::{golden_max, golden_width};
use crate::model::Model;

/// A force whose largest value a run tracks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PeakForce {
    /// The floor's total normal force on the chain (force units; what a
    /// scale under it reads), with the weight of the contact points it
    /// pushes at that instant as its reference.
    Floor,
    /// The magnitude `|F_1|` of the support's force on the first rod
    /// (force units; zero once the pivot is let go). Reference: 0.
    Pivot,
    /// The largest tension over the joints `0..n` (joint 0 the pivot),
    /// `T_k = -F_k . u_k` (force units; positive when joint `k` pulls rod
    /// `k` back toward the support). Reference: that joint's index `k`.
    Tension,
}

impl PeakForce {
    /// The force's name in output (`simulate --json`'s `<name>_max`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Floor => "floor_force",
            Self::Pivot => "pivot_force",
            Self::Tension => "tension",
        }
    }
}

/// Scratch a model's [`StateView::peak_force`](crate::StateView::peak_force) keeps across a run's steps:
/// made empty with the run, grown by the model at its first evaluation,
/// never again (no allocation per step). The rigid chain keeps its DAE's
/// consistent state (the multipliers, `rigid.rs`) for the last state it
/// solved, so that the pivot force and the tensions of one state cost one
/// recursion.
#[derive(Debug, Default)]
pub struct ForceScratch {
    /// The time and state whose forces `joint` holds, if any.
    pub(crate) key: Option<f64>,
    pub(crate) state: Vec<f64>,
    /// The joints' forces of that state on the rod after each (physical
    /// units), joints `0..n`.
    pub(crate) joint: Vec<crate::kinematics::Vec2>,
    /// The model's own scratch (the rigid chain's DAE and its workspace).
    pub(crate) rigid: Option<Box<crate::model::RigidForces>>,
}

impl ForceScratch {
    /// True if `joint` holds the forces of `y` at `t` (an O(n) compare,
    /// cheaper than a solve).
    pub(crate) fn holds(&self, t: f64, y: &[f64]) -> bool {
        self.key == Some(t) && self.state == y
    }

    /// Marks `joint` as the forces of `y` at `t`.
    pub(crate) fn keep(&mut self, t: f64, y: &[f64]) {
        self.key = Some(t);
        self.state.clear();
        self.state.extend_from_slice(y);
    }
}

/// A force's value at a state, `[value, reference]`: the scalar whose
/// maximum is tracked and a quantity of the same instant that the summary
/// relates it to (the floor: the weight `g sum m_i / 2` of the contact
/// points it pushes, the tip's point with the tip mass; the tension: the
/// joint that carries it; the pivot: 0).
pub type PeakValue = [f64; 2];

/// The largest value of one force over a run, when, and its reference then.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Peak {
    pub force: PeakForce,
    /// The largest value (force units).
    pub value: f64,
    /// When it was reached.
    pub t: f64,
    /// The force's reference at that instant ([`PeakValue`]).
    pub reference: f64,
}

/// A step whose ends are both below this fraction of the running peak is
/// not searched inside: its interior would have to rise more than twice
/// its ends' value within one step the error control accepted. The
/// floor's: an impact's force rises from zero within a step.
const SEARCH_FRACTION: f64 = 0.5;

/// [`SEARCH_FRACTION`] for the pivot's force and the tensions, smooth
/// functions of the state that a step the error control accepted follows:
/// their interior would have to rise 11% above both ends. It keeps the
/// searches (and the slope's evaluation) to the steps near the peak: on
/// `scenes/span-d3.toml` (rigid, DOPRI5, 1,352 steps) the fraction 0.5
/// doubled the run's time, as many turning points of the ringing force
/// were searched.
const SEARCH_FRACTION_SMOOTH: f64 = 0.9;

impl PeakForce {
    /// The fraction of the running peak below which a step is not searched.
    fn search_fraction(self) -> f64 {
        match self {
            Self::Floor => SEARCH_FRACTION,
            Self::Pivot | Self::Tension => SEARCH_FRACTION_SMOOTH,
        }
    }
}

/// The running peak of one force.
pub(crate) struct PeakTrack {
    peak: Peak,
    /// The value and slope sign at the last step's end.
    last: f64,
    rising: bool,
}

impl PeakTrack {
    /// The track of `force` from `(t0, y0)`.
    pub fn start<M: Model>(
        model: &M,
        force: PeakForce,
        t0: f64,
        y0: &[f64],
        scratch: &mut ForceScratch,
    ) -> Self {
        let [value, reference] = model.view().peak_force(force, t0, y0, scratch);
        Self {
            peak: Peak {
                force,
                value,
                t: t0,
                reference,
            },
            last: value,
            rising: false,
        }
    }

    /// The peak so far.
    pub fn peak(&self) -> Peak {
        self.peak
    }

    /// An accepted step; `buf` is scratch of the state's size.
    pub fn step<M: Model>(
        &mut self,
        model: &M,
        step: &StepView<'_>,
        buf: &mut [f64],
        scratch: &mut ForceScratch,
    ) {
        let (t0, t1) = (step.t0, step.t1);
        let force = self.peak.force;
        let [value, reference] = model.view().peak_force(force, t1, step.y1, scratch);
        let worth = self.last.max(value) >= force.search_fraction() * self.peak.value;
        // The slope's sign at t1, from the state's derivative there (`y1 -
        // d f1` is the state at `t1 - d` to O(d^2)): no dense output, whose
        // stages a lazy method (DOP853) would pay at every step. A step
        // whose ends are far below the peak is not searched, and its
        // slope is the chord's (one evaluation saved where the force is
        // low).
        let rising = if worth {
            let d = 1e-3 * (t1 - t0);
            for ((b, y), f) in buf.iter_mut().zip(step.y1).zip(step.f1) {
                *b = y - d * f;
            }
            value > model.view().peak_force(force, t1 - d, buf, scratch)[0]
        } else {
            value > self.last
        };
        if self.rising && !rising && worth && t1 > t0 {
            // 1e-5 of the step: the value at the vertex is then right to
            // about 1e-10 of its curvature's scale (it is quadratic there).
            let tol = (1e-5 * (t1 - t0)).max(golden_width(t0, t1));
            let (t, v, _) = golden_max(t0, t1, tol, |t| {
                step.interpolant.eval(t, buf);
                model.view().peak_force(force, t, buf, scratch)[0]
            });
            if v > self.peak.value || v.is_nan() {
                step.interpolant.eval(t, buf);
                self.peak.value = v;
                self.peak.t = t;
                self.peak.reference = model.view().peak_force(force, t, buf, scratch)[1];
            }
        }
        if value > self.peak.value || value.is_nan() {
            self.peak.value = value;
            self.peak.t = t1;
            self.peak.reference = reference;
        }
        self.last = value;
        self.rising = rising;
    }
}
