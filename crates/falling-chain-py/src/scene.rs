//! `falling_chain.Scene`: a scene file, as the CLI reads it.

use std::path::PathBuf;

use ::fc_scene::{Error, Scene};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{table_to_dict, to_toml, value_error};

/// The longest scene text: the largest scene file the CLI reads (1 MiB).
const MAX_SCENE_TEXT: usize = ::fc_scene::scene::MAX_SCENE_BYTES as usize;

/// The most keys one `Scene.set({...})` takes.
const MAX_SET_KEYS: usize = 1000;

/// A scene: a chain, how it starts and how to run it (the TOML files of
/// `scenes/`, described in `scenes/README.md`).
///
/// Make one with `Scene.load(path)` or `Scene.from_toml(text)`; change it
/// with `scene.set(key, value)`, which returns a new scene. Loading and
/// `set` check the keys and the types, as the CLI does when it reads a
/// scene and its `--set` overrides; the ranges (a positive length, a
/// catenary that fits, a known method, ...) are checked when the scene runs,
/// or by `scene.check()`. Every error is a `ValueError` whose message is the
/// CLI's one line, starting with the field (`chain.links: ...`).
#[pyclass(name = "Scene", module = "falling_chain", frozen, eq)]
#[derive(Clone, PartialEq)]
pub struct PyScene {
    pub inner: Scene,
}

impl PyScene {
    pub fn new(inner: Scene) -> Self {
        Self { inner }
    }
}

#[pymethods]
impl PyScene {
    /// Reads a scene file. A scene without `name` is named after the file.
    ///
    /// Raises ValueError (`scene: cannot read '...': ...`, or the field at
    /// fault) as `falling-chain simulate PATH` would report it.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        Scene::load(&path).map(Self::new).map_err(value_error)
    }

    /// Parses a scene from TOML text. A scene without `name` is named "scene".
    /// The text is at most 1 MiB, as a scene file is.
    #[staticmethod]
    fn from_toml(text: &str) -> PyResult<Self> {
        if text.len() > MAX_SCENE_TEXT {
            return Err(value_error(Error::field(
                "scene",
                format!(
                    "the scene text is larger than {MAX_SCENE_TEXT} bytes (1 MiB, the largest scene file; got {})",
                    text.len()
                ),
            )));
        }
        Scene::from_toml_str(text)
            .map(Self::new)
            .map_err(value_error)
    }

    /// A new scene with the value at the dotted `key` replaced, as
    /// `--set KEY=VALUE` does: `scene.set("chain.links", 100)`,
    /// `scene.set("start.p1", [2.5, 0.0])`, `scene.set("start.p1.0", 2.5)`,
    /// `scene.set("run.method", "dopri5")`; or, given one dict, several
    /// values at once, applied in order and checked together:
    /// `scene.set({"start.kind": "angles", "start.angles": phi})`.
    ///
    /// A `str` value is read as the text after `=` in `--set` (so
    /// `"[2.5, 0.0]"` is an array and `"dopri5"` a string); numbers, bools,
    /// sequences (numpy arrays too) and dicts are taken as they are.
    /// Setting `start.kind` removes the `[start]` keys the new kind does not
    /// take (`p1` when a catenary start becomes `folded`), so a start
    /// changes kind with its own keys in one call. The scene is not
    /// changed. Raises ValueError naming the key for an unknown key or a
    /// value of the wrong type; a dict holds at most 1000 keys.
    #[pyo3(signature = (key, value=None))]
    fn set(&self, key: &Bound<'_, PyAny>, value: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let values = match (key.cast::<PyDict>(), value) {
            (Ok(dict), None) => {
                if dict.len() > MAX_SET_KEYS {
                    return Err(value_error(Error::field(
                        "set",
                        format!("at most {MAX_SET_KEYS} keys at once (got {})", dict.len()),
                    )));
                }
                let mut values = Vec::with_capacity(dict.len());
                for (k, v) in dict.iter() {
                    let k: String = k.extract().map_err(|_| {
                        PyTypeError::new_err("set: the dict's keys must be dotted key strings")
                    })?;
                    let v = to_toml(&v, &k)?;
                    values.push((k, v));
                }
                values
            }
            (Err(_), Some(value)) => {
                let k: String = key.extract().map_err(|_| {
                    PyTypeError::new_err("set: key must be a dotted key string (or one dict)")
                })?;
                let v = to_toml(value, &k)?;
                vec![(k, v)]
            }
            (Ok(_), Some(_)) => {
                return Err(PyTypeError::new_err(
                    "set: give one dict of keys and values, or a key and a value",
                ))
            }
            (Err(_), None) => {
                return Err(PyTypeError::new_err(
                    "set: missing the value (set(key, value), or set({key: value, ...}))",
                ))
            }
        };
        let values: Vec<(&str, toml::Value)> = values
            .iter()
            .map(|(k, v)| (k.as_str(), v.clone()))
            .collect();
        self.inner
            .with_values(&values)
            .map(Self::new)
            .map_err(value_error)
    }

    /// A new scene without the value at the dotted `key`, which takes its
    /// default again (`scene.unset("run.method")`); unsetting a key that is
    /// not set changes nothing. Raises ValueError naming the key for an
    /// unknown key, an element (`start.p1.0`) or a key that must be given
    /// (`chain.links`, a start's own required keys).
    fn unset(&self, key: &str) -> PyResult<Self> {
        self.inner.without(key).map(Self::new).map_err(value_error)
    }

    /// A new scene: the same continuous chain cut into `n` rods, by the
    /// rule `falling-chain converge` uses (`--refine N` on the CLI): the
    /// total mass `M = n m`, the length, the bending viscosity `eta = r l`,
    /// EA, EI and the tip mass kept, so the per-rod `chain.mass` and
    /// `chain.damping` change. `scene.set("chain.links", n)` is not a
    /// refinement: it keeps the per-rod mass and friction. A folded
    /// start's `start.down` scales with n. Raises ValueError for n outside
    /// 1..=1000000 (naming `n`) and for an `angles` start.
    fn refine(&self, n: usize) -> PyResult<Self> {
        ::fc_scene::refine::check_links("n", n).map_err(value_error)?;
        self.inner.refined(n).map(Self::new).map_err(value_error)
    }

    /// The scene as TOML text (with every `set` applied; defaults left out).
    fn to_toml(&self) -> String {
        self.inner.to_toml_string()
    }

    /// The scene's TOML tree as a dict (defaults left out).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        table_to_dict(py, self.inner.tree())
    }

    /// Checks everything a run needs (chain, start, method, options), as
    /// the CLI does before it runs; raises ValueError naming the field.
    fn check(&self) -> PyResult<()> {
        self.inner.prepare().map(|_| ()).map_err(value_error)
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> &str {
        self.inner.name()
    }

    /// What the scene is (free text).
    #[getter]
    fn description(&self) -> &str {
        self.inner.description()
    }

    fn __repr__(&self) -> String {
        format!("Scene(name={:?})", self.inner.name())
    }
}
