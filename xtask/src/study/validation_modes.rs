//! `normal-modes`: the lowest five frequencies of the linearised hanging
//! chain of n rods against the continuum's `omega_k = (j_{0,k}/2) sqrt(g/L)`,
//! and the convergence order fitted to the relative errors (least squares
//! in log-log over n >= 40).

use falling_chain::study::validation;
use figures::{palette, LinePlot, Series, Style};

use crate::ctx::Ctx;
use crate::data::distinct;
use crate::registry::{Figure, Make};

const LINKS: [usize; 12] = [10, 14, 20, 28, 40, 57, 80, 100, 160, 226, 320, 400];
const MODES: usize = 5;
const FIT_FROM: usize = 40;

pub struct NormalModes;

impl Make for NormalModes {
    /// `normal-modes.csv` (every n and mode, also in units of `sqrt(g/L)`)
    /// and `normal-modes-fit.csv` (the fitted order of each mode).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let (csv, fit, notes) = validation::normal_modes(&LINKS, MODES, FIT_FROM)?;
        for n in notes {
            println!("  {}: {n}", fig.id);
        }
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &csv)?,
            ctx.write(&format!("{}-fit.csv", fig.id), &fit)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let (links, mode, rel) = (t.nums("links")?, t.strs("mode")?, t.nums("relative_error")?);
        let (omega, bessel) = (
            t.nums("omega_sqrt_L_over_g")?,
            t.nums("omega_bessel_sqrt_L_over_g")?,
        );
        let f = ctx.read(&format!("{}-fit.csv", fig.id))?;
        let (fit_mode, order, coefficient) =
            (f.strs("mode")?, f.nums("order")?, f.nums("coefficient")?);
        let fit_from = f.strs("fit_from_links")?.first().copied().unwrap_or("?");
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
        let mut notes = vec![format!("fit over n >= {fit_from}: error = C / n^p")];
        for (k, m) in distinct(&mode).into_iter().enumerate() {
            let rows: Vec<usize> = (0..t.len()).filter(|&j| mode[j] == m).collect();
            if let Some(j) = fit_mode.iter().position(|x| *x == m) {
                notes.push(format!(
                    "mode {m}: p = {:.3}, C = {:.4}",
                    order[j], coefficient[j]
                ));
            }
            left.series.push(
                Series::new(
                    format!("mode {m}"),
                    rows.iter().map(|&j| (links[j], omega[j])).collect(),
                    Style::LinePoints,
                )
                .with_color(palette(k)),
            );
            let b = bessel[rows[0]];
            left.series.push(
                Series::new(
                    if k == 0 { "j_0k / 2 (continuum)" } else { "" },
                    vec![(8.0, b), (500.0, b)],
                    Style::Dashed,
                )
                .with_color(palette(k)),
            );
            right.series.push(
                Series::new(
                    format!("mode {m}"),
                    rows.iter().map(|&j| (links[j], rel[j])).collect(),
                    Style::LinePoints,
                )
                .with_color(palette(k)),
            );
        }
        left.x_range = Some((8.0, 500.0));
        left.y_range = Some((0.0, 15.0));
        right.x_range = Some((8.0, 500.0));
        right.y_range = Some((1e-8, 1e5));
        right.annotations = notes;
        let title = "Small oscillations of the hanging chain: n rods against the Bessel zeros";
        let out = figures::line_plot_pair(&left, &right, title, &ctx.stem(fig.id))
            .map_err(|e| format!("{}: {e}", fig.id))?;
        Ok(ctx.drawn(&out))
    }
}
