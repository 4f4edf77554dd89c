//! The study's commands: `precision`, `stability`, `needs`, `ensemble` and `merge`
//! (the computations are the fc-study crate's).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use fc_batch::budget::{check_budget, Budget};
use fc_batch::shard::{self, Shard};
use fc_batch::sweep::Vary;
use fc_csv::format::exp;
use fc_scene::atomic::{begin, check_distinct, check_not_inputs, check_writable};
use fc_scene::error::echo_path;
use fc_scene::Error;
use fc_study::measure::{Measure, Measures};
use fc_study::{self as study, ensemble, needs, plot, precision, stability};

use crate::stdout::{say, say_raw};
use crate::{JobsArgs, SceneArgs};

/// The flags the study's table commands share.
#[derive(Args)]
pub struct StudyArgs {
    /// Only these methods, M1,M2,... (default: every method).
    #[arg(long, value_name = "M1,M2,...")]
    methods: Option<String>,
    /// What the errors measure, M1,M2,...: tip (the default: the tip's
    /// end and its largest speed), tip_speed_max, pivot_force_max,
    /// tension_max, floor_force_max, floor_reading, dissipated; with
    /// several, the error is the largest over them (each is reported).
    #[arg(long, value_name = "M1,M2,...")]
    measure: Option<String>,
    /// Write the table as CSV (the columns of the study's data files, then
    /// wall_seconds, run, runs, scene_hash).
    #[arg(long, value_name = "FILE.csv")]
    out: Option<PathBuf>,
    /// Draw the figure to FILE.png or FILE.svg.
    #[arg(long, value_name = "FILE.svg|FILE.png")]
    plot: Option<PathBuf>,
    /// Stop after this many seconds of wall time, in (0, 2592000] (30
    /// days): every phase (precision's reference and its checks too) runs
    /// within it; points that would not fit are not run, runs still going
    /// are stopped, and all are listed.
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    budget: Option<f64>,
    /// Run only runs I, I+N, ... of the study (0 <= I < N); join the
    /// tables with `merge`.
    #[arg(long, value_name = "I/N", allow_hyphen_values = true)]
    shard: Option<String>,
    #[command(flatten)]
    jobs: JobsArgs,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

#[derive(Args)]
pub struct PrecisionArgs {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    study: StudyArgs,
    /// RK4's step in the check of the reference, in [t_end / 1e7, t_end]
    /// (3 t_end / 1e7 with --richardson): at most 1e7 RK4 steps, refused
    /// before any run.
    #[arg(long = "check-dt", value_name = "DT", default_value_t = precision::CHECK_DT, allow_negative_numbers = true)]
    check_dt: f64,
    /// Check the reference with RK4 at --check-dt and its half,
    /// extrapolated (Richardson).
    #[arg(long)]
    richardson: bool,
}

#[derive(Args)]
pub struct StabilityArgs {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    study: StudyArgs,
    /// A row per value: KEY=V1,V2,... or KEY=START:STOP:COUNT (at most
    /// 1000 values), e.g. chain.damping=0,1e-3,1e-2.
    #[arg(long, value_name = "KEY=VALUES", allow_hyphen_values = true)]
    vary: Option<String>,
}

#[derive(Args)]
pub struct NeedsArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// The tolerance, in [1e-9, 1): relative on the maximum tip speed and
    /// the method's error, over L on the tip end and path.
    #[arg(long, value_name = "TOL", allow_negative_numbers = true)]
    tol: f64,
    /// The ladder of n, N1,N2,... (the largest is the reference; 2 to 32
    /// different numbers, each in 2..=1000000).
    #[arg(
        long,
        value_name = "N1,N2,...",
        default_value = "25,50,100,200,400",
        allow_hyphen_values = true
    )]
    links: String,
    /// The methods tried at the answer's n (default: all but bdf-dense).
    #[arg(long, value_name = "M1,M2,...")]
    methods: Option<String>,
    /// What the answer is judged on, M1,M2,...: tip (the default),
    /// tip_speed_max, pivot_force_max, tension_max, floor_force_max,
    /// floor_reading, dissipated.
    #[arg(long, value_name = "M1,M2,...")]
    measure: Option<String>,
    /// Stop after this many seconds of wall time, in (0, 2592000] (30
    /// days): every phase (the ladder of n, the reference and its checks,
    /// the methods, the terms) runs within it; what it stopped is listed.
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    budget: Option<f64>,
    #[command(flatten)]
    jobs: JobsArgs,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

#[derive(Args)]
pub struct EnsembleArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Members: starts run, in 2..=4096.
    #[arg(long, value_name = "N", default_value_t = ensemble::DEFAULT_MEMBERS, allow_negative_numbers = true, value_parser = parse_members)]
    members: usize,
    /// Each start angle is moved by a number drawn uniformly from
    /// [-S, S] rad, S in [0, 0.1].
    #[arg(long, value_name = "S", default_value_t = ensemble::DEFAULT_SPREAD, allow_negative_numbers = true)]
    spread: f64,
    /// Which perturbations (member j draws from stream j + 2^32 SEED), an
    /// integer in 0..=4294967295.
    #[arg(long, value_name = "SEED", default_value_t = 0, allow_negative_numbers = true, value_parser = parse_seed)]
    seed: u32,
    /// Write one row per member as CSV: member, status, and the quantities
    /// (tip_speed_max, t_tip_speed_max, tip_end_x, tip_end_y, energy_end,
    /// dissipated, floor_force_max, steps).
    #[arg(long, value_name = "FILE.csv")]
    out: Option<PathBuf>,
    /// Write the time series as CSV: one row per output time (the members
    /// share them), t, members (those that ended ok), then for each output
    /// (tip_x, tip_y, tip_vx, tip_vy, tip_speed, energy, dissipated,
    /// pivot_x, pivot_y, and with a floor floor_x, floor_y, landed_weight,
    /// landed_length) its _mean, _sem, _sd, _min and _max over them.
    #[arg(long = "out-series", value_name = "FILE.csv")]
    out_series: Option<PathBuf>,
    /// Also the statistics of these measures, M1,M2,...: tip (the
    /// default: the quantities above), tip_speed_max, pivot_force_max,
    /// tension_max, floor_force_max, floor_reading, dissipated; the
    /// pivot's force and the tensions are tracked only when measured.
    #[arg(long, value_name = "M1,M2,...")]
    measure: Option<String>,
    /// Stop after this many seconds of wall time, in (0, 2592000] (30
    /// days): members that cannot start within it are not run, runs still
    /// going are stopped, and all are listed.
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true)]
    budget: Option<f64>,
    #[command(flatten)]
    jobs: JobsArgs,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

fn parse_members(text: &str) -> Result<usize, String> {
    crate::int_in(text, 2, ensemble::MAX_MEMBERS)
}

fn parse_seed(text: &str) -> Result<u32, String> {
    text.trim()
        .parse::<u32>()
        .map_err(|_| format!("must be an integer in 0..={}", u32::MAX))
}

#[derive(Args)]
pub struct MergeArgs {
    /// The shards' tables (written by --shard I/N --out).
    #[arg(value_name = "SHARD.csv", required = true)]
    shards: Vec<PathBuf>,
    /// The joined table.
    #[arg(long, value_name = "ALL.csv", required = true)]
    out: PathBuf,
}

fn progress_bar(quiet: bool, total: usize) -> indicatif::ProgressBar {
    if quiet {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::with_draw_target(
        Some(total as u64),
        indicatif::ProgressDrawTarget::stderr(),
    );
    match indicatif::ProgressStyle::with_template("{msg} {bar:40} {pos}/{len}, {elapsed}") {
        Ok(style) => bar.with_style(style),
        Err(_) => bar,
    }
}

/// Checks `--plot` (its extension, that it can be written) and that it is
/// not the file `--out` writes.
fn check_plot(plot: Option<&Path>, out: Option<&Path>) -> Result<(), Error> {
    check_distinct(&[("--out", out), ("--plot", plot)])?;
    if let Some(p) = plot {
        let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
        if !matches!(ext.to_ascii_lowercase().as_str(), "png" | "svg") {
            return Err(Error::field(
                "--plot",
                format!("must end in .png or .svg (got '{}')", echo_path(p)),
            ));
        }
        check_writable("--plot", p)?;
    }
    Ok(())
}

fn draw(path: &Path, result: Result<(), figures::FigureError>) -> Result<(), Error> {
    result
        .map_err(|e| Error::field("--plot", format!("cannot write '{}': {e}", echo_path(path))))?;
    eprintln!("wrote {}", echo_path(path));
    Ok(())
}

fn budget_of(what: &str, b: Option<f64>) -> Result<Option<f64>, Error> {
    b.map(|s| check_budget(what, s)).transpose()
}

pub fn precision(args: &PrecisionArgs) -> Result<ExitCode, Error> {
    let a = &args.study;
    let scene = args
        .scene
        .load(&[("--out", a.out.as_deref()), ("--plot", a.plot.as_deref())])?;
    let options = precision::Options {
        methods: study::parse_methods("--methods", a.methods.as_deref())?,
        checks: precision::Checks {
            check_dt: precision::check_check_dt(
                "--check-dt",
                args.check_dt,
                scene.options()?.t_end,
                args.richardson,
            )?,
            richardson: args.richardson,
        },
        budget: budget_of("--budget", a.budget)?,
        shard: a.shard.as_deref().map(Shard::parse).transpose()?,
        jobs: a.jobs.threads()?,
        measures: Measures::parse_for("--measure", a.measure.as_deref(), &scene.prepare()?)?,
    };
    check_plot(a.plot.as_deref(), a.out.as_deref())?;
    let out = a.out.as_deref().map(|o| begin("--out", o)).transpose()?;
    let total = precision::ladder(&options.methods).len();
    let bar = progress_bar(
        a.quiet,
        options.shard.map_or(total, |s| total.div_ceil(s.count)),
    );
    bar.set_message("points");
    let s = precision::study(&scene, &options, None, &|| bar.inc(1))?;
    bar.finish_and_clear();
    let (a_rk4, a_bdf) = precision::agreement(&s.rows);
    if s.measures.is_tip() {
        say!(
            "{}: work-precision at t = {}; error = max(|tip - tip_ref|/L, |vmax/vmax_ref - 1|)",
            s.name,
            s.t_eval
        );
    } else {
        say!(
            "{}: work-precision at t = {}; error = the largest relative error of {}",
            s.name,
            s.t_eval,
            s.measures.names()
        );
    }
    let reference = &s.rows[0];
    if reference.ok() && s.plan != precision::ReferencePlan::Explicit {
        say!(
            "  reference: {}; the two runs agree to {}{}",
            s.plan.describe(),
            if a_rk4.is_finite() {
                format!("{a_rk4:.1e}")
            } else {
                "- (the check did not finish)".to_string()
            },
            if a_rk4 <= precision::CONFIRMED {
                String::new()
            } else {
                format!(" (not confirmed: above {})", exp(precision::CONFIRMED))
            }
        );
    } else if reference.ok() {
        // A check that did not finish (the budget) agrees to no number.
        let agree = |a: f64| {
            if a.is_finite() {
                format!("{a:.1e}")
            } else {
                "- (the check did not finish)".to_string()
            }
        };
        say!(
            "  reference: DOPRI5 rtol {}; it agrees with RK4 dt {}{} to {} and with BDF rtol {} to {}",
            exp(precision::REF_RTOL),
            exp(args.check_dt),
            if args.richardson { " (extrapolated)" } else { "" },
            agree(a_rk4),
            exp(precision::CHECK_BDF_RTOL),
            agree(a_bdf)
        );
    } else {
        say!(
            "  reference: {} ended {}{}: no error is measured, no point ran",
            precision::reference_name(s.plan),
            reference.status,
            if reference.note.is_empty() {
                String::new()
            } else {
                format!(" ({})", reference.note)
            }
        );
    }
    if !s.measures.is_tip() && reference.ok() {
        let values: Vec<String> = s
            .measures
            .list()
            .into_iter()
            .filter(|&m| m != Measure::Tip)
            .map(|m| format!("{} {}", m.name(), s.reference.values.get(m)))
            .collect();
        if !values.is_empty() {
            say!("  reference values: {}", values.join(", "));
        }
    }
    let levels: Vec<f64> = (1..=12).map(|k| 10f64.powi(-k)).collect();
    let by_wall = precision::fastest(&s.rows, &levels, |pt| study::median(&pt.walls));
    let by_work = precision::fastest(&s.rows, &levels, |pt| pt.rhs_equiv() as f64);
    say!(
        "  {:>7}  {:<26} {:<26}",
        "error",
        "fastest (wall time)",
        "least work (RHS + JVP)"
    );
    for ((level, w), (_, k)) in by_wall.iter().zip(&by_work) {
        let show = |pt: &Option<&precision::Point>, cost: String| match pt {
            Some(pt) => format!("{} {} {} ({cost})", pt.method, pt.param_name, exp(pt.param)),
            None => "-".into(),
        };
        if w.is_none() && k.is_none() {
            continue;
        }
        say!(
            "  {:>7}  {:<26} {:<26}",
            exp(*level),
            show(
                w,
                format!("{:.2e} s", w.map_or(f64::NAN, |p| study::median(&p.walls)))
            ),
            show(k, format!("{}", k.map_or(0, precision::Point::rhs_equiv)))
        );
    }
    let skipped = s.skipped();
    if !skipped.is_empty() {
        say!("  not run for --budget: {}", skipped.join(", "));
    }
    if let Some(out) = out {
        let shown = echo_path(out.path());
        out.write(|w| w.write_all(s.csv().as_bytes()))?;
        eprintln!("wrote {} rows to {shown}", s.rows.len());
    }
    if let Some(path) = &a.plot {
        let label = format!("{} (n = {})", s.name, s.links);
        draw(path, plot::precision(&label, &s.csv(), path))?;
    }
    Ok(report_failures(&s.failures))
}

/// Prints the failures on one line (joined by "; ") and returns exit 1, or
/// exit 0 if none.
fn report_failures(failures: &[String]) -> ExitCode {
    if !failures.is_empty() {
        eprintln!("{}", failures.join("; "));
    }
    if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

pub fn stability(args: &StabilityArgs) -> Result<ExitCode, Error> {
    let a = &args.study;
    let scene = args
        .scene
        .load(&[("--out", a.out.as_deref()), ("--plot", a.plot.as_deref())])?;
    let options = stability::Options {
        methods: study::parse_methods("--methods", a.methods.as_deref())?,
        measures: Measures::parse_for("--measure", a.measure.as_deref(), &scene.prepare()?)?,
        vary: args.vary.as_deref().map(Vary::parse).transpose()?,
        budget: budget_of("--budget", a.budget)?,
        shard: a.shard.as_deref().map(Shard::parse).transpose()?,
        jobs: a.jobs.threads()?,
    };
    // Every row's scene is checked before any output is begun.
    let rows = stability::rows_of(&scene, options.vary.as_ref())?;
    check_plot(a.plot.as_deref(), a.out.as_deref())?;
    let out = a.out.as_deref().map(|o| begin("--out", o)).transpose()?;
    let total = stability::jobs(rows.len(), &options.methods).len();
    let bar = progress_bar(
        a.quiet,
        options.shard.map_or(total, |s| total.div_ceil(s.count)),
    );
    bar.set_message("cells");
    let s = stability::run_study(&scene, &options, None, &|| bar.inc(1))?;
    bar.finish_and_clear();
    say!(
        "{}: where each method fails (step budget {}, energy limit {} of M g L)",
        s.name,
        exp(stability::MAX_STEPS as f64),
        stability::ENERGY_LIMIT
    );
    for (m, verdict) in stability::verdicts(&s.cells, &options.methods) {
        say!("  {:>9}: {verdict}", m.as_str());
    }
    let skipped = s.skipped();
    if !skipped.is_empty() {
        say!("  not run for --budget: {}", skipped.join(", "));
    }
    if let Some(out) = out {
        let shown = echo_path(out.path());
        out.write(|w| w.write_all(s.csv().as_bytes()))?;
        eprintln!("wrote {} rows to {shown}", s.cells.len());
    }
    if let Some(path) = &a.plot {
        let title = format!("Where each method fails: {}", s.name);
        draw(path, plot::stability(&title, &s.csv(), path))?;
    }
    Ok(report_failures(&s.failures))
}

pub fn needs(args: &NeedsArgs) -> Result<ExitCode, Error> {
    needs::check_tol("--tol", args.tol)?;
    let links = fc_study::converge::parse_links(&args.links)?;
    let methods = match &args.methods {
        Some(m) => study::parse_methods("--methods", Some(m))?,
        None => needs::default_methods(),
    };
    let budget = budget_of("--budget", args.budget)?;
    let jobs = args.jobs.threads()?;
    let scene = args.scene.load(&[])?;
    let bar = progress_bar(args.quiet, 0);
    let options = needs::NeedsOptions {
        tol: args.tol,
        links,
        methods,
        jobs,
        measures: Measures::parse_for("--measure", args.measure.as_deref(), &scene.prepare()?)?,
    };
    let answer = Budget::run(budget, None, |b| {
        needs::run(&scene, &options, b, &|phase, done, total| {
            bar.set_message(phase.to_string());
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        })
    })?;
    bar.finish_and_clear();
    if args.json {
        say!("{}", answer.to_json());
    } else {
        say!("{answer}");
    }
    Ok(report_failures(&answer.failures()))
}

pub fn ensemble(args: &EnsembleArgs) -> Result<ExitCode, Error> {
    let mut options = ensemble::EnsembleOptions {
        members: args.members,
        spread: args.spread,
        seed: args.seed,
        jobs: args.jobs.threads()?,
        measures: Measures::TIP,
    };
    options.validate()?;
    let budget = budget_of("--budget", args.budget)?;
    if let Some(out) = &args.out {
        check_writable("--out", out)?;
    }
    let scene = args.scene.load(&[
        ("--out", args.out.as_deref()),
        ("--out-series", args.out_series.as_deref()),
    ])?;
    options.measures =
        Measures::parse_for("--measure", args.measure.as_deref(), &scene.prepare()?)?;
    let series_out = series_output(args, &scene, &options)?;
    let out = args.out.as_deref().map(|o| begin("--out", o)).transpose()?;
    let bar = progress_bar(args.quiet, options.members);
    let (result, series) = Budget::run(budget, None, |b| {
        let progress = |done, _| bar.set_position(done as u64);
        match series_out {
            None => ensemble::run(&scene, &options, b, &progress).map(|r| (r, None)),
            Some(_) => study::ensemble_series::run(&scene, &options, b, &progress)
                .map(|(r, s)| (r, Some(s))),
        }
    })?;
    bar.finish_and_clear();
    if let (Some(out), Some(series)) = (series_out, series) {
        let shown = echo_path(out.path());
        let text = series.csv();
        out.write(|w| w.write_all(text.as_bytes()))?;
        eprintln!(
            "wrote {} times of {} members to {shown}",
            series.t.len(),
            series.count
        );
    }
    if let Some(out) = out {
        let shown = echo_path(out.path());
        let text = result.csv();
        out.write(|w| w.write_all(text.as_bytes()))?;
        eprintln!("wrote {} rows to {shown}", result.members.len());
    }
    if args.json {
        say!("{}", result.to_json());
    } else {
        say_raw!("{result}");
    }
    Ok(report_failures(&result.failures()))
}

/// `ensemble --out-series`: checked (distinct from `--out`, writable, the
/// series' memory) and begun before any run.
fn series_output(
    args: &EnsembleArgs,
    scene: &fc_scene::Scene,
    options: &ensemble::EnsembleOptions,
) -> Result<Option<fc_scene::atomic::PendingOutput>, Error> {
    let Some(path) = args.out_series.as_deref() else {
        return Ok(None);
    };
    check_distinct(&[("--out", args.out.as_deref()), ("--out-series", Some(path))])?;
    check_writable("--out-series", path)?;
    study::ensemble_series::check_size("--out-series", scene, options)?;
    begin("--out-series", path).map(Some)
}

pub fn merge(args: &MergeArgs) -> Result<ExitCode, Error> {
    let inputs: Vec<(&str, &Path)> = args
        .shards
        .iter()
        .map(|p| ("SHARD.csv", p.as_path()))
        .collect();
    check_not_inputs(&[("--out", Some(&args.out))], &inputs)?;
    let texts = shard::read(&args.shards)?;
    let out = begin("--out", &args.out)?;
    let merged = shard::merge(&texts)?;
    // Records, not lines: a quoted cell may hold a line break.
    let rows = fc_csv::records(&merged).map_or(0, |r| r.len().saturating_sub(1));
    let shown = echo_path(out.path());
    out.write(|w| w.write_all(merged.as_bytes()))?;
    eprintln!("wrote {rows} rows from {} shards to {shown}", texts.len());
    Ok(ExitCode::SUCCESS)
}
