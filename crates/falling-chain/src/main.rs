//! `falling-chain`: hanging-chain shapes and falling-chain runs from the
//! command line.
//!
//! Exit status: 0 on success, 1 if a run failed (its summary and partial
//! outputs are still written), 2 for bad input or an output that could not be
//! written, with a one-line message on stderr naming the field.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::{Args, Parser, Subcommand};
use falling_chain::atomic::{check_writable, write_atomic};
use falling_chain::{csv, CatenaryReport, Error, RunSummary, Scene};

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
}

#[derive(Args)]
struct CatenaryArgs {
    /// First anchor P0 (the pivot).
    #[arg(long, value_name = "X,Y", value_parser = parse_point, allow_hyphen_values = true, default_value = "0,0")]
    p0: [f64; 2],
    /// Second anchor P1 (where the free end is held).
    #[arg(long, value_name = "X,Y", value_parser = parse_point, allow_hyphen_values = true)]
    p1: [f64; 2],
    /// Chain length L (must exceed |P1 - P0|).
    #[arg(long, value_name = "L", allow_negative_numbers = true)]
    length: f64,
    /// Also solve the exact equilibrium of N rigid rods.
    #[arg(long, value_name = "N")]
    links: Option<usize>,
    /// Print one JSON object instead of a table.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct SimulateArgs {
    /// The scene file (see scenes/README.md).
    #[arg(value_name = "SCENE.toml")]
    scene: PathBuf,
    /// Integration method (overrides run.method).
    #[arg(long, value_name = "M")]
    method: Option<String>,
    /// Fixed step (overrides run.dt).
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    dt: Option<f64>,
    /// Relative tolerance (overrides run.rtol).
    #[arg(long, value_name = "R", allow_negative_numbers = true)]
    rtol: Option<f64>,
    /// Absolute tolerance (overrides run.atol).
    #[arg(long, value_name = "A", allow_negative_numbers = true)]
    atol: Option<f64>,
    /// End time (overrides run.t_end).
    #[arg(long = "t-end", value_name = "T", allow_negative_numbers = true)]
    t_end: Option<f64>,
    /// Set any scene key by its dotted path, e.g. chain.links=100,
    /// start.p1=[3.0,0.0], start.p1.0=2.5 (applied before the flags above).
    #[arg(long = "set", value_name = "KEY=VALUE", allow_hyphen_values = true)]
    set: Vec<String>,
    /// Write every sample as CSV: t, tip_x, tip_y, tip_vx, tip_vy, energy,
    /// dissipated, phi_1..phi_n.
    #[arg(long, value_name = "FILE.csv")]
    out: Option<PathBuf>,
    /// Print one JSON object instead of a readable summary.
    #[arg(long)]
    json: bool,
}

/// Parses `X,Y`.
fn parse_point(text: &str) -> Result<[f64; 2], String> {
    let bad = || format!("expected two numbers X,Y (got '{text}')");
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
        println!("{}", report.to_json());
    } else {
        println!("{report}");
    }
    Ok(ExitCode::SUCCESS)
}

fn simulate(args: &SimulateArgs) -> Result<ExitCode, Error> {
    let mut scene = Scene::load(&args.scene)?.with_overrides(&args.set)?;
    let flags = [
        ("run.method", args.method.clone().map(toml::Value::String)),
        ("run.dt", args.dt.map(toml::Value::Float)),
        ("run.rtol", args.rtol.map(toml::Value::Float)),
        ("run.atol", args.atol.map(toml::Value::Float)),
        ("run.t_end", args.t_end.map(toml::Value::Float)),
    ];
    for (path, value) in flags {
        if let Some(value) = value {
            scene = scene.with_value(path, value)?;
        }
    }
    let run = scene.prepare()?;
    if let Some(out) = &args.out {
        check_writable("--out", out)?;
    }
    let traj = run.solve()?;
    let summary = RunSummary::from_trajectory(scene.name(), &traj);
    if args.json {
        println!("{}", summary.to_json());
    } else {
        println!("{summary}");
    }
    if let Some(out) = &args.out {
        write_atomic("--out", out, |w| csv::write_trajectory(w, &traj))?;
    }
    Ok(if summary.is_ok() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Clap's message on one line, without the usage and help hints.
fn one_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("Usage:") && !l.starts_with("For more"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn main() -> ExitCode {
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
    };
    result.unwrap_or_else(|e| {
        eprintln!("error: {e}");
        ExitCode::from(2)
    })
}
