//! Air drag: a quadratic drag on every rod, `chain.air_drag = c` (force per
//! length per speed squared, mass per length squared).
//!
//! Rod `i`, of length `l_i`, feels `F_i = -c l_i |v_i| v_i` at its centre,
//! `v_i` its centre's velocity in the inertial frame (the rod's turning
//! about its centre is not counted), and loses the power
//! `c l_i |v_i|^3` to the air. It reads the centres, so the rigid chain's
//! paths compute them (an O(n) pass, only when the drag is on) and its
//! banded DAE keeps the derivatives within the band. A chain falling flat
//! reaches the speed `sqrt(m_i g / (c l_i))` (`docs/model.md`, "Air drag").

use super::{Kinematics, Load, Reads, RodForce, Stiffness, Units};
use crate::chain::{check, Chain, ChainParams};
use crate::scalar::Scalar;
use fc_methods::InvalidParameter;

/// The largest `chain.air_drag`.
pub const MAX_AIR_DRAG: f64 = 1e9;

/// The drag in a path's units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Drag {
    /// `c`, or `c l^2 / m` in rod units: the force per length and speed squared.
    force: f64,
    /// `c`, or `c l^4`: the power per length and speed cubed, in physical units.
    power: f64,
}

impl Load for Drag {
    const NAME: &'static str = "air drag";
    const KEY: &'static str = "chain.air_drag";
    const COEFFICIENT: bool = true;

    fn is_on(params: &ChainParams) -> bool {
        params.coefficients.get(Self::KEY) > 0.0
    }

    fn switch_off(params: &mut ChainParams) {
        params.coefficients.set(Self::KEY, 0.0);
    }

    fn switch_on(params: &mut ChainParams) {
        params.coefficients.set(Self::KEY, 0.05);
    }

    fn validate(params: &ChainParams) -> Result<(), InvalidParameter> {
        let c = params.coefficients.get(Self::KEY);
        check(
            c.is_finite() && (0.0..=MAX_AIR_DRAG).contains(&c),
            Self::KEY,
            "a finite number in 0..=1e9",
            c,
        )
    }

    fn of(chain: &Chain, units: Units) -> Option<Self> {
        let c = chain.params().coefficients.get(Self::KEY);
        let (m, l) = (chain.mass(), chain.rod_length());
        (c > 0.0).then(|| match units {
            Units::Rod => Self {
                force: c * l * l / m,
                power: c * l.powi(4),
            },
            Units::Physical => Self { force: c, power: c },
        })
    }

    fn reads(&self) -> Reads {
        Reads {
            centres: true,
            ..Reads::default()
        }
    }

    #[inline(always)]
    fn add_to_rod<T: Scalar, K: Kinematics<T>>(&self, i: usize, k: &K, out: &mut RodForce<T>) {
        let [vx, vy] = k.centre_velocity(i);
        let v2 = vx * vx + vy * vy;
        // |v|, its derivative 0 at rest (the limit of |v| v's).
        let speed = if v2.value() > 0.0 {
            v2.sqrt()
        } else {
            T::cst(0.0)
        };
        let len = 2.0 * k.half_length(i);
        let drag = speed * (self.force * len);
        out.force = [out.force[0] - drag * vx, out.force[1] - drag * vy];
        out.power += speed * v2 * (self.power * len);
    }

    /// Its linearised rate `2 c l_i |v| / m_i` at the speed of a fall over
    /// the chain's length, `sqrt(2 g L)`, on the lightest rod per length.
    fn stiffness(&self, chain: &Chain) -> Stiffness {
        let c = chain.params().coefficients.get(Self::KEY);
        let mu = chain.rods().map_or(1.0, |r| {
            r.mass
                .iter()
                .zip(&r.length)
                .map(|(m, l)| m / l)
                .fold(f64::INFINITY, f64::min)
        }) * chain.mass()
            / chain.rod_length();
        let v = (2.0 * chain.gravity() * chain.length()).sqrt();
        Stiffness::Rate(2.0 * c * v / mu)
    }
}
