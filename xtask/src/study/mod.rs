//! The new figures of the study (`../shared/figures.md`, "New figures"):
//! each computes its data, writes it as CSV to `figures/data/<id>.csv`, and
//! draws `figures/<id>.png` and `.svg` from that data.

mod precision;
mod validation;

use std::path::PathBuf;

/// What a study figure may use.
pub struct Ctx {
    /// The workspace root.
    pub root: PathBuf,
    /// `figures/`.
    pub out: PathBuf,
    /// `figures/data/`.
    pub data: PathBuf,
    /// Worker threads for independent runs (never for timed runs).
    pub jobs: usize,
}

/// One new figure (or a family of figures sharing one computation).
pub struct Study {
    /// The id `--only` selects it by; its files are `<id>*.png/.svg/.csv`.
    pub id: &'static str,
    /// One line for figures/README.md.
    pub what: &'static str,
    /// Computes, writes the data and draws; returns the files it wrote
    /// (relative to the workspace root).
    pub make: fn(&Ctx) -> Result<Vec<String>, String>,
}

/// Every study figure, in the order of figures.md.
pub fn all() -> Vec<&'static Study> {
    precision::STUDIES
        .iter()
        .chain(validation::STUDIES.iter())
        .collect()
}
