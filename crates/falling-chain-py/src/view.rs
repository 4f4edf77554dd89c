//! `falling_chain.view`: runs as `falling-chain view`'s HTML page.

use std::path::PathBuf;

use ::fc_scene::atomic::{check_writable, write_atomic};
use ::fc_scene::Error;
use ::fc_viewer::{self as viewer, DATA_BUDGET_BYTES};
use pyo3::prelude::*;

use crate::convert::value_error;
use crate::run::Run;

/// Writes the runs (one `Run` or a list of 1 to 8) as one self-contained
/// HTML page at `path` (`FILE.html`), as `falling-chain view` does for
/// scenes: the chains to scale, play, pause and scrub, the tip speed and
/// the energy balance, each run's summary. Returns `path`. Bad input
/// raises ValueError naming `runs` or `path`; nothing is written then.
#[pyfunction]
pub fn view(py: Python<'_>, runs: &Bound<'_, PyAny>, path: PathBuf) -> PyResult<PathBuf> {
    let runs: Vec<PyRef<'_, Run>> = match runs.extract::<PyRef<'_, Run>>() {
        Ok(run) => vec![run],
        Err(_) => runs.extract().map_err(|_| {
            value_error(Error::field(
                "runs",
                "must be a Run or a list of 1 to 8 Runs",
            ))
        })?,
    };
    viewer::check_run_count("runs", runs.len()).map_err(value_error)?;
    viewer::check_page_path("path", &path).map_err(value_error)?;
    for run in &runs {
        viewer::check_chain("runs", run.chain()).map_err(value_error)?;
    }
    check_writable("path", &path).map_err(value_error)?;
    let budget = DATA_BUDGET_BYTES / runs.len();
    let mut pages = runs
        .iter()
        .map(|r| r.view_run(py, budget))
        .collect::<PyResult<Vec<_>>>()?;
    for k in 1..pages.len() {
        if pages[..k].iter().any(|r| r.label == pages[k].label) {
            pages[k].label = format!("{} #{}", pages[k].label, k + 1);
        }
    }
    let title = pages
        .iter()
        .map(|r| r.label.as_str())
        .collect::<Vec<_>>()
        .join(" vs ");
    let page = viewer::fitted_page("runs", &title, &mut pages).map_err(value_error)?;
    write_atomic("path", &path, |w| w.write_all(page.as_bytes())).map_err(value_error)?;
    Ok(path)
}
