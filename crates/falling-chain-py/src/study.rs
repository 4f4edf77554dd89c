//! `falling_chain.precision`, `stability`, `needs`, `ensemble` and `merge`: the CLI's
//! commands of the same names, returning the tables of their `--out` as
//! dicts of numpy columns (`needs`: its `--json` object as a dict).

use ::fc_batch::budget::check_budget;
use ::fc_batch::shard;
use ::fc_csv::{column_type, Column};
use ::fc_scene::Error;
use ::fc_study::stability as core_stability;
use ::fc_study::{
    self as study, ensemble as core_ensemble, needs as core_needs, precision as core_precision,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use crate::convert::{echo, json_to_dict, read_only, value_error};
use crate::interrupt::run_interruptible;
use crate::scene::PyScene;
use crate::sweep::{column, csv_records, jobs_of, shard_of, vary_of, SWEEP_COLUMNS};

/// A table of ours (header, then rows) as a dict of read-only numpy
/// columns, each of the type its writer declares (`declared`, the CSV
/// layer's [`Column`]s: int64, float64 with NaN for an empty cell, str; an
/// integer column with an empty cell, a run not made, is float64). A column
/// no writer declares is a sweep's varied key, whose values are the
/// user's: int64 if every cell is an integer, float64 if every cell is a
/// number, str otherwise (as `sweep` types it by its values).
fn table<'py>(
    py: Python<'py>,
    text: &str,
    declared: &[&[(&str, Column)]],
) -> PyResult<Bound<'py, PyDict>> {
    let mut records = csv_records(text)?.into_iter();
    let header = records.next().unwrap_or_default();
    let rows: Vec<Vec<String>> = records.collect();
    let out = PyDict::new(py);
    for (i, name) in header.iter().enumerate() {
        let cells: Vec<String> = rows
            .iter()
            .map(|r| r.get(i).cloned().unwrap_or_default())
            .collect();
        let kind = column_type(declared, name).unwrap_or_else(|| {
            if cells.iter().all(|c| c.parse::<i64>().is_ok()) {
                Column::Int
            } else if cells.iter().all(|c| c.parse::<f64>().is_ok()) {
                Column::Float
            } else {
                Column::Text
            }
        });
        out.set_item(name, read_only(column(py, kind, cells)?)?)?;
    }
    Ok(out)
}

/// `methods=`: `None`, `"rk4,dop853"` or a sequence of names.
/// `measure=`: a str `"tip,pivot_force_max"` or a list of names, checked
/// against `scene` ([`Measures::parse`]: bad names and measures the scene
/// cannot have raise ValueError naming `measure`).
fn measures_of(
    measure: Option<&Bound<'_, PyAny>>,
    scene: &fc_scene::Scene,
) -> PyResult<::fc_study::measure::Measures> {
    let text = match measure {
        None => None,
        Some(m) if m.cast::<PyString>().is_ok() => Some(m.str()?.to_string()),
        Some(m) => {
            let names: Vec<String> = m
                .try_iter()
                .and_then(|it| it.take(64).map(|x| x?.extract::<String>()).collect())
                .map_err(|_| {
                    PyTypeError::new_err(format!(
                        "measure: expected a str \"tip,pivot_force_max\" or a list of names (got {})",
                        echo(m)
                    ))
                })?;
            Some(names.join(","))
        }
    };
    let p = scene.prepare().map_err(value_error)?;
    ::fc_study::measure::Measures::parse_for("measure", text.as_deref(), &p).map_err(value_error)
}

fn methods_of(methods: Option<&Bound<'_, PyAny>>) -> PyResult<Option<String>> {
    let Some(m) = methods else {
        return Ok(None);
    };
    if let Ok(s) = m.cast::<PyString>() {
        return Ok(Some(s.to_cow()?.into_owned()));
    }
    let names: Vec<String> = m
        .try_iter()
        .and_then(|it| it.take(64).map(|x| x?.extract::<String>()).collect())
        .map_err(|_| {
            PyTypeError::new_err(format!(
                "methods: expected a str \"rk4,dop853\" or a list of names (got {})",
                echo(m)
            ))
        })?;
    Ok(Some(names.join(",")))
}

fn budget_of(budget: Option<f64>) -> PyResult<Option<f64>> {
    budget
        .map(|b| check_budget("budget", b))
        .transpose()
        .map_err(value_error)
}

/// The work-precision table of `scene` (`falling-chain precision --out`'s
/// columns): every method (or `methods`) across tolerances (RK4 across
/// steps), the errors against the DOPRI5 reference at rtol 1e-13 and its
/// RK4 and BDF checks (the first rows, whose `run` is NaN), the work and
/// `wall_seconds`. `check_dt` (at most 1e7 RK4 steps) and `richardson` set
/// the RK4 check; `budget` (seconds) holds in every phase, the reference
/// and its checks too, and skips or stops what is past it (`budget: ...`
/// in the `note`); `shard` ("I/N" or (I, N)) runs only its points (join with
/// `merge`); `jobs` threads (1 to 256). `measure` (`--measure`: a str
/// "tip,pivot_force_max" or a list; default "tip") sets what the errors
/// measure: then each measure's but the tip's `err_<name>` and `<name>_ref` are the last
/// columns, and a stiff scene's reference is DOPRI5 checked by DOP853.
/// Releases the GIL; Ctrl-C raises
/// KeyboardInterrupt. Bad input raises ValueError naming the argument.
#[pyfunction]
#[pyo3(signature = (scene, *, methods=None, check_dt=None, richardson=false, budget=None, shard=None, jobs=None, measure=None))]
#[allow(clippy::too_many_arguments)]
pub fn precision<'py>(
    py: Python<'py>,
    scene: &Bound<'_, PyScene>,
    methods: Option<&Bound<'_, PyAny>>,
    check_dt: Option<f64>,
    richardson: bool,
    budget: Option<f64>,
    shard: Option<&Bound<'_, PyAny>>,
    jobs: Option<&Bound<'_, PyAny>>,
    measure: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene.get().inner.clone();
    let t_end = scene.options().map_err(value_error)?.t_end;
    let methods = methods_of(methods)?;
    let options = core_precision::Options {
        methods: study::parse_methods("methods", methods.as_deref()).map_err(value_error)?,
        checks: core_precision::Checks {
            check_dt: core_precision::check_check_dt(
                "check_dt",
                check_dt.unwrap_or(core_precision::CHECK_DT),
                t_end,
                richardson,
            )
            .map_err(value_error)?,
            richardson,
        },
        budget: budget_of(budget)?,
        shard: shard_of(shard)?,
        jobs: jobs_of(jobs, usize::MAX)?,
        measures: measures_of(measure, &scene)?,
    };
    scene.prepare().map_err(value_error)?;
    let s = run_interruptible(py, |cancel| {
        core_precision::study(&scene, &options, Some(cancel), &|| {})
    })?
    .map_err(value_error)?;
    let declared: [&[(&str, Column)]; 3] = [
        &core_precision::COLUMNS,
        &core_precision::CLI_COLUMNS,
        &shard::COLUMNS,
    ];
    table(py, &s.csv(), &declared)
}

/// Where each method fails on `scene` (`falling-chain stability --out`'s
/// columns): every method (or `methods`) at every step or tolerance, run to
/// the end with at most 2e5 steps: `outcome`, `status`, `t_reached`, the
/// energy-balance error, `wall_seconds`. `vary` ({key: values}, one key, at
/// most 1000 values, or a str in `--vary` syntax) makes a row per value;
/// `budget`, `shard` and `jobs` as in `precision`. Releases the GIL;
/// Ctrl-C raises KeyboardInterrupt. Bad input raises ValueError.
#[pyfunction]
#[pyo3(signature = (scene, *, methods=None, vary=None, budget=None, shard=None, jobs=None, measure=None))]
#[allow(clippy::too_many_arguments)]
pub fn stability<'py>(
    py: Python<'py>,
    scene: &Bound<'_, PyScene>,
    methods: Option<&Bound<'_, PyAny>>,
    vary: Option<&Bound<'_, PyDict>>,
    budget: Option<f64>,
    shard: Option<&Bound<'_, PyAny>>,
    jobs: Option<&Bound<'_, PyAny>>,
    measure: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene.get().inner.clone();
    let methods = methods_of(methods)?;
    let vary = match vary {
        None => None,
        Some(d) => {
            let items = d.items();
            if items.len() != 1 {
                return Err(value_error(Error::field(
                    "vary",
                    format!("give one key and its values (got {} keys)", items.len()),
                )));
            }
            let (k, v) = items
                .get_item(0)?
                .extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>()?;
            Some(vary_of(&k, &v)?)
        }
    };
    let options = core_stability::Options {
        methods: study::parse_methods("methods", methods.as_deref()).map_err(value_error)?,
        measures: measures_of(measure, &scene)?,
        vary,
        budget: budget_of(budget)?,
        shard: shard_of(shard)?,
        jobs: jobs_of(jobs, usize::MAX)?,
    };
    core_stability::rows_of(&scene, options.vary.as_ref()).map_err(value_error)?;
    let s = run_interruptible(py, |cancel| {
        core_stability::run_study(&scene, &options, Some(cancel), &|| {})
    })?
    .map_err(value_error)?;
    let declared: [&[(&str, Column)]; 3] = [
        &core_stability::COLUMNS,
        &core_stability::CLI_COLUMNS,
        &shard::COLUMNS,
    ];
    table(py, &s.csv(), &declared)
}

/// What `scene` needs at tolerance `tol` (`falling-chain needs --json` as a
/// dict): `links`, the smallest n whose tip path, tip end and maximum tip
/// speed agree with the finest of `links_ladder` (default 25 to 400) within
/// `tol`; `fastest` and `least_work`, the method and tolerance reaching
/// `tol` at that n; `terms`, whether each optional term the scene turns on
/// (joint friction) is `needed`; `ladder`, converge's report. `methods`,
/// `budget` (seconds, every phase: the ladder, the reference, the methods,
/// the terms) and `jobs` as in `precision`.
/// Releases the GIL; Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (scene, tol, *, links=None, methods=None, budget=None, jobs=None, measure=None))]
#[allow(clippy::too_many_arguments)]
pub fn needs<'py>(
    py: Python<'py>,
    scene: &Bound<'_, PyScene>,
    tol: f64,
    links: Option<&Bound<'_, PyAny>>,
    methods: Option<&Bound<'_, PyAny>>,
    budget: Option<f64>,
    jobs: Option<&Bound<'_, PyAny>>,
    measure: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene.get().inner.clone();
    core_needs::check_tol("--tol", tol).map_err(value_error)?;
    let links = match links {
        None => ::fc_study::converge::DEFAULT_LINKS.to_vec(),
        Some(l) => {
            let text = if let Ok(s) = l.cast::<PyString>() {
                s.to_cow()?.into_owned()
            } else {
                // Read no more values than a ladder may hold (each distinct
                // one a level), counting the rest: the error says how many.
                let cap = ::fc_study::converge::MAX_LEVELS;
                let v: Vec<String> = l
                    .try_iter()
                    .and_then(|it| {
                        it.take(cap + 1)
                            .map(|x| Ok(x?.str()?.to_string()))
                            .collect()
                    })
                    .map_err(|_| {
                        PyTypeError::new_err(format!("links: expected ints (got {})", echo(l)))
                    })?;
                if v.len() > cap {
                    let count = l
                        .len()
                        .map_or(format!("more than {cap}"), |n| n.to_string());
                    return Err(PyValueError::new_err(format!(
                        "links: at most {cap} numbers of rods (got {count} values)"
                    )));
                }
                v.join(",")
            };
            ::fc_study::converge::parse_links(&text).map_err(value_error)?
        }
    };
    let methods = match methods_of(methods)? {
        Some(m) => study::parse_methods("methods", Some(&m)).map_err(value_error)?,
        None => core_needs::default_methods(),
    };
    let options = core_needs::NeedsOptions {
        tol,
        links,
        methods,
        jobs: jobs_of(jobs, usize::MAX)?,
        measures: measures_of(measure, &scene)?,
    };
    let budget = budget_of(budget)?;
    let answer = run_interruptible(py, |cancel| {
        ::fc_batch::budget::Budget::run(budget, Some(cancel), |b| {
            core_needs::run(&scene, &options, b, &|_, _, _| {})
        })
    })?
    .map_err(value_error)?;
    json_to_dict(py, &answer.to_json())
}

/// `scene` run from `members` starts whose rod angles are each moved by a
/// number drawn uniformly from `[-spread, spread]` rad (`seed` chooses the
/// draws, the same on every machine): `falling-chain ensemble --json` as a
/// dict (`members`, `spread`, `seed`, `ok`, `stats` by quantity with
/// `mean`, `sd`, `sem`, `min`, `max`, `count`, and `failures`). `members`
/// in 2..=4096 (default 16), `seed` in 0..=2^32-1 (default 0), `spread` in
/// [0, 0.1]; `budget` and `jobs` as in
/// `precision`. Releases the GIL; Ctrl-C raises KeyboardInterrupt.
#[pyfunction]
#[pyo3(signature = (scene, *, members=None, spread=1e-3, seed=None, budget=None, jobs=None, measure=None))]
#[allow(clippy::too_many_arguments)]
pub fn ensemble<'py>(
    py: Python<'py>,
    scene: &Bound<'_, PyScene>,
    members: Option<&Bound<'_, PyAny>>,
    spread: f64,
    seed: Option<&Bound<'_, PyAny>>,
    budget: Option<f64>,
    jobs: Option<&Bound<'_, PyAny>>,
    measure: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = scene.get().inner.clone();
    let (members, seed) = members_and_seed(members, seed)?;
    let options = core_ensemble::EnsembleOptions {
        members,
        spread,
        seed,
        jobs: jobs_of(jobs, members)?,
        measures: measures_of(measure, &scene)?,
    };
    options.validate().map_err(value_error)?;
    let budget = budget_of(budget)?;
    let result = run_interruptible(py, |cancel| {
        ::fc_batch::budget::Budget::run(budget, Some(cancel), |b| {
            core_ensemble::run(&scene, &options, b, &|_, _| {})
        })
    })?
    .map_err(value_error)?;
    json_to_dict(py, &result.to_json().to_string())
}

/// An ensemble's `members` (in `2..=4096`, default 16) and `seed` (in
/// `0..=2^32-1`, default 0), as the CLI's `--members` and `--seed`: any
/// Python object, checked by [`int_in`].
pub(crate) fn members_and_seed(
    members: Option<&Bound<'_, PyAny>>,
    seed: Option<&Bound<'_, PyAny>>,
) -> PyResult<(usize, u32)> {
    let max = core_ensemble::MAX_MEMBERS as u64;
    let members = match members {
        Some(m) => int_in("members", m, 2, max)? as usize,
        None => core_ensemble::DEFAULT_MEMBERS,
    };
    let seed = match seed {
        Some(s) => int_in("seed", s, 0, u64::from(u32::MAX))? as u32,
        None => 0,
    };
    Ok((members, seed))
}

/// The int `value` of the keyword argument `name` in `lo..=hi`: a
/// TypeError for what is not an int (a bool, a float), a ValueError naming
/// `name` and the range for an int outside it (`-1`, `10**30`), never
/// Python's OverflowError.
fn int_in(name: &str, value: &Bound<'_, PyAny>, lo: u64, hi: u64) -> PyResult<u64> {
    if !value.is_instance_of::<pyo3::types::PyInt>()
        || value.is_instance_of::<pyo3::types::PyBool>()
    {
        return Err(PyTypeError::new_err(format!(
            "{name}: must be an int in {lo}..={hi} (got '{}')",
            value.get_type().name()?
        )));
    }
    match value.extract::<u64>() {
        Ok(n) if (lo..=hi).contains(&n) => Ok(n),
        _ => Err(PyValueError::new_err(format!(
            "{name}: must be an integer in {lo}..={hi} (got {})",
            echo(value)
        ))),
    }
}

/// Joins the tables of a sharded sweep, precision or stability (files
/// written with `--shard I/N --out`, or tables saved from Python) into the
/// table of the whole run, as numpy columns: `falling-chain merge`, with
/// its checks (ValueError for a missing or repeated run, a row not run
/// within its shard's budget, or shards of another scene or options).
/// `paths` is a list of paths (str or os.PathLike); a single path, or
/// anything else, raises TypeError naming `paths`.
#[pyfunction]
pub fn merge<'py>(py: Python<'py>, paths: &Bound<'_, PyAny>) -> PyResult<Bound<'py, PyDict>> {
    let paths = paths_of(paths)?;
    let texts = shard::read(&paths).map_err(|e| value_error(paths_named(e)))?;
    let merged = shard::merge(&texts).map_err(value_error)?;
    // A shard is precision's, stability's or a sweep's table: each names
    // its columns with their types (the same name has one type in all).
    let mut declared: Vec<&[(&str, Column)]> = vec![
        &core_precision::COLUMNS,
        &core_precision::CLI_COLUMNS,
        &core_stability::COLUMNS,
        &core_stability::CLI_COLUMNS,
    ];
    declared.extend_from_slice(SWEEP_COLUMNS);
    table(py, &merged, &declared)
}

/// An error of [`shard::read`] about one file (its role `shard`) or the
/// set of files (`merge`), said of `paths=`.
fn paths_named(e: Error) -> Error {
    match e {
        Error::Read { path, source, .. } => Error::Read {
            what: "paths",
            path,
            source,
        },
        Error::Field { message, .. } => Error::Field {
            field: "paths".into(),
            message,
        },
        e => e,
    }
}

/// `paths=` of `merge`: a sequence of str or os.PathLike, at most
/// `shard::MAX_SHARDS` of them (read lazily: an endless iterator fails at
/// the cap).
fn paths_of(paths: &Bound<'_, PyAny>) -> PyResult<Vec<std::path::PathBuf>> {
    let single = paths.is_instance_of::<PyString>()
        || paths.is_instance_of::<pyo3::types::PyBytes>()
        || paths.hasattr("__fspath__")?;
    if single {
        return Err(PyTypeError::new_err(format!(
            "paths: expected a list of shard files, got the one path {} (write merge([path]))",
            echo(paths)
        )));
    }
    let wrong = || {
        PyTypeError::new_err(format!(
            "paths: expected a list of shard files (str or os.PathLike) (got {})",
            echo(paths)
        ))
    };
    let mut out = vec![];
    for item in paths.try_iter().map_err(|_| wrong())? {
        let item = item?;
        if out.len() == shard::MAX_SHARDS {
            return Err(value_error(Error::field(
                "paths",
                format!("at most {} shard files", shard::MAX_SHARDS),
            )));
        }
        out.push(item.extract::<std::path::PathBuf>().map_err(|_| {
            PyTypeError::new_err(format!(
                "paths: every element must be a str or os.PathLike (got {})",
                echo(&item)
            ))
        })?);
    }
    Ok(out)
}
