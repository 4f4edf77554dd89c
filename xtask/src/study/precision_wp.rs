//! Work-precision diagrams, `wp-<scene>`: the error of two well-conditioned
//! quantities (the tip position at an evaluation time, the maximum tip speed
//! up to it) against the wall time and against the right-hand-side
//! evaluations of each method, relative to a reference computed far tighter
//! than any plotted point and confirmed by two other methods.
//!
//! Which points a line runs is decided by their cost (see [`sweep`]), and
//! so by wall times: `--timings` measures them and records the decision,
//! the plan, with the wall times in `<id>-timing.csv`; without it the
//! points of the recorded plan are run once each, untimed and in parallel,
//! so that `<id>.csv` (steps, evaluations, errors: no wall time) is the
//! same to the byte whenever the physics is.

use std::fmt::Write as _;

use chain_ode::kinematics::tip;
use chain_ode::{solve, Method, Status};
use falling_chain::study::precision::{
    self, params, reference_options, Checks, Plan, Point, Reference,
};
use falling_chain::Prepared;
use figures::{palette, LinePlot, Series, Style};

use crate::ctx::Ctx;
use crate::data::{distinct, exp, exp_digits, num, short_err, text, Table};
use crate::registry::{Figure, Make};
use crate::timing::median;

/// Errors below this are drawn at it (a log axis cannot show 0).
const DRAW_FLOOR: f64 = 1e-16;

/// Where a work-precision figure evaluates its errors.
pub enum Eval {
    /// At the scene's end.
    End,
    /// At the last time before two runs started [`PERTURBATION`] apart
    /// separate (their tip distance amplified more than
    /// [`AMPLIFICATION_MAX`] times), or at the end if they never do;
    /// measured for the scene and for its `r = 0` variant, and written to
    /// `<id>-divergence.csv`.
    BeforeSeparation,
}

/// One work-precision figure.
pub struct Spec {
    scene: &'static str,
    /// Shown in the title.
    label: &'static str,
    /// RK4 step of the check of the reference.
    check_dt: f64,
    /// Check with RK4 at `check_dt` and `check_dt / 2`, extrapolated.
    richardson: bool,
    eval: Eval,
}

pub const SPAN_D3: Spec = Spec {
    scene: "span-d3",
    label: "span d = 3 (n = 50, r = 5e-4)",
    check_dt: 1e-4,
    richardson: false,
    eval: Eval::End,
};

pub const FOLDED: Spec = Spec {
    scene: "folded",
    label: "folded (n = 50, r = 1e-3)",
    check_dt: 2e-5,
    richardson: true,
    eval: Eval::BeforeSeparation,
};

pub const STIFF_ROPE: Spec = Spec {
    scene: "stiff-rope",
    label: "stiff rope (n = 100, r = 1, γ = 1389)",
    check_dt: 3e-5,
    richardson: false,
    eval: Eval::End,
};

impl Make for Spec {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let mut files = vec![];
        let p = ctx.prepare::<&str>(self.scene, &[])?;
        let (p, t_eval) = match self.eval {
            Eval::End => {
                let t_eval = p.options.t_end;
                (p, t_eval)
            }
            Eval::BeforeSeparation => {
                let div = divergence(&p)?;
                let undamped = divergence(&ctx.prepare(self.scene, &["chain.damping=0"])?)?;
                let mut csv = String::from("damping,t,tip_separation,amplification\n");
                for (r, d) in [(p.chain.damping(), &div), (0.0, &undamped)] {
                    for &(t, sep) in &d.curve {
                        writeln!(
                            csv,
                            "{},{},{},{}",
                            num(r),
                            num(t),
                            exp(sep),
                            exp(sep / PERTURBATION)
                        )
                        .unwrap();
                    }
                }
                files.push(ctx.write(&format!("{}-divergence.csv", fig.id), &csv)?);
                let t_eval = div.t_eval;
                if t_eval < div.t_whip {
                    return Err(format!(
                        "{}: runs separate (t = {t_eval}) before the whip (t = {:.3})",
                        fig.id, div.t_whip
                    ));
                }
                (
                    ctx.prepare(self.scene, &[format!("run.t_end={t_eval}")])?,
                    t_eval,
                )
            }
        };
        files.extend(study(ctx, fig, self, p, t_eval)?);
        Ok(files)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let rows = read_rows(ctx, fig)?;
        let notes = match self.eval {
            Eval::End => vec![],
            Eval::BeforeSeparation => {
                vec![divergence_note(
                    &ctx.read(&format!("{}-divergence.csv", fig.id))?,
                )?]
            }
        };
        let out = draw(ctx, fig, self, &rows, notes)?;
        Ok(ctx.drawn(&out))
    }
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
    /// The last sample time before they separate, or the end.
    t_eval: f64,
}

/// When two runs' tips first separate (see [`AMPLIFICATION_MAX`]), if they
/// do: the index into `curve` of `(t, |tip - tip'|)`.
fn separation(curve: &[(f64, f64)]) -> Option<usize> {
    let limit = AMPLIFICATION_MAX * PERTURBATION;
    curve.iter().position(|c| c.1 > limit)
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
    let t_eval = match separation(&curve) {
        // Round the sample time to the 0.01 grid it sits on.
        Some(k) => (curve[k.saturating_sub(1)].0 * 100.0).round() / 100.0,
        None => p.options.t_end,
    };
    Ok(Divergence {
        t_whip: a.summary.t_tip_speed_max,
        t_eval,
        curve,
    })
}

/// The legend line of `<id>-divergence.csv`: how far the scene's runs (its
/// first damping) and the `r = 0` runs separate.
fn divergence_note(t: &Table) -> Result<String, String> {
    let (damping, time, sep) = (t.strs("damping")?, t.nums("t")?, t.nums("tip_separation")?);
    let fmt = |r: &str| {
        let curve: Vec<(f64, f64)> = (0..t.len())
            .filter(|&k| damping[k] == r)
            .map(|k| (time[k], sep[k]))
            .collect();
        match separation(&curve) {
            Some(k) => format!("×{} by t = {:.2}", short_err(AMPLIFICATION_MAX), curve[k].0),
            None => format!(
                "×{:.0}",
                curve.iter().map(|c| c.1).fold(0.0, f64::max) / PERTURBATION
            ),
        }
    };
    match distinct(&damping)[..] {
        [scene, undamped] => Ok(format!(
            "runs {} apart: {} (r = 0: {})",
            exp(PERTURBATION),
            fmt(scene),
            fmt(undamped)
        )),
        _ => Err(format!("{}: expected two dampings", t.name)),
    }
}

/// Every line as the plan in `<id>-timing.csv` says, each point run once,
/// untimed, in parallel.
fn planned(
    ctx: &Ctx,
    fig: &Figure,
    p: &Prepared,
    reference: &Reference,
) -> Result<Vec<Point>, String> {
    let file = format!("{}-timing.csv", fig.id);
    let t = ctx.read(&file)?;
    let (method, param, plan) = (t.strs("method")?, t.strs("param")?, t.strs("plan")?);
    let mut jobs = vec![];
    for m in Method::ALL {
        for &x in params(m) {
            let k = (0..t.len())
                .find(|&k| method[k] == m.as_str() && param[k] == exp(x))
                .ok_or_else(|| {
                    format!(
                        "figures/data/{file} has no plan for {m} at {} {}: run \
                         `cargo xtask figures --only {} --timings`",
                        m.accuracy_name(),
                        exp(x),
                        fig.id
                    )
                })?;
            jobs.push((m, x, Plan::parse(plan[k])?));
        }
    }
    ctx.pool()?
        .install(|| precision::run_planned(p, &jobs, reference))
        .map_err(|e| e.to_string())
}

fn study(
    ctx: &Ctx,
    fig: &Figure,
    spec: &Spec,
    p: Prepared,
    t_eval: f64,
) -> Result<Vec<String>, String> {
    let checks = Checks {
        check_dt: spec.check_dt,
        richardson: spec.richardson,
    };
    let (reference, mut rows) =
        precision::reference(&p, t_eval, checks).map_err(|e| e.to_string())?;
    let Some(reference) = reference else {
        return Err(format!(
            "{}: the reference run ended {}",
            fig.id, rows[0].status
        ));
    };
    // The lines: timed, or as the timing file's plan says.
    if ctx.timings {
        for method in Method::ALL {
            rows.extend(precision::timed_line(&p, method, &reference).map_err(|e| e.to_string())?);
        }
        precision::repeat_interleaved(&p, &mut rows).map_err(|e| e.to_string())?;
    } else {
        rows.extend(planned(ctx, fig, &p, &reference)?);
    }
    let csv = precision::csv_text(spec.scene, t_eval, &reference, &rows, None);
    let mut files = vec![ctx.write(&format!("{}.csv", fig.id), &csv)?];
    if ctx.timings {
        files.push(write_timing(ctx, fig, &rows)?);
    }
    Ok(files)
}

/// `<id>-timing.csv`: the plan, and the median wall time of each run.
fn write_timing(ctx: &Ctx, fig: &Figure, rows: &[Point]) -> Result<String, String> {
    let mut csv = String::from("method,param_name,param,plan,repeats,wall_median,note\n");
    for pt in rows {
        let wall = if pt.walls.is_empty() {
            String::new()
        } else {
            exp_digits(median(&mut pt.walls.clone()), 3)
        };
        writeln!(
            csv,
            "{},{},{},{},{},{wall},{}",
            pt.method,
            pt.param_name,
            exp(pt.param),
            pt.plan.as_str(),
            pt.walls.len(),
            text(&pt.timing_note)
        )
        .unwrap();
    }
    ctx.write(&format!("{}-timing.csv", fig.id), &csv)
}

/// A row of `<id>.csv` as the drawing needs it, with its wall time from
/// `<id>-timing.csv`.
struct Drawn {
    method: String,
    param_name: String,
    param: f64,
    status: String,
    switched: bool,
    err_tip: f64,
    err_vmax: f64,
    rhs_equiv: f64,
    wall: f64,
}

impl Drawn {
    fn plotted(&self) -> bool {
        self.status == Status::Ok.as_str() && self.err_tip.is_finite()
    }
    fn err(&self) -> f64 {
        self.err_tip.max(self.err_vmax)
    }
}

/// `<id>.csv` joined with the wall times of `<id>-timing.csv` by method and
/// accuracy; the evaluation time.
fn read_rows(ctx: &Ctx, fig: &Figure) -> Result<(f64, Vec<Drawn>), String> {
    let t = ctx.read(&format!("{}.csv", fig.id))?;
    let w = ctx.read(&format!("{}-timing.csv", fig.id))?;
    let (wm, wp, wall) = (w.strs("method")?, w.strs("param")?, w.nums("wall_median")?);
    let (method, param_name, param) = (t.strs("method")?, t.strs("param_name")?, t.strs("param")?);
    let (status, switched) = (t.strs("status")?, t.strs("switched")?);
    let (err_tip, err_vmax, rhs) = (
        t.nums("err_tip")?,
        t.nums("err_vmax")?,
        t.nums("rhs_equiv")?,
    );
    let t_eval = t.nums("t_eval")?.first().copied().unwrap_or(f64::NAN);
    let rows = (0..t.len())
        .map(|k| {
            let wall = (0..w.len())
                .find(|&j| wm[j] == method[k] && wp[j] == param[k])
                .map_or(f64::NAN, |j| wall[j]);
            Ok(Drawn {
                method: method[k].to_string(),
                param_name: param_name[k].to_string(),
                param: crate::data::parse_num(param[k])?,
                status: status[k].to_string(),
                switched: switched[k] == "1",
                err_tip: err_tip[k],
                err_vmax: err_vmax[k],
                rhs_equiv: rhs[k],
                wall,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok((t_eval, rows))
}

/// `a … b` of the parameters of `pts` (or the one, or a list of two).
fn span(pts: &[&Drawn]) -> String {
    match pts {
        [] => String::new(),
        [a] => exp(a.param),
        [a, b] => format!("{}, {}", exp(a.param), exp(b.param)),
        [a, .., b] => format!("{} … {}", exp(a.param), exp(b.param)),
    }
}

/// The legend entry of a method's line: what ran, what failed.
fn method_label<'a>(method: &str, rows: &'a [Drawn]) -> (String, Vec<&'a Drawn>) {
    let mine: Vec<&Drawn> = rows.iter().filter(|pt| pt.method == method).collect();
    let ok: Vec<&Drawn> = mine.iter().copied().filter(|pt| pt.plotted()).collect();
    let failed: Vec<&Drawn> = mine
        .iter()
        .copied()
        .filter(|pt| pt.status != "ok" && pt.status != "not_run")
        .collect();
    let name = method.to_uppercase();
    let param = mine.first().map_or("", |pt| pt.param_name.as_str());
    let mut label =
        if method == Method::Auto.as_str() && !ok.is_empty() && ok.iter().all(|pt| !pt.switched) {
            format!("{name} (dashed, on top; one method per run)")
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

/// Which explicit method each of auto's points is (same parameter, same
/// errors and work): lines "AUTO = DOPRI5 at 1e-3 … 1e-6," and
/// "  = DOP853 at 1e-7 … 1e-12".
fn same_as(auto: &[&Drawn], rows: &[Drawn]) -> Vec<String> {
    let twin = |pt: &Drawn| {
        rows.iter()
            .find(|r| {
                r.method != pt.method
                    && Method::ALL.iter().any(|m| m.as_str() == r.method)
                    && r.param == pt.param
                    && r.err_tip == pt.err_tip
                    && r.err_vmax == pt.err_vmax
                    && r.rhs_equiv == pt.rhs_equiv
            })
            .map_or("?".to_string(), |r| r.method.to_uppercase())
    };
    let mut groups: Vec<(String, Vec<&Drawn>)> = vec![];
    for &pt in auto {
        let m = twin(pt);
        match groups.last_mut() {
            Some((g, v)) if *g == m => v.push(pt),
            _ => groups.push((m, vec![pt])),
        }
    }
    groups
        .iter()
        .enumerate()
        .map(|(k, (m, v))| {
            let head = if k == 0 { "AUTO" } else { "   " };
            let tail = if k + 1 < groups.len() { "," } else { "" };
            format!("{head} = {m} at {}{tail}", span(v))
        })
        .collect()
}

/// How far the checks agree with the reference, from their rows.
fn agreement(rows: &[Drawn]) -> Result<(f64, Vec<String>), String> {
    let find = |m: &str| rows.iter().find(|r| r.method == m);
    let missing = |m: &str| format!("no '{m}' row");
    let reference = find("reference-dopri5").ok_or_else(|| missing("reference-dopri5"))?;
    let rk4 = match find("check-rk4-richardson") {
        Some(r) => format!("RK4 (extrapolated) to {}", short_err(r.err())),
        None => {
            let r = find("check-rk4").ok_or_else(|| missing("check-rk4"))?;
            format!("RK4 dt {} to {}", exp(r.param), short_err(r.err()))
        }
    };
    let bdf = find("check-bdf").ok_or_else(|| missing("check-bdf"))?;
    let bdf = format!("BDF {} to {}", exp(bdf.param), short_err(bdf.err()));
    Ok((reference.param, vec![rk4, bdf]))
}

fn draw(
    ctx: &Ctx,
    fig: &Figure,
    spec: &Spec,
    (t_eval, rows): &(f64, Vec<Drawn>),
    notes: Vec<String>,
) -> Result<figures::Output, String> {
    // The error the paper uses: the larger of the two relative errors.
    let y_label = "max(|Δr_tip| / L, |Δv_max| / v_max)";
    let mut left = LinePlot::new("error vs wall time", "wall time (s, median)", y_label);
    let mut right = LinePlot::new(
        "error vs work",
        "RHS evaluations (+ one per JVP of BDF)",
        y_label,
    );
    let floor = |e: f64| e.max(DRAW_FLOOR);
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for (i, method) in Method::ALL.into_iter().enumerate() {
        let (label, pts) = method_label(method.as_str(), rows);
        let color = palette(i);
        // auto runs one of the explicit methods: drawn dashed and on top
        // (last), so that the curve it coincides with shows through.
        let style = if method == Method::Auto {
            Style::Dashed
        } else {
            Style::LinePoints
        };
        let wall = |pt: &Drawn| pt.wall;
        let work = |pt: &Drawn| pt.rhs_equiv;
        for (plot, x, label) in [
            (&mut left, &wall as &dyn Fn(&Drawn) -> f64, label.as_str()),
            (&mut right, &work, ""),
        ] {
            let pts: Vec<(f64, f64)> = pts
                .iter()
                .filter(|pt| x(pt).is_finite())
                .map(|pt| (x(pt), floor(pt.err())))
                .collect();
            for p in &pts {
                lo = lo.min(p.1);
                hi = hi.max(p.1);
            }
            plot.series
                .push(Series::new(label, pts, style).with_color(color));
        }
    }
    // Fitted to the data, with a third of a decade to spare below and
    // room above for the legend and the note (one line each about 4% of
    // the height).
    let margin = 10f64.powf(1.0 / 3.0);
    let lines = 8.0;
    for plot in [&mut left, &mut right] {
        plot.log_x = true;
        plot.log_y = true;
        if lo.is_finite() && hi > 0.0 {
            let (a, b) = ((lo / margin).log10(), (hi * margin).log10());
            let top = b + (b - a) * lines * 0.05 / (1.0 - lines * 0.05);
            plot.y_range = Some((10f64.powf(a), 10f64.powf(top)));
        }
    }
    let (ref_rtol, agree) = agreement(rows)?;
    let mut text = vec![format!(
        "reference: DOPRI5 rtol {}, agrees with",
        exp(ref_rtol)
    )];
    text.push(format!("  {}", agree.join(", ")));
    text.push(format!("tip position error Δr_tip at t = {t_eval}"));
    let (_, auto) = method_label(Method::Auto.as_str(), rows);
    if !auto.is_empty() && auto.iter().all(|pt| !pt.switched) {
        text.extend(same_as(&auto, rows));
    }
    text.extend(notes);
    right.annotations = text;
    let title = format!(
        "Work-precision: {}; error: larger of tip position, max tip speed errors",
        spec.label
    );
    figures::line_plot_pair(&left, &right, &title, &ctx.stem(fig.id)).map_err(|e| e.to_string())
}
