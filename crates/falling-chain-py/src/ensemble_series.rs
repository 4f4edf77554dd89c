//! `falling_chain.ensemble_series`: `falling-chain ensemble --out-series`,
//! its time series as numpy arrays.

use ::fc_batch::budget::{check_budget, Budget};
use ::fc_study::ensemble::EnsembleOptions;
use ::fc_study::ensemble_series::{self as core, STATS};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{array1, json_to_dict, value_error};
use crate::interrupt::run_interruptible;
use crate::scene::PyScene;
use crate::sweep::jobs_of;

/// `scene` run from `members` perturbed starts, as `ensemble` runs it, and
/// the statistics over the members that ended ok of every output at each
/// output time (the members share them): `falling-chain ensemble
/// --out-series` as a dict. `t` (times,); `members` (how many ended ok and
/// are in the statistics); `series`, by output (`tip_x`, `tip_y`,
/// `tip_vx`, `tip_vy`, `tip_speed`, `energy`, `dissipated`, `pivot_x`,
/// `pivot_y`, and with a floor `floor_x`, `floor_y`, `landed_weight`,
/// `landed_length`), a dict of arrays `mean`, `sem` (standard error of
/// the mean), `sd`, `min`, `max`, each (times,); and `ensemble`, what
/// `ensemble(...)` returns for the same arguments. The statistics are the
/// same on any number of `jobs`, bit for bit. ValueError as `ensemble`,
/// and naming `members` when the series would take more than 1 GiB.
/// Releases the GIL; Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (scene, *, members=None, spread=1e-3, seed=None, budget=None, jobs=None))]
pub fn ensemble_series<'py>(
    py: Python<'py>,
    scene: &Bound<'_, PyScene>,
    members: Option<&Bound<'_, PyAny>>,
    spread: f64,
    seed: Option<&Bound<'_, PyAny>>,
    budget: Option<f64>,
    jobs: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene.get().inner.clone();
    // `members` and `seed` as `ensemble` takes them (16 and 0 by default).
    let (members, seed) = crate::study::members_and_seed(members, seed)?;
    let options = EnsembleOptions {
        members,
        spread,
        seed,
        jobs: jobs_of(jobs, members)?,
        measures: fc_study::measure::Measures::TIP,
    };
    options.validate().map_err(value_error)?;
    let budget = budget
        .map(|b| check_budget("budget", b))
        .transpose()
        .map_err(value_error)?;
    core::check_size("members", &scene, &options).map_err(value_error)?;
    let (result, series) = run_interruptible(py, |cancel| {
        Budget::run(budget, Some(cancel), |b| {
            core::run(&scene, &options, b, &|_, _| {})
        })
    })?
    .map_err(value_error)?;
    let out = PyDict::new(py);
    out.set_item("t", array1(py, series.t.clone())?)?;
    out.set_item("members", series.count)?;
    let by_name = PyDict::new(py);
    for (q, name) in series.names.iter().enumerate() {
        let stats = PyDict::new(py);
        for stat in STATS {
            stats.set_item(stat, array1(py, series.column(q, stat))?)?;
        }
        by_name.set_item(name, stats)?;
    }
    out.set_item("series", by_name)?;
    out.set_item("ensemble", json_to_dict(py, &result.to_json().to_string())?)?;
    Ok(out)
}
