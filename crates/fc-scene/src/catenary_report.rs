//! What `falling-chain catenary` prints: the continuous catenary through two
//! anchors and, for a number of rods, the exact discrete equilibrium.

use std::fmt;

use catenary::{discrete_equilibrium, joints, Catenary};
use serde::{Deserialize, Serialize};

use crate::error::{CatenaryNames, Error};

/// The bounds of a catenary's inputs, checked by the catenary crate with
/// errors naming the input: at most `MAX_LINKS` rods (the scenes' cap on
/// `chain.links`), coordinates and length within `MAX_MAGNITUDE`, length at
/// least `MIN_LENGTH`.
pub use catenary::{MAX_LINKS, MAX_MAGNITUDE, MIN_LENGTH};

/// The discrete equilibrium of `links` rods between the same anchors.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DiscreteReport {
    pub links: usize,
    /// `phi_1..phi_n` (rad from the horizontal).
    pub angles: Vec<f64>,
    /// `|r_n - p1|`.
    pub end_error: f64,
    /// `tan phi_i = alpha + (i - 1/2) beta` (in the frame running towards +x).
    pub alpha: f64,
    pub beta: f64,
    /// Joint positions `r_0 = p0 .. r_n`.
    pub joints: Vec<[f64; 2]>,
}

/// The continuous catenary `y = a cosh((x - x0)/a) + c` through `p0`, `p1`
/// with arc length `length`, and optionally the discrete equilibrium.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CatenaryReport {
    pub p0: [f64; 2],
    pub p1: [f64; 2],
    pub length: f64,
    pub a: f64,
    pub x0: f64,
    pub c: f64,
    /// `(x0, a + c)`, possibly outside the span.
    pub vertex: [f64; 2],
    /// The lowest point of the hanging segment.
    pub lowest_point: [f64; 2],
    #[serde(flatten, skip_serializing_if = "Option::is_none")]
    pub discrete: Option<DiscreteReport>,
}

impl CatenaryReport {
    /// The names of the inputs on the command line.
    pub const CLI_NAMES: CatenaryNames = CatenaryNames {
        p0: "--p0",
        p1: "--p1",
        length: "--length",
        links: "--links",
        other: "catenary",
    };

    /// Computes the report; errors name the inputs as in `names`.
    pub fn compute(
        p0: [f64; 2],
        p1: [f64; 2],
        length: f64,
        links: Option<usize>,
        names: &CatenaryNames,
    ) -> Result<Self, Error> {
        let err = |e| Error::from_catenary(&e, names);
        let cat = Catenary::through(p0, p1, length).map_err(err)?;
        let discrete = match links {
            None => None,
            Some(n) => {
                let eq = discrete_equilibrium(p0, p1, length, n).map_err(err)?;
                Some(DiscreteReport {
                    links: n,
                    joints: joints(p0, length, &eq.angles),
                    angles: eq.angles,
                    end_error: eq.end_error,
                    alpha: eq.alpha,
                    beta: eq.beta,
                })
            }
        };
        Ok(Self {
            p0,
            p1,
            length,
            a: cat.a,
            x0: cat.x0,
            c: cat.c,
            vertex: cat.vertex(),
            lowest_point: cat.lowest_point(),
            discrete,
        })
    }

    /// One line of JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|e| {
            serde_json::json!({ "error": format!("the report did not serialise: {e}") }).to_string()
        })
    }
}

impl fmt::Display for CatenaryReport {
    /// A short table.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "catenary y = a cosh((x - x0)/a) + c from P0 ({}, {}) to P1 ({}, {}), L = {}",
            self.p0[0], self.p0[1], self.p1[0], self.p1[1], self.length
        )?;
        writeln!(f, "  a             {:.12}", self.a)?;
        writeln!(f, "  x0            {:.12}", self.x0)?;
        writeln!(f, "  c             {:.12}", self.c)?;
        writeln!(
            f,
            "  vertex        ({:.9}, {:.9})",
            self.vertex[0], self.vertex[1]
        )?;
        write!(
            f,
            "  lowest point  ({:.9}, {:.9})",
            self.lowest_point[0], self.lowest_point[1]
        )?;
        if let Some(d) = &self.discrete {
            writeln!(f)?;
            writeln!(f, "discrete equilibrium of {} rods", d.links)?;
            writeln!(f, "  alpha         {:.12}", d.alpha)?;
            writeln!(f, "  beta          {:.12}", d.beta)?;
            write!(f, "  end error     {:.3e}", d.end_error)?;
        }
        Ok(())
    }
}
