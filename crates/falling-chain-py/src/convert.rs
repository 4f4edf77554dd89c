//! Conversions between Python objects and the values of the Rust API: scene
//! values (TOML), the CLI's JSON objects, errors, and numpy arrays.

use ::falling_chain::overrides::parse_value;
use ::falling_chain::Error;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString};

/// The CLI's one-line error (what `falling-chain` prints after `error: `)
/// as a `ValueError`.
pub fn value_error(e: Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A Python value as a scene value, as `--set KEY=VALUE` would give it:
/// a `str` is parsed as the text after `=` (`"dopri5"`, `"[3.0, 0.0]"`,
/// `"100"`), `bool`, `int` and `float` (numpy scalars too) are themselves,
/// sequences (lists, tuples, numpy arrays) are arrays and dicts are tables.
/// `key` names the value in errors.
pub fn to_toml(value: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if let Ok(s) = value.cast::<PyString>() {
        return parse_value(&s.to_cow()?).map_err(|m| value_error(Error::field(key, m)));
    }
    if value.is_instance_of::<PyInt>() {
        return value
            .extract::<i64>()
            .map(toml::Value::Integer)
            .map_err(|_| {
                value_error(Error::field(
                    key,
                    format!("{value} does not fit a 64-bit integer"),
                ))
            });
    }
    if let Ok(x) = value.cast::<PyFloat>() {
        return Ok(toml::Value::Float(x.value()));
    }
    if let Ok(d) = value.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in d.iter() {
            let k: String = k.extract().map_err(|_| {
                PyTypeError::new_err(format!("{key}: table keys must be str (got {k})"))
            })?;
            let v = to_toml(&v, &format!("{key}.{k}"))?;
            table.insert(k, v);
        }
        return Ok(toml::Value::Table(table));
    }
    // numpy.bool_ (pyo3 accepts it as a bool, and nothing but bools).
    if let Ok(b) = value.extract::<bool>() {
        return Ok(toml::Value::Boolean(b));
    }
    // Integers that are not `int` (numpy.int64): anything with `__index__`.
    if value.hasattr("__index__")? {
        if let Ok(i) = value.extract::<i64>() {
            return Ok(toml::Value::Integer(i));
        }
    }
    if !value.is_instance_of::<pyo3::types::PyBytes>() {
        if let Ok(items) = value.try_iter() {
            let mut array = Vec::new();
            for (i, item) in items.enumerate() {
                array.push(to_toml(&item?, &format!("{key}.{i}"))?);
            }
            return Ok(toml::Value::Array(array));
        }
    }
    // Other numbers (numpy.float32, a 0-d array, Fraction, Decimal).
    if let Ok(x) = value.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    Err(PyTypeError::new_err(format!(
        "{key}: cannot use a value of type '{}' in a scene (use str, bool, int, float, a sequence or a dict)",
        value.get_type().name()?
    )))
}

/// A scene value as a Python object (tables as dicts, arrays as lists).
pub fn from_toml<'py>(py: Python<'py>, value: &toml::Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        toml::Value::String(s) => s.into_pyobject(py)?.into_any(),
        toml::Value::Integer(i) => i.into_pyobject(py)?.into_any(),
        toml::Value::Float(x) => x.into_pyobject(py)?.into_any(),
        toml::Value::Boolean(b) => b.into_pyobject(py)?.to_owned().into_any(),
        toml::Value::Datetime(d) => d.to_string().into_pyobject(py)?.into_any(),
        toml::Value::Array(a) => {
            let items = a
                .iter()
                .map(|v| from_toml(py, v))
                .collect::<PyResult<Vec<_>>>()?;
            PyList::new(py, items)?.into_any()
        }
        toml::Value::Table(t) => table_to_dict(py, t)?.into_any(),
    })
}

/// A TOML table as a dict, in the table's order.
pub fn table_to_dict<'py>(py: Python<'py>, table: &toml::Table) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, v) in table {
        d.set_item(k, from_toml(py, v)?)?;
    }
    Ok(d)
}

/// Parses one line of JSON with Python's own `json.loads`, so that the dict
/// has the keys in the order the CLI prints them and the very same values.
pub fn json_to_dict<'py>(py: Python<'py>, json: &str) -> PyResult<Bound<'py, PyDict>> {
    static LOADS: PyOnceLock<Py<PyAny>> = PyOnceLock::new();
    let loads = LOADS.get_or_try_init(py, || -> PyResult<_> {
        Ok(py.import("json")?.getattr("loads")?.unbind())
    })?;
    Ok(loads.bind(py).call1((json,))?.cast_into::<PyDict>()?)
}

/// Marks an array read-only: it shows a finished run, which it must not change.
pub fn read_only<'py, T>(array: Bound<'py, T>) -> PyResult<Bound<'py, T>> {
    let kwargs = PyDict::new(array.py());
    kwargs.set_item("write", false)?;
    array.as_any().call_method("setflags", (), Some(&kwargs))?;
    Ok(array)
}

/// A read-only float64 array over `data` (no copy: numpy takes the vector).
pub fn array1(py: Python<'_>, data: Vec<f64>) -> PyResult<Py<PyArray1<f64>>> {
    Ok(read_only(data.into_pyarray(py))?.unbind())
}

/// A read-only `(rows, cols)` float64 array over `data`, row-major (no copy).
pub fn array2(
    py: Python<'_>,
    data: Vec<f64>,
    rows: usize,
    cols: usize,
) -> PyResult<Py<PyArray2<f64>>> {
    let a = Array2::from_shape_vec((rows, cols), data)
        .map_err(|e| PyValueError::new_err(format!("array shape: {e}")))?;
    Ok(read_only(a.into_pyarray(py))?.unbind())
}

/// A `(rows, 2)` array of points.
pub fn points(py: Python<'_>, points: &[[f64; 2]]) -> PyResult<Py<PyArray2<f64>>> {
    let data = points.iter().flatten().copied().collect();
    array2(py, data, points.len(), 2)
}

/// An array handed back through `Py`, bound again (for getters).
pub fn bound<'py, T>(py: Python<'py>, array: &Py<T>) -> Bound<'py, T> {
    array.bind(py).clone()
}
