//! `falling_chain.sweep`: the CLI's `sweep`, with numpy columns for its CSV.

use ::fc_batch::shard::{self, Provenance, Shard};
use ::fc_batch::sweep as core;
use ::fc_batch::sweep::{SweepRow, Vary};
use ::fc_csv::{column_type, Column};
use ::fc_scene::{Error, SUMMARY_CSV_COLUMNS};
use numpy::IntoPyArray;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyInt, PyList, PyString};

use crate::convert::{echo, echo_text, read_only, to_toml_items, value_error};
use crate::interrupt::run_interruptible;
use crate::run::with_flags;
use crate::scene::PyScene;

/// The most runs a sweep may have (the sweep's own grid cap), so that no
/// list of `vary` is longer than a sweep can run; and the most threads
/// `jobs=` may ask for. Both are the CLI's.
use ::fc_batch::{shard::MAX_RUNS, sweep::MAX_JOBS};

/// One key of `vary`: a `str` is the right-hand side of `--vary KEY=...`
/// (`"0.3:5.97:120"`, `"rk4,dopri5"`); anything else is a sequence of values
/// (at most [`MAX_RUNS`], read lazily: an endless iterator fails at the cap).
pub(crate) fn vary_of(key: &Bound<'_, PyAny>, values: &Bound<'_, PyAny>) -> PyResult<Vary> {
    let key: String = key
        .extract()
        .map_err(|_| PyTypeError::new_err(format!("vary: keys must be str (got {})", echo(key))))?;
    let vary = if let Ok(spec) = values.cast::<PyString>() {
        Vary::parse(&format!("{key}={}", spec.to_cow()?)).map_err(value_error)?
    } else {
        let why = format!("a sweep runs at most {MAX_RUNS} scenes");
        let values = to_toml_items(values, &key, MAX_RUNS, &why)?.ok_or_else(|| {
            PyTypeError::new_err(format!(
                "vary: the values of '{}' must be a sequence or a str such as \"0.3:5.97:120\"",
                echo_text(&key)
            ))
        })?;
        Vary { key, values }
    };
    if vary.values.is_empty() {
        return Err(value_error(Error::field(
            "vary",
            format!("'{}' has no values", vary.key),
        )));
    }
    Ok(vary)
}

/// `None`, `"I/N"` or `(I, N)`.
pub(crate) fn shard_of(shard: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Shard>> {
    let Some(shard) = shard else {
        return Ok(None);
    };
    let spec = if let Ok(s) = shard.cast::<PyString>() {
        s.to_cow()?.into_owned()
    } else if let Ok((i, n)) = shard.extract::<(Bound<'_, PyInt>, Bound<'_, PyInt>)>() {
        // Any ints: one that fits no integer type is out of range, which
        // the parser says in the CLI's words.
        format!("{i}/{n}")
    } else {
        return Err(PyTypeError::new_err(format!(
            "shard: expected \"I/N\" or (I, N) (got {})",
            echo(shard)
        )));
    };
    Shard::parse(&spec).map(Some).map_err(value_error)
}

/// The cells of CSV text of ours, read by the project's one reader
/// (`fc_csv`, RFC 4180: a name with a comma, a quote or a line
/// break is one quoted cell).
pub(crate) fn csv_records(text: &str) -> PyResult<Vec<Vec<String>>> {
    ::fc_csv::records(text).map_err(|e| PyValueError::new_err(format!("csv: {e}")))
}

/// The type of a varied key's column from its values (a varied key's
/// column is the one column no writer declares: its values are the user's).
fn value_kind(values: &[&toml::Value]) -> Column {
    if values.iter().all(|v| v.is_integer()) {
        Column::Int
    } else if values.iter().all(|v| v.is_integer() || v.is_float()) {
        Column::Float
    } else {
        Column::Text
    }
}

/// A column of cells as a numpy array of its declared type: int64
/// ([`Column::Int`] with every cell given; with an empty cell, a run not
/// made, float64 with NaN there), float64 (empty cells are NaN) or str.
pub(crate) fn column<'py>(
    py: Python<'py>,
    kind: Column,
    cells: Vec<String>,
) -> PyResult<Bound<'py, PyAny>> {
    let bad = |c: &str| PyValueError::new_err(format!("csv: cannot read the cell '{c}'"));
    let kind = match kind {
        Column::Int if cells.iter().any(String::is_empty) => Column::Float,
        k => k,
    };
    Ok(match kind {
        Column::Int => cells
            .iter()
            .map(|c| c.parse::<i64>().map_err(|_| bad(c)))
            .collect::<PyResult<Vec<_>>>()?
            .into_pyarray(py)
            .into_any(),
        Column::Float => cells
            .iter()
            .map(|c| {
                if c.is_empty() {
                    Ok(f64::NAN)
                } else {
                    c.parse::<f64>().map_err(|_| bad(c))
                }
            })
            .collect::<PyResult<Vec<_>>>()?
            .into_pyarray(py)
            .into_any(),
        Column::Text => {
            let np = py.import("numpy")?;
            let list = PyList::new(py, cells)?;
            np.call_method1("array", (list, "str"))?
        }
    })
}

/// The columns a sweep's table declares: its run number, the summary's
/// and the provenance's (the varied keys' are typed by their values).
pub(crate) const SWEEP_COLUMNS: &[&[(&str, Column)]] = &[
    &[("run", Column::Int)],
    &SUMMARY_CSV_COLUMNS,
    &shard::COLUMNS,
];

/// The rows as the columns of `sweep --out`'s CSV: the cells are those of
/// the CSV, typed as the CSV layer's writers declare them.
fn columns<'py>(
    py: Python<'py>,
    vary: &[Vary],
    rows: &[SweepRow],
    provenance: &Provenance,
) -> PyResult<Bound<'py, PyDict>> {
    let mut text = core::csv_header(vary) + &Provenance::header_suffix() + "\n";
    for r in rows {
        text.push_str(&core::csv_row(r));
        text.push_str(&provenance.cells());
        text.push('\n');
    }
    let mut table = csv_records(&text)?.into_iter();
    let header = table.next().unwrap_or_default();
    let table: Vec<Vec<String>> = table.collect();
    let out = PyDict::new(py);
    for (i, name) in header.iter().enumerate() {
        let kind = if (1..=vary.len()).contains(&i) {
            value_kind(
                &rows
                    .iter()
                    .filter_map(|r| r.values.get(i - 1))
                    .collect::<Vec<_>>(),
            )
        } else {
            column_type(SWEEP_COLUMNS, name).unwrap_or(Column::Text)
        };
        let cells = table
            .iter()
            .map(|r| r.get(i).cloned().unwrap_or_default())
            .collect();
        out.set_item(name, read_only(column(py, kind, cells)?)?)?;
    }
    Ok(out)
}

/// The threads of `jobs=`: an int in `1..=MAX_JOBS`; by default the
/// machine's cores (at most [`MAX_JOBS`]). Never more than `runs`.
pub(crate) fn jobs_of(jobs: Option<&Bound<'_, PyAny>>, runs: usize) -> PyResult<usize> {
    let wanted = match jobs {
        None => std::thread::available_parallelism().map_or(1, |n| n.get().min(MAX_JOBS)),
        Some(j) => {
            if !j.is_instance_of::<PyInt>() || j.is_instance_of::<pyo3::types::PyBool>() {
                return Err(PyTypeError::new_err(format!(
                    "jobs: must be an int (got '{}')",
                    j.get_type().name()?
                )));
            }
            match j
                .extract::<i64>()
                .ok()
                .and_then(|n| usize::try_from(n).ok())
            {
                Some(n) if (1..=MAX_JOBS).contains(&n) => n,
                _ => {
                    return Err(value_error(Error::field(
                        "jobs",
                        format!("must be an integer in 1..={MAX_JOBS} (got {})", echo(j)),
                    )))
                }
            }
        }
    };
    Ok(wanted.min(runs.max(1)))
}

/// The number of runs of the sweep (or of its shard), or the error naming
/// `vary` when the whole grid has more than [`MAX_RUNS`]: checked before
/// anything is built.
fn runs_of(vary: &[Vary], shard: Option<Shard>) -> PyResult<usize> {
    let total = vary
        .iter()
        .try_fold(1usize, |acc, v| acc.checked_mul(v.values.len()))
        .filter(|&n| n <= MAX_RUNS);
    let Some(total) = total else {
        let lengths: Vec<String> = vary.iter().map(|v| v.values.len().to_string()).collect();
        return Err(value_error(Error::field(
            "vary",
            format!(
                "the sweep has {} runs; at most {MAX_RUNS} are allowed",
                lengths.join(" x ")
            ),
        )));
    };
    Ok(match shard {
        // Runs index, index + count, ... below total.
        Some(s) => total.saturating_sub(s.index).div_ceil(s.count),
        None => total,
    })
}

/// Runs `scene` once per value of the keys in `vary`, in parallel, and
/// returns the rows of `falling-chain sweep --out` as a dict of numpy
/// columns named as its CSV header: `run`, the varied keys, then the fields
/// of `simulate --json` (`tip_end` as `tip_end_x`, `tip_end_y`, ...).
///
/// `vary` maps dotted scene keys to sequences of values (a numpy array, a
/// list) or to a `str` in `--vary` syntax (`"0.3:5.97:120"` for 120 values
/// from 0.3 to 5.97, `"rk4,dopri5"`); several keys give their product, the
/// last varying fastest. `method`, `rtol` and `atol` set `run.method`,
/// `run.rtol` and `run.atol` first. `shard` ("I/N" or (I, N)) runs only
/// runs I, I + N, ...; `jobs` is the number of threads (1 to 256; default:
/// all cores). Integer columns are int64, numbers float64 (`t_failed` is
/// NaN where a run did not fail), text columns str. Every run's scene is
/// checked before any runs; bad input raises ValueError naming the field
/// (a sweep has at most 1000000 runs). The sweep releases the GIL, and
/// Ctrl-C stops it within a fraction of a second: it then raises
/// KeyboardInterrupt (and returns no rows).
#[pyfunction]
#[pyo3(signature = (scene, vary, *, method=None, rtol=None, atol=None, shard=None, jobs=None))]
#[allow(clippy::too_many_arguments)]
pub fn sweep<'py>(
    py: Python<'py>,
    scene: &Bound<'_, PyScene>,
    vary: &Bound<'_, PyDict>,
    method: Option<String>,
    rtol: Option<f64>,
    atol: Option<f64>,
    shard: Option<&Bound<'_, PyAny>>,
    jobs: Option<&Bound<'_, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = with_flags(
        &scene.get().inner,
        &[
            ("run.method", method.map(toml::Value::String)),
            ("run.rtol", rtol.map(toml::Value::Float)),
            ("run.atol", atol.map(toml::Value::Float)),
        ],
    )
    .map_err(value_error)?;
    if vary.is_empty() {
        return Err(value_error(Error::field(
            "vary",
            "give at least one key, e.g. {\"start.p1.0\": [1.0, 2.0, 3.0]}",
        )));
    }
    // A snapshot of the items: reading the values runs Python code, which
    // may change the dict.
    let vary = vary
        .items()
        .iter()
        .map(|item| {
            let (k, v) = item.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>()?;
            vary_of(&k, &v)
        })
        .collect::<PyResult<Vec<_>>>()?;
    let shard = shard_of(shard)?;
    let runs = runs_of(&vary, shard)?;
    let jobs = jobs_of(jobs, runs)?;
    // Once Ctrl-C sets `cancel`, no run starts and runs in progress stop.
    let rows = run_interruptible(py, |cancel| {
        core::run_cancellable(&scene, &vary, shard, jobs, &|_, _| {}, Some(cancel))
    })?
    .map_err(value_error)?;
    let provenance = core::provenance(&scene, &vary).map_err(value_error)?;
    columns(py, &vary, &rows, &provenance)
}
