//! The study on any scene: work-precision ([`precision`]), where each
//! method fails ([`stability`]), and what a scene needs ([`needs`]: rods,
//! method and tolerance, physical terms), with their time budget
//! ([`budget`]) and shards ([`shard`]); the tables of the convergence in
//! n ([`convergence`]), of matched accuracy ([`matched`]) and of when two
//! runs separate ([`divergence`]), which the paper's figures use.
//!
//! Each takes a prepared scene (or a scene) and options and returns rows of
//! plain data, with the text of its CSV table; it knows nothing of figure
//! files or of the paper. The CLI's `precision`, `stability`, `needs` and
//! `merge`, Python's functions of the same names and the figures of `cargo
//! xtask figures` (which keeps the choice of scenes and the drawing) call
//! these.

pub mod budget;
pub mod convergence;
pub mod divergence;
pub mod format;
pub mod matched;
pub mod needs;
pub mod plot;
pub mod precision;
pub mod shard;
pub mod stability;
pub mod tip_mass;

use chain_ode::Method;

use crate::error::{echo, Error};

/// The median of `xs` (NaN if empty).
pub fn median(xs: &[f64]) -> f64 {
    let mut v = xs.to_vec();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        k if k % 2 == 1 => v[k / 2],
        k => 0.5 * (v[k / 2 - 1] + v[k / 2]),
    }
}

/// Parses `--methods rk4,dop853`: method names (each at most once, in
/// `Method::ALL` order); `None` or empty text: every method.
pub fn parse_methods(what: &str, text: Option<&str>) -> Result<Vec<Method>, Error> {
    let Some(text) = text.filter(|t| !t.trim().is_empty()) else {
        return Ok(Method::ALL.to_vec());
    };
    let mut chosen = vec![];
    for name in text.split(',').map(str::trim) {
        let m = Method::ALL
            .into_iter()
            .find(|m| m.as_str() == name)
            .ok_or_else(|| {
                let names: Vec<&str> = Method::ALL.iter().map(|m| m.as_str()).collect();
                Error::field(
                    what,
                    format!("'{}' is not one of {}", echo(name), names.join(", ")),
                )
            })?;
        if !chosen.contains(&m) {
            chosen.push(m);
        }
    }
    Ok(Method::ALL
        .into_iter()
        .filter(|m| chosen.contains(m))
        .collect())
}
