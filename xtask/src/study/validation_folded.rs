//! `folded-vs-analytic`, `support-force` and `folded-tip-acceleration`:
//! the folded chain with r = 0 against the energy-conserving law (Calkin &
//! March 1989), the force on the pivot during the fall, and the tip's
//! acceleration. The tables are `fc_paper_figures::folded`'s; here are
//! the scenes and the drawing.

use std::sync::OnceLock;

use fc_paper_figures::folded::{self, FoldedRun};
use fc_paper_figures::plot;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

static FOLDED: OnceLock<Result<Vec<FoldedRun>, String>> = OnceLock::new();

/// The folded runs with r = 0, n = 50 .. 400, made once per process.
fn folded_runs(ctx: &Ctx) -> Result<&'static [FoldedRun], String> {
    FOLDED
        .get_or_init(|| {
            let base = ctx.scene("folded", &["chain.damping=0"])?;
            let runs = ctx.pool()?.install(|| folded::folded_runs(&base))?;
            for r in &runs {
                println!("  {}", r.note);
            }
            Ok(runs)
        })
        .as_ref()
        .map(|v| v.as_slice())
        .map_err(|e| e.clone())
}

/// Writes `tables` as `<id><suffix>.csv` and prints `notes`.
fn write_all(
    ctx: &Ctx,
    id: &str,
    tables: &[(&str, &str)],
    notes: &[String],
) -> Result<Vec<String>, String> {
    for n in notes {
        println!("  {id}: {n}");
    }
    ctx.write_tables(id, tables)
}

pub struct FoldedVsAnalytic;

impl Make for FoldedVsAnalytic {
    /// `folded-vs-analytic.csv` (the fall of each n), `-times.csv` (times to
    /// L/2 and 0.9 L against the law) and `-law.csv` (the law's and free
    /// fall's speed against `xi`).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = folded::vs_law(folded_runs(ctx)?)?;
        let tables = [("", &*t.curve), ("-times", &*t.times), ("-law", &*t.law)];
        write_all(ctx, fig.id, &tables, &t.notes)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::folded::vs_law)
    }
}

pub struct SupportForce;

impl Make for SupportForce {
    /// `support-force.csv`: the pivot force at every sample of the folded
    /// falls and of the span d = 3 scene; `support-force-law.csv`: the law.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let runs = folded_runs(ctx)?;
        // The catenary scene for comparison, as the scene runs it (adaptive).
        let span = ctx.scene::<&str>("span-d3", &[])?;
        let span_traj = folded::span_run(&span).map_err(|e| format!("{}: span-d3: {e}", fig.id))?;
        let t = folded::support_force(runs, ("span-d3", &span_traj))?;
        write_all(ctx, fig.id, &[("", &t.force), ("-law", &t.law)], &t.notes)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::folded::support_force)
    }
}

/// Why the tip beats `g`: the simulated tip's downward acceleration in the
/// folded fall (r = 0) against the law and free fall.
pub struct FoldedTipAcceleration;

impl Make for FoldedTipAcceleration {
    /// `folded-tip-acceleration.csv`: `links,t,xi,accel_over_g,law_over_g`
    /// at every output sample of the fall of the runs of `ACCEL_LINKS`
    /// rods, and `-at.csv`, the comparison at a few `xi`
    /// (`fc_paper_figures::folded::tip_acceleration`).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let (csv, at) = folded::tip_acceleration(folded_runs(ctx)?);
        write_all(ctx, fig.id, &[("", &csv), ("-at", &at)], &[])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::folded::tip_acceleration)
    }
}
