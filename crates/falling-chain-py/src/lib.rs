//! `falling_chain`, the Python module: a thin layer of PyO3 over fc-scene
//! (scenes, `--set`, `RunSummary`, the catenary report), fc-batch (sweeps,
//! shards, `merge`), fc-study without its drawings (the studies), fc-viewer
//! (`view`) and chain-ode (`solve`, `kinematics`).
//!
//! Every Python name maps to one call of the Rust API (ARCHITECTURE.md has
//! the table); nothing of the scene schema, the methods or the summary is
//! repeated here. Runs and sweeps release the GIL and stop on Ctrl-C
//! (`interrupt`); Python values become scene values within bounds on their
//! length and depth (`convert`), so that no input can exhaust the
//! interpreter's memory or stack.
//!
//! Its files:
//! * `catenary.rs`: `falling_chain.catenary`: what `falling-chain catenary --json` prints.
//! * `ensemble_series.rs`: `falling_chain.ensemble_series`: `falling-chain ensemble --out-series`, its time series as numpy arrays.
//! * `convert.rs`: Conversions between Python objects and the values of the Rust API: scene values (TOML), the CLI's JSON objects, errors, and numpy arrays.
//! * `interrupt.rs`: Long work that Ctrl-C stops: the work runs on a worker thread with the GIL released ...
//! * `run.rs`: `falling_chain.simulate` and the `Run` it returns.
//! * `scene.rs`: `falling_chain.Scene`: a scene file, as the CLI reads it.
//! * `study.rs`: `falling_chain.precision`, `stability`, `needs`, `ensemble` and `merge`: the CLI's commands of the same names ...
//! * `sweep.rs`: `falling_chain.sweep`: the CLI's `sweep`, with numpy columns for its CSV.
//! * `view.rs`: `falling_chain.view`: runs as `falling-chain view`'s HTML page.

use pyo3::prelude::*;

mod catenary;
mod convert;
mod ensemble_series;
mod interrupt;
mod run;
mod scene;
mod study;
mod sweep;
mod view;

/// The names of the integration methods a scene's `run.method` accepts.
#[pyfunction]
fn methods() -> Vec<&'static str> {
    chain_ode::Method::ALL.iter().map(|m| m.as_str()).collect()
}

/// The falling chain of n rigid rods, from the Rust core.
///
/// A chain hangs in a "U" between two anchors; at t = 0 one end is
/// released. Load a scene (`Scene.load("scenes/span-d3.toml")`), change
/// it (`scene.set("chain.links", 100)`), run it (`simulate(scene)` returns
/// a `Run` whose arrays are numpy), sweep a key (`sweep(scene,
/// {"start.p1.0": [1, 2, 3]})`) or solve the hanging chain (`catenary`); `view(runs, path)` writes
/// runs as one HTML page that plays them (a `Run` shows as it in Jupyter).
/// Errors are ValueErrors with the CLI's one-line message naming the field;
/// Ctrl-C stops a run or a sweep with KeyboardInterrupt.
#[pymodule]
#[pyo3(name = "falling_chain")]
fn falling_chain_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<run::Run>()?;
    m.add_function(wrap_pyfunction!(run::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(catenary::catenary, m)?)?;
    m.add_function(wrap_pyfunction!(study::precision, m)?)?;
    m.add_function(wrap_pyfunction!(study::stability, m)?)?;
    m.add_function(wrap_pyfunction!(study::needs, m)?)?;
    m.add_function(wrap_pyfunction!(study::ensemble, m)?)?;
    m.add_function(wrap_pyfunction!(ensemble_series::ensemble_series, m)?)?;
    m.add_function(wrap_pyfunction!(study::merge, m)?)?;
    m.add_function(wrap_pyfunction!(methods, m)?)?;
    m.add_function(wrap_pyfunction!(view::view, m)?)?;
    m.add(
        "__all__",
        [
            "Scene",
            "Run",
            "simulate",
            "sweep",
            "catenary",
            "methods",
            "precision",
            "stability",
            "needs",
            "ensemble",
            "ensemble_series",
            "merge",
            "view",
        ],
    )?;
    Ok(())
}
