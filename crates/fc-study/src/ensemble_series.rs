//! An ensemble's time series: the mean, standard error, standard deviation
//! and range over the members of every per-sample output (the tip, its
//! velocity and speed, the energy, the dissipated work, the support's
//! force, and with a floor its force and the weight and length landed on
//! it) at each output time, which the members share (`falling-chain
//! ensemble --out-series`, Python's `ensemble_series`).
//!
//! Past a whip or a landing a single run's curve is not reproducible, its
//! ensemble's mean curve is, to its standard error: Cayley's reading
//! `F / (3 mu g x)` against time is such a mean. The members run as
//! [`ensemble::run_watching`] runs them; each member's series is folded
//! into the statistics as it ends, in member order (a member that ends
//! before those before it waits, so that the sums are the same on any
//! number of threads, bit for bit), and then dropped: the memory is the
//! statistics and the series of the members waiting, never a trajectory
//! per member.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::sync::Mutex;

use chain_ode::Trajectory;
use fc_batch::budget::Budget;
use fc_csv::format::num;
use fc_scene::error::Error;
use fc_scene::scene::Scene;

use crate::ensemble::{self, Ensemble, EnsembleOptions};

/// The per-sample outputs of every run, by name (`tip_speed` is
/// `|tip velocity|`; `pivot_x`, `pivot_y` the support's force on the first
/// rod, scene axes).
pub const SERIES: [&str; 9] = [
    "tip_x",
    "tip_y",
    "tip_vx",
    "tip_vy",
    "tip_speed",
    "energy",
    "dissipated",
    "pivot_x",
    "pivot_y",
];

/// The per-sample outputs a scene with a floor adds: its total force
/// (what a scale under the chain reads) and the weight and length landed
/// on it (`Trajectory::floor_landed_weight`, `floor_landed_length`).
pub const FLOOR_SERIES: [&str; 4] = ["floor_x", "floor_y", "landed_weight", "landed_length"];

/// The statistics each output has at each time, in the CSV's order.
pub const STATS: [&str; 5] = ["mean", "sem", "sd", "min", "max"];

/// The most memory the series may take (bytes), the members waiting to be
/// folded included: 1 GiB, as a run's samples.
pub const MAX_SERIES_BYTES: f64 = (1u64 << 30) as f64;

/// The outputs of a scene (with `floor`: [`FLOOR_SERIES`] too).
pub fn names(floor: bool) -> Vec<&'static str> {
    let mut v = SERIES.to_vec();
    if floor {
        v.extend(FLOOR_SERIES);
    }
    v
}

/// Sample `k` of `traj`: its time and its outputs, in the order of
/// [`names`].
pub fn sample(traj: &Trajectory, k: usize, floor: bool, out: &mut Vec<f64>) {
    let p = traj.tip(k);
    let v = traj.tip_velocity(k);
    let f = traj.support_force(k);
    out.extend([
        p[0],
        p[1],
        v[0],
        v[1],
        v[0].hypot(v[1]),
        traj.energy(k),
        traj.sample(k).dissipated,
        f[0],
        f[1],
    ]);
    if floor {
        let ff = traj.floor_force(k).unwrap_or([0.0, 0.0]);
        out.extend([
            ff[0],
            ff[1],
            traj.floor_landed_weight(k).unwrap_or(0.0),
            traj.floor_landed_length(k).unwrap_or(0.0),
        ]);
    }
}

/// The statistics over the members of every output at every time.
#[derive(Clone, Debug, PartialEq)]
pub struct EnsembleSeries {
    /// The outputs, in column order ([`names`]).
    pub names: Vec<&'static str>,
    /// The output times, which every member shares.
    pub t: Vec<f64>,
    /// The members folded in: those that ended `ok` with finite outputs.
    pub count: usize,
    /// Means, `t.len() x names.len()`, row by row.
    pub mean: Vec<f64>,
    /// Sums of squared deviations from the mean (Welford's).
    m2: Vec<f64>,
    pub min: Vec<f64>,
    pub max: Vec<f64>,
}

impl EnsembleSeries {
    fn new(names: Vec<&'static str>) -> Self {
        Self {
            names,
            t: Vec::new(),
            count: 0,
            mean: Vec::new(),
            m2: Vec::new(),
            min: Vec::new(),
            max: Vec::new(),
        }
    }

    /// Folds in one member: its times and its outputs, row by row.
    fn add(&mut self, member: usize, t: &[f64], values: &[f64]) -> Result<(), Error> {
        if self.count == 0 {
            self.t = t.to_vec();
            self.mean = values.to_vec();
            self.m2 = vec![0.0; values.len()];
            self.min = values.to_vec();
            self.max = values.to_vec();
            self.count = 1;
            return Ok(());
        }
        if t != self.t.as_slice() {
            return Err(Error::field(
                "ensemble",
                format!(
                    "member {member}'s {} output times differ from the first member's {}: \
                     the members do not share an output grid",
                    t.len(),
                    self.t.len()
                ),
            ));
        }
        self.count += 1;
        let c = self.count as f64;
        for (i, &x) in values.iter().enumerate() {
            let d = x - self.mean[i];
            self.mean[i] += d / c;
            self.m2[i] += d * (x - self.mean[i]);
            self.min[i] = self.min[i].min(x);
            self.max[i] = self.max[i].max(x);
        }
        Ok(())
    }

    /// The index of output `name`, if the series has it.
    pub fn index(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| *n == name)
    }

    /// The sample standard deviation of output `q` at time `k` (0 for one
    /// member).
    pub fn sd(&self, k: usize, q: usize) -> f64 {
        if self.count < 2 {
            return 0.0;
        }
        (self.m2[k * self.names.len() + q] / (self.count as f64 - 1.0)).sqrt()
    }

    /// The standard error of the mean of output `q` at time `k`.
    pub fn sem(&self, k: usize, q: usize) -> f64 {
        self.sd(k, q) / (self.count.max(1) as f64).sqrt()
    }

    /// Statistic `stat` ([`STATS`]) of output `q` at every time.
    pub fn column(&self, q: usize, stat: &str) -> Vec<f64> {
        let w = self.names.len();
        (0..self.t.len())
            .map(|k| match stat {
                "mean" => self.mean[k * w + q],
                "sem" => self.sem(k, q),
                "sd" => self.sd(k, q),
                "min" => self.min[k * w + q],
                _ => self.max[k * w + q],
            })
            .collect()
    }

    /// The CSV header: `t,members`, then `NAME_STAT` for every output and
    /// statistic ([`STATS`]).
    pub fn csv_header(&self) -> String {
        let mut h = String::from("t,members");
        for n in &self.names {
            for s in STATS {
                let _ = write!(h, ",{n}_{s}");
            }
        }
        h
    }

    /// The table: one row per output time.
    pub fn csv(&self) -> String {
        let mut out = self.csv_header();
        out.push('\n');
        let w = self.names.len();
        for (k, t) in self.t.iter().enumerate() {
            let _ = write!(out, "{},{}", num(*t), self.count);
            for q in 0..w {
                let i = k * w + q;
                let _ = write!(
                    out,
                    ",{},{},{},{},{}",
                    num(self.mean[i]),
                    num(self.sem(k, q)),
                    num(self.sd(k, q)),
                    num(self.min[i]),
                    num(self.max[i])
                );
            }
            out.push('\n');
        }
        out
    }
}

/// One member's output times and outputs (row by row), or `None` when it
/// did not end ok.
type Member = Option<(Vec<f64>, Vec<f64>)>;

/// The members' series folded in member order: a member's waits in
/// `pending` until every member before it has ended (`None`: it did not
/// end ok, and is skipped).
struct Fold {
    next: usize,
    pending: BTreeMap<usize, Member>,
    series: EnsembleSeries,
}

impl Fold {
    fn push(&mut self, j: usize, member: Member) -> Result<(), Error> {
        self.pending.insert(j, member);
        while let Some(m) = self.pending.remove(&self.next) {
            if let Some((t, v)) = m {
                self.series.add(self.next, &t, &v)?;
            }
            self.next += 1;
        }
        Ok(())
    }

    /// Folds what still waits (after members that never ran), in order.
    fn finish(mut self) -> Result<EnsembleSeries, Error> {
        let rest = std::mem::take(&mut self.pending);
        for (j, m) in rest {
            if let Some((t, v)) = m {
                self.series.add(j, &t, &v)?;
            }
        }
        Ok(self.series)
    }
}

/// Checks that the series of `options.members` members of `scene` fit in
/// [`MAX_SERIES_BYTES`] should every member wait to be folded; the error
/// names `what` (`--out-series`, Python's `members`).
pub fn check_size(what: &str, scene: &Scene, options: &EnsembleOptions) -> Result<(), Error> {
    let p = scene.prepare()?;
    let floor = p.chain.floor().is_some();
    let dt = p.options.output_dt.unwrap_or(p.options.t_end);
    let samples = (p.options.t_end / dt).ceil() + 2.0;
    let row = (names(floor).len() + 1) as f64 * 8.0;
    let bytes = samples * row * (options.members as f64 + 5.0);
    if bytes > MAX_SERIES_BYTES {
        return Err(Error::field(
            what,
            format!(
                "the series of {} members at {} output times take up to {:.3} GB, more \
                 than 1 GiB: fewer members or a larger run.output_dt",
                options.members,
                samples as u64,
                bytes / 1e9
            ),
        ));
    }
    Ok(())
}

/// Runs the ensemble of `scene` ([`ensemble::run`]) and its time series:
/// the statistics of every output over the members that ended `ok`, at
/// each output time. Every bound is checked before any run.
pub fn run(
    scene: &Scene,
    options: &EnsembleOptions,
    budget: &Budget,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(Ensemble, EnsembleSeries), Error> {
    options.validate()?;
    check_size("--out-series", scene, options)?;
    let floor = scene.prepare()?.chain.floor().is_some();
    let fold = Mutex::new(Fold {
        next: 0,
        pending: BTreeMap::new(),
        series: EnsembleSeries::new(names(floor)),
    });
    let each = |j: usize, traj: &Trajectory| -> Result<(), Error> {
        let mut values = Vec::with_capacity(traj.len() * (names(floor).len()));
        for k in 0..traj.len() {
            sample(traj, k, floor, &mut values);
        }
        let ok = traj.status.is_ok() && values.iter().all(|x| x.is_finite());
        let member = ok.then(|| (traj.times.clone(), values));
        fold.lock()
            .map_err(|_| Error::field("ensemble", "a member's thread failed"))?
            .push(j, member)
    };
    let result = ensemble::run_watching(scene, options, budget, progress, &each)?;
    let fold = fold
        .into_inner()
        .map_err(|_| Error::field("ensemble", "a member's thread failed"))?;
    Ok((result, fold.finish()?))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fold_of(members: &[(usize, Vec<f64>)]) -> EnsembleSeries {
        let mut f = Fold {
            next: 0,
            pending: BTreeMap::new(),
            series: EnsembleSeries::new(vec!["x"]),
        };
        for (j, v) in members {
            f.push(*j, Some((vec![0.0, 1.0], v.clone()))).unwrap();
        }
        f.finish().unwrap()
    }

    /// The members record the scene's samples: every output time from 0
    /// to `t_end` is in the series (the summaries-only ensemble keeps no
    /// samples; its members must not lose them here), each with every
    /// member, and the start's spread is the spread the seed drew.
    #[test]
    fn the_series_holds_every_output_time_of_the_scene() {
        let scene = Scene::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenes/span-d3.toml"
        ))
        .unwrap()
        .with_overrides(&["chain.links=4", "run.t_end=0.05", "run.output_dt=0.01"])
        .unwrap();
        let options = EnsembleOptions {
            members: 3,
            spread: 1e-3,
            seed: 0,
            jobs: 1,
            measures: crate::measure::Measures::TIP,
        };
        let (result, series) =
            Budget::run(None, None, |b| run(&scene, &options, b, &|_, _| {})).unwrap();
        assert_eq!(result.members.len(), 3);
        assert_eq!(series.count, 3);
        assert_eq!(series.t.len(), 6, "{:?}", series.t);
        for (k, t) in series.t.iter().enumerate() {
            assert!((t - 0.01 * k as f64).abs() < 1e-12, "{:?}", series.t);
        }
        // The tip's x at t = 0: the members' starts differ (spread > 0).
        let q = series.names.iter().position(|&n| n == "tip_x").unwrap();
        assert!(series.max[q] > series.min[q]);
    }

    /// The statistics are the two-pass ones of `ensemble::moments`, and
    /// members arriving in any order fold to the same numbers, bit for bit.
    #[test]
    fn the_fold_is_the_samples_statistics_in_any_arrival_order() {
        let xs = [0.3, 1.7, -2.2, 5.0, 0.1];
        let members: Vec<(usize, Vec<f64>)> = xs
            .iter()
            .enumerate()
            .map(|(j, &x)| (j, vec![x, 2.0 * x]))
            .collect();
        let a = fold_of(&members);
        let mut shuffled = members.clone();
        shuffled.reverse();
        shuffled.swap(1, 3);
        assert_eq!(a, fold_of(&shuffled));
        let (mean, sd, sem) = ensemble::moments(&xs).unwrap();
        assert!((a.mean[0] - mean).abs() < 1e-15 && (a.sd(0, 0) - sd).abs() < 1e-14);
        assert!((a.sem(0, 0) - sem).abs() < 1e-14);
        assert!((a.mean[1] - 2.0 * mean).abs() < 1e-14 && (a.sd(1, 0) - 2.0 * sd).abs() < 1e-13);
        assert_eq!((a.min[0], a.max[0], a.count), (-2.2, 5.0, 5));
        // A member that never arrives (not run) is skipped, not waited for.
        let gap = fold_of(&[(0, vec![1.0, 1.0]), (2, vec![3.0, 3.0])]);
        assert_eq!((gap.count, gap.mean[0]), (2, 2.0));
        let csv = a.csv();
        assert!(csv.starts_with("t,members,x_mean,x_sem,x_sd,x_min,x_max\n0,5,"));
        assert_eq!(csv.lines().count(), 3);
    }
}
