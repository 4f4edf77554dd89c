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
