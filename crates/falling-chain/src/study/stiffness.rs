//! `stiffness`: where the implicit method pays. DOPRI5 against the O(n) BDF
//! over rods `n` and the damping rate `gamma = r / (m l^2)`, on the span
//! d = 3 start (report chain, `r` set from `gamma`), `t_end = 1`, rtol 1e-6,
//! atol 1e-8. The cell is DOPRI5's wall time over BDF's (median of 3 where a
//! run is short).
//!
//! An explicit method on a stiff chain is held at its stability limit: its
//! steps are all alike, and its cost is proportional to the time it covers.
//! Where DOPRI5 would take far more than [`EXPLICIT_BUDGET`] seconds, it is
//! stopped by a step budget and its wall time is extrapolated to `t_end`
//! from the time it reached (`dopri5_extrapolated = 1` in the CSV).
//!
//! Also written: the crossover `gamma` for each `n` (where the ratio first
//! exceeds 1, interpolated in `log gamma`) beside the rule `auto` uses
//! ([`chain_ode::bdf_crossover_gamma`]), and BDF's wall time per step.
//!
//! All of it is wall times: computed only by `--timings`, into
//! `stiffness-timing.csv` and `stiffness-crossover-timing.csv`.

use std::fmt::Write as _;

use chain_ode::{
    bdf_crossover_gamma, solve, Chain, Method, SolveOptions, Start, Status, Trajectory,
};

use super::format::{exp, exp_digits, fixed};
use super::median;

const T_END: f64 = 1.0;
const RTOL: f64 = 1e-6;
const ATOL: f64 = 1e-8;
/// Seconds DOPRI5 may run per cell before its time is extrapolated.
pub const EXPLICIT_BUDGET: f64 = 0.4;
/// Repeat a run (median of 3) when it is shorter than this (s).
const REPEAT_BELOW: f64 = 0.2;
/// DOPRI5's wall time per step and rod on this kind of machine (s), for its
/// step budget only: 6 right-hand sides at about 28 ns per rod.
const DOPRI5_STEP_PER_ROD: f64 = 1.7e-7;

/// The span d = 3 start of `n` rods at damping rate `gamma`.
fn scene(n: usize, gamma: f64) -> Result<(Chain, chain_ode::State), String> {
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

/// The run and its median wall time.
fn timed(
    chain: &Chain,
    s: &chain_ode::State,
    m: Method,
    o: &SolveOptions,
) -> Result<(Trajectory, f64), String> {
    let run = || solve(chain, s, m, o).map_err(|e| e.to_string());
    let first = run()?;
    if first.summary.wall_seconds > REPEAT_BELOW {
        let w = first.summary.wall_seconds;
        return Ok((first, w));
    }
    let mut walls = vec![first.summary.wall_seconds];
    for _ in 0..2 {
        walls.push(run()?.summary.wall_seconds);
    }
    Ok((first, median(&walls)))
}

/// One cell of the table.
struct Cell {
    n: usize,
    gamma: f64,
    explicit: Trajectory,
    /// DOPRI5's wall time to `t_end`, measured or extrapolated.
    explicit_wall: f64,
    extrapolated: bool,
    bdf: Trajectory,
    bdf_wall: f64,
}

impl Cell {
    /// DOPRI5's wall time over BDF's.
    fn ratio(&self) -> f64 {
        self.explicit_wall / self.bdf_wall
    }
}

/// Runs one cell.
fn cell(n: usize, gamma: f64) -> Result<Cell, String> {
    let (chain, s) = scene(n, gamma)?;
    let base = SolveOptions {
        t_end: T_END,
        rtol: RTOL,
        atol: ATOL,
        ..Default::default()
    };
    let budget = (EXPLICIT_BUDGET / (DOPRI5_STEP_PER_ROD * n as f64)).max(2000.0) as u64;
    let explicit_opts = SolveOptions {
        max_steps: budget,
        ..base.clone()
    };
    let (explicit, wall) = timed(&chain, &s, Method::Dopri5, &explicit_opts)?;
    let extrapolated = explicit.status == Status::MaxSteps;
    let explicit_wall = if extrapolated {
        wall * T_END / explicit.t_reached
    } else {
        wall
    };
    let (bdf, bdf_wall) = timed(&chain, &s, Method::Bdf, &base)?;
    if !bdf.status.is_ok() {
        return Err(format!(
            "n = {n}, gamma = {gamma:e}: bdf ended {}",
            bdf.status
        ));
    }
    Ok(Cell {
        n,
        gamma,
        explicit,
        explicit_wall,
        extrapolated,
        bdf,
        bdf_wall,
    })
}

/// The `gamma` at which the ratio first exceeds 1, interpolated in log-log,
/// from `(gamma, ratio)` in increasing `gamma`.
fn crossover(row: &[(f64, f64)]) -> Option<f64> {
    row.windows(2).find_map(|p| {
        let (a, b) = (p[0], p[1]);
        let (ra, rb) = (a.1.ln(), b.1.ln());
        (ra < 0.0 && rb >= 0.0).then(|| {
            let s = -ra / (rb - ra);
            (a.0.ln() + s * (b.0.ln() - a.0.ln())).exp()
        })
    })
}

/// The stiffness tables, wall times all, timed one run at a time: a row per
/// `(n, gamma)` of `rods` x `gammas` (DOPRI5 and BDF, their ratio), and the
/// crossover `gamma` of each `n` beside `auto`'s rule.
pub fn tables(rods: &[usize], gammas: &[f64]) -> Result<(String, String), String> {
    let mut cells = vec![];
    for &n in rods {
        for &gamma in gammas {
            cells.push(cell(n, gamma)?);
        }
    }

    let mut csv = String::from(
        "n,gamma,r,dopri5_status,dopri5_steps,dopri5_t_reached,dopri5_wall,\
         dopri5_extrapolated,bdf_status,bdf_steps,bdf_rejected,bdf_jacobians,bdf_lu,bdf_wall,\
         bdf_wall_per_step,tip_difference,ratio_dopri5_over_bdf\n",
    );
    for c in &cells {
        // The tip difference only where both reached t_end.
        let tip = if c.extrapolated {
            f64::NAN
        } else {
            let (a, b) = (c.explicit.summary.tip_end, c.bdf.summary.tip_end);
            (a[0] - b[0]).hypot(a[1] - b[1])
        };
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            c.n,
            exp(c.gamma),
            exp(c.bdf.chain.damping()),
            c.explicit.status,
            c.explicit.stats.steps,
            fixed(c.explicit.t_reached, 6),
            exp_digits(c.explicit_wall, 4),
            u8::from(c.extrapolated),
            c.bdf.status,
            c.bdf.stats.steps,
            c.bdf.stats.rejected_steps,
            c.bdf.stats.jacobian_evals,
            c.bdf.stats.lu_factorizations,
            exp_digits(c.bdf_wall, 4),
            exp_digits(c.bdf_wall / c.bdf.stats.steps.max(1) as f64, 4),
            exp_digits(tip, 2),
            fixed(c.ratio(), 4)
        );
    }

    // The measured crossover beside auto's rule (`bdf_crossover_gamma`).
    let mut cross = String::from("n,gamma_crossover,gamma_crossover_rule,rule_over_measured\n");
    for &n in rods {
        let row: Vec<&Cell> = cells.iter().filter(|c| c.n == n).collect();
        let pts: Vec<(f64, f64)> = row.iter().map(|c| (c.gamma, c.ratio())).collect();
        let g = crossover(&pts).unwrap_or(f64::NAN);
        let rule = bdf_crossover_gamma(&Chain::report(n, 0.0).map_err(|e| e.to_string())?);
        let _ = writeln!(
            cross,
            "{n},{},{},{}",
            exp_digits(g, 4),
            exp_digits(rule, 4),
            fixed(rule / g, 3)
        );
    }
    Ok((csv, cross))
}
