//! `elastic-layout-order`: how the elastic chain converges to the
//! continuum rope as `n` grows at fixed `EA` and mass per length
//! (`docs/model.md`, "Where the compliance sits"). A rope of unit length,
//! mass and gravity hangs at rest; its axial frequencies (from the model's
//! own Jacobian, [`chain_ode::modes::axial_frequencies`]) are compared with
//! the fixed-free rope's `(2j - 1) pi c / (2L)`, `c = sqrt(EA / mu)`, and
//! its tip's self-weight stretch with the rope's `(M/2 + M_t) g L / EA`,
//! without and with a tip mass `M_t = M`. Deterministic.

use std::fmt::Write as _;

use chain_ode::modes::axial_frequencies;
use chain_ode::{elastic, Chain, ChainParams, Start};
use fc_csv::format::num;
use fc_study::linear_fit;

/// `links,mode,omega,omega_rope,relative_error`.
pub const MODES_HEADER: &str = "links,mode,omega,omega_rope,relative_error\n";
/// `links,tip_mass_over_M,stretch,stretch_rope,relative_error`.
pub const STRETCH_HEADER: &str = "links,tip_mass_over_M,stretch,stretch_rope,relative_error\n";
/// `quantity,order,from_links,to_links`: the least-squares slope of
/// `log |error|` against `log n`, negated.
pub const FIT_HEADER: &str = "quantity,order,from_links,to_links\n";

/// The rope: unit length, mass and gravity, `EA` in units of `M g`.
const LENGTH: f64 = 1.0;
const MASS: f64 = 1.0;
const EA: f64 = 1e4;

fn rope(n: usize, tip_mass: f64) -> Result<Chain, String> {
    Chain::new(ChainParams {
        links: n,
        length: LENGTH,
        mass: MASS / n as f64,
        gravity: 1.0,
        tip_mass,
        axial_stiffness: Some(EA),
        ..ChainParams::default()
    })
    .map_err(|e| e.to_string())
}

/// The self-weight stretch of `chain` hanging at rest: how far below `L`
/// the tip of the model's own equilibrium start hangs.
fn stretch(chain: &Chain) -> Result<f64, String> {
    let s = Start::Angles {
        p0: [0.0, 0.0],
        angles: vec![-std::f64::consts::FRAC_PI_2; chain.links()],
        rates: None,
    }
    .state(chain)
    .map_err(|e| e.to_string())?;
    let y = elastic::start_state(chain, &s);
    Ok(-elastic::tip(chain, [0.0, 0.0], &y)[1] - chain.length())
}

/// Relative errors below this are rounding (a stretch of `5e-5 L` read off
/// positions of order `L` summed over up to hundreds of rods).
pub const ROUNDING: f64 = 1e-8;

/// The order fitted to `(n, error)` from `from` rods on (errors at rounding
/// left out).
fn order(points: &[(usize, f64)], from: usize) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.0 >= from && p.1.abs() > ROUNDING)
        .map(|p| ((p.0 as f64).ln(), p.1.abs().ln()))
        .collect();
    (logs.len() >= 2).then(|| -linear_fit(&logs).1)
}

/// The three tables, for each of `links` and the lowest `modes` modes;
/// the orders are fitted from `fit_from` rods on.
pub fn tables(links: &[usize], modes: usize, fit_from: usize) -> Result<[String; 3], String> {
    let (mut freq, mut stretches, mut fit) = (
        MODES_HEADER.to_string(),
        STRETCH_HEADER.to_string(),
        FIT_HEADER.to_string(),
    );
    let c = (EA / (MASS / LENGTH)).sqrt();
    let mut mode_errors = vec![vec![]; modes];
    let mut stretch_errors = [vec![], vec![]];
    for &n in links {
        let chain = rope(n, 0.0)?;
        let omega = axial_frequencies(&chain).ok_or("a rope without EA")?;
        if omega.len() < modes || omega.iter().any(|w| !w.is_finite()) {
            return Err(format!("n = {n}: fewer than {modes} finite frequencies"));
        }
        for (j, errors) in mode_errors.iter_mut().enumerate() {
            let exact = (2 * j + 1) as f64 * std::f64::consts::PI * c / (2.0 * LENGTH);
            let rel = omega[j] / exact - 1.0;
            let _ = writeln!(
                freq,
                "{n},{},{},{},{}",
                j + 1,
                num(omega[j]),
                num(exact),
                num(rel)
            );
            errors.push((n, rel));
        }
        for (k, ratio) in [0.0, 1.0].into_iter().enumerate() {
            let chain = rope(n, ratio * MASS)?;
            let got = stretch(&chain)?;
            let exact = (0.5 + ratio) * MASS * LENGTH / EA;
            let rel = got / exact - 1.0;
            let _ = writeln!(
                stretches,
                "{n},{ratio},{},{},{}",
                num(got),
                num(exact),
                num(rel)
            );
            stretch_errors[k].push((n, rel));
        }
    }
    let last = links.last().copied().unwrap_or(0);
    let mut row = |name: String, points: &[(usize, f64)]| {
        let o = order(points, fit_from).map_or(String::new(), num);
        let _ = writeln!(fit, "{name},{o},{fit_from},{last}");
    };
    for (j, e) in mode_errors.iter().enumerate() {
        row(format!("mode {}", j + 1), e);
    }
    row("stretch".into(), &stretch_errors[0]);
    row("stretch with M_t = M".into(), &stretch_errors[1]);
    Ok([freq, stretches, fit])
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc_csv::table::Table;

    /// The fitted orders are the derivation's: 2 for every mode, 1 for the
    /// stretch with a tip mass, and no order for the uniform stretch, which
    /// is the rope's to rounding.
    #[test]
    fn the_orders_are_two_for_the_modes_and_the_stretch_is_exact() {
        let [_, stretch, fit] = tables(&[10, 20, 40, 80], 3, 10).unwrap();
        let t = Table::parse("fit", &fit).unwrap();
        let (q, o) = (t.strs("quantity").unwrap(), t.strs("order").unwrap());
        for (q, o) in q.iter().zip(&o) {
            match *q {
                "stretch" => assert!(o.is_empty(), "{q}: {o}"),
                "stretch with M_t = M" => {
                    let o: f64 = o.parse().unwrap();
                    assert!((o - 1.0).abs() < 0.05, "{q}: {o}");
                }
                _ => {
                    let o: f64 = o.parse().unwrap();
                    assert!((o - 2.0).abs() < 0.05, "{q}: {o}");
                }
            }
        }
        let s = Table::parse("stretch", &stretch).unwrap();
        let (ratio, rel) = (
            s.nums("tip_mass_over_M").unwrap(),
            s.nums("relative_error").unwrap(),
        );
        for (r, e) in ratio.iter().zip(&rel) {
            if *r == 0.0 {
                assert!(e.abs() < ROUNDING, "{e}");
            }
        }
    }
}
