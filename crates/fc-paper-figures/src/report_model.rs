//! The tables of the report's own model as a control (`model.report =
//! true`, `docs/model.md`, "The report's model"): its Figs. 3, 4, 5 and 7
//! as snapshots of the report's model in its own clock ([`snapshots`],
//! beside the corrected fig03 .. fig07), and its Fig. 9 with what each
//! erratum changes ([`vmax`], [`errata`]). `cargo xtask figures` chooses
//! the scenes, writes these tables to `figures/data/` and draws them
//! (`super::plot::report_model`).

use std::fmt::Write as _;

use chain_ode::report::{finite_difference_tip_speeds, ReportModel};
use chain_ode::{solve, Method, ModelKind, Trajectory};

use fc_csv::format::{fixed, num};
use fc_scene::scene::Scene;
use fc_study::render;
use rayon::prelude::*;

/// The report's step over a span `t` of its clock: its code steps over
/// `linspace(0, t, 100 t)`, so `dt = t / (100 t - 1)` (0.01001 at t = 10),
/// and draws every 25th step ([`EVERY`]).
pub fn report_dt(t: f64) -> f64 {
    t / (100.0 * t - 1.0)
}

/// The report draws every 25th step.
pub const EVERY: f64 = 25.0;

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// The corrected scene as the report ran it (`--set` form):
/// `model.report = true`, RK4 at its step ([`report_dt`]) to `t_report`
/// in its clock, sampled every [`EVERY`] steps.
pub fn overrides(t_report: f64) -> Vec<String> {
    vec![
        "model.report=true".to_string(),
        "run.method=\"rk4\"".to_string(),
        format!("run.t_end={t_report}"),
        format!("run.dt={}", report_dt(t_report)),
        format!("run.output_dt={}", snapshot_dt(t_report)),
    ]
}

/// The time between the report's drawn snapshots over a span `t_report`
/// of its clock: [`EVERY`] of its steps.
pub fn snapshot_dt(t_report: f64) -> f64 {
    EVERY * report_dt(t_report)
}

/// The snapshots of a run of [`overrides`]: `point,t,x,y` as the corrected
/// snapshots (`t` in the report's clock, `every` apart), and a last row
/// `status,<t_reached>,,` with how the run ended.
pub fn snapshots(traj: &Trajectory, every: f64) -> String {
    let p0 = traj.anchor;
    let mut csv = format!("point,t,x,y\nP0,,{},{}\n", num(p0[0]), num(p0[1]));
    for (t, joints) in render::frames(traj, Some(every)) {
        for (i, p) in joints.iter().enumerate() {
            let _ = writeln!(csv, "{i},{},{},{}", num(t), fixed(p[0], 6), fixed(p[1], 6));
        }
    }
    let _ = writeln!(csv, "{},{},,", traj.status, num(traj.t_reached));
    csv
}

/// The tables of a report figure's scene `scene` (called `name`) run as
/// the report ran it ([`overrides`]) to `t_report`, as `(suffix, csv)`:
/// its [`snapshots`] (`""`) and, with `cases`, the pair of runs of its
/// stepper (`-cases`, [`super::report_model_tip::cases`]).
pub fn snapshot_tables(
    name: &str,
    scene: &Scene,
    t_report: f64,
    cases: bool,
) -> Result<Vec<(&'static str, String)>, String> {
    let traj = (scene.with_overrides(&overrides(t_report)))
        .and_then(|s| s.prepare())
        .and_then(|p| p.solve())
        .map_err(err)?;
    let mut tables = vec![("", snapshots(&traj, snapshot_dt(t_report)))];
    if cases {
        let pair = super::report_model_tip::cases(&[(name, scene)], t_report)?;
        tables.push(("-cases", pair));
    }
    Ok(tables)
}

/// The report's Fig. 9 as published, read off its page by eye (the
/// centre of each marker against the y axis's labelled ticks 1.8 .. 2.5,
/// about +-0.01), at [`report_spans`].
pub const READ_OFF_FIG9: [f64; 14] = [
    2.43, 2.435, 2.515, 2.48, 2.42, 2.37, 2.30, 2.165, 2.04, 1.94, 1.84, 1.775, 1.795, 1.975,
];

/// The largest angle between neighbouring rods (rad, in `[0, pi]`).
pub fn kink(phi: &[f64]) -> f64 {
    phi.windows(2)
        .map(|p| {
            let d = (p[1] - p[0]).rem_euclid(std::f64::consts::TAU);
            d.min(std::f64::consts::TAU - d)
        })
        .fold(0.0, f64::max)
}

/// The report's 14 spans: `linspace(0, 6, 20)[5..19]`.
pub fn report_spans() -> Vec<f64> {
    (5..19).map(|i| 6.0 * i as f64 / 19.0).collect()
}

/// Errata cases: each the report's model as coded with one switch changed,
/// then every switch corrected.
pub const CASES: &[(&str, ReportModel)] = &[
    ("as coded", ReportModel::AS_CODED),
    (
        "indices corrected (erratum 2)",
        ReportModel {
            indices: false,
            ..ReportModel::AS_CODED
        },
    ),
    (
        "clock corrected (erratum 3)",
        ReportModel {
            clock: false,
            ..ReportModel::AS_CODED
        },
    ),
    (
        "stepper corrected to RK4 (erratum 4)",
        ReportModel {
            stepper: false,
            ..ReportModel::AS_CODED
        },
    ),
    (
        "friction sign as printed (erratum 1)",
        ReportModel {
            printed_friction_sign: true,
            ..ReportModel::AS_CODED
        },
    ),
    ("every erratum corrected", ReportModel::CORRECTED),
];

/// The report's Fig. 9 in its model: `d,vmax_report,vmax_fd,vmax,t_vmax,
/// status,corrected,read_off` at the report's 14 spans ([`report_spans`],
/// set as `start.p1.0` on `base`), the report's model run as its code ran
/// it to `t_report` of its clock: `vmax_report` the exact maximum tip
/// speed in its clock, `vmax_fd` the largest of its own speeds (erratum 5:
/// [`finite_difference_tip_speeds`], what its Fig. 9 plots), `vmax` and
/// `t_vmax` the exact ones in our units (`/ sqrt(l/g)`, `* sqrt(l/g)`),
/// and `corrected`, the corrected model (DOPRI5, rtol 1e-8) to the same
/// physical time; `read_off`, the published Fig. 9 ([`READ_OFF_FIG9`]).
pub fn vmax(base: &Scene, t_report: f64) -> Result<String, String> {
    let spans: Vec<(f64, f64)> = report_spans().into_iter().zip(READ_OFF_FIG9).collect();
    // The spans in parallel, their rows in order.
    let rows = spans.par_iter().map(|&(d, read)| {
        let s = base
            .with_overrides(&[format!("start.p1.0={d}")])
            .map_err(err)?;
        let p = s.prepare().map_err(err)?;
        let unit = ReportModel::AS_CODED.time_unit(&p.chain);
        let mut o = p.options.clone();
        o.t_end = t_report;
        o.dt = report_dt(t_report);
        o.output_dt = Some(o.dt);
        let traj = solve(
            ModelKind::choose(&p.chain, Some(ReportModel::AS_CODED)),
            &p.state,
            Method::Rk4,
            &o,
        )
        .map_err(err)?;
        let angles: Vec<&[f64]> = traj.samples().map(|s| s.angles).collect();
        let fd = finite_difference_tip_speeds(&p.chain, &traj.times, &angles)
            .iter()
            .fold(0.0f64, |m, tv| m.max(tv[1]));
        let mut oc = p.options.clone();
        oc.t_end = t_report * unit;
        oc.rtol = 1e-8;
        oc.atol = 1e-10;
        oc.output_dt = None;
        let cor = chain_ode::solve(&p.chain, &p.state, Method::Dopri5, &oc).map_err(err)?;
        let sm = &traj.summary;
        Ok(format!(
            "{},{},{},{},{},{},{},{}\n",
            num(d),
            num(sm.tip_speed_max),
            num(fd),
            num(sm.tip_speed_max / unit),
            num(sm.t_tip_speed_max * unit),
            traj.status,
            num(cor.summary.tip_speed_max),
            num(read)
        ))
    });
    table(
        "d,vmax_report,vmax_fd,vmax,t_vmax,status,corrected,read_off\n",
        rows,
    )
}

/// `head` and the rows, in their order; the first error if any.
fn table(
    head: &str,
    rows: impl IndexedParallelIterator<Item = Result<String, String>>,
) -> Result<String, String> {
    let rows: Vec<String> = rows.collect::<Result<_, String>>()?;
    Ok(std::iter::once(head.to_string()).chain(rows).collect())
}

/// Fig. 9 with each erratum undone in turn: `d,case,vmax,t_vmax,status,
/// t_reached` at the report's 14 spans ([`report_spans`] on `base`), each
/// case of [`CASES`] run as [`errata`] runs it (to `t_report` of the
/// report's clock, at its step, in physical time when the clock is
/// corrected), the maximum tip speed and its time in our units.
pub fn errata_spans(base: &Scene, t_report: f64) -> Result<String, String> {
    let spans = report_spans();
    let rows = spans.par_iter().map(|&d| {
        let s = base
            .with_overrides(&[format!("start.p1.0={d}")])
            .map_err(err)?;
        let p = s.prepare().map_err(err)?;
        let coded = ReportModel::AS_CODED.time_unit(&p.chain);
        let mut csv = String::new();
        for (case, model) in CASES {
            let unit = model.time_unit(&p.chain);
            let mut o = p.options.clone();
            o.t_end = t_report * coded / unit;
            o.dt = report_dt(t_report) * coded / unit;
            o.output_dt = None;
            let traj = solve(
                ModelKind::choose(&p.chain, Some(*model)),
                &p.state,
                Method::Rk4,
                &o,
            )
            .map_err(err)?;
            let _ = writeln!(
                csv,
                "{},{case},{},{},{},{}",
                num(d),
                num(traj.summary.tip_speed_max / unit),
                num(traj.summary.t_tip_speed_max * unit),
                traj.status,
                num(traj.t_reached * unit),
            );
        }
        Ok(csv)
    });
    table("d,case,vmax,t_vmax,status,t_reached\n", rows)
}

/// What each erratum changes: `scene,case,vmax,t_vmax,status,t_reached,
/// balance,kink`, each `(name, scene, t_report)` of `scenes` in each case
/// of [`CASES`] at the report's step and span (`dt = t / (100 t - 1)` and
/// `t = t_report` of the report's clock: 12 (Figs. 7, 9) or 10 (Fig. 4),
/// kept in physical time when the clock is corrected), in our units;
/// `balance`, the largest `|E + W - E(0)|` of the model's own energy over
/// its energy scale; `kink`, the largest angle between neighbouring rods
/// at the end (rad, [`kink`]): how crumpled the chain ends.
pub fn errata(scenes: &[(&str, &Scene, f64)]) -> Result<String, String> {
    let runs: Vec<_> = (scenes.iter())
        .flat_map(|s| CASES.iter().map(move |c| (s, c)))
        .collect();
    let rows = runs
        .par_iter()
        .map(|&(&(name, scene, t_report), (case, model))| {
            let p = scene.prepare().map_err(err)?;
            let coded = ReportModel::AS_CODED.time_unit(&p.chain);
            let unit = model.time_unit(&p.chain);
            let mut o = p.options.clone();
            o.t_end = t_report * coded / unit;
            o.dt = report_dt(t_report) * coded / unit;
            o.output_dt = None;
            let traj = solve(
                ModelKind::choose(&p.chain, Some(*model)),
                &p.state,
                Method::Rk4,
                &o,
            )
            .map_err(err)?;
            Ok(format!(
                "{name},{case},{},{},{},{},{},{}\n",
                num(traj.summary.tip_speed_max / unit),
                num(traj.summary.t_tip_speed_max * unit),
                traj.status,
                num(traj.t_reached * unit),
                num(traj.summary.energy_balance_error / model.energy_scale(&p.chain)),
                num(kink(&traj.final_state[..p.chain.links()]))
            ))
        });
    table(
        "scene,case,vmax,t_vmax,status,t_reached,balance,kink\n",
        rows,
    )
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    use super::*;
    use crate::report::linspace;

    #[test]
    fn the_step_is_that_of_the_reports_linspace() {
        for t in [10.0, 12.0, 40.0] {
            let grid = linspace(0.0, t, (100.0 * t) as usize);
            let dt = report_dt(t);
            for w in grid.windows(2) {
                assert!((w[1] - w[0] - dt).abs() < 1e-12 * t, "t = {t}");
            }
            assert!((snapshot_dt(t) - 25.0 * (grid[1] - grid[0])).abs() < 1e-12 * t);
        }
    }

    #[test]
    fn the_spans_are_the_reports_fourteen() {
        let spans = report_spans();
        assert_eq!(spans, linspace(0.0, 6.0, 20)[5..19].to_vec());
        assert_eq!(spans.len(), READ_OFF_FIG9.len());
    }

    #[test]
    fn the_kink_is_the_largest_bend_whatever_the_turns() {
        // A straight chain, also with whole turns between rods.
        assert_eq!(kink(&[0.3, 0.3 + TAU, 0.3 - 2.0 * TAU]), 0.0);
        // A right angle, and a bend of 0.2 across the cut at +-pi.
        let k = kink(&[0.0, FRAC_PI_2, PI - 0.1, -PI + 0.1]);
        assert!((k - FRAC_PI_2).abs() < 1e-12, "{k}");
        let k = kink(&[PI - 0.1, -PI + 0.1]);
        assert!((k - 0.2).abs() < 1e-12, "{k}");
        // A bend the other way is as large.
        let k = kink(&[0.5, 0.3, 0.3]);
        assert!((k - 0.2).abs() < 1e-12, "{k}");
        // Folded back on itself: pi, never more.
        assert!((kink(&[0.0, PI, 0.0]) - PI).abs() < 1e-12);
    }
}
