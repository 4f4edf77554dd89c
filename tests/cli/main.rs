//! End-to-end tests of the `falling-chain` binary, run as a user would, and of
//! the scene files in `scenes/`, one module per command. Expected values come
//! from the physics (closed forms, energy balance, geometry), never from
//! earlier output.
// The helpers are test code too: a failing check is a panic.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "test code: a failed check panics"
)]

mod browser;
mod browser_profile;
mod browser_runs;
mod catenary;
mod cluster;
mod common;
mod converge;
mod ensemble;
mod floor;
mod fuzz;
mod gen_alpha;
mod hardening_three;
mod hostile;
mod hostile_files;
mod hostile_model;
mod hostile_studies;
mod memory;
mod newton_counters;
mod pivot;
mod plot;
mod progress;
mod readme;
mod report;
mod scenes;
mod simulate;
mod study;
mod sweep;
mod view;
mod wind_model;
