//! Cayley's scale as an ensemble: the chain of `scenes/cayley-scale.toml`
//! (hanging straight down, its lower end on the floor, let go at the top)
//! run from `members` starts whose rod angles are perturbed by a few
//! `spread` rad, and the scale's reading averaged over the members.
//!
//! One run's reading past the first landings is not reproducible (a
//! `1e-10` rad change of one start angle moves the mid-fall dissipation by
//! 7% to 9%, `docs/model.md`, "Why no matched error exists at mid-fall"),
//! so the well-posed quantity is the ensemble's: its mean and its standard
//! error over the members. Every member's reading is the one a scale with a
//! finite response gives, averaged over `t ± WINDOW` from the chain's
//! momentum (`F = dP_y/dt + M g`, exact: the floor and gravity are the only
//! forces on the released chain), and is reported over the ideal's average
//! over the same window, `3 mu g (g/2) (t² + WINDOW²/3)` (`mu = M / L`).
//! Beside it: the momentum over the ideal's `−mu (L − x) g t`, the work
//! dissipated over the ideal plastic landings' `mu g³ t⁴ / 8`, and the top's
//! fall over the free fall's `g t² / 2` (`x = g t² / 2`, the landed length).
//!
//! The figures `cayley-scale` (the reading) and `cayley-top` (the top's
//! fall against free fall) draw [`series_csv`], [`midfall_csv`] and
//! [`top_csv`].

use std::fmt::Write as _;

use rayon::prelude::*;

use chain_ode::{Method, Trajectory};
use fc_csv::format::{exp, num};
use fc_scene::scene::Scene;
// The perturbations are the `ensemble` study's draws, member `j` on stream
// `j` (seed 0), so that `falling-chain ensemble` with seed 0 draws the same.
use fc_study::ensemble::uniform;

/// Half the window the reading is averaged over (units of `sqrt(L / g)`).
pub const WINDOW: f64 = 0.05;
/// Half the wide window (units of `sqrt(L / g)`): at mid-fall it spans
/// the landings of `0.4 n` rods where [`WINDOW`]'s spans `0.1 n`, so that
/// the phase of the discrete landings against the window's edges weighs
/// four times less.
pub const WIDE: f64 = 0.2;
/// The samples' spacing (units of `sqrt(L / g)`): half the window, so that
/// the reading is on a grid of `WINDOW / 2`.
pub const SAMPLE_DT: f64 = 0.025;
/// The runs end here (units of `sqrt(L / g)`), before the ideal chain's
/// last rod lands at `sqrt(2) = 1.414`.
pub const T_END: f64 = 1.4;
/// Mid-fall: the ideal's landed length is `L / 2` (units of `sqrt(L / g)`).
pub const T_MID: f64 = 1.0;
/// The most members an ensemble may have (the `ensemble` study's bound).
pub use fc_study::ensemble::MAX_MEMBERS;

/// One ensemble: the chain, its floor, the start's zigzag and how it is
/// run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    /// Rods (`chain.links`); the total mass and length are the scene's.
    pub links: usize,
    /// `floor.stiffness` (force per length).
    pub stiffness: f64,
    /// `floor.damping` (force per speed).
    pub damping: f64,
    /// `floor.friction`, the floor's Coulomb coefficient `mu_f`.
    pub friction: f64,
    /// `chain.damping`, the joints' friction `r`.
    pub joint_friction: f64,
    /// The rods start at `∓tilt` rad from the vertical, alternately.
    pub tilt: f64,
    /// Each start angle is moved by a number drawn uniformly from
    /// `[−spread, spread]` rad (a member's own, by its seed).
    pub spread: f64,
    pub members: usize,
    pub method: Method,
    /// `run.rtol`; `run.atol` is `rtol / 100`.
    pub rtol: f64,
}

/// One member's readings at the sample times [`sample_times`].
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// The averaged reading over the ideal's average.
    pub reading: Vec<f64>,
    /// The same over [`WIDE`], where `t ± WIDE` is within the run.
    pub reading_wide: Vec<Option<f64>>,
    /// The momentum over the ideal's.
    pub momentum: Vec<f64>,
    /// The dissipated work over the ideal's.
    pub dissipated: Vec<f64>,
    /// The top's fall over the free fall's.
    pub top: Vec<f64>,
    pub steps: u64,
    pub rhs_evals: u64,
    /// The integration's wall time (s): reported only by the examples,
    /// never written to a figure's data.
    pub wall_seconds: f64,
}

/// Mean and standard error of one quantity over the members.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stat {
    pub mean: f64,
    /// The sample standard deviation over the members.
    pub sd: f64,
    /// `sd / sqrt(members)`.
    pub sem: f64,
}

impl Stat {
    /// The statistics of `xs` (at least two values;
    /// [`fc_study::ensemble::moments`]).
    pub fn of(xs: &[f64]) -> Stat {
        let (mean, sd, sem) = fc_study::ensemble::moments(xs).unwrap_or((f64::NAN, 0.0, 0.0));
        Stat { mean, sd, sem }
    }
}

/// An ensemble's result at one sample time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// The time (units of `sqrt(L / g)`).
    pub t: f64,
    pub reading: Stat,
    /// Over [`WIDE`], where `t ± WIDE` is within the run.
    pub reading_wide: Option<Stat>,
    pub momentum: Stat,
    pub dissipated: Stat,
    pub top: Stat,
}

/// A finished ensemble.
#[derive(Clone, Debug, PartialEq)]
pub struct Ensemble {
    pub case: Case,
    /// One per sample time of [`sample_times`].
    pub points: Vec<Point>,
    /// Steps and right-hand sides summed over the members.
    pub steps: u64,
    pub rhs_evals: u64,
    /// The members' integration wall times summed (s).
    pub wall_seconds: f64,
    /// The members whose runs did not end `ok`, and how each ended (the
    /// statistics are over the others).
    pub failed: Vec<(usize, String)>,
}

impl Ensemble {
    /// The point at mid-fall ([`T_MID`]).
    pub fn midfall(&self) -> &Point {
        let k = self
            .points
            .iter()
            .position(|p| (p.t - T_MID).abs() < 1e-9)
            .unwrap_or(self.points.len() / 2);
        &self.points[k]
    }
}

/// The times the readings are given at: `WINDOW .. T_END − WINDOW` on the
/// grid of [`SAMPLE_DT`] (so that each has a sample `WINDOW` either side).
pub fn sample_times() -> Vec<f64> {
    let per = (WINDOW / SAMPLE_DT).round() as usize;
    let last = (T_END / SAMPLE_DT).round() as usize - per;
    (per..=last).map(|k| k as f64 * SAMPLE_DT).collect()
}

/// The start angles of member `member`: rod `i` at `−pi/2 ± tilt` (`+` for
/// even `i`) plus its perturbation.
pub fn start_angles(case: &Case, member: usize) -> Vec<f64> {
    (0..case.links)
        .map(|i| {
            let zig = if i % 2 == 0 { case.tilt } else { -case.tilt };
            -std::f64::consts::FRAC_PI_2 + zig + case.spread * uniform(member as u64, i as u64)
        })
        .collect()
}

/// `base` (the Cayley scene) as member `member` of `case`: its rods,
/// the same total mass, its floor, the start and the run.
pub fn member_scene(base: &Scene, case: &Case, member: usize) -> Result<Scene, String> {
    let p = base.chain_params();
    let total = p.mass * p.links as f64;
    let angles = start_angles(case, member)
        .into_iter()
        .map(toml::Value::Float)
        .collect();
    let sets: [(&str, toml::Value); 12] = [
        ("chain.links", toml::Value::Integer(case.links as i64)),
        ("chain.mass", toml::Value::Float(total / case.links as f64)),
        ("chain.damping", toml::Value::Float(case.joint_friction)),
        ("floor.stiffness", toml::Value::Float(case.stiffness)),
        ("floor.damping", toml::Value::Float(case.damping)),
        ("floor.friction", toml::Value::Float(case.friction)),
        ("start.angles", toml::Value::Array(angles)),
        ("run.method", toml::Value::String(case.method.to_string())),
        ("run.rtol", toml::Value::Float(case.rtol)),
        ("run.atol", toml::Value::Float(case.rtol * 1e-2)),
        ("run.t_end", toml::Value::Float(T_END)),
        ("run.output_dt", toml::Value::Float(SAMPLE_DT)),
    ];
    let mut scene = base.clone();
    for (key, value) in sets {
        scene = scene.with_value(key, value).map_err(|e| e.to_string())?;
    }
    Ok(scene)
}

/// The readings of one finished run, in units of `L`, `g` and `M`.
pub fn readings(traj: &Trajectory) -> Result<Member, String> {
    let chain = traj.chain();
    let (l, g) = (chain.length(), chain.gravity());
    let mass = chain.mass() * chain.links() as f64;
    let mu = mass / l;
    let top0 = traj.joints(0)[0][1];
    let at = |t: f64| {
        traj.times
            .iter()
            .position(|&s| (s - t).abs() < 1e-9)
            .ok_or_else(|| format!("no sample at t = {t}"))
    };
    let mut m = Member {
        reading: Vec::new(),
        reading_wide: Vec::new(),
        momentum: Vec::new(),
        dissipated: Vec::new(),
        top: Vec::new(),
        steps: traj.stats.steps,
        rhs_evals: traj.stats.rhs_evals,
        wall_seconds: traj.summary.wall_seconds,
    };
    let scale = (l / g).sqrt();
    // The reading over `t ± d` (units of `sqrt(L / g)`) over the ideal's
    // average over the same window; `None` where the window leaves the run.
    let averaged = |t: f64, d: f64| -> Option<f64> {
        let (lo, hi) = (at((t - d) * scale).ok()?, at((t + d) * scale).ok()?);
        let (tt, dd) = (t * scale, d * scale);
        let f = (traj.momentum(hi)[1] - traj.momentum(lo)[1]) / (2.0 * dd) + mass * g;
        Some(f / (3.0 * mu * g * 0.5 * g * (tt * tt + dd * dd / 3.0)))
    };
    for t in sample_times() {
        let k = at(t * scale)?;
        let tt = t * scale;
        let x = 0.5 * g * tt * tt;
        m.reading.push(
            averaged(t, WINDOW)
                .ok_or_else(|| format!("no samples {WINDOW} either side of t = {t}"))?,
        );
        m.reading_wide
            .push((t >= WIDE - 1e-9).then(|| averaged(t, WIDE)).flatten());
        m.momentum
            .push(traj.momentum(k)[1] / (-mu * (l - x) * g * tt));
        m.dissipated
            .push(traj.sample(k).dissipated / (mu * g.powi(3) * tt.powi(4) / 8.0));
        m.top.push((top0 - traj.joints(k)[0][1]) / x);
    }
    Ok(m)
}

/// Runs the ensemble `case` from `base` (its members in parallel): [`run_all`]
/// of the one case.
pub fn run(base: &Scene, case: &Case) -> Result<Ensemble, String> {
    run_all(base, std::slice::from_ref(case))?
        .pop()
        .ok_or_else(|| "cayley: no ensemble".to_string())
}

/// Runs the ensembles `cases` from `base`, every member of every case in
/// one parallel loop (no case waits for another's slowest member; each
/// member's run is its own, so the ensembles are those of [`run`] one case
/// at a time, bit for bit). A member whose run ends with a failed status is
/// listed in [`Ensemble::failed`] and left out of the statistics; fewer
/// than two members that end `ok` is an error naming the first failure.
pub fn run_all(base: &Scene, cases: &[Case]) -> Result<Vec<Ensemble>, String> {
    if let Some(c) = cases
        .iter()
        .find(|c| !(2..=MAX_MEMBERS).contains(&c.members))
    {
        return Err(format!(
            "cayley: members must be 2 to {MAX_MEMBERS} (got {})",
            c.members
        ));
    }
    let jobs: Vec<(usize, usize)> = (cases.iter().enumerate())
        .flat_map(|(c, case)| (0..case.members).map(move |j| (c, j)))
        .collect();
    let mut runs: Vec<Result<Member, String>> = jobs
        .par_iter()
        .map(|&(c, j)| {
            let scene = member_scene(base, &cases[c], j)?;
            let traj = scene
                .prepare()
                .map_err(|e| e.to_string())?
                .solve()
                .map_err(|e| e.to_string())?;
            Ok(if traj.status.is_ok() {
                Ok(readings(&traj)?)
            } else {
                Err(format!("status {} at t = {}", traj.status, traj.t_reached))
            })
        })
        .collect::<Result<Vec<_>, String>>()?
        .into_iter()
        .rev()
        .collect();
    cases
        .iter()
        .map(|case| {
            let mine: Vec<_> = (0..case.members).filter_map(|_| runs.pop()).collect();
            ensemble(case, mine)
        })
        .collect()
}

/// The statistics of `case`'s members' runs (in member order).
fn ensemble(case: &Case, runs: Vec<Result<Member, String>>) -> Result<Ensemble, String> {
    let failed: Vec<(usize, String)> = runs
        .iter()
        .enumerate()
        .filter_map(|(j, r)| r.as_ref().err().map(|e| (j, e.clone())))
        .collect();
    let members: Vec<Member> = runs.into_iter().filter_map(Result::ok).collect();
    if members.len() < 2 {
        let (j, why) = failed.first().cloned().unwrap_or_default();
        return Err(format!(
            "cayley n = {}, k = {}: {} of {} members ended ok (member {j}: {why})",
            case.links,
            case.stiffness,
            members.len(),
            case.members
        ));
    }
    let stat = |k: usize, f: fn(&Member) -> &Vec<f64>| {
        Stat::of(&members.iter().map(|m| f(m)[k]).collect::<Vec<_>>())
    };
    let points = sample_times()
        .into_iter()
        .enumerate()
        .map(|(k, t)| Point {
            t,
            reading: stat(k, |m| &m.reading),
            reading_wide: members
                .iter()
                .map(|m| m.reading_wide[k])
                .collect::<Option<Vec<f64>>>()
                .map(|xs| Stat::of(&xs)),
            momentum: stat(k, |m| &m.momentum),
            dissipated: stat(k, |m| &m.dissipated),
            top: stat(k, |m| &m.top),
        })
        .collect();
    Ok(Ensemble {
        case: *case,
        points,
        steps: members.iter().map(|m| m.steps).sum(),
        rhs_evals: members.iter().map(|m| m.rhs_evals).sum(),
        wall_seconds: members.iter().map(|m| m.wall_seconds).sum(),
        failed,
    })
}

/// The columns of a case in the CSVs.
const CASE_HEAD: &str =
    "links,stiffness,damping,friction,joint_friction,tilt,spread,members,method,rtol";

fn case_cells(c: &Case) -> String {
    format!(
        "{},{},{},{},{},{},{},{},{},{}",
        c.links,
        exp(c.stiffness),
        num(c.damping),
        num(c.friction),
        exp(c.joint_friction),
        num(c.tilt),
        exp(c.spread),
        c.members,
        c.method,
        exp(c.rtol)
    )
}

fn stat_cells(s: &Stat) -> String {
    format!("{},{},{}", num(s.mean), num(s.sd), num(s.sem))
}

/// [`stat_cells`], or three empty cells.
fn wide_cells(s: Option<&Stat>) -> String {
    s.map_or_else(|| ",,".to_string(), stat_cells)
}

/// Every ensemble's readings at every sample time: one row per ensemble
/// and time.
pub fn series_csv(ensembles: &[Ensemble]) -> String {
    let mut s = format!(
        "{CASE_HEAD},t,reading_mean,reading_sd,reading_sem,reading_wide_mean,reading_wide_sd,\
         reading_wide_sem,momentum_mean,momentum_sd,momentum_sem\n"
    );
    for e in ensembles {
        for p in &e.points {
            let _ = writeln!(
                s,
                "{},{},{},{},{}",
                case_cells(&e.case),
                num(p.t),
                stat_cells(&p.reading),
                wide_cells(p.reading_wide.as_ref()),
                stat_cells(&p.momentum)
            );
        }
    }
    s
}

/// Every ensemble's top: its fall over the free fall's at every sample
/// time, one row per ensemble and time.
pub fn top_csv(ensembles: &[Ensemble]) -> String {
    let mut s = format!("{CASE_HEAD},t,top_mean,top_sd,top_sem\n");
    for e in ensembles {
        for p in &e.points {
            let _ = writeln!(
                s,
                "{},{},{}",
                case_cells(&e.case),
                num(p.t),
                stat_cells(&p.top)
            );
        }
    }
    s
}

/// Every ensemble at mid-fall: the reading, the momentum, the dissipated
/// work and the top's fall, with the steps the members took in all.
pub fn midfall_csv(ensembles: &[Ensemble]) -> String {
    let mut s = format!(
        "{CASE_HEAD},reading_mean,reading_sd,reading_sem,reading_wide_mean,reading_wide_sd,\
         reading_wide_sem,momentum_mean,momentum_sd,momentum_sem,\
         dissipated_mean,dissipated_sd,dissipated_sem,top_mean,top_sd,top_sem,steps,rhs_evals\n"
    );
    for e in ensembles {
        let p = e.midfall();
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{}",
            case_cells(&e.case),
            stat_cells(&p.reading),
            wide_cells(p.reading_wide.as_ref()),
            stat_cells(&p.momentum),
            stat_cells(&p.dissipated),
            stat_cells(&p.top),
            e.steps,
            e.rhs_evals
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> Scene {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/cayley-scale.toml");
        Scene::load(path).unwrap()
    }

    fn case(links: usize, spread: f64, members: usize) -> Case {
        Case {
            links,
            stiffness: 1e5,
            damping: 100.0,
            friction: 0.0,
            joint_friction: 0.0,
            tilt: 0.2,
            spread,
            members,
            method: Method::Dop853,
            rtol: 1e-6,
        }
    }

    /// A member is the scene at the asked rods (its total mass kept), floor
    /// and run, its rods at `∓tilt` within `spread`.
    #[test]
    fn a_member_is_the_scene_at_the_asked_rods_floor_and_start() {
        let c = case(10, 1e-3, 2);
        let p = member_scene(&base(), &c, 1).unwrap().prepare().unwrap();
        assert_eq!(p.chain.links(), 10);
        assert!((p.chain.mass() * 10.0 - 1.0).abs() < 1e-12);
        let f = p.chain.floor().unwrap();
        assert_eq!((f.stiffness, f.damping, f.friction), (1e5, 100.0, 0.0));
        assert_eq!(p.chain.damping(), 0.0);
        assert_eq!(
            (p.method, p.options.rtol, p.options.t_end),
            (Method::Dop853, 1e-6, T_END)
        );
        for (i, a) in start_angles(&c, 1).iter().enumerate() {
            let zig = if i % 2 == 0 { 0.2 } else { -0.2 };
            let off = a + std::f64::consts::FRAC_PI_2 - zig;
            assert!(off.abs() <= 1e-3 && off != 0.0, "rod {i}: {off}");
        }
    }

    /// The reading from the momentum, `dP_y/dt + M g` over the window, is
    /// the floor's force integrated over the same window from the contact
    /// forces themselves (the trapezoid rule on samples `1e-5` apart): two
    /// formulations, one from the chain's motion and one from the floor's
    /// law. Dropping the weight `M g` (or the window's `2 d`) fails it by
    /// far more than the bound. Measured: they agree to 3.8e-4 of the
    /// reading (or of 1 where it is below); on samples `1e-4` apart the
    /// trapezoid misses the plastic kicks by up to 8%.
    #[test]
    fn the_reading_from_the_momentum_is_the_floor_force_averaged() {
        let c = case(10, 0.0, 2);
        let scene = member_scene(&base(), &c, 0)
            .unwrap()
            .with_value("run.output_dt", toml::Value::Float(1e-5))
            .unwrap();
        let traj = scene.prepare().unwrap().solve().unwrap();
        assert!(traj.status.is_ok(), "{}", traj.status);
        let m = readings(&traj).unwrap();
        let ts = sample_times();
        let mut worst: f64 = 0.0;
        for (j, &t) in ts.iter().enumerate().step_by(4) {
            let (lo, hi) = (t - WINDOW, t + WINDOW);
            let ks: Vec<usize> = (0..traj.len())
                .filter(|&k| traj.times[k] >= lo - 1e-9 && traj.times[k] <= hi + 1e-9)
                .collect();
            let impulse: f64 = ks
                .windows(2)
                .map(|w| {
                    let (a, b) = (w[0], w[1]);
                    let fa = traj.floor_force(a).unwrap()[1];
                    let fb = traj.floor_force(b).unwrap()[1];
                    0.5 * (fa + fb) * (traj.times[b] - traj.times[a])
                })
                .sum();
            let ideal = 3.0 * 0.5 * (t * t + WINDOW * WINDOW / 3.0);
            let direct = impulse / (2.0 * WINDOW) / ideal;
            worst = worst.max((m.reading[j] - direct).abs() / direct.max(1.0));
        }
        assert!(worst < 2e-3, "the two readings differ by {worst}");
    }

    /// Without a perturbation the members are one run (their spread is 0);
    /// with one they differ. Over `t = 0.3 .. 0.9` (`x = 0.045 .. 0.405 L`)
    /// the ensemble's momentum over the ideal's `−mu (L − x) g t` averages
    /// to 1 within 3% (what has not landed falls freely, what has landed
    /// rests; each landing of one of the 10 rods moves it by up to 10%, so
    /// the mean over the window is tested, measured 0.993); a floor that
    /// is missed gives the free fall's `1 / (1 − x)`, 1.2 on average there.
    #[test]
    fn an_ensemble_spreads_only_when_perturbed_and_follows_the_ideal_early() {
        let still = run(&base(), &case(10, 0.0, 2)).unwrap();
        let moved = run(&base(), &case(10, 1e-3, 4)).unwrap();
        let mid = still.midfall();
        assert_eq!((mid.reading.sd, mid.top.sd), (0.0, 0.0), "{mid:?}");
        assert!(moved.midfall().reading.sd > 0.0);
        let window: Vec<f64> = moved
            .points
            .iter()
            .filter(|p| p.t > 0.3 - 1e-9 && p.t < 0.9 + 1e-9)
            .map(|p| p.momentum.mean)
            .collect();
        let mean = window.iter().sum::<f64>() / window.len() as f64;
        assert_eq!(window.len(), 25);
        assert!(
            (mean - 1.0).abs() < 0.03,
            "momentum over the ideal's {mean}"
        );
        assert!(
            run(&base(), &case(10, 0.0, 1)).is_err(),
            "one member has no spread"
        );
        assert!(still.failed.is_empty() && moved.failed.is_empty());
    }

    /// The cases run together ([`run_all`], every member in one parallel
    /// loop) are the cases run one at a time, bit for bit (the wall times
    /// aside), in the cases' order; a case with too few members is refused
    /// before anything runs.
    #[test]
    fn cases_run_together_are_the_cases_run_alone() {
        let cases = [case(10, 1e-3, 3), case(6, 1e-3, 2), case(10, 0.0, 2)];
        let together = run_all(&base(), &cases).unwrap();
        assert_eq!(together.len(), cases.len());
        for (c, e) in cases.iter().zip(&together) {
            let alone = run(&base(), c).unwrap();
            assert_eq!(e.case, *c);
            assert_eq!(e.points, alone.points, "{c:?}");
            assert_eq!((e.steps, e.rhs_evals), (alone.steps, alone.rhs_evals));
            assert_eq!(e.failed, alone.failed);
        }
        assert_ne!(together[0].points, together[1].points);
        assert!(run_all(&base(), &[case(10, 1e-3, 2), case(10, 1e-3, 1)]).is_err());
    }

    #[test]
    fn the_sample_times_have_a_sample_a_window_either_side() {
        let ts = sample_times();
        assert!((ts[0] - WINDOW).abs() < 1e-12);
        assert!((ts[ts.len() - 1] + WINDOW - T_END).abs() < 1e-12);
        assert!(ts.iter().any(|t| (t - T_MID).abs() < 1e-12));
    }

    #[test]
    fn the_statistics_of_a_sample_are_its_mean_and_spread() {
        let s = Stat::of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(s.mean, 2.5);
        assert!((s.sd - (5.0_f64 / 3.0).sqrt()).abs() < 1e-15);
        assert!((s.sem - s.sd / 2.0).abs() < 1e-15);
    }
}
