//! Each method's line of points, loose to tight: its accuracies
//! ([`params`], [`ladder`]), one point's run, the figure's planned and
//! timed runs, and the CLI's lines within a budget with RK4's floor rule.

use super::*;
use std::time::Instant;

use chain_ode::{Method, SolveOptions};
use rayon::prelude::*;

use crate::subject::Subject;
use fc_batch::budget::Budget;
use fc_csv::format::num;
use fc_scene::error::Error;

/// `gen-alpha`'s tolerances, loose to tight: of second order, it reaches
/// the tighter ones only in steps that no study affords (its steps grow
/// like `rtol^(-1/3)`), so its line stops at 1e-8.
pub const GEN_ALPHA_RTOLS: [f64; 6] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];

/// The accuracies a method's line runs over: RK4's steps, the others'
/// tolerances (gen-alpha's its own, [`GEN_ALPHA_RTOLS`]).
pub fn params(method: Method) -> &'static [f64] {
    if method.accuracy_name() == "dt" {
        &RK4_DTS
    } else if method == Method::GenAlpha {
        &GEN_ALPHA_RTOLS
    } else {
        &RTOLS
    }
}

/// The ladder's points, numbered in this order: each of `methods`, each of
/// its [`params`].
pub fn ladder(methods: &[Method]) -> Vec<(Method, f64)> {
    methods
        .iter()
        .flat_map(|&m| params(m).iter().map(move |&x| (m, x)))
        .collect()
}

/// The options of a point: the subject's, with the method's accuracy
/// `param` and no samples ([`Subject::options_for`]; for a scene, atol =
/// rtol / 100).
pub fn options_for<S: Subject>(p: &S, method: Method, param: f64) -> SolveOptions {
    p.options_for(method, param)
}

/// One point, run once.
pub fn run_point<S: Subject>(
    p: &S,
    method: Method,
    param: f64,
    reference: &Reference,
) -> Result<Point, Error> {
    let t = p.solve(method, &options_for(p, method, param))?;
    Ok(Point::from_run(
        method.as_str().into(),
        method.accuracy_name(),
        param,
        &t,
        p,
        reference,
    ))
}

/// Every point of `jobs` as its plan says, each run once, untimed, in
/// parallel on the current rayon pool (the order of `jobs` kept).
pub fn run_planned<S: Subject>(
    p: &S,
    jobs: &[(Method, f64, Plan)],
    reference: &Reference,
) -> Result<Vec<Point>, Error> {
    jobs.par_iter()
        .map(|&(m, x, plan)| {
            if plan != Plan::Run {
                return Ok(Point::not_run(m, x, plan, String::new()));
            }
            run_point(p, m, x, reference)
        })
        .collect()
}

/// Repeats of a point whose first run took `wall` seconds.
pub fn repeats_for(wall: f64) -> usize {
    if wall < 0.2 {
        REPEATS_CHEAP
    } else {
        REPEATS
    }
}

/// Runs every timed point again until it has its repeats, a round over all
/// points at a time (so that a burst of load elsewhere on the machine falls
/// on many points once rather than on one point every time).
pub fn repeat_interleaved<S: Subject>(p: &S, rows: &mut [Point]) -> Result<(), Error> {
    for _ in 1..REPEATS_CHEAP.max(REPEATS) {
        for pt in rows.iter_mut() {
            let Some((method, o)) = &pt.rerun else {
                continue;
            };
            if pt.walls.len() >= repeats_for(pt.walls.first().copied().unwrap_or(0.0)) {
                continue;
            }
            let t = p.solve(*method, o)?;
            pt.walls.push(t.summary.wall_seconds);
        }
    }
    Ok(())
}

/// The wall time a line's next point is predicted to take, from its
/// completed points `(param, wall)`: RK4's scales with the number of steps,
/// an adaptive line's grows as its last two did (by 1.6 after one point).
fn predict(rk4: bool, x: f64, done: &[(f64, f64)]) -> f64 {
    match done {
        [] => 0.0,
        [.., (px, pw)] if rk4 => pw * px / x,
        [(_, w0)] => w0 * 1.6,
        [.., (_, w1), (_, w2)] => w2 * (w2 / w1).clamp(1.0, 4.0),
    }
}

/// One method's line, timed (`cargo xtask figures --timings`): RK4 over
/// [`RK4_DTS`], the others over [`RTOLS`].
///
/// Points are run once each, from cheap to costly (their repeats come
/// later, see [`repeat_interleaved`]). A point whose single run is
/// predicted (from the last completed point) to exceed [`MAX_RUN`] s, or to
/// overrun the line's [`LINE_BUDGET`], is not run, nor is any point after
/// it; RK4 stops once its errors reach [`ERR_FLOOR`]; an adaptive line whose
/// first run exceeds [`THIN_ABOVE`] s runs every third tolerance only.
pub fn timed_line<S: Subject>(
    p: &S,
    method: Method,
    reference: &Reference,
) -> Result<Vec<Point>, Error> {
    let rk4 = method.accuracy_name() == "dt";
    let mut out = vec![];
    let mut spent = 0.0;
    let mut done: Vec<(f64, f64)> = vec![];
    let mut stop: Option<(Plan, String)> = None;
    let mut thin = false;
    for (k, &x) in params(method).iter().enumerate() {
        if let Some((plan, why)) = &stop {
            out.push(Point::not_run(method, x, *plan, why.clone()));
            continue;
        }
        if thin && k % 3 != 0 {
            out.push(Point::not_run(method, x, Plan::Thinned, String::new()));
            continue;
        }
        let predicted = predict(rk4, x, &done);
        let reps = repeats_for(predicted) as f64;
        if predicted > MAX_RUN || spent + reps * predicted > LINE_BUDGET {
            let why = format!(
                "cost: predicted {predicted:.1} s per run (limit {MAX_RUN} s per run; \
                 {LINE_BUDGET} s per line)"
            );
            out.push(Point::not_run(method, x, Plan::Cost, why.clone()));
            stop = Some((Plan::Cost, why));
            continue;
        }
        let o = options_for(p, method, x);
        let t = p.solve(method, &o)?;
        let wall = t.summary.wall_seconds;
        let mut pt = Point::from_run(
            method.as_str().into(),
            method.accuracy_name(),
            x,
            &t,
            p,
            reference,
        );
        if t.status.is_ok() {
            // The repeats come later (see `repeat_interleaved`); count them now.
            spent += wall * repeats_for(wall) as f64;
            pt.rerun = Some((method, o));
            if done.is_empty() && !rk4 && wall > THIN_ABOVE {
                thin = true;
            }
            done.push((x, wall));
            if rk4 && pt.err() < ERR_FLOOR {
                stop = Some((Plan::Floor, String::new()));
            }
        }
        out.push(pt);
    }
    Ok(out)
}

/// The lines of the CLI's `precision`: the points of [`ladder`]`(methods)`
/// whose run number `take` accepts (a shard), each method's line from loose
/// to tight on one thread, the lines in parallel on the current rayon pool.
/// A line stops once a completed point passes `stop` (the later points are
/// `floor`; the CLI's [`rk4_floor`]); a point that the budget cannot fit (predicted from the line's
/// last point as [`timed_line`] does, or not started before the deadline)
/// is `budget`, and so is a run the deadline stops. `progress` is called
/// after each point. On RK4's line a shard runs the coarser points it does
/// not own, unrecorded, while they can still fire `stop`, so that its rows
/// are the whole run's rows of its run numbers (`merge` gives the
/// unsharded table).
pub fn run_lines<S: Subject>(
    p: &S,
    methods: &[Method],
    reference: &Reference,
    take: &(dyn Fn(usize) -> bool + Sync),
    budget: &Budget,
    stop: &(dyn Fn(&Point) -> bool + Sync),
    progress: &(dyn Fn() + Sync),
) -> Result<Vec<Point>, Error> {
    let mut first = 0;
    let lines: Vec<(Method, usize)> = methods
        .iter()
        .map(|&m| {
            let start = first;
            first += params(m).len();
            (m, start)
        })
        .collect();
    let per_line: Vec<Vec<Point>> = lines
        .par_iter()
        .map(|&(method, start)| {
            let rk4 = method.accuracy_name() == "dt";
            let mut out = vec![];
            let mut done: Vec<(f64, f64)> = vec![];
            let mut floor = false;
            let xs = params(method);
            // One run of the line at `x` within the budget: its point, or
            // `Err(t_reached)` if the deadline stopped it. A completed
            // point joins `done` and tells whether `stop` fired.
            let run_at = |x: f64,
                          done: &mut Vec<(f64, f64)>,
                          floor: &mut bool|
             -> Result<Result<Point, f64>, Error> {
                let mut o = options_for(p, method, x);
                o.cancel = Some(budget.cancel().clone());
                let t = p.solve(method, &o)?;
                if t.status == chain_ode::Status::Interrupted {
                    return Ok(Err(t.t_reached));
                }
                let pt = Point::from_run(
                    method.as_str().into(),
                    method.accuracy_name(),
                    x,
                    &t,
                    p,
                    reference,
                );
                if pt.ok() {
                    done.push((x, t.summary.wall_seconds));
                    *floor = stop(&pt);
                }
                Ok(Ok(pt))
            };
            for (k, &x) in xs.iter().enumerate() {
                let run = start + k;
                if !take(run) {
                    // A shard decides RK4's stop rule as the whole run does:
                    // while the rule has not fired and a finer point of the
                    // line is its own, it runs the coarser point it does not
                    // own (cheaper than its own, RK4's cost being 1/dt) and
                    // records nothing of it but the rule's answer.
                    let finer_own = (k + 1..xs.len()).any(|j| take(start + j));
                    if rk4
                        && !floor
                        && finer_own
                        && bound_of(p, method, x).is_none()
                        && budget.fits(predict(rk4, x, &done))
                    {
                        run_at(x, &mut done, &mut floor)?.ok();
                    }
                    continue;
                }
                let bound = bound_of(p, method, x);
                let plan = if floor {
                    Plan::Floor
                } else if bound.is_some() {
                    Plan::Bound
                } else if !budget.fits(predict(rk4, x, &done)) {
                    Plan::Budget
                } else {
                    Plan::Run
                };
                let mut pt = if plan == Plan::Run {
                    let started = Instant::now();
                    match run_at(x, &mut done, &mut floor)? {
                        Ok(pt) => pt,
                        Err(t_reached) => {
                            let mut pt = Point::not_run(method, x, Plan::Budget, String::new());
                            pt.note = format!(
                                "budget: stopped at t = {} after {:.1} s",
                                num(t_reached),
                                started.elapsed().as_secs_f64()
                            );
                            pt
                        }
                    }
                } else {
                    let mut pt = Point::not_run(method, x, plan, String::new());
                    if let Some(why) = &bound {
                        pt.note = format!("not run: {why}");
                    }
                    pt
                };
                pt.run = Some(run);
                out.push(pt);
                progress();
            }
            Ok(out)
        })
        .collect::<Result<_, Error>>()?;
    Ok(per_line.into_iter().flatten().collect())
}

/// The stop rule of the CLI's lines: RK4's line stops once both errors are
/// below [`ERR_FLOOR`], as in the study's figures.
pub fn rk4_floor(p: &Point) -> bool {
    p.param_name == "dt" && p.err() < ERR_FLOOR
}
