//! The rigid chain on a constraint floor as a [`Model`] (`floor.law =
//! "constraint"`): the rods in maximal coordinates, its joints and the
//! floor as constraints, run by `moreau-jean` (the problem is
//! [`crate::contact`]'s; `docs/model.md`, "The floor as a constraint").
//! The state is the elastic chain's `[theta, w, W, x, y, vx, vy]` (rod
//! centres relative to the start's anchor) and each joint's contact and
//! joint force over the step that ended there ([`Offsets`]); what such a
//! state means is [`ContactView`] (the elastic chain's kinematics, the
//! joints' and the floor's forces read from the state).
//!
//! Its event is the release of the pivot at `0 < t_r < t_end`: the run is
//! cut there and goes on without the pivot's rows.

use super::{Layout, Model, Observed, StateView};
use crate::chain::{check, Chain};
use crate::contact::floor_set::FloorSet;
use crate::contact::{ContactChain, Offsets};
use crate::elastic;
use crate::floor::{self, FloorTerm};
use crate::kinematics::Vec2;
use crate::solve::SolveOptions;
use crate::state::State;
use fc_methods::{AutoPlan, InvalidParameter, Method, Problem};

/// How far (length, relative to the chain's length) a start's joint may
/// lie inside a constraint floor: the rounding of the joints' positions
/// (a start exactly on the floor is on it).
pub const START_TOLERANCE: f64 = 1e-12;

/// The rigid chain on a constraint floor.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactModel {
    view: ContactView,
    /// The pivot has let go of joint 0.
    released: bool,
}

/// What a state of the rigid chain on a constraint floor means: the rods
/// in maximal coordinates from the start's anchor, and the forces of the
/// step that ended there.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactView {
    chain: Chain,
    anchor: Vec2,
    /// The floor in the anchor's frame, once placed by the start.
    floor: Option<FloorTerm>,
}

impl ContactModel {
    /// The model of a validated chain whose floor is a constraint.
    pub fn new(chain: &Chain) -> Self {
        Self {
            view: ContactView {
                chain: chain.clone(),
                anchor: [0.0, 0.0],
                floor: None,
            },
            released: chain.pivot().release == Some(0.0),
        }
    }

    /// The chain.
    pub fn chain_ref(&self) -> &Chain {
        &self.view.chain
    }

    /// The floor's set of rows, as the start placed it (before the start:
    /// none the chain can reach).
    fn floor_set(&self) -> FloorSet {
        let f = self.view.chain.floor();
        FloorSet {
            term: self.view.floor.unwrap_or(FloorTerm {
                line: crate::floor::Line {
                    t: [1.0, 0.0],
                    n: [0.0, 1.0],
                    level: f64::NEG_INFINITY,
                },
                law: crate::floor::Penalty {
                    k: 0.0,
                    c: 0.0,
                    mu: 0.0,
                    inv_vs: 0.0,
                },
            }),
            friction: f.map_or(0.0, |f| f.friction),
            restitution: f.map_or(0.0, |f| f.restitution),
        }
    }
}

impl ContactView {
    fn offsets(&self) -> Offsets {
        Offsets {
            n: self.chain.links(),
        }
    }

    /// True while the pivot holds joint 0 at `t`.
    fn held_at(&self, t: f64) -> bool {
        !elastic::pivot_free_at(&self.chain, t)
    }
}

/// `[theta, w, W, x, y, vx, vy]`, the contact and joint forces; a sample is
/// the state, its time and the joints' positions.
fn contact_layout(chain: &Chain) -> Layout {
    let n = chain.links();
    let o = Offsets { n };
    let numbers = (o.dim() as u64 + 1) + 2 * (n as u64 + 1);
    Layout {
        positions: Some(o.x()..o.vx()),
        velocities: Some(o.vx()..o.contact()),
        ..Layout::angles_rates_work(n, o.dim(), numbers)
    }
}

impl Model for ContactModel {
    fn name(&self) -> &'static str {
        "contact"
    }

    fn chain(&self) -> Option<&Chain> {
        Some(&self.view.chain)
    }

    fn layout(&self) -> Layout {
        contact_layout(&self.view.chain)
    }

    /// `moreau-jean` (or `auto`, which runs it) at a fixed step within the
    /// span and the budget, and the samples' memory.
    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter> {
        options.validate()?;
        check(
            method == Method::MoreauJean || method == Method::Auto,
            "run.method",
            "moreau-jean or auto with floor.law = \"constraint\" (the other methods integrate \
             smooth problems: floor.law = \"penalty\" runs them)",
            method,
        )?;
        options.validate_fixed_step(Method::MoreauJean)?;
        options.validate_samples(&self.layout())
    }

    fn initial_state(&mut self, start: &State) -> Result<Vec<f64>, InvalidParameter> {
        super::check_start(&self.view.chain, start)?;
        self.view.anchor = start.anchor;
        let chain = &self.view.chain;
        let o = self.view.offsets();
        let n = o.n;
        let mut y = vec![0.0; o.dim()];
        let (mut ex, mut ey, mut evx, mut evy) = (0.0, 0.0, 0.0, 0.0);
        for i in 0..n {
            let h = elastic::rod_half_length(chain, i);
            let (s, c) = crate::scalar::sin_cos(start.angles[i]);
            let w = start.rates[i];
            let (x, yy) = (ex + h * c, ey + h * s);
            let (vx, vy) = (evx - h * s * w, evy + h * c * w);
            y[o.theta() + i] = start.angles[i];
            y[o.w() + i] = w;
            y[o.x() + i] = x;
            y[o.x() + n + i] = yy;
            y[o.vx() + i] = vx;
            y[o.vx() + n + i] = vy;
            (ex, ey, evx, evy) = (x + h * c, yy + h * s, vx - h * s * w, vy + h * c * w);
        }
        if let Some(f) = chain.floor() {
            let joints = elastic::joints(chain, [0.0, 0.0], &y);
            let term = match f.height {
                Some(h) => f.term(h, start.anchor),
                None => f.term(0.0, start.anchor).touching(joints.iter().copied()),
            };
            let tolerance = START_TOLERANCE * chain.length();
            let deepest = joints
                .iter()
                .enumerate()
                .map(|(k, p)| (k.min(n - 1), term.penetration(*p)))
                .max_by(|a, b| a.1.total_cmp(&b.1));
            if let Some((rod, depth)) = deepest {
                if depth > tolerance {
                    return Err(floor::constraint_inside_error(rod, depth, tolerance));
                }
            }
            self.view.floor = Some(term);
        }
        Ok(y)
    }

    fn problem(&self) -> Box<dyn Problem + '_> {
        Box::new(ContactChain::new(
            &self.view.chain,
            self.floor_set(),
            !self.released,
        ))
    }

    fn energy_scale(&self) -> f64 {
        self.view.chain.energy_scale()
    }

    /// `moreau-jean` at the run's step.
    fn auto_plan(&self, _rtol: f64) -> AutoPlan {
        AutoPlan {
            explicit: None,
            hand_over_above: f64::INFINITY,
            implicit: Method::MoreauJean,
            implicit_tolerance: 1.0,
            implicit_rho_inf: None,
        }
    }

    fn event_time(&self) -> Option<f64> {
        self.view.chain.pivot().release
    }

    fn at_event(&mut self, _t: f64, _y: &mut [f64]) {
        self.released = true;
    }

    fn view(&self) -> &dyn StateView {
        &self.view
    }
}

impl StateView for ContactView {
    fn observe(&self, t: f64, y: &[f64], f: &[f64], _trig: &mut Vec<(f64, f64)>) -> Observed {
        Observed {
            energy: self.energy(t, y),
            tip_velocity: elastic::tip_velocity(&self.chain, y),
            tip_acceleration: elastic::tip_acceleration(&self.chain, y, f),
        }
    }

    /// `T + V` (and bending): the elastic chain's energy without springs.
    fn energy(&self, t: f64, y: &[f64]) -> f64 {
        elastic::energy_at(&self.chain, t, y)
    }

    fn tip(&self, _t: f64, y: &[f64]) -> Vec2 {
        elastic::tip(&self.chain, self.anchor, y)
    }

    fn tip_velocity(&self, _t: f64, y: &[f64]) -> Vec2 {
        elastic::tip_velocity(&self.chain, y)
    }

    /// The anchor while the pivot holds; once let go, joint 0 (rod 0's
    /// start) and its velocity.
    fn support(&self, t: f64, y: &[f64]) -> [Vec2; 2] {
        if self.held_at(t) {
            return [self.anchor, [0.0, 0.0]];
        }
        let o = self.offsets();
        let n = o.n;
        let h = elastic::rod_half_length(&self.chain, 0);
        let (s, c) = crate::scalar::sin_cos(y[o.theta()]);
        let w = y[o.w()];
        [
            [
                self.anchor[0] + y[o.x()] - h * c,
                self.anchor[1] + y[o.x() + n] - h * s,
            ],
            [y[o.vx()] + h * s * w, y[o.vx() + n] - h * c * w],
        ]
    }

    fn joints(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        elastic::joints_at(&self.chain, t, self.anchor, y)
    }

    /// The joints' forces over the last step, as `[tension, shear]`.
    fn joint_forces(&self, _t: f64, y: &[f64]) -> Vec<Vec2> {
        let o = self.offsets();
        let n = o.n;
        let forces: Vec<Vec2> = (0..=n)
            .map(|k| [y[o.joint() + 2 * k], y[o.joint() + 2 * k + 1]])
            .collect();
        elastic::tension_shear(&y[..n], &forces)
    }

    /// The pivot's force on rod 1 over the last step (zero once let go).
    fn support_force(&self, t: f64, y: &[f64]) -> Vec2 {
        if !self.held_at(t) {
            return [0.0, 0.0];
        }
        let o = self.offsets();
        [y[o.joint()], y[o.joint() + 1]]
    }

    /// The steps' ends only: between them the speed is the step's.
    fn refines_tip_speed(&self) -> bool {
        false
    }

    fn momentum(&self, _t: f64, y: &[f64]) -> Vec2 {
        elastic::momentum(&self.chain, y)
    }

    /// Each joint's contact force over the last step, shared between the
    /// two rod ends that meet there in proportion to their rods' masses
    /// (the penalty floor's points: rod 0's start, rod 0's end, ...): the
    /// sums per joint and in all are the joint's and the floor's.
    fn floor_forces(&self, _t: f64, y: &[f64]) -> Option<Vec<Vec2>> {
        self.floor.as_ref()?;
        let o = self.offsets();
        let n = o.n;
        let at = |k: usize| [y[o.contact() + 2 * k], y[o.contact() + 2 * k + 1]];
        let mut out = vec![[0.0, 0.0]; 2 * n];
        for k in 0..=n {
            let f = at(k);
            match (k.checked_sub(1), (k < n).then_some(k)) {
                (Some(a), Some(b)) => {
                    let (ma, mb) = (
                        elastic::rod_mass(&self.chain, a),
                        elastic::rod_mass(&self.chain, b),
                    );
                    let share = ma / (ma + mb);
                    out[2 * a + 1] = [share * f[0], share * f[1]];
                    out[2 * b] = [(1.0 - share) * f[0], (1.0 - share) * f[1]];
                }
                (None, Some(b)) => out[2 * b] = f,
                (Some(a), None) => out[2 * a + 1] = f,
                (None, None) => {}
            }
        }
        Some(out)
    }

    fn floor_line(&self) -> Option<(f64, f64)> {
        let (term, f) = (self.floor.as_ref()?, self.chain.floor()?);
        Some((term.height(self.anchor), f.angle))
    }
}
