//! Why a catenary could not be built.

use std::fmt;

/// The input of a catenary that an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Input {
    /// The pinned end `P0`.
    P0,
    /// The other end `P1`.
    P1,
    /// The chain's length `L`.
    Length,
    /// The number of rods `n`.
    Links,
}

impl Input {
    /// Its name in messages: `p0`, `p1`, `length` or `links`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::P0 => "p0",
            Self::P1 => "p1",
            Self::Length => "length",
            Self::Links => "links",
        }
    }
}

impl fmt::Display for Input {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// Error of [`Catenary::through`](crate::Catenary::through) and
/// [`discrete_equilibrium`](crate::discrete_equilibrium). Each variant holds
/// the values it is about; [`input`](Self::input) says which input is wrong
/// and [`reason`](Self::reason) what was accepted and what was got, so that
/// a caller can name the input its own way. `Display` is one line: the
/// input's name (or `solver`), then the reason.
#[derive(Debug, Clone, PartialEq)]
pub enum CatenaryError {
    /// An input is NaN or infinite (`P0`, `P1` or the length).
    NonFinite { input: Input, value: f64 },
    /// A finite input outside [`MAX_MAGNITUDE`]: a coordinate of `P0` or
    /// `P1` with `|x| > MAX_MAGNITUDE`, or a length above it or below
    /// [`MIN_LENGTH`]. Past these, sums and products of the inputs overflow
    /// or underflow before any equation is solved.
    OutOfRange { input: Input, value: f64 },
    /// `links > MAX_LINKS`.
    TooManyLinks { links: usize },
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

impl CatenaryError {
    /// The input the error is about; `None` when no input is wrong (a
    /// solver did not converge).
    pub fn input(&self) -> Option<Input> {
        match *self {
            Self::NonFinite { input, .. } | Self::OutOfRange { input, .. } => Some(input),
            Self::NonPositiveLength { .. } | Self::TooShort { .. } => Some(Input::Length),
            Self::NoLinks | Self::TooManyLinks { .. } | Self::SingleRod { .. } => {
                Some(Input::Links)
            }
            Self::Vertical { .. } => Some(Input::P1),
            Self::NoConvergence { .. } => None,
        }
    }

    /// What is wrong, without the input's name: what is accepted and what
    /// was got.
    pub fn reason(&self) -> String {
        match *self {
            Self::NonFinite { value, .. } => format!("must be finite (got {value})"),
            Self::OutOfRange {
                input: Input::Length,
                value,
            } => format!("must be in [{MIN_LENGTH:e}, {MAX_MAGNITUDE:e}] (got {value:e})"),
            Self::OutOfRange { value, .. } => format!(
                "must have coordinates in [-{MAX_MAGNITUDE:e}, {MAX_MAGNITUDE:e}] (got {value:e})"
            ),
            Self::TooManyLinks { links } => {
                format!("must be an integer in 1..={MAX_LINKS} (got {links})")
            }
            Self::NonPositiveLength { length } => format!("must be > 0 (got {length})"),
            Self::NoLinks => format!("must be an integer in 1..={MAX_LINKS} (got 0)"),
            Self::TooShort { length, distance } if length < distance => {
                format!("must exceed the anchor distance |P1 - P0| = {distance} (got {length})")
            }
            Self::TooShort { length, distance } => format!(
                "must exceed the anchor distance |P1 - P0| = {distance} by more than 1e-12 \
                 relative for a hanging chain (got {length}); a taut chain is straight: use \
                 the stretched start"
            ),
            Self::Vertical { length, distance } => format!(
                "must not lie straight above or below p0 (x1 == x0, |y1 - y0| = {distance} \
                 < length = {length}): a vertical chain is an unstable equilibrium of the rod \
                 model; use the folded start"
            ),
            Self::SingleRod { length, distance } => format!(
                "must be >= 2 for a hanging chain; a single rod needs |P1 - P0| = length \
                 = {length} (got |P1 - P0| = {distance})"
            ),
            Self::NoConvergence {
                solver,
                iterations,
                residual,
            } => format!(
                "{solver} did not converge after {iterations} iterations (residual {residual:e})"
            ),
        }
    }
}

impl fmt::Display for CatenaryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.input() {
            Some(input) => write!(f, "{input}: {}", self.reason()),
            None => write!(f, "solver: {}", self.reason()),
        }
    }
}

impl std::error::Error for CatenaryError {}

/// The largest number of rods of a discrete catenary (and of a chain in a
/// scene): `10^6`. Larger counts are refused before anything is allocated.
pub const MAX_LINKS: usize = 1_000_000;

/// The largest magnitude accepted of an anchor coordinate or of the length
/// (length units): `1e150`. Sums, differences and squares of such inputs
/// stay finite.
pub const MAX_MAGNITUDE: f64 = 1e150;

/// The smallest length accepted (length units): `1e-150`, so that the
/// squares of lengths and distances stay normal numbers.
pub const MIN_LENGTH: f64 = 1e-150;

/// Checks shared by both constructors: finite inputs within
/// [`MAX_MAGNITUDE`], `MIN_LENGTH <= length`, `length >= |P1 - P0|`.
/// Returns `|P1 - P0|`.
pub(crate) fn check_inputs(p0: [f64; 2], p1: [f64; 2], length: f64) -> Result<f64, CatenaryError> {
    for (input, p) in [(Input::P0, p0), (Input::P1, p1)] {
        if let Some(&value) = p.iter().find(|v| !v.is_finite()) {
            return Err(CatenaryError::NonFinite { input, value });
        }
        if let Some(&value) = p.iter().find(|v| v.abs() > MAX_MAGNITUDE) {
            return Err(CatenaryError::OutOfRange { input, value });
        }
    }
    if !length.is_finite() {
        return Err(CatenaryError::NonFinite {
            input: Input::Length,
            value: length,
        });
    }
    if length <= 0.0 {
        return Err(CatenaryError::NonPositiveLength { length });
    }
    if !(MIN_LENGTH..=MAX_MAGNITUDE).contains(&length) {
        return Err(CatenaryError::OutOfRange {
            input: Input::Length,
            value: length,
        });
    }
    // Finite: every coordinate is at most 1e150 in magnitude.
    let distance = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
    if distance > length + TAUT * length {
        return Err(CatenaryError::TooShort { length, distance });
    }
    Ok(distance)
}

/// Relative tolerance within which `|P1 - P0| == length` counts as taut.
pub(crate) const TAUT: f64 = 1e-12;
