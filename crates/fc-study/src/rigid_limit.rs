//! "When can I use the rigid model": the axial stiffness `EA` above which
//! a scene's elastic chain agrees with its rigid one within `tol`.
//!
//! The scene is run once with rigid links (`chain.axial_stiffness` absent)
//! and then with elastic links on a ladder of `EA` (equal steps in `log EA`,
//! loosest first), each at the scene's own `n`, mass per rod and friction,
//! with the axial damping set for a damping ratio `zeta` of one joint
//! (`eta = 2 zeta sqrt(EA m l)`, `docs/model.md`, "The elastic chain"), the
//! same method and tolerance for every run. Each elastic run's distance from
//! the rigid run is [`Deviation`]: the tip path (`max_t |tip - tip_rigid| /
//! L` over the samples) and the maximum tip speed (relative). The ladder
//! stops after [`CONFIRM`] passing rungs in a row (`max(path, speed) <
//! tol`) or at its top. The threshold is where the deviation crosses `tol`
//! between the last failing rung and the first rung of that passing run,
//! interpolated linearly in `log EA` - `log deviation` (the deviation falls
//! like `1/EA` in the rigid limit, so this is nearly exact there).

use serde::Serialize;

use crate::converge::{self, Deviation, Level};
use fc_csv::format::{exp, num, opt};
use fc_scene::error::Error;
use fc_scene::scene::Scene;

/// Passing rungs in a row that end the ladder.
pub const CONFIRM: usize = 2;

/// The largest number of rungs a ladder may have.
pub const MAX_RUNGS: usize = 64;

/// What to run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Agreement wanted in tip path (relative to `L`) and maximum tip speed.
    pub tol: f64,
    /// Damping ratio `C / (2 sqrt(K m))` of one joint.
    pub zeta: f64,
    /// The ladder's lowest and highest `EA` (force units).
    pub ea_from: f64,
    pub ea_to: f64,
    /// Rungs per decade of `EA`.
    pub per_decade: usize,
    /// Method of every run (`run.method`).
    pub method: String,
    /// Relative tolerance of every run (`atol = rtol / 100`).
    pub rtol: f64,
}

impl Default for Options {
    /// `tol = 1e-3`, 5% damping of a joint, `EA = 1e3 .. 1e9` at two rungs
    /// per decade, DOPRI5 at `rtol = 1e-8`.
    fn default() -> Self {
        Self {
            tol: 1e-3,
            zeta: 0.05,
            ea_from: 1e3,
            ea_to: 1e9,
            per_decade: 2,
            method: "dopri5".into(),
            rtol: 1e-8,
        }
    }
}

impl Options {
    /// Checks every field; the error names the first one out of range.
    pub fn validate(&self) -> Result<(), Error> {
        if !(self.tol.is_finite() && self.tol > 0.0 && self.tol < 1.0) {
            return Err(Error::field("tol", "must be in (0, 1)"));
        }
        if !(self.zeta.is_finite() && self.zeta >= 0.0 && self.zeta <= 10.0) {
            return Err(Error::field("zeta", "must be in [0, 10]"));
        }
        let ok_ea = |x: f64| x.is_finite() && x > 0.0 && x <= 1e15;
        if !(ok_ea(self.ea_from) && ok_ea(self.ea_to) && self.ea_from <= self.ea_to) {
            return Err(Error::field(
                "ea",
                "the ladder's EA must be in (0, 1e15], lowest first",
            ));
        }
        if self.per_decade == 0 || self.ladder().len() > MAX_RUNGS {
            return Err(Error::field(
                "per_decade",
                format!("must be at least 1, with at most {MAX_RUNGS} rungs in all"),
            ));
        }
        Ok(())
    }

    /// The ladder of `EA`: `ea_from * 10^(k / per_decade)` up to `ea_to`.
    pub fn ladder(&self) -> Vec<f64> {
        let decades = (self.ea_to / self.ea_from).log10();
        let rungs = (decades * self.per_decade as f64 + 1e-9).floor() as usize;
        (0..=rungs.min(MAX_RUNGS))
            .map(|k| self.ea_from * 10f64.powf(k as f64 / self.per_decade as f64))
            .collect()
    }
}

/// One elastic run of the ladder.
#[derive(Clone, Debug, Serialize)]
pub struct Rung {
    /// `EA` (force units).
    pub axial_stiffness: f64,
    /// `eta` (force x time) for the wanted damping ratio.
    pub axial_damping: f64,
    pub status: String,
    /// Its distance from the rigid run (`None` if it did not complete).
    pub deviation: Option<Deviation>,
    pub steps: u64,
    pub rhs_evals: u64,
    /// Wall time of the run (seconds; not reproducible).
    pub wall_seconds: f64,
}

impl Rung {
    /// `max(tip path, tip speed)` deviation, if the run completed.
    pub fn worst(&self) -> Option<f64> {
        self.deviation
            .map(|d| d.tip_path.max(d.tip_speed_max))
            .filter(|x| x.is_finite())
    }
}

/// The answer for one scene.
#[derive(Clone, Debug, Serialize)]
pub struct RigidLimit {
    pub scene: String,
    pub links: usize,
    pub tol: f64,
    pub zeta: f64,
    /// The rigid run's status and maximum tip speed.
    pub rigid_status: String,
    pub rigid_tip_speed_max: f64,
    pub rungs: Vec<Rung>,
    /// The `EA` above which the elastic chain agrees within `tol`; `None`
    /// when the ladder never passed [`CONFIRM`] times in a row.
    pub threshold: Option<f64>,
    /// True when the lowest rung already passed: the threshold is then at
    /// most `ea_from` (reported as `ea_from`).
    pub below_ladder: bool,
}

/// `EA` where the deviation crosses `tol` between `(ea0, dev0)` (failing)
/// and `(ea1, dev1)` (passing), log-log interpolated.
pub fn crossing(tol: f64, (ea0, dev0): (f64, f64), (ea1, dev1): (f64, f64)) -> f64 {
    if !(dev0 > 0.0 && dev1 > 0.0) || dev0 == dev1 {
        return ea1;
    }
    let s = (tol.ln() - dev0.ln()) / (dev1.ln() - dev0.ln());
    (ea0.ln() + s.clamp(0.0, 1.0) * (ea1.ln() - ea0.ln())).exp()
}

/// The threshold of a finished ladder (rungs lowest `EA` first): the first
/// rung of the first run of [`CONFIRM`] passing rungs that reaches the top or
/// the ladder's end, interpolated against the rung before it.
pub fn threshold(tol: f64, rungs: &[Rung]) -> (Option<f64>, bool) {
    let pass = |r: &Rung| r.worst().is_some_and(|w| w < tol);
    let mut run = 0;
    for (k, r) in rungs.iter().enumerate() {
        run = if pass(r) { run + 1 } else { 0 };
        if run == CONFIRM {
            let first = k + 1 - CONFIRM;
            if first == 0 {
                return (Some(rungs[0].axial_stiffness), true);
            }
            let before = &rungs[first - 1];
            let at = &rungs[first];
            let (Some(d0), Some(d1)) = (before.worst(), at.worst()) else {
                return (Some(at.axial_stiffness), false);
            };
            let ea = crossing(tol, (before.axial_stiffness, d0), (at.axial_stiffness, d1));
            return (Some(ea), false);
        }
    }
    (None, false)
}

/// `scene` with rigid links.
pub fn rigid(scene: &Scene) -> Result<Scene, Error> {
    let mut params = scene.chain_params().clone();
    params.axial_stiffness = None;
    scene.with_chain(&chain_ode::Chain::new(params)?)
}

/// `scene` with elastic links of stiffness `ea` and damping ratio `zeta` of
/// one joint; returns it and its `eta`.
pub fn elastic(scene: &Scene, ea: f64, zeta: f64) -> Result<(Scene, f64), Error> {
    let p = scene.chain_params();
    let l = p.length / p.links as f64;
    let eta = 2.0 * zeta * (ea * p.mass * l).sqrt();
    let s = scene
        .with_value("chain.axial_stiffness", toml::Value::Float(ea))?
        .with_value("chain.axial_damping", toml::Value::Float(eta))?;
    Ok((s, eta))
}

fn run(scene: &Scene, opts: &Options) -> Result<Level, Error> {
    let n = scene.chain_params().links;
    converge::run_level(scene, n, Some(&opts.method), Some(opts.rtol))
}

/// Runs the ladder for `scene` (see the module's text).
pub fn rigid_limit(scene: &Scene, opts: &Options) -> Result<RigidLimit, Error> {
    opts.validate()?;
    let reference = run(&rigid(scene)?, opts)?;
    let mut out = RigidLimit {
        scene: scene.name().to_string(),
        links: reference.links(),
        tol: opts.tol,
        zeta: opts.zeta,
        rigid_status: reference.summary.status.clone(),
        rigid_tip_speed_max: reference.summary.tip_speed_max,
        rungs: vec![],
        threshold: None,
        below_ladder: false,
    };
    if !reference.summary.is_ok() {
        return Ok(out);
    }
    let mut passed = 0;
    for ea in opts.ladder() {
        let (s, eta) = elastic(scene, ea, opts.zeta)?;
        let level = run(&s, opts)?;
        let ok = level.summary.is_ok();
        let rung = Rung {
            axial_stiffness: ea,
            axial_damping: eta,
            status: level.summary.status.clone(),
            deviation: ok.then(|| Deviation::between(&level, &reference)),
            steps: level.summary.steps,
            rhs_evals: level.summary.rhs_evals,
            wall_seconds: level.summary.wall_seconds,
        };
        passed = if rung.worst().is_some_and(|w| w < opts.tol) {
            passed + 1
        } else {
            0
        };
        out.rungs.push(rung);
        if passed == CONFIRM {
            break;
        }
    }
    (out.threshold, out.below_ladder) = threshold(opts.tol, &out.rungs);
    Ok(out)
}

/// The header of [`rungs_csv`].
pub const RUNGS_HEADER: &str = "scene,links,axial_stiffness,axial_damping,zeta,status,\
                                tip_path,tip_speed_max,steps,rhs_evals,wall_seconds\n";

/// Every rung of `r`, one CSV row each (after [`RUNGS_HEADER`]); the wall
/// time, in the last column, is not reproducible.
pub fn rungs_csv(r: &RigidLimit) -> String {
    let mut s = String::new();
    for g in &r.rungs {
        let d = g.deviation;
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{:.3e}\n",
            r.scene,
            r.links,
            exp(g.axial_stiffness),
            num(g.axial_damping),
            num(r.zeta),
            g.status,
            opt(d.map(|d| d.tip_path), exp),
            opt(d.map(|d| d.tip_speed_max), exp),
            g.steps,
            g.rhs_evals,
            g.wall_seconds
        ));
    }
    s
}

/// The header of [`threshold_csv`].
pub const THRESHOLD_HEADER: &str =
    "scene,links,tol,zeta,rigid_status,rigid_tip_speed_max,threshold,below_ladder\n";

/// The answer of `r`, one CSV row (after [`THRESHOLD_HEADER`]).
pub fn threshold_csv(r: &RigidLimit) -> String {
    format!(
        "{},{},{},{},{},{},{},{}\n",
        r.scene,
        r.links,
        exp(r.tol),
        num(r.zeta),
        r.rigid_status,
        num(r.rigid_tip_speed_max),
        opt(r.threshold, exp),
        r.below_ladder
    )
}

/// The rigid limit of every scene of `scenes` (`(name, scene)`, run on the
/// current rayon pool) with `opts`, as `(suffix, csv)`: every rung
/// (`-timing`, [`rungs_csv`]) and each scene's answer (`-threshold-timing`,
/// [`threshold_csv`]), both with wall times; `tick` gets a line per
/// scene, in order.
pub fn tables(
    scenes: &[(&str, Scene)],
    opts: &Options,
    tick: &dyn Fn(String),
) -> Result<Vec<(&'static str, String)>, String> {
    use rayon::prelude::*;
    let results: Vec<Result<RigidLimit, String>> = (scenes.par_iter())
        .map(|(name, scene)| rigid_limit(scene, opts).map_err(|e| format!("{name}: {e}")))
        .collect();
    let (mut rungs, mut answers) = (RUNGS_HEADER.to_string(), THRESHOLD_HEADER.to_string());
    for r in results {
        let r = r?;
        rungs.push_str(&rungs_csv(&r));
        answers.push_str(&threshold_csv(&r));
        let above = (r.threshold).map_or("none in the ladder".into(), |t| format!("{t:.3e}"));
        tick(format!("{}: EA above {above}", r.scene));
    }
    Ok(vec![("-timing", rungs), ("-threshold-timing", answers)])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rung(ea: f64, worst: f64) -> Rung {
        Rung {
            axial_stiffness: ea,
            axial_damping: 0.0,
            status: "ok".into(),
            deviation: Some(Deviation {
                tip_speed_max: worst / 2.0,
                tip_end: 0.0,
                tip_path: worst,
                measured: None,
            }),
            steps: 0,
            rhs_evals: 0,
            wall_seconds: 0.0,
        }
    }

    /// On `dev = C / EA` the crossing is exact; a passing rung followed by
    /// a failing one does not count; a ladder that never passes twice in a
    /// row has no threshold; one that passes from its start says so.
    #[test]
    fn threshold_is_the_interpolated_crossing_of_the_last_passing_run() {
        let law = |ea: f64| 30.0 / ea;
        let ladder = [1e3, 1e4, 1e5, 1e6];
        let rungs: Vec<Rung> = ladder.iter().map(|&e| rung(e, law(e))).collect();
        let (t, below) = threshold(1e-3, &rungs);
        assert!(!below);
        assert!((t.unwrap() / 3e4 - 1.0).abs() < 1e-12, "{t:?}");
        // pass, fail, pass, pass: the answer is the second run's.
        let rungs = vec![
            rung(1e3, 1e-4),
            rung(1e4, 1e-2),
            rung(1e5, 1e-4),
            rung(1e6, 1e-5),
        ];
        let t = threshold(1e-3, &rungs).0.unwrap();
        assert!((t / 10f64.powf(4.5) - 1.0).abs() < 1e-12, "{t}");
        assert_eq!(threshold(1e-3, &rungs[..3]).0, None);
        let all = vec![rung(1e3, 1e-4), rung(1e4, 1e-5)];
        assert_eq!(threshold(1e-3, &all), (Some(1e3), true));
    }

    #[test]
    fn the_ladder_has_per_decade_rungs_and_bad_options_are_refused() {
        let o = Options {
            ea_from: 1e3,
            ea_to: 1e5,
            per_decade: 2,
            ..Options::default()
        };
        let l = o.ladder();
        assert_eq!(l.len(), 5);
        assert!((l[1] / 10f64.powf(3.5) - 1.0).abs() < 1e-12 && (l[4] / 1e5 - 1.0).abs() < 1e-12);
        for bad in [
            Options {
                tol: 0.0,
                ..o.clone()
            },
            Options {
                zeta: f64::NAN,
                ..o.clone()
            },
            Options {
                ea_to: 1e2,
                ..o.clone()
            },
            Options {
                per_decade: 0,
                ..o.clone()
            },
            Options {
                per_decade: 100,
                ..o.clone()
            },
        ] {
            assert!(bad.validate().is_err());
        }
        assert!(o.validate().is_ok());
    }
}

#[cfg(test)]
mod physics {
    use super::*;

    const SCENE: &str = r#"
name = "small-span"
[chain]
length = 6.0
links = 10
mass = 0.2
gravity = 1.0
damping = 0.0005
[start]
kind = "catenary"
p0 = [0.0, 0.0]
p1 = [3.0, 0.0]
[run]
t_end = 3.0
method = "dopri5"
output_dt = 0.02
"#;

    /// The elastic chain tends to the rigid one at first order in `1/EA`
    /// (a wrong limit, say a stretched rest length or a missing
    /// pre-stretch, leaves an offset and the slope flattens), and the
    /// threshold separates runs that fail from runs that pass.
    #[test]
    fn deviation_falls_like_one_over_ea_and_the_threshold_separates() {
        let scene = Scene::from_toml_str(SCENE).unwrap();
        let opts = Options {
            ea_from: 1e3,
            ea_to: 1e7,
            per_decade: 1,
            rtol: 1e-9,
            ..Options::default()
        };
        let r = rigid_limit(&scene, &opts).unwrap();
        let worst: Vec<(f64, f64)> = r
            .rungs
            .iter()
            .map(|g| (g.axial_stiffness, g.worst().unwrap()))
            .collect();
        eprintln!("{worst:?} -> {:?}", r.threshold);
        let (a, b) = (worst[worst.len() - 2], worst[worst.len() - 1]);
        let order = -(b.1 / a.1).ln() / (b.0 / a.0).ln();
        assert!((0.7..1.3).contains(&order), "order {order}: {worst:?}");
        let t = r.threshold.unwrap();
        assert!(!r.below_ladder);
        let dev_at = |ea: f64| {
            let (s, _) = elastic(&scene, ea, opts.zeta).unwrap();
            let level = run(&s, &opts).unwrap();
            let reference = run(&rigid(&scene).unwrap(), &opts).unwrap();
            let d = Deviation::between(&level, &reference);
            d.tip_path.max(d.tip_speed_max)
        };
        assert!(
            dev_at(2.0 * t) < opts.tol && dev_at(0.5 * t) > opts.tol,
            "{t}"
        );
    }
}
