//! A parameter outside its range, with its fields ([`InvalidParameter`]):
//! the error of a method's name that is not one ([`crate::Method`]'s
//! `FromStr`), and of every bound that chain-ode's run layer and models
//! check (it re-exports it). The wording for users is the caller's.

use std::borrow::Cow;
use std::fmt;

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
