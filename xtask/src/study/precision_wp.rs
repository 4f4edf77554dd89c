//! Work-precision diagrams, `wp-<scene>`: the error of two well-conditioned
//! quantities (the tip position at an evaluation time, the maximum tip speed
//! up to it) against the wall time and against the right-hand-side
//! evaluations of each method, relative to a reference computed far tighter
//! than any plotted point and confirmed by two other methods.
//!
//! Which points a line runs is decided by their cost (see [`sweep`]), and
//! so by wall times: `--timings` measures them and records the decision,
//! the plan, with the wall times in `<id>-timing.csv`; without it the
//! points of the recorded plan are run once each, untimed and in parallel,
//! so that `<id>.csv` (steps, evaluations, errors: no wall time) is the
//! same to the byte whenever the physics is.

use std::fmt::Write as _;

use chain_ode::Method;
use falling_chain::study::divergence::{self, divergence};
use falling_chain::study::plot;
use falling_chain::study::precision::{self, params, Checks, Plan, Point, Reference};
use falling_chain::Prepared;

use crate::ctx::Ctx;
use crate::data::{exp, exp_digits, text};
use crate::registry::{Figure, Make};
use crate::timing::median;

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
        let notes = match self.eval {
            Eval::End => vec![],
            Eval::BeforeSeparation => {
                vec![divergence::note(
                    &ctx.read(&format!("{}-divergence.csv", fig.id))?,
                )?]
            }
        };
        let out = plot::work_precision(self.label, &rows, notes)
            .save(&ctx.stem(fig.id))
            .map_err(|e| e.to_string())?;
        Ok(ctx.drawn(&out))
    }
}

/// Every line as the plan in `<id>-timing.csv` says, each point run once,
/// untimed, in parallel.
fn planned(
    ctx: &Ctx,
    fig: &Figure,
    p: &Prepared,
    reference: &Reference,
) -> Result<Vec<Point>, String> {
    let file = format!("{}-timing.csv", fig.id);
    let t = ctx.read(&file)?;
    let (method, param, plan) = (t.strs("method")?, t.strs("param")?, t.strs("plan")?);
    let mut jobs = vec![];
    for m in Method::ALL {
        for &x in params(m) {
            let k = (0..t.len())
                .find(|&k| method[k] == m.as_str() && param[k] == exp(x))
                .ok_or_else(|| {
                    format!(
                        "figures/data/{file} has no plan for {m} at {} {}: run \
                         `cargo xtask figures --only {} --timings`",
                        m.accuracy_name(),
                        exp(x),
                        fig.id
                    )
                })?;
            jobs.push((m, x, Plan::parse(plan[k])?));
        }
    }
    ctx.pool()?
        .install(|| precision::run_planned(p, &jobs, reference))
        .map_err(|e| e.to_string())
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
    let (reference, mut rows) =
        precision::reference(&p, t_eval, checks).map_err(|e| e.to_string())?;
    let Some(reference) = reference else {
        return Err(format!(
            "{}: the reference run ended {}",
            fig.id, rows[0].status
        ));
    };
    // The lines: timed, or as the timing file's plan says.
    if ctx.timings {
        for method in Method::ALL {
            rows.extend(precision::timed_line(&p, method, &reference).map_err(|e| e.to_string())?);
        }
        precision::repeat_interleaved(&p, &mut rows).map_err(|e| e.to_string())?;
    } else {
        rows.extend(planned(ctx, fig, &p, &reference)?);
    }
    let csv = precision::csv_text(spec.scene, t_eval, &reference, &rows, None);
    let mut files = vec![ctx.write(&format!("{}.csv", fig.id), &csv)?];
    if ctx.timings {
        files.push(write_timing(ctx, fig, &rows)?);
    }
    Ok(files)
}

/// `<id>-timing.csv`: the plan, and the median wall time of each run.
fn write_timing(ctx: &Ctx, fig: &Figure, rows: &[Point]) -> Result<String, String> {
    let mut csv = String::from("method,param_name,param,plan,repeats,wall_median,note\n");
    for pt in rows {
        let wall = if pt.walls.is_empty() {
            String::new()
        } else {
            exp_digits(median(&mut pt.walls.clone()), 3)
        };
        writeln!(
            csv,
            "{},{},{},{},{},{wall},{}",
            pt.method,
            pt.param_name,
            exp(pt.param),
            pt.plan.as_str(),
            pt.walls.len(),
            text(&pt.timing_note)
        )
        .unwrap();
    }
    ctx.write(&format!("{}-timing.csv", fig.id), &csv)
}

