//! Joint friction: a viscous torque `r (w_{i+1} - w_i)` in every joint
//! between two rods (the pivot has none), `chain.damping = r`.
//!
//! Rod `i` feels `r D_i(w)`, `D_i(w) = (w_{i-1} - w_i) + (w_{i+1} - w_i)`
//! ([`damping_stencil`]), and the joints draw the power
//! `2R = r sum_{i>=1} (w_i - w_{i-1})^2` from the chain (Rayleigh's
//! function `R`). Its stiffness is the decay rate of the fastest rod,
//! `r / min_i (m_i l_i^2)` ([`Chain::stiffest_damping_rate`]): `auto` runs
//! BDF from the start past the rigid chain's crossover.

use super::{Kinematics, Load, Reads, RodForce, Stiffness, Units};
use crate::chain::{Chain, ChainParams};
use crate::dynamics::damping_stencil;
use crate::scalar::Scalar;

/// Joint friction in a path's units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// The torque's coefficient: `r`, or `gamma = r / (m l^2)` in rod units.
    pub rate: f64,
    /// `r` (physical units), for the power.
    pub r: f64,
}

impl Load for Friction {
    const NAME: &'static str = "joint friction";
    const KEY: &'static str = "chain.damping";

    fn is_on(params: &ChainParams) -> bool {
        params.damping > 0.0
    }

    fn switch_off(params: &mut ChainParams) {
        params.damping = 0.0;
    }

    fn switch_on(params: &mut ChainParams) {
        params.damping = 0.01;
    }

    /// Always there: at `r = 0` its terms are exact zeros, and the banded
    /// DAE's Jacobian keeps one pattern for every chain.
    fn of(chain: &Chain, units: Units) -> Option<Self> {
        let rate = match units {
            Units::Rod => chain.damping_rate(),
            Units::Physical => chain.damping(),
        };
        Some(Self {
            rate,
            r: chain.damping(),
        })
    }

    fn reads(&self) -> Reads {
        Reads {
            rates: true,
            ..Reads::default()
        }
    }

    #[inline(always)]
    fn add_to_rod<T: Scalar, K: Kinematics<T>>(&self, i: usize, k: &K, out: &mut RodForce<T>) {
        out.torque += damping_stencil(k.rates(), i) * (self.rate * k.torque_unit(i));
    }

    /// `2R = r sum (w_i - w_{i-1})^2`.
    #[inline(always)]
    fn joint_power<T: Scalar, K: Kinematics<T>>(&self, k: &K) -> Option<T> {
        let w = k.rates();
        let mut sum = T::cst(0.0);
        for i in 1..w.len() {
            let dw = w[i] - w[i - 1];
            sum += dw * dw;
        }
        Some(sum * self.r)
    }

    fn stiffness(&self, chain: &Chain) -> Stiffness {
        Stiffness::Rate(chain.stiffest_damping_rate())
    }
}
