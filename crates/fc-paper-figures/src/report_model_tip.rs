//! The report's Figs. 8 and 11 in its own model (`model.report = true`,
//! `docs/model.md`, "The report's model"): the tip speed against time and
//! the tip velocity `v_y` against `v_x` as its code measured them (erratum
//! 5: the finite difference, between steps, of a point that leaves rod 1
//! out and ends at the last rod's midpoint), in its clock, beside the
//! corrected fig08 and fig11; and, per scene, the pair of runs that says
//! what its stepper (erratum 4) did to those curves: as coded, and with
//! RK4 for its stepper on the same equations. `cargo xtask figures`
//! chooses the scenes; `super::plot::report_model::tip` draws the tables.

use std::fmt::Write as _;

use chain_ode::report::{finite_difference_tip_velocities, ReportModel};
use chain_ode::{solve, Method, ModelKind, Trajectory};

use super::report_model::report_dt;
use fc_csv::format::{fixed, num};
use fc_scene::scene::Scene;

/// The two cases of each scene: the report's model as coded, and the same
/// with RK4 for its stepper.
pub const CASES: [(&str, ReportModel); 2] = [
    ("as coded", ReportModel::AS_CODED),
    (
        "stepper corrected to RK4 (erratum 4)",
        ReportModel {
            stepper: false,
            ..ReportModel::AS_CODED
        },
    ),
];

/// The largest of the report's own tip speeds `[t, v_x, v_y]` (as
/// [`finite_difference_tip_velocities`] gives them) and its time; `(0, 0)`
/// for fewer than two samples.
fn largest(v: &[[f64; 3]]) -> (f64, f64) {
    v.iter()
        .map(|&[t, vx, vy]| (vx.hypot(vy), t))
        .fold((0.0, 0.0), |m, x| if x.0 > m.0 { x } else { m })
}

/// The report's tip velocities of a run sampled at every step.
fn velocities(traj: &Trajectory) -> Vec<[f64; 3]> {
    let angles: Vec<&[f64]> = traj.samples().map(|s| s.angles).collect();
    finite_difference_tip_velocities(traj.chain(), &traj.times, &angles)
}

/// The runs of `scene` in each case of [`CASES`], in the report's model with
/// `rk4` at the report's step over `t_report` of its clock
/// ([`report_dt`]), sampled at every step.
fn runs(scene: &Scene, t_report: f64) -> Result<Vec<Trajectory>, String> {
    let p = scene.prepare().map_err(|e| e.to_string())?;
    let mut o = p.options.clone();
    o.t_end = t_report;
    o.dt = report_dt(t_report);
    o.output_dt = Some(o.dt);
    CASES
        .iter()
        .map(|(_, model)| {
            solve(
                ModelKind::choose(&p.chain, Some(*model)),
                &p.state,
                Method::Rk4,
                &o,
            )
            .map_err(|e| format!("{}: {e}", scene.name()))
        })
        .collect()
}

/// The header of [`cases`]' table.
const CASES_HEADER: &str = "scene,case,status,t_reached,vmax_fd,t_vmax_fd,vmax\n";

/// The rows of [`cases`]' table for the runs of one scene.
fn case_rows(csv: &mut String, name: &str, runs: &[Trajectory], v: &[Vec<[f64; 3]>]) {
    for ((case, _), (traj, v)) in CASES.iter().zip(runs.iter().zip(v)) {
        let (vmax, t_vmax) = largest(v);
        let _ = writeln!(
            csv,
            "{name},{case},{},{},{},{},{}",
            traj.status,
            num(traj.t_reached),
            num(vmax),
            num(t_vmax),
            num(traj.summary.tip_speed_max)
        );
    }
}

/// The pair of runs of each of `scenes` (`(name, scene)`), as coded and
/// with RK4 for its stepper ([`CASES`]), over `t_report` of its clock at
/// its step: `scene,case,status,t_reached,vmax_fd,t_vmax_fd,vmax`, how each
/// ended, the largest of its own speeds and when, and the exact tip's
/// largest speed (all in its clock; a diverged run's up to where it
/// stopped, its last differences included).
pub fn cases(scenes: &[(&str, &Scene)], t_report: f64) -> Result<String, String> {
    Ok(tables(scenes, t_report)?.1)
}

/// [`cases`], and the curves of the runs as coded:
/// `scene,t,speed,v_x,v_y`, the report's own speed and velocity at every
/// step (in its clock, 6 decimals), up to where each stopped.
pub fn tables(scenes: &[(&str, &Scene)], t_report: f64) -> Result<(String, String), String> {
    let mut curves = String::from("scene,t,speed,v_x,v_y\n");
    let mut table = String::from(CASES_HEADER);
    for &(name, scene) in scenes {
        let runs = runs(scene, t_report)?;
        let v: Vec<Vec<[f64; 3]>> = runs.iter().map(velocities).collect();
        for &[t, vx, vy] in &v[0] {
            let s = vx.hypot(vy);
            let (t, s, vx, vy) = (fixed(t, 5), fixed(s, 6), fixed(vx, 6), fixed(vy, 6));
            let _ = writeln!(curves, "{name},{t},{s},{vx},{vy}");
        }
        case_rows(&mut table, name, &runs, &v);
    }
    Ok((curves, table))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_largest_speed_is_the_largest_norm_and_its_time() {
        let v = [[0.1, 3.0, 4.0], [0.2, -6.0, 0.0], [0.3, 0.0, 5.5]];
        assert_eq!(largest(&v), (6.0, 0.2));
        assert_eq!(largest(&[]), (0.0, 0.0));
    }

    #[test]
    fn the_cases_differ_in_the_stepper_only() {
        let (a, b) = (CASES[0].1, CASES[1].1);
        assert_eq!(a, ReportModel::AS_CODED);
        assert!(a.stepper && !b.stepper);
        assert_eq!(ReportModel { stepper: true, ..b }, a);
    }
}
