//! The report's own model as a control (`model.report = true`,
//! `docs/model.md`, "The report's model"): its Figs. 3, 4, 5 and 7 as
//! snapshots of the report's model in its own clock ([`ReportSnapshots`],
//! beside the corrected fig03 .. fig07), and its Fig. 9 with what each
//! erratum changes ([`ReportVmax`]).

use std::fmt::Write as _;

use chain_ode::report::{finite_difference_tip_speeds, ReportModel};
use chain_ode::{solve_report, Method, Trajectory};
use falling_chain::render;
use figures::{ChainSnapshots, LinePlot, Series, Style};

use crate::ctx::Ctx;
use crate::data::{fixed, num};
use crate::registry::{Figure, Make};

/// The report's step over a span `t` of its clock: its code steps over
/// `linspace(0, t, 100 t)`, so `dt = t / (100 t - 1)` (0.01001 at t = 10),
/// and draws every 25th step.
fn report_dt(t: f64) -> f64 {
    t / (100.0 * t - 1.0)
}
const EVERY: f64 = 25.0;

fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// The corrected scene `scene` as the report ran it: `model.report = true`,
/// its step ([`report_dt`]) to `t_report` in its clock, sampled every
/// `output_dt`.
fn report_run(ctx: &Ctx, scene: &str, t_report: f64, output_dt: f64) -> Result<Trajectory, String> {
    let run = ctx.run(scene)?;
    let s = run
        .scene
        .with_overrides(&[
            "model.report=true".to_string(),
            "run.method=\"rk4\"".to_string(),
            format!("run.t_end={t_report}"),
            format!("run.dt={}", report_dt(t_report)),
            format!("run.output_dt={output_dt}"),
        ])
        .map_err(err)?;
    s.prepare().map_err(err)?.solve().map_err(err)
}

/// Snapshots of a report scene run in the report's model.
pub struct ReportSnapshots {
    pub title: &'static str,
    /// The corrected scene (fig03 .. fig07's).
    pub scene: &'static str,
    /// The report figure's time span, in its clock.
    pub t_report: f64,
}

impl Make for ReportSnapshots {
    fn scenes(&self) -> Vec<&'static str> {
        vec![self.scene]
    }

    /// `<id>.csv`: `point,t,x,y` as the corrected snapshots (`t` in the
    /// report's clock), and a last row `status,<t_reached>,,` with how the
    /// run ended.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let every = EVERY * report_dt(self.t_report);
        let traj = report_run(ctx, self.scene, self.t_report, every)?;
        let p0 = traj.anchor;
        let mut csv = format!("point,t,x,y\nP0,,{},{}\n", num(p0[0]), num(p0[1]));
        for (t, joints) in render::frames(&traj, Some(every)) {
            for (i, p) in joints.iter().enumerate() {
                writeln!(csv, "{i},{},{},{}", num(t), fixed(p[0], 6), fixed(p[1], 6))
                    .map_err(err)?;
            }
        }
        writeln!(csv, "{},{},,", traj.status, num(traj.t_reached)).map_err(err)?;
        Ok(vec![ctx.write(&format!("{}.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let (point, time, x, y) = (t.strs("point")?, t.strs("t")?, t.strs("x")?, t.strs("y")?);
        let parse = |s: &str| s.parse::<f64>().map_err(err);
        let mut p0 = [0.0, 0.0];
        let mut status = String::new();
        let mut frames: Vec<(f64, Vec<[f64; 2]>)> = vec![];
        for k in 0..t.len() {
            match point[k] {
                "P0" => p0 = [parse(x[k])?, parse(y[k])?],
                "0" => frames.push((parse(time[k])?, vec![[parse(x[k])?, parse(y[k])?]])),
                p if p.parse::<usize>().is_ok() => frames
                    .last_mut()
                    .ok_or_else(|| format!("{}: a joint before joint 0", t.name))?
                    .1
                    .push([parse(x[k])?, parse(y[k])?]),
                s => status = format!("{s} at t = {}", time[k]),
            }
        }
        let title = format!("{} ({status})", self.title);
        let f = ChainSnapshots::new(&title, frames, p0);
        out(ctx, fig, figures::chain_snapshots(&f, &ctx.stem(fig.id)))
    }
}

fn out(
    ctx: &Ctx,
    fig: &Figure,
    o: Result<figures::Output, figures::FigureError>,
) -> Result<Vec<String>, String> {
    o.map(|o| ctx.drawn(&o))
        .map_err(|e| format!("{}: {e}", fig.id))
}

/// The report's Fig. 9 in its model, and a pair of runs per erratum.
pub struct ReportVmax {
    pub title: &'static str,
    /// The corrected scene of the spans (span-d3: n = 50, r = 0.0005).
    pub scene: &'static str,
    /// The report figure's time span, in its clock (12).
    pub t_report: f64,
}

/// The report's Fig. 9 as published, read off its page by eye (the
/// centre of each marker against the y axis's labelled ticks 1.8 .. 2.5,
/// about +-0.01), at [`report_spans`].
const READ_OFF_FIG9: [f64; 14] = [
    2.43, 2.435, 2.515, 2.48, 2.42, 2.37, 2.30, 2.165, 2.04, 1.94, 1.84, 1.775, 1.795, 1.975,
];

/// The largest angle between neighbouring rods (rad, in `[0, pi]`).
fn kink(phi: &[f64]) -> f64 {
    phi.windows(2)
        .map(|p| {
            let d = (p[1] - p[0]).rem_euclid(std::f64::consts::TAU);
            d.min(std::f64::consts::TAU - d)
        })
        .fold(0.0, f64::max)
}

/// The report's 14 spans: `linspace(0, 6, 20)[5..19]`.
fn report_spans() -> Vec<f64> {
    (5..19).map(|i| 6.0 * i as f64 / 19.0).collect()
}

/// Errata cases: each the report's model as coded with one switch changed,
/// then every switch corrected.
const CASES: &[(&str, ReportModel)] = &[
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

impl Make for ReportVmax {
    fn scenes(&self) -> Vec<&'static str> {
        vec![self.scene, "horizontal-damped", "horizontal-undamped"]
    }

    /// `<id>.csv`: `d,vmax_report,vmax_fd,vmax,t_vmax,status` at the
    /// report's 14 spans, the report's model run as its code ran it:
    /// `vmax_report` the exact maximum tip speed in its clock,
    /// `vmax_fd` the largest of its own speeds (erratum 5:
    /// [`finite_difference_tip_speeds`], what its Fig. 9 plots),
    /// `vmax` and `t_vmax` the exact ones in our units (`/ sqrt(l/g)`,
    /// `* sqrt(l/g)`), and `corrected`, the corrected model (DOPRI5,
    /// rtol 1e-8) to the same physical time; `read_off`, the published
    /// Fig. 9 ([`READ_OFF_FIG9`]).
    ///
    /// `<id>-errata.csv`: `scene,case,vmax,t_vmax,status,t_reached,balance,kink`:
    /// the scene in
    /// each case of [`CASES`] at the report's step and span (`dt = t / (100 t - 1)`
    /// and `t = 12` (Figs. 7, 9) or 10 (Fig. 4) of the report's clock,
    /// kept in physical time when the clock is corrected), in our units;
    /// `balance`, the largest `|E + W - E(0)|` of the model's own energy
    /// over its energy scale; `kink`, the largest angle between neighbouring
    /// rods at the end (rad): how crumpled the chain ends.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let base = ctx.run(self.scene)?.scene.clone();
        let mut csv = String::from("d,vmax_report,vmax_fd,vmax,t_vmax,status,corrected,read_off\n");
        for (d, read) in report_spans().into_iter().zip(READ_OFF_FIG9) {
            let s = base
                .with_overrides(&[format!("start.p1.0={d}")])
                .map_err(err)?;
            let p = s.prepare().map_err(err)?;
            let unit = ReportModel::AS_CODED.time_unit(&p.chain);
            let mut o = p.options.clone();
            o.t_end = self.t_report;
            o.dt = report_dt(self.t_report);
            o.output_dt = Some(o.dt);
            let traj = solve_report(&p.chain, &p.state, ReportModel::AS_CODED, Method::Rk4, &o)
                .map_err(err)?;
            let angles: Vec<&[f64]> = traj.samples().map(|s| s.angles).collect();
            let fd = finite_difference_tip_speeds(&p.chain, &traj.times, &angles)
                .iter()
                .fold(0.0f64, |m, tv| m.max(tv[1]));
            let mut oc = p.options.clone();
            oc.t_end = self.t_report * unit;
            oc.rtol = 1e-8;
            oc.atol = 1e-10;
            oc.output_dt = None;
            let cor = chain_ode::solve(&p.chain, &p.state, Method::Dopri5, &oc).map_err(err)?;
            let sm = &traj.summary;
            writeln!(
                csv,
                "{},{},{},{},{},{},{},{}",
                num(d),
                num(sm.tip_speed_max),
                num(fd),
                num(sm.tip_speed_max / unit),
                num(sm.t_tip_speed_max * unit),
                traj.status,
                num(cor.summary.tip_speed_max),
                num(read)
            )
            .map_err(err)?;
        }
        let mut errata = String::from("scene,case,vmax,t_vmax,status,t_reached,balance,kink\n");
        for (scene, t_report) in [
            (self.scene, self.t_report),
            ("horizontal-damped", 10.0),
            ("horizontal-undamped", 10.0),
        ] {
            let p = ctx.run(scene)?.scene.prepare().map_err(err)?;
            let coded = ReportModel::AS_CODED.time_unit(&p.chain);
            for (case, model) in CASES {
                let unit = model.time_unit(&p.chain);
                let mut o = p.options.clone();
                o.t_end = t_report * coded / unit;
                o.dt = report_dt(t_report) * coded / unit;
                o.output_dt = None;
                let traj =
                    solve_report(&p.chain, &p.state, *model, Method::Rk4, &o).map_err(err)?;
                writeln!(
                    errata,
                    "{scene},{case},{},{},{},{},{},{}",
                    num(traj.summary.tip_speed_max / unit),
                    num(traj.summary.t_tip_speed_max * unit),
                    traj.status,
                    num(traj.t_reached * unit),
                    num(traj.summary.energy_balance_error / model.energy_scale(&p.chain)),
                    num(kink(&traj.final_state[..p.chain.links()]))
                )
                .map_err(err)?;
            }
        }
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &csv)?,
            ctx.write(&format!("{}-errata.csv", fig.id), &errata)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let d = t.nums("d")?;
        let col = |name: &str| -> Result<Vec<(f64, f64)>, String> {
            let v = t.nums(name)?;
            Ok(d.iter()
                .zip(v.iter())
                .filter(|(_, v)| v.is_finite())
                .map(|(&d, &v)| (d, v))
                .collect())
        };
        let title = format!("{}: {}", fig.id, self.title);
        let mut p = LinePlot::new(&title, "span d", "maximum tip speed");
        p.x_tick_step = Some(0.5);
        // Log: the report's values (1.7 .. 2.5) and ours (5 .. 19) apart.
        p.log_y = true;
        p.series.push(Series::points(
            "the report's Fig. 9, read off its page",
            col("read_off")?,
        ));
        p.series.push(Series::new(
            "report's model, its own speed (rod 1 left out, last rod's middle)",
            col("vmax_fd")?,
            Style::LinePoints,
        ));
        p.series.push(Series::new(
            "report's model, its clock, the tip's exact speed",
            col("vmax_report")?,
            Style::LinePoints,
        ));
        p.series.push(Series::new(
            "report's model in our units (/ sqrt(l/g))",
            col("vmax")?,
            Style::LinePoints,
        ));
        p.series.push(Series::new(
            "corrected model (DOPRI5, rtol 1e-8)",
            col("corrected")?,
            Style::LinePoints,
        ));
        out(ctx, fig, figures::line_plot(&p, &ctx.stem(fig.id)))
    }
}
