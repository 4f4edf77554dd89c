//! `falling-chain`: hanging-chain shapes and falling-chain runs from the
//! command line.
//!
//! Exit status: 0 on success, 1 if a run failed (its summary and partial
//! outputs are still written), 2 for bad input or an output that could not be
//! written, with a one-line message on stderr naming the field; 130 or 143
//! when stopped by SIGINT or SIGTERM (the temporary output file removed).
//!
//! Its files:
//! * `progress.rs`: `simulate --progress`: the time a long run has reached, on stderr.
//! * `stdout.rs`: Standard output as a pipe's reader may close it: `falling-chain ... | head -3` is an ordinary end.
//! * `study_commands.rs`: The study's commands: `precision`, `stability`, `needs`, `ensemble` and `merge` (the computations are the fc-study crate's).

use std::path::PathBuf;
use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::{Args, Parser, Subcommand};
use fc_batch::shard::Provenance;
use fc_scene::atomic::{begin, check_distinct, check_not_inputs, check_writable};
use fc_scene::error::{echo, echo_path, escape, number};
use fc_scene::summary::stiffness_hint_for_model;
use fc_scene::{csv, CatenaryReport, Error, RunSummary, Scene};
use stdout::{say, say_raw};

mod progress;
mod stdout;
mod study_commands;

#[derive(Parser)]
#[command(
    name = "falling-chain",
    version,
    about = "A chain of n rigid rods falling after one end of a hanging U is released."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The hanging chain between P0 and P1: the continuous catenary and,
    /// with --links, the exact equilibrium of that many rods.
    Catenary(CatenaryArgs),
    /// Run a scene file and print a summary of the run.
    Simulate(SimulateArgs),
    /// Run a scene once per value of one or more keys, in parallel; one
    /// summary row per run (never trajectories).
    Sweep(SweepArgs),
    /// Draw the snapshot figure of a scene (the chain coloured by time).
    Plot(PlotArgs),
    /// Write an animated GIF of a scene's fall.
    Animate(AnimateArgs),
    /// Run a scene at increasing numbers of rods n, with the continuum held
    /// fixed, and report the smallest n that agrees with the finest.
    ///
    /// Refinement: the total mass M = n m and the bending viscosity
    /// eta = r l of the scene are kept, so m = M/n and r = eta n/L (a joint's
    /// friction torque r (w_{i+1} - w_i) is the viscous bending moment
    /// r l d(omega)/ds). The damping rate r/(m l^2) then grows like n^4: large
    /// n is stiff. An n is adequate when its tip_speed_max (relative) and its
    /// tip end position (relative to L) differ from the finest n's by less
    /// than --tol, and so do those of every n between it and the finest.
    /// tip_speed_max is relative to max(|finest n's|, sqrt(g L)) (L per time
    /// unit at g = 0), so a speed that is zero at every level agrees.
    /// Exit 0 with the answer (or "refine further"), 1 if a run failed.
    Converge(ConvergeArgs),
    /// Run one or more scenes (or read runs written by simulate --out) and
    /// write one self-contained HTML page that plays, scrubs and overlays
    /// them: the chain to scale with the tip's path, the tip speed and the
    /// energy balance with a cursor, each run's summary. Exit 1 if a run
    /// failed (the page is still written, showing where it failed).
    View(ViewArgs),
    /// The work-precision diagram of a scene: error against work and wall
    /// time for every method across tolerances.
    ///
    /// Every method (or --methods) across tolerances (RK4 across steps), the error of the tip position
    /// at the end and of the maximum tip speed against a reference (DOPRI5,
    /// rtol 1e-13) checked by RK4 and BDF, the work and the wall time; prints
    /// how well the checks agree and the fastest method at each error level.
    /// Every bound of every run is checked before any run; --budget holds
    /// in every phase, the reference and its checks included. Exit 1 if
    /// the reference failed, was stopped by --budget or is not confirmed,
    /// or if every point that ran failed or none ran within --budget (what
    /// ran is still written).
    Precision(study_commands::PrecisionArgs),
    /// Where each method fails on a scene (or on each value of --vary).
    ///
    /// Per method and step or tolerance, the status, the time it stopped and the energy-balance error (rows:
    /// the scene, or one per value of --vary), and per method where it
    /// completes every row and where it fails, read off the cells. Exit 1
    /// if every run that ran failed, or none ran within --budget.
    Stability(study_commands::StabilityArgs),
    /// What a scene needs at --tol: rods, method and tolerance, physical
    /// terms.
    ///
    /// The smallest n (converge's ladder, on tip
    /// path, tip end and maximum tip speed), the fastest method and
    /// tolerance reaching --tol at that n (precision's lines), and which
    /// optional physical terms (joint friction) change those quantities by
    /// more than --tol. Exit 1 if no n or no method meets --tol, or if
    /// --budget stopped the phase that would find it (the line says which).
    Needs(study_commands::NeedsArgs),
    /// The scene run from perturbed starts, and its summary's statistics.
    ///
    /// Each of --members starts moves every rod angle by a number drawn
    /// uniformly from [-S, S] rad (--spread; the same draws on every
    /// machine, chosen by --seed): past a whip or a landing on a floor a
    /// single run is not reproducible, its ensemble's mean and standard
    /// error are. Prints the mean, standard deviation and error, minimum
    /// and maximum of the tip's largest speed and its time, the tip's end,
    /// the energy, the dissipated work, the floor's peak force and the
    /// steps over the members that ended ok. Exit 1 if a member failed or
    /// --budget stopped it.
    Ensemble(study_commands::EnsembleArgs),
    /// Join the tables of a sharded sweep, precision or stability.
    ///
    /// The --out tables of --shard I/N runs become the table of the whole
    /// run; merge refuses a missing or
    /// repeated run and shards of another scene or options.
    Merge(study_commands::MergeArgs),
}

/// What every scene-taking command (simulate, sweep, converge, plot,
/// animate) reads: the scene file and its `--set` overrides.
#[derive(Args)]
pub(crate) struct SceneArgs {
    /// The scene file (its keys: scenes/README.md).
    #[arg(value_name = "SCENE.toml")]
    scene: PathBuf,
    /// Set any scene key by its dotted path, e.g. chain.links=100,
    /// start.p1=[3.0,0.0], start.p1.0=2.5. Repeatable; applied in order,
    /// before the command's own flags (simulate's --method, --dt, ...,
    /// sweep's --vary, converge's refinement).
    #[arg(long = "set", value_name = "KEY=VALUE", allow_hyphen_values = true)]
    set: Vec<String>,
    #[command(flatten)]
    refine: RefineArgs,
}

impl SceneArgs {
    /// The scene file with the overrides applied, then refined, once the
    /// command's `outputs` (`(flag, path)`, `None`: not asked for) are known
    /// not to be the scene file itself.
    pub(crate) fn load(
        &self,
        outputs: &[(&'static str, Option<&std::path::Path>)],
    ) -> Result<Scene, Error> {
        check_not_inputs(outputs, &[("SCENE.toml", &self.scene)])?;
        self.refine
            .apply(Scene::load(&self.scene)?.with_overrides(&self.set)?)
    }
}

/// `--refine N`: the scene cut into N rods at fixed continuum.
#[derive(Args)]
pub(crate) struct RefineArgs {
    /// Cut the chain into N rods (1..=1000000) at fixed continuum, after
    /// every --set: total mass, length, the bending viscosity r l, EA, EI
    /// and the tip mass kept (so chain.mass and chain.damping, which are
    /// per rod, change), as converge refines. chain.links=N alone is not a
    /// refinement: it keeps the per-rod mass and friction. An angles start
    /// refines only if its angles repeat a pattern (a zigzag), continued.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = parse_rods)]
    refine: Option<usize>,
}

impl RefineArgs {
    /// `scene` refined to `--refine` rods, or as it is.
    pub(crate) fn apply(&self, scene: Scene) -> Result<Scene, Error> {
        match self.refine {
            None => Ok(scene),
            Some(n) => {
                fc_scene::refine::check_links("--refine", n)?;
                scene.refined(n)
            }
        }
    }
}

/// `--jobs` of the commands that run scenes in parallel (sweep, converge).
#[derive(Args)]
pub(crate) struct JobsArgs {
    /// Worker threads, 1..=256 (default: all cores, at most 256); never
    /// more threads than runs.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = parse_jobs)]
    jobs: Option<usize>,
}

impl JobsArgs {
    /// The number of threads: `--jobs` (1..=256), else every core.
    pub(crate) fn threads(&self) -> Result<usize, Error> {
        match self.jobs {
            Some(n) => fc_batch::sweep::check_jobs("--jobs", n),
            None => Ok(std::thread::available_parallelism()
                .map_or(1, |n| n.get())
                .min(fc_batch::sweep::MAX_JOBS)),
        }
    }
}

#[derive(Args)]
struct ConvergeArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Relative tolerance on tip_speed_max and on the tip end (over L), in
    /// [1e-12, 1).
    #[arg(long, value_name = "TOL", allow_negative_numbers = true)]
    tol: f64,
    /// The numbers of rods to run, N1,N2,... (the largest is the reference;
    /// 2 to 32 different numbers, each in 2..=1000000).
    #[arg(
        long,
        value_name = "N1,N2,...",
        default_value = "25,50,100,200,400",
        allow_hyphen_values = true
    )]
    links: String,
    /// Integration method of every run. The default is DOPRI5 because the
    /// scaled damping makes a scene's fixed-step RK4 unstable at large n.
    #[arg(long, value_name = "M", default_value = "dopri5")]
    method: String,
    /// Relative tolerance of adaptive runs (atol = rtol / 100), in
    /// [1e-14, 0.1]; default: the scene's run.rtol.
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    rtol: Option<f64>,
    #[command(flatten)]
    jobs: JobsArgs,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
    /// What the levels must agree on, M1,M2,...: tip (the default: the
    /// largest tip speed and the tip's end), tip_speed_max,
    /// pivot_force_max, tension_max, floor_force_max, floor_reading,
    /// dissipated; the pivot's force and the tensions are tracked only
    /// when measured.
    #[arg(long, value_name = "M1,M2,...")]
    measure: Option<String>,
}

#[derive(Args)]
struct ViewArgs {
    /// Scene files to run, each with the --set overrides (with --method,
    /// once per method); with --from, none are needed. At most 8 runs in all.
    #[arg(value_name = "SCENE.toml")]
    scenes: Vec<PathBuf>,
    /// Set any scene key of every scene by its dotted path (as simulate).
    #[arg(long = "set", value_name = "KEY=VALUE", allow_hyphen_values = true)]
    set: Vec<String>,
    #[command(flatten)]
    refine: RefineArgs,
    /// Run every scene with each of these methods, M1,M2,... (overrides
    /// run.method), e.g. to overlay rk4 and dopri5.
    #[arg(long, value_name = "M1,M2,...")]
    method: Option<String>,
    /// A run already written by simulate --out, shown without running it
    /// again (repeatable). It may carry joint forces as extra columns
    /// tension_0..tension_n and shear_0..shear_n. A run on a floor (its CSV
    /// has floor_x, floor_y, landed_weight) is refused: its rods stretch,
    /// which a CSV does not hold; view its scene instead.
    #[arg(long, value_name = "RUN.csv")]
    from: Vec<PathBuf>,
    /// Carry each run's joint forces (tension and shear at the n + 1 joints,
    /// as simulate --forces writes them) and colour the chain by them. The
    /// page's data stay within 1.8 MB, each run's first and last frame
    /// within its share: with forces, at most 3511 rods per run at 8 runs
    /// (7027 at 4), else refused before any run.
    #[arg(long)]
    forces: bool,
    /// Open the page at time T (the sample nearest it), in [0, the runs'
    /// last time]; a `#t=T` at the end of the page's URL does the same,
    /// and the page keeps the time shown there as it is scrubbed.
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    at: Option<f64>,
    /// The page, FILE.html (ending in `.html` exactly: not `.htm`, not
    /// `.HTML`).
    #[arg(short = 'o', long = "out", value_name = "FILE.html")]
    out: PathBuf,
}

#[derive(Args)]
struct PlotArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// The figure: FILE.png or FILE.svg.
    #[arg(short = 'o', long = "out", value_name = "FILE.png|FILE.svg")]
    out: PathBuf,
    /// Number of snapshots drawn (spread evenly over the run), 1..=10000.
    #[arg(long, value_name = "N", default_value_t = 50, allow_negative_numbers = true,
          value_parser = parse_snapshots)]
    snapshots: usize,
}

#[derive(Args)]
struct AnimateArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// The animation, FILE.gif.
    #[arg(short = 'o', long = "out", value_name = "FILE.gif")]
    out: PathBuf,
    /// Frames per second (1..=50).
    #[arg(long, value_name = "F", default_value_t = 20, allow_negative_numbers = true,
          value_parser = parse_fps)]
    fps: u32,
    /// Length of the animation in seconds of playback, in (0, 600] (sets
    /// the frame count).
    #[arg(
        long,
        value_name = "S",
        default_value_t = 5.0,
        allow_negative_numbers = true
    )]
    seconds: f64,
}

#[derive(Args)]
struct SweepArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// KEY=START:STOP:COUNT (COUNT values, ends included) or KEY=V1,V2,...
    /// for any scene key by dotted path (array elements by index:
    /// start.p1.0). Several --vary make the Cartesian product, of at most
    /// 1000000 runs; each key at most once.
    #[arg(
        long,
        value_name = "KEY=VALUES",
        required = true,
        allow_hyphen_values = true
    )]
    vary: Vec<String>,
    #[command(flatten)]
    jobs: JobsArgs,
    /// Run only runs I, I+N, I+2N, ... of the sweep (0 <= I < N), for
    /// splitting a sweep across machines; rows keep their run number.
    #[arg(long, value_name = "I/N", allow_hyphen_values = true)]
    shard: Option<String>,
    /// Write the rows as CSV (run, varied keys, then the summary fields of
    /// simulate --json) instead of printing them.
    #[arg(long, value_name = "FILE.csv")]
    out: Option<PathBuf>,
    /// Print a JSON array of row objects instead of CSV.
    #[arg(long)]
    json: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
}

#[derive(Args)]
struct CatenaryArgs {
    /// First anchor P0 (the pivot), coordinates in [-1e150, 1e150].
    #[arg(long, value_name = "X,Y", value_parser = parse_point, allow_hyphen_values = true, default_value = "0,0")]
    p0: [f64; 2],
    /// Second anchor P1 (where the free end is held), coordinates in
    /// [-1e150, 1e150].
    #[arg(long, value_name = "X,Y", value_parser = parse_point, allow_hyphen_values = true)]
    p1: [f64; 2],
    /// Chain length L, in [1e-150, 1e150] (must exceed |P1 - P0|).
    #[arg(long, value_name = "L", allow_negative_numbers = true)]
    length: f64,
    /// Also solve the exact equilibrium of N rigid rods (1..=1000000, the
    /// scenes' cap on chain.links).
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = parse_rods)]
    links: Option<usize>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct SimulateArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Integration method (overrides run.method).
    #[arg(long, value_name = "M")]
    method: Option<String>,
    /// Fixed step (overrides run.dt), in [t_end / max_steps, t_end] (the
    /// run's run.t_end and run.max_steps).
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    dt: Option<f64>,
    /// Relative tolerance (overrides run.rtol), in [1e-14, 0.1].
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    rtol: Option<f64>,
    /// Absolute tolerance (overrides run.atol), in [1e-20, 1].
    #[arg(long, value_name = "A", allow_negative_numbers = true)]
    atol: Option<f64>,
    /// End time (overrides run.t_end), in (0, inf): any finite number > 0.
    #[arg(long = "t-end", value_name = "T", allow_negative_numbers = true)]
    t_end: Option<f64>,
    /// Write every sample as CSV: t, tip_x, tip_y, tip_vx, tip_vy, energy,
    /// dissipated, phi_1..phi_n; with a floor, then its total force
    /// floor_x, floor_y (what a scale under the chain reads) and
    /// landed_weight (the weight resting on it).
    #[arg(long, value_name = "FILE.csv")]
    out: Option<PathBuf>,
    /// Write the joint forces at every sample as CSV: t, then for each
    /// joint k = 0 (the pivot) .. n (the free tip) its tension_k and
    /// shear_k in the frame of the rod after it (tension > 0 pulls that rod
    /// back toward the pivot; force units). With a floor, then the floor's
    /// force at each joint, floor_x_k and floor_y_k (scene axes), and its
    /// total floor_x, floor_y (what a scale under the chain reads).
    #[arg(long, value_name = "FILE.csv")]
    forces: Option<PathBuf>,
    /// Print one JSON object instead of a readable summary.
    #[arg(long)]
    json: bool,
    /// Print the time reached on stderr every SECONDS of wall time, in
    /// 0.01..=3600 (default 5), for a long run; on by default when stderr
    /// is a terminal. Never on stdout.
    #[arg(
        long,
        value_name = "SECONDS",
        num_args = 0..=1,
        default_missing_value = "5",
        allow_negative_numbers = true
    )]
    progress: Option<f64>,
}

/// The most snapshots `plot` draws.
const MAX_SNAPSHOTS: usize = 10_000;

/// Parses a whole number for a flag whose range is `lo..=hi`: text that
/// is no whole number (`-1`, `1e300`, `nan`) is refused with the range
/// (clap names the flag); a number out of the range is refused by the
/// command's own check, as `--jobs: must be an integer in 1..=256`.
fn int_in(text: &str, lo: usize, hi: usize) -> Result<usize, String> {
    text.trim()
        .parse::<usize>()
        .map_err(|_| format!("must be an integer in {lo}..={hi}"))
}

fn parse_jobs(text: &str) -> Result<usize, String> {
    int_in(text, 1, fc_batch::sweep::MAX_JOBS)
}

fn parse_snapshots(text: &str) -> Result<usize, String> {
    int_in(text, 1, MAX_SNAPSHOTS)
}

fn parse_fps(text: &str) -> Result<u32, String> {
    int_in(text, 1, 50)
        .and_then(|n| u32::try_from(n).map_err(|_| "must be an integer in 1..=50".to_string()))
}

fn parse_rods(text: &str) -> Result<usize, String> {
    int_in(text, 1, 1_000_000)
}

/// `e` named by the flag the user gave for its field: `--dt` for `run.dt`
/// when `--dt` set it (`given`: the flags given, as `(field, flag)`); an
/// error about another `run.*` bound that `--t-end` moves (the samples,
/// RK4's smallest step) is said to be about `--t-end` when it was given.
fn named_by_flag(e: Error, given: &[(&str, &str)]) -> Error {
    let Error::Field { field, message } = e else {
        return e;
    };
    if let Some((_, flag)) = given.iter().find(|(path, _)| *path == field) {
        return Error::field(*flag, message);
    }
    // A bound of the run section (its section name, not a key) that
    // follows from --t-end names the flag.
    let in_run = field.split('.').next() == Some("run");
    if in_run && given.iter().any(|(_, f)| *f == "--t-end") {
        return Error::field("--t-end", format!("{field}: {message}"));
    }
    Error::Field { field, message }
}

/// Parses `X,Y`.
fn parse_point(text: &str) -> Result<[f64; 2], String> {
    let bad = || format!("expected two numbers X,Y (got '{}')", echo(text));
    let (x, y) = text.split_once(',').ok_or_else(bad)?;
    let x = x.trim().parse::<f64>().map_err(|_| bad())?;
    let y = y.trim().parse::<f64>().map_err(|_| bad())?;
    Ok([x, y])
}

fn catenary(args: &CatenaryArgs) -> Result<ExitCode, Error> {
    let report = CatenaryReport::compute(
        args.p0,
        args.p1,
        args.length,
        args.links,
        &CatenaryReport::CLI_NAMES,
    )?;
    if args.json {
        say!("{}", report.to_json());
    } else {
        say!("{report}");
    }
    Ok(ExitCode::SUCCESS)
}

fn simulate(args: &SimulateArgs) -> Result<ExitCode, Error> {
    let mut scene = args.scene.load(&[
        ("--out", args.out.as_deref()),
        ("--forces", args.forces.as_deref()),
    ])?;
    let flags = [
        ("run.method", args.method.clone().map(toml::Value::String)),
        ("run.dt", args.dt.map(toml::Value::Float)),
        ("run.rtol", args.rtol.map(toml::Value::Float)),
        ("run.atol", args.atol.map(toml::Value::Float)),
        ("run.t_end", args.t_end.map(toml::Value::Float)),
    ];
    // The numeric flags' errors name the flag; --method keeps its key's.
    let names = [
        ("run.method", "run.method"),
        ("run.dt", "--dt"),
        ("run.rtol", "--rtol"),
        ("run.atol", "--atol"),
        ("run.t_end", "--t-end"),
    ];
    let mut given = vec![];
    for ((path, value), (_, flag)) in flags.into_iter().zip(names) {
        if let Some(value) = value {
            given.push((path, flag));
            scene = scene
                .with_value(path, value)
                .map_err(|e| named_by_flag(e, &given))?;
        }
    }
    let run = scene.prepare().map_err(|e| named_by_flag(e, &given))?;
    if let Some(dt) = args.dt {
        // A step for any method, not only where RK4 takes it.
        let (t_end, max_steps) = (run.options.t_end, run.options.max_steps);
        let lo = t_end / max_steps as f64;
        if !(dt.is_finite() && dt >= lo && dt <= t_end) {
            return Err(Error::field(
                "--dt",
                format!(
                    "must be a step in [{lo:e}, run.t_end = {t_end}] (run.t_end / \
                     run.max_steps to run.t_end; got {dt})"
                ),
            ));
        }
    }
    let every = match args.progress {
        Some(s) if s.is_finite() && (0.01..=3600.0).contains(&s) => Some(s),
        Some(s) => {
            return Err(Error::field(
                "--progress",
                format!(
                    "must be a number of seconds in 0.01..=3600 (got {})",
                    number(s)
                ),
            ))
        }
        None => std::io::IsTerminal::is_terminal(&std::io::stderr()).then_some(5.0),
    };
    check_distinct(&[
        ("--out", args.out.as_deref()),
        ("--forces", args.forces.as_deref()),
    ])?;
    let out = args.out.as_deref().map(|o| begin("--out", o)).transpose()?;
    let forces = args
        .forces
        .as_deref()
        .map(|o| begin("--forces", o))
        .transpose()?;
    let traj = match every {
        None => run.solve()?,
        Some(every) => progress::solve_showing(&run, every)?,
    };
    let summary = RunSummary::from_trajectory(scene.name(), &traj);
    if args.json {
        say!("{}", summary.to_json());
    } else {
        say!("{summary}");
    }
    if let Some(hint) = stiffness_hint_for_model([&summary], run.report.is_some()) {
        eprintln!("{hint}");
    }
    if let Some(out) = out {
        out.write(|w| csv::write_trajectory(w, &traj))?;
    }
    if let Some(forces) = forces {
        forces.write(|w| csv::write_forces(w, &traj))?;
    }
    Ok(if summary.is_ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn sweep(args: &SweepArgs) -> Result<ExitCode, Error> {
    use fc_batch::shard::Shard;
    use fc_batch::sweep::{self, Vary};
    let scene = args.scene.load(&[("--out", args.out.as_deref())])?;
    let vary = args
        .vary
        .iter()
        .map(|v| Vary::parse(v))
        .collect::<Result<Vec<_>, _>>()?;
    let shard = args.shard.as_deref().map(Shard::parse).transpose()?;
    let jobs = args.jobs.threads()?;
    sweep::grid_size(&vary)?;
    let out = args.out.as_deref().map(|o| begin("--out", o)).transpose()?;
    // The grid's size, its keys and every run's scene are checked by
    // `sweep::run` before any run starts.
    let bar = if args.quiet {
        indicatif::ProgressBar::hidden()
    } else {
        let bar = indicatif::ProgressBar::new(0);
        // The template is a constant; were it refused, the default style stays.
        match indicatif::ProgressStyle::with_template(
            "{bar:40} {pos}/{len} runs, {elapsed} ({eta} left)",
        ) {
            Ok(style) => bar.with_style(style),
            Err(_) => bar,
        }
    };
    let rows = sweep::run(&scene, &vary, shard, jobs, &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    })?;
    bar.finish_and_clear();
    let report = scene.prepare().is_ok_and(|p| p.report.is_some());
    if let Some(hint) = stiffness_hint_for_model(rows.iter().map(|r| &r.summary), report) {
        eprintln!("{hint}");
    }
    let failed = rows.iter().filter(|r| !r.summary.is_ok()).count();
    // Every row ends with the sweep's provenance (its number of runs and
    // the hash of its scene and values), which `merge` checks.
    let provenance = sweep::provenance(&scene, &vary)?;
    let csv_text = || {
        let mut text = sweep::csv_header(&vary);
        text.push_str(&Provenance::header_suffix());
        text.push('\n');
        for r in &rows {
            text.push_str(&sweep::csv_row(r));
            text.push_str(&provenance.cells());
            text.push('\n');
        }
        text
    };
    if args.json {
        let objects: Vec<serde_json::Value> = rows
            .iter()
            .map(|r| {
                let values: serde_json::Map<String, serde_json::Value> = vary
                    .iter()
                    .zip(&r.values)
                    .map(|(v, x)| (v.key.clone(), serde_json::to_value(x).unwrap_or_default()))
                    .collect();
                serde_json::json!({ "run": r.run, "values": values, "summary": r.summary })
            })
            .collect();
        say!("{}", serde_json::Value::Array(objects));
    } else if args.out.is_none() {
        say_raw!("{}", csv_text());
    }
    if let Some(out) = out {
        let shown = echo_path(out.path());
        out.write(|w| w.write_all(csv_text().as_bytes()))?;
        eprintln!("wrote {} rows to {shown}", rows.len());
    }
    if failed > 0 {
        eprintln!("{failed} of {} runs failed (see their status)", rows.len());
        return Ok(ExitCode::FAILURE);
    }
    Ok(ExitCode::SUCCESS)
}

/// The most joint positions a figure or animation draws (frames times
/// rods): 10^7 points, about 160 MB of coordinates and seconds of drawing.
const MAX_DRAWN_POINTS: usize = 10_000_000;

/// Checks that `frames` drawings of the scene's chain stay within
/// [`MAX_DRAWN_POINTS`]; the error names `flag` and its largest value here.
fn check_drawn_points(scene: &Scene, frames: usize, flag: &'static str) -> Result<(), Error> {
    let links = scene.chain()?.links();
    let points = frames.saturating_mul(links.saturating_add(1));
    if points > MAX_DRAWN_POINTS {
        return Err(Error::field(
            flag,
            format!(
                "{frames} frames of {links} rods are {points} points to draw, more than \
                 {MAX_DRAWN_POINTS}: at most {} frames at this chain.links",
                MAX_DRAWN_POINTS / (links + 1)
            ),
        ));
    }
    Ok(())
}

/// Runs `scene` with `frames` evenly spaced samples; returns the trajectory
/// and the release point. A failed run is drawn up to where it got.
fn run_for_drawing(
    scene: &Scene,
    frames: usize,
) -> Result<(chain_ode::Trajectory, chain_ode::Vec2), Error> {
    let mut run = scene.prepare()?;
    run.options.output_dt = Some(run.options.t_end / frames.max(1) as f64);
    let release = scene
        .start()
        .release_point(&run.chain)
        .map_err(Error::from)?;
    Ok((run.solve()?, release))
}

fn figure_error(what: &str, path: &std::path::Path, e: figures::FigureError) -> Error {
    Error::field(what, format!("cannot write '{}': {e}", echo_path(path)))
}

fn plot(args: &PlotArgs) -> Result<ExitCode, Error> {
    let ext = args.out.extension().and_then(|e| e.to_str()).unwrap_or("");
    if !matches!(ext.to_ascii_lowercase().as_str(), "png" | "svg") {
        return Err(Error::field(
            "--out",
            format!("must end in .png or .svg (got '{}')", echo_path(&args.out)),
        ));
    }
    if !(1..=MAX_SNAPSHOTS).contains(&args.snapshots) {
        return Err(Error::field(
            "--snapshots",
            format!(
                "must be an integer in 1..={MAX_SNAPSHOTS} (got {})",
                args.snapshots
            ),
        ));
    }
    let scene = args.scene.load(&[("--out", Some(&args.out))])?;
    check_drawn_points(&scene, args.snapshots, "--snapshots")?;
    check_writable("--out", &args.out)?;
    draw_scene(&scene, &args.out, args.snapshots, "snapshots", |fig| {
        figures::chain_snapshots_to(fig, &args.out)
    })
}

/// Runs `scene` for drawing, draws it with `draw` and reports what it wrote;
/// exit 1 if the run failed (what it computed is still drawn).
fn draw_scene(
    scene: &Scene,
    out: &std::path::Path,
    frames: usize,
    noun: &str,
    draw: impl FnOnce(&figures::ChainSnapshots) -> Result<(), figures::FigureError>,
) -> Result<ExitCode, Error> {
    let (traj, release) = run_for_drawing(scene, frames)?;
    let title = format!(
        "{} (n = {}, {})",
        scene.name(),
        traj.chain().links(),
        traj.method
    );
    let fig = fc_study::render::snapshots(&title, &traj, None, Some(release));
    draw(&fig).map_err(|e| figure_error("--out", out, e))?;
    eprintln!(
        "wrote {} ({} {noun}, status {})",
        echo_path(out),
        fig.frames.len(),
        traj.status
    );
    Ok(if traj.status.is_ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn animate(args: &AnimateArgs) -> Result<ExitCode, Error> {
    if !args
        .out
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gif"))
    {
        return Err(Error::field(
            "--out",
            format!("must end in .gif (got '{}')", echo_path(&args.out)),
        ));
    }
    if !(1..=50).contains(&args.fps) {
        return Err(Error::field(
            "--fps",
            format!("must be an integer in 1..=50 (got {})", args.fps),
        ));
    }
    if !(args.seconds.is_finite() && args.seconds > 0.0 && args.seconds <= 600.0) {
        return Err(Error::field(
            "--seconds",
            format!(
                "must be a number in (0, 600] (got {})",
                number(args.seconds)
            ),
        ));
    }
    let scene = args.scene.load(&[("--out", Some(&args.out))])?;
    check_writable("--out", &args.out)?;
    let frames = ((args.seconds * f64::from(args.fps)).round() as usize).max(2);
    check_drawn_points(&scene, frames, "--seconds")?;
    draw_scene(&scene, &args.out, frames, "frames", |fig| {
        figures::chain_animation(fig, &args.out, args.fps)
    })
}

fn view(args: &ViewArgs) -> Result<ExitCode, Error> {
    use fc_viewer::{self as viewer, ViewRun, DATA_BUDGET_BYTES};
    viewer::check_page_path("--out", &args.out)?;
    let inputs: Vec<(&str, &std::path::Path)> = (args.scenes.iter().map(|p| ("SCENE.toml", p)))
        .chain(args.from.iter().map(|p| ("--from", p)))
        .map(|(role, p)| (role, p.as_path()))
        .collect();
    check_not_inputs(&[("--out", Some(&args.out))], &inputs)?;
    let methods: Vec<Option<&str>> = match &args.method {
        None => vec![None],
        Some(list) => list.split(',').map(|m| Some(m.trim())).collect(),
    };
    let count = args
        .scenes
        .len()
        .saturating_mul(methods.len())
        .saturating_add(args.from.len());
    viewer::check_run_count("SCENE.toml/--from", count)?;
    // Every scene is checked, and every CSV read, before any run starts.
    let mut prepared = Vec::new();
    for path in &args.scenes {
        let base = args
            .refine
            .apply(Scene::load(path)?.with_overrides(&args.set)?)?;
        for method in &methods {
            let scene = match method {
                Some(m) => base.with_value("run.method", toml::Value::String((*m).to_string()))?,
                None => base.clone(),
            };
            let run = scene.prepare()?;
            viewer::check_chain("chain.links", &run.chain)?;
            // Its first and last frame must fit its share of the page.
            viewer::check_fits(
                if args.forces {
                    "--forces"
                } else {
                    "chain.links"
                },
                run.chain.links(),
                if args.forces { 2 } else { 0 },
                run.chain.rods().is_some(),
                DATA_BUDGET_BYTES / count,
            )?;
            let label = match method {
                Some(m) if methods.len() > 1 => format!("{} ({m})", scene.name()),
                _ => scene.name().to_string(),
            };
            prepared.push((label, scene, run));
        }
    }
    let budget = DATA_BUDGET_BYTES / count;
    let from = args
        .from
        .iter()
        .map(|p| fc_viewer::run_csv::read_run_csv(p, budget))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(at) = args.at {
        // The longest run's last time: its t_end, or a CSV's last row.
        let last = prepared
            .iter()
            .map(|(_, _, run)| run.options.t_end)
            .chain(from.iter().filter_map(|r| r.t.last().copied()))
            .fold(0.0, f64::max);
        viewer::check_at("--at", at, last)?;
    }
    let out = begin("--out", &args.out)?;
    let mut runs = Vec::with_capacity(count);
    let mut failed = 0;
    for (label, scene, run) in prepared {
        let traj = run.solve()?;
        let summary = RunSummary::from_trajectory(scene.name(), &traj);
        failed += usize::from(!summary.is_ok());
        runs.push(ViewRun::from_trajectory(
            &label,
            &traj,
            &summary,
            budget,
            args.forces,
        ));
    }
    runs.extend(from);
    // Two runs of one label are told apart by their number.
    for k in 1..runs.len() {
        if runs[..k].iter().any(|r| r.label == runs[k].label) {
            runs[k].label = format!("{} #{}", runs[k].label, k + 1);
        }
    }
    let title = runs
        .iter()
        .map(|r| r.label.as_str())
        .collect::<Vec<_>>()
        .join(" vs ");
    // The data within the page's cap: halved where the estimate was short,
    // refused (no file) where the first and last frames alone exceed it.
    let page = viewer::fitted_page_at("--out", &title, &mut runs, args.at)?;
    let shown = echo_path(out.path());
    out.write(|w| w.write_all(page.as_bytes()))?;
    let thinned = runs.iter().filter(|r| r.stride > 1).count();
    eprintln!(
        "wrote {shown} ({} run{}, {} bytes{})",
        runs.len(),
        if runs.len() == 1 { "" } else { "s" },
        page.len(),
        if thinned > 0 {
            format!(", {thinned} thinned")
        } else {
            String::new()
        }
    );
    if failed > 0 {
        eprintln!(
            "{failed} of {} runs failed (see their status on the page)",
            runs.len()
        );
        return Ok(ExitCode::FAILURE);
    }
    Ok(ExitCode::SUCCESS)
}

fn converge(args: &ConvergeArgs) -> Result<ExitCode, Error> {
    use fc_study::converge;
    converge::check_tol(args.tol)?;
    if let Some(r) = args.rtol {
        converge::check_rtol("--rtol", r)?;
    }
    let links = converge::parse_links(&args.links)?;
    let jobs = args.jobs.threads()?;
    let scene = args.scene.load(&[])?;
    let measures = fc_study::measure::Measures::parse_for(
        "--measure",
        args.measure.as_deref(),
        &scene.prepare()?,
    )?;
    let report = converge::run_measured(
        &scene,
        &links,
        args.tol,
        Some(&args.method),
        args.rtol,
        jobs,
        &|done, total| eprintln!("converge: {done} of {total} runs done"),
        measures,
    )?;
    if args.json {
        say!("{}", report.to_json());
    } else {
        say!("{report}");
    }
    if let Some(hint) = &report.stiffness_hint {
        eprintln!("{hint}");
    }
    Ok(if report.all_ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Clap's message on one line, without the usage and help hints.
fn one_line(message: &str) -> String {
    let line = message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("Usage:") && !l.starts_with("For more"))
        .collect::<Vec<_>>()
        .join(" ");
    let line = escape(&line);
    // Clap echoes a bad value whole: cut a very long one in the middle.
    let count = line.chars().count();
    if count <= 600 {
        return line;
    }
    let head: String = line.chars().take(480).collect();
    let tail: String = line.chars().skip(count - 100).collect();
    format!("{head} … ({count} characters) … {tail}")
}

/// On SIGINT or SIGTERM: remove the hidden temporary output files in
/// progress and exit 128 + the signal (130, 143), as a shell does. The
/// handler is a thread that waits for the signal (signal-hook), so it may
/// lock and remove files; it holds the list's lock while the process ends,
/// so that no new temporary file is started meanwhile.
fn remove_temporaries_on_signals() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
        return;
    };
    let _ = std::thread::Builder::new()
        .name("signals".into())
        .spawn(move || {
            if let Some(signal) = signals.forever().next() {
                let _held = fc_atomic::remove_temporaries();
                std::process::exit(128 + signal);
            }
        });
}

fn main() -> ExitCode {
    remove_temporaries_on_signals();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // --help, --version
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // No subcommand: the help, as a usage error.
            let _ = e.print();
            return ExitCode::from(2);
        }
        Err(e) => {
            eprintln!("{}", one_line(&e.render().to_string()));
            return ExitCode::from(2);
        }
    };
    let result = match &cli.command {
        Command::Catenary(args) => catenary(args),
        Command::Simulate(args) => simulate(args),
        Command::Sweep(args) => sweep(args),
        Command::Plot(args) => plot(args),
        Command::Animate(args) => animate(args),
        Command::Converge(args) => converge(args),
        Command::View(args) => view(args),
        Command::Precision(args) => study_commands::precision(args),
        Command::Stability(args) => study_commands::stability(args),
        Command::Needs(args) => study_commands::needs(args),
        Command::Ensemble(args) => study_commands::ensemble(args),
        Command::Merge(args) => study_commands::merge(args),
    };
    result.unwrap_or_else(|e| {
        eprintln!("error: {e}");
        ExitCode::from(2)
    })
}
