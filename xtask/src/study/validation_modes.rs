//! `normal-modes`: the lowest five frequencies of the linearised hanging
//! chain of n rods against the continuum's `omega_k = (j_{0,k}/2) sqrt(g/L)`,
//! and the convergence order fitted to the relative errors (least squares
//! in log-log over n >= 40).

use chain_ode::analysis::bessel_frequencies;
use chain_ode::modes::hanging_frequencies;
use chain_ode::Chain;
use figures::{palette, LinePlot, Series, Style};

use super::{figure_files, num, stem, write_data};
use crate::study::Ctx;

const ID: &str = "normal-modes";
const LINKS: [usize; 12] = [10, 14, 20, 28, 40, 57, 80, 100, 160, 226, 320, 400];
const MODES: usize = 5;
const FIT_FROM: usize = 40;

/// Least-squares slope and intercept of `y = a + b x`.
fn fit(pts: &[(f64, f64)]) -> (f64, f64) {
    let k = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mx, my) = (sx / k, sy / k);
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let b = sxy / sxx;
    (my - b * mx, b)
}

pub fn make(ctx: &Ctx) -> Result<Vec<String>, String> {
    let base = Chain::report(LINKS[0], 0.0).map_err(|e| e.to_string())?;
    let bessel = bessel_frequencies(&base);
    let unit = (base.length / base.gravity).sqrt();
    let mut csv = String::from("links,mode,omega,omega_bessel,relative_error\n");
    let mut errors = vec![vec![]; MODES];
    let mut omegas = vec![vec![]; MODES];
    for &n in &LINKS {
        let chain = Chain::report(n, 0.0).map_err(|e| e.to_string())?;
        let w = hanging_frequencies(&chain);
        for k in 0..MODES {
            let rel = w[k] / bessel[k] - 1.0;
            csv.push_str(&format!(
                "{n},{},{},{},{}\n",
                k + 1,
                num(w[k]),
                num(bessel[k]),
                num(rel)
            ));
            errors[k].push((n as f64, rel));
            omegas[k].push((n as f64, w[k] * unit));
        }
    }
    let mut fit_csv = String::from("mode,order,coefficient,fit_from_links,fit_to_links\n");
    let mut left = LinePlot::new(
        "frequencies against the continuum",
        "n (rods)",
        "omega sqrt(L/g)",
    );
    left.log_x = true;
    let mut right = LinePlot::new(
        "relative error (all positive: the chain is stiffer)",
        "n (rods)",
        "omega_n / omega_Bessel - 1",
    );
    right.log_x = true;
    right.log_y = true;
    let mut notes = vec!["fit over n >= 40: error = C / n^p".to_string()];
    for k in 0..MODES {
        let logs: Vec<(f64, f64)> = errors[k]
            .iter()
            .filter(|p| p.0 >= FIT_FROM as f64 && p.1 > 0.0)
            .map(|p| (p.0.ln(), p.1.ln()))
            .collect();
        let (a, b) = fit(&logs);
        let (order, coefficient) = (-b, a.exp());
        fit_csv.push_str(&format!(
            "{},{},{},{FIT_FROM},{}\n",
            k + 1,
            num(order),
            num(coefficient),
            LINKS[LINKS.len() - 1]
        ));
        notes.push(format!(
            "mode {}: p = {order:.3}, C = {coefficient:.4}",
            k + 1
        ));
        left.series.push(
            Series::new(
                format!("mode {}", k + 1),
                omegas[k].clone(),
                Style::LinePoints,
            )
            .with_color(palette(k)),
        );
        left.series.push(
            Series::new(
                if k == 0 { "j_0k / 2 (continuum)" } else { "" },
                vec![(8.0, bessel[k] * unit), (500.0, bessel[k] * unit)],
                Style::Dashed,
            )
            .with_color(palette(k)),
        );
        right.series.push(
            Series::new(
                format!("mode {}", k + 1),
                errors[k].clone(),
                Style::LinePoints,
            )
            .with_color(palette(k)),
        );
    }
    left.x_range = Some((8.0, 500.0));
    left.y_range = Some((0.0, 15.0));
    right.x_range = Some((8.0, 500.0));
    right.y_range = Some((1e-8, 1e5));
    right.annotations = notes.clone();
    let mut files = vec![
        write_data(ctx, &format!("{ID}.csv"), &csv)?,
        write_data(ctx, &format!("{ID}-fit.csv"), &fit_csv)?,
    ];
    let title = "Small oscillations of the hanging chain: n rods against the Bessel zeros";
    figures::line_plot_pair(&left, &right, title, &stem(ctx, ID))
        .map_err(|e| format!("{ID}: {e}"))?;
    for n in &notes {
        println!("  {ID}: {n}");
    }
    files.extend(figure_files(ID));
    Ok(files)
}
