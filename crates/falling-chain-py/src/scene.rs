//! `falling_chain.Scene`: a scene file, as the CLI reads it.

use std::path::PathBuf;

use ::fc_scene::{Error, Scene};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{table_to_dict, to_toml, value_error};

/// The longest scene text: the largest scene file the CLI reads (1 MiB).
const MAX_SCENE_TEXT: usize = ::fc_scene::scene::MAX_SCENE_BYTES as usize;

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
    /// `scene.set("run.method", "dopri5")`.
    ///
    /// A `str` value is read as the text after `=` in `--set` (so
    /// `"[2.5, 0.0]"` is an array and `"dopri5"` a string); numbers, bools,
    /// sequences (numpy arrays too) and dicts are taken as they are. The
    /// scene is not changed. Raises ValueError naming the key for an unknown
    /// key or a value of the wrong type.
    fn set(&self, key: &str, value: &Bound<'_, PyAny>) -> PyResult<Self> {
        let value = to_toml(value, key)?;
        self.inner
            .with_value(key, value)
            .map(Self::new)
            .map_err(value_error)
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
