//! Work-precision diagrams, `wp-<scene>`: the error of two well-conditioned
//! quantities (the tip position at an evaluation time, the maximum tip speed
//! up to it) against the wall time and against the right-hand-side
//! evaluations of each method, relative to a reference computed far tighter
//! than any plotted point and confirmed by two other methods.

use std::fmt::Write as _;

use chain_ode::kinematics::tip;
use chain_ode::{solve, Accuracy, Method, SolveOptions, Stats, Status, Trajectory};
use falling_chain::Prepared;
use figures::{palette, LinePlot, RGBColor, Series, Style};

use super::{median, prepare, short, write_text, written, Ctx};

/// The reference: DOPRI5 at these tolerances.
const REF_RTOL: f64 = 1e-13;
const REF_ATOL: f64 = 1e-15;
/// The second check of the reference: BDF at these tolerances.
const CHECK_BDF_RTOL: f64 = 1e-12;
const CHECK_BDF_ATOL: f64 = 1e-14;

/// RK4's steps, coarse to fine (a sweep stops early, see [`sweep`]).
const RK4_DTS: [f64; 11] = [
    0.02, 0.01, 0.005, 0.002, 0.001, 5e-4, 2e-4, 1e-4, 5e-5, 3e-5, 2e-5,
];
/// The adaptive methods' relative tolerances, loose to tight (atol = rtol / 100).
const RTOLS: [f64; 10] = [
    1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12,
];
/// A point whose single run is predicted to take longer (s) is not run.
const MAX_RUN: f64 = 2.0;
/// Seconds of timed repeats one method's line may spend.
const LINE_BUDGET: f64 = 8.0;
/// A line whose first run takes longer (s) runs every third tolerance only.
const THIN_ABOVE: f64 = 0.5;
/// RK4's sweep stops once both errors are below this (the reference's level).
const ERR_FLOOR: f64 = 1e-12;
/// Repeats of a timed run: more for cheap runs, whose times are noisier.
const REPEATS_CHEAP: usize = 5;
const REPEATS: usize = 3;
/// Errors below this are drawn at it (a log axis cannot show 0).
const DRAW_FLOOR: f64 = 1e-16;

/// One work-precision figure.
struct Spec {
    id: &'static str,
    scene: &'static str,
    /// Shown in the title.
    label: &'static str,
    /// RK4 step of the check of the reference.
    check_dt: f64,
    /// Check with RK4 at `check_dt` and `check_dt / 2`, extrapolated.
    richardson: bool,
}

pub fn span_d3(ctx: &Ctx) -> Result<Vec<String>, String> {
    let spec = Spec {
        id: "wp-span-d3",
        scene: "span-d3",
        label: "span d = 3 (n = 50, r = 5e-4)",
        check_dt: 1e-4,
        richardson: false,
    };
    let p = prepare(ctx, spec.scene, &[])?;
    let t_eval = p.options.t_end;
    study(ctx, &spec, p, t_eval, vec![])
}

/// The folded scene is evaluated at the last time before two runs started
/// [`PERTURBATION`] apart separate (their tip distance amplified more than
/// [`AMPLIFICATION_MAX`] times), or at its end if they never do; measured
/// here for the scene and for its `r = 0` variant, and written to
/// `wp-folded-divergence.csv`.
pub fn folded(ctx: &Ctx) -> Result<Vec<String>, String> {
    let spec = Spec {
        id: "wp-folded",
        scene: "folded",
        label: "folded (n = 50, r = 1e-3)",
        check_dt: 2e-5,
        richardson: true,
    };
    let p = prepare(ctx, spec.scene, &[])?;
    let div = divergence(&p)?;
    let undamped = divergence(&prepare(ctx, spec.scene, &["chain.damping=0".into()])?)?;
    let mut csv = String::from("damping,t,tip_separation,amplification\n");
    for (r, d) in [(p.chain.damping, &div), (0.0, &undamped)] {
        for &(t, sep) in &d.curve {
            writeln!(csv, "{r},{t},{sep:e},{:e}", sep / PERTURBATION).unwrap();
        }
    }
    let path = ctx.data.join(format!("{}-divergence.csv", spec.id));
    let mut files = vec![write_text(ctx, &path, &csv)?];
    let t_eval = div.t_eval;
    if t_eval < div.t_whip {
        return Err(format!(
            "{}: runs separate (t = {t_eval}) before the whip (t = {:.3})",
            spec.id, div.t_whip
        ));
    }
    let p = prepare(ctx, spec.scene, &[format!("run.t_end={t_eval}")])?;
    let fmt_div = |d: &Divergence| match d.t_separate {
        Some(t) => format!("×{} by t = {t:.2}", short_err(AMPLIFICATION_MAX)),
        None => format!("×{:.0}", d.max_amplification),
    };
    let notes = vec![format!(
        "runs {} apart: {} (r = 0: {})",
        short(PERTURBATION),
        fmt_div(&div),
        fmt_div(&undamped)
    )];
    files.extend(study(ctx, &spec, p, t_eval, notes)?);
    Ok(files)
}

pub fn stiff_rope(ctx: &Ctx) -> Result<Vec<String>, String> {
    let spec = Spec {
        id: "wp-stiff-rope",
        scene: "stiff-rope",
        label: "stiff rope (n = 100, r = 1, γ = 1389)",
        check_dt: 3e-5,
        richardson: false,
    };
    let p = prepare(ctx, spec.scene, &[])?;
    let t_eval = p.options.t_end;
    study(ctx, &spec, p, t_eval, vec![])
}

/// Size of the perturbation of the initial angles in the divergence test.
const PERTURBATION: f64 = 1e-10;
/// Two runs have separated once their tips are this many times further
/// apart than the perturbation.
const AMPLIFICATION_MAX: f64 = 1e3;

struct Divergence {
    /// `(t, |tip - tip'|)` of two reference-accuracy runs, every 0.01.
    curve: Vec<(f64, f64)>,
    /// The reference run's maximum tip speed: the whip.
    t_whip: f64,
    /// When the tips first separate (see [`AMPLIFICATION_MAX`]), if they do.
    t_separate: Option<f64>,
    max_amplification: f64,
    /// The last sample time before they separate, or the end.
    t_eval: f64,
}

/// Two DOPRI5 runs at the reference tolerance, one from angles perturbed by
/// [`PERTURBATION`]: how far apart their tips are over the scene's time.
fn divergence(p: &Prepared) -> Result<Divergence, String> {
    let mut opts = reference_options(p.options.t_end);
    opts.output_dt = Some(0.01);
    let a = solve(&p.chain, &p.state, Method::Dopri5, &opts).map_err(|e| e.to_string())?;
    let mut state = p.state.clone();
    for (i, phi) in state.angles.iter_mut().enumerate() {
        *phi += PERTURBATION * ((i + 1) as f64).sin();
    }
    let b = solve(&p.chain, &state, Method::Dopri5, &opts).map_err(|e| e.to_string())?;
    if !a.status.is_ok() || !b.status.is_ok() {
        return Err(format!(
            "divergence runs ended {} and {}",
            a.status, b.status
        ));
    }
    let curve: Vec<(f64, f64)> = a
        .samples()
        .zip(b.samples())
        .map(|(sa, sb)| {
            let ta = tip(&p.chain, a.anchor, sa.angles);
            let tb = tip(&p.chain, b.anchor, sb.angles);
            (sa.t, (ta[0] - tb[0]).hypot(ta[1] - tb[1]))
        })
        .collect();
    let limit = AMPLIFICATION_MAX * PERTURBATION;
    let first = curve.iter().position(|c| c.1 > limit);
    let t_separate = first.map(|k| curve[k].0);
    let t_eval = match first {
        // Round the sample time to the 0.01 grid it sits on.
        Some(k) => (curve[k.saturating_sub(1)].0 * 100.0).round() / 100.0,
        None => p.options.t_end,
    };
    Ok(Divergence {
        t_whip: a.summary.t_tip_speed_max,
        t_separate,
        max_amplification: curve.iter().map(|c| c.1).fold(0.0, f64::max) / PERTURBATION,
        t_eval,
        curve,
    })
}

fn reference_options(t_end: f64) -> SolveOptions {
    SolveOptions {
        t_end,
        rtol: REF_RTOL,
        atol: REF_ATOL,
        output_dt: None,
        ..SolveOptions::default()
    }
}

/// The reference values the errors are measured against.
struct Reference {
    tip: [f64; 2],
    vmax: f64,
    length: f64,
}

impl Reference {
    /// Relative errors `(|tip - tip_ref| / L, |vmax - vmax_ref| / vmax_ref)`.
    fn errors(&self, t: &Trajectory) -> (f64, f64) {
        let s = &t.summary;
        let e_tip = (s.tip_end[0] - self.tip[0]).hypot(s.tip_end[1] - self.tip[1]) / self.length;
        let e_v = (s.tip_speed_max - self.vmax).abs() / self.vmax;
        (e_tip, e_v)
    }
}

/// One row of the CSV: a run (or a point not run) and its errors.
struct Point {
    method: String,
    param_name: &'static str,
    param: f64,
    status: String,
    t_reached: f64,
    stats: Stats,
    dim: usize,
    repeats: usize,
    /// The median of `walls` once every repeat has run.
    wall: f64,
    /// Wall times of the runs so far.
    walls: Vec<f64>,
    /// How to run it again (completed, timed points only).
    rerun: Option<(Method, SolveOptions)>,
    err_tip: f64,
    err_vmax: f64,
    /// For `auto`: whether it switched to BDF.
    switched: bool,
    note: String,
}

impl Point {
    fn plotted(&self) -> bool {
        self.status == Status::Ok.as_str() && self.err_tip.is_finite()
    }

    /// RHS evaluations plus one per Jacobian-vector product.
    fn rhs_equiv(&self) -> u64 {
        self.stats.rhs_evals + self.stats.jacobian_evals * self.dim as u64
    }

    fn not_run(method: Method, param_name: &'static str, param: f64, note: String) -> Point {
        Point {
            method: method.as_str().into(),
            param_name,
            param,
            status: "not_run".into(),
            t_reached: f64::NAN,
            stats: Stats::default(),
            dim: 0,
            repeats: 0,
            wall: f64::NAN,
            walls: vec![],
            rerun: None,
            err_tip: f64::NAN,
            err_vmax: f64::NAN,
            switched: false,
            note,
        }
    }

    fn from_run(
        method: String,
        param_name: &'static str,
        param: f64,
        t: &Trajectory,
        walls: &mut [f64],
        reference: &Reference,
    ) -> Point {
        let (err_tip, err_vmax) = if t.status.is_ok() {
            reference.errors(t)
        } else {
            (f64::NAN, f64::NAN)
        };
        let note = match t.t_failed {
            Some(tf) => format!("failed at t = {tf:.4}"),
            None => String::new(),
        };
        Point {
            method,
            param_name,
            param,
            status: t.status.as_str().into(),
            t_reached: t.t_reached,
            stats: t.stats,
            dim: 2 * t.chain.links + 1,
            repeats: walls.len(),
            wall: median(&mut walls.to_vec()),
            walls: walls.to_vec(),
            rerun: None,
            err_tip,
            err_vmax,
            switched: t.segments.len() > 1,
            note,
        }
    }
}

fn options_for(p: &Prepared, method: Method, param: f64) -> SolveOptions {
    let mut o = p.options.clone().at_accuracy(method, param);
    o.output_dt = None;
    o
}

/// Repeats of a point whose first run took `wall` seconds.
fn repeats_for(wall: f64) -> usize {
    if wall < 0.2 {
        REPEATS_CHEAP
    } else {
        REPEATS
    }
}

/// Runs every timed point again until it has its repeats, a round over all
/// points at a time (so that a burst of load elsewhere on the machine falls
/// on many points once rather than on one point every time), and takes
/// the median.
fn repeat_interleaved(p: &Prepared, rows: &mut [Point]) -> Result<(), String> {
    for _ in 1..REPEATS_CHEAP.max(REPEATS) {
        for pt in rows.iter_mut() {
            let Some((method, o)) = &pt.rerun else {
                continue;
            };
            if pt.walls.len() >= repeats_for(pt.walls[0]) {
                continue;
            }
            let t = solve(&p.chain, &p.state, *method, o).map_err(|e| e.to_string())?;
            pt.walls.push(t.summary.wall_seconds);
        }
    }
    for pt in rows.iter_mut().filter(|pt| pt.rerun.is_some()) {
        pt.repeats = pt.walls.len();
        pt.wall = median(&mut pt.walls.clone());
    }
    Ok(())
}

/// One method's line: RK4 over [`RK4_DTS`], the others over [`RTOLS`].
///
/// Points are run once each, from cheap to costly (their repeats come
/// later, see [`repeat_interleaved`]). A point whose single run is
/// predicted (from the last completed point) to exceed [`MAX_RUN`] s, or to
/// overrun the line's [`LINE_BUDGET`], is not run, nor is any point after
/// it; RK4 stops once its errors reach [`ERR_FLOOR`]; an adaptive line whose
/// first run exceeds [`THIN_ABOVE`] s runs every third tolerance only.
fn sweep(p: &Prepared, method: Method, reference: &Reference) -> Result<Vec<Point>, String> {
    let fixed_step = !method.adaptive();
    let name = method.accuracy_name();
    let params: &[f64] = match method.accuracy() {
        Accuracy::Step => &RK4_DTS,
        Accuracy::Tolerance => &RTOLS,
    };
    let mut out = vec![];
    let mut spent = 0.0;
    let mut done: Vec<(f64, f64)> = vec![]; // (param, single-run wall) of completed points
    let mut stop: Option<String> = None;
    let mut thin = false;
    for (k, &x) in params.iter().enumerate() {
        if let Some(why) = &stop {
            out.push(Point::not_run(method, name, x, why.clone()));
            continue;
        }
        if thin && k % 3 != 0 {
            out.push(Point::not_run(
                method,
                name,
                x,
                format!("thinned: a run takes > {THIN_ABOVE} s"),
            ));
            continue;
        }
        let predicted = match done.as_slice() {
            [] => 0.0,
            [.., (px, pw)] if fixed_step => pw * px / x,
            [(_, w0)] => w0 * 1.6,
            [.., (_, w1), (_, w2)] => w2 * (w2 / w1).clamp(1.0, 4.0),
        };
        let reps = repeats_for(predicted) as f64;
        if predicted > MAX_RUN || spent + reps * predicted > LINE_BUDGET {
            let why = format!(
                "cost: predicted {predicted:.1} s per run (limit {MAX_RUN} s per run, \
                 {LINE_BUDGET} s per line)"
            );
            out.push(Point::not_run(method, name, x, why.clone()));
            stop = Some(why);
            continue;
        }
        let o = options_for(p, method, x);
        let t = solve(&p.chain, &p.state, method, &o).map_err(|e| e.to_string())?;
        let wall = t.summary.wall_seconds;
        let mut pt = Point::from_run(method.as_str().into(), name, x, &t, &mut [wall], reference);
        if t.status.is_ok() {
            // The repeats come later (see `repeat_interleaved`); count them now.
            spent += wall * repeats_for(wall) as f64;
            pt.rerun = Some((method, o));
            if done.is_empty() && !fixed_step && t.summary.wall_seconds > THIN_ABOVE {
                thin = true;
            }
            done.push((x, wall));
            if fixed_step && pt.err_tip.max(pt.err_vmax) < ERR_FLOOR {
                stop = Some(format!(
                    "a coarser dt is already at the reference's level (< {})",
                    short(ERR_FLOOR)
                ));
            }
        }
        out.push(pt);
    }
    Ok(out)
}

/// Relative-error text, e.g. `3e-12`.
fn short_err(e: f64) -> String {
    if e.is_finite() && e > 0.0 {
        let x = 10f64.powf(e.log10().floor());
        format!("{:.0}e{}", (e / x).floor(), x.log10().round() as i64)
    } else {
        format!("{e}")
    }
}

fn study(
    ctx: &Ctx,
    spec: &Spec,
    p: Prepared,
    t_eval: f64,
    notes: Vec<String>,
) -> Result<Vec<String>, String> {
    // The reference and its two checks.
    let ref_opts = reference_options(t_eval);
    let r = solve(&p.chain, &p.state, Method::Dopri5, &ref_opts).map_err(|e| e.to_string())?;
    if !r.status.is_ok() {
        return Err(format!("{}: the reference run ended {}", spec.id, r.status));
    }
    let reference = Reference {
        tip: r.summary.tip_end,
        vmax: r.summary.tip_speed_max,
        length: p.chain.length,
    };
    let mut rows = vec![Point::from_run(
        "reference-dopri5".into(),
        "rtol",
        REF_RTOL,
        &r,
        &mut [r.summary.wall_seconds],
        &reference,
    )];
    let mut agreement = vec![];
    let run = |method: Method, o: &SolveOptions| -> Result<Trajectory, String> {
        solve(&p.chain, &p.state, method, o).map_err(|e| e.to_string())
    };
    // RK4 with a small step, and (where that alone is not close enough)
    // Richardson's extrapolation from it and its half: (16 y(h/2) - y(h)) / 15.
    let coarse = run(
        Method::Rk4,
        &SolveOptions {
            dt: spec.check_dt,
            ..ref_opts.clone()
        },
    )?;
    let mut pt = Point::from_run(
        "check-rk4".into(),
        "dt",
        spec.check_dt,
        &coarse,
        &mut [coarse.summary.wall_seconds],
        &reference,
    );
    let mut rk4_text = format!("RK4 dt {}", short(spec.check_dt));
    let mut rk4_err = pt.err_tip.max(pt.err_vmax);
    rows.push(pt);
    if spec.richardson {
        let h2 = spec.check_dt / 2.0;
        let fine = run(
            Method::Rk4,
            &SolveOptions {
                dt: h2,
                ..ref_opts.clone()
            },
        )?;
        pt = Point::from_run(
            "check-rk4".into(),
            "dt",
            h2,
            &fine,
            &mut [fine.summary.wall_seconds],
            &reference,
        );
        rows.push(pt);
        let x = |f: f64, c: f64| (16.0 * f - c) / 15.0;
        let (sf, sc) = (&fine.summary, &coarse.summary);
        let tip = [
            x(sf.tip_end[0], sc.tip_end[0]),
            x(sf.tip_end[1], sc.tip_end[1]),
        ];
        let vmax = x(sf.tip_speed_max, sc.tip_speed_max);
        let err_tip =
            (tip[0] - reference.tip[0]).hypot(tip[1] - reference.tip[1]) / reference.length;
        let err_vmax = (vmax - reference.vmax).abs() / reference.vmax;
        rows.push(Point {
            method: "check-rk4-richardson".into(),
            err_tip,
            err_vmax,
            note: format!(
                "(16 y(dt/2) - y(dt)) / 15 from dt {} and {}",
                short(spec.check_dt),
                short(h2)
            ),
            status: "ok".into(),
            wall: coarse.summary.wall_seconds + fine.summary.wall_seconds,
            repeats: 1,
            ..Point::not_run(Method::Rk4, "dt", spec.check_dt, String::new())
        });
        rk4_text = "RK4 (extrapolated)".to_string();
        rk4_err = err_tip.max(err_vmax);
    }
    agreement.push(format!("{rk4_text} to {}", short_err(rk4_err)));
    let bdf = run(
        Method::Bdf,
        &SolveOptions {
            rtol: CHECK_BDF_RTOL,
            atol: CHECK_BDF_ATOL,
            ..ref_opts.clone()
        },
    )?;
    let pt = Point::from_run(
        "check-bdf".into(),
        "rtol",
        CHECK_BDF_RTOL,
        &bdf,
        &mut [bdf.summary.wall_seconds],
        &reference,
    );
    agreement.push(format!(
        "BDF {} to {}",
        short(CHECK_BDF_RTOL),
        short_err(pt.err_tip.max(pt.err_vmax))
    ));
    rows.push(pt);

    // The lines.
    for method in Method::ALL {
        rows.extend(sweep(&p, method, &reference)?);
    }
    repeat_interleaved(&p, &mut rows)?;

    let mut files = vec![write_csv(ctx, spec, t_eval, &reference, &rows)?];
    let out = draw(ctx, spec, t_eval, &rows, &agreement, notes)?;
    files.extend(written(ctx, &out));
    Ok(files)
}

fn write_csv(
    ctx: &Ctx,
    spec: &Spec,
    t_eval: f64,
    reference: &Reference,
    rows: &[Point],
) -> Result<String, String> {
    let mut csv = String::from(
        "scene,t_eval,method,param_name,param,status,t_reached,steps,rejected_steps,rhs_evals,\
         jacobian_evals,lu_factorizations,rhs_equiv,repeats,wall_median,err_tip,err_vmax,\
         tip_ref_x,tip_ref_y,vmax_ref,note\n",
    );
    for pt in rows {
        let s = &pt.stats;
        writeln!(
            csv,
            "{},{t_eval},{},{},{:e},{},{},{},{},{},{},{},{},{},{:e},{:e},{:e},{},{},{},{}",
            spec.scene,
            pt.method,
            pt.param_name,
            pt.param,
            pt.status,
            pt.t_reached,
            s.steps,
            s.rejected_steps,
            s.rhs_evals,
            s.jacobian_evals,
            s.lu_factorizations,
            pt.rhs_equiv(),
            pt.repeats,
            pt.wall,
            pt.err_tip,
            pt.err_vmax,
            reference.tip[0],
            reference.tip[1],
            reference.vmax,
            pt.note.replace(',', ";")
        )
        .unwrap();
    }
    write_text(ctx, &ctx.data.join(format!("{}.csv", spec.id)), &csv)
}

/// `a … b` of the parameters of `pts` (or the one, or a list of two).
fn span(pts: &[&Point]) -> String {
    match pts {
        [] => String::new(),
        [a] => short(a.param),
        [a, b] => format!("{}, {}", short(a.param), short(b.param)),
        [a, .., b] => format!("{} … {}", short(a.param), short(b.param)),
    }
}

/// The legend entry of a method's line: what ran, what failed.
fn method_label(method: Method, rows: &[Point]) -> (String, Vec<&Point>) {
    let mine = |pt: &&Point| pt.method == method.as_str();
    let ok: Vec<&Point> = rows.iter().filter(mine).filter(|pt| pt.plotted()).collect();
    let failed: Vec<&Point> = rows
        .iter()
        .filter(mine)
        .filter(|pt| pt.status != "ok" && pt.status != "not_run")
        .collect();
    let name = method.as_str().to_uppercase();
    let param = method.accuracy_name();
    let mut label = if method == Method::Auto && !ok.is_empty() && ok.iter().all(|pt| !pt.switched)
    {
        format!("{name} (never switched: = DOPRI5)")
    } else if ok.is_empty() {
        format!("{name}: no run completed")
    } else {
        format!("{name} ({param} {})", span(&ok))
    };
    if !failed.is_empty() {
        label.push_str(&format!("; fails at {}", span(&failed)));
    }
    (label, ok)
}

fn draw(
    ctx: &Ctx,
    spec: &Spec,
    t_eval: f64,
    rows: &[Point],
    agreement: &[String],
    notes: Vec<String>,
) -> Result<figures::Output, String> {
    let mut left = LinePlot::new(
        "error vs wall time",
        "wall time (s, median)",
        "relative error",
    );
    let mut right = LinePlot::new(
        "error vs work",
        "RHS evaluations (+ one per JVP of BDF)",
        "relative error",
    );
    let floor = |e: f64| e.max(DRAW_FLOOR);
    for (i, method) in Method::ALL.into_iter().enumerate() {
        let (label, pts) = method_label(method, rows);
        let color = palette(i);
        let wall = |pt: &Point| pt.wall;
        let work = |pt: &Point| pt.rhs_equiv() as f64;
        for (plot, x, label) in [
            (&mut left, &wall as &dyn Fn(&Point) -> f64, label.as_str()),
            (&mut right, &work, ""),
        ] {
            let tip: Vec<(f64, f64)> = pts.iter().map(|pt| (x(pt), floor(pt.err_tip))).collect();
            let vmax: Vec<(f64, f64)> = pts.iter().map(|pt| (x(pt), floor(pt.err_vmax))).collect();
            let vstyle = if vmax.len() > 1 {
                Style::Dashed
            } else {
                Style::Points
            };
            plot.series
                .push(Series::new(label, tip, Style::LinePoints).with_color(color));
            plot.series
                .push(Series::new("", vmax, vstyle).with_color(color));
        }
    }
    for plot in [&mut left, &mut right] {
        plot.log_x = true;
        plot.log_y = true;
    }
    // The key to the two line styles (series without points), then lines
    // of text (invisible swatches): the legend, unlike a note box, gets room
    // of its own above the data.
    let key = palette(7);
    right.series.push(
        Series::new(
            format!("tip position |Δr| / L at t = {t_eval}"),
            vec![],
            Style::LinePoints,
        )
        .with_color(key),
    );
    right
        .series
        .push(Series::new("max tip speed |Δv_max| / v_max", vec![], Style::Dashed).with_color(key));
    let mut text = vec![format!(
        "reference: DOPRI5 rtol {}, agrees with",
        short(REF_RTOL)
    )];
    text.push(format!("  {}", agreement.join(", ")));
    text.extend(notes);
    for line in text {
        right
            .series
            .push(Series::new(line, vec![], Style::Points).with_color(RGBColor(255, 255, 255)));
    }
    let title = format!("Work-precision: {}", spec.label);
    figures::line_plot_pair(&left, &right, &title, &ctx.out.join(spec.id))
        .map_err(|e| e.to_string())
}
