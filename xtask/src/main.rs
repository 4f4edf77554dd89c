#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "the build tool: a failed figure run stops the build with its message"
)]
//! `cargo xtask figures`: regenerates every figure of the registry
//! (`registry.rs`, the catalogue of `docs/figures.md`) into `figures/`, its
//! data into `figures/data/`, the animations, `figures/README.md` and
//! the papers (`paper/paper.md`, `paper/methods.md`, `paper/supplement.md`). `cargo xtask paper
//! [--check]` fills the papers alone.
//!
//! Its files:
//! * `ctx.rs`: What a figure's `compute` and `draw` may use: the workspace's folders, the one scene loader, the scene runs the report's figures share, and reading and writing `figures/data/`.
//! * `data.rs`: `figures/data/`: the CSV files every figure is drawn from and the paper quotes, read as a `Table` and written in the study's formats (`fc_csv::format`) ...
//! * `registry.rs`: Every figure, one entry each: the one place to add a figure.
//! * `report.rs`: The kinds of the report's figures (fig01 to fig12), each a `Make` with its parameters.
//! * `report_accuracy.rs`: `report-scenes-accuracy`: is each report figure drawn from a converged run? The report scenes with dynamics (and the folded chain) ...
//! * `report_model.rs`: The report's own model as a control (`model.report = true`): its figures `rm03` to `rm12` and the runs that measure each erratum.
//! * `runs.rs`: The scene runs the report's figures share, each made once, in parallel (`fc_paper_figures::scene_run`), and the summary of them the paper quotes (`scenes.csv`).
//! * `study/`: The study's figures (`docs/figures.md`, "The study's figures"), one file per subject: speed against accuracy (`precision_*`: work-precision, stability map, stiffness ...
//! * `timing.rs`: Wall times, kept apart from the data that reproduce to the byte ...
//! * `viewer_shot.rs`: `viewer-peak`: a screenshot of `falling-chain view`'s page for the folded chain, at the instant of its peak tip speed, for the README.

mod ctx;
mod data;
mod registry;
mod report;
mod report_accuracy;
mod report_model;
mod runs;
mod study;
mod timing;
mod viewer_shot;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use paper::catalogue;
use rayon::prelude::*;

use ctx::{write_text, Ctx};
use registry::{Figure, Timing, FIGURES};

/// The workspace's automation: the figures, the paper and the scene keys.
#[derive(clap::Parser)]
#[command(name = "cargo xtask", bin_name = "cargo xtask")]
enum Command {
    /// Compute every figure's data into figures/data/ (reading the committed
    /// wall times, never rewriting them), draw every figure from its data,
    /// make the animations, write figures/README.md and the papers (paper/paper.md, paper/methods.md, paper/supplement.md).
    Figures(Args),
    /// Fill the papers' templates (paper/paper.tmpl.md, paper/methods.tmpl.md, paper/supplement.tmpl.md) from figures/data/; fail on a typed decimal paper/inputs.csv does not list.
    Paper {
        /// Fail if paper/paper.md, paper/methods.md or paper/supplement.md is stale.
        #[arg(long, conflicts_with = "pdf")]
        check: bool,
        /// Then typeset paper/*.md as paper/*.pdf with pandoc and headless
        /// Chromium (apt-get install pandoc chromium); the PDFs are not
        /// committed.
        #[arg(long)]
        pdf: bool,
    },
    /// Write the key table of scenes/README.md from the scene schema.
    SceneKeys {
        /// Fail if the table is stale.
        #[arg(long)]
        check: bool,
    },
}

#[derive(clap::Args)]
struct Args {
    /// Only these figures (and `anim` for the animations); the paper and
    /// figures/data/scenes.csv are then left as they are.
    #[arg(long, num_args = 1.., value_name = "ID")]
    only: Vec<String>,
    /// No animations.
    #[arg(long = "no-anim", action = clap::ArgAction::SetFalse)]
    anim: bool,
    /// Draw every figure from the data in figures/data/ as it is, computing
    /// nothing (no animations: they are made from runs).
    #[arg(long, conflicts_with = "timings")]
    draw_only: bool,
    /// Also measure the wall times, and rewrite the timing files
    /// (figures/data/*-timing.csv, machine-timing.csv, and with no --only
    /// run-timing.csv).
    #[arg(long)]
    timings: bool,
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace")
        .to_path_buf()
}

/// A figure and what its `compute` wrote (or why it failed).
type Computed<'a> = (&'a Figure, Result<Vec<String>, String>);

fn figures_cmd(args: Args) -> Result<(), String> {
    let clock = Instant::now();
    let c_all = timing::cpu_seconds();
    let root = root();
    let jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut ctx = Ctx::new(&root, jobs, args.timings);
    let anim_dir = ctx.out.join("anim");
    fs::create_dir_all(&ctx.data).map_err(|e| e.to_string())?;
    fs::create_dir_all(&anim_dir).map_err(|e| e.to_string())?;
    let all = args.only.is_empty();
    let selected: Vec<&Figure> = FIGURES
        .iter()
        .filter(|f| all || args.only.iter().any(|o| o == f.id))
        .collect();
    let anim_scenes: Vec<&'static str> =
        if !args.draw_only && args.anim && (all || args.only.iter().any(|o| o == "anim")) {
            FIGURES.iter().filter_map(|f| f.make.animation()).collect()
        } else {
            vec![]
        };
    // Each step's wall time and the CPU time the process spent in it.
    let mut steps: Vec<(String, f64, Option<f64>)> = vec![];
    let cpu = timing::cpu_seconds;
    let since = |c0: Option<f64>| c0.zip(cpu()).map(|(a, b)| b - a);
    let mut failed: Vec<String> = vec![];
    let mut computed: Vec<&Figure> = vec![];

    if !args.draw_only {
        // The scene runs the report's figures and the animations share.
        let (t0, c0) = (Instant::now(), cpu());
        let mut needed: BTreeSet<&'static str> =
            selected.iter().flat_map(|f| f.make.scenes()).collect();
        needed.extend(anim_scenes.iter().copied());
        let needed: Vec<&'static str> = needed.into_iter().collect();
        let bar = ProgressBar::new(needed.len() as u64).with_style(
            ProgressStyle::with_template("scene runs {bar:40} {pos}/{len} {msg} ({elapsed})")
                .expect("a valid template"),
        );
        ctx.runs = runs::run_all(&ctx, &needed, &|name| {
            bar.set_message(format!("ran {name}"));
            bar.inc(1);
        })?;
        bar.finish_and_clear();
        println!("ran {} scenes", needed.len());
        if all {
            ctx.write("scenes.csv", &runs::summary_csv(&ctx.runs))?;
            println!("wrote figures/data/scenes.csv");
        }
        steps.push(("scene runs".into(), t0.elapsed().as_secs_f64(), since(c0)));

        // The report's figures, in parallel (nothing in them is timed):
        // each one's wall time, and their CPU time together.
        let (t0, c0) = (Instant::now(), cpu());
        let (report, study): (Vec<&Figure>, Vec<&Figure>) =
            selected.iter().partition(|f| f.report.is_some());
        let results: Vec<(Computed, f64)> = report
            .par_iter()
            .map(|&f| {
                let t0 = Instant::now();
                ((f, f.make.compute(&ctx, f)), t0.elapsed().as_secs_f64())
            })
            .collect();
        if !report.is_empty() {
            steps.push((
                "report figures".into(),
                t0.elapsed().as_secs_f64(),
                since(c0),
            ));
        }
        let mut results: Vec<Computed> = (results.into_iter())
            .map(|((f, r), secs)| {
                steps.push((f.id.to_string(), secs, None));
                (f, r)
            })
            .collect();
        // The study's, one after another: some time their runs.
        for f in study {
            if f.timing == Timing::Only && !ctx.timings {
                println!("{}: timing only, drawn from its committed data", f.id);
                continue;
            }
            let (t0, c0) = (Instant::now(), cpu());
            let r = f.make.compute(&ctx, f);
            let (secs, used) = (t0.elapsed().as_secs_f64(), since(c0));
            let used_s = used.map_or(String::new(), |c| format!(", {c:.1} s of CPU"));
            println!("  ({} computed in {secs:.1} s{used_s})", f.id);
            steps.push((f.id.to_string(), secs, used));
            results.push((f, r));
        }
        for (f, r) in results {
            match r.and_then(|files| {
                catalogue::check_written(&f.entry(), &files, ctx.timings)?;
                Ok(files)
            }) {
                Ok(files) => {
                    for file in files {
                        println!("wrote {file}");
                    }
                    computed.push(f);
                }
                Err(e) => failed.push(format!("{}: {e}", f.id)),
            }
        }
    }

    // Every selected figure is drawn from its data (a figure whose compute
    // failed is not), with the animations beside them.
    let (t0, c0) = (Instant::now(), cpu());
    let to_draw: Vec<&Figure> = selected
        .iter()
        .copied()
        .filter(|f| {
            args.draw_only
                || computed.iter().any(|c| c.id == f.id)
                || (f.timing == Timing::Only && !ctx.timings)
        })
        .collect();
    let drawn: Vec<Result<Vec<String>, String>> = to_draw
        .par_iter()
        .map(|f| f.make.draw(&ctx, f).map_err(|e| format!("{}: {e}", f.id)))
        .chain(anim_scenes.par_iter().map(|&name| {
            let run = ctx.run(name)?;
            run.animation(name, &anim_dir)?;
            Ok(vec![format!("figures/anim/{name}.gif")])
        }))
        .collect();
    for d in drawn {
        match d {
            Ok(files) => {
                for file in files {
                    println!("wrote {file}");
                }
            }
            Err(e) => failed.push(e),
        }
    }
    let drawing = t0.elapsed().as_secs_f64();
    steps.push(("drawing and animations".into(), drawing, since(c0)));
    if let Ok(problems) = ctx.layout_problems.lock() {
        for (id, lines) in problems.iter() {
            for line in lines {
                println!("warning: {id}: {line}");
            }
        }
    }

    let entries = registry::entries();
    write_text(&ctx.out.join("README.md"), &catalogue::readme(&entries))?;
    println!("wrote figures/README.md");
    if all {
        for stray in catalogue::strays(&ctx.data, &entries)? {
            println!("warning: figures/data/{stray} belongs to no figure (delete it?)");
        }
    }
    if ctx.timings && selected.iter().any(|f| f.timing != Timing::None) {
        let machine = timing::machine_csv();
        ctx.write(timing::MACHINE, &machine)?;
        println!("wrote figures/data/{}", timing::MACHINE);
        if all {
            steps.push(("all".into(), clock.elapsed().as_secs_f64(), since(c_all)));
            ctx.write(timing::RUN, &catalogue::run_timing(&steps))?;
            println!("wrote figures/data/{}", timing::RUN);
        }
    } else if !args.draw_only {
        // Without --timings the costs go beside the build, never into
        // figures/data/ (which reproduces to the byte).
        steps.push(("all".into(), clock.elapsed().as_secs_f64(), since(c_all)));
        let costs = root.join("target").join(timing::RUN);
        write_text(&costs, &catalogue::run_timing(&steps))?;
        println!(
            "wrote target/{} (each step's wall and CPU time)",
            timing::RUN
        );
    }
    if all && failed.is_empty() && root.join("paper/paper.tmpl.md").exists() {
        paper::fill::run(&root, false)?;
    }
    println!(
        "{} figures {} and {} animations in {:.1} s",
        to_draw.len(),
        if args.draw_only {
            "drawn from their data"
        } else {
            "computed and drawn"
        },
        anim_scenes.len(),
        clock.elapsed().as_secs_f64()
    );
    if failed.is_empty() {
        Ok(())
    } else {
        Err(failed.join("\n"))
    }
}

/// `cargo xtask scene-keys [--check]`: writes the key table of
/// `scenes/README.md` from falling-chain's scene schema; `--check` fails if
/// it is stale (falling-chain's tests check it too).
fn scene_keys(check: bool) -> Result<(), String> {
    let done = fc_scene::schema::sync_readme(&root().join("scenes/README.md"), check)?;
    println!("scenes/README.md: {done}");
    Ok(())
}

fn main() -> ExitCode {
    let result = match <Command as clap::Parser>::parse() {
        Command::Figures(args) => catalogue::check_only(&registry::entries(), &args.only, "anim")
            .and_then(|()| figures_cmd(args)),
        Command::Paper { check, pdf } => paper::fill::run(&root(), check).and_then(|()| {
            if pdf {
                paper::pdf::build(&root()).map(|_| ())
            } else {
                Ok(())
            }
        }),
        Command::SceneKeys { check } => scene_keys(check),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
