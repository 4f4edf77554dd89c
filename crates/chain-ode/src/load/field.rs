//! A uniform field: gravity, the one load every mass feels.
//!
//! The field is an acceleration `a` per unit mass (`(0, -g)`; `g/l` per
//! time squared in rod units). Rod `i` feels `m_i a` at its centre and the
//! tip mass `M_t a`; its potential is `-sum m a . x` over the masses, the
//! chain's weight times the height of its centre of mass. Every path
//! applies it to the masses it holds in its own arithmetic (the recursion
//! to each rod and to the tip mass's articulated body, the banded DAE in
//! its first rod's row, where a uniform field does not cancel, the elastic
//! chain as an acceleration of every rod), so that [`Load::add_to_rod`]
//! here serves the dense reference alone.

use super::{Kinematics, Load, Reads, RodForce, Stiffness, Units};
use crate::chain::{Chain, ChainParams};
use crate::scalar::Scalar;

/// The field's acceleration in a path's units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Field {
    /// `a = (a_x, a_y)`: `(0, -g)`, or `(0, -g/l)` in rod units.
    pub acceleration: [f64; 2],
}

impl Load for Field {
    const NAME: &'static str = "gravity";
    const KEY: &'static str = "chain.gravity";

    fn is_on(params: &ChainParams) -> bool {
        params.gravity != 0.0
    }

    fn switch_off(params: &mut ChainParams) {
        params.gravity = 0.0;
    }

    fn switch_on(params: &mut ChainParams) {
        params.gravity = 1.0;
    }

    /// Always there (at zero strength without gravity).
    fn of(chain: &Chain, units: Units) -> Option<Self> {
        let ay = match units {
            Units::Rod => -chain.gravity_rate(),
            Units::Physical => -chain.gravity(),
        };
        Some(Self {
            acceleration: [0.0, ay],
        })
    }

    fn reads(&self) -> Reads {
        Reads::default()
    }

    /// `m_i a` at rod `i`'s centre ([`Kinematics::mass`]); no power: the
    /// field is conservative, its energy the masses' potential.
    #[inline(always)]
    fn add_to_rod<T: Scalar, K: Kinematics<T>>(&self, i: usize, k: &K, out: &mut RodForce<T>) {
        let m = k.mass(i);
        out.force[0] += T::cst(m * self.acceleration[0]);
        out.force[1] += T::cst(m * self.acceleration[1]);
    }

    fn stiffness(&self, _chain: &Chain) -> Stiffness {
        Stiffness::None
    }
}

impl Field {
    /// The field of `chain` in `units` (always present).
    pub fn new(chain: &Chain, units: Units) -> Self {
        match <Self as Load>::of(chain, units) {
            Some(f) => f,
            None => Self {
                acceleration: [0.0, 0.0],
            },
        }
    }

    /// Its vertical component `a_y` (`-g`).
    #[inline(always)]
    pub fn y(&self) -> f64 {
        self.acceleration[1]
    }
}
