//! The floor as a contact set: every joint of the rigid chain (the pivot
//! end, the joints between rods, the tip) against the floor's line, a
//! unilateral normal row with Newton's restitution and a Coulomb tangent
//! row (`docs/model.md`, "The floor as a constraint").
//!
//! A rod is straight, so its lowest point is an end, and every rod end is
//! a joint: the `n + 1` joints are the chain's contact points. (The
//! penalty floor has `2 n`, one per rod end, because its rods' ends part
//! at a joint; here they are one point, and two rows on it would be
//! redundant.)

use fc_methods::{Row, RowKind, MAX_BODY};

use super::rods::BODY;
use super::ContactSet;
use crate::floor::FloorTerm;
use crate::kinematics::Vec2;

/// The floor's rows: its line (in the anchor's frame), its friction and
/// its restitution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloorSet {
    pub term: FloorTerm,
    /// `mu`.
    pub friction: f64,
    /// `e`.
    pub restitution: f64,
}

impl ContactSet for FloorSet {
    fn rows_per_joint(&self) -> usize {
        2
    }

    /// The normal row (the gap `n . p − level`, positive above the floor)
    /// and, with friction, the tangent row.
    fn joint_rows(&self, p: Vec2, jac: &[[f64; BODY]; 2], half: usize, out: &mut [Row]) {
        let (n, t) = (self.term.line.n, self.term.line.t);
        let mut normal = Row {
            kind: RowKind::Normal {
                restitution: self.restitution,
            },
            jac: [0.0; 2 * MAX_BODY],
            gap: -self.term.penetration(p),
        };
        let mut tangent = Row {
            kind: RowKind::Tangent {
                friction: self.friction,
            },
            ..normal
        };
        let at = half * MAX_BODY;
        for (c, (dx, dy)) in jac[0].iter().zip(&jac[1]).enumerate() {
            normal.jac[at + c] = n[0] * dx + n[1] * dy;
            tangent.jac[at + c] = t[0] * dx + t[1] * dy;
        }
        out[0] = normal;
        out[1] = if self.friction > 0.0 {
            tangent
        } else {
            Row::OFF
        };
    }

    fn force(&self, impulses: &[f64], h: f64) -> Vec2 {
        let (n, t) = (self.term.line.n, self.term.line.t);
        let (pn, pt) = (impulses[0], impulses[1]);
        [(pn * n[0] + pt * t[0]) / h, (pn * n[1] + pt * t[1]) / h]
    }
}
