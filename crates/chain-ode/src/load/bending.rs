//! Bending springs: a torque `k_j (phi_j - phi_{j-1})` in every joint `j`
//! between two rods (the pivot has none), `chain.bending_stiffness = EI`.
//!
//! Joint `j`'s spring is `EI / s_j`, `s_j` the distance between the two
//! rods' centres (`l` for equal rods; `(l_{j-1} + l_j) / 2` for a
//! profile: `docs/model.md`, "Bending of unequal rods"). Rod `i` feels
//! `k_i (phi_{i-1} - phi_i) + k_{i+1} (phi_{i+1} - phi_i)`, and the springs
//! store `U_b = sum_j k_j (phi_j - phi_{j-1})^2 / 2`. Its stiffness is the
//! fastest bending mode's frequency, about `2 sqrt(k / J)` with `J` the
//! lightest rod's moment of inertia about its centre.

use std::sync::Arc;

use super::{Kinematics, Load, Reads, RodForce, Stiffness, Units};
use crate::chain::{Chain, ChainParams};
use crate::profile::Rods;
use crate::scalar::Scalar;

/// The joints' springs as one path writes them: each joint's factor, by
/// which a scale multiplies (see [`Bending`]).
#[derive(Clone, Debug, PartialEq)]
pub enum JointSprings {
    /// Every joint 1 (equal rods).
    Equal,
    /// Joint `j`'s `2 / (lambda_{j-1} + lambda_j)` ([`Rods::joint`]),
    /// relative to the mean rod's `EI / l`.
    Relative(Arc<Rods>),
    /// Each joint's own spring, given (entry 0 unused).
    Absolute(Arc<[f64]>),
    /// `ei / (h_{j-1} + h_j)` from the rods' half lengths `h_j = l_j / 2`
    /// (`l` the mean rod's length, the rods' relative lengths if unequal),
    /// computed as it is read (no storage).
    Shares {
        ei: f64,
        l: f64,
        rods: Option<Arc<Rods>>,
    },
}

impl JointSprings {
    /// Joint `j`'s factor.
    #[inline(always)]
    fn at(&self, j: usize) -> f64 {
        match self {
            Self::Equal => 1.0,
            Self::Relative(r) => r.joint[j],
            Self::Absolute(k) => k[j],
            Self::Shares { ei, l, rods } => {
                let h = |i: usize| match rods {
                    None => 0.5 * l,
                    Some(r) => 0.5 * (l * r.length[i]),
                };
                ei / (h(j - 1) + h(j))
            }
        }
    }

    /// `sum_j k_j (phi_j - phi_{j-1})^2`.
    fn energy_sum(&self, phi: &[f64]) -> f64 {
        match self {
            Self::Equal => phi.windows(2).map(|p| (p[1] - p[0]).powi(2)).sum::<f64>(),
            _ => {
                let mut sum = 0.0;
                for j in 1..phi.len() {
                    sum += self.at(j) * (phi[j] - phi[j - 1]).powi(2);
                }
                sum
            }
        }
    }
}

/// The springs' torque on rod `i`, over the scale: equal springs as the
/// neighbours' stencil of `phi` (`D_i(phi)`), others joint by joint.
#[inline(always)]
fn stencil<T: Scalar>(springs: &JointSprings, phi: &[T], i: usize) -> T {
    match springs {
        JointSprings::Equal => crate::dynamics::damping_stencil(phi, i),
        s => {
            let n = phi.len();
            let mut d = T::cst(0.0);
            if i > 0 {
                d += (phi[i - 1] - phi[i]) * s.at(i);
            }
            if i + 1 < n {
                d += (phi[i + 1] - phi[i]) * s.at(i + 1);
            }
            d
        }
    }
}

/// Bending springs in a path's units: the torque `scale * springs` (rod
/// units: `kappa = EI / (l m l^2)` times the relative springs; physical:
/// `EI / l`, or each joint's own), and the energy `energy_scale / 2 *
/// energy_springs` in physical units, as each model has always written it.
#[derive(Clone, Debug, PartialEq)]
pub struct Bending {
    pub scale: f64,
    pub springs: JointSprings,
    pub energy_scale: f64,
    pub energy_springs: JointSprings,
}

impl Load for Bending {
    const NAME: &'static str = "bending stiffness";
    const KEY: &'static str = "chain.bending_stiffness";

    fn is_on(params: &ChainParams) -> bool {
        params.bending_stiffness > 0.0
    }

    fn switch_off(params: &mut ChainParams) {
        params.bending_stiffness = 0.0;
    }

    fn switch_on(params: &mut ChainParams) {
        params.bending_stiffness = 0.01;
    }

    /// Present with `EI > 0` only: a chain without it runs no operation of it.
    fn of(chain: &Chain, units: Units) -> Option<Self> {
        if chain.bending_rate() == 0.0 {
            return None;
        }
        let kb = chain.bending_spring();
        let relative = || match chain.rods_shared() {
            Some(r) => JointSprings::Relative(r),
            None => JointSprings::Equal,
        };
        Some(match units {
            Units::Rod => Self {
                scale: chain.bending_rate(),
                springs: relative(),
                energy_scale: kb,
                energy_springs: relative(),
            },
            Units::Physical => {
                let ei = chain.bending_stiffness();
                let (springs, scale) = match chain.rods() {
                    None => (JointSprings::Equal, kb),
                    Some(r) => {
                        let l = chain.rod_length();
                        let li = |i: usize| l * r.length[i];
                        let k: Vec<f64> = (0..r.length.len())
                            .map(|j| match j {
                                0 => 0.0,
                                _ => ei / (0.5 * (li(j - 1) + li(j))),
                            })
                            .collect();
                        (JointSprings::Absolute(k.into()), 1.0)
                    }
                };
                // The elastic chain's energy: `EI / l` times the stencil for
                // a plain chain, each joint's `EI / (h_{j-1} + h_j)` else.
                let plain =
                    chain.rods().is_none() && chain.tip_mass() == 0.0 && chain.pivot().is_fixed();
                let (energy_springs, energy_scale) = if plain {
                    (JointSprings::Equal, kb)
                } else {
                    let shares = JointSprings::Shares {
                        ei,
                        l: chain.rod_length(),
                        rods: chain.rods_shared(),
                    };
                    (shares, 1.0)
                };
                Self {
                    scale,
                    springs,
                    energy_scale,
                    energy_springs,
                }
            }
        })
    }

    fn reads(&self) -> Reads {
        Reads {
            angles: true,
            ..Reads::default()
        }
    }

    #[inline(always)]
    fn add_to_rod<T: Scalar, K: Kinematics<T>>(&self, i: usize, k: &K, out: &mut RodForce<T>) {
        out.torque += stencil(&self.springs, k.angles(), i) * (self.scale * k.torque_unit(i));
    }

    /// `U_b`.
    fn potential<K: Kinematics<f64>>(&self, k: &K) -> Option<f64> {
        Some(0.5 * self.energy_scale * self.energy_springs.energy_sum(k.angles()))
    }

    /// `2 sqrt(k_max / J_min)`: the zig-zag mode of the stiffest spring on
    /// the lightest rods (`J = m_i l_i^2 / 12`).
    fn stiffness(&self, chain: &Chain) -> Stiffness {
        let j = chain.rods().map_or(1.0, |r| {
            r.mass
                .iter()
                .zip(&r.length)
                .map(|(m, l)| m * l * l)
                .fold(f64::INFINITY, f64::min)
        }) * chain.mass()
            * chain.rod_length().powi(2)
            / 12.0;
        let k = chain
            .rods()
            .map_or(1.0, |r| r.joint.iter().copied().fold(0.0, f64::max))
            * chain.bending_spring();
        Stiffness::Frequency(2.0 * (k / j).sqrt())
    }
}
