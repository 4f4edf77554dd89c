//! `figures/data/`: the CSV files every figure is drawn from and the paper
//! quotes, read as a [`Table`] and written in the study's formats
//! (`fc_csv::format`): every number of the deterministic data
//! is `num` (shortest text that reads back to the same `f64`, so a figure
//! drawn from the file is the figure drawn from the computation) or `exp`,
//! except long per-sample tables, which are `fixed` to a few decimals to
//! stay small. Timing files use `fixed` and `exp_digits`.

// Every helper a figure file may use, as before the move to the library
// (figures added on other branches use them).
#[allow(
    unused_imports,
    reason = "the figure files' helpers: not every one is used by today's figures"
)]
pub use fc_csv::format::{exp, exp_digits, fixed, num, opt, short_err, text};
#[allow(
    unused_imports,
    reason = "the figure files' helpers: not every one is used by today's figures"
)]
pub use fc_csv::table::{distinct, parse_num, Table};
