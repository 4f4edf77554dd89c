//! Scenes, outputs and the `falling-chain` command line.
//!
//! This is the only crate of the workspace that knows TOML, CSV and JSON:
//! [`Scene`] reads a scene file (and `--set` overrides) into the chain-ode
//! types, checked against [`schema::KEYS`], the one table of scene keys;
//! [`RunSummary`] is what a run prints as JSON or as a CSV row, [`csv`] writes a trajectory's samples, and [`atomic`] makes every output
//! file appear whole or not at all; [`viewer`] writes the self-contained
//! HTML page of `view` (and [`run_csv`] reads a run back from `--out`'s CSV). Every error is an [`Error`], one line
//! that starts with the field it is about.

pub mod atomic;
pub mod catenary_report;
pub mod converge;
pub mod csv;
pub mod error;
pub mod overrides;
pub mod progress;
pub mod render;
pub mod run_csv;
pub mod scene;
pub mod schema;
pub mod study;
pub mod summary;
pub mod sweep;
pub mod viewer;

pub use catenary_report::{CatenaryReport, DiscreteReport};
pub use error::{CatenaryNames, Error};
pub use scene::{Prepared, Scene};
pub use schema::StartKind;
pub use summary::{RunSummary, SegmentSummary, SUMMARY_CSV_COLUMNS};
