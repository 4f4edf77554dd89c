//! What a finished run returns: its [`Summary`] (the scalar results) and
//! its [`Trajectory`] (the model, the samples, the work counters and the
//! status), whose every accessor of a sample asks the model.

use fc_methods::{Method, Segment, Stats, Status};

use crate::chain::Chain;
use crate::kinematics::Vec2;
use crate::model::{Model, ModelKind};

/// The scalar results of a run: what `simulate --json` prints.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// `E(0) = T + V` at the start.
    pub energy_start: f64,
    /// `E` at `t_reached`.
    pub energy_end: f64,
    /// Work `W` dissipated by joint friction up to `t_reached`.
    pub dissipated: f64,
    /// `max |E + W - E(0)|` over every step.
    pub energy_balance_error: f64,
    /// Largest rise of `E` from one step to the next (0 if it never rose).
    pub max_energy_rise: f64,
    /// Tip position at `t_reached`.
    pub tip_end: Vec2,
    /// Tip velocity at `t_reached`.
    pub tip_velocity_end: Vec2,
    /// Continuous maximum of the exact tip speed over the run.
    pub tip_speed_max: f64,
    /// When it happened.
    pub t_tip_speed_max: f64,
    /// The largest pivot force `|F_1|` (force units) and when, `(force,
    /// t)`: the [`PeakForce::Pivot`](crate::model::PeakForce::Pivot) peak
    /// of `peaks` (tracked at every accepted step and refined inside it).
    /// `None` for a model that does not track it (the contact model, the
    /// BEAM).
    pub pivot_force_max: Option<(f64, f64)>,
    /// False when the run's forces (the peaks of `peaks`, the joints' and
    /// the pivot's forces of its samples) are not right to its tolerance
    /// although everything else is (`solve/forces.rs`): gen-alpha stepped
    /// over the axial modes that carry them. True for every other run.
    pub forces_resolved: bool,
    /// The largest value of each force the model tracks
    /// ([`StateView::peak_forces`](crate::StateView::peak_forces): the pivot's force, the largest joint
    /// tension, the floor's normal force), at the start, every accepted
    /// step's end and inside the steps where it turns: a property of the
    /// run, whatever its output samples.
    pub peaks: Vec<crate::model::Peak>,
    /// Wall time of the integration (s).
    pub wall_seconds: f64,
}

impl Summary {
    /// The peak of `force`, if the model tracks it.
    pub fn peak(&self, force: crate::model::PeakForce) -> Option<crate::model::Peak> {
        self.peaks.iter().find(|p| p.force == force).copied()
    }

    /// True if every field is finite. `solve` never reports a run as `ok`
    /// when this is false: such a run ends `diverged`.
    pub fn all_finite(&self) -> bool {
        [
            self.energy_start,
            self.energy_end,
            self.dissipated,
            self.energy_balance_error,
            self.max_energy_rise,
            self.tip_end[0],
            self.tip_end[1],
            self.tip_velocity_end[0],
            self.tip_velocity_end[1],
            self.tip_speed_max,
            self.t_tip_speed_max,
            self.wall_seconds,
            self.pivot_force_max.map_or(0.0, |p| p.0),
            self.pivot_force_max.map_or(0.0, |p| p.1),
        ]
        .iter()
        .all(|v| v.is_finite())
            && self
                .peaks
                .iter()
                .all(|p| p.value.is_finite() && p.t.is_finite() && p.reference.is_finite())
    }
}

/// A finished run: the model as it was at the end, the samples, the
/// summary, the work counters and how it ended. Every accessor of a sample
/// asks the model.
#[derive(Clone, Debug, PartialEq)]
pub struct Trajectory<M = ModelKind> {
    /// The model run (with its pivot's path as the run left it).
    pub model: M,
    /// The pivot `P0` at `t = 0`.
    pub anchor: Vec2,
    pub method: Method,
    pub status: Status,
    /// The requested end time.
    pub t_end: f64,
    /// The last time with a finite state.
    pub t_reached: f64,
    /// When the run failed, if it did.
    pub t_failed: Option<f64>,
    pub stats: Stats,
    pub segments: Vec<Segment>,
    pub summary: Summary,
    /// Sample times (`output_dt` apart, plus the final time).
    pub times: Vec<f64>,
    /// Samples, [`Layout::dim`] numbers each, laid out as the model says.
    pub(super) states: Vec<f64>,
    /// The state at `t_reached`.
    pub final_state: Vec<f64>,
}

/// One recorded sample of a trajectory.
#[derive(Clone, Copy, Debug)]
pub struct Sample<'a> {
    pub t: f64,
    pub angles: &'a [f64],
    pub rates: &'a [f64],
    /// The work accumulator `W` (0 for a model without one).
    pub dissipated: f64,
}

impl<M: Model> Trajectory<M> {
    /// Number of samples.
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// True when no sample was recorded.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Rods (or segments) of the model.
    pub fn links(&self) -> usize {
        self.model.layout().links
    }

    /// Sample `k`.
    pub fn sample(&self, k: usize) -> Sample<'_> {
        let layout = self.model.layout();
        let y = self.state(k);
        Sample {
            t: self.times[k],
            angles: &y[layout.angles],
            rates: &y[layout.rates],
            dissipated: layout.work.map_or(0.0, |i| y[i]),
        }
    }

    /// Every sample, in time order.
    pub fn samples(&self) -> impl Iterator<Item = Sample<'_>> + '_ {
        (0..self.len()).map(|k| self.sample(k))
    }

    /// The state vector of sample `k`.
    pub fn state(&self, k: usize) -> &[f64] {
        let d = self.model.layout().dim;
        &self.states[k * d..(k + 1) * d]
    }

    /// The pivot's position and velocity at sample `k`.
    pub fn pivot_at(&self, k: usize) -> [Vec2; 2] {
        self.model.view().support(self.times[k], self.state(k))
    }

    /// The joints `P_0..P_n` at sample `k`.
    pub fn joints(&self, k: usize) -> Vec<Vec2> {
        self.model.view().joints(self.times[k], self.state(k))
    }

    /// The tip at sample `k`.
    pub fn tip(&self, k: usize) -> Vec2 {
        self.model.view().tip(self.times[k], self.state(k))
    }

    /// The tip's velocity at sample `k` (inertial frame).
    pub fn tip_velocity(&self, k: usize) -> Vec2 {
        self.model.view().tip_velocity(self.times[k], self.state(k))
    }

    /// The energy at sample `k`, the run's own ([`StateView::energy`](crate::StateView::energy)).
    pub fn energy(&self, k: usize) -> f64 {
        self.model.view().energy(self.times[k], self.state(k))
    }

    /// The joint forces `[tension, shear]` at joints `0..=n` at sample `k`.
    pub fn joint_forces(&self, k: usize) -> Vec<Vec2> {
        self.model.view().joint_forces(self.times[k], self.state(k))
    }

    /// The support's force on the first rod at sample `k`.
    pub fn support_force(&self, k: usize) -> Vec2 {
        self.model
            .view()
            .support_force(self.times[k], self.state(k))
    }

    /// The momentum relative to the support at sample `k`.
    pub fn momentum(&self, k: usize) -> Vec2 {
        self.model.view().momentum(self.times[k], self.state(k))
    }

    /// The floor's force on each contact point at sample `k`
    /// ([`StateView::floor_forces`](crate::StateView::floor_forces)), `None` without a floor.
    pub fn floor_forces(&self, k: usize) -> Option<Vec<Vec2>> {
        self.model.view().floor_forces(self.times[k], self.state(k))
    }

    /// The floor's force gathered at each joint at sample `k`, `n + 1` of
    /// them (joint 0 the pivot, joint `n` the tip): joint `j` carries the
    /// contact at rod `j − 1`'s end and at rod `j`'s start, which the
    /// rigid chain's joint would be (physical units; `None` without a
    /// floor). They sum to [`Trajectory::floor_force`].
    pub fn floor_joint_forces(&self, k: usize) -> Option<Vec<Vec2>> {
        let f = self.floor_forces(k)?;
        let mut joints = vec![[0.0, 0.0]; f.len() / 2 + 1];
        for (j, p) in f.iter().enumerate() {
            // Point 2i is rod i's start (joint i), 2i + 1 its end (i + 1).
            let joint = &mut joints[j.div_ceil(2)];
            joint[0] += p[0];
            joint[1] += p[1];
        }
        Some(joints)
    }

    /// The floor's total force on the chain at sample `k` (what a scale
    /// under it reads, upward positive), `None` without a floor.
    pub fn floor_force(&self, k: usize) -> Option<Vec2> {
        let f = self.floor_forces(k)?;
        Some(f.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]))
    }

    /// The weight of what has landed at sample `k`: `g m_i / 2` for each
    /// contact point the floor pushes (each end of rod `i` stands for half
    /// of it; the tip's point also for the tip mass), `None` without a floor.
    pub fn floor_landed_weight(&self, k: usize) -> Option<f64> {
        let f = self.floor_forces(k)?;
        let chain = self.model.chain()?;
        let g = chain.gravity();
        let last = f.len().saturating_sub(1);
        Some(
            f.iter()
                .enumerate()
                .filter(|(_, p)| p[0] != 0.0 || p[1] != 0.0)
                .map(|(j, _)| {
                    let tip = if j == last { chain.tip_mass() } else { 0.0 };
                    g * (0.5 * crate::elastic::rod_mass(chain, j / 2) + tip)
                })
                .sum(),
        )
    }

    /// The length of chain that has landed at sample `k`: `l_i / 2` for
    /// each end of rod `i` at most [`LANDED_HEIGHT`]` l_i` (one rod) above
    /// the floor line or inside it, `None` without a floor: the part of the
    /// chain that lies on the floor or has piled up on it, to about a rod.
    /// It is read off the rods' ends, not off the contact forces: a landed
    /// rod rests at a deflection `m g / 2k` far below the run's tolerance
    /// (3e-9 of `L` on `scenes/cayley-scale.toml`), and on a plastic floor
    /// the landed rods tumble a fraction of a rod above it, so at a sample
    /// most of what has landed is pushed by nothing (the floor pushes at
    /// 37 of the 321 samples of that scene's run, `falling-chain simulate
    /// scenes/cayley-scale.toml --out`). Landed rods thrown higher than a
    /// rod are not counted: on that chain it follows `g t^2 / 2` to 1.5
    /// rods up to `x = L / 2`, and falls behind as the pile is thrown up to
    /// four rods high (0.54 against 0.72 at `t = 1.2`).
    pub fn floor_landed_length(&self, k: usize) -> Option<f64> {
        let (h, a) = self.model.view().floor_line()?;
        let chain = self.model.chain()?;
        let joints = self.joints(k);
        let (sin, cos) = a.sin_cos();
        let above = |p: Vec2| -sin * p[0] + cos * (p[1] - h);
        Some(
            (0..chain.links())
                .map(|i| {
                    let half = crate::elastic::rod_half_length(chain, i);
                    let ends = [joints[i], joints[i + 1]];
                    let down = ends
                        .iter()
                        .filter(|&&p| above(p) <= LANDED_HEIGHT * 2.0 * half)
                        .count();
                    half * down as f64
                })
                .sum(),
        )
    }
}

/// How high above the floor a rod's end still counts as landed, in its
/// rod's lengths ([`Trajectory::floor_landed_length`]): the rods landed on
/// a plastic floor tumble up to 0.9 of a rod above it (measured on the
/// 40-rod Cayley chain of `tests/physics/floor.rs`).
pub const LANDED_HEIGHT: f64 = 1.0;

impl Trajectory<ModelKind> {
    /// The chain run.
    pub fn chain(&self) -> &Chain {
        self.model.chain()
    }
}
