//! Parameter sweeps: one run per value of one or more scene keys, in
//! parallel, keeping summaries (never trajectories).
//!
//! `--vary KEY=START:STOP:COUNT` (COUNT values, ends included) or
//! `--vary KEY=V1,V2,...`; several `--vary` make the Cartesian product, the
//! last one varying fastest. Runs are numbered from 0 in that order; a shard
//! `I/N` takes runs `I, I + N, I + 2N, ...` ([`Shard`]).
//!
//! Bounds, checked before anything is built or run: at most [`MAX_RUNS`]
//! runs in the whole grid (the product of the value counts, multiplied with
//! overflow checks), each key once, and 1..=[`MAX_JOBS`] threads (the pool
//! has no more threads than runs). A run's values are worked out from its
//! number ([`values_of`]): the grid is never held in memory.

use std::sync::atomic::{AtomicUsize, Ordering};

use chain_ode::Cancel;
use rayon::prelude::*;

use fc_csv::field as csv_field;
use fc_scene::error::{echo, Error};
use fc_scene::overrides::parse_value;
use fc_scene::scene::Scene;
use fc_scene::summary::RunSummary;

use crate::shard::{Provenance, Shard, MAX_RUNS};

/// The most worker threads of a sweep or a convergence ladder (`--jobs`).
pub const MAX_JOBS: usize = 256;

/// Checks a thread count: an integer in 1..=[`MAX_JOBS`]; `what` names it
/// in the error (`"--jobs"`, Python's `"jobs"`).
pub fn check_jobs(what: &str, jobs: usize) -> Result<usize, Error> {
    if (1..=MAX_JOBS).contains(&jobs) {
        Ok(jobs)
    } else {
        Err(Error::field(
            what,
            format!("must be an integer in 1..={MAX_JOBS} (got {jobs})"),
        ))
    }
}

/// One varied key and its values.
#[derive(Clone, Debug, PartialEq)]
pub struct Vary {
    /// Dotted scene path (`chain.damping`, `start.p1.0`).
    pub key: String,
    /// The values, in run order.
    pub values: Vec<toml::Value>,
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
        format!(
            "{why} in '{}' (expected KEY=START:STOP:COUNT or KEY=V1,V2,...)",
            echo(spec)
        ),
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
                    .ok_or_else(|| {
                        vary_error(spec, format!("'{}' is not a finite number", echo(s)))
                    })
            };
            let (start, stop) = (num(a)?, num(b)?);
            let count: usize = c
                .parse()
                .ok()
                .filter(|&k| (1..=MAX_RUNS).contains(&k))
                .ok_or_else(|| {
                    vary_error(
                        spec,
                        format!("COUNT '{}' is not an integer in 1..={MAX_RUNS}", echo(c)),
                    )
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
            let count = rhs.split(',').count();
            if count > MAX_RUNS {
                return Err(vary_error(
                    spec,
                    format!("{count} values (at most {MAX_RUNS})"),
                ));
            }
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

/// The number of runs of the whole grid (the product of the value counts),
/// at most [`MAX_RUNS`]; every key at most once (a key and one of its
/// elements, `start.p1` and `start.p1.0`, count as the same key), and every
/// key with at least one value. Checked with overflow checks, before
/// anything is built.
pub fn grid_size(vary: &[Vary]) -> Result<usize, Error> {
    for (i, v) in vary.iter().enumerate() {
        if v.values.is_empty() {
            return Err(Error::field(
                "--vary",
                format!("'{}' has no values", echo(&v.key)),
            ));
        }
        let overlaps = |a: &str, b: &str| {
            a == b || a.strip_prefix(b).is_some_and(|rest| rest.starts_with('.'))
        };
        if let Some(w) = vary[..i]
            .iter()
            .find(|w| overlaps(&v.key, &w.key) || overlaps(&w.key, &v.key))
        {
            let what = if w.key == v.key {
                format!("'{}' is varied twice", echo(&v.key))
            } else {
                format!(
                    "'{}' and '{}' vary the same value",
                    echo(&w.key),
                    echo(&v.key)
                )
            };
            return Err(Error::field(
                "--vary",
                format!("{what}: give each key once, with all its values"),
            ));
        }
    }
    let mut size: usize = 1;
    for v in vary {
        size = size
            .checked_mul(v.values.len())
            .filter(|&n| n <= MAX_RUNS)
            .ok_or_else(|| {
                let counts: Vec<String> = vary.iter().map(|v| v.values.len().to_string()).collect();
                Error::field(
                    "--vary",
                    format!(
                        "the sweep has {} runs; at most {MAX_RUNS} are allowed",
                        counts.join(" x ")
                    ),
                )
            })?;
    }
    Ok(size)
}

/// The values of run `run` (numbered as in [`grid`]: the last key varies
/// fastest), by mixed radix; `run` must be below the grid's size.
pub fn values_of(vary: &[Vary], run: usize) -> Vec<toml::Value> {
    let mut values = vec![toml::Value::Boolean(false); vary.len()];
    let mut rest = run;
    for (slot, v) in values.iter_mut().zip(vary).rev() {
        let count = v.values.len().max(1);
        if let Some(x) = v.values.get(rest % count) {
            *slot = x.clone();
        }
        rest /= count;
    }
    values
}

/// The values of every run, in run order (the Cartesian product, the last
/// key varying fastest), made one run at a time. The grid is checked
/// first ([`grid_size`]).
pub fn grid(vary: &[Vary]) -> Result<impl Iterator<Item = Vec<toml::Value>> + '_, Error> {
    let size = grid_size(vary)?;
    Ok((0..size).map(move |run| values_of(vary, run)))
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
    check_cancellable(scene, vary, None)
}

/// [`check`] that stops with [`Error::Interrupted`] once `cancel` is set:
/// preparing 10^6 scenes takes seconds, and Ctrl-C must not wait for it.
pub fn check_cancellable(
    scene: &Scene,
    vary: &[Vary],
    cancel: Option<&Cancel>,
) -> Result<(), Error> {
    check_runs(scene, vary, cancel, 1)
}

/// [`check_cancellable`] for `concurrent` runs at once: each point's runs
/// must fit in memory together ([`fc_scene::scene::Prepared::check_memory`],
/// without samples, as a sweep's runs keep none).
fn check_runs(
    scene: &Scene,
    vary: &[Vary],
    cancel: Option<&Cancel>,
    concurrent: usize,
) -> Result<(), Error> {
    for values in grid(vary)? {
        if cancel.is_some_and(Cancel::is_cancelled) {
            return Err(Error::Interrupted);
        }
        let prepared = scene_for(scene, vary, &values)?.prepare()?;
        if concurrent > 1 {
            prepared.check_memory(concurrent, false)?;
        }
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
    let jobs = check_jobs("--jobs", jobs)?;
    let size = grid_size(vary)?;
    let runs: Vec<usize> = (0..size)
        .filter(|&i| shard.is_none_or(|s| s.takes(i)))
        .collect();
    let total = runs.len();
    check_runs(scene, vary, cancel, jobs.min(total).max(1))?;
    let done = AtomicUsize::new(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.min(total).max(1))
        .build()
        .map_err(|e| Error::field("--jobs", e))?;
    let rows: Result<Vec<SweepRow>, Error> = pool.install(|| {
        runs.into_par_iter()
            .map(|run| {
                if cancelled() {
                    return Err(Error::Interrupted);
                }
                let values = values_of(vary, run);
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

/// Where a sweep's rows come from ([`crate::shard`]): its number of
/// runs and the hash of its scene and varied values (each key and value as
/// its CSV cell), the same from the CLI and from Python.
pub fn provenance(scene: &Scene, vary: &[Vary]) -> Result<Provenance, Error> {
    let runs = grid_size(vary)?;
    let options: Vec<String> = vary
        .iter()
        .map(|v| {
            let values: Vec<String> = v.values.iter().map(value_cell).collect();
            format!("{}={}", v.key, values.join(","))
        })
        .collect();
    Ok(Provenance::new(scene, "sweep", &options, runs))
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
        let g: Vec<_> = grid(&[a, b]).unwrap().collect();
        assert_eq!(g.len(), 10);
        assert_eq!(g[1][1], toml::Value::String("dopri5".into()));
        assert_eq!(g[1][0], toml::Value::Float(0.0));
        assert_eq!(g[9][0], toml::Value::Float(1.0));
    }

    #[test]
    fn grids_are_bounded_and_keys_given_once() {
        // Mixed radix, last key fastest, against the nested loops.
        let a = Vary::floats("chain.damping", &[0.0, 1.0, 2.0]);
        let b = Vary::floats("chain.mass", &[5.0, 6.0]);
        let c = Vary::floats("chain.length", &[7.0, 8.0, 9.0, 10.0]);
        let vary = [a.clone(), b.clone(), c.clone()];
        let mut run = 0;
        for x in &a.values {
            for y in &b.values {
                for z in &c.values {
                    assert_eq!(values_of(&vary, run), vec![x.clone(), y.clone(), z.clone()]);
                    run += 1;
                }
            }
        }
        assert_eq!(grid_size(&vary).unwrap(), 24);
        // A product beyond the cap (and beyond usize) is refused unbuilt.
        let big = Vary::parse("chain.damping=0:1:1000000").unwrap();
        let big2 = Vary::parse("chain.mass=1:2:1000000").unwrap();
        let e = grid_size(&[big.clone(), big2]).unwrap_err().to_string();
        assert!(
            e.starts_with("--vary: the sweep has 1000000 x 1000000 runs"),
            "{e}"
        );
        assert_eq!(grid_size(&[big]).unwrap(), MAX_RUNS);
        let list = format!("chain.damping={}", vec!["1"; MAX_RUNS + 1].join(","));
        let e = Vary::parse(&list).unwrap_err().to_string();
        assert!(e.contains("1000001 values (at most 1000000)"), "{e}");
        assert!(e.len() < 400, "{}", e.len());
        let e = Vary::parse("start.p1.0=1:5:100000000000000")
            .unwrap_err()
            .to_string();
        assert!(e.contains("1..=1000000"), "{e}");
        // The same key twice, or a key and its element.
        for (k1, k2) in [
            ("chain.damping", "chain.damping"),
            ("start.p1", "start.p1.0"),
        ] {
            let e = grid_size(&[Vary::floats(k1, &[0.0]), Vary::floats(k2, &[3.0])])
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("--vary: '"), "{e}");
        }
        assert!(grid_size(&[
            Vary::floats("start.p1.0", &[0.0]),
            Vary::floats("start.p1.1", &[3.0])
        ])
        .is_ok());
        assert_eq!(check_jobs("--jobs", 256).unwrap(), 256);
        for bad in [0, 257, usize::MAX] {
            let e = check_jobs("--jobs", bad).unwrap_err().to_string();
            assert_eq!(
                e,
                format!("--jobs: must be an integer in 1..=256 (got {bad})")
            );
        }
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
