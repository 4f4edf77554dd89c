//! What a state means, apart from how it is made: the [`StateView`] trait.
//!
//! A model ([`Model`](super::Model)) is the problem side: its layout, its
//! bounds, its first state, its problem, its event and `auto`'s plan. What
//! a state of it means (the tip, the joints, the energy, the forces) is its
//! view, one per state layout and shared by the models that have it: the
//! rigid chain's `[phi, w, W]` ([`RigidView`](super::RigidView), the rigid
//! and the report models), the elastic links' `[phi, w, W, x, y, vx, vy]`
//! ([`LinkView`](super::LinkView)), the contact chain's, which adds the
//! forces of the last step ([`ContactView`](super::ContactView)), and a
//! model's own (BEAM's, a model of another crate's).

use super::{ForceScratch, Observed, PeakForce, PeakValue};
use crate::kinematics::Vec2;

/// What a state `y` at `t` means: read by the run layer at every accepted
/// step ([`StateView::observe`]) and by every accessor of a trajectory's
/// sample. Every method takes `&self`: a view never changes along a run.
pub trait StateView {
    /// The run's view of `y` at `t` (`f = y'` there), in one pass. `trig`
    /// is scratch the model may use (no allocation once it has grown).
    fn observe(&self, t: f64, y: &[f64], f: &[f64], trig: &mut Vec<(f64, f64)>) -> Observed;

    /// The energy of `y` at `t`, as [`StateView::observe`] has it.
    fn energy(&self, t: f64, y: &[f64]) -> f64;

    /// The tip (the free end) at `t`.
    fn tip(&self, t: f64, y: &[f64]) -> Vec2;

    /// The tip's velocity at `t` in the inertial frame.
    fn tip_velocity(&self, t: f64, y: &[f64]) -> Vec2;

    /// The support's (pivot's) position and velocity at `t`.
    fn support(&self, _t: f64, _y: &[f64]) -> [Vec2; 2] {
        [[0.0, 0.0], [0.0, 0.0]]
    }

    /// The joints `P_0..P_n` at `t`.
    fn joints(&self, t: f64, y: &[f64]) -> Vec<Vec2>;

    /// The joint forces `[tension, shear]` at joints `0..=n` at `t`.
    fn joint_forces(&self, t: f64, y: &[f64]) -> Vec<Vec2>;

    /// The force of the support on the first rod at `t` (zero where the
    /// model has none).
    fn support_force(&self, _t: f64, _y: &[f64]) -> Vec2 {
        [0.0, 0.0]
    }

    /// True when the summary's tip speed maximum is refined inside the
    /// steps on the continuous extension (the chains'); false keeps the
    /// step ends' values only, so that a benchmark's work counters are its
    /// integrator's alone (a lazy dense output costs right-hand sides).
    fn refines_tip_speed(&self) -> bool {
        true
    }

    /// The momentum relative to the support.
    fn momentum(&self, _t: f64, _y: &[f64]) -> Vec2 {
        [0.0, 0.0]
    }

    /// The floor's force on each contact point at `t` (physical units; the
    /// elastic chain's: rod 0's start, rod 0's end, rod 1's start, ...), or
    /// `None` for a model without a floor.
    fn floor_forces(&self, _t: f64, _y: &[f64]) -> Option<Vec<Vec2>> {
        None
    }

    /// The floor as placed for the run, `(height at x = 0, angle)` in scene
    /// coordinates, or `None` without a floor.
    fn floor_line(&self) -> Option<(f64, f64)> {
        None
    }

    /// The forces whose peaks the run tracks at every accepted step
    /// ([`PeakForce`]; `Summary::peaks`): none by default.
    fn peak_forces(&self) -> &'static [PeakForce] {
        &[]
    }

    /// `force`'s value and reference at `(t, y)` ([`PeakValue`]), for a
    /// force of [`StateView::peak_forces`]: a function of the state alone,
    /// O(n) and allocation free once `scratch` has grown at the run's
    /// first call (it runs at every step).
    fn peak_force(
        &self,
        _force: PeakForce,
        _t: f64,
        _y: &[f64],
        _scratch: &mut ForceScratch,
    ) -> PeakValue {
        [0.0, 0.0]
    }
}
