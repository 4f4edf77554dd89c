//! Tables that check the model against physics: the energy budget of runs
//! (`E + W` conserved, with `W` the work dissipated by joint friction) and
//! the normal modes of the hanging chain against the continuum's Bessel
//! frequencies. `cargo xtask figures` chooses the runs and draws them
//! (`energy-budget`, `normal-modes`).

use std::fmt::Write as _;

use chain_ode::analysis::bessel_frequencies;
use chain_ode::kinematics::{kinetic_energy, potential_energy};
use chain_ode::modes::hanging_frequencies;
use chain_ode::{Chain, Trajectory};

use fc_csv::format::num;
use fc_study::linear_fit;

/// The energy `E = T + V`, the dissipated work `W` and the balance
/// `(E + W - E(0)) / (M g L)` at every sample of each run:
/// `damping,damping_rate,energy_scale,t,kinetic,potential,energy,dissipated,
/// balance_over_MgL`; and a line per run with its largest balance error.
pub fn energy_budget(runs: &[Trajectory]) -> (String, Vec<String>) {
    let mut notes = vec![];
    let mut csv = String::from(
        "damping,damping_rate,energy_scale,t,kinetic,potential,energy,dissipated,\
         balance_over_MgL\n",
    );
    for traj in runs {
        let chain = traj.chain();
        let scale = chain.energy_scale();
        let mut e0 = None;
        let mut worst: f64 = 0.0;
        for s in traj.samples() {
            let t = kinetic_energy(chain, s.angles, s.rates);
            let v = potential_energy(chain, s.angles);
            let e = t + v;
            let e0 = *e0.get_or_insert(e);
            let b = (e + s.dissipated - e0) / scale;
            worst = worst.max(b.abs());
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{}",
                num(chain.damping()),
                num(chain.damping_rate()),
                num(scale),
                num(s.t),
                num(t),
                num(v),
                num(e),
                num(s.dissipated),
                num(b)
            );
        }
        notes.push(format!(
            "r = {} (r/(m l^2) = {:.3}): max |E + W - E(0)| = {worst:.2e} M g L",
            chain.damping(),
            chain.damping_rate()
        ));
    }
    (csv, notes)
}

/// The lowest `modes` frequencies of the linearised hanging report chain of
/// each of `links` rods against `omega_k = (j_{0,k}/2) sqrt(g/L)`
/// (`links,mode,omega,omega_bessel,relative_error,omega_sqrt_L_over_g,
/// omega_bessel_sqrt_L_over_g`), and the convergence order of each mode
/// fitted (least squares in log-log) to the relative errors from
/// `fit_from` rods on (`mode,order,coefficient,fit_from_links,
/// fit_to_links`), with a line per mode.
pub fn normal_modes(
    links: &[usize],
    modes: usize,
    fit_from: usize,
) -> Result<(String, String, Vec<String>), String> {
    let first = links.first().copied().unwrap_or(10);
    let last = links.last().copied().unwrap_or(first);
    let base = Chain::report(first, 0.0).map_err(|e| e.to_string())?;
    let bessel = bessel_frequencies(&base);
    let unit = (base.length() / base.gravity()).sqrt();
    let mut csv = String::from(
        "links,mode,omega,omega_bessel,relative_error,omega_sqrt_L_over_g,\
         omega_bessel_sqrt_L_over_g\n",
    );
    let mut errors = vec![vec![]; modes];
    for &n in links {
        let chain = Chain::report(n, 0.0).map_err(|e| e.to_string())?;
        let w = hanging_frequencies(&chain);
        if w.len() < modes || bessel.len() < modes {
            return Err(format!("n = {n}: fewer than {modes} modes"));
        }
        for k in 0..modes {
            let rel = w[k] / bessel[k] - 1.0;
            let _ = writeln!(
                csv,
                "{n},{},{},{},{},{},{}",
                k + 1,
                num(w[k]),
                num(bessel[k]),
                num(rel),
                num(w[k] * unit),
                num(bessel[k] * unit)
            );
            errors[k].push((n as f64, rel));
        }
    }
    let mut fit_csv = String::from("mode,order,coefficient,fit_from_links,fit_to_links\n");
    let mut notes = vec![];
    for (k, errors) in errors.iter().enumerate() {
        let logs: Vec<(f64, f64)> = errors
            .iter()
            .filter(|p| p.0 >= fit_from as f64 && p.1 > 0.0)
            .map(|p| (p.0.ln(), p.1.ln()))
            .collect();
        let (a, b) = linear_fit(&logs);
        let (order, coefficient) = (-b, a.exp());
        let _ = writeln!(
            fit_csv,
            "{},{},{},{fit_from},{last}",
            k + 1,
            num(order),
            num(coefficient),
        );
        notes.push(format!(
            "mode {}: p = {order:.3}, C = {coefficient:.4}",
            k + 1
        ));
    }
    Ok((csv, fit_csv, notes))
}
