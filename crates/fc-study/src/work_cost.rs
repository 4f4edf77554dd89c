//! The work of a run in one currency: right-hand-side equivalents, with
//! BDF's residuals (each followed by a Newton solve), Jacobians and LU
//! factorisations weighted by their cost measured on this machine
//! ([`chain_ode::unit_costs`]) relative to one right-hand side of the O(n)
//! recursion. The table (`<id>-cost-timing.csv` of a work-precision
//! figure, wall times all: written only by `--timings`) is
//! `method,unit,seconds_per_call,rhs_equivalents`; the drawing reads the
//! weights back with [`Weights::from_table`].

use std::fmt::Write as _;

use chain_ode::{unit_costs, Chain, State, UnitCosts};

use fc_csv::format::exp_digits;
use fc_csv::table::Table;

/// The cost table of `chain` at `state` (see the module doc), or why not.
pub fn csv_text(chain: &Chain, state: &State) -> Result<String, String> {
    let c: UnitCosts = unit_costs(chain, state)
        .ok_or("unit costs: the Newton matrix could not be built or factorised")?;
    let mut s = String::from("method,unit,seconds_per_call,rhs_equivalents\n");
    for (method, unit, secs) in [
        ("explicit", "rhs", c.rhs),
        ("bdf", "residual_and_solve", c.bdf_residual),
        ("bdf", "jacobian", c.bdf_jacobian),
        ("bdf", "lu", c.bdf_lu),
        ("bdf-dense", "residual_and_solve", c.dense_residual),
        ("bdf-dense", "jacobian", c.dense_jacobian),
        ("bdf-dense", "lu", c.dense_lu),
    ] {
        let _ = writeln!(
            s,
            "{method},{unit},{},{}",
            exp_digits(secs, 3),
            exp_digits(secs / c.rhs, 3)
        );
    }
    Ok(s)
}

/// The weights of one implicit method's units, in right-hand sides.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitWeights {
    /// Per counted right-hand side (residual) evaluation, with its solve.
    pub residual: f64,
    pub jacobian: f64,
    pub lu: f64,
}

impl UnitWeights {
    /// The work of `rhs` evaluations, `jac` Jacobians and `lu`
    /// factorisations, in right-hand sides.
    pub fn work(&self, rhs: f64, jac: f64, lu: f64) -> f64 {
        rhs * self.residual + jac * self.jacobian + lu * self.lu
    }
}

/// The weights of `bdf` and `bdf-dense`, read back from a cost table.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Weights {
    pub bdf: UnitWeights,
    pub dense: UnitWeights,
}

impl Weights {
    /// From the table of [`csv_text`] as read back.
    pub fn from_table(t: &Table) -> Result<Weights, String> {
        let (method, unit, w) = (
            t.strs("method")?,
            t.strs("unit")?,
            t.nums("rhs_equivalents")?,
        );
        let get = |m: &str, u: &str| {
            (0..t.len())
                .find(|&k| method[k] == m && unit[k] == u)
                .map(|k| w[k])
                .filter(|x| x.is_finite() && *x > 0.0)
                .ok_or_else(|| format!("{}: no positive weight of {m} {u}", t.name))
        };
        let of = |m: &str| -> Result<UnitWeights, String> {
            Ok(UnitWeights {
                residual: get(m, "residual_and_solve")?,
                jacobian: get(m, "jacobian")?,
                lu: get(m, "lu")?,
            })
        };
        Ok(Weights {
            bdf: of("bdf")?,
            dense: of("bdf-dense")?,
        })
    }

    /// The weights of `method`'s units: `bdf-dense`'s, `bdf`'s (also for
    /// `auto` when it factorised: it runs the O(n) BDF), else none (an
    /// explicit run: one per right-hand side).
    pub fn of(&self, method: &str, factorised: bool) -> Option<UnitWeights> {
        match method {
            "bdf-dense" => Some(self.dense),
            "bdf" | "check-bdf" => Some(self.bdf),
            "auto" if factorised => Some(self.bdf),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use chain_ode::{ChainParams, Start};

    /// The table reads back into the weights it was written with, each
    /// unit over the right-hand side's time, and a weighted work adds up.
    #[test]
    fn the_cost_table_reads_back_and_weighs_work() {
        let chain = Chain::new(ChainParams {
            links: 20,
            ..ChainParams::default()
        })
        .unwrap();
        let start = Start::Folded {
            p0: [0.0, 0.0],
            down: None,
        };
        let csv = csv_text(&chain, &start.state(&chain).unwrap()).unwrap();
        let t = Table::parse("cost", &csv).unwrap();
        let w = Weights::from_table(&t).unwrap();
        let secs = t.nums("seconds_per_call").unwrap();
        let rhs = secs[0];
        // Written to 4 significant digits: the weights agree to 1e-3.
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-3 * b;
        assert!(close(w.bdf.lu, secs[3] / rhs), "{w:?}");
        assert!(close(w.dense.jacobian, secs[5] / rhs), "{w:?}");
        let u = UnitWeights {
            residual: 2.0,
            jacobian: 10.0,
            lu: 100.0,
        };
        assert_eq!(u.work(5.0, 2.0, 1.0), 10.0 + 20.0 + 100.0);
        assert_eq!(w.of("dopri5", false), None);
        assert_eq!(w.of("auto", false), None);
        assert_eq!(w.of("auto", true), Some(w.bdf));
        assert_eq!(w.of("bdf-dense", true), Some(w.dense));
        // A table without a unit is refused.
        let short = csv.lines().take(4).collect::<Vec<_>>().join("\n");
        assert!(Weights::from_table(&Table::parse("cost", &short).unwrap()).is_err());
    }
}
