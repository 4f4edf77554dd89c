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

use falling_chain::study::divergence;
use falling_chain::study::plan;
use falling_chain::study::plot;
use falling_chain::study::precision::Checks;
use falling_chain::study::work_cost::{self, Weights};

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
        let id = fig.id;
        let mut files = vec![];
        let mut p = ctx.prepare::<&str>(self.scene, &[])?;
        let mut t_eval = p.options.t_end;
        if let Eval::BeforeSeparation = self.eval {
            let undamped = ctx.prepare(self.scene, &["chain.damping=0"])?;
            let (csv, t) =
                divergence::evaluation(&p, &undamped).map_err(|e| format!("{id}: {e}"))?;
            files.push(ctx.write(&format!("{id}-divergence.csv"), &csv)?);
            (p, t_eval) = (ctx.prepare(self.scene, &[format!("run.t_end={t}")])?, t);
        }
        let checks = Checks {
            check_dt: self.check_dt,
            richardson: self.richardson,
        };
        // The points: timed, or as the timing file's plan says.
        let plan = (!ctx.timings)
            .then(|| ctx.read(&format!("{id}-timing.csv")))
            .transpose()?;
        let (csv, timing) = ctx
            .pool()?
            .install(|| plan::tables(self.scene, &p, t_eval, checks, plan.as_ref()))
            .map_err(|e| format!("{id}: {e} (`cargo xtask figures --only {id} --timings`)"))?;
        files.push(ctx.write(&format!("{id}.csv"), &csv)?);
        if let Some(timing) = timing {
            files.push(ctx.write(&format!("{id}-timing.csv"), &timing)?);
            // What BDF's units cost against a right-hand side, at the start.
            let cost = work_cost::csv_text(&p.chain, &p.state)?;
            files.push(ctx.write(&format!("{id}-cost-timing.csv"), &cost)?);
        }
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
