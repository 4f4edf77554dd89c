//! Cayley's scale as single runs (issue 50): the chain of
//! `scenes/cayley-scale.toml` at `n` rods (its total mass and length
//! kept, its rods zigzagging by the scene's tilt), on either floor law,
//! read over the windows `t = 0.3 .. 1.2` (`chain_ode::analysis::scale_reading`):
//! the mean reading, its scatter over the windows, and the run's wall
//! time. The constraint floor's runs are reproducible (the contact is
//! exact, there is no contact time to resolve); the penalty floor's are
//! one sample of the landing sequence each (`docs/model.md`).

use std::fmt::Write as _;

use chain_ode::analysis::{scale_reading, scale_windows, ScaleReading, SCALE_HALF_WINDOW};
use chain_ode::{Method, Trajectory};
use fc_csv::format::{exp, num};
use fc_scene::scene::Scene;

/// The runs end here (units of `sqrt(L / g)`): the last window's edge.
pub const T_END: f64 = 1.25;

/// The samples' spacing: the windows' half width, so that every edge is
/// a sample.
pub const SAMPLE_DT: f64 = SCALE_HALF_WINDOW;

/// One run: the rods, the floor's law and how it is run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Single {
    pub links: usize,
    /// `floor.law`: `"constraint"` or `"penalty"` (the scene's stiffness
    /// and damping).
    pub law: &'static str,
    pub method: Method,
    /// `run.dt` for a fixed-step method, `run.rtol` (`atol = rtol / 100`)
    /// for an adaptive one.
    pub accuracy: f64,
}

/// One run's result.
#[derive(Clone, Debug, PartialEq)]
pub struct Read {
    pub single: Single,
    pub reading: ScaleReading,
    /// `sqrt(mean (reading_j − 1)²)` over the windows: the reading's error
    /// against Cayley's, its bias and scatter together.
    pub error: f64,
    pub steps: u64,
    pub wall_seconds: f64,
    pub status: String,
}

/// `base` at `single`'s rods (the total mass kept), its rods at `∓tilt`
/// from the vertical as the scene's first two rods give it, on its law,
/// sampled at every window edge to [`T_END`].
pub fn scene(base: &Scene, single: &Single) -> Result<Scene, String> {
    let p = base.chain_params();
    let total = p.mass * p.links as f64;
    let tilt = match base.start() {
        chain_ode::Start::Angles { angles, .. } => angles
            .first()
            .map_or(0.0, |a0| a0 + std::f64::consts::FRAC_PI_2),
        _ => 0.0,
    };
    let angles = (0..single.links)
        .map(|i| {
            let zig = if i % 2 == 0 { tilt } else { -tilt };
            toml::Value::Float(-std::f64::consts::FRAC_PI_2 + zig)
        })
        .collect();
    let mut sets: Vec<(&str, toml::Value)> = vec![
        ("chain.links", toml::Value::Integer(single.links as i64)),
        (
            "chain.mass",
            toml::Value::Float(total / single.links as f64),
        ),
        ("floor.law", toml::Value::String(single.law.to_string())),
        ("start.angles", toml::Value::Array(angles)),
        ("run.method", toml::Value::String(single.method.to_string())),
        ("run.t_end", toml::Value::Float(T_END)),
        ("run.output_dt", toml::Value::Float(SAMPLE_DT)),
    ];
    if single.method.adaptive() {
        sets.push(("run.rtol", toml::Value::Float(single.accuracy)));
        sets.push(("run.atol", toml::Value::Float(single.accuracy * 1e-2)));
    } else {
        sets.push(("run.dt", toml::Value::Float(single.accuracy)));
    }
    let mut scene = base.clone();
    for (key, value) in sets {
        scene = scene.with_value(key, value).map_err(|e| e.to_string())?;
    }
    Ok(scene)
}

/// Runs `single` from `base` and reads its scale.
pub fn run(base: &Scene, single: &Single) -> Result<(Trajectory, Read), String> {
    let traj = scene(base, single)?
        .prepare()
        .map_err(|e| e.to_string())?
        .solve()
        .map_err(|e| e.to_string())?;
    let reading = scale_reading(&traj, &scale_windows(), SCALE_HALF_WINDOW)?;
    let error = (reading
        .windows
        .iter()
        .map(|w| (w.1 - 1.0).powi(2))
        .sum::<f64>()
        / reading.windows.len() as f64)
        .sqrt();
    let read = Read {
        single: *single,
        error,
        steps: traj.stats.steps,
        wall_seconds: traj.summary.wall_seconds,
        status: traj.status.to_string(),
        reading,
    };
    Ok((traj, read))
}

/// One row per run: its case, reading, scatter, error and steps (no wall
/// time: a figure's data holds none).
pub fn readings_csv(reads: &[Read]) -> String {
    let mut s = String::from("links,law,method,accuracy,status,reading,scatter,error,steps\n");
    for r in reads {
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{}",
            r.single.links,
            r.single.law,
            r.single.method,
            exp(r.single.accuracy),
            r.status,
            num(r.reading.mean),
            num(r.reading.scatter),
            num(r.error),
            r.steps
        );
    }
    s
}

/// The windows' force in units of the weight `M g` at the window centre
/// `c` (units of `sqrt(L / g)`) of half width `d`, for a reading `r`:
/// `r` times the ideal's window mean, `3 mu g (g/2)(t² + d²/3)` over
/// `M g`, that is `1.5 (c² + d²/3)`.
pub fn ideal_over_weight(c: f64) -> f64 {
    let d = SCALE_HALF_WINDOW;
    1.5 * (c * c + d * d / 3.0)
}

/// One row per run and window: the run's case, the window's centre `t`
/// (units of `sqrt(L / g)`), its reading (the floor's force averaged over
/// the window over the ideal's), that force over the weight `M g`, and the
/// ideal's `3 mu g x` averaged over the window over `M g`.
pub fn windows_csv(reads: &[Read]) -> String {
    let mut s =
        String::from("links,law,method,accuracy,t,reading,force_over_weight,ideal_over_weight\n");
    for r in reads {
        for &(c, reading) in &r.reading.windows {
            let ideal = ideal_over_weight(c);
            let _ = writeln!(
                s,
                "{},{},{},{},{},{},{},{}",
                r.single.links,
                r.single.law,
                r.single.method,
                exp(r.single.accuracy),
                num(c),
                num(reading),
                num(reading * ideal),
                num(ideal)
            );
        }
    }
    s
}
