//! The number and text formats of the study's CSV tables (and of
//! `figures/data/`, which xtask writes with the same functions).
//!
//! Every number of a deterministic table is [`num`] (the shortest text that
//! reads back to the same `f64`) or [`exp`] (the same in exponent form, for
//! steps, tolerances and errors: `1e-3`). A text cell never holds a comma
//! ([`text`]), so the tables need no quoting.

/// `x` in the shortest text that reads back to `x`: `0.0005`, `4.157`, `NaN`.
pub fn num(x: f64) -> String {
    format!("{x}")
}

/// `x` in the shortest exponent text that reads back to `x`: `1e-3`, `2.5e-5`.
pub fn exp(x: f64) -> String {
    format!("{x:e}")
}

/// An optional number: empty when absent.
pub fn opt(x: Option<f64>, f: fn(f64) -> String) -> String {
    x.map_or_else(String::new, f)
}

/// A text cell: commas (the separator) become semicolons.
pub fn text(s: &str) -> String {
    s.replace(',', ";")
}
