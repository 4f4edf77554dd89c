//! `ensemble`: a scene run from `members` starts whose rod angles are
//! moved by a few `spread` rad, and the statistics of its summary over them
//! (`docs/model.md`, "Ensembles over perturbed starts").
//!
//! Past a whip or a landing on a floor a single run is not reproducible: a
//! change of the start far below any tolerance moves what it reports by
//! per cents. What is reproducible there is the distribution over nearby
//! starts, and its mean is known to its standard error. Member `j` starts
//! with angle `i` moved by `spread u(seed, j, i)`, `u` uniform on `[-1, 1]`
//! from a fixed hash ([`uniform`]), so that an ensemble is the same on
//! every machine; its rates are the scene's.

use std::fmt::{self, Write as _};
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use serde_json::{json, Value};

use crate::measure::{Measure, Measures, Values};
use fc_batch::budget::Budget;
use fc_csv::format::{exp, num};
use fc_scene::error::Error;
use fc_scene::scene::{Prepared, Scene};
use fc_scene::summary::RunSummary;

/// The most members an ensemble may have.
pub const MAX_MEMBERS: usize = 4096;
/// The largest spread (rad).
pub const MAX_SPREAD: f64 = 0.1;
/// The most members a failure line names ([`Ensemble::failures`]).
pub const LISTED: usize = 8;
/// The default members and spread.
pub const DEFAULT_MEMBERS: usize = 16;
pub const DEFAULT_SPREAD: f64 = 1e-3;

/// What an ensemble is asked for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EnsembleOptions {
    /// Members, in `2..=MAX_MEMBERS`.
    pub members: usize,
    /// The perturbation's half width (rad), in `[0, MAX_SPREAD]`.
    pub spread: f64,
    /// Which perturbations: seed `s` draws member `j`'s from stream
    /// `j + 2^32 s`.
    pub seed: u32,
    /// Worker threads.
    pub jobs: usize,
    /// What it measures beyond [`QUANTITIES`] (`--measure`): the
    /// statistics of each measure not among them (`pivot_force_max`,
    /// `tension_max`, `floor_reading`), and the force peaks tracked only
    /// when measured (the studies' one rule).
    pub measures: Measures,
}

impl EnsembleOptions {
    /// Checks `--members` and `--spread`, each naming its flag.
    pub fn validate(&self) -> Result<(), Error> {
        if !(2..=MAX_MEMBERS).contains(&self.members) {
            return Err(Error::field(
                "--members",
                format!("must be in 2..={MAX_MEMBERS} (got {})", self.members),
            ));
        }
        if !(self.spread.is_finite() && (0.0..=MAX_SPREAD).contains(&self.spread)) {
            return Err(Error::field(
                "--spread",
                format!(
                    "must be a number of radians in [0, {MAX_SPREAD}] (got {})",
                    fc_scene::error::number(self.spread)
                ),
            ));
        }
        Ok(())
    }
}

/// A deterministic uniform number in `[−1, 1]` for `(stream, i)`
/// (SplitMix64's finaliser on the pair, 53 bits of it).
pub fn uniform(stream: u64, i: u64) -> f64 {
    let mut z = stream
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add(i.wrapping_add(1).wrapping_mul(0xBF58_476D_1CE4_E5B9));
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    2.0 * ((z >> 11) as f64 / (1u64 << 53) as f64) - 1.0
}

/// The stream of member `member` under `seed`.
pub fn stream(seed: u32, member: usize) -> u64 {
    member as u64 + (u64::from(seed) << 32)
}

/// The quantities of a run's summary an ensemble reports, by their
/// `simulate --json` names (`tip_end_x`, `tip_end_y` for `tip_end`);
/// `floor_force_max` only for a scene with a floor.
pub const QUANTITIES: [&str; 8] = [
    "tip_speed_max",
    "t_tip_speed_max",
    "tip_end_x",
    "tip_end_y",
    "energy_end",
    "dissipated",
    "floor_force_max",
    "steps",
];

fn quantity(s: &RunSummary, name: &str) -> Option<f64> {
    match name {
        "tip_speed_max" => Some(s.tip_speed_max),
        "t_tip_speed_max" => Some(s.t_tip_speed_max),
        "tip_end_x" => Some(s.tip_end[0]),
        "tip_end_y" => Some(s.tip_end[1]),
        "energy_end" => Some(s.energy_end),
        "dissipated" => Some(s.dissipated),
        "floor_force_max" => s.floor_force_max,
        "steps" => Some(s.steps as f64),
        _ => None,
    }
}

/// One quantity over the members that ended `ok`.
#[derive(Clone, Debug, PartialEq)]
pub struct Stat {
    pub name: &'static str,
    pub mean: f64,
    /// The sample standard deviation (0 for one member).
    pub sd: f64,
    /// `sd / sqrt(count)`.
    pub sem: f64,
    pub min: f64,
    pub max: f64,
    pub count: usize,
}

/// `(mean, sample standard deviation, standard error)` of `xs` (the
/// deviation 0 for one value; `None` for none). Scaled before it sums or
/// squares (by the largest magnitude, then by the largest deviation), so
/// that neither overflows nor underflows: values near 1e-300 that differ
/// have a deviation that is not 0, values near 1e308 a finite mean.
pub fn moments(xs: &[f64]) -> Option<(f64, f64, f64)> {
    if xs.is_empty() {
        return None;
    }
    let m = xs.len() as f64;
    let big = xs.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    let mean = if big > 0.0 && big.is_finite() {
        big * (xs.iter().map(|x| x / big).sum::<f64>() / m)
    } else {
        xs.iter().sum::<f64>() / m
    };
    let var = if xs.len() > 1 {
        let wide = xs.iter().fold(0.0_f64, |a, x| a.max((x - mean).abs()));
        if wide > 0.0 && wide.is_finite() {
            let sum = xs.iter().map(|x| ((x - mean) / wide).powi(2)).sum::<f64>();
            // sd = wide sqrt(sum / (m - 1)): the square of `wide` never formed.
            return Some((
                mean,
                wide * (sum / (m - 1.0)).sqrt(),
                wide * (sum / (m - 1.0) / m).sqrt(),
            ));
        }
        xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (m - 1.0)
    } else {
        0.0
    };
    Some((mean, var.sqrt(), (var / m).sqrt()))
}

impl Stat {
    fn of(name: &'static str, xs: &[f64]) -> Option<Stat> {
        let (mean, sd, sem) = moments(xs)?;
        Some(Stat {
            name,
            mean,
            sd,
            sem,
            min: xs.iter().copied().fold(f64::INFINITY, f64::min),
            max: xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            count: xs.len(),
        })
    }
}

/// A finished ensemble.
#[derive(Clone, Debug)]
pub struct Ensemble {
    pub name: String,
    pub options: EnsembleOptions,
    /// Each member's summary (`None`: not run within the budget), in order.
    pub members: Vec<Option<RunSummary>>,
    /// The quantities over the members that ended `ok`.
    pub stats: Vec<Stat>,
}

impl Ensemble {
    /// The members that did not end `ok` or did not run, grouped by why
    /// (not run within `--budget`, stopped by `--budget`, or the status
    /// they ended with), one line per group in the order first seen:
    /// `N members STATUS (j at t = T, ...)`, at most [`LISTED`] members
    /// named in a group and the rest counted, so that 4096 failures are a
    /// few short lines.
    pub fn failures(&self) -> Vec<String> {
        let mut groups: Vec<(String, Vec<String>)> = Vec::new();
        for (j, m) in self.members.iter().enumerate() {
            let (why, at) = match m {
                None => ("not run within --budget".to_string(), format!("{j}")),
                Some(s) if s.is_ok() => continue,
                Some(s) => {
                    // The ensemble's runs are cancelled only by its budget.
                    let why = if s.status == "interrupted" {
                        "stopped by --budget".to_string()
                    } else {
                        format!("ended {}", s.status)
                    };
                    (why, format!("{j} at t = {}", num(s.t_reached)))
                }
            };
            match groups.iter_mut().find(|(w, _)| *w == why) {
                Some((_, list)) => list.push(at),
                None => groups.push((why, vec![at])),
            }
        }
        groups
            .into_iter()
            .map(|(why, list)| {
                let count = list.len();
                let noun = if count == 1 { "member" } else { "members" };
                let mut named = list
                    .iter()
                    .take(LISTED)
                    .cloned()
                    .collect::<Vec<_>>()
                    .join(", ");
                if count > LISTED {
                    let _ = write!(named, " and {} more", count - LISTED);
                }
                format!("{count} {noun} {why} ({named})")
            })
            .collect()
    }

    /// One row per member: `member,status,` then [`QUANTITIES`] (empty
    /// cells where a member did not run or has no floor).
    pub fn csv(&self) -> String {
        let mut s = format!("member,status,{}\n", QUANTITIES.join(","));
        for (j, m) in self.members.iter().enumerate() {
            let status = m.as_ref().map_or("not run", |m| m.status.as_str());
            let _ = write!(s, "{j},{status}");
            for q in QUANTITIES {
                let v = m.as_ref().and_then(|m| quantity(m, q));
                let _ = write!(s, ",{}", v.map_or(String::new(), num));
            }
            s.push('\n');
        }
        s
    }

    /// The ensemble as one JSON object: the scene, the options, how many
    /// members ended `ok`, the statistics by quantity and the failures.
    pub fn to_json(&self) -> Value {
        let ok = self.members.iter().flatten().filter(|m| m.is_ok()).count();
        let stats: serde_json::Map<String, Value> = self
            .stats
            .iter()
            .map(|s| {
                (
                    s.name.to_string(),
                    json!({"mean": s.mean, "sd": s.sd, "sem": s.sem, "min": s.min,
                           "max": s.max, "count": s.count}),
                )
            })
            .collect();
        json!({
            "name": self.name,
            "members": self.options.members,
            "spread": self.options.spread,
            "seed": self.options.seed,
            "ok": ok,
            "stats": stats,
            "failures": self.failures(),
        })
    }
}

impl fmt::Display for Ensemble {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let ok = self.members.iter().flatten().filter(|m| m.is_ok()).count();
        writeln!(
            f,
            "{}: ensemble of {} starts, angles moved by up to {} rad (seed {}); {ok} ended ok",
            self.name,
            self.options.members,
            exp(self.options.spread),
            self.options.seed
        )?;
        writeln!(
            f,
            "  {:<16} {:>14} {:>11} {:>11} {:>14} {:>14}",
            "quantity", "mean", "sd", "sem", "min", "max"
        )?;
        for s in &self.stats {
            writeln!(
                f,
                "  {:<16} {:>14.7e} {:>11.3e} {:>11.3e} {:>14.7e} {:>14.7e}",
                s.name, s.mean, s.sd, s.sem, s.min, s.max
            )?;
        }
        for line in self.failures() {
            writeln!(f, "  {line}")?;
        }
        Ok(())
    }
}

/// Runs the ensemble of `scene` (its members in parallel on
/// `options.jobs` threads, each stopped by `budget`; a member that cannot
/// start within it is not run). Every bound (the options, the scene's
/// run) is checked before any run; `progress(done, total)` after each.
pub fn run(
    scene: &Scene,
    options: &EnsembleOptions,
    budget: &Budget,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Ensemble, Error> {
    run_members(scene, options, budget, progress, None)
}

/// What [`run_watching`] calls with each member's number and run, on the
/// thread that ran it, before the run is dropped.
pub type Watcher<'a> = dyn Fn(usize, &chain_ode::Trajectory) -> Result<(), Error> + Sync + 'a;

/// [`run`], showing each member's run to `each` as it ends: how
/// `ensemble_series` reads the members' samples without keeping them. Its
/// members record the scene's samples (`run.output_dt`), which [`run`]'s
/// do not (`ensemble_series::check_size` bounds what they take).
pub fn run_watching(
    scene: &Scene,
    options: &EnsembleOptions,
    budget: &Budget,
    progress: &(dyn Fn(usize, usize) + Sync),
    each: &Watcher<'_>,
) -> Result<Ensemble, Error> {
    run_members(scene, options, budget, progress, Some(each))
}

/// [`run`] and [`run_watching`]: the members sampled only when watched.
fn run_members(
    scene: &Scene,
    options: &EnsembleOptions,
    budget: &Budget,
    progress: &(dyn Fn(usize, usize) + Sync),
    each: Option<&Watcher<'_>>,
) -> Result<Ensemble, Error> {
    let samples = each.is_some();
    options.validate()?;
    let jobs = fc_batch::sweep::check_jobs("--jobs", options.jobs)?;
    let prepared = scene.prepare()?;
    // The members that run at once must fit in memory together.
    prepared.check_memory(jobs.min(options.members), samples)?;
    // Every member's start is checked before any run: a perturbation that
    // moves a start out of its bounds (into a floor) is the spread's doing,
    // and the error says so, naming the member.
    for j in 0..options.members {
        member(&prepared, options, j, samples)
            .check_start()
            .map_err(|e| spread_error(e, options, j))?;
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.min(options.members).max(1))
        .build()
        .map_err(|e| Error::field("--jobs", e))?;
    let done = AtomicUsize::new(0);
    let members: Vec<Option<(RunSummary, Values)>> = pool.install(|| {
        (0..options.members)
            .into_par_iter()
            .map(|j| {
                if !budget.fits(0.0) {
                    return Ok(None);
                }
                let mut p = member(&prepared, options, j, samples);
                p.options.cancel = Some(budget.cancel().clone());
                if let Some(dt) = options.measures.output_dt(p.options.t_end) {
                    p.options.output_dt = Some(p.options.output_dt.map_or(dt, |o| o.min(dt)));
                }
                let traj = p.solve_measuring(options.measures.tracks_forces())?;
                if let Some(each) = each {
                    each(j, &traj)?;
                }
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, options.members);
                Ok(Some((
                    RunSummary::from_trajectory(scene.name(), &traj),
                    Values::of(&traj, options.measures),
                )))
            })
            .collect::<Result<Vec<_>, Error>>()
    })?;
    let ok: Vec<&(RunSummary, Values)> = members.iter().flatten().filter(|m| m.0.is_ok()).collect();
    let mut stats: Vec<Stat> = QUANTITIES
        .iter()
        .filter_map(|&q| {
            let xs: Vec<f64> = ok.iter().filter_map(|m| quantity(&m.0, q)).collect();
            Stat::of(q, &xs)
        })
        .collect();
    for m in options.measures.list() {
        if m == Measure::Tip || QUANTITIES.contains(&m.name()) {
            continue;
        }
        let xs: Vec<f64> = ok
            .iter()
            .map(|v| v.1.get(m))
            .filter(|x| x.is_finite())
            .collect();
        stats.extend(Stat::of(m.name(), &xs));
    }
    let members = members.into_iter().map(|m| m.map(|m| m.0)).collect();
    Ok(Ensemble {
        name: scene.name().to_string(),
        options: *options,
        members,
        stats,
    })
}

/// Member `j`'s run: the scene's, its start angles moved, recording no
/// samples unless `samples` (an ensemble keeps summaries only, and every
/// quantity of a summary, the floor's peak force included, is tracked at
/// every step: memory O(n) per running member, whatever `run.output_dt`;
/// `ensemble_series` reads the samples, bounded by its own size check).
fn member(prepared: &Prepared, options: &EnsembleOptions, j: usize, samples: bool) -> Prepared {
    let mut p = prepared.clone();
    if !samples {
        p.options.output_dt = None;
    }
    let s = stream(options.seed, j);
    for (i, a) in p.state.angles.iter_mut().enumerate() {
        *a += options.spread * uniform(s, i as u64);
    }
    p
}

/// `e`, the refusal of member `j`'s start, said to be the doing of
/// `--spread` (the scene's own start was accepted).
fn spread_error(e: Error, options: &EnsembleOptions, j: usize) -> Error {
    let why = match e {
        Error::Field { field, message } => format!("{field}: {message}"),
        other => other.to_string(),
    };
    Error::field(
        "--spread",
        format!(
            "member {j}'s start (its angles moved by up to {} rad, seed {}) is refused where \
             the scene's own start is not; a smaller --spread may fit: {why}",
            fc_scene::error::number(options.spread),
            options.seed
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_perturbations_are_uniform_on_the_interval_and_seeded() {
        // Mean 0 and variance 1/3 of U(-1, 1) to a few standard errors of
        // 20000 draws; a generator stuck on one half fails.
        let xs: Vec<f64> = (0..20_000).map(|i| uniform(7, i)).collect();
        let s = Stat::of("u", &xs).unwrap();
        assert!(xs.iter().all(|x| (-1.0..=1.0).contains(x)));
        assert!(
            s.mean.abs() < 4.0 * (1.0 / 3.0 / 20_000.0_f64).sqrt(),
            "{s:?}"
        );
        assert!((s.sd * s.sd - 1.0 / 3.0).abs() < 0.01, "{s:?}");
        assert_ne!(uniform(stream(0, 1), 0), uniform(stream(1, 1), 0));
        assert_eq!(stream(0, 5), 5);
    }

    #[test]
    fn the_statistics_of_a_sample_are_its_mean_spread_and_range() {
        let s = Stat::of("x", &[1.0, 2.0, 3.0, 4.0]).unwrap();
        assert_eq!((s.mean, s.min, s.max, s.count), (2.5, 1.0, 4.0, 4));
        assert!((s.sd - (5.0_f64 / 3.0).sqrt()).abs() < 1e-15);
        assert!((s.sem - s.sd / 2.0).abs() < 1e-15);
        assert_eq!(Stat::of("x", &[]), None);
    }

    #[test]
    fn members_and_spread_out_of_range_are_refused_naming_their_flag() {
        let ok = EnsembleOptions {
            members: 16,
            spread: 1e-3,
            seed: 0,
            jobs: 1,
            measures: crate::measure::Measures::TIP,
        };
        assert!(ok.validate().is_ok());
        for (o, flag) in [
            (EnsembleOptions { members: 1, ..ok }, "--members"),
            (
                EnsembleOptions {
                    members: MAX_MEMBERS + 1,
                    ..ok
                },
                "--members",
            ),
            (
                EnsembleOptions {
                    spread: -1e-3,
                    ..ok
                },
                "--spread",
            ),
            (EnsembleOptions { spread: 0.2, ..ok }, "--spread"),
            (
                EnsembleOptions {
                    spread: f64::NAN,
                    ..ok
                },
                "--spread",
            ),
        ] {
            let e = o.validate().unwrap_err().to_string();
            assert!(e.contains(flag), "{e}");
        }
    }
}
