//! `tip-mass-fall`: the folded chain with a point mass `M` at its free end
//! (n = 400, r = 0) against the energy-conserving law, for `M / m_c` from
//! 0.1 to 10: the fall time over free fall and the tip speed at the end of
//! the fall. The runs and the table are the library's
//! (`falling_chain::study::tip_mass`); this file keeps the choice of ratios
//! and the drawing.

use falling_chain::study::tip_mass;
use figures::{palette, LinePlot, RGBColor, Series, Style};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The mass ratios `k = M / m_c` run.
const RATIOS: [f64; 7] = [0.1, 0.25, 0.5, 1.0, 2.0, 5.0, 10.0];
/// Rods: the n = 400.
const LINKS: usize = 400;

pub struct TipMassFall;

impl Make for TipMassFall {
    /// `tip-mass-fall.csv` (one run per ratio against the law) and
    /// `tip-mass-fall-law.csv` (the law's curves).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let rows = ctx.pool()?.install(|| tip_mass::rows(&RATIOS, LINKS))?;
        for r in &rows {
            println!(
                "  {id}: M/m_c = {}: fall time {:+.3}% of the law's",
                r.ratio,
                100.0 * (r.t_fall / r.t_law - 1.0)
            );
        }
        Ok(vec![
            ctx.write(&format!("{id}.csv"), &tip_mass::csv_text(&rows))?,
            ctx.write(
                &format!("{id}-law.csv"),
                &tip_mass::law_csv(0.05, 20.0, 200),
            )?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let id = fig.id;
        let runs = ctx.read(&format!("{id}.csv"))?;
        let (k, t, v) = (
            runs.nums("ratio")?,
            runs.nums("t_fall")?,
            runs.nums("v_fall")?,
        );
        let (t_law, v_law) = (runs.nums("t_law")?, runs.nums("v_law")?);
        let law = ctx.read(&format!("{id}-law.csv"))?;
        let (lk, lt, lv) = (law.nums("ratio")?, law.nums("t_law")?, law.nums("v_final")?);
        let black = RGBColor(0, 0, 0);
        let zip = |a: &[f64], b: &[f64]| a.iter().copied().zip(b.iter().copied()).collect();
        let mut left = LinePlot::new(
            "fall time over free fall sqrt(2L/g)",
            "M / m_c",
            "t_fall / sqrt(2 L / g)",
        );
        left.series.push(
            Series::new("law (full extension)", zip(&lk, &lt), Style::Dashed).with_color(black),
        );
        left.series.push(
            Series::new("law at 0.99 (L - l)", zip(&k, &t_law), Style::Points)
                .with_color(palette(1)),
        );
        left.series.push(
            Series::new(
                format!("n = {LINKS}, r = 0"),
                zip(&k, &t),
                Style::LinePoints,
            )
            .with_color(palette(0)),
        );
        left.log_x = true;
        let mut right = LinePlot::new(
            "tip speed at the end of the fall",
            "M / m_c",
            "|v| / sqrt(g L)",
        );
        right.series.push(
            Series::new(
                "law at full extension: sqrt(2 (1 + m_c / 4M))",
                zip(&lk, &lv),
                Style::Dashed,
            )
            .with_color(black),
        );
        right.series.push(
            Series::new("law at 0.99 (L - l)", zip(&k, &v_law), Style::Points)
                .with_color(palette(1)),
        );
        right.series.push(
            Series::new(
                format!("n = {LINKS}, r = 0"),
                zip(&k, &v),
                Style::LinePoints,
            )
            .with_color(palette(0)),
        );
        right.log_x = true;
        right.log_y = true;
        let out = figures::line_plot_pair(
            &left,
            &right,
            "Folded chain with a tip mass M: runs against the energy-conserving law",
            &ctx.stem(id),
        )
        .map_err(|e| format!("{id}: {e}"))?;
        Ok(ctx.drawn(&out))
    }
}
