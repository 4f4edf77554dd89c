//! From finished trajectories to the figures crate's plain data: chain
//! frames, tip speed and tip velocity series. Nothing here runs a simulation.

use chain_ode::{Trajectory, Vec2};
use figures::ChainSnapshots;

/// Joint positions of every sample whose time is a multiple of `spacing`
/// (within 1e-9 of it), plus the last sample: the report's snapshot curves.
/// With `spacing = None`, every sample.
pub fn frames(traj: &Trajectory, spacing: Option<f64>) -> Vec<(f64, Vec<[f64; 2]>)> {
    traj.samples()
        .enumerate()
        .filter(|(k, s)| {
            *k + 1 == traj.len()
                || spacing.is_none_or(|dt| {
                    let q = s.t / dt;
                    (q - q.round()).abs() < 1e-6
                })
        })
        .map(|(k, s)| (s.t, traj.joints(k)))
        .collect()
}

/// The snapshot figure of a trajectory: frames `spacing` apart, P0 and the
/// release point `p1` marked.
pub fn snapshots<'a>(
    title: &'a str,
    traj: &Trajectory,
    spacing: Option<f64>,
    p1: Option<Vec2>,
) -> ChainSnapshots<'a> {
    let mut fig = ChainSnapshots::new(title, frames(traj, spacing), traj.anchor);
    fig.p1 = p1;
    fig
}

/// `(t, |v_tip|)` at every sample.
pub fn tip_speed(traj: &Trajectory) -> Vec<(f64, f64)> {
    traj.samples()
        .enumerate()
        .map(|(k, s)| {
            let v = traj.tip_velocity(k);
            (s.t, v[0].hypot(v[1]))
        })
        .collect()
}

/// `(v_x, v_y)` of the tip at every sample.
pub fn tip_velocity_path(traj: &Trajectory) -> Vec<(f64, f64)> {
    (0..traj.len())
        .map(|k| {
            let v = traj.tip_velocity(k);
            (v[0], v[1])
        })
        .collect()
}
