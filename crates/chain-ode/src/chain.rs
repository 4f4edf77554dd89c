//! The chain's physical parameters, validated once.

use std::borrow::Cow;
use std::fmt;

/// The largest number of rods of a chain (`chain.links`): the same cap as
/// the catenary's ([`catenary::MAX_LINKS`]), so that every chain has a
/// catenary start.
pub const MAX_LINKS: usize = catenary::MAX_LINKS;

/// A chain of `links` equal rigid rods pinned at the anchor `P0`.
///
/// Units are the user's (the report uses `L = 6`, `m = 0.2` per rod, `g = 1`).
/// `mass` is **per rod**, as in the report: at fixed `damping` the damping rate
/// `r / (m l^2)` grows like `n^2`, so changing `links` at fixed `damping` is not
/// a pure refinement.
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    /// Total length `L` (> 0).
    pub length: f64,
    /// Number of rods `n` (>= 1).
    pub links: usize,
    /// Mass of one rod `m` (> 0).
    pub mass: f64,
    /// Gravitational acceleration `g` (>= 0), pointing to -y.
    pub gravity: f64,
    /// Joint friction coefficient `r` (>= 0): torque `r (w_{i+1} - w_i)` between neighbours.
    pub damping: f64,
}

/// A parameter outside its accepted range. `Display` is one line naming the field.
#[derive(Clone, Debug, PartialEq)]
pub struct InvalidParameter {
    /// The field, by its scene path (e.g. `chain.links`).
    pub field: &'static str,
    /// What is accepted: a range a user can act on (for bounds that depend
    /// on other fields, with the numbers for this run).
    pub accepted: Cow<'static, str>,
    /// The value given, as text.
    pub got: String,
}

impl fmt::Display for InvalidParameter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: must be {} (got {})",
            self.field, self.accepted, self.got
        )
    }
}

impl std::error::Error for InvalidParameter {}

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
            got: got.to_string(),
        })
    }
}

/// The accepted range of `chain.links`, in words.
const LINKS_RANGE: &str = "an integer in 1..=1000000";

impl Chain {
    /// A validated chain.
    pub fn new(
        length: f64,
        links: usize,
        mass: f64,
        gravity: f64,
        damping: f64,
    ) -> Result<Self, InvalidParameter> {
        let chain = Self {
            length,
            links,
            mass,
            gravity,
            damping,
        };
        chain.validate()?;
        Ok(chain)
    }

    /// The report's chain: `L = 6`, `m = 0.2` per rod, `g = 1`.
    pub fn report(links: usize, damping: f64) -> Result<Self, InvalidParameter> {
        Self::new(6.0, links, 0.2, 1.0, damping)
    }

    /// Checks every field; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), InvalidParameter> {
        let finite_pos = |x: f64| x.is_finite() && x > 0.0;
        let finite_nonneg = |x: f64| x.is_finite() && x >= 0.0;
        check(
            finite_pos(self.length),
            "chain.length",
            "a finite number > 0",
            self.length,
        )?;
        check(
            (1..=MAX_LINKS).contains(&self.links),
            "chain.links",
            LINKS_RANGE,
            self.links,
        )?;
        check(
            finite_pos(self.mass),
            "chain.mass",
            "a finite number > 0",
            self.mass,
        )?;
        check(
            finite_nonneg(self.gravity),
            "chain.gravity",
            "a finite number >= 0",
            self.gravity,
        )?;
        check(
            finite_nonneg(self.damping),
            "chain.damping",
            "a finite number >= 0",
            self.damping,
        )
    }

    /// Rod length `l = L / n`.
    pub fn rod_length(&self) -> f64 {
        self.length / self.links as f64
    }

    /// Total mass `M = n m`.
    pub fn total_mass(&self) -> f64 {
        self.mass * self.links as f64
    }

    /// The chain's weight `M g`.
    pub fn weight(&self) -> f64 {
        self.total_mass() * self.gravity
    }

    /// Damping rate `gamma = r / (m l^2)` (1/time): the stiffness parameter.
    pub fn damping_rate(&self) -> f64 {
        self.damping / (self.mass * self.rod_length().powi(2))
    }

    /// `g / l` (1/time^2).
    pub fn gravity_rate(&self) -> f64 {
        self.gravity / self.rod_length()
    }

    /// Energy scale `M g L`, against which energy errors are judged.
    pub fn energy_scale(&self) -> f64 {
        let w = self.weight();
        if w > 0.0 {
            w * self.length
        } else {
            self.total_mass() * self.length.powi(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_each_bad_field_by_name() {
        let bad = [
            (Chain::new(-1.0, 5, 1.0, 1.0, 0.0), "chain.length"),
            (Chain::new(f64::NAN, 5, 1.0, 1.0, 0.0), "chain.length"),
            (Chain::new(1.0, 0, 1.0, 1.0, 0.0), "chain.links"),
            (Chain::new(1.0, 5, 0.0, 1.0, 0.0), "chain.mass"),
            (Chain::new(1.0, 5, 1.0, f64::INFINITY, 0.0), "chain.gravity"),
            (Chain::new(1.0, 5, 1.0, 1.0, -1e-3), "chain.damping"),
            (Chain::new(1.0, 5, 1.0, 1.0, f64::NAN), "chain.damping"),
        ];
        for (res, field) in bad {
            let e = res.unwrap_err();
            assert_eq!(e.field, field);
            assert!(e.to_string().starts_with(field));
            assert!(!e.to_string().contains('\n'));
        }
        assert!(Chain::report(50, 5e-4).is_ok());
    }

    #[test]
    fn the_links_cap_is_the_catenarys_and_its_message_states_it() {
        assert_eq!(LINKS_RANGE, format!("an integer in 1..={MAX_LINKS}"));
        assert!(Chain::report(MAX_LINKS, 0.0).is_ok());
        let e = Chain::report(MAX_LINKS + 1, 0.0).unwrap_err();
        assert_eq!(e.field, "chain.links");
    }
}
