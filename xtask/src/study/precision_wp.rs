//! Work-precision diagrams, `wp-<scene>`: the error of two well-conditioned
//! quantities (the tip position at an evaluation time, the maximum tip speed
//! up to it) against the wall time and against the right-hand-side
//! evaluations of each method, relative to a reference computed far tighter
//! than any plotted point and confirmed by two other methods.
//!
//! Which points a line runs is decided by their cost (see `fc_paper_figures::plan`), and
//! so by wall times: `--timings` measures them and records the decision,
//! the plan, with the wall times in `<id>-timing.csv`; without it the
//! points of the recorded plan are run once each, untimed and in parallel,
//! so that `<id>.csv` (steps, evaluations, errors: no wall time) is the
//! same to the byte whenever the physics is.

use fc_paper_figures::plan::{self, Eval};
use fc_paper_figures::plot;
use fc_study::precision::Checks;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

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
        let checks = Checks {
            check_dt: self.check_dt,
            richardson: self.richardson,
        };
        // The points: timed, or as the timing file's plan says.
        let plan = (!ctx.timings)
            .then(|| ctx.read(&format!("{id}-timing.csv")))
            .transpose()?;
        let prepare = |set: &[String]| ctx.prepare(self.scene, set);
        let tables = ctx
            .pool()?
            .install(|| plan::figure(self.scene, &prepare, self.eval, checks, plan.as_ref()))
            .map_err(|e| format!("{id}: {e} (`cargo xtask figures --only {id} --timings`)"))?;
        ctx.write_tables(id, &tables)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, |r, s| plot::wp_figure(r, s, self.label, self.eval))
    }
}
