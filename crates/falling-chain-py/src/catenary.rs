//! `falling_chain.catenary`: what `falling-chain catenary --json` prints.

use ::fc_scene::{CatenaryNames, CatenaryReport, Error};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt};

use crate::convert::{array1, echo, json_to_dict, points, value_error, MAX_LINKS};

/// The inputs as Python calls them (the CLI's flags without `--`).
const NAMES: CatenaryNames = CatenaryNames {
    p0: "p0",
    p1: "p1",
    length: "length",
    links: "links",
    other: "catenary",
};

/// A point `(x, y)` from any sequence of two numbers.
fn point(value: &Bound<'_, PyAny>, field: &str) -> PyResult<[f64; 2]> {
    value.extract::<[f64; 2]>().map_err(|_| {
        value_error(Error::field(
            field,
            format!("expected two numbers (x, y) (got {})", echo(value)),
        ))
    })
}

/// The hanging chain between `p0` and `p1` with arc length `length`: the
/// dict `falling-chain catenary --json` prints, with the continuous catenary
/// `y = a cosh((x - x0)/a) + c` (`a`, `x0`, `c`, `vertex`, `lowest_point`)
/// and, with `links`, the exact static equilibrium of that many rods:
/// `angles` (numpy, shape (links,)), `joints` (numpy, shape (links + 1, 2)),
/// `end_error`, `alpha`, `beta`.
///
/// Raises ValueError naming the input (`length: must exceed ...`).
#[pyfunction]
#[pyo3(signature = (p0, p1, length, links=None))]
pub fn catenary<'py>(
    py: Python<'py>,
    p0: &Bound<'_, PyAny>,
    p1: &Bound<'_, PyAny>,
    length: f64,
    links: Option<&Bound<'_, PyInt>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (p0, p1) = (point(p0, "p0")?, point(p1, "p1")?);
    // Any int: one that fits no usize is out of the scene's range.
    let links = links
        .map(|n| {
            n.extract::<usize>().map_err(|_| {
                value_error(Error::field(
                    "links",
                    format!("must be an integer in 1..={MAX_LINKS} (got {})", echo(n)),
                ))
            })
        })
        .transpose()?;
    let report = py
        .detach(|| CatenaryReport::compute(p0, p1, length, links, &NAMES))
        .map_err(value_error)?;
    let out = json_to_dict(py, &report.to_json())?;
    if let Some(d) = report.discrete {
        out.set_item("angles", array1(py, d.angles)?)?;
        out.set_item("joints", points(py, &d.joints)?)?;
    }
    Ok(out)
}
