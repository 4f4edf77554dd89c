//! The report's U onto a floor (`scenes/span-d3-floor.toml`): the chain at
//! a few times with the floor's line, and the released end's speed and the
//! floor's force against time beside the same U without a floor
//! (`scenes/span-d3.toml`). The figure `floor-span-d3` draws
//! [`snapshots_csv`] and [`series_csv`].

use std::fmt::Write as _;

use chain_ode::{Model as _, Trajectory};
use fc_csv::format::num;

/// The chain's joints at the samples nearest each of `times` (the
/// trajectory's own clock), one row per joint: `t,joint,x,y`; then the
/// floor's line as two rows `t = -1` at `x` from the chain's leftmost to its
/// rightmost joint over all those times (`joint` 0 and 1).
pub fn snapshots_csv(traj: &Trajectory, times: &[f64]) -> Result<String, String> {
    let mut s = String::from("t,joint,x,y\n");
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for &t in times {
        let k = (0..traj.len())
            .min_by(|&a, &b| {
                (traj.times[a] - t)
                    .abs()
                    .total_cmp(&(traj.times[b] - t).abs())
            })
            .ok_or("the run has no samples")?;
        for (j, p) in traj.joints(k).iter().enumerate() {
            lo = lo.min(p[0]);
            hi = hi.max(p[0]);
            let _ = writeln!(s, "{},{j},{},{}", num(traj.times[k]), num(p[0]), num(p[1]));
        }
    }
    let (h, angle) = traj
        .model
        .view()
        .floor_line()
        .ok_or("the scene has no floor")?;
    for (j, x) in [lo, hi].into_iter().enumerate() {
        let _ = writeln!(s, "-1,{j},{},{}", num(x), num(h + x * angle.tan()));
    }
    Ok(s)
}

/// Every sample of each `(label, run)`: `scene,t,tip_speed,floor_y`, the
/// released end's speed and the floor's total upward force (empty for a
/// run without a floor).
pub fn series_csv(runs: &[(&str, &Trajectory)]) -> String {
    let mut s = String::from("scene,t,tip_speed,floor_y\n");
    for (label, traj) in runs {
        for k in 0..traj.len() {
            let v = traj.tip_velocity(k);
            let floor = traj.floor_force(k).map_or(String::new(), |f| num(f[1]));
            let _ = writeln!(
                s,
                "{label},{},{},{floor}",
                num(traj.times[k]),
                num(v[0].hypot(v[1]))
            );
        }
    }
    s
}
