//! Work-precision diagrams, `wp-<scene>`: the error of two well-conditioned
//! quantities (the tip position at an evaluation time, the maximum tip speed
//! up to it) against the wall time and against the right-hand-side
//! evaluations of each method, relative to a reference computed far tighter
//! than any plotted point and confirmed by two other methods.
//!
//! Which points a line runs is decided by their cost (see `falling_chain::study::plan`), and
//! so by wall times: `--timings` measures them and records the decision,
//! the plan, with the wall times in `<id>-timing.csv`; without it the
//! points of the recorded plan are run once each, untimed and in parallel,
//! so that `<id>.csv` (steps, evaluations, errors: no wall time) is the
//! same to the byte whenever the physics is.

use falling_chain::study::divergence::{self, divergence};
use falling_chain::study::plan;
use falling_chain::study::plot;
use falling_chain::study::precision::{self, Checks};
use falling_chain::study::work_cost::{self, Weights};
use falling_chain::Prepared;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// Where a work-precision figure evaluates its errors.
pub enum Eval {
    /// At the scene's end.
    End,
    /// At the last time before two runs started [`divergence::PERTURBATION`] apart
    /// separate (their tip distance amplified more than
    /// [`divergence::AMPLIFICATION_MAX`] times), or at the end if they never do;
    /// measured for the scene and for its `r = 0` variant, and written to
    /// `<id>-divergence.csv`.
    BeforeSeparation,
}

/// One work-precision figure.
pub struct Spec {
    scene: &'static str,
    /// Shown in the title.
    label: &'static str,
    /// RK4 step of the check of the reference.
    check_dt: f64,
    /// Check with RK4 at `check_dt` and `check_dt / 2`, extrapolated.
    richardson: bool,
    eval: Eval,
}

pub const SPAN_D3: Spec = Spec {
    scene: "span-d3",
    label: "span d = 3 (n = 50, r = 5e-4)",
    check_dt: 1e-4,
    richardson: false,
    eval: Eval::End,
};

pub const FOLDED: Spec = Spec {
    scene: "folded",
    label: "folded (n = 50, r = 1e-3)",
    check_dt: 2e-5,
    richardson: true,
    eval: Eval::BeforeSeparation,
};

pub const STIFF_ROPE: Spec = Spec {
    scene: "stiff-rope",
    label: "stiff rope (n = 100, r = 1, γ = 1389)",
    check_dt: 3e-5,
    richardson: false,
    eval: Eval::End,
};

impl Make for Spec {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let mut files = vec![];
        let p = ctx.prepare::<&str>(self.scene, &[])?;
        let (p, t_eval) = match self.eval {
            Eval::End => {
                let t_eval = p.options.t_end;
                (p, t_eval)
            }
            Eval::BeforeSeparation => {
                let div = divergence(&p).map_err(|e| e.to_string())?;
                let undamped = divergence(&ctx.prepare(self.scene, &["chain.damping=0"])?)
                    .map_err(|e| e.to_string())?;
                let csv = divergence::csv_text(&[(p.chain.damping(), &div), (0.0, &undamped)]);
                files.push(ctx.write(&format!("{}-divergence.csv", fig.id), &csv)?);
                let t_eval = div.t_eval;
                if t_eval < div.t_whip {
                    return Err(format!(
                        "{}: runs separate (t = {t_eval}) before the whip (t = {:.3})",
                        fig.id, div.t_whip
                    ));
                }
                (
                    ctx.prepare(self.scene, &[format!("run.t_end={t_eval}")])?,
                    t_eval,
                )
            }
        };
        files.extend(study(ctx, fig, self, p, t_eval)?);
        Ok(files)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let rows = plot::wp_points(&t, Some(&ctx.read(&format!("{}-timing.csv", fig.id))?))?;
        let weights = Weights::from_table(&ctx.read(&format!("{}-cost-timing.csv", fig.id))?)?;
        let notes = match self.eval {
            Eval::End => vec![],
            Eval::BeforeSeparation => {
                vec![divergence::note(
                    &ctx.read(&format!("{}-divergence.csv", fig.id))?,
                )?]
            }
        };
        let out = plot::work_precision_weighted(self.label, &rows, notes, Some(weights))
            .save(&ctx.stem(fig.id))
            .map_err(|e| e.to_string())?;
        Ok(ctx.drawn(&out))
    }
}

fn study(
    ctx: &Ctx,
    fig: &Figure,
    spec: &Spec,
    p: Prepared,
    t_eval: f64,
) -> Result<Vec<String>, String> {
    let checks = Checks {
        check_dt: spec.check_dt,
        richardson: spec.richardson,
    };
    // The lines: timed, or as the timing file's plan says.
    let jobs = if ctx.timings {
        None
    } else {
        let timing = ctx.read(&format!("{}-timing.csv", fig.id))?;
        Some(plan::plan_of(&timing).map_err(|e| {
            format!(
                "figures/data/{e}: run `cargo xtask figures --only {} --timings`",
                fig.id
            )
        })?)
    };
    let (reference, rows) = ctx
        .pool()?
        .install(|| plan::rows(&p, t_eval, checks, jobs.as_deref()))
        .map_err(|e| format!("{}: {e}", fig.id))?;
    let csv = precision::csv_text(spec.scene, t_eval, &reference, &rows, None);
    let mut files = vec![ctx.write(&format!("{}.csv", fig.id), &csv)?];
    if ctx.timings {
        let timing = plan::timing_text(&rows);
        files.push(ctx.write(&format!("{}-timing.csv", fig.id), &timing)?);
        // What BDF's units cost against a right-hand side, at the start.
        let cost = work_cost::csv_text(&p.chain, &p.state)?;
        files.push(ctx.write(&format!("{}-cost-timing.csv", fig.id), &cost)?);
    }
    Ok(files)
}
