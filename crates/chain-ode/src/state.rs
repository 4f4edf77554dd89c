//! Chain states and the starts that make them.

use catenary::CatenaryError;

use crate::chain::{check, number_text, Chain};
use crate::kinematics::Vec2;
use fc_methods::InvalidParameter;
use std::f64::consts::FRAC_PI_2;
use std::fmt;

/// A configuration and its rates: absolute angles `phi_i` (rad, from the
/// horizontal, counter-clockwise) and `w_i = dphi_i/dt` (rad/time), with the
/// pivot `anchor` (`P0`) that places them in the plane.
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// The pivot `P0`.
    pub anchor: Vec2,
    /// Angles `phi_1..phi_n`.
    pub angles: Vec<f64>,
    /// Rates `w_1..w_n`.
    pub rates: Vec<f64>,
}

/// The largest `|phi_i|` a start may give (rad): two turns, `4 pi`. Every
/// configuration has angles within one turn; a larger angle only costs
/// precision (at `1e300` the rod cannot turn at all).
pub const MAX_START_ANGLE: f64 = 4.0 * std::f64::consts::PI;

/// How the chain is laid out at `t = 0` (always at rest unless `Angles` gives rates).
#[derive(Clone, Debug, PartialEq)]
pub enum Start {
    /// Straight from `p0` to `p1`; needs `|p1 - p0| = L`.
    Stretched { p0: Vec2, p1: Vec2 },
    /// The exact discrete equilibrium of the rods pinned at `p0` and `p1`.
    Catenary { p0: Vec2, p1: Vec2 },
    /// `down` rods hanging from `p0` (default `n / 2`), one horizontal, the rest up.
    Folded { p0: Vec2, down: Option<usize> },
    /// Explicit angles, and optionally rates (default zero).
    Angles {
        p0: Vec2,
        angles: Vec<f64>,
        rates: Option<Vec<f64>>,
    },
}

/// Why a start could not be built. `Display` is one line naming the field.
#[derive(Clone, Debug, PartialEq)]
pub enum StartError {
    /// A parameter out of range.
    Parameter(InvalidParameter),
    /// The catenary could not be built.
    Catenary(CatenaryError),
}

impl fmt::Display for StartError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Parameter(e) => e.fmt(f),
            Self::Catenary(e) => write!(f, "start: {e}"),
        }
    }
}

impl std::error::Error for StartError {}

impl From<InvalidParameter> for StartError {
    fn from(e: InvalidParameter) -> Self {
        Self::Parameter(e)
    }
}

fn finite_point(p: Vec2, field: &'static str) -> Result<(), InvalidParameter> {
    check(
        p.iter().all(|x| x.is_finite()),
        field,
        "a pair of finite numbers",
        format!("[{}, {}]", number_text(p[0]), number_text(p[1])),
    )
}

impl Start {
    /// The pivot `P0`.
    pub fn anchor(&self) -> Vec2 {
        match self {
            Self::Stretched { p0, .. }
            | Self::Catenary { p0, .. }
            | Self::Folded { p0, .. }
            | Self::Angles { p0, .. } => *p0,
        }
    }

    /// Where the free end is held before release (`P1`), for every start.
    pub fn release_point(&self, chain: &Chain) -> Result<Vec2, StartError> {
        let s = self.state(chain)?;
        Ok(crate::kinematics::tip(chain, s.anchor, &s.angles))
    }

    /// The initial state of `chain` (a `Chain` is valid by construction).
    pub fn state(&self, chain: &Chain) -> Result<State, StartError> {
        let n = chain.links();
        let p0 = self.anchor();
        finite_point(p0, "start.p0")?;
        let (angles, rates) = match self {
            Self::Stretched { p1, .. } => {
                finite_point(*p1, "start.p1")?;
                let (dx, dy) = (p1[0] - p0[0], p1[1] - p0[1]);
                let span = dx.hypot(dy);
                check(
                    (span - chain.length()).abs() <= 1e-9 * chain.length(),
                    "start.p1",
                    "at distance chain.length from start.p0 for a stretched start",
                    format!(
                        "|P1 - P0| = {}, L = {}",
                        number_text(span),
                        number_text(chain.length())
                    ),
                )?;
                (vec![dy.atan2(dx); n], vec![0.0; n])
            }
            Self::Catenary { p1, .. } => {
                finite_point(*p1, "start.p1")?;
                let angles = match chain.rods() {
                    // Unequal rods: the minimum of the convex complementary
                    // energy (catenary::discrete_equilibrium_rods).
                    Some(rods) => {
                        catenary::discrete_equilibrium_rods(
                            p0,
                            *p1,
                            chain.length(),
                            &rods.mass,
                            &rods.length,
                        )
                        .map_err(StartError::Catenary)?
                        .angles
                    }
                    None => {
                        catenary::discrete_equilibrium(p0, *p1, chain.length(), n)
                            .map_err(StartError::Catenary)?
                            .angles
                    }
                };
                (angles, vec![0.0; n])
            }
            Self::Folded { down, .. } => {
                let down = down.unwrap_or(n / 2);
                // One rod cannot fold: the error is about chain.links, not
                // about a start.down that was not even given.
                check(
                    n >= 2,
                    "chain.links",
                    "an integer >= 2 for a folded start",
                    n,
                )?;
                check(
                    down < n,
                    "start.down",
                    format!("an integer in 0..={} (chain.links - 1)", n - 1),
                    down,
                )?;
                let angles = (0..n)
                    .map(|i| match i.cmp(&down) {
                        std::cmp::Ordering::Less => -FRAC_PI_2,
                        std::cmp::Ordering::Equal => 0.0,
                        std::cmp::Ordering::Greater => FRAC_PI_2,
                    })
                    .collect();
                (angles, vec![0.0; n])
            }
            Self::Angles { angles, rates, .. } => {
                check(
                    angles.len() == n,
                    "start.angles",
                    "a list of chain.links angles",
                    format!("{} values", angles.len()),
                )?;
                check(
                    angles.iter().all(|a| a.is_finite()),
                    "start.angles",
                    "finite numbers",
                    "a non-finite value",
                )?;
                // An angle so large that its rounding unit is a visible
                // fraction of a turn freezes its rod (`phi + dphi == phi`
                // at 1e300): bounded to two turns either way, which holds
                // every configuration.
                let worst = angles.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
                check(
                    worst <= MAX_START_ANGLE,
                    "start.angles",
                    "angles with |phi| <= 4 pi rad (two turns)",
                    worst,
                )?;
                let rates = rates.clone().unwrap_or_else(|| vec![0.0; n]);
                check(
                    rates.len() == n && rates.iter().all(|a| a.is_finite()),
                    "start.rates",
                    "a list of chain.links finite numbers",
                    format!("{} values", rates.len()),
                )?;
                (angles.clone(), rates)
            }
        };
        Ok(State {
            anchor: p0,
            angles,
            rates,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::tip;

    #[test]
    fn folded_start_matches_the_report() {
        let chain = Chain::report(50, 1e-3).unwrap();
        let s = Start::Folded {
            p0: [0.0, 0.0],
            down: None,
        }
        .state(&chain)
        .unwrap();
        let l = chain.rod_length();
        let t = tip(&chain, s.anchor, &s.angles);
        assert!(
            (t[0] - l).abs() < 1e-12 && (t[1] + l).abs() < 1e-12,
            "{t:?}"
        );
        assert_eq!(s.angles.iter().filter(|a| **a < 0.0).count(), 25);
        assert_eq!(s.angles.iter().filter(|a| **a > 0.0).count(), 24);
    }

    #[test]
    fn a_folded_start_names_the_field_that_is_wrong() {
        let folded = |down| Start::Folded {
            p0: [0.0, 0.0],
            down,
        };
        // One rod: chain.links, whether start.down was given or not.
        let one = Chain::report(1, 0.0).unwrap();
        for down in [None, Some(0)] {
            let e = folded(down).state(&one).unwrap_err().to_string();
            assert_eq!(
                e,
                "chain.links: must be an integer >= 2 for a folded start (got 1)"
            );
        }
        let ten = Chain::report(10, 0.0).unwrap();
        let e = folded(Some(10)).state(&ten).unwrap_err().to_string();
        assert_eq!(
            e,
            "start.down: must be an integer in 0..=9 (chain.links - 1) (got 10)"
        );
        assert!(folded(Some(9)).state(&ten).is_ok());
        assert!(folded(None).state(&Chain::report(2, 0.0).unwrap()).is_ok());
    }

    #[test]
    fn stretched_needs_full_length() {
        let chain = Chain::report(10, 0.0).unwrap();
        let bad = Start::Stretched {
            p0: [0.0, 0.0],
            p1: [5.0, 0.0],
        };
        let e = bad.state(&chain).unwrap_err();
        assert!(e.to_string().starts_with("start.p1"), "{e}");
        let good = Start::Stretched {
            p0: [1.0, 1.0],
            p1: [1.0, 7.0],
        };
        let s = good.state(&chain).unwrap();
        assert!(s.angles.iter().all(|a| (a - FRAC_PI_2).abs() < 1e-15));
    }

    #[test]
    fn catenary_start_ends_at_p1() {
        let chain = Chain::report(25, 1e-3).unwrap();
        let start = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [5.0, 1.0],
        };
        let p1 = start.release_point(&chain).unwrap();
        assert!((p1[0] - 5.0).abs() < 1e-11 && (p1[1] - 1.0).abs() < 1e-11);
    }
}
