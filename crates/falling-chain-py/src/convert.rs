//! Conversions between Python objects and the values of the Rust API: scene
//! values (TOML), the CLI's JSON objects, errors, and numpy arrays.

use ::fc_scene::overrides::parse_value;
use ::fc_scene::Error;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::{PyKeyboardInterrupt, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString};

/// The CLI's one-line error (what `falling-chain` prints after `error: `)
/// as a `ValueError`; work stopped from outside (Ctrl-C) is a
/// KeyboardInterrupt.
pub fn value_error(e: Error) -> PyErr {
    match python_names(e) {
        e @ Error::Interrupted => PyKeyboardInterrupt::new_err(e.to_string()),
        e => PyValueError::new_err(e.to_string()),
    }
}

/// An error in the words of Python's keyword arguments: the CLI's flag
/// `--check-dt` (which the library's checks name, being the CLI's too) is
/// `check_dt=` here, `--shard` is `shard=`, `--links` is `links=`.
pub fn python_names(e: Error) -> Error {
    match e {
        Error::Field { field, message } if field.starts_with("--") => Error::Field {
            field: field[2..].replace('-', "_"),
            message,
        },
        e => e,
    }
}

/// The most characters of a value or key that a message shows.
const ECHO_MAX: usize = 80;

/// Text as a one-line message shows it: control characters escaped (a key
/// with a newline stays on one line), cut after [`ECHO_MAX`] characters.
pub fn echo_text(text: &str) -> String {
    let mut out = String::new();
    for (i, c) in text.chars().enumerate() {
        if i == ECHO_MAX {
            out.push('…');
            break;
        }
        if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    out
}

/// A Python value as a one-line message shows it: a container of more than
/// eight items by its type and length (never written out whole), anything
/// else by its `repr` through [`echo_text`].
pub fn echo(value: &Bound<'_, PyAny>) -> String {
    let kind = value
        .get_type()
        .name()
        .map_or_else(|_| "object".to_string(), |n| n.to_string());
    let text = value.is_instance_of::<PyString>() || value.is_instance_of::<pyo3::types::PyBytes>();
    match value.len() {
        Ok(len) if len > 8 && !text => format!("a {kind} of {len} items"),
        _ => value.repr().map_or_else(
            |_| format!("<{kind} too long to show>"),
            |r| echo_text(&r.to_string_lossy()),
        ),
    }
}

/// The largest `chain.links` a scene accepts (chain-ode's `Chain::validate`),
/// so the longest list a scene key takes (`start.angles`, `start.rates`).
pub use chain_ode::MAX_LINKS;

/// The most items one list, tuple, array, iterator or dict may hold when it
/// becomes a scene value: the longest list a scene key takes.
pub const MAX_ITEMS: usize = MAX_LINKS;

/// The most items a whole value may hold, nested ones included: a section
/// set whole (`scene.set("start", {...})`) holds `start.angles` and
/// `start.rates` at their longest, and a few more keys.
pub const MAX_TOTAL_ITEMS: usize = 2 * MAX_LINKS + 1_000;

/// How deeply a value may nest. A scene value is at most three deep (a
/// section, a point or list in it, a number); anything deeper is not a
/// scene value, and a list or dict that contains itself would go on for ever.
pub const MAX_DEPTH: usize = 8;

/// The longest `str` value (`scene.set("start.angles", "[0.1, ...]")`):
/// `start.angles` at `chain.links`' cap, written with every digit, fits.
pub const MAX_TEXT: usize = 32 << 20;

/// How often (in items) a long conversion checks for Ctrl-C.
const SIGNAL_EVERY: usize = 1 << 16;

/// Where a value sits inside the value being converted, for error messages:
/// the key, then the index or dict key of each level (`start.p1.0`). Built
/// only when an error needs it.
#[derive(Clone, Copy)]
enum Place<'a> {
    Key(&'a str),
    Index(&'a Place<'a>, usize),
    Name(&'a Place<'a>, &'a str),
}

impl Place<'_> {
    fn depth(&self) -> usize {
        match self {
            Place::Key(_) => 0,
            Place::Index(up, _) | Place::Name(up, _) => up.depth() + 1,
        }
    }
}

impl std::fmt::Display for Place<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Place::Key(key) => f.write_str(key),
            Place::Index(up, i) => write!(f, "{up}.{i}"),
            Place::Name(up, name) => write!(f, "{up}.{name}"),
        }
    }
}

/// The error about the value at `place`: a ValueError with the CLI's one line.
fn field_error(place: &Place<'_>, message: impl std::fmt::Display) -> PyErr {
    value_error(Error::field(place.to_string(), message))
}

/// What a conversion may still take: items in all, counted as they come.
struct Budget {
    items: usize,
}

impl Budget {
    /// Counts one more item at `place`; errors once the whole value holds
    /// more than [`MAX_TOTAL_ITEMS`]. Checks for Ctrl-C now and then, since
    /// a long conversion holds the GIL.
    fn take(&mut self, py: Python<'_>, place: &Place<'_>) -> PyResult<()> {
        self.items += 1;
        if self.items > MAX_TOTAL_ITEMS {
            return Err(too_many(place));
        }
        if self.items.is_multiple_of(SIGNAL_EVERY) {
            py.check_signals()?;
        }
        Ok(())
    }
}

/// Why the list at a key may hold no more: the longest list a scene key takes.
const LONGEST_LIST: &str = "the longest list a scene key takes: start.angles at chain.links' cap";

/// The error for a sequence or dict at `place` longer than `max` (`why`).
fn too_long(place: &Place<'_>, max: usize, why: &str) -> PyErr {
    field_error(
        place,
        format!("a list or dict here holds at most {max} items ({why}); this one holds more"),
    )
}

/// The error for a value that holds more than [`MAX_TOTAL_ITEMS`] in all.
fn too_many(place: &Place<'_>) -> PyErr {
    field_error(
        place,
        format!(
            "a value holds at most {MAX_TOTAL_ITEMS} items in all, nested ones included \
             (start.angles and start.rates at chain.links' cap, and the other keys); this one holds more"
        ),
    )
}

/// The error for a value nested deeper than [`MAX_DEPTH`] at `place`.
fn too_deep(place: &Place<'_>) -> PyErr {
    field_error(
        place,
        format!(
            "a value nests at most {MAX_DEPTH} levels deep (a scene value has at most 3: \
             a section, a list in it, a number); does a list or dict contain itself?"
        ),
    )
}

/// A Python value as a scene value, as `--set KEY=VALUE` would give it:
/// a `str` is parsed as the text after `=` (`"dopri5"`, `"[3.0, 0.0]"`,
/// `"100"`), `bool`, `int` and `float` (numpy scalars too) are themselves,
/// sequences (lists, tuples, numpy arrays, iterators) are arrays and dicts
/// are tables. `key` names the value in errors.
///
/// The conversion is bounded before it allocates: a list, iterator or dict
/// holds at most [`MAX_ITEMS`] items, the whole value [`MAX_TOTAL_ITEMS`],
/// it nests at most [`MAX_DEPTH`] deep, and a `str` is at most
/// [`MAX_TEXT`] bytes. Past a bound (an endless iterator such as
/// `itertools.count()`, a list that contains itself) it raises ValueError
/// naming the key.
pub fn to_toml(value: &Bound<'_, PyAny>, key: &str) -> PyResult<toml::Value> {
    convert(value, &Place::Key(key), &mut Budget { items: 0 })
}

/// The items of a sequence or iterator (not a `str`, `bytes` or dict) as
/// scene values, each converted as [`to_toml`] does and named `key` in
/// errors: a sweep's values. At most `max` items (`why` says whose cap),
/// and [`MAX_TOTAL_ITEMS`] in all; `None` if `values` is not iterable.
pub fn to_toml_items(
    values: &Bound<'_, PyAny>,
    key: &str,
    max: usize,
    why: &str,
) -> PyResult<Option<Vec<toml::Value>>> {
    if values.is_instance_of::<PyString>()
        || values.is_instance_of::<pyo3::types::PyBytes>()
        || values.is_instance_of::<PyDict>()
    {
        return Ok(None);
    }
    let Ok(items) = values.try_iter() else {
        return Ok(None);
    };
    let place = Place::Key(key);
    if values.len().is_ok_and(|len| len > max) {
        return Err(too_long(&place, max, why));
    }
    let mut budget = Budget { items: 0 };
    let mut out = Vec::new();
    for (i, item) in items.enumerate() {
        if i >= max {
            return Err(too_long(&place, max, why));
        }
        budget.take(values.py(), &place)?;
        // Each value is a scene value of its own (its elements are named
        // `key.0`, ... as `--set` would), at the depth of the key.
        out.push(convert(&item?, &place, &mut budget)?);
    }
    Ok(Some(out))
}

/// The conversion of [`to_toml`] of the value at `place`.
fn convert(
    value: &Bound<'_, PyAny>,
    place: &Place<'_>,
    budget: &mut Budget,
) -> PyResult<toml::Value> {
    let py = value.py();
    if place.depth() > MAX_DEPTH {
        return Err(too_deep(place));
    }
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(toml::Value::Boolean(b.is_true()));
    }
    if let Ok(s) = value.cast::<PyString>() {
        let text = s.to_cow()?;
        if text.len() > MAX_TEXT {
            return Err(field_error(
                place,
                format!(
                    "text values must be at most {MAX_TEXT} bytes (got {})",
                    text.len()
                ),
            ));
        }
        let parsed = parse_value(&text).map_err(|m| field_error(place, m))?;
        check_parsed(&parsed, place, budget)?;
        return Ok(parsed);
    }
    if value.is_instance_of::<PyInt>() {
        return value
            .extract::<i64>()
            .map(toml::Value::Integer)
            .map_err(|_| {
                field_error(
                    place,
                    format!(
                        "must fit a 64-bit integer, {}..={} (got {})",
                        i64::MIN,
                        i64::MAX,
                        echo(value)
                    ),
                )
            });
    }
    if let Ok(x) = value.cast::<PyFloat>() {
        return Ok(toml::Value::Float(x.value()));
    }
    if let Ok(d) = value.cast::<PyDict>() {
        if d.len() > MAX_ITEMS {
            return Err(too_long(place, MAX_ITEMS, LONGEST_LIST));
        }
        let mut table = toml::Table::new();
        // A snapshot of the items: converting a value runs Python code
        // (`__iter__`, `__index__`), which may change the dict.
        for item in d.items().iter() {
            let (k, v) = item.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>()?;
            let k: String = k.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "{}: table keys must be str (got {})",
                    echo_text(&place.to_string()),
                    echo(&k)
                ))
            })?;
            let inner = Place::Name(place, &k);
            budget.take(py, &inner)?;
            let v = convert(&v, &inner, budget)?;
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
            // A sized sequence (a list, a numpy array, `range`) that is too
            // long fails before a single item is read.
            if let Ok(len) = value.len() {
                if len > MAX_ITEMS {
                    return Err(too_long(place, MAX_ITEMS, LONGEST_LIST));
                }
            }
            let mut array = Vec::new();
            for (i, item) in items.enumerate() {
                if i >= MAX_ITEMS {
                    return Err(too_long(place, MAX_ITEMS, LONGEST_LIST));
                }
                let inner = Place::Index(place, i);
                budget.take(py, &inner)?;
                array.push(convert(&item?, &inner, budget)?);
            }
            return Ok(toml::Value::Array(array));
        }
    }
    // Other numbers (numpy.float32, a 0-d array, Fraction, Decimal).
    if let Ok(x) = value.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    Err(PyTypeError::new_err(format!(
        "{}: cannot use a value of type '{}' in a scene (use str, bool, int, float, a sequence or a dict)",
        echo_text(&place.to_string()),
        echo_text(&value.get_type().name()?.to_string_lossy())
    )))
}

/// The bounds of [`to_toml`] on a value parsed from text: its depth (the
/// TOML parser has its own, larger limit) and its items.
fn check_parsed(value: &toml::Value, place: &Place<'_>, budget: &mut Budget) -> PyResult<()> {
    let depth = place.depth();
    if depth > MAX_DEPTH {
        return Err(too_deep(place));
    }
    let len = match value {
        toml::Value::Array(a) => a.len(),
        toml::Value::Table(t) => t.len(),
        _ => return Ok(()),
    };
    if len > MAX_ITEMS {
        return Err(too_long(place, MAX_ITEMS, LONGEST_LIST));
    }
    budget.items = budget.items.saturating_add(len);
    if budget.items > MAX_TOTAL_ITEMS {
        return Err(too_many(place));
    }
    match value {
        toml::Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                check_parsed(v, &Place::Index(place, i), budget)?;
            }
        }
        toml::Value::Table(t) => {
            for (k, v) in t {
                check_parsed(v, &Place::Name(place, k), budget)?;
            }
        }
        _ => {}
    }
    Ok(())
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

/// A read-only `(a, b, c)` float64 array over `data`, row-major (no copy).
pub fn array3(
    py: Python<'_>,
    data: Vec<f64>,
    shape: (usize, usize, usize),
) -> PyResult<Py<PyArray3<f64>>> {
    let a = Array3::from_shape_vec(shape, data)
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
