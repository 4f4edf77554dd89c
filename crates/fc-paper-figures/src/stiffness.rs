//! `stiffness`: where the implicit method pays, at matched accuracy.
//! DOPRI5 against the O(n) BDF over rods `n` and the damping rate
//! `gamma = r / (m l^2)` (1/time, `m` the rod mass), on the span d = 3 start
//! (report chain, `r` set from `gamma`) up to [`T_END`], past the whip (the
//! maximum tip speed comes at `t` = 2.76 to 2.93 for `gamma` = 0.17 to 1e4
//! at n = 50).
//!
//! Each method runs a ladder of tolerances ([`LADDER`], `atol = rtol/100`),
//! loosest first, until a run's error is at most [`TARGET`]; the error is the
//! paper's measure, the larger of the tip's error at `t_end` (over `L`) and
//! the maximum tip speed's (relative), against DOPRI5 at [`REF_RTOL`]. A
//! method's cost at the target is its wall time interpolated in log-log
//! between the two runs that bracket the target (`matched::time_at`), or,
//! where its loosest run is already below it (an explicit method held at
//! its stability limit, whose cost no tolerance lowers), that run's time
//! (`*_at = loosest` in the CSV). The cell's ratio is DOPRI5's cost over
//! BDF's at the same error; nothing is extrapolated.
//!
//! A stability-limited DOPRI5 run costs about
//! [`DOPRI5_STEPS_PER_GAMMA`]` gamma t_end` steps of
//! [`DOPRI5_STEP_PER_ROD`]` n` seconds; a cell whose predicted DOPRI5 cost
//! (its run and the reference) exceeds [`EXPLICIT_BUDGET`] is not run
//! (`run = 0`, its numbers empty) and is not drawn: it lies past the
//! crossover, where the ratio only grows.
//!
//! Wall times are the least of several runs ([`repeats`]): the machine may
//! be shared, and another process only adds to a run's time.
//!
//! Also written: the crossover `gamma` of each `n` (where the ratio reaches
//! 1 for the last time, interpolated in log-log between the bracketing grid
//! points) beside the rule `auto` uses
//! ([`chain_ode::bdf_crossover_gamma`]), and BDF's wall time per step. All
//! of it is wall times: computed only by `--timings`, into
//! `stiffness-timing.csv` and `stiffness-crossover-timing.csv`.

use std::fmt::Write as _;

use chain_ode::{bdf_crossover_gamma, solve, Chain, Method, SolveOptions, Start, State};

use super::matched::time_at;
use fc_csv::format::{exp, exp_digits, fixed};
use fc_study::precision::Reference;

/// End of each run: past the whip of the span d = 3 fall.
pub const T_END: f64 = 3.0;
/// The error both methods are timed at (the larger of the tip's and the
/// maximum tip speed's relative errors).
pub const TARGET: f64 = 1e-6;
/// The tolerances each method runs, loosest first, until one reaches
/// [`TARGET`].
pub const LADDER: [f64; 8] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10];
/// The reference: DOPRI5 at this `rtol` (`atol = rtol / 100`).
pub const REF_RTOL: f64 = 1e-11;
/// Seconds DOPRI5 (a ladder run and the reference) may be predicted to take
/// in one cell; beyond it the cell is not run.
pub const EXPLICIT_BUDGET: f64 = 6.0;
/// How many times a run of `wall` seconds is timed: 7 below 0.05 s, 3 below
/// 0.5 s, else once.
pub fn repeats(wall: f64) -> usize {
    if wall < 0.05 {
        7
    } else if wall < 0.5 {
        3
    } else {
        1
    }
}
/// DOPRI5's wall time per step and rod on this kind of machine (s), for the
/// budget only: 6 right-hand sides at about 28 ns per rod.
pub const DOPRI5_STEP_PER_ROD: f64 = 1.7e-7;
/// DOPRI5's steps per unit time and unit `gamma` at its stability limit
/// (1450 steps to t = 1 at `gamma` = 100, n = 25 to 3200, in the earlier
/// equal-tolerance study).
pub const DOPRI5_STEPS_PER_GAMMA: f64 = 14.5;
/// Step budget of any one run (a cap; no cell comes near it).
const MAX_STEPS: u64 = 2_000_000;

/// The span d = 3 start of `n` rods at damping rate `gamma`.
fn scene(n: usize, gamma: f64) -> Result<(Chain, State), String> {
    let base = Chain::report(n, 0.0).map_err(|e| e.to_string())?;
    let r = gamma * base.mass() * base.rod_length().powi(2);
    let chain = Chain::report(n, r).map_err(|e| e.to_string())?;
    let s = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    }
    .state(&chain)
    .map_err(|e| e.to_string())?;
    Ok((chain, s))
}

fn options(rtol: f64) -> SolveOptions {
    SolveOptions {
        t_end: T_END,
        max_steps: MAX_STEPS,
        ..SolveOptions::default()
    }
    .at_accuracy(Method::Dopri5, rtol)
}

/// One run: its error against `reference`, its least wall time and steps.
struct Rung {
    rtol: f64,
    err: f64,
    wall: f64,
    steps: u64,
}

/// Runs `m` at `rtol`; the wall time is the least of [`repeats`] runs
/// (another process can only add to a run's wall time, so the least is the
/// estimate least disturbed by a shared machine).
fn rung(chain: &Chain, s: &State, m: Method, rtol: f64, rf: &Reference) -> Result<Rung, String> {
    let o = options(rtol);
    let run = || solve(chain, s, m, &o).map_err(|e| e.to_string());
    let first = run()?;
    if !first.status.is_ok() {
        return Err(format!(
            "stiffness: {} at rtol {rtol:e} ended {} at t = {}",
            m.as_str(),
            first.status,
            first.t_reached
        ));
    }
    let mut wall = first.summary.wall_seconds;
    for _ in 1..repeats(wall) {
        wall = wall.min(run()?.summary.wall_seconds);
    }
    let (et, ev) = rf.errors(&first);
    Ok(Rung {
        rtol,
        err: et.max(ev),
        wall,
        steps: first.stats.steps,
    })
}

/// A method's ladder in one cell, up to the first run at or below
/// [`TARGET`].
struct Ladder {
    rungs: Vec<Rung>,
}

impl Ladder {
    fn run(chain: &Chain, s: &State, m: Method, rf: &Reference) -> Result<Ladder, String> {
        let mut rungs = vec![];
        for rtol in LADDER {
            let r = rung(chain, s, m, rtol, rf)?;
            let done = r.err <= TARGET;
            rungs.push(r);
            if done {
                break;
            }
        }
        Ok(Ladder { rungs })
    }

    /// The cost at [`TARGET`] and how it was found (`interpolated`,
    /// `loosest`), or `None` if no run reached it.
    fn at_target(&self) -> Option<(f64, &'static str)> {
        let first = self.rungs.first()?;
        if first.err <= TARGET {
            return Some((first.wall, "loosest"));
        }
        let pts: Vec<(f64, f64)> = self.rungs.iter().map(|r| (r.err, r.wall)).collect();
        time_at(&pts, TARGET).map(|t| (t, "interpolated"))
    }

    /// The last (tightest) run.
    fn last(&self) -> Option<&Rung> {
        self.rungs.last()
    }
}

/// One cell of the table; `None` ladders: not run (over budget).
struct Cell {
    n: usize,
    gamma: f64,
    r: f64,
    predicted: f64,
    run: Option<(Ladder, Ladder, f64)>,
}

/// DOPRI5's predicted wall time (s) for a ladder run and the reference in
/// a cell, at its stability limit.
pub fn predicted_explicit_seconds(n: usize, gamma: f64) -> f64 {
    let steps = (DOPRI5_STEPS_PER_GAMMA * gamma * T_END).max(1.0);
    2.0 * steps * DOPRI5_STEP_PER_ROD * n as f64
}

fn cell(n: usize, gamma: f64) -> Result<Cell, String> {
    let (chain, s) = scene(n, gamma)?;
    let predicted = predicted_explicit_seconds(n, gamma);
    let r = chain.damping();
    if predicted > EXPLICIT_BUDGET {
        return Ok(Cell {
            n,
            gamma,
            r,
            predicted,
            run: None,
        });
    }
    let reference =
        solve(&chain, &s, Method::Dopri5, &options(REF_RTOL)).map_err(|e| e.to_string())?;
    if !reference.status.is_ok() {
        return Err(format!(
            "stiffness: n = {n}, gamma = {gamma:e}: the reference ended {}",
            reference.status
        ));
    }
    let rf = Reference {
        tip: reference.summary.tip_end,
        vmax: reference.summary.tip_speed_max,
        length: chain.length(),
        values: fc_study::measure::Values::NONE,
    };
    let explicit = Ladder::run(&chain, &s, Method::Dopri5, &rf)?;
    let bdf = Ladder::run(&chain, &s, Method::Bdf, &rf)?;
    Ok(Cell {
        n,
        gamma,
        r,
        predicted,
        run: Some((explicit, bdf, reference.summary.t_tip_speed_max)),
    })
}

/// The `gamma` at which the ratio reaches 1 for the last time (from below),
/// interpolated in log-log, from `(gamma, ratio)` in increasing `gamma`;
/// `None` if no pair of neighbours brackets it. The last crossing, so that
/// a noisy point below the crossover does not place it.
pub fn crossover(row: &[(f64, f64)]) -> Option<f64> {
    row.windows(2).rev().find_map(|p| {
        let (a, b) = (p[0], p[1]);
        let (ra, rb) = (a.1.ln(), b.1.ln());
        (ra < 0.0 && rb >= 0.0).then(|| {
            let s = -ra / (rb - ra);
            (a.0.ln() + s * (b.0.ln() - a.0.ln())).exp()
        })
    })
}

/// A method's columns: cost at the target, how, runs, tightest rtol, its
/// error, steps of the run that reached the target.
fn ladder_cols(l: &Ladder) -> [String; 6] {
    let (cost, how) = l
        .at_target()
        .map_or((String::new(), "not_reached"), |(c, h)| {
            (exp_digits(c, 3), h)
        });
    let last = l.last();
    [
        cost,
        how.to_string(),
        l.rungs.len().to_string(),
        last.map_or(String::new(), |r| exp(r.rtol)),
        last.map_or(String::new(), |r| exp_digits(r.err, 2)),
        last.map_or(String::new(), |r| r.steps.to_string()),
    ]
}

/// The stiffness tables, wall times all, timed one run at a time: a row per
/// `(n, gamma)` of `grid` (each `n` with its damping rates, increasing):
/// each method's cost at [`TARGET`], their ratio; and the crossover `gamma`
/// of each `n` beside `auto`'s rule.
pub fn tables(grid: &[(usize, Vec<f64>)]) -> Result<(String, String), String> {
    let mut cells = vec![];
    for (n, gammas) in grid {
        for &gamma in gammas {
            cells.push(cell(*n, gamma)?);
        }
    }

    let mut csv = String::from(
        "n,gamma,r,run,predicted_dopri5_seconds,t_vmax,\
         dopri5_wall,dopri5_at,dopri5_runs,dopri5_rtol,dopri5_err,dopri5_steps,\
         bdf_wall,bdf_at,bdf_runs,bdf_rtol,bdf_err,bdf_steps,bdf_wall_per_step,\
         ratio_dopri5_over_bdf\n",
    );
    let mut ratios: Vec<(usize, f64, f64)> = vec![];
    for c in &cells {
        let _ = write!(
            csv,
            "{},{},{},{},{},",
            c.n,
            exp(c.gamma),
            exp_digits(c.r, 4),
            u8::from(c.run.is_some()),
            exp_digits(c.predicted, 2)
        );
        let Some((ex, bdf, t_vmax)) = &c.run else {
            let _ = writeln!(csv, "{}", [""; 15].join(","));
            continue;
        };
        let ratio = match (ex.at_target(), bdf.at_target()) {
            (Some((a, _)), Some((b, _))) => a / b,
            _ => f64::NAN,
        };
        if ratio.is_finite() {
            ratios.push((c.n, c.gamma, ratio));
        }
        let per_step = bdf
            .last()
            .map_or(f64::NAN, |r| r.wall / r.steps.max(1) as f64);
        let _ = writeln!(
            csv,
            "{},{},{},{},{}",
            fixed(*t_vmax, 3),
            ladder_cols(ex).join(","),
            ladder_cols(bdf).join(","),
            exp_digits(per_step, 2),
            exp_digits(ratio, 2),
        );
    }

    // The measured crossover beside auto's rule (`bdf_crossover_gamma`).
    let mut cross = String::from("n,gamma_crossover,gamma_crossover_rule,rule_over_measured\n");
    for &(n, _) in grid {
        let pts: Vec<(f64, f64)> = ratios
            .iter()
            .filter(|c| c.0 == n)
            .map(|c| (c.1, c.2))
            .collect();
        let g = crossover(&pts);
        let rule = bdf_crossover_gamma(&Chain::report(n, 0.0).map_err(|e| e.to_string())?);
        let _ = writeln!(
            cross,
            "{n},{},{},{}",
            g.map_or(String::new(), |g| exp_digits(g, 2)),
            exp_digits(rule, 2),
            g.map_or(String::new(), |g| fixed(rule / g, 2))
        );
    }
    Ok((csv, cross))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_crossover_is_where_the_ratio_reaches_one_in_log_log() {
        // Ratio 0.1 at gamma 10 and 10 at gamma 1000: 1 at gamma 100.
        let g = crossover(&[(1.0, 0.05), (10.0, 0.1), (1000.0, 10.0)]);
        assert!(g.is_some_and(|g| (g - 100.0).abs() < 1e-9), "{g:?}");
        assert_eq!(crossover(&[(1.0, 0.5), (10.0, 0.9)]), None);
        // A noisy point above 1 below the crossover does not place it: the
        // last upward crossing, between 100 and 1000, at
        // 100 * 10^(ln 2 / ln 20).
        let g = crossover(&[(1.0, 0.5), (10.0, 2.0), (100.0, 0.5), (1000.0, 10.0)]);
        let want = 100.0 * 10f64.powf(2f64.ln() / 20f64.ln());
        assert!(g.is_some_and(|g| (g - want).abs() < 1e-9 * want), "{g:?}");
    }
}
