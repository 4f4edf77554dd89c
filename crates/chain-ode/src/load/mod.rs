//! Forces as data: a [`Load`] is a force on the chain that every solver
//! path sums (`docs/model.md`, "Loads").
//!
//! A load reads the state's kinematics through a [`Kinematics`] view (each
//! rod's angle and rate, its centre's position and velocity, its ends'),
//! whatever the state's coordinates, and gives
//! * per rod, a generalised force: a force at the rod's centre and a torque
//!   about it, and the power it draws from the chain there
//!   ([`Load::add_to_rod`], over any [`Scalar`]: the same code runs on dual
//!   numbers for the exact Jacobians);
//! * the power it draws through the joints ([`Load::joint_power`]: joint
//!   friction), which with the per-rod power is its term of the work `W` in
//!   the balance `E + W = E(0)`;
//! * its potential energy when it is conservative ([`Load::potential`]);
//! * its stiffness ([`Load::stiffness`]: a rate, or an oscillation's
//!   frequency), which `auto`, the stiffness hint and `needs` read.
//!
//! The paths that sum the loads: the rigid chain's recursion
//! ([`crate::dynamics`]), its banded DAE ([`crate::dae`], whose Jacobian
//! takes the loads' derivatives by dual numbers), the dense reference
//! ([`crate::dense`], by virtual work), the elastic chain's right-hand side
//! ([`crate::elastic`]) and the energies of both models. Each path gives a
//! load its view in its own units ([`Units`]): the rigid paths in the mean
//! rod's (`m = l = 1`), the elastic one in the scene's. A load is built for
//! one path's units ([`Load::of`]) and scales its coefficients once.
//!
//! The chain keeps its geometry and its masses ([`crate::Chain`]); a
//! uniform field ([`Field`]: gravity) is the one load every mass feels, the
//! rods' and the tip mass's alike, so each path applies it to its masses
//! itself. The other loads are listed once, in [`loads!`]'s invocation
//! below, in the order every path adds them: adding a load is a file here
//! and a line there (ARCHITECTURE.md, "How to add a load").
//!
//! Its files, one load each: `field.rs` (gravity), `friction.rs` (joint
//! friction), `bending.rs` (bending springs), `contact.rs` (the floor's
//! contact and friction), `drag.rs` (air drag).

mod bending;
mod contact;
mod drag;
mod field;
mod friction;

use std::fmt::Debug;

pub use bending::{Bending, JointSprings};
pub use contact::FloorContact;
pub use drag::{Drag, MAX_AIR_DRAG};
pub use field::Field;
pub use friction::Friction;

use crate::chain::{Chain, ChainParams};
use crate::scalar::Scalar;
use crate::Vec2;
use fc_methods::InvalidParameter;

/// The unit system of a path. [`Units::Rod`]: mass in the mean rod's `m`,
/// length in its `l`, time unchanged (forces in `m l / T^2`, torques in
/// `m l^2 / T^2`): the recursion, the banded DAE and the dense reference.
/// [`Units::Physical`]: the scene's (the elastic chain).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    Rod,
    Physical,
}

/// What a load reads of the state; a path computes only what some load reads.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Reads {
    /// The rods' angles.
    pub angles: bool,
    /// Their rates.
    pub rates: bool,
    /// The rods' centres (and ends): positions and velocities in the
    /// inertial frame.
    pub centres: bool,
}

impl Reads {
    /// Both.
    pub fn or(self, o: Self) -> Self {
        Self {
            angles: self.angles || o.angles,
            rates: self.rates || o.rates,
            centres: self.centres || o.centres,
        }
    }
}

/// How stiff a load is, for `auto`, the stiffness hint and `needs`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stiffness {
    /// Not stiff (a field).
    None,
    /// A decay rate (1/time): the largest real eigenvalue magnitude it
    /// puts in the Jacobian (friction's `r / min(m_i l_i^2)`, the drag's
    /// linearised rate). `auto` compares it with the rigid chain's
    /// crossover ([`crate::bdf_crossover_gamma`]).
    Rate(f64),
    /// An oscillation's angular frequency (1/time): a spring's (bending,
    /// the floor's contact). An explicit step must resolve it.
    Frequency(f64),
}

impl Stiffness {
    /// The rate, if it is one.
    pub fn rate(self) -> Option<f64> {
        match self {
            Self::Rate(r) => Some(r),
            _ => None,
        }
    }

    /// The time scale `1 / rate` or `1 / frequency` (infinite when not stiff).
    pub fn time_scale(self) -> f64 {
        match self {
            Self::None => f64::INFINITY,
            Self::Rate(x) | Self::Frequency(x) => 1.0 / x,
        }
    }
}

/// What the loads add to one rod, accumulated in the order of [`Loads`]:
/// a force at its centre, a torque about its centre (both in the path's
/// units, a torque already times the path's [`Kinematics::torque_unit`])
/// and the power drawn from the chain (physical units, `>= 0` for a
/// dissipative load). A path starts it from its own terms, so that the
/// loads add to them in the order its arithmetic always had.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodForce<T> {
    pub force: [T; 2],
    pub torque: T,
    pub power: T,
}

impl<T: Scalar> RodForce<T> {
    /// All zero.
    #[inline(always)]
    pub fn zero() -> Self {
        let z = T::cst(0.0);
        Self {
            force: [z, z],
            torque: z,
            power: z,
        }
    }
}

/// The state's kinematics as a path shows it to a load, in the path's
/// units. Rods are 0-based from the pivot.
pub trait Kinematics<T: Scalar> {
    /// Every rod's angle `phi_i` (rad, from the horizontal).
    fn angles(&self) -> &[T];
    /// Every rod's rate `w_i`.
    fn rates(&self) -> &[T];
    /// `(sin phi_i, cos phi_i)`.
    fn sin_cos(&self, i: usize) -> (T, T);
    /// Rod `i`'s half length.
    fn half_length(&self, i: usize) -> f64;
    /// Rod `i`'s mass.
    fn mass(&self, i: usize) -> f64;
    /// The factor a torque on rod `i` carries into the path's rod equation
    /// (the recursion's `1 / lambda_i`; 1 elsewhere): a load multiplies its
    /// coefficient by it, so that equal rods keep their arithmetic.
    fn torque_unit(&self, i: usize) -> f64;
    /// Rod `i`'s centre (inertial frame; only when a load reads centres).
    fn centre(&self, i: usize) -> [T; 2];
    /// Its velocity (inertial frame; only when a load reads centres).
    fn centre_velocity(&self, i: usize) -> [T; 2];
    /// Rod `i`'s two ends, start (`c - h u`) then end (`c + h u`), each
    /// `[position, velocity]`.
    #[inline(always)]
    fn ends(&self, i: usize) -> [[[T; 2]; 2]; 2] {
        let (s, c) = self.sin_cos(i);
        let h = self.half_length(i);
        let w = self.rates()[i];
        let (p, v) = (self.centre(i), self.centre_velocity(i));
        let (hc, hs) = (c * h, s * h);
        let (hsw, hcw) = (hs * w, hc * w);
        [
            [[p[0] - hc, p[1] - hs], [v[0] + hsw, v[1] - hcw]],
            [[p[0] + hc, p[1] + hs], [v[0] - hsw, v[1] + hcw]],
        ]
    }
}

/// A rigid chain's state in rod units, from the slices a path has at hand
/// (the banded DAE's and the dense reference's view): the angles, rates
/// and their `(sin, cos)`, the rods' lengths and masses relative to the
/// mean rod (`None`: equal rods, 1), the centres and their velocities. A
/// torque enters the angles' rows as it is (`torque_unit` 1).
pub(crate) struct RodSlices<'a> {
    pub phi: &'a [f64],
    pub w: &'a [f64],
    pub trig: &'a [(f64, f64)],
    /// `lambda_i` (`None`: all 1).
    pub length: Option<&'a [f64]>,
    /// `mu_i` (`None`: all 1).
    pub mass: Option<&'a [f64]>,
    pub centre: &'a [[f64; 2]],
    pub velocity: &'a [[f64; 2]],
}

impl Kinematics<f64> for RodSlices<'_> {
    fn angles(&self) -> &[f64] {
        self.phi
    }
    fn rates(&self) -> &[f64] {
        self.w
    }
    fn sin_cos(&self, i: usize) -> (f64, f64) {
        self.trig[i]
    }
    fn half_length(&self, i: usize) -> f64 {
        0.5 * self.length.map_or(1.0, |l| l[i])
    }
    fn mass(&self, i: usize) -> f64 {
        self.mass.map_or(1.0, |m| m[i])
    }
    fn torque_unit(&self, _i: usize) -> f64 {
        1.0
    }
    fn centre(&self, i: usize) -> [f64; 2] {
        self.centre[i]
    }
    fn centre_velocity(&self, i: usize) -> [f64; 2] {
        self.velocity[i]
    }
}

/// A state's angles and rates alone, as a load reads them where nothing
/// else is at hand (the rigid chain's energy: bending's potential reads the
/// angles only). Centres read through it are NaN: a load that reads them
/// has to be given a path's full view.
pub struct Angles<'a> {
    pub phi: &'a [f64],
    pub w: &'a [f64],
}

impl Kinematics<f64> for Angles<'_> {
    fn angles(&self) -> &[f64] {
        self.phi
    }
    fn rates(&self) -> &[f64] {
        self.w
    }
    fn sin_cos(&self, i: usize) -> (f64, f64) {
        crate::scalar::sin_cos(self.phi[i])
    }
    fn half_length(&self, _i: usize) -> f64 {
        f64::NAN
    }
    fn mass(&self, _i: usize) -> f64 {
        f64::NAN
    }
    fn torque_unit(&self, _i: usize) -> f64 {
        1.0
    }
    fn centre(&self, _i: usize) -> [f64; 2] {
        [f64::NAN; 2]
    }
    fn centre_velocity(&self, _i: usize) -> [f64; 2] {
        [f64::NAN; 2]
    }
}

/// A force on the chain that every path sums; see the module doc.
pub trait Load: Clone + Debug + PartialEq + Sized {
    /// Its name in output (`"joint friction"`).
    const NAME: &'static str;
    /// The scene key that turns it on (and that a model which cannot carry
    /// it names when it refuses it).
    const KEY: &'static str;

    /// True when its strength is an entry of [`ChainParams::coefficients`]
    /// under [`Load::KEY`] (a load with a scene key of its own and no field
    /// of [`ChainParams`]).
    const COEFFICIENT: bool = false;

    /// True when `params` turn it on.
    fn is_on(params: &ChainParams) -> bool;

    /// `params` with it switched off (`needs` compares a scene with it off).
    fn switch_off(params: &mut ChainParams);

    /// `params` with it switched on at a strength of the scene's order
    /// (for the tests that walk every load).
    fn switch_on(params: &mut ChainParams);

    /// Checks its parameters in `params` (its range; the error names its
    /// key). [`crate::Chain::new`] calls it.
    fn validate(_params: &ChainParams) -> Result<(), InvalidParameter> {
        Ok(())
    }

    /// The load of `chain` in `units`, if the chain has it (a load whose
    /// absence would change a path's pattern of operations may be present
    /// at zero strength: joint friction).
    fn of(chain: &Chain, units: Units) -> Option<Self>;

    /// What it reads.
    fn reads(&self) -> Reads;

    /// Adds its force and torque on rod `i` and the power it draws there.
    fn add_to_rod<T: Scalar, K: Kinematics<T>>(&self, i: usize, k: &K, out: &mut RodForce<T>);

    /// The power it draws through the joints (physical units), if any.
    fn joint_power<T: Scalar, K: Kinematics<T>>(&self, _k: &K) -> Option<T> {
        None
    }

    /// Its potential energy (physical units) when it is conservative.
    fn potential<K: Kinematics<f64>>(&self, _k: &K) -> Option<f64> {
        None
    }

    /// How stiff it is on `chain`.
    fn stiffness(&self, chain: &Chain) -> Stiffness;
}

/// A load kind as plain data, for the lists that walk every load (the
/// report model's refusals, `needs`, the tests).
#[derive(Clone, Copy, Debug)]
pub struct Kind {
    /// [`Load::NAME`].
    pub name: &'static str,
    /// [`Load::KEY`].
    pub key: &'static str,
    /// [`Load::is_on`].
    pub is_on: fn(&ChainParams) -> bool,
    /// [`Load::switch_off`].
    pub switch_off: fn(&mut ChainParams),
    /// [`Load::switch_on`].
    pub switch_on: fn(&mut ChainParams),
    /// [`Load::COEFFICIENT`].
    pub coefficient: bool,
    /// [`Load::validate`].
    pub validate: fn(&ChainParams) -> Result<(), InvalidParameter>,
}

impl Kind {
    const fn of<L: Load>() -> Self {
        Self {
            name: L::NAME,
            key: L::KEY,
            is_on: L::is_on,
            switch_off: L::switch_off,
            switch_on: L::switch_on,
            coefficient: L::COEFFICIENT,
            validate: L::validate,
        }
    }
}

/// The strengths of the loads that take a `chain.*` scene key of their
/// own ([`Load::COEFFICIENT`]), by key: plain data of
/// [`ChainParams`], checked by [`crate::Chain::new`] (each load its range,
/// [`Load::validate`]; a key of no load is refused). An absent key is 0.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coefficients(Vec<(&'static str, f64)>);

impl Coefficients {
    /// The strength under `key` (0 when absent).
    pub fn get(&self, key: &str) -> f64 {
        self.0
            .iter()
            .find(|(k, _)| *k == key)
            .map_or(0.0, |&(_, x)| x)
    }

    /// Sets the strength under `key`.
    pub fn set(&mut self, key: &'static str, x: f64) {
        match self.0.iter_mut().find(|(k, _)| *k == key) {
            Some(entry) => entry.1 = x,
            None => self.0.push((key, x)),
        }
    }

    /// Every entry given, in the order set.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.0.iter().copied()
    }
}

/// The scene keys of the loads whose strength is a coefficient.
pub fn coefficient_keys() -> impl Iterator<Item = &'static str> {
    KINDS.iter().filter(|k| k.coefficient).map(|k| k.key)
}

/// Checks every load's parameters in `params`, and that each coefficient
/// is some load's.
pub(crate) fn validate(params: &ChainParams) -> Result<(), InvalidParameter> {
    for (key, x) in params.coefficients.iter() {
        crate::chain::check(
            coefficient_keys().any(|k| k == key),
            "chain",
            "the coefficients of loads only (load::coefficient_keys)",
            format_args!("{key} = {x}"),
        )?;
    }
    KINDS.iter().try_for_each(|k| (k.validate)(params))
}

/// What a load is on one chain, for output: its name, key and stiffness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Present {
    pub name: &'static str,
    pub key: &'static str,
    pub stiffness: Stiffness,
}

/// The list of loads: one line each, in the order every path adds them.
macro_rules! loads {
    ($($field:ident: $ty:ty),* $(,)?) => {
        /// The loads of one chain in one path's units ([`Load::of`]), the
        /// field apart ([`Field`]), in the order every path adds them.
        #[derive(Clone, Debug, PartialEq)]
        pub struct Loads {
            /// The uniform field (gravity), which the paths apply to every mass.
            pub field: Field,
            $(pub $field: Option<$ty>,)*
        }

        /// Every load kind but the field, in order.
        pub const KINDS: &[Kind] = &[$(Kind::of::<$ty>(),)*];

        impl Loads {
            /// The loads of `chain` in `units`.
            pub fn of(chain: &Chain, units: Units) -> Self {
                Self {
                    field: Field::new(chain, units),
                    $($field: <$ty as Load>::of(chain, units),)*
                }
            }

            /// The key of the first load that reads the rods' centres, if any.
            pub fn first_reading_centres(&self) -> Option<&'static str> {
                $(if let Some(l) = &self.$field {
                    if l.reads().centres {
                        return Some(<$ty as Load>::KEY);
                    }
                })*
                None
            }

            /// What they read, together.
            pub fn reads(&self) -> Reads {
                let mut r = Reads::default();
                $(if let Some(l) = &self.$field {
                    r = r.or(l.reads());
                })*
                r
            }

            /// Every load's force and torque on rod `i`, and its power
            /// there, added to `out` in order.
            #[inline(always)]
            pub fn add_to_rod<T: Scalar, K: Kinematics<T>>(
                &self,
                i: usize,
                k: &K,
                out: &mut RodForce<T>,
            ) {
                $(if let Some(l) = &self.$field {
                    l.add_to_rod(i, k, out);
                })*
            }

            /// The power drawn through the joints, summed in order from
            /// `start` (physical units).
            #[inline(always)]
            pub fn joint_power<T: Scalar, K: Kinematics<T>>(&self, k: &K, start: T) -> T {
                let mut p = start;
                $(if let Some(l) = &self.$field {
                    if let Some(q) = l.joint_power(k) {
                        p += q;
                    }
                })*
                p
            }

            /// The conservative loads' potential energy added to `start`
            /// in order (the field's is the masses', which the models
            /// compute with the kinetic energy).
            pub fn potential<K: Kinematics<f64>>(&self, k: &K, start: f64) -> f64 {
                let mut e = start;
                $(if let Some(l) = &self.$field {
                    if let Some(v) = l.potential(k) {
                        e += v;
                    }
                })*
                e
            }

            /// [`Loads::potential`] with `between` added right after the
            /// load whose key is `after` (its place in an energy written
            /// before the loads were: the elastic chain's tip mass).
            pub fn potential_split<K: Kinematics<f64>>(
                &self,
                k: &K,
                start: f64,
                after: &str,
                between: f64,
            ) -> f64 {
                let mut e = start;
                $(
                    if let Some(l) = &self.$field {
                        if let Some(v) = l.potential(k) {
                            e += v;
                        }
                    }
                    if <$ty as Load>::KEY == after {
                        e += between;
                    }
                )*
                e
            }

            /// The loads present (the field first), with their stiffness on `chain`.
            pub fn present(&self, chain: &Chain) -> Vec<Present> {
                let mut out = vec![Present {
                    name: Field::NAME,
                    key: Field::KEY,
                    stiffness: self.field.stiffness(chain),
                }];
                $(if let Some(l) = &self.$field {
                    out.push(Present {
                        name: <$ty as Load>::NAME,
                        key: <$ty as Load>::KEY,
                        stiffness: l.stiffness(chain),
                    });
                })*
                out
            }
        }
    };
}

loads! {
    friction: Friction,
    bending: Bending,
    floor: FloorContact,
    drag: Drag,
}

impl Loads {
    /// The largest decay rate of the loads on `chain` (0 for none): what
    /// `auto` compares with the crossover.
    pub fn stiffest_rate(&self, chain: &Chain) -> f64 {
        self.present(chain)
            .iter()
            .filter_map(|p| p.stiffness.rate())
            .fold(0.0, f64::max)
    }

    /// True when some load reads the rods' centres.
    #[inline(always)]
    pub fn reads_centres(&self) -> bool {
        self.reads().centres
    }
}

/// The keys of every load that `chain` carries but the field (whose key,
/// `chain.gravity`, every model takes): what a model that carries only
/// some loads checks ([`crate::report::ReportModel::validate`]).
pub fn keys_on(params: &ChainParams) -> impl Iterator<Item = &'static str> + '_ {
    KINDS
        .iter()
        .filter(move |k| (k.is_on)(params))
        .map(|k| k.key)
}

/// The plane's 2-vector of a load's force (physical units).
pub type Force = Vec2;

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kind has a key of the scene's `chain.` or `floor.` sections,
    /// a name, is off by default, on after `switch_on` (a chain that
    /// validates) and off again after `switch_off`; a coefficient's key is
    /// refused out of its range, and a key of no load is refused.
    #[test]
    fn every_kind_switches_on_and_off() {
        for k in KINDS {
            assert!(k.key.starts_with("chain.") || k.key.starts_with("floor."));
            assert!(!k.name.is_empty());
            let mut p = ChainParams::default();
            assert!(!(k.is_on)(&p), "{} on by default", k.name);
            (k.switch_on)(&mut p);
            assert!((k.is_on)(&p), "{}", k.name);
            assert!(Chain::new(p.clone()).is_ok(), "{}", k.name);
            (k.switch_off)(&mut p);
            assert!(!(k.is_on)(&p), "{}", k.name);
            if k.coefficient {
                p.coefficients.set(k.key, -1.0);
                assert_eq!(Chain::new(p).unwrap_err().field, k.key);
            }
        }
        let mut p = ChainParams::default();
        p.coefficients.set("chain.nonesuch", 1.0);
        assert!(Chain::new(p).is_err());
    }
}
