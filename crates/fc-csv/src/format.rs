//! The number and text formats of the study's CSV tables (and of
//! `figures/data/`, which xtask writes with the same functions).
//!
//! Every number of a deterministic table is [`num`] (the shortest text that
//! reads back to the same `f64`) or [`exp`] (the same in exponent form, for
//! steps, tolerances and errors: `1e-3`). A label never holds a comma
//! ([`text`]: semicolons instead, so the figures' tables need no quotes);
//! a user's text that must read back as given (a scene name) is
//! [`crate::field`], quoted when it holds a comma, a quote or a line
//! break.

/// `x` in the shortest text that reads back to `x`: `0.0005`, `4.157`, `NaN`.
pub fn num(x: f64) -> String {
    format!("{x}")
}

/// `x` in the shortest exponent text that reads back to `x`: `1e-3`, `2.5e-5`.
pub fn exp(x: f64) -> String {
    format!("{x:e}")
}

/// `x` in the shortest text that reads back to `x`, as a person writes
/// it: [`num`]'s plain decimals for magnitudes in `[1e-4, 1e16)` (and 0,
/// NaN, inf), [`exp`]'s exponent form outside (`1e-300`, not 302
/// digits). For the cells and messages that echo a user's value.
pub fn short(x: f64) -> String {
    if !x.is_finite() || x == 0.0 || (1e-4..1e16).contains(&x.abs()) {
        num(x)
    } else {
        exp(x)
    }
}

/// An optional number: empty when absent.
pub fn opt(x: Option<f64>, f: fn(f64) -> String) -> String {
    x.map_or_else(String::new, f)
}

/// A text cell: commas (the separator) become semicolons, and a cell that
/// still holds a quote or a line break is quoted (RFC 4180), so that every
/// table reads back ([`crate::Reader`]).
pub fn text(s: &str) -> String {
    crate::field(&s.replace(',', ";")).into_owned()
}

/// `x` with `decimals` decimals (long per-sample tables, wall times).
pub fn fixed(x: f64, decimals: usize) -> String {
    format!("{x:.decimals$}")
}

/// `x` in exponent form with `digits` decimals: `1.23e-5` (wall times:
/// more digits than the noise would be false precision).
pub fn exp_digits(x: f64, digits: usize) -> String {
    format!("{x:.digits$e}")
}

/// A short relative-error text for legends, e.g. `3e-12` (the leading digit
/// rounded down).
pub fn short_err(e: f64) -> String {
    if e.is_finite() && e > 0.0 {
        let x = 10f64.powf(e.log10().floor());
        format!("{:.0}e{}", (e / x).floor(), x.log10().round() as i64)
    } else {
        format!("{e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::table::parse_num;

    #[test]
    fn numbers_read_back_exactly() {
        for x in [0.1, 1.0 / 3.0, 4.157, 1e-13, 6.02e23, -0.0005] {
            assert_eq!(parse_num(&num(x)).unwrap(), x);
            assert_eq!(parse_num(&exp(x)).unwrap(), x);
        }
        assert!(parse_num("").unwrap().is_nan());
        assert!(parse_num(&num(f64::NAN)).unwrap().is_nan());
        assert_eq!(exp(1e-3), "1e-3");
        assert_eq!(exp(5e-4), "5e-4");
        assert_eq!(exp(0.02), "2e-2");
        assert_eq!(short_err(3.7e-12), "3e-12");
        assert_eq!(fixed(0.1234567, 6), "0.123457");
        assert_eq!(text("folded, r = 0"), "folded; r = 0");
        assert_eq!(text("a \"b\"\nc"), "\"a \"\"b\"\"\nc\"");
    }
}
