//! The floor: a straight line the elastic chain falls onto, with penalty
//! contact at every rod's two ends (`docs/model.md`, "The floor").
//!
//! The floor is the line through `(0, h)` (scene coordinates) at the angle
//! `a` from the horizontal, with unit tangent `t = (cos a, sin a)` and unit
//! normal `n = (-sin a, cos a)` pointing out of it. A point `p` is inside
//! by the penetration `delta = n . ((0, h) - p)` (length; > 0 inside), at
//! the rate `delta' = -n . p'`. Each contact point (the two ends
//! `c_i -+ h_i u_i` of every rod: a straight rod's penetration is affine
//! along it, so its deepest point is an end) feels, while `delta > 0`,
//!
//! ```text
//! N = max(0, k delta (1 + c delta'))           normal force (never pulls)
//! T = -mu N tanh(v_t / v_s),  v_t = t . p'     friction (regularised Coulomb)
//! ```
//!
//! (`k` force/length, `c` time/length, `mu` dimensionless, `v_s` a speed):
//! the Hunt–Crossley law with exponent 1, zero at touch-down. Its stored
//! energy `U = k delta^2 / 2` is part of the energy `E`; the rest of its
//! power goes to the work `W`:
//! `W' = N delta' - k delta delta' + mu N tanh(v_t / v_s) v_t >= 0`
//! (the first two `k c delta delta'^2` unless `N` is clamped at 0).
//!
//! The force on rod `i` depends on rod `i`'s coordinates alone, so the
//! elastic chain's Jacobian keeps its band. Positions in the state are
//! relative to the pivot's anchor `P0`; a [`FloorTerm`] holds the floor in
//! that frame.

use fc_methods::InvalidParameter;

use crate::chain::{check, number_text};
use crate::kinematics::Vec2;
use crate::scalar::Scalar;

/// The largest floor angle `|a|` (rad).
pub const MAX_FLOOR_ANGLE: f64 = 1.5;

/// How the floor pushes (`floor.law`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FloorLaw {
    /// A stiff spring-damper at each rod end (Hunt–Crossley, this module)
    /// on the elastic chain: the floor of issue 36.
    Penalty,
    /// A unilateral constraint at each joint of the rigid chain, with
    /// Newton's restitution and Coulomb's friction, stepped over by
    /// `moreau-jean` (`crate::contact`; `docs/model.md`, "The floor as a
    /// constraint").
    Constraint,
}

impl FloorLaw {
    /// Both laws, as scenes name them.
    pub const ALL: [FloorLaw; 2] = [FloorLaw::Penalty, FloorLaw::Constraint];

    /// The name in scenes: `"penalty"`, `"constraint"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Penalty => "penalty",
            Self::Constraint => "constraint",
        }
    }
}

/// A floor as the scene gives it (the `[floor]` keys), in the scene's units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Floor {
    /// Height `h` of the floor line at `x = 0` (length, scene coordinates),
    /// or `None`: the floor touches the start's lowest rod end (placed by
    /// the model from the start, [`FloorTerm::touching`]).
    pub height: Option<f64>,
    /// Its angle `a` from the horizontal (rad; positive rises to +x).
    pub angle: f64,
    /// Normal stiffness `k` of each contact point (force / length).
    pub stiffness: f64,
    /// Hunt–Crossley damping `c` (time / length): the normal force is
    /// `k delta (1 + c delta')`; `c v >> 1` at an impact speed `v` makes the
    /// impact plastic.
    pub damping: f64,
    /// Coulomb friction coefficient `mu` (>= 0).
    pub friction: f64,
    /// The regularisation speed `v_s` of the friction (> 0): below it the
    /// friction grows linearly with the slip speed.
    pub slip_speed: f64,
    /// How the floor pushes ([`FloorLaw`]): `stiffness`, `damping` and
    /// `slip_speed` are the penalty's, `restitution` the constraint's.
    pub law: FloorLaw,
    /// The constraint's coefficient of restitution `e` in `[0, 1]` (0:
    /// plastic): Newton's law on a contact's normal velocity,
    /// `u⁺ = −e u⁻` at an impact.
    pub restitution: f64,
}

impl Floor {
    /// Checks every field; the error names the first key out of range.
    pub fn validate(&self) -> Result<(), InvalidParameter> {
        let fin = |x: f64| x.is_finite();
        if let Some(h) = self.height {
            check(
                fin(h) && h.abs() <= 1e9,
                "floor.height",
                "a number in -1e9..=1e9",
                h,
            )?;
        }
        check(
            fin(self.angle) && self.angle.abs() <= MAX_FLOOR_ANGLE,
            "floor.angle",
            "a number in -1.5..=1.5 (rad)",
            self.angle,
        )?;
        check(
            fin(self.stiffness) && self.stiffness > 0.0 && self.stiffness <= 1e15,
            "floor.stiffness",
            "a finite number in (0, 1e15]",
            self.stiffness,
        )?;
        check(
            fin(self.damping) && (0.0..=1e12).contains(&self.damping),
            "floor.damping",
            "a finite number in 0..=1e12",
            self.damping,
        )?;
        check(
            fin(self.friction) && (0.0..=100.0).contains(&self.friction),
            "floor.friction",
            "a finite number in 0..=100",
            self.friction,
        )?;
        check(
            fin(self.slip_speed) && self.slip_speed > 0.0 && self.slip_speed <= 1e6,
            "floor.slip_speed",
            "a finite number in (0, 1e6]",
            self.slip_speed,
        )?;
        check(
            fin(self.restitution) && (0.0..=1.0).contains(&self.restitution),
            "floor.restitution",
            "a number in [0, 1]",
            self.restitution,
        )?;
        check(
            self.law == FloorLaw::Constraint || self.restitution == 0.0,
            "floor.restitution",
            "0 with floor.law = \"penalty\" (its impacts' restitution is set by floor.damping); \
             another value with floor.law = \"constraint\"",
            self.restitution,
        )
    }

    /// The floor at the height `height` in the frame of the anchor `P0`
    /// (state positions are relative to it).
    pub fn term(&self, height: f64, anchor: Vec2) -> FloorTerm {
        let (s, c) = self.angle.sin_cos();
        let n = [-s, c];
        FloorTerm {
            line: Line {
                t: [c, s],
                n,
                level: n[0] * (0.0 - anchor[0]) + n[1] * (height - anchor[1]),
            },
            law: Penalty {
                k: self.stiffness,
                c: self.damping,
                mu: self.friction,
                inv_vs: 1.0 / self.slip_speed,
            },
        }
    }
}

/// The floor's geometry in the anchor's frame: the line a point may not
/// cross. What a contact solver reads of the obstacle (the gap of a point,
/// the directions of its normal and tangential motion), apart from any
/// force law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    /// Unit tangent `t`.
    pub t: Vec2,
    /// Unit normal `n` (out of the floor).
    pub n: Vec2,
    /// `n . ((0, h) - P0)`: a point `p` (relative to `P0`) is inside by
    /// `delta = level - n . p`.
    pub level: f64,
}

impl Line {
    /// The penetration `delta = level - n . p` of the point `p` (> 0 inside).
    #[inline(always)]
    pub fn gap<T: Scalar>(&self, p: [T; 2]) -> T {
        T::cst(self.level) - (p[0] * self.n[0] + p[1] * self.n[1])
    }

    /// The rate of penetration `delta' = -n . v` of a point moving at `v`.
    #[inline(always)]
    pub fn gap_rate<T: Scalar>(&self, v: [T; 2]) -> T {
        -(v[0] * self.n[0] + v[1] * self.n[1])
    }

    /// The slip speed `t . v` along the floor.
    #[inline(always)]
    pub fn slip<T: Scalar>(&self, v: [T; 2]) -> T {
        v[0] * self.t[0] + v[1] * self.t[1]
    }
}

/// The penalty law of a contact point: the Hunt–Crossley normal force and
/// regularised Coulomb friction of the module doc, from the penetration,
/// its rate and the slip speed. A time-stepping contact method would put a
/// complementarity condition on the same [`Line`] in its place.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Penalty {
    /// `k`.
    pub k: f64,
    /// `c`.
    pub c: f64,
    /// `mu`.
    pub mu: f64,
    /// `1 / v_s`.
    pub inv_vs: f64,
}

/// What the law gives one point inside: the normal push `N >= 0`, the
/// tangential force `T`, and the power lost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reaction<T> {
    pub normal: T,
    pub tangential: T,
    pub dissipation: T,
}

impl Penalty {
    /// The reaction at the penetration `delta > 0`, its rate `rate` and the
    /// slip speed `slip` (evaluated lazily: only when the point pushes).
    #[inline(always)]
    pub fn reaction<T: Scalar>(&self, delta: T, rate: T, slip: impl FnOnce() -> T) -> Reaction<T> {
        let zero = T::cst(0.0);
        let spring = delta * self.k;
        let push = spring + spring * rate * self.c;
        if push.value() <= 0.0 {
            // Clamped: the floor does not pull. The spring's energy leaves.
            return Reaction {
                normal: zero,
                tangential: zero,
                dissipation: -(spring * rate),
            };
        }
        let slip = slip();
        let x = slip.value() * self.inv_vs;
        let th = x.tanh();
        let tanh = (slip * self.inv_vs).chain_rule(th, 1.0 - th * th);
        let tangential = -(push * tanh * self.mu);
        Reaction {
            normal: push,
            tangential,
            dissipation: push * rate - spring * rate - tangential * slip,
        }
    }
}

/// The floor as the right-hand side reads it (positions relative to `P0`):
/// its line and its law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloorTerm {
    pub line: Line,
    pub law: Penalty,
}

/// What one contact point receives: its force, and the power it loses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contact<T> {
    /// Force on the point (x, y).
    pub force: [T; 2],
    /// Power dissipated, `W'` (>= 0).
    pub dissipation: T,
}

impl FloorTerm {
    /// This floor moved along its normal to touch the lowest of the points
    /// `points` (relative to `P0`): `level = min n . p`.
    pub fn touching(mut self, points: impl Iterator<Item = Vec2>) -> Self {
        let n = self.line.n;
        self.line.level = points
            .map(|p| n[0] * p[0] + n[1] * p[1])
            .fold(f64::INFINITY, f64::min);
        self
    }

    /// The height `h` of this floor at `x = 0` in scene coordinates, for
    /// the anchor `P0`: `n . ((0, h) - P0) = level`.
    pub fn height(&self, anchor: Vec2) -> f64 {
        let Line { n, level, .. } = self.line;
        (level + n[0] * anchor[0] + n[1] * anchor[1]) / n[1]
    }

    /// The penetration `delta` of the point `p` (relative to `P0`).
    #[inline(always)]
    pub fn penetration(&self, p: Vec2) -> f64 {
        self.line.gap(p)
    }

    /// The contact at the point `p` moving at `v` (relative to `P0`); zero
    /// when the point is out of the floor: the line's gap, the law's
    /// reaction, along the line's normal and tangent.
    #[inline(always)]
    pub fn contact<T: Scalar>(&self, p: [T; 2], v: [T; 2]) -> Contact<T> {
        let zero = T::cst(0.0);
        let delta = self.line.gap(p);
        if delta.value() <= 0.0 {
            return Contact {
                force: [zero, zero],
                dissipation: zero,
            };
        }
        let r = self
            .law
            .reaction(delta, self.line.gap_rate(v), || self.line.slip(v));
        let Line { t, n, .. } = self.line;
        Contact {
            force: [
                r.normal * n[0] + r.tangential * t[0],
                r.normal * n[1] + r.tangential * t[1],
            ],
            dissipation: r.dissipation,
        }
    }

    /// Its stored energy at the point `p`: `k delta^2 / 2` inside, else 0.
    #[inline(always)]
    pub fn energy(&self, p: Vec2) -> f64 {
        let d = self.penetration(p);
        if d > 0.0 {
            0.5 * self.law.k * d * d
        } else {
            0.0
        }
    }

    /// The floor's force and torque on a rod from its two ends `ends`
    /// (start `c - h u`, end `c + h u`, each `[position, velocity]`, the
    /// rod's `(hc, hs) = h (cos, sin)`): `[F_x, F_y, torque about c, W']`.
    #[inline(always)]
    pub fn on_ends<T: Scalar>(&self, ends: [[[T; 2]; 2]; 2], (hc, hs): (T, T)) -> [T; 4] {
        let [[pa, va], [pb, vb]] = ends;
        let a = self.contact(pa, va);
        let b = self.contact(pb, vb);
        let fx = a.force[0] + b.force[0];
        let fy = a.force[1] + b.force[1];
        // r x F with r = -+ h u.
        let torque = (hc * (b.force[1] - a.force[1])) - (hs * (b.force[0] - a.force[0]));
        [fx, fy, torque, a.dissipation + b.dissipation]
    }
}

/// The floor's line in scene coordinates, for a drawing: the two points
/// `(x0, h + x0 tan a)` and `(x1, h + x1 tan a)`.
/// `height` is the floor's at `x = 0` ([`FloorTerm::height`]).
pub fn line(floor: &Floor, height: f64, x0: f64, x1: f64) -> [Vec2; 2] {
    let slope = floor.angle.tan();
    [[x0, height + x0 * slope], [x1, height + x1 * slope]]
}

/// The most a start may lie inside the floor, summed over every contact
/// point inside it: the static deflection of one point carrying the whole
/// chain, `M g / k` (so the start's contact forces `k sum delta` hold at
/// most the chain's weight, and its stored energy is at most
/// `(M g)^2 / 2k`), and never more than [`START_OVERLAP_OF_LENGTH`] of the
/// chain's length `L` (a soft floor far above the chain, `M g / k` of
/// 10^9, is a mistake, not a start: its spring would throw the chain).
pub fn start_tolerance(floor: &Floor, weight: f64, length: f64) -> f64 {
    (weight / floor.stiffness).min(START_OVERLAP_OF_LENGTH * length)
}

/// The largest start overlap as a fraction of the chain's length
/// ([`start_tolerance`]).
pub const START_OVERLAP_OF_LENGTH: f64 = 0.01;

/// The one-line reason a start is refused: its contact points lie `total`
/// inside the floor in all, `count` of them, the deepest at rod `rod`.
pub(crate) fn inside_error(overlap: Overlap, tolerance: f64) -> InvalidParameter {
    InvalidParameter {
        field: "floor.height",
        accepted: format!(
            "a floor below the chain's start (it may touch it, within {} summed over every \
             contact point inside it: the static deflection of the whole weight on one point, \
             at most 1% of the chain's length)",
            number_text(tolerance)
        )
        .into(),
        got: format!(
            "{} inside at {} point{} (deepest: rod {})",
            number_text(overlap.total),
            overlap.count,
            if overlap.count == 1 { "" } else { "s" },
            overlap.rod + 1
        ),
    }
}

/// The one-line reason a start is refused by the constraint floor (a
/// rigid joint cannot lie inside it by more than the rounding `tolerance`,
/// `1e-12 L`): its deepest joint, of rod `rod`, lies `depth` inside.
pub(crate) fn constraint_inside_error(rod: usize, depth: f64, tolerance: f64) -> InvalidParameter {
    InvalidParameter {
        field: "floor.height",
        accepted: format!(
            "a floor below the chain's start (a constraint floor may touch it, within the \
             rounding {} = 1e-12 of the chain's length)",
            number_text(tolerance)
        )
        .into(),
        got: format!(
            "the start inside the floor by {} at rod {}",
            number_text(depth),
            rod + 1
        ),
    }
}

/// How far a start lies inside the floor ([`overlap`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overlap {
    /// The sum of the depths of the contact points inside.
    pub total: f64,
    /// How many points are inside.
    pub count: usize,
    /// The deepest point's depth and its rod.
    pub deepest: f64,
    pub rod: usize,
}

/// The contact points of the elastic state `y` (relative to `P0`), in
/// order: rod 0's start, rod 0's end, rod 1's start, ..., with their
/// velocities; `2 n` of them.
pub fn points(chain: &crate::Chain, y: &[f64]) -> Vec<[Vec2; 2]> {
    let n = chain.links();
    let (ox, oy, ovx, ovy) = (2 * n + 1, 3 * n + 1, 4 * n + 1, 5 * n + 1);
    let mut out = Vec::with_capacity(2 * n);
    for i in 0..n {
        let h = crate::elastic::rod_half_length(chain, i);
        let (s, c) = crate::scalar::sin_cos(y[i]);
        let w = y[n + i];
        let (cx, cy, vx, vy) = (y[ox + i], y[oy + i], y[ovx + i], y[ovy + i]);
        out.push([[cx - h * c, cy - h * s], [vx + h * s * w, vy - h * c * w]]);
        out.push([[cx + h * c, cy + h * s], [vx - h * s * w, vy + h * c * w]]);
    }
    out
}

/// The floor's force on each contact point of [`points`] (physical units).
pub fn point_forces(chain: &crate::Chain, term: &FloorTerm, y: &[f64]) -> Vec<Vec2> {
    points(chain, y)
        .into_iter()
        .map(|[p, v]| term.contact(p, v).force)
        .collect()
}

/// The floor's total normal force on the elastic state `y` (the sum of
/// its contact points' pushes `N`, along the floor's normal) and the
/// weight of the points it pushes, `g sum m_i / 2` (each end of rod `i`
/// stands for half of it; the tip's point also for the tip mass): one
/// pass, no allocation (a run's peak tracking calls it at every step).
pub fn normal_and_landed(chain: &crate::Chain, term: &FloorTerm, y: &[f64]) -> [f64; 2] {
    let n = chain.links();
    let (ox, oy, ovx, ovy) = (2 * n + 1, 3 * n + 1, 4 * n + 1, 5 * n + 1);
    let g = chain.gravity();
    let (mut normal, mut landed) = (0.0, 0.0);
    for i in 0..n {
        let h = crate::elastic::rod_half_length(chain, i);
        let (s, c) = crate::scalar::sin_cos(y[i]);
        let w = y[n + i];
        let (cx, cy, vx, vy) = (y[ox + i], y[oy + i], y[ovx + i], y[ovy + i]);
        let ends = [
            ([cx - h * c, cy - h * s], [vx + h * s * w, vy - h * c * w]),
            ([cx + h * c, cy + h * s], [vx - h * s * w, vy + h * c * w]),
        ];
        for (k, (p, v)) in ends.into_iter().enumerate() {
            let f = term.contact(p, v).force;
            if f[0] != 0.0 || f[1] != 0.0 {
                normal += term.line.n[0] * f[0] + term.line.n[1] * f[1];
                let tip = if i + 1 == n && k == 1 {
                    chain.tip_mass()
                } else {
                    0.0
                };
                landed += g * (0.5 * crate::elastic::rod_mass(chain, i) + tip);
            }
        }
    }
    [normal, landed]
}

/// The floor's total force on the chain, the sum of [`point_forces`]: what
/// a scale under the chain reads (with the opposite sign).
pub fn total_force(chain: &crate::Chain, term: &FloorTerm, y: &[f64]) -> Vec2 {
    point_forces(chain, term, y)
        .iter()
        .fold([0.0, 0.0], |a, f| [a[0] + f[0], a[1] + f[1]])
}

/// The floor's stored energy `sum k delta^2 / 2` in the elastic state `y`.
pub fn stored_energy(chain: &crate::Chain, term: &FloorTerm, y: &[f64]) -> f64 {
    points(chain, y).iter().map(|[p, _]| term.energy(*p)).sum()
}

/// How far the start `y` lies inside the floor, over every contact point
/// (`None` when none is inside).
pub fn overlap(chain: &crate::Chain, term: &FloorTerm, y: &[f64]) -> Option<Overlap> {
    let mut o: Option<Overlap> = None;
    for (j, [p, _]) in points(chain, y).iter().enumerate() {
        let d = term.penetration(*p);
        if d > 0.0 {
            let o = o.get_or_insert(Overlap {
                total: 0.0,
                count: 0,
                deepest: d,
                rod: j / 2,
            });
            o.total += d;
            o.count += 1;
            if d > o.deepest {
                o.deepest = d;
                o.rod = j / 2;
            }
        }
    }
    o
}
