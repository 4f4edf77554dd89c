//! The paper of the study, as a document tool apart from the figures:
//! [`fill`] fills `paper/paper.tmpl.md`, `paper/methods.tmpl.md` and
//! `paper/supplement.tmpl.md` with numbers read from the CSV files of
//! `figures/data/` and writes `paper/<name>.md` (or checks that they
//! are current, and that every typed decimal is an input [`typed`] finds
//! listed in `paper/inputs.csv`); [`pdf`] typesets the filled papers as PDF; [`catalogue`]
//! is the figure catalogue as plain data (`figures/README.md`, the checks of
//! what each figure writes). `cargo xtask paper [--check | --pdf]` and
//! `cargo xtask figures` call them.

pub mod catalogue;
pub mod fill;
pub mod pdf;
pub mod typed;
