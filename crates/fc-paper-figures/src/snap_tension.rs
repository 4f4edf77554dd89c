//! The tables of the snap's tension wave (`snap-tension`, drawn by
//! `super::plot::elastic::snap_tension`) from one measured run of
//! [`fc_study::snap::measure`]: the tension along the chain at six times, the
//! support force around the snap, and the run's peak and times.

use std::fmt::Write as _;

use chain_ode::Trajectory;

use fc_csv::format::{fixed, num};
use fc_study::snap::{tension_profiles, Snap};

/// The times of the profiles: the tip's maximum speed `t_v` (the tip is
/// arrested), four equal steps from it to the peak of the support force
/// `t_p`, and `t_p + 0.05`.
pub fn times(r: &Snap) -> Vec<f64> {
    let (tv, tp) = (r.t_tip_speed_max, r.t_peak_force);
    let mut times: Vec<f64> = (0..5).map(|k| tv + (tp - tv) * k as f64 / 4.0).collect();
    times.push(tp + 0.05);
    times
}

/// The three tables of the run `traj` of `links` rods measured as `r` with
/// `EA = axial_stiffness` (force units): `t,joint,s_over_L,tension_mg` at
/// [`times`] (`s / L = joint / n`, tension over `M g`);
/// `t,pivot_force_mg`, the support force over `M g` from `t_v - 0.4` to
/// `t_p + 0.3`; and the summary, `links,axial_stiffness,tip_speed_max,
/// t_tip_speed_max,peak_force_mg,t_peak_force,impulse`.
pub fn tables(
    r: &Snap,
    traj: &Trajectory,
    links: usize,
    axial_stiffness: f64,
) -> (String, String, String) {
    let (tv, tp) = (r.t_tip_speed_max, r.t_peak_force);
    let mut csv = String::from("t,joint,s_over_L,tension_mg\n");
    for (t, tension) in tension_profiles(traj, &times(r)) {
        for (k, x) in tension.iter().enumerate() {
            let _ = writeln!(
                csv,
                "{},{k},{},{}",
                num(t),
                num(k as f64 / links as f64),
                fixed(*x, 5)
            );
        }
    }
    let weight = traj.chain().weight();
    let mut force = String::from("t,pivot_force_mg\n");
    for (t, f) in chain_ode::analysis::pivot_forces(traj) {
        if (tv - 0.4..=tp + 0.3).contains(&t) {
            let _ = writeln!(
                force,
                "{},{}",
                fixed(t, 4),
                fixed(f[0].hypot(f[1]) / weight, 5)
            );
        }
    }
    let summary = format!(
        "links,axial_stiffness,tip_speed_max,t_tip_speed_max,peak_force_mg,t_peak_force,\
         impulse\n{links},{axial_stiffness:e},{},{},{},{},{}\n",
        num(r.tip_speed_max),
        num(tv),
        num(r.peak_force),
        num(tp),
        num(r.impulse)
    );
    (csv, force, summary)
}
