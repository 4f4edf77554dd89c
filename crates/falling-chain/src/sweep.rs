//! Parameter sweeps: one run per value of one or more scene keys, in
//! parallel, keeping summaries (never trajectories).
//!
//! `--vary KEY=START:STOP:COUNT` (COUNT values, ends included) or
//! `--vary KEY=V1,V2,...`; several `--vary` make the Cartesian product, the
//! last one varying fastest. Runs are numbered from 0 in that order; a shard
//! `I/N` takes runs `I, I + N, I + 2N, ...`.

use std::sync::atomic::{AtomicUsize, Ordering};

use chain_ode::Cancel;
use rayon::prelude::*;

use crate::csv::field as csv_field;
use crate::error::Error;
use crate::overrides::parse_value;
use crate::scene::Scene;
use crate::summary::RunSummary;

/// One varied key and its values.
#[derive(Clone, Debug, PartialEq)]
pub struct Vary {
    /// Dotted scene path (`chain.damping`, `start.p1.0`).
    pub key: String,
    /// The values, in run order.
    pub values: Vec<toml::Value>,
}

/// A slice of a sweep: runs `index, index + count, ...`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

/// One finished run of a sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepRow {
    /// The run's number in the whole (unsharded) sweep.
    pub run: usize,
    /// The varied values, in `--vary` order.
    pub values: Vec<toml::Value>,
    pub summary: RunSummary,
}

fn vary_error(spec: &str, why: impl std::fmt::Display) -> Error {
    Error::field(
        "--vary",
        format!("{why} in '{spec}' (expected KEY=START:STOP:COUNT or KEY=V1,V2,...)"),
    )
}

impl Vary {
    /// `key` over the numbers `values`.
    pub fn floats(key: &str, values: &[f64]) -> Self {
        Self {
            key: key.to_string(),
            values: values.iter().map(|&x| toml::Value::Float(x)).collect(),
        }
    }

    /// Parses `KEY=START:STOP:COUNT` or `KEY=V1,V2,...`.
    pub fn parse(spec: &str) -> Result<Self, Error> {
        let (key, rhs) = spec
            .split_once('=')
            .ok_or_else(|| vary_error(spec, "no '='"))?;
        let key = key.trim();
        if key.is_empty() {
            return Err(vary_error(spec, "no key"));
        }
        let values = if rhs.contains(':') {
            let parts: Vec<&str> = rhs.split(':').map(str::trim).collect();
            let [a, b, c] = parts[..] else {
                return Err(vary_error(spec, "a range needs START:STOP:COUNT"));
            };
            let num = |s: &str| -> Result<f64, Error> {
                s.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| vary_error(spec, format!("'{s}' is not a finite number")))
            };
            let (start, stop) = (num(a)?, num(b)?);
            let count: usize =
                c.parse().ok().filter(|&k| k >= 1).ok_or_else(|| {
                    vary_error(spec, format!("COUNT '{c}' is not an integer >= 1"))
                })?;
            (0..count)
                .map(|i| {
                    let x = if count == 1 {
                        start
                    } else {
                        start + (stop - start) * i as f64 / (count - 1) as f64
                    };
                    toml::Value::Float(x)
                })
                .collect()
        } else {
            rhs.split(',')
                .map(|v| parse_value(v.trim()).map_err(|e| vary_error(spec, e)))
                .collect::<Result<Vec<_>, _>>()?
        };
        Ok(Self {
            key: key.to_string(),
            values,
        })
    }
}

impl Shard {
    /// Parses `I/N` with `0 <= I < N`.
    pub fn parse(spec: &str) -> Result<Self, Error> {
        let bad = || {
            Error::field(
                "--shard",
                format!("must be I/N with integers 0 <= I < N (got '{spec}')"),
            )
        };
        let (i, n) = spec.split_once('/').ok_or_else(bad)?;
        let (index, count): (usize, usize) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    fn takes(&self, run: usize) -> bool {
        run % self.count == self.index
    }
}

/// The values of every run, in run order (the Cartesian product).
pub fn grid(vary: &[Vary]) -> Vec<Vec<toml::Value>> {
    vary.iter().fold(vec![vec![]], |acc, v| {
        acc.iter()
            .flat_map(|prefix| {
                v.values.iter().map(move |x| {
                    let mut row = prefix.clone();
                    row.push(x.clone());
                    row
                })
            })
            .collect()
    })
}

/// The scene of one run: `scene` with the run's values set (an integer
/// key takes a whole float, as the schema says: `chain.links = 100.0` is
/// 100). Sweeps keep summaries only: [`run`] switches output sampling off.
pub fn scene_for(scene: &Scene, vary: &[Vary], values: &[toml::Value]) -> Result<Scene, Error> {
    let mut s = scene.clone();
    for (v, x) in vary.iter().zip(values) {
        s = s.with_value(&v.key, x.clone())?;
    }
    Ok(s)
}

/// Checks every run's scene before any run starts: a bad key or value is an
/// error naming it, and no run is wasted.
pub fn check(scene: &Scene, vary: &[Vary]) -> Result<(), Error> {
    for values in grid(vary) {
        scene_for(scene, vary, &values)?.prepare()?;
    }
    Ok(())
}

/// Runs the sweep (or its shard) on `jobs` threads, calling `progress` after
/// each run with the number done and the total. Rows come back in run order.
/// The same as [`run_cancellable`] with no cancel flag.
pub fn run(
    scene: &Scene,
    vary: &[Vary],
    shard: Option<Shard>,
    jobs: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<SweepRow>, Error> {
    run_cancellable(scene, vary, shard, jobs, progress, None)
}

/// [`run`] that can be stopped from outside: `cancel` is put into every
/// run's `SolveOptions::cancel` (a run in progress stops at its next step),
/// no run starts once it is set, and the sweep then returns
/// [`Error::Interrupted`] (never a partial list of rows), even if every run
/// had finished when the flag was seen.
pub fn run_cancellable(
    scene: &Scene,
    vary: &[Vary],
    shard: Option<Shard>,
    jobs: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: Option<&Cancel>,
) -> Result<Vec<SweepRow>, Error> {
    let cancelled = || cancel.is_some_and(Cancel::is_cancelled);
    check(scene, vary)?;
    let runs: Vec<(usize, Vec<toml::Value>)> = grid(vary)
        .into_iter()
        .enumerate()
        .filter(|(i, _)| shard.is_none_or(|s| s.takes(*i)))
        .collect();
    let total = runs.len();
    let done = AtomicUsize::new(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.max(1))
        .build()
        .map_err(|e| Error::field("--jobs", e))?;
    let rows: Result<Vec<SweepRow>, Error> = pool.install(|| {
        runs.into_par_iter()
            .map(|(run, values)| {
                if cancelled() {
                    return Err(Error::Interrupted);
                }
                let s = scene_for(scene, vary, &values)?;
                let mut prepared = s.prepare()?;
                prepared.options.output_dt = None;
                prepared.options.cancel = cancel.cloned();
                let traj = prepared.solve()?;
                if cancelled() {
                    return Err(Error::Interrupted);
                }
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
                Ok(SweepRow {
                    run,
                    values,
                    summary: RunSummary::from_trajectory(s.name(), &traj),
                })
            })
            .collect()
    });
    if cancelled() {
        return Err(Error::Interrupted);
    }
    rows
}

fn value_cell(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => csv_field(s).into_owned(),
        toml::Value::Float(x) => x.to_string(),
        other => csv_field(&other.to_string()).into_owned(),
    }
}

/// The CSV header: `run`, the varied keys, then the summary columns.
pub fn csv_header(vary: &[Vary]) -> String {
    let mut h = String::from("run");
    for v in vary {
        h.push(',');
        h.push_str(&csv_field(&v.key));
    }
    h.push(',');
    h.push_str(&RunSummary::csv_header());
    h
}

/// One CSV line of a row.
pub fn csv_row(row: &SweepRow) -> String {
    let mut line = row.run.to_string();
    for v in &row.values {
        line.push(',');
        line.push_str(&value_cell(v));
    }
    line.push(',');
    line.push_str(&row.summary.csv_row());
    line
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_lists_and_products() {
        let a = Vary::parse("chain.damping=0:1:5").unwrap();
        assert_eq!(a.values.len(), 5);
        assert_eq!(a.values[4], toml::Value::Float(1.0));
        let b = Vary::parse("run.method=rk4,dopri5").unwrap();
        assert_eq!(b.values[1], toml::Value::String("dopri5".into()));
        let g = grid(&[a, b]);
        assert_eq!(g.len(), 10);
        assert_eq!(g[1][1], toml::Value::String("dopri5".into()));
    }

    #[test]
    fn bad_specs_name_the_flag() {
        for bad in [
            "chain.links",
            "=1,2",
            "chain.links=1:2",
            "x=1:2:0",
            "x=a:2:3",
        ] {
            let e = Vary::parse(bad).unwrap_err().to_string();
            assert!(e.starts_with("--vary"), "{e}");
        }
        for bad in ["1", "2/2", "a/3", "1/0"] {
            assert!(Shard::parse(bad)
                .unwrap_err()
                .to_string()
                .starts_with("--shard"));
        }
        assert_eq!(Shard::parse("1/3").unwrap(), Shard { index: 1, count: 3 });
    }

    #[test]
    fn a_cancelled_sweep_starts_no_run_and_says_interrupted() {
        let scene = Scene::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenes/folded.toml"
        ))
        .unwrap()
        .with_overrides(&["run.t_end=0.01", "chain.links=4", "start.down=2"])
        .unwrap();
        let vary = [Vary::floats("chain.damping", &[0.0, 0.1, 0.2])];
        let cancel = Cancel::new();
        cancel.cancel();
        let started = AtomicUsize::new(0);
        let e = run_cancellable(
            &scene,
            &vary,
            None,
            2,
            &|_, _| {
                started.fetch_add(1, Ordering::Relaxed);
            },
            Some(&cancel),
        )
        .unwrap_err();
        assert!(matches!(e, Error::Interrupted), "{e}");
        assert_eq!(started.load(Ordering::Relaxed), 0);
        // Without the flag the same sweep runs.
        let rows = run_cancellable(&scene, &vary, None, 2, &|_, _| {}, None).unwrap();
        assert_eq!(rows.len(), 3);
    }
}
