//! Work-precision lines whose points are chosen by their cost, and so by
//! wall times, made reproducible: a timed study records its decision, the
//! plan, beside its wall times ([`timing_text`]); an untimed one reads the
//! plan back ([`plan_of`]) and runs those points once each, in parallel, so
//! that its table (steps, evaluations, errors, no wall time) is the same to
//! the byte whenever the physics is ([`rows`]).

use chain_ode::Method;

use fc_csv::format::{exp, exp_digits, text};
use fc_csv::table::Table;
use fc_scene::scene::Prepared;
use fc_study::precision::{self, params, Checks, Plan, Point, Reference};

/// The plan of every method's every point from a timing table
/// (`method,param,plan`), in [`crate::PAPER_METHODS`] order.
pub fn plan_of(t: &Table) -> Result<Vec<(Method, f64, Plan)>, String> {
    let (method, param, plan) = (t.strs("method")?, t.strs("param")?, t.strs("plan")?);
    let mut jobs = vec![];
    for m in crate::PAPER_METHODS {
        for &x in params(m) {
            let k = (0..t.len())
                .find(|&k| method[k] == m.as_str() && param[k] == exp(x))
                .ok_or_else(|| {
                    format!(
                        "{} has no plan for {m} at {} {}",
                        t.name,
                        m.accuracy_name(),
                        exp(x)
                    )
                })?;
            jobs.push((m, x, Plan::parse(plan[k])?));
        }
    }
    Ok(jobs)
}

/// The reference at `t_eval` (with its `checks`) and every method's line:
/// timed, repeated and interleaved when `plan` is `None`, else the points
/// of `plan`, each run once, untimed, in parallel on the current rayon pool.
pub fn rows(
    p: &Prepared,
    t_eval: f64,
    checks: Checks,
    plan: Option<&[(Method, f64, Plan)]>,
) -> Result<(Reference, Vec<Point>), String> {
    let (reference, mut rows) =
        precision::reference(p, t_eval, checks).map_err(|e| e.to_string())?;
    let Some(reference) = reference else {
        return Err(format!("the reference run ended {}", rows[0].status));
    };
    match plan {
        None => {
            for method in crate::PAPER_METHODS {
                rows.extend(
                    precision::timed_line(p, method, &reference).map_err(|e| e.to_string())?,
                );
            }
            precision::repeat_interleaved(p, &mut rows).map_err(|e| e.to_string())?;
        }
        Some(jobs) => {
            rows.extend(precision::run_planned(p, jobs, &reference).map_err(|e| e.to_string())?)
        }
    }
    Ok((reference, rows))
}

/// A work-precision study's tables: its points ([`precision::csv_text`]
/// of scene `scene` at `t_eval`) and, when timed (`plan` is `None`), its
/// timing table ([`timing_text`]); else the points of the timing table
/// `plan` ([`plan_of`]) are run once each, untimed, on the current rayon
/// pool.
pub fn tables(
    scene: &str,
    p: &Prepared,
    t_eval: f64,
    checks: Checks,
    plan: Option<&Table>,
) -> Result<(String, Option<String>), String> {
    let jobs = plan.map(plan_of).transpose()?;
    let (reference, points) = rows(p, t_eval, checks, jobs.as_deref())?;
    let csv = precision::csv_text(scene, t_eval, &reference, &points, None);
    Ok((csv, plan.is_none().then(|| timing_text(&points))))
}

/// Where a work-precision figure evaluates its errors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Eval {
    /// At the scene's end.
    End,
    /// At the last time before two runs started
    /// [`super::divergence::PERTURBATION`] apart separate (their tip
    /// distance amplified more than [`super::divergence::AMPLIFICATION_MAX`]
    /// times), or at the end if they never do; measured for the scene and
    /// for its `r = 0` variant ([`super::divergence::evaluation`]).
    BeforeSeparation,
}

/// The tables of the work-precision figure of scene `scene`, as
/// `(suffix, csv)` in the order written: `-divergence` (with
/// [`Eval::BeforeSeparation`]), the points ([`tables`], `""`) and, when
/// timed (`plan` is `None`), `-timing` and `-cost-timing` (what BDF's
/// units cost against a right-hand side at the start,
/// [`fc_study::work_cost::csv_text`]). `prepare` gives the scene with the
/// overrides passed (`chain.damping=0`, `run.t_end=...`) and no samples.
pub fn figure(
    scene: &str,
    prepare: &dyn Fn(&[String]) -> Result<Prepared, String>,
    eval: Eval,
    checks: Checks,
    plan: Option<&Table>,
) -> Result<Vec<(&'static str, String)>, String> {
    let mut files = vec![];
    let mut p = prepare(&[])?;
    let mut t_eval = p.options.t_end;
    if eval == Eval::BeforeSeparation {
        let undamped = prepare(&["chain.damping=0".into()])?;
        let (csv, t) = super::divergence::evaluation(&p, &undamped)?;
        files.push(("-divergence", csv));
        (p, t_eval) = (prepare(&[format!("run.t_end={t}")])?, t);
    }
    let (csv, timing) = tables(scene, &p, t_eval, checks, plan)?;
    files.push(("", csv));
    if let Some(timing) = timing {
        files.push(("-timing", timing));
        files.push((
            "-cost-timing",
            fc_study::work_cost::csv_text(&p.chain, &p.state)?,
        ));
    }
    Ok(files)
}

/// The timing table: `method,param_name,param,plan,repeats,wall_median,note`,
/// the plan and the median wall time (s) of each point's runs.
pub fn timing_text(rows: &[Point]) -> String {
    let mut csv = String::from("method,param_name,param,plan,repeats,wall_median,note\n");
    for pt in rows {
        let wall = if pt.walls.is_empty() {
            String::new()
        } else {
            exp_digits(fc_study::median(&pt.walls), 3)
        };
        csv.push_str(&format!(
            "{},{},{},{},{},{wall},{}\n",
            pt.method,
            pt.param_name,
            exp(pt.param),
            pt.plan.as_str(),
            pt.walls.len(),
            text(&pt.timing_note)
        ));
    }
    csv
}
