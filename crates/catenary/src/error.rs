//! Why a catenary could not be built.

use std::fmt;

/// Error of [`Catenary::through`](crate::Catenary::through) and
/// [`discrete_equilibrium`](crate::discrete_equilibrium). `Display` is one line
/// that names the offending field and the accepted range.
#[derive(Debug, Clone, PartialEq)]
pub enum CatenaryError {
    /// An input is NaN or infinite (`field` is `"p0"`, `"p1"` or `"length"`).
    NonFinite { field: &'static str, value: f64 },
    /// `length <= 0`.
    NonPositiveLength { length: f64 },
    /// `links == 0`.
    NoLinks,
    /// The chain cannot reach or cannot sag: `length < |P1 - P0|`, or
    /// `length <= |P1 - P0| (1 + 1e-12)` where a sagging chain is required.
    TooShort { length: f64, distance: f64 },
    /// `x1 == x0` with a slack chain: no catenary (`distance = |y1 - y0|`).
    Vertical { length: f64, distance: f64 },
    /// `links == 1` but the chain is not taut (`|P1 - P0| != length`).
    SingleRod { length: f64, distance: f64 },
    /// A solver did not reach the required accuracy.
    NoConvergence {
        solver: &'static str,
        iterations: u64,
        residual: f64,
    },
}

impl fmt::Display for CatenaryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NonFinite { field, value } => {
                write!(f, "{field}: must be finite (got {value})")
            }
            Self::NonPositiveLength { length } => {
                write!(f, "length: must be > 0 (got {length})")
            }
            Self::NoLinks => write!(f, "links: must be >= 1 (got 0)"),
            Self::TooShort { length, distance } if length < distance => write!(
                f,
                "length: must exceed the anchor distance |P1 - P0| = {distance} (got {length})"
            ),
            Self::TooShort { length, distance } => write!(
                f,
                "length: must exceed the anchor distance |P1 - P0| = {distance} by more than \
                 1e-12 relative for a hanging chain (got {length}); a taut chain is straight: \
                 use the stretched start"
            ),
            Self::Vertical { length, distance } => write!(
                f,
                "p1: must not lie straight above or below p0 (x1 == x0, |y1 - y0| = {distance} \
                 < length = {length}): a vertical chain is an unstable equilibrium of the rod \
                 model; use the folded start (start.kind = \"folded\")"
            ),
            Self::SingleRod { length, distance } => write!(
                f,
                "links: must be >= 2 for a hanging chain; a single rod needs |P1 - P0| = length \
                 = {length} (got |P1 - P0| = {distance})"
            ),
            Self::NoConvergence {
                solver,
                iterations,
                residual,
            } => write!(
                f,
                "solver: {solver} did not converge after {iterations} iterations \
                 (residual {residual:e})"
            ),
        }
    }
}

impl std::error::Error for CatenaryError {}

/// Checks shared by both constructors: finite inputs, `length > 0`,
/// `length >= |P1 - P0|`. Returns `|P1 - P0|`.
pub(crate) fn check_inputs(p0: [f64; 2], p1: [f64; 2], length: f64) -> Result<f64, CatenaryError> {
    for (field, p) in [("p0", p0), ("p1", p1)] {
        if let Some(&value) = p.iter().find(|v| !v.is_finite()) {
            return Err(CatenaryError::NonFinite { field, value });
        }
    }
    if !length.is_finite() {
        return Err(CatenaryError::NonFinite {
            field: "length",
            value: length,
        });
    }
    if length <= 0.0 {
        return Err(CatenaryError::NonPositiveLength { length });
    }
    let distance = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
    if !distance.is_finite() {
        return Err(CatenaryError::NonFinite {
            field: "p1",
            value: distance,
        });
    }
    if distance > length + TAUT * length {
        return Err(CatenaryError::TooShort { length, distance });
    }
    Ok(distance)
}

/// Relative tolerance within which `|P1 - P0| == length` counts as taut.
pub(crate) const TAUT: f64 = 1e-12;
