//! The chain's physical parameters, validated once.

use std::borrow::Cow;
use std::fmt;

use fc_methods::InvalidParameter;

use crate::floor::{Floor, FloorLaw};
use crate::load::Coefficients;
use crate::pivot::Pivot;
use crate::profile::{Profile, Rods};

/// The largest number of rods of a chain (`chain.links`): the same cap as
/// the catenary's ([`catenary::MAX_LINKS`]), so that every chain has a
/// catenary start.
pub const MAX_LINKS: usize = catenary::MAX_LINKS;

/// The parameters of a chain, as given: plain data, not yet checked.
///
/// Build a [`Chain`] from it with [`Chain::new`], which checks every field
/// once. Fields left out take the report's values
/// (`..ChainParams::default()`: `L = 6`, `n = 50`, `m = 0.2`, `g = 1`, `r = 0`).
/// Units are the user's. `mass` is **per rod**, as in the report: at fixed
/// `damping` the damping rate `r / (m l^2)` grows like `n^2`, so changing
/// `links` at fixed `damping` is not a pure refinement ([`Chain::refined`] is).
#[derive(Clone, Debug, PartialEq)]
pub struct ChainParams {
    /// Total length `L` (> 0).
    pub length: f64,
    /// Number of rods `n` (in `1..=MAX_LINKS`).
    pub links: usize,
    /// Mass of one rod `m` (> 0).
    pub mass: f64,
    /// Gravitational acceleration `g` (>= 0), pointing to -y.
    pub gravity: f64,
    /// Joint friction coefficient `r` (>= 0): torque `r (w_{i+1} - w_i)` between neighbours.
    pub damping: f64,
    /// Axial stiffness `EA` of the rope (force; finite, > 0), or `None` for
    /// rigid links (the default: the pinned chain of rigid rods). With
    /// `Some(EA)` every joint, the pivot included, is a spring of stiffness
    /// `K = EA / l` (`n` of them in series give the rope `EA / L`), and the
    /// chain is the elastic model of `docs/model.md`.
    pub axial_stiffness: Option<f64>,
    /// Axial (Kelvin–Voigt) viscosity `eta` of the rope (force x time,
    /// at least 0): each joint spring has a dashpot `C = eta / l` in
    /// parallel. Acts only with `axial_stiffness`; a rigid chain ignores it.
    pub axial_damping: f64,
    /// Bending stiffness `EI` (force x length^2, at least 0): a torque
    /// `(EI / l) (phi_{i+1} - phi_i)` between neighbouring rods (the pivot
    /// is free). Default 0. Works with rigid and elastic links.
    pub bending_stiffness: f64,
    /// A point mass `M_t` (mass, at least 0) at the free end, pinned to the
    /// last rod's tip. Default 0. Works with rigid and elastic links.
    pub tip_mass: f64,
    /// How the pivot `P0` moves: fixed (the default), along a prescribed
    /// path, or let go at a time ([`Pivot`], the `pivot.*` keys). Works
    /// with rigid and elastic links.
    pub pivot: Pivot,
    /// How the mass `n m` and the length `L` are shared among the rods
    /// ([`Profile`], the keys `chain.taper`, `chain.rod_masses`,
    /// `chain.rod_lengths`); equal rods by default. It combines with every
    /// other term (tip mass, bending, a moving or released pivot) on rigid
    /// and on elastic links.
    pub profile: Profile,
    /// A floor the chain falls onto ([`Floor`], the `[floor]` keys), or
    /// `None` (the default: no floor). It needs elastic links
    /// (`axial_stiffness`) and a pivot that does not move on a path.
    pub floor: Option<Floor>,
    /// The strengths of the loads that take a `chain.*` key of their own
    /// ([`crate::load::Load::COEFFICIENT`]), by key; none by default.
    pub coefficients: Coefficients,
}

impl Default for ChainParams {
    /// The report's chain of 50 rods without friction.
    fn default() -> Self {
        Self {
            length: 6.0,
            links: 50,
            mass: 0.2,
            gravity: 1.0,
            damping: 0.0,
            axial_stiffness: None,
            axial_damping: 0.0,
            bending_stiffness: 0.0,
            tip_mass: 0.0,
            pivot: Pivot::default(),
            profile: Profile::default(),
            floor: None,
            coefficients: Coefficients::default(),
        }
    }
}

/// A chain of `links` equal rigid rods pinned at the anchor `P0`: a
/// [`ChainParams`] that has passed the range checks. Its fields are private,
/// so that no chain skips them; read them by the accessors of the same names.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    params: ChainParams,
    /// The rods' masses and lengths for a profiled chain, `None` for equal rods.
    rods: Option<std::sync::Arc<Rods>>,
}

pub(crate) fn check(
    ok: bool,
    field: &'static str,
    accepted: impl Into<Cow<'static, str>>,
    got: impl fmt::Display,
) -> Result<(), InvalidParameter> {
    if ok {
        Ok(())
    } else {
        Err(InvalidParameter {
            field,
            accepted: accepted.into(),
            got: got_text(got.to_string()),
        })
    }
}

/// A number as an error shows it: the shortest text that reads back to
/// it, as a person writes it (`0.5`, `4.157`, `1e300`, not the 301 digits
/// of `f64`'s `Display`; `1e-9`, not `0.000000001`; `NaN`, `inf`).
pub(crate) fn number_text(x: f64) -> String {
    if !x.is_finite() || x == 0.0 || (1e-4..1e16).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A value as an error shows it: a number by [`number_text`], any other
/// text as it is.
fn got_text(text: String) -> String {
    match text.parse::<f64>() {
        Ok(x) if x.is_finite() && (text.len() > 17 || text.contains('.')) => number_text(x),
        _ => text,
    }
}

/// How many times the chain's weight its axial stiffness `EA` is when a
/// rigid chain is put on a floor: its own weight stretches it by at most
/// `1 / RIGID_FLOOR_EA_PER_WEIGHT` of its length.
pub const RIGID_FLOOR_EA_PER_WEIGHT: f64 = 1e4;

/// The axial stiffness a rigid chain on a floor runs with:
/// `EA = 1e4 n m g` (`g = 0`: `1e4 n m` in the scene's units).
pub fn rigid_floor_stiffness(p: &ChainParams) -> f64 {
    let g = if p.gravity > 0.0 { p.gravity } else { 1.0 };
    RIGID_FLOOR_EA_PER_WEIGHT * p.links as f64 * p.mass * g
}

/// The accepted range of `chain.links`, in words.
const LINKS_RANGE: &str = "an integer in 1..=1000000";

/// The smallest `floor.slip_speed` with friction, as a fraction of the
/// scene's speed scale `sqrt(g L)` (see [`validate`]).
pub const MIN_SLIP_SPEED_OF_SCALE: f64 = 1e-10;

/// Checks every field of `p`; the error names the first one out of range.
/// Only [`Chain::new`] calls it.
fn validate(p: &ChainParams) -> Result<(), InvalidParameter> {
    let finite_pos = |x: f64| x.is_finite() && x > 0.0;
    let finite_nonneg = |x: f64| x.is_finite() && x >= 0.0;
    check(
        finite_pos(p.length),
        "chain.length",
        "a finite number > 0",
        p.length,
    )?;
    check(
        (1..=MAX_LINKS).contains(&p.links),
        "chain.links",
        LINKS_RANGE,
        p.links,
    )?;
    check(
        finite_pos(p.mass),
        "chain.mass",
        "a finite number > 0",
        p.mass,
    )?;
    check(
        finite_nonneg(p.gravity),
        "chain.gravity",
        "a finite number >= 0",
        p.gravity,
    )?;
    check(
        finite_nonneg(p.damping),
        "chain.damping",
        "a finite number >= 0",
        p.damping,
    )?;
    if let Some(ea) = p.axial_stiffness {
        check(
            finite_pos(ea),
            "chain.axial_stiffness",
            "a finite number > 0",
            ea,
        )?;
    }
    check(
        finite_nonneg(p.axial_damping),
        "chain.axial_damping",
        "a finite number >= 0",
        p.axial_damping,
    )?;
    check(
        finite_nonneg(p.bending_stiffness),
        "chain.bending_stiffness",
        "a finite number >= 0",
        p.bending_stiffness,
    )?;
    check(
        finite_nonneg(p.tip_mass),
        "chain.tip_mass",
        "a finite number >= 0",
        p.tip_mass,
    )?;
    p.pivot.validate()?;
    p.profile.validate(p.links)?;
    if let Some(floor) = &p.floor {
        floor.validate()?;
        // Friction's tanh(v_t / v_s) is a switch of width v_s in the slip
        // speed: far below the scene's speeds it is a step the Newton
        // iteration cannot cross (bdf stalled at v_s = 1e-12 sqrt(g L)).
        let least = MIN_SLIP_SPEED_OF_SCALE * (p.gravity * p.length).sqrt();
        check(
            floor.friction == 0.0 || floor.slip_speed >= least,
            "floor.slip_speed",
            format!(
                "at least 1e-10 sqrt(g L) = {} with floor.friction > 0 (a narrower friction \
                 switch is a step no method crosses)",
                number_text(least)
            ),
            number_text(floor.slip_speed),
        )?;
        check(
            !p.pivot.is_driven(),
            "floor.height",
            "a floor with a pivot that stays put until any pivot.release (pivot.acceleration, \
             pivot.amplitude and pivot.jerk zero)",
            "a floor with a moving pivot",
        )?;
        if floor.law == FloorLaw::Constraint {
            // The constraint floor is the rigid chain's (docs/model.md,
            // "The floor as a constraint").
            check(
                p.axial_stiffness.is_none(),
                "floor.law",
                "\"penalty\" with chain.axial_stiffness (\"constraint\" holds rigid rods on a \
                 rigid floor)",
                "constraint",
            )?;
            check(
                p.tip_mass == 0.0,
                "floor.law",
                "\"penalty\" with chain.tip_mass (\"constraint\" has no tip mass yet)",
                "constraint",
            )?;
        }
    }
    // A profile takes every other term, on rigid and on elastic links
    // (`dynamics.rs`, `elastic.rs`). Each load checks its own.
    crate::load::validate(p)
}

impl Chain {
    /// The chain of `params`, checked; the error names the first field out
    /// of range. This is the one place a chain is validated.
    pub fn new(params: ChainParams) -> Result<Self, InvalidParameter> {
        validate(&params)?;
        let mut params = params;
        if params.floor.is_some_and(|f| f.law == FloorLaw::Penalty)
            && params.axial_stiffness.is_none()
        {
            // A rigid chain on a penalty floor is the elastic chain at a
            // stiffness where the two agree (docs/model.md, "The floor").
            params.axial_stiffness = Some(rigid_floor_stiffness(&params));
        }
        let rods = params.profile.rods(params.links).map(std::sync::Arc::new);
        Ok(Self { params, rods })
    }

    /// The report's chain: `L = 6`, `m = 0.2` per rod, `g = 1`.
    pub fn report(links: usize, damping: f64) -> Result<Self, InvalidParameter> {
        Self::new(ChainParams {
            links,
            damping,
            ..ChainParams::default()
        })
    }

    /// The parameters it was built from.
    pub fn params(&self) -> &ChainParams {
        &self.params
    }

    /// Total length `L`.
    pub fn length(&self) -> f64 {
        self.params.length
    }

    /// Number of rods `n`.
    pub fn links(&self) -> usize {
        self.params.links
    }

    /// Mass of one rod `m`.
    pub fn mass(&self) -> f64 {
        self.params.mass
    }

    /// Gravitational acceleration `g`, along -y.
    pub fn gravity(&self) -> f64 {
        self.params.gravity
    }

    /// Joint friction coefficient `r`.
    pub fn damping(&self) -> f64 {
        self.params.damping
    }

    /// Axial stiffness `EA` (force), `None` for rigid links.
    pub fn axial_stiffness(&self) -> Option<f64> {
        self.params.axial_stiffness
    }

    /// Axial viscosity `eta` (force x time); acts only on elastic links.
    pub fn axial_damping(&self) -> f64 {
        self.params.axial_damping
    }

    /// Bending stiffness `EI` (force x length^2).
    pub fn bending_stiffness(&self) -> f64 {
        self.params.bending_stiffness
    }

    /// The point mass `M_t` at the free end (0 for none).
    pub fn tip_mass(&self) -> f64 {
        self.params.tip_mass
    }

    /// How the pivot moves ([`Pivot`]; fixed by default).
    pub fn pivot(&self) -> &Pivot {
        &self.params.pivot
    }

    /// The floor, if the chain has one.
    pub fn floor(&self) -> Option<&Floor> {
        self.params.floor.as_ref()
    }

    /// The rods' masses and lengths in mean-rod units for a profiled chain
    /// ([`Rods`]), `None` for equal rods.
    pub fn rods(&self) -> Option<&Rods> {
        self.rods.as_deref()
    }

    /// [`Chain::rods`], shared (for a load that keeps them).
    pub(crate) fn rods_shared(&self) -> Option<std::sync::Arc<Rods>> {
        self.rods.clone()
    }

    /// The tip mass in rod masses, `mu = M_t / m`: the recursion's and the
    /// dense reference's unit.
    pub fn tip_mass_ratio(&self) -> f64 {
        self.params.tip_mass / self.params.mass
    }

    /// True for elastic links (`axial_stiffness` given).
    pub fn is_elastic(&self) -> bool {
        self.params.axial_stiffness.is_some()
    }

    /// The joint spring `K = EA / l` (force / length), `None` for rigid links.
    pub fn joint_stiffness(&self) -> Option<f64> {
        self.params.axial_stiffness.map(|ea| ea / self.rod_length())
    }

    /// The joint dashpot `C = eta / l` (force x time / length).
    pub fn joint_damping(&self) -> f64 {
        self.params.axial_damping / self.rod_length()
    }

    /// The bending spring between neighbouring rods, `EI / l` (torque per radian).
    pub fn bending_spring(&self) -> f64 {
        self.params.bending_stiffness / self.rod_length()
    }

    /// The bending rate `kappa = EI / (l m l^2)` (1/time^2): the bending
    /// spring in rod units, as `damping_rate` is the friction's.
    pub fn bending_rate(&self) -> f64 {
        self.bending_spring() / (self.params.mass * self.rod_length().powi(2))
    }

    /// The same continuous chain cut into `links` rods: this chain refined
    /// (or coarsened) at fixed continuum properties. Every other field is
    /// carried unchanged. The one refinement: `analysis::refined` and
    /// falling-chain's `converge` both call it.
    ///
    /// * The total mass `M = n m` is kept: `m' = M / n'`.
    /// * The joint friction is kept as a continuum viscous bending moment
    ///   `M_b(s) = eta * d(omega)/ds`: a joint's torque `r (w_{i+1} - w_i)`
    ///   is `r l d(omega)/ds`, and the dissipated power
    ///   `r sum (w_{i+1} - w_i)^2` tends to `r l * integral (d(omega)/ds)^2 ds`,
    ///   so `eta = r l` ([`Chain::bending_viscosity`]) is the continuum
    ///   quantity and `r' = eta / l' = r n' / n` (rounded as `(r n') / n`).
    ///
    /// * The tip mass `M_t` is a point mass: carried as it is.
    /// * The pivot's motion is carried as it is.
    /// * The rod profile holds the continuum's mass per length and length
    ///   fixed: a taper is carried; lists are cut ([`Profile`]'s refinement).
    /// * The axial stiffness `EA`, the axial viscosity `eta` and the bending
    ///   stiffness `EI` are continuum properties of the rope: carried as
    ///   they are (the joint spring `K = EA / l`, dashpot `eta / l` and
    ///   bending spring `EI / l` follow the new `l`).
    ///
    /// The damping rate `r / (m l^2) = eta n^4 / (M L^3)` then grows like
    /// `n^4`: the grid-scale bending modes of a viscous rope are damped that
    /// fast, which makes the refined problem stiff.
    pub fn refined(&self, links: usize) -> Result<Self, InvalidParameter> {
        let (n, n_new) = (self.params.links as f64, links as f64);
        Self::new(ChainParams {
            links,
            mass: self.total_mass() / n_new,
            damping: self.params.damping * n_new / n,
            profile: self.params.profile.refined(self.params.links, links)?,
            ..self.params.clone()
        })
    }

    /// The continuum bending viscosity `eta = r l` (see [`Chain::refined`]).
    pub fn bending_viscosity(&self) -> f64 {
        self.params.damping * self.rod_length()
    }

    /// Rod length `l = L / n`.
    pub fn rod_length(&self) -> f64 {
        self.params.length / self.params.links as f64
    }

    /// Total mass `M = n m`.
    pub fn total_mass(&self) -> f64 {
        self.params.mass * self.params.links as f64
    }

    /// The chain's weight `M g`.
    pub fn weight(&self) -> f64 {
        self.total_mass() * self.params.gravity
    }

    /// Damping rate `gamma = r / (m l^2)` (1/time): the stiffness parameter.
    pub fn damping_rate(&self) -> f64 {
        self.params.damping / (self.params.mass * self.rod_length().powi(2))
    }

    /// The largest damping rate of one rod, `r / min_i (m_i l_i^2)`
    /// (1/time): the friction's stiffness on a profiled chain, where a
    /// light or short rod is damped far faster than the mean rod
    /// ([`Chain::damping_rate`]); equal to it for equal rods (the same
    /// number, bit for bit: the minimum is exactly 1).
    pub fn stiffest_damping_rate(&self) -> f64 {
        let smallest = self.rods().map_or(1.0, |r| {
            r.mass
                .iter()
                .zip(&r.length)
                .map(|(mu, lambda)| mu * lambda * lambda)
                .fold(f64::INFINITY, f64::min)
        });
        self.damping_rate() / smallest
    }

    /// `g / l` (1/time^2).
    pub fn gravity_rate(&self) -> f64 {
        self.params.gravity / self.rod_length()
    }

    /// Energy scale `M g L` (`M L^2` at `g = 0`), against which energy
    /// errors are judged; with a tip mass, `M` includes it (`n m + M_t`).
    pub fn energy_scale(&self) -> f64 {
        if self.params.tip_mass != 0.0 {
            let m = self.total_mass() + self.params.tip_mass;
            let g = self.params.gravity;
            let l = self.params.length;
            return if g > 0.0 { m * g * l } else { m * l * l };
        }
        let w = self.weight();
        if w > 0.0 {
            w * self.params.length
        } else {
            self.total_mass() * self.params.length.powi(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_given_is_shown_in_its_shortest_form() {
        assert_eq!(got_text(1e300.to_string()), "1e300");
        assert_eq!(got_text((-2.5e-9f64).to_string()), "-2.5e-9");
        assert_eq!(got_text(0.5f64.to_string()), "0.5");
        assert_eq!(got_text("1000000".into()), "1000000");
        assert_eq!(got_text("NaN".into()), "NaN");
        assert_eq!(got_text("a rod profile".into()), "a rod profile");
        let e = check(false, "run.dt", "positive", 1e300).unwrap_err();
        assert_eq!(e.to_string(), "run.dt: must be positive (got 1e300)");
    }

    /// `ChainParams` with `field` replaced.
    fn with(field: &str, x: f64) -> ChainParams {
        let mut p = ChainParams {
            length: 1.0,
            links: 5,
            mass: 1.0,
            gravity: 1.0,
            damping: 0.0,
            ..ChainParams::default()
        };
        match field {
            "chain.length" => p.length = x,
            "chain.links" => p.links = x as usize,
            "chain.mass" => p.mass = x,
            "chain.gravity" => p.gravity = x,
            "chain.axial_stiffness" => p.axial_stiffness = Some(x),
            "chain.axial_damping" => p.axial_damping = x,
            "chain.bending_stiffness" => p.bending_stiffness = x,
            "chain.tip_mass" => p.tip_mass = x,
            _ => p.damping = x,
        }
        p
    }

    #[test]
    fn rejects_each_bad_field_by_name() {
        let bad = [
            ("chain.length", -1.0),
            ("chain.length", f64::NAN),
            ("chain.links", 0.0),
            ("chain.mass", 0.0),
            ("chain.gravity", f64::INFINITY),
            ("chain.damping", -1e-3),
            ("chain.damping", f64::NAN),
            ("chain.axial_stiffness", 0.0),
            ("chain.axial_stiffness", -1e4),
            ("chain.axial_stiffness", f64::NAN),
            ("chain.axial_stiffness", f64::INFINITY),
            ("chain.axial_damping", -1.0),
            ("chain.axial_damping", f64::NAN),
            ("chain.axial_damping", f64::INFINITY),
            ("chain.bending_stiffness", -1e-3),
            ("chain.bending_stiffness", f64::NAN),
            ("chain.bending_stiffness", f64::INFINITY),
            ("chain.tip_mass", -0.1),
            ("chain.tip_mass", f64::NAN),
            ("chain.tip_mass", f64::INFINITY),
        ];
        for (field, x) in bad {
            let e = Chain::new(with(field, x)).unwrap_err();
            assert_eq!(e.field, field);
            assert!(e.to_string().starts_with(field));
            assert!(!e.to_string().contains('\n'));
        }
        assert!(Chain::report(50, 5e-4).is_ok());
        assert!(Chain::new(ChainParams::default()).is_ok());
        // A tip mass works with rigid and elastic links.
        let mut p = with("chain.tip_mass", 0.5);
        assert!(Chain::new(p.clone()).is_ok());
        p.axial_stiffness = Some(1e4);
        assert!(Chain::new(p).is_ok());
    }

    /// The refinement carries every field: each is set to a value no
    /// default has, and the destructuring below is exhaustive, so a field
    /// added to `ChainParams` does not compile here until this test (and
    /// so `Chain::refined`) says what becomes of it.
    #[test]
    fn refinement_carries_every_field() {
        let given = ChainParams {
            length: 2.5,
            links: 40,
            mass: 0.35,
            gravity: 9.81,
            damping: 3e-3,
            axial_stiffness: Some(2.5e4),
            axial_damping: 0.7,
            bending_stiffness: 0.03,
            tip_mass: 0.0,
            pivot: Pivot::default(),
            profile: Profile::default(),
            floor: Some(crate::floor::Floor {
                height: Some(-3.0),
                angle: 0.1,
                stiffness: 1e5,
                damping: 10.0,
                friction: 0.4,
                slip_speed: 0.02,
                law: crate::floor::FloorLaw::Penalty,
                restitution: 0.0,
            }),
            coefficients: {
                let mut c = Coefficients::default();
                for key in crate::load::coefficient_keys() {
                    c.set(key, 0.3);
                }
                c
            },
        };
        assert_ne!(given, ChainParams::default());
        let chain = Chain::new(given.clone()).unwrap();
        let refined = chain.refined(160).unwrap();
        let ChainParams {
            length,
            links,
            mass,
            gravity,
            damping,
            axial_stiffness,
            axial_damping,
            bending_stiffness,
            tip_mass,
            pivot,
            profile,
            floor,
            coefficients,
        } = refined.params().clone();
        // The loads' coefficients (per unit length, per speed): carried.
        assert_eq!(coefficients, given.coefficients);
        // The floor is a place and a law per contact point: carried (its
        // stiffness is per rod end, so a default `1e4 m g / l` stays).
        assert_eq!(floor, given.floor);
        // Equal rods stay equal rods (a taper is carried: profile.rs).
        assert_eq!(profile, given.profile);
        // The pivot's motion: carried.
        assert_eq!(pivot, given.pivot);
        // The tip mass is a point mass: carried.
        assert_eq!(tip_mass.to_bits(), given.tip_mass.to_bits());
        // Carried as they are.
        assert_eq!(length.to_bits(), given.length.to_bits());
        assert_eq!(gravity.to_bits(), given.gravity.to_bits());
        // Continuum properties of the rope: carried.
        assert_eq!(axial_stiffness, given.axial_stiffness);
        assert_eq!(axial_damping.to_bits(), given.axial_damping.to_bits());
        assert_eq!(
            bending_stiffness.to_bits(),
            given.bending_stiffness.to_bits()
        );
        // Refined: the continuum's total mass and bending viscosity kept.
        assert_eq!(links, 160);
        assert_eq!(mass.to_bits(), (0.35 * 40.0 / 160.0_f64).to_bits());
        assert_eq!(damping.to_bits(), (3e-3 * 160.0 / 40.0_f64).to_bits());
        assert!((refined.total_mass() - chain.total_mass()).abs() < 1e-15);
        assert!((refined.bending_viscosity() - chain.bending_viscosity()).abs() < 1e-18);
        // And back.
        let back = refined.refined(40).unwrap();
        assert!((back.mass() - chain.mass()).abs() < 1e-15);
        assert!((back.damping() - chain.damping()).abs() < 1e-18);
        assert_eq!(back.length(), chain.length());
        assert_eq!(back.gravity(), chain.gravity());
    }

    #[test]
    fn the_energy_scale_counts_the_tip_mass() {
        let bare = Chain::new(with("chain.tip_mass", 0.0)).unwrap();
        let tipped = Chain::new(with("chain.tip_mass", 2.0)).unwrap();
        // n m = 5, g = 1, L = 1: M g L = 5, and 7 with M_t = 2.
        assert_eq!(bare.energy_scale(), 5.0);
        assert_eq!(tipped.energy_scale(), 7.0);
        let mut p = with("chain.tip_mass", 2.0);
        p.gravity = 0.0;
        assert_eq!(Chain::new(p).unwrap().energy_scale(), 7.0);
    }

    #[test]
    fn accessors_read_the_params() {
        let chain = Chain::report(7, 0.25).unwrap();
        let p = chain.params();
        assert_eq!(
            (
                chain.length(),
                chain.links(),
                chain.mass(),
                chain.gravity(),
                chain.damping()
            ),
            (p.length, p.links, p.mass, p.gravity, p.damping)
        );
        assert_eq!((p.links, p.damping), (7, 0.25));
    }

    #[test]
    fn the_links_cap_is_the_catenarys_and_its_message_states_it() {
        assert_eq!(LINKS_RANGE, format!("an integer in 1..={MAX_LINKS}"));
        assert!(Chain::report(MAX_LINKS, 0.0).is_ok());
        let e = Chain::report(MAX_LINKS + 1, 0.0).unwrap_err();
        assert_eq!(e.field, "chain.links");
    }

    /// The stiffest rod's damping rate is the mean rod's, exactly, for
    /// equal rods, and `r / min (m_i l_i^2)` for a profile: relative masses
    /// `(1, 1, 4, 2)` (mean 2) make the lightest rod half the mean rod
    /// (`m = 1`), so the rate is `r / (0.5 l^2)`, twice the mean's.
    #[test]
    fn the_stiffest_damping_rate_is_the_lightest_rods() {
        let mut p = with("chain.damping", 0.3);
        p.links = 4;
        let equal = Chain::new(p.clone()).unwrap();
        assert_eq!(equal.stiffest_damping_rate(), equal.damping_rate());
        p.profile.masses = Some(vec![1.0, 1.0, 4.0, 2.0]);
        let c = Chain::new(p).unwrap();
        let l = c.rod_length();
        let expected = 0.3 / (0.5 * l * l);
        assert!((c.stiffest_damping_rate() / expected - 1.0).abs() < 1e-14);
    }
}
