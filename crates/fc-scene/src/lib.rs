//! The scene and a run's outputs: what every front end of falling-chain
//! (the `falling-chain` CLI, the Python module) reads and writes around one
//! run, and what the batch, study and viewer crates build on.
//!
//! [`Scene`] reads a scene file (and `--set` overrides, [`overrides`]) into
//! the chain-ode types, checked against [`schema::KEYS`], the one table of
//! scene keys; [`RunSummary`] is what a run prints as JSON or as a CSV row,
//! [`csv`] writes a trajectory's samples (with the CSV layer, `fc-csv`),
//! [`catenary_report`] is the `catenary` command's answer, and [`atomic`]
//! makes every output file appear whole or not at all; [`refine`] cuts a
//! scene's chain into another number of rods at fixed continuum. Every error is an
//! [`Error`], one line that starts with the field it is about.
//!
//! Its files:
//! * `atomic.rs`: Files that appear whole or not at all.
//! * `catenary_report.rs`: What `falling-chain catenary` prints: the continuous catenary through two anchors and, for a number of rods, the exact discrete equilibrium.
//! * `csv.rs`: A trajectory's CSV files (`simulate --out` and `--forces`): one row per sample, written with the cells of the CSV layer (`fc_csv` ...
//! * `error.rs`: The one error type of this crate: every failure is one line that starts with the field (or file role) it is about.
//! * `overrides.rs`: `--set KEY=VALUE`: changes to a scene's TOML tree by dotted path, applied before the tree is deserialised ...
//! * `scene.rs`: Scenes: a chain, how it starts, and how to run it, as a TOML file.
//! * `schema.rs`: The scene schema: `KEYS`, one row per scene key, is the single source of each key's dotted path, type, default, the start kinds that take it, and its doc line.
//! * `summary.rs`: The scalar results of one run, as printed by `simulate --json` and as one CSV row per run (for sweeps).

pub mod atomic;
pub mod catenary_report;
pub mod csv;
pub mod error;
pub mod overrides;
pub mod refine;
pub mod scene;
pub mod schema;
pub mod summary;

pub use catenary_report::{CatenaryReport, DiscreteReport};
pub use error::{CatenaryNames, Error};
pub use scene::{Prepared, Scene};
pub use schema::StartKind;
pub use summary::{RunSummary, SegmentSummary, SUMMARY_CSV_COLUMNS};
