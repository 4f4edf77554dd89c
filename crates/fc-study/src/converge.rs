//! Convergence in the number of rods: one scene run at several `n` with the
//! continuum held fixed, and the smallest `n` that agrees with the finest.
//!
//! A scene's `n`, `m` (per rod) and `r` describe one discretisation of a
//! continuous chain. Refining it keeps what the continuum sees:
//!
//! * the total mass `M = n m` (so `m = M / n`);
//! * the bending viscosity `eta = r l`: a joint's friction torque
//!   `r (w_{i+1} - w_i)` is `r l d(omega)/ds`, a viscous bending moment, and
//!   the dissipated power `r sum (w_{i+1} - w_i)^2` tends to
//!   `eta * integral (d(omega)/ds)^2 ds`; so `r = eta n / L`.
//!
//! The damping rate `r / (m l^2) = eta n^4 / (M L^3)` then grows like `n^4`
//! (the grid-scale bending modes are damped that fast): large `n` is stiff.
//! At the report's fixed per-rod `m` and `r` the model itself would change
//! with `n` (docs/model.md), which is not a refinement.
//!
//! A folded start's `start.down` (if given) scales with `n` (rounded down);
//! an `angles` start refines only when its angles repeat a short pattern
//! (a zigzag), which continues rod by rod (`fc_scene::Scene::refined`).

use std::sync::atomic::{AtomicUsize, Ordering};

use chain_ode::analysis::{bending_viscosity, tip_track};
use chain_ode::{Chain, Vec2};
use rayon::prelude::*;
use serde::Serialize;

use crate::measure::{Measure, Measures, Values};
use fc_scene::error::Error;
use fc_scene::scene::Scene;
use fc_scene::summary::RunSummary;

/// One line stating the refinement, for help texts, figures and data.
pub const SCALING: &str = "total mass M = n m and bending viscosity eta = r l kept: \
                           m = M/n, r = eta n/L (damping rate r/(m l^2) grows like n^4)";

/// The default ladder of `n`.
pub const DEFAULT_LINKS: [usize; 5] = [25, 50, 100, 200, 400];

/// `scene` cut into `links` rods at fixed total mass and bending viscosity:
/// [`Scene::refined`], the one refinement (`fc_scene::refine`), which
/// `--refine N` and Python's `Scene.refine(n)` call too.
pub fn refined_scene(scene: &Scene, links: usize) -> Result<Scene, Error> {
    scene.refined(links)
}

/// One finished run of the ladder.
#[derive(Clone, Debug)]
pub struct Level {
    /// The refined chain it ran.
    pub chain: Chain,
    pub summary: RunSummary,
    /// `(t, tip)` at every output sample.
    pub track: Vec<(f64, Vec2)>,
    /// The values of what the study measures (`--measure`; NaN where not
    /// measured: `tip` alone measures none of them).
    pub values: Values,
    /// What it measured.
    pub measures: Measures,
}

impl Level {
    /// Number of rods.
    pub fn links(&self) -> usize {
        self.chain.links()
    }
}

/// Runs `scene` refined to `links` rods with `method` and `rtol` (the
/// scene's own when `None`).
pub fn run_level(
    scene: &Scene,
    links: usize,
    method: Option<&str>,
    rtol: Option<f64>,
) -> Result<Level, Error> {
    run_level_until(scene, links, method, rtol, None)
}

/// [`run_level`], stopped when `cancel` is set (the run then ends
/// `interrupted`, at once if it was set before it started): how a time
/// budget stops a ladder.
pub fn run_level_until(
    scene: &Scene,
    links: usize,
    method: Option<&str>,
    rtol: Option<f64>,
    cancel: Option<&chain_ode::Cancel>,
) -> Result<Level, Error> {
    run_level_measured(scene, links, method, rtol, cancel, Measures::TIP)
}

/// [`run_level_until`] measuring `measures`: the pivot's force and the
/// tensions tracked exactly when it measures one of them
/// ([`Measures::tracks_forces`], the studies' one rule).
pub fn run_level_measured(
    scene: &Scene,
    links: usize,
    method: Option<&str>,
    rtol: Option<f64>,
    cancel: Option<&chain_ode::Cancel>,
    measures: Measures,
) -> Result<Level, Error> {
    let mut s = refined_scene(scene, links)?;
    if let Some(m) = method {
        s = s.with_value("run.method", toml::Value::String(m.to_string()))?;
    }
    if let Some(r) = rtol {
        s = s.with_value("run.rtol", toml::Value::Float(r))?;
        s = s.with_value("run.atol", toml::Value::Float(r * 1e-2))?;
    }
    let mut prepared = s.prepare()?;
    prepared.options.cancel = cancel.cloned();
    if let Some(dt) = measures.output_dt(prepared.options.t_end) {
        // The floor's reading's windows need samples at least this often.
        prepared.options.output_dt = Some(prepared.options.output_dt.map_or(dt, |o| o.min(dt)));
    }
    let traj = prepared.solve_measuring(measures.tracks_forces())?;
    let track = tip_track(&traj)
        .into_iter()
        .map(|(t, p, _)| (t, p))
        .collect();
    Ok(Level {
        chain: prepared.chain,
        summary: RunSummary::from_trajectory(scene.name(), &traj),
        track,
        values: Values::of(&traj, measures),
        measures,
    })
}

/// How far one level is from the reference (the finest).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Deviation {
    /// `|v_max / v_max_ref - 1|`; where `|v_max_ref|` is below the chain's
    /// speed scale `v_s` ([`speed_scale`]: `sqrt(g L)`, or `L` per time unit
    /// at `g = 0`), `|v_max - v_max_ref| / v_s` instead, so that a speed that
    /// is zero at every level (a chain at rest at `g = 0`) deviates by its
    /// rounding, not by 0/0.
    pub tip_speed_max: f64,
    /// `|tip_end - tip_end_ref| / L`.
    pub tip_end: f64,
    /// `max_t |tip(t) - tip_ref(t)| / L` over the common sample times.
    pub tip_path: f64,
    /// With `--measure` other than `tip`: the largest relative deviation
    /// of its other measures ([`crate::measure`]'s errors); absent for
    /// `tip` alone.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measured: Option<f64>,
}

/// The speed scale of `chain`: `sqrt(E_s / M)` with `E_s` the chain's energy
/// scale (`Chain::energy_scale`), which is `sqrt(g L)` when `g > 0` and `L`
/// per time unit at `g = 0`.
pub fn speed_scale(chain: &Chain) -> f64 {
    (chain.energy_scale() / chain.total_mass()).sqrt()
}

/// `|v / v_ref - 1|`, or `|v - v_ref| / scale` where `|v_ref| < scale`.
fn relative_speed(v: f64, v_ref: f64, scale: f64) -> f64 {
    if v_ref.abs() >= scale || !scale.is_finite() || scale <= 0.0 {
        (v / v_ref - 1.0).abs()
    } else {
        (v - v_ref).abs() / scale
    }
}

impl Deviation {
    /// The deviation of `level` from `reference`.
    pub fn between(level: &Level, reference: &Level) -> Self {
        let length = reference.chain.length();
        let d = |a: Vec2, b: Vec2| (a[0] - b[0]).hypot(a[1] - b[1]);
        let path = level
            .track
            .iter()
            .zip(&reference.track)
            .filter(|(a, b)| (a.0 - b.0).abs() <= 1e-9 * a.0.abs().max(1.0))
            .map(|(a, b)| d(a.1, b.1))
            .fold(0.0, f64::max);
        Self {
            tip_speed_max: relative_speed(
                level.summary.tip_speed_max,
                reference.summary.tip_speed_max,
                speed_scale(&reference.chain),
            ),
            tip_end: d(level.summary.tip_end, reference.summary.tip_end) / length,
            tip_path: path / length,
            measured: (!level.measures.is_tip()).then(|| {
                let others: Vec<Measure> = level
                    .measures
                    .list()
                    .into_iter()
                    .filter(|&m| m != Measure::Tip)
                    .collect();
                others
                    .iter()
                    .map(|&m| reference.values.error(&level.values, m))
                    .fold(
                        0.0,
                        |a: f64, e| if e.is_nan() { f64::NAN } else { a.max(e) },
                    )
            }),
        }
    }

    /// Whether the other measures (if any) are within `tol`.
    pub fn measured_within(&self, tol: f64) -> bool {
        self.measured.is_none_or(|e| e < tol)
    }
}

/// The smallest `n` of `levels` (sorted by `n`, the last the reference)
/// from which on every coarser-than-reference level passes `ok`; `None` if
/// even the one below the reference fails (or there is only one level).
pub fn smallest_adequate(levels: &[Level], ok: impl Fn(&Deviation) -> bool) -> Option<usize> {
    let reference = levels.last()?;
    let below = &levels[..levels.len() - 1];
    let mut answer = None;
    for level in below.iter().rev() {
        if ok(&Deviation::between(level, reference)) {
            answer = Some(level.links());
        } else {
            break;
        }
    }
    answer
}

/// The `converge` result: every level, its deviation and the answer.
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    pub name: String,
    pub tol: f64,
    pub scaling: &'static str,
    pub total_mass: f64,
    pub bending_viscosity: f64,
    /// The finest `n`, the reference.
    pub reference_links: usize,
    /// The smallest adequate `n` (`null`: none below the reference).
    pub adequate_links: Option<usize>,
    pub levels: Vec<ReportLevel>,
    /// The one-line stiffness hint of the ladder's runs, if an explicit
    /// method kept detecting stiffness ([`fc_scene::summary::stiffness_hint_for`]).
    #[serde(skip)]
    pub stiffness_hint: Option<String>,
    /// What the levels must agree on (`--measure`'s names; `tip` by
    /// default).
    pub measure: String,
}

/// One row of [`Report`].
#[derive(Clone, Debug, Serialize)]
pub struct ReportLevel {
    pub links: usize,
    pub mass: f64,
    pub damping: f64,
    /// The level's stiffness parameter, `Chain::stiffest_damping_rate`.
    pub damping_rate: f64,
    pub status: String,
    /// `E(0)`: the start's energy (converges with n at fixed `M`).
    pub energy_start: f64,
    pub tip_speed_max: f64,
    pub tip_end: [f64; 2],
    pub deviation: Deviation,
    pub rhs_evals: u64,
    pub wall_seconds: f64,
}

/// Parses `--links 25,50,100`: at least two distinct integers >= 2 (sorted).
pub fn parse_links(text: &str) -> Result<Vec<usize>, Error> {
    let bad = |why: String| Error::field("--links", why);
    let mut links = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<usize>()
                .ok()
                .filter(|&n| (2..=1_000_000).contains(&n))
                .ok_or_else(|| {
                    bad(format!(
                        "'{}' is not an integer in 2..=1000000 (expected N1,N2,...)",
                        fc_scene::error::echo(s.trim())
                    ))
                })
        })
        .collect::<Result<Vec<_>, _>>()?;
    links.sort_unstable();
    links.dedup();
    if links.len() < 2 {
        return Err(bad(format!(
            "needs at least two different numbers of rods (got '{}')",
            fc_scene::error::echo(text)
        )));
    }
    check_ladder_length(links.len())?;
    Ok(links)
}

/// The most levels of a ladder (each keeps its tip track in memory).
pub const MAX_LEVELS: usize = 32;

fn check_ladder_length(levels: usize) -> Result<(), Error> {
    if levels > MAX_LEVELS {
        return Err(Error::field(
            "--links",
            format!("at most {MAX_LEVELS} different numbers of rods (got {levels})"),
        ));
    }
    Ok(())
}

/// The smallest `--tol` of `converge`: deviations below it are the
/// rounding of the runs (rtol is at least 1e-14), not the discretisation.
pub const MIN_TOL: f64 = 1e-12;

/// Checks `--tol`: a number in [[`MIN_TOL`], 1).
pub fn check_tol(tol: f64) -> Result<(), Error> {
    if tol.is_finite() && (MIN_TOL..1.0).contains(&tol) {
        Ok(())
    } else {
        Err(Error::field(
            "--tol",
            format!(
                "must be a number in [{MIN_TOL:e}, 1) (got {})",
                fc_scene::error::number(tol)
            ),
        ))
    }
}

/// Checks `converge --rtol`: within `run.rtol`'s range
/// ([`chain_ode::RTOL_RANGE`]), named by the flag.
pub fn check_rtol(what: &str, rtol: f64) -> Result<f64, Error> {
    let (lo, hi) = chain_ode::RTOL_RANGE;
    if (lo..=hi).contains(&rtol) {
        Ok(rtol)
    } else {
        Err(Error::field(
            what,
            format!(
                "must be a number in [{lo:e}, {hi}] (got {})",
                fc_scene::error::number(rtol)
            ),
        ))
    }
}

/// Runs the ladder `links` on `jobs` threads and finds the smallest `n`
/// whose tip_speed_max and tip end both agree with the finest `n` to `tol`
/// (relative; the tip end relative to `L`), for it and every finer `n`
/// below the finest. `progress(done, total)` is called after each run.
pub fn run(
    scene: &Scene,
    links: &[usize],
    tol: f64,
    method: Option<&str>,
    rtol: Option<f64>,
    jobs: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Report, Error> {
    run_measured(
        scene,
        links,
        tol,
        method,
        rtol,
        jobs,
        progress,
        Measures::TIP,
    )
}

/// [`run`] measuring `measures` (`--measure`): a level is adequate when its
/// tip speed and tip end and every other measure agree with the finest to
/// `tol`.
#[allow(clippy::too_many_arguments)]
pub fn run_measured(
    scene: &Scene,
    links: &[usize],
    tol: f64,
    method: Option<&str>,
    rtol: Option<f64>,
    jobs: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
    measures: Measures,
) -> Result<Report, Error> {
    check_tol(tol)?;
    let levels = run_levels_measured(scene, links, method, rtol, jobs, progress, None, measures)?;
    report(scene, &levels, tol)
}

/// Runs the ladder `links` (sorted, each once; 2 to [`MAX_LEVELS`] of them)
/// of `scene` on `jobs` threads, finest first, every scene checked before
/// any run starts: the levels, coarse to fine. `converge` and `needs` share
/// it.
pub fn run_levels(
    scene: &Scene,
    links: &[usize],
    method: Option<&str>,
    rtol: Option<f64>,
    jobs: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Vec<Level>, Error> {
    run_levels_until(scene, links, method, rtol, jobs, progress, None)
}

/// [`run_levels`], each run stopped when `cancel` is set (see
/// [`run_level_until`]).
pub fn run_levels_until(
    scene: &Scene,
    links: &[usize],
    method: Option<&str>,
    rtol: Option<f64>,
    jobs: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: Option<&chain_ode::Cancel>,
) -> Result<Vec<Level>, Error> {
    run_levels_measured(
        scene,
        links,
        method,
        rtol,
        jobs,
        progress,
        cancel,
        Measures::TIP,
    )
}

/// [`run_levels_until`] measuring `measures`.
#[allow(clippy::too_many_arguments)]
pub fn run_levels_measured(
    scene: &Scene,
    links: &[usize],
    method: Option<&str>,
    rtol: Option<f64>,
    jobs: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
    cancel: Option<&chain_ode::Cancel>,
    measures: Measures,
) -> Result<Vec<Level>, Error> {
    let jobs = fc_batch::sweep::check_jobs("--jobs", jobs)?;
    // The report's model keeps its time unit sqrt(l / g) per rod, which
    // changes with n: its levels are not one physical problem refined.
    scene.prepare()?.require_corrected("converge")?;
    let mut links = links.to_vec();
    links.sort_unstable();
    links.dedup();
    if links.len() < 2 {
        return Err(Error::field(
            "--links",
            format!(
                "needs at least two different numbers of rods (got {})",
                links.len()
            ),
        ));
    }
    check_ladder_length(links.len())?;
    // Every scene is checked before any run starts, its memory with as
    // many levels beside it as run at once.
    let concurrent = jobs.min(links.len()).max(1);
    for &n in &links {
        let mut s = refined_scene(scene, n)?;
        if let Some(m) = method {
            s = s.with_value("run.method", toml::Value::String(m.to_string()))?;
        }
        if let Some(r) = rtol {
            s = s.with_value("run.rtol", toml::Value::Float(r))?;
        }
        s.prepare()?.check_memory(concurrent, true)?;
    }
    let done = AtomicUsize::new(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.min(links.len()).max(1))
        .build()
        .map_err(|e| Error::field("--jobs", e))?;
    let total = links.len();
    // Finest first: the longest run starts first.
    let mut levels: Vec<Level> = pool.install(|| {
        links
            .par_iter()
            .rev()
            .map(|&n| {
                let level = run_level_measured(scene, n, method, rtol, cancel, measures)?;
                progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
                Ok(level)
            })
            .collect::<Result<Vec<_>, Error>>()
    })?;
    levels.sort_by_key(Level::links);
    Ok(levels)
}

/// The `converge` report of a finished ladder `levels` (coarse to fine, the
/// last the reference): the smallest `n` whose tip_speed_max and tip end
/// agree with the finest to `tol` from it on, if every run ended `ok`.
pub fn report(scene: &Scene, levels: &[Level], tol: f64) -> Result<Report, Error> {
    let reference = levels
        .last()
        .ok_or_else(|| Error::field("--links", "no level ran"))?;
    let base = scene.chain()?;
    let adequate = if levels.iter().all(|l| l.summary.is_ok()) {
        smallest_adequate(levels, |d| {
            d.tip_speed_max < tol && d.tip_end < tol && d.measured_within(tol)
        })
    } else {
        None
    };
    Ok(Report {
        name: scene.name().to_string(),
        tol,
        scaling: SCALING,
        total_mass: base.total_mass(),
        bending_viscosity: bending_viscosity(&base),
        reference_links: reference.links(),
        adequate_links: adequate,
        measure: reference.measures.names(),
        stiffness_hint: fc_scene::summary::stiffness_hint_for(levels.iter().map(|l| &l.summary)),
        levels: levels
            .iter()
            .map(|l| ReportLevel {
                links: l.links(),
                mass: l.chain.mass(),
                damping: l.chain.damping(),
                damping_rate: l.chain.stiffest_damping_rate(),
                status: l.summary.status.clone(),
                energy_start: l.summary.energy_start,
                tip_speed_max: l.summary.tip_speed_max,
                tip_end: l.summary.tip_end,
                deviation: Deviation::between(l, reference),
                rhs_evals: l.summary.rhs_evals,
                wall_seconds: l.summary.wall_seconds,
            })
            .collect(),
    })
}

impl Report {
    /// True if every run reached its end time.
    pub fn all_ok(&self) -> bool {
        self.levels.iter().all(|l| l.status == "ok")
    }

    /// One line of JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|e| {
            serde_json::json!({ "error": format!("the report did not serialise: {e}") }).to_string()
        })
    }
}

impl std::fmt::Display for Report {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "{}: convergence in n (M = {}, eta = r l = {:e})",
            self.name, self.total_mass, self.bending_viscosity
        )?;
        writeln!(f, "  refinement: {}", self.scaling)?;
        writeln!(
            f,
            "  {:>7} {:>12} {:>12} {:>9} {:>14} {:>11} {:>11} {:>11} {:>9}",
            "n",
            "r",
            "r/(m l^2)",
            "status",
            "tip_speed_max",
            "d(vmax)",
            "d(tip_end)",
            "d(path)",
            "wall s"
        )?;
        for l in &self.levels {
            writeln!(
                f,
                "  {:>7} {:>12.4e} {:>12.4e} {:>9} {:>14.8} {:>11.3e} {:>11.3e} {:>11.3e} {:>9.2}",
                l.links,
                l.damping,
                l.damping_rate,
                l.status,
                l.tip_speed_max,
                l.deviation.tip_speed_max,
                l.deviation.tip_end,
                l.deviation.tip_path,
                l.wall_seconds
            )?;
            if let Some(d) = l.deviation.measured {
                writeln!(f, "          d({}) = {d:.3e}", self.measure)?;
            }
        }
        writeln!(
            f,
            "  d(vmax) = |vmax/vmax_ref - 1| (|vmax - vmax_ref|/sqrt(g L) where vmax_ref < sqrt(g L); \
             L per time unit at g = 0), d(tip_end) = |tip_end - tip_end_ref|/L, \
             d(path) = max_t |tip - tip_ref|/L; reference n = {}",
            self.reference_links
        )?;
        match self.adequate_links {
            Some(n) => write!(
                f,
                "smallest adequate n = {n} (d(vmax) and d(tip_end){} < {} from n = {n} on)",
                if self.measure == "tip" {
                    String::new()
                } else {
                    format!(" and d({})", self.measure)
                },
                self.tol
            ),
            None if !self.all_ok() => write!(f, "no answer: a run failed (see its status)"),
            None => write!(
                f,
                "no n below {} agrees with it to {}: refine further",
                self.reference_links, self.tol
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_empty_or_single_ladder_is_an_error_not_a_panic() {
        let scene = Scene::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenes/span-d3.toml"
        ))
        .unwrap();
        for links in [&[][..], &[8][..], &[8, 8][..]] {
            let e = run(&scene, links, 0.1, None, None, 1, &|_, _| {})
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("--links: "), "{e}");
        }
        let e = run(&scene, &[4, 8], 0.1, None, None, 1000, &|_, _| {})
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--jobs: "), "{e}");
    }

    #[test]
    fn the_speed_deviation_is_finite_when_every_speed_is_zero() {
        let scale = 2.0;
        assert_eq!(relative_speed(0.0, 0.0, scale), 0.0);
        assert_eq!(relative_speed(4e-16, 0.0, scale), 2e-16);
        // Above the scale: the relative deviation, as before (bit for bit).
        let (v, r) = (10.3_f64, 10.6_f64);
        assert_eq!(relative_speed(v, r, scale), (v / r - 1.0).abs());
    }

    #[test]
    fn links_and_tol_are_checked_by_name() {
        assert_eq!(parse_links("100, 25,50,25").unwrap(), vec![25, 50, 100]);
        let many: Vec<String> = (2..=34).map(|n| n.to_string()).collect();
        let many = many.join(",");
        for bad in ["", "25", "25,25", "a,50", "1,50", "-3,50", many.as_str()] {
            let e = parse_links(bad).unwrap_err().to_string();
            assert!(e.starts_with("--links: "), "{e}");
        }
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 1.0, 1e-300, 1e300] {
            let e = check_tol(bad).unwrap_err().to_string();
            assert!(e.starts_with("--tol: ") && !e.contains('\n'), "{e}");
        }
        assert!(check_tol(0.01).is_ok());
    }

    /// The mass per length of each rod, `m_i / l_i`, and its midpoint's
    /// arc length `s_i`, in physical units.
    fn densities(c: &chain_ode::Chain) -> Vec<(f64, f64)> {
        let rods = c.rods().unwrap();
        let (m, l) = (c.mass(), c.rod_length());
        let mut s = 0.0;
        (0..c.links())
            .map(|i| {
                let li = rods.length[i] * l;
                s += li;
                (s - 0.5 * li, rods.mass[i] * m / li)
            })
            .collect()
    }

    /// A tapered scene refines by its profile: the continuum's mass per
    /// length `rho(s)` (linear for a taper, piecewise constant for lists)
    /// and its length are the same at every level, not equal rods.
    #[test]
    fn refinement_holds_the_profiles_continuum() {
        let taper = Scene::from_toml_str(
            "[chain]\nlinks = 10\ntaper = 10\n[start]\nkind = \"catenary\"\np1 = [3, 0]\n[run]\nt_end = 1\n",
        )
        .unwrap();
        let coarse = taper.chain().unwrap();
        let fine = refined_scene(&taper, 40).unwrap().chain().unwrap();
        // rho(s) = a - b s through the coarse rods' midpoints.
        let d = densities(&coarse);
        let b = (d[0].1 - d[9].1) / (d[9].0 - d[0].0);
        let a = d[0].1 + b * d[0].0;
        assert!((a / (a - b * 6.0) - 10.0).abs() < 1e-12);
        for (s, rho) in densities(&fine) {
            assert!((rho - (a - b * s)).abs() < 1e-12 * a, "{s}: {rho}");
        }
        assert!((fine.total_mass() - coarse.total_mass()).abs() < 1e-12);
        // Lists: each rod cut into equal parts, rho piecewise the same.
        let lists = Scene::from_toml_str(
            "[chain]\nlinks = 3\nrod_masses = [3, 2, 1]\nrod_lengths = [1, 2, 3]\n[start]\nkind = \"folded\"\n[run]\nt_end = 1\n",
        )
        .unwrap();
        let coarse = densities(&lists.chain().unwrap());
        let fine = refined_scene(&lists, 12).unwrap().chain().unwrap();
        for (s, rho) in densities(&fine) {
            // The coarse rod that holds s: boundaries at 1, 3 (of 6).
            let k = if s < 1.0 {
                0
            } else if s < 3.0 {
                1
            } else {
                2
            };
            assert!((rho - coarse[k].1).abs() < 1e-12 * rho, "{s}: {rho}");
        }
        // Any number of rods: the masses integrated over each new rod, the
        // totals and the arc length of each fractional joint index kept.
        let c = lists.chain().unwrap();
        let odd = refined_scene(&lists, 5).unwrap().chain().unwrap();
        assert!((odd.total_mass() - c.total_mass()).abs() < 1e-12);
        let d = densities(&odd);
        // Rod 1 of 5 spans index [0.6, 1.2]: arc 0.6..1.4 of L/6 units (rod
        // 0 of length 1 at density 3, then rod 1 of length 2 at density 1).
        let len1 = d[1].0 - d[0].0;
        assert!((len1 - 0.5 * (0.6 + 0.8)).abs() < 1e-12, "{d:?}");
        let want = (3.0 * 0.4 + 1.0 * 0.4) / 0.8 * coarse[0].1 / 3.0;
        assert!((d[1].1 - want).abs() < 1e-12 * want, "{d:?} vs {want}");
    }

    /// A list scene refined to a number of rods that is not a multiple of
    /// its list's agrees with the nearest multiple as closely as two
    /// neighbouring multiples agree: the same continuum (a wrong density
    /// at the straddled joints would show as an O(1 / n) offset).
    #[test]
    fn a_list_scene_at_any_n_runs_the_same_continuum() {
        let lists = Scene::from_toml_str(
            "[chain]\nlinks = 3\nrod_masses = [3, 2, 1]\nrod_lengths = [1, 2, 3]\n\
             [start]\nkind = \"catenary\"\np1 = [3, 0]\n\
             [run]\nt_end = 1.5\nmethod = \"dopri5\"\nrtol = 1e-9\n",
        )
        .unwrap();
        let tip = |n: usize| {
            let traj = refined_scene(&lists, n)
                .and_then(|s| s.prepare())
                .and_then(|p| p.solve())
                .unwrap();
            assert!(traj.status.is_ok());
            traj.tip(traj.len() - 1)
        };
        let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        let (t30, t60, t61, t63) = (tip(30), tip(60), tip(61), tip(63));
        let step = dist(t30, t60);
        assert!(step > 1e-4, "the ladder does not move: {step}");
        for (n, t) in [(61, t61), (63, t63)] {
            assert!(
                dist(t, t60) < 0.2 * step,
                "n = {n}: {} vs {step}",
                dist(t, t60)
            );
        }
    }

    #[test]
    fn refinement_keeps_mass_viscosity_and_fold_proportions() {
        let text = r#"
[chain]
links = 50
mass = 0.2
damping = 0.001
[start]
kind = "folded"
down = 25
[run]
t_end = 1
"#;
        let scene = Scene::from_toml_str(text).unwrap();
        let s = refined_scene(&scene, 200).unwrap();
        let c = s.chain().unwrap();
        assert_eq!(c.links(), 200);
        assert!((c.total_mass() - 10.0).abs() < 1e-12);
        assert!((c.damping() * c.rod_length() - 0.001 * 0.12).abs() < 1e-15);
        assert_eq!(
            s.start(),
            chain_ode::Start::Folded {
                p0: [0.0, 0.0],
                down: Some(100)
            }
        );
        let angles = Scene::from_toml_str(
            "[chain]\nlinks = 2\n[start]\nkind = \"angles\"\nangles = [0, 0.1]\n[run]\nt_end = 1\n",
        )
        .unwrap();
        let e = refined_scene(&angles, 4).unwrap_err().to_string();
        assert!(e.starts_with("start.kind: "), "{e}");
    }
}
