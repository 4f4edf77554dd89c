//! The snap at full extension: the force and the impulse on the support,
//! and the tension along the chain around it.
//!
//! One run of a scene ([`measure`]) gives:
//!
//! * the **peak support force** `max_t |F_1(t)|`, in units of the chain's
//!   weight `M g` (`M = n m`, rods only). Elastic links: the pivot spring's
//!   force at every accepted step's end (`Summary::pivot_force_max`), so a
//!   pulse narrower than the output spacing is still seen. Rigid links: the
//!   DAE's pivot force at the output samples only: a rigid chain arrested
//!   at full extension takes an impulse, and its sampled peak depends on
//!   the sampling (it has no limit);
//! * the **impulse of the snap**: the momentum the support takes out of the
//!   chain over the window `[t_p - w, t_p + w]` around the peak's time `t_p`,
//!   `J = ∫ F_1 dt = P(t_p + w) - P(t_p - w) + (M + M_t) g (2 w) ŷ` (Newton's
//!   second law for the whole chain, `P = Σ m_i c_i' + M_t v_tip` its
//!   momentum, each model's own: [`momentum`]), read from the two samples
//!   that bound the window: exact whatever the pulse's width, for either
//!   model, any rod profile and a tip mass. In units of `M sqrt(g L)`; the
//!   weight's share `(M + M_t) g 2w` in the same units is given beside it.
//!
//! [`tension_profiles`] gives the tension at every joint at chosen times.

use chain_ode::{Model, Solve, StepView, Trajectory, Vec2, Watch};
use serde::Serialize;

use fc_csv::format::{exp, num};
use fc_scene::error::Error;
use fc_scene::scene::Scene;

/// What to run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Method and relative tolerance of the run (`atol = rtol / 100`).
    pub method: String,
    pub rtol: f64,
    /// Output spacing (time units): the rigid model's peak is sampled at
    /// it; the impulse window's ends are the samples nearest `t_p ± w`.
    pub output_dt: f64,
    /// Half-width `w` of the impulse window (time units).
    pub window: f64,
    /// End time of the run (time units), or the scene's own.
    pub t_end: Option<f64>,
}

impl Default for Options {
    /// DOPRI5 at `rtol = 1e-8`, samples every `1e-3`, `w = 0.2`.
    fn default() -> Self {
        Self {
            method: "dopri5".into(),
            rtol: 1e-8,
            output_dt: 1e-3,
            window: 0.2,
            t_end: None,
        }
    }
}

/// One run's snap.
#[derive(Clone, Debug, Serialize)]
pub struct Snap {
    pub scene: String,
    pub links: usize,
    /// `M = n m` (mass units).
    pub total_mass: f64,
    /// `EA` (force units) or `None` for rigid links.
    pub axial_stiffness: Option<f64>,
    pub axial_damping: f64,
    pub bending_stiffness: f64,
    /// Joint friction `r`.
    pub damping: f64,
    pub status: String,
    pub tip_speed_max: f64,
    pub t_tip_speed_max: f64,
    /// Peak support force over `M g`, and when.
    pub peak_force: f64,
    pub t_peak_force: f64,
    /// The largest support force over `M g` at any accepted step's end, and
    /// when ([`StepPeak`], a watch on the run): for elastic links the same
    /// as `peak_force`; for rigid links what the integrator's own steps
    /// see, which grows as they shrink around the arrest (no limit).
    pub peak_force_steps: f64,
    pub t_peak_force_steps: f64,
    /// `|J|` over `M sqrt(g L)`, the window's ends, and the weight's share.
    pub impulse: f64,
    pub window: (f64, f64),
    pub impulse_weight: f64,
    pub steps: u64,
    pub rhs_evals: u64,
    /// Wall time (seconds; not reproducible).
    pub wall_seconds: f64,
}

/// The chain's momentum relative to the pivot, `P = Σ m_i c_i' + M_t v_tip`,
/// at sample `k`: the model's own ([`chain_ode::StateView::momentum`]), so
/// that a tip mass and unequal rods count as the equations of motion count
/// them.
pub fn momentum(traj: &Trajectory, k: usize) -> Vec2 {
    traj.momentum(k)
}

/// The largest support force `|F_1|` (force units) at the start and at
/// every accepted step's end of a run, and when: a [`Watch`] on the run
/// ([`Solve::watch`]), asking the model's view
/// ([`StateView::support_force`](chain_ode::StateView::support_force)), so that
/// a pulse between two output samples is still seen.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepPeak {
    pub force: f64,
    pub t: f64,
}

impl StepPeak {
    fn see(&mut self, t: f64, f: Vec2) {
        let m = f[0].hypot(f[1]);
        if m > self.force {
            (self.force, self.t) = (m, t);
        }
    }
}

impl<M: Model> Watch<M> for StepPeak {
    fn start(&mut self, model: &M, t0: f64, y0: &[f64]) {
        self.see(t0, model.view().support_force(t0, y0));
    }

    fn step(&mut self, model: &M, step: &StepView<'_>) {
        self.see(step.t1, model.view().support_force(step.t1, step.y1));
    }
}

/// The sample of `traj` nearest `t`.
fn nearest(traj: &Trajectory, t: f64) -> usize {
    let k = traj.times.partition_point(|&s| s < t);
    if k == 0 {
        0
    } else if k >= traj.len() {
        traj.len() - 1
    } else if t - traj.times[k - 1] <= traj.times[k] - t {
        k - 1
    } else {
        k
    }
}

/// Runs `scene` as it is (its `n`, masses, `EA`, `EI`) with `opts` and
/// measures its snap.
pub fn measure(scene: &Scene, opts: &Options) -> Result<(Snap, Trajectory), Error> {
    if !(opts.window.is_finite() && opts.window > 0.0) {
        return Err(Error::field("window", "must be finite and > 0"));
    }
    let mut s = scene
        .with_value("run.method", toml::Value::String(opts.method.clone()))?
        .with_value("run.rtol", toml::Value::Float(opts.rtol))?
        .with_value("run.atol", toml::Value::Float(opts.rtol * 1e-2))?
        .with_value("run.output_dt", toml::Value::Float(opts.output_dt))?;
    if let Some(t) = opts.t_end {
        s = s.with_value("run.t_end", toml::Value::Float(t))?;
    }
    let prepared = s.prepare()?;
    prepared.require_corrected("the snap")?;
    let mut steps = StepPeak::default();
    let traj = Solve::new(
        &prepared.chain,
        &prepared.state,
        prepared.method,
        &prepared.options,
    )
    .watch(&mut steps)
    .run()?;
    let chain = traj.chain();
    let p = chain.params();
    let (weight, mass) = (chain.weight(), chain.total_mass());
    // The momentum balance's weight: the whole chain's, tip mass included
    // (`weight`, the peak force's unit, is the rods' alone).
    let carried = (mass + chain.tip_mass()) * chain.gravity();
    let momentum_unit = mass * (chain.gravity() * chain.length()).sqrt();
    // Elastic links: the peak at the steps' ends (the watch's, which the
    // study's figures hold; `Summary::pivot_force_max` also refines it
    // inside the steps since issue 49). The rigid chain's peak stays the
    // samples' (the module's doc): an arrest at full extension is an
    // impulse whose peak has no limit.
    let tracked = traj.chain().is_elastic().then_some((steps.force, steps.t));
    let (peak, t_peak) = match tracked {
        Some(pf) => pf,
        None => chain_ode::analysis::pivot_forces(&traj)
            .into_iter()
            .map(|(t, f)| (f[0].hypot(f[1]), t))
            .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a }),
    };
    let (mut impulse, mut window, mut impulse_weight) = (f64::NAN, (f64::NAN, f64::NAN), f64::NAN);
    if !traj.is_empty() {
        let (a, b) = (
            nearest(&traj, t_peak - opts.window),
            nearest(&traj, t_peak + opts.window),
        );
        let (ta, tb) = (traj.times[a], traj.times[b]);
        let (pa, pb) = (momentum(&traj, a), momentum(&traj, b));
        let j = [pb[0] - pa[0], pb[1] - pa[1] + carried * (tb - ta)];
        impulse = j[0].hypot(j[1]) / momentum_unit;
        window = (ta, tb);
        impulse_weight = carried * (tb - ta) / momentum_unit;
    }
    let snap = Snap {
        scene: scene.name().to_string(),
        links: chain.links(),
        total_mass: mass,
        axial_stiffness: p.axial_stiffness,
        axial_damping: p.axial_damping,
        bending_stiffness: p.bending_stiffness,
        damping: p.damping,
        status: traj.status.as_str().to_string(),
        tip_speed_max: traj.summary.tip_speed_max,
        t_tip_speed_max: traj.summary.t_tip_speed_max,
        peak_force: peak / weight,
        t_peak_force: t_peak,
        peak_force_steps: steps.force / weight,
        t_peak_force_steps: steps.t,
        impulse,
        window,
        impulse_weight,
        steps: traj.stats.steps,
        rhs_evals: traj.stats.rhs_evals,
        wall_seconds: traj.summary.wall_seconds,
    };
    Ok((snap, traj))
}

/// The tension at every joint (`k = 0` the pivot .. `n` the free tip, over
/// `M g`) at the samples nearest each of `times`: `(t, tensions)`.
pub fn tension_profiles(traj: &Trajectory, times: &[f64]) -> Vec<(f64, Vec<f64>)> {
    let weight = traj.chain().weight();
    times
        .iter()
        .filter(|_| !traj.is_empty())
        .map(|&t| {
            let k = nearest(traj, t);
            let f = traj.joint_forces(k);
            (traj.times[k], f.iter().map(|x| x[0] / weight).collect())
        })
        .collect()
}

/// The header of [`snap_row`].
pub const SNAP_HEADER: &str = "scene,variant,links,total_mass,axial_stiffness,axial_damping,\
                               bending_stiffness,damping,status,tip_speed_max,t_tip_speed_max,\
                               peak_force_mg,t_peak_force,impulse,window_from,window_to,\
                               impulse_weight,steps,rhs_evals,wall_seconds\n";

/// One CSV row of `s` (after [`SNAP_HEADER`]); `variant` names the case.
pub fn snap_row(variant: &str, s: &Snap) -> String {
    format!(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.3e}\n",
        s.scene,
        fc_csv::format::text(variant),
        s.links,
        num(s.total_mass),
        s.axial_stiffness.map_or(String::new(), exp),
        num(s.axial_damping),
        num(s.bending_stiffness),
        num(s.damping),
        s.status,
        num(s.tip_speed_max),
        num(s.t_tip_speed_max),
        num(s.peak_force),
        num(s.t_peak_force),
        num(s.impulse),
        num(s.window.0),
        num(s.window.1),
        num(s.impulse_weight),
        s.steps,
        s.rhs_evals,
        s.wall_seconds
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The small span with `extra` lines in `[chain]` (a tip mass, a
    /// profile).
    fn scene_with(ea: Option<f64>, extra: &str) -> Scene {
        let elastic = ea.map_or(String::new(), |ea| {
            format!("axial_stiffness = {ea}\naxial_damping = 0.5\n")
        });
        let elastic = format!("{elastic}{extra}");
        Scene::from_toml_str(&format!(
            r#"
name = "small-span"
[chain]
length = 6.0
links = 10
mass = 1.0
gravity = 1.0
damping = 0.0005
{elastic}
[start]
kind = "catenary"
p0 = [0.0, 0.0]
p1 = [3.0, 0.0]
[run]
t_end = 3.6
"#
        ))
        .unwrap()
    }

    /// The watch sees every accepted step: with RK4 sampled at its own
    /// step, every sample is a step end, so the watch's rigid peak is the
    /// sampled peak of the support force (computed apart, from the samples,
    /// by `analysis::pivot_forces`); a watch that skipped steps or read the
    /// wrong state misses it.
    #[test]
    fn the_step_peak_is_the_peak_over_every_step() {
        let dt = 1e-3;
        let scene = scene_with(None, "tip_mass = 0.5\n")
            .with_value("run.dt", toml::Value::Float(dt))
            .unwrap();
        let opts = Options {
            method: "rk4".into(),
            output_dt: dt,
            ..Options::default()
        };
        let (snap, traj) = measure(&scene, &opts).unwrap();
        assert_eq!(snap.status, "ok");
        let f = chain_ode::analysis::pivot_forces(&traj);
        let (sampled, t) = f
            .iter()
            .map(|p| (p.1[0].hypot(p.1[1]), p.0))
            .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        let w = traj.chain().weight();
        assert!(
            (snap.peak_force_steps - sampled / w).abs() < 1e-9 * snap.peak_force_steps,
            "{} vs {}",
            snap.peak_force_steps,
            sampled / w
        );
        assert!(
            (snap.t_peak_force_steps - t).abs() < 1e-9,
            "{} vs {t}",
            snap.t_peak_force_steps
        );
    }

    /// The impulse from the momentum balance is the time integral of the
    /// pivot force (trapezoid over fine samples), for both models: an
    /// independent formulation that a wrong momentum (a missing half rod, a
    /// wrong sign of the weight) fails. The elastic peak, tracked at every
    /// step, is at least every sampled force.
    #[test]
    fn the_impulse_is_the_integral_of_the_pivot_force() {
        // Equal rods, a tip mass, and a taper with a tip mass: a momentum
        // that drops the tip mass or reads equal rods fails the last two.
        let extras = ["", "tip_mass = 0.8\n", "taper = 4.0\ntip_mass = 0.3\n"];
        for (ea, extra) in [None, Some(3e3)]
            .into_iter()
            .flat_map(|ea| extras.iter().map(move |x| (ea, *x)))
        {
            let opts = Options {
                output_dt: 1e-4,
                ..Options::default()
            };
            let (snap, traj) = measure(&scene_with(ea, extra), &opts).unwrap();
            assert_eq!(snap.status, "ok", "{ea:?} {extra}");
            let f = chain_ode::analysis::pivot_forces(&traj);
            let (a, b) = (nearest(&traj, snap.window.0), nearest(&traj, snap.window.1));
            let mut j = [0.0, 0.0];
            for k in a..b {
                let dt = f[k + 1].0 - f[k].0;
                for (d, jd) in j.iter_mut().enumerate() {
                    *jd += 0.5 * dt * (f[k].1[d] + f[k + 1].1[d]);
                }
            }
            let unit = traj.chain().total_mass() * (traj.chain().length()).sqrt();
            let trapezoid = j[0].hypot(j[1]) / unit;
            assert!(
                (trapezoid / snap.impulse - 1.0).abs() < 2e-3,
                "{ea:?} {extra}: {trapezoid} vs {}",
                snap.impulse
            );
            let sampled = f.iter().map(|p| p.1[0].hypot(p.1[1])).fold(0.0, f64::max);
            assert!(sampled / traj.chain().weight() <= snap.peak_force * 1.001);
            // For elastic links the watch's peak is the summary's own
            // per-step peak.
            if ea.is_some() {
                assert_eq!(
                    (snap.peak_force_steps, snap.t_peak_force_steps),
                    (snap.peak_force, snap.t_peak_force),
                    "{extra}"
                );
            }
            assert!(snap.peak_force > 2.0 && snap.t_peak_force > 2.0, "{snap:?}");
        }
    }
}
