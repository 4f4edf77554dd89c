//! The floor's contact and friction as a load (`[floor]`,
//! `docs/model.md`, "The floor").
//!
//! A contact set is the chain's points that may touch (every rod's two
//! ends, [`Kinematics::ends`]: a straight rod's penetration is affine along
//! it, so its deepest point is an end) against an obstacle's geometry (the
//! floor's [`Line`]); the penalty law ([`Penalty`]: Hunt–Crossley and
//! regularised Coulomb friction) turns each point's penetration, its rate
//! and its slip into a force. The two ends' forces are rod `i`'s force at
//! its centre and torque about it, their lost power its share of `W`, the
//! springs' `k delta^2 / 2` its potential. The force on rod `i` reads rod
//! `i`'s coordinates alone, so the elastic chain's Jacobian keeps its band.
//! The floor needs the elastic model (a rigid chain on a floor runs it at
//! `EA = 1e4 M g`: [`crate::Chain::new`]), and the model places the floor
//! for its start ([`crate::ElasticModel`]), so [`Load::of`] here gives
//! none: the model sets the placed one ([`FloorContact::placed`]).

use super::{Kinematics, Load, Reads, RodForce, Stiffness, Units};
use crate::chain::{Chain, ChainParams};
use crate::floor::{FloorTerm, Line, Penalty};
use crate::scalar::Scalar;

/// The floor's contact set and law, placed in the anchor's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FloorContact {
    pub term: FloorTerm,
}

impl FloorContact {
    /// The contact of the floor `term` as the model placed it.
    pub fn placed(term: FloorTerm) -> Self {
        Self { term }
    }

    /// The obstacle's geometry.
    pub fn line(&self) -> &Line {
        &self.term.line
    }

    /// The penalty law.
    pub fn law(&self) -> &Penalty {
        &self.term.law
    }
}

impl Load for FloorContact {
    const NAME: &'static str = "floor contact";
    /// Any `[floor]` key makes a floor; a refusal names its height.
    const KEY: &'static str = "floor.height";

    fn is_on(params: &ChainParams) -> bool {
        params.floor.is_some()
    }

    fn switch_off(params: &mut ChainParams) {
        params.floor = None;
    }

    /// A floor well below the report's chain (`k = 1e4 m g / l`).
    fn switch_on(params: &mut ChainParams) {
        let l = params.length / params.links.max(1) as f64;
        params.floor = Some(crate::Floor {
            height: Some(-2.0 * params.length),
            angle: 0.0,
            stiffness: 1e4 * params.mass * params.gravity.max(1.0) / l,
            damping: 0.0,
            friction: 0.0,
            slip_speed: 1e-3,
            law: crate::floor::FloorLaw::Penalty,
            restitution: 0.0,
        });
    }

    /// None: the model places the floor for its start.
    fn of(_chain: &Chain, _units: Units) -> Option<Self> {
        None
    }

    fn reads(&self) -> Reads {
        Reads {
            centres: true,
            ..Reads::default()
        }
    }

    #[inline(always)]
    fn add_to_rod<T: Scalar, K: Kinematics<T>>(&self, i: usize, k: &K, out: &mut RodForce<T>) {
        let (s, c) = k.sin_cos(i);
        let h = k.half_length(i);
        let [gx, gy, gt, gw] = self.term.on_ends(k.ends(i), (c * h, s * h));
        out.force = [out.force[0] + gx, out.force[1] + gy];
        out.torque += gt;
        out.power += gw;
    }

    /// The springs' `k delta^2 / 2` at every rod end.
    fn potential<K: Kinematics<f64>>(&self, k: &K) -> Option<f64> {
        let n = k.angles().len();
        let mut e = 0.0;
        for i in 0..n {
            for [p, _] in k.ends(i) {
                e += self.term.energy(p);
            }
        }
        Some(e)
    }

    /// A contact point's frequency on a rod: `sqrt(2 k / m)` for the
    /// lightest rod (two ends, half the rod's mass each).
    fn stiffness(&self, chain: &Chain) -> Stiffness {
        let m = chain.rods().map_or(1.0, |r| {
            r.mass.iter().copied().fold(f64::INFINITY, f64::min)
        }) * chain.mass();
        Stiffness::Frequency((2.0 * self.term.law.k / m).sqrt())
    }
}
