//! What a figure's `compute` and `draw` may use: the workspace's folders,
//! the one scene loader, the scene runs the report's figures share, and
//! reading and writing `figures/data/`.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use fc_paper_figures::plot::Reader;
use fc_scene::{Prepared, Scene};

use crate::data::Table;
use crate::registry::Figure;
use crate::runs::SceneRun;

pub struct Ctx {
    /// The workspace root.
    pub root: PathBuf,
    /// `figures/`.
    pub out: PathBuf,
    /// `figures/data/`.
    pub data: PathBuf,
    /// Worker threads for independent, untimed runs (never for timed ones).
    pub jobs: usize,
    /// `--timings`: measure wall times and rewrite the timing files.
    pub timings: bool,
    /// The scene runs of the report's figures, made once before they are
    /// computed (empty with `--draw-only`).
    pub runs: BTreeMap<&'static str, SceneRun>,
    /// What each figure drawn so far got wrong in its layout (its id and
    /// `figures::Output::problems`: data spanning less than half an axis,
    /// a box over data), for the warning after drawing and the registry's
    /// test.
    pub layout_problems: Mutex<Vec<(String, Vec<String>)>>,
    /// How many panels drawn so far reported their layout.
    pub panels_checked: AtomicUsize,
}

impl Ctx {
    pub fn new(root: &Path, jobs: usize, timings: bool) -> Ctx {
        let out = root.join("figures");
        Ctx {
            root: root.to_path_buf(),
            data: out.join("data"),
            out,
            jobs,
            timings,
            runs: BTreeMap::new(),
            layout_problems: Mutex::new(Vec::new()),
            panels_checked: AtomicUsize::new(0),
        }
    }

    /// The scene file `scenes/<name>.toml` with `overrides` (`key=value`)
    /// applied: the one way xtask loads a scene.
    pub fn scene<S: AsRef<str>>(&self, name: &str, overrides: &[S]) -> Result<Scene, String> {
        let path = self.root.join("scenes").join(format!("{name}.toml"));
        let scene = Scene::load(&path).map_err(|e| e.to_string())?;
        if overrides.is_empty() {
            return Ok(scene);
        }
        scene
            .with_overrides(overrides)
            .map_err(|e| format!("{name}: {e}"))
    }

    /// [`Ctx::scene`], ready to run and recording no samples (summaries only).
    pub fn prepare<S: AsRef<str>>(&self, name: &str, overrides: &[S]) -> Result<Prepared, String> {
        let mut p = self
            .scene(name, overrides)?
            .prepare()
            .map_err(|e| format!("{name}: {e}"))?;
        p.options.output_dt = None;
        Ok(p)
    }

    /// The shared run of scene `name` (made before the report's figures).
    pub fn run(&self, name: &str) -> Result<&SceneRun, String> {
        self.runs
            .get(name)
            .ok_or_else(|| format!("the scene '{name}' was not run"))
    }

    /// A worker pool of [`Ctx::jobs`] threads.
    pub fn pool(&self) -> Result<rayon::ThreadPool, String> {
        rayon::ThreadPoolBuilder::new()
            .num_threads(self.jobs.max(1))
            .build()
            .map_err(|e| e.to_string())
    }

    /// Writes `figures/data/<file>` atomically; returns its path relative to
    /// the root.
    pub fn write(&self, file: &str, text: &str) -> Result<String, String> {
        write_text(&self.data.join(file), text)?;
        Ok(self.relative(&self.data.join(file)))
    }

    /// Writes each `(suffix, csv)` of `tables` as `<id><suffix>.csv`.
    pub fn write_tables<S: AsRef<str>>(
        &self,
        id: &str,
        tables: &[(&str, S)],
    ) -> Result<Vec<String>, String> {
        (tables.iter())
            .map(|(suffix, csv)| self.write(&format!("{id}{suffix}.csv"), csv.as_ref()))
            .collect()
    }

    /// Reads `figures/data/<file>`.
    pub fn read(&self, file: &str) -> Result<Table, String> {
        Table::read(&self.data.join(file)).map_err(|e| {
            if self.data.join(file).exists() {
                e
            } else {
                format!(
                    "figures/data/{file} is missing: run `cargo xtask figures{}`",
                    if file.ends_with(crate::timing::SUFFIX) {
                        " --timings"
                    } else {
                        ""
                    }
                )
            }
        })
    }

    /// `figures/<id>`, the stem the figures crate appends `.png` and `.svg` to.
    pub fn stem(&self, id: &str) -> PathBuf {
        self.out.join(id)
    }

    /// Draws `fig` with `draw` (a drawing of `fc_paper_figures::plot`)
    /// from its data files `<id><suffix>.csv`; returns the files written.
    pub fn draw(
        &self,
        fig: &Figure,
        draw: impl Fn(Reader, &Path) -> Result<figures::Output, String>,
    ) -> Result<Vec<String>, String> {
        let read = |suffix: &str| self.read(&format!("{}{suffix}.csv", fig.id));
        let out = draw(&read, &self.stem(fig.id)).map_err(|e| format!("{}: {e}", fig.id))?;
        self.panels_checked
            .fetch_add(out.panels.len(), Ordering::Relaxed);
        let problems = out.problems();
        if !problems.is_empty() {
            if let Ok(mut all) = self.layout_problems.lock() {
                all.push((fig.id.to_string(), problems));
            }
        }
        Ok(self.drawn(&out))
    }

    /// The files a figure was drawn to, relative to the root.
    pub fn drawn(&self, out: &figures::Output) -> Vec<String> {
        vec![self.relative(&out.png), self.relative(&out.svg)]
    }

    /// `path` relative to the workspace root.
    pub fn relative(&self, path: &Path) -> String {
        path.strip_prefix(&self.root)
            .unwrap_or(path)
            .display()
            .to_string()
    }
}

/// Writes `text` to `path` atomically (xtask's every text output).
pub fn write_text(path: &Path, text: &str) -> Result<(), String> {
    fc_scene::atomic::write_atomic("xtask output", path, |w: &mut dyn Write| {
        w.write_all(text.as_bytes())
    })
    .map_err(|e| e.to_string())
}
