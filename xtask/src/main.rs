//! `cargo xtask figures [--only ID...] [--no-anim]`: regenerates every figure
//! of `../shared/figures.md` into `figures/` from the scene files, in
//! parallel, and writes `figures/README.md`.

mod catalog;
mod make;
mod paper;
mod runs;
mod study;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use catalog::{Figure, FIGURES};

const USAGE: &str = "usage: cargo xtask figures [--only ID...] [--no-anim] | \
                     cargo xtask paper [--check] | cargo xtask scene-keys [--check]";

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives in the workspace")
        .to_path_buf()
}

struct Args {
    only: Vec<String>,
    anim: bool,
}

fn parse(args: &[String]) -> Result<Args, String> {
    let mut out = Args {
        only: vec![],
        anim: true,
    };
    let mut in_only = false;
    for a in args {
        match a.as_str() {
            "--only" => in_only = true,
            "--no-anim" => {
                out.anim = false;
                in_only = false;
            }
            s if in_only && !s.starts_with("--") => out.only.push(s.to_string()),
            s => return Err(format!("unknown argument '{s}'; {USAGE}")),
        }
    }
    for id in &out.only {
        let known = FIGURES.iter().any(|f| f.id == id)
            || study::all().iter().any(|s| s.id == id)
            || id == "anim";
        if !known {
            let ids: Vec<&str> = FIGURES
                .iter()
                .map(|f| f.id)
                .chain(study::all().iter().map(|s| s.id))
                .collect();
            return Err(format!(
                "--only: unknown figure '{id}' (known: {}, anim)",
                ids.join(", ")
            ));
        }
    }
    Ok(out)
}

fn figures_cmd(args: Args) -> Result<(), String> {
    let clock = Instant::now();
    let root = root();
    let out = root.join("figures");
    let scenes_dir = root.join("scenes");
    let anim_dir = out.join("anim");
    let data_dir = out.join("data");
    fs::create_dir_all(&anim_dir).map_err(|e| e.to_string())?;

    let selected: Vec<&Figure> = FIGURES
        .iter()
        .filter(|f| args.only.is_empty() || args.only.iter().any(|o| o == f.id))
        .collect();
    let animate = args.anim && (args.only.is_empty() || args.only.iter().any(|o| o == "anim"));
    let mut needed: BTreeSet<&'static str> = selected.iter().flat_map(|f| f.scenes()).collect();
    let anim_scenes: Vec<&'static str> = if animate {
        FIGURES
            .iter()
            .filter(|f| matches!(f.kind, catalog::Kind::Snapshots { .. }))
            .flat_map(|f| f.scenes())
            .collect()
    } else {
        vec![]
    };
    needed.extend(anim_scenes.iter().copied());
    let needed: Vec<&'static str> = needed.into_iter().collect();

    let bar = ProgressBar::new((needed.len() + selected.len() + anim_scenes.len()) as u64)
        .with_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} ({elapsed})")
                .expect("a valid template"),
        );
    let runs = runs::run_all(&scenes_dir, &needed, &|name| {
        bar.set_message(format!("ran {name}"));
        bar.inc(1);
    })?;
    let jobs = std::thread::available_parallelism().map_or(1, |n| n.get());
    if args.only.is_empty() {
        fs::create_dir_all(&data_dir).map_err(|e| e.to_string())?;
        fs::write(data_dir.join("scenes.csv"), runs::summary_csv(&runs))
            .map_err(|e| e.to_string())?;
        println!("wrote figures/data/scenes.csv");
    }
    let inputs = make::Inputs {
        runs: &runs,
        data_dir: &data_dir,
        jobs,
    };
    let drawn: Vec<Result<&str, String>> = selected
        .par_iter()
        .map(|f| {
            make::figure(f, &inputs, &out)?;
            bar.set_message(format!("drew {}", f.id));
            bar.inc(1);
            Ok(f.id)
        })
        .chain(anim_scenes.par_iter().map(|&name| {
            make::animation(name, &runs[name], &anim_dir)?;
            bar.set_message(format!("animated {name}"));
            bar.inc(1);
            Ok(name)
        }))
        .collect();
    bar.finish_and_clear();
    let mut timing = vec![(
        "report figures and animations".to_string(),
        clock.elapsed().as_secs_f64(),
    )];
    let mut failed = vec![];
    for d in &drawn {
        match d {
            Ok(_) => {}
            Err(e) => failed.push(e.clone()),
        }
    }
    for f in &selected {
        println!("wrote figures/{0}.png, figures/{0}.svg", f.id);
    }
    for name in &anim_scenes {
        println!("wrote figures/anim/{name}.gif");
    }
    // The study figures, one after the other: some of them time runs.
    let ctx = study::Ctx {
        root: root.clone(),
        out: out.clone(),
        data: data_dir.clone(),
        jobs,
    };
    fs::create_dir_all(&ctx.data).map_err(|e| e.to_string())?;
    for st in study::all() {
        if !(args.only.is_empty() || args.only.iter().any(|o| o == st.id)) {
            continue;
        }
        let t0 = Instant::now();
        match (st.make)(&ctx) {
            Ok(files) => {
                for f in files {
                    println!("wrote {f}");
                }
                let secs = t0.elapsed().as_secs_f64();
                println!("  ({} in {secs:.1} s)", st.id);
                timing.push((st.id.to_string(), secs));
            }
            Err(e) => failed.push(format!("{}: {e}", st.id)),
        }
    }
    fs::write(out.join("README.md"), readme()).map_err(|e| e.to_string())?;
    println!("wrote figures/README.md");
    if args.only.is_empty() {
        // How long each step took, for the paper's reproducibility section.
        timing.push(("all".to_string(), clock.elapsed().as_secs_f64()));
        let mut csv = String::from("step,seconds\n");
        for (step, secs) in &timing {
            csv.push_str(&format!("{step},{secs:.1}\n"));
        }
        fs::write(data_dir.join("timing.csv"), csv).map_err(|e| e.to_string())?;
        println!("wrote figures/data/timing.csv");
    }
    if args.only.is_empty() && root.join("paper/paper.tmpl.md").exists() {
        paper::run(&root, false)?;
    }
    println!(
        "{} report figures, {} animations from {} scene runs, and the study figures, in {:.1} s",
        selected.len(),
        anim_scenes.len(),
        needed.len(),
        clock.elapsed().as_secs_f64()
    );
    if failed.is_empty() {
        Ok(())
    } else {
        Err(failed.join("\n"))
    }
}

/// `figures/README.md`: every figure, what it shows, where it comes from.
fn readme() -> String {
    let mut s = String::from(
        "# Figures\n\nRegenerated by `cargo xtask figures` (this file too) from the scene files \
         in `scenes/` and the model of `physics.md`. One figure alone: \
         `cargo xtask figures --only ID`. Animations of the report scenes are in `anim/`.\n\n\
         | id | report | what it shows | scene files | command |\n|---|---|---|---|---|\n",
    );
    for f in FIGURES {
        let scenes: Vec<String> = f
            .scenes()
            .iter()
            .map(|s| format!("[`{s}`](../scenes/{s}.toml)"))
            .collect();
        let scenes = if scenes.is_empty() {
            "—".to_string()
        } else {
            scenes.join(", ")
        };
        s.push_str(&format!(
            "| [{id}]({id}.png) | {} | {} | {} | `cargo xtask figures --only {id}` |\n",
            f.report,
            f.what,
            scenes,
            id = f.id
        ));
    }
    s.push_str("\n## New figures\n\nTheir data are in `data/<id>*.csv`.\n\n| id | what it shows | command |\n|---|---|---|\n");
    for st in study::all() {
        s.push_str(&format!(
            "| {id} | {} | `cargo xtask figures --only {id}` |\n",
            st.what,
            id = st.id
        ));
    }
    s
}

/// `cargo xtask scene-keys [--check]`: writes the key table of
/// `scenes/README.md` from falling-chain's scene schema; `--check` fails if
/// it is stale (falling-chain's tests check it too).
fn scene_keys(check: bool) -> Result<(), String> {
    let path = root().join("scenes/README.md");
    let text = fs::read_to_string(&path).map_err(|e| format!("scenes/README.md: {e}"))?;
    let want = falling_chain::schema::with_markdown_table(&text)
        .map_err(|e| format!("scenes/README.md: {e}"))?;
    if want == text {
        println!("scenes/README.md: the key table is up to date");
    } else if check {
        return Err("scenes/README.md: the key table differs from \
                    crates/falling-chain/src/schema.rs (run `cargo xtask scene-keys`)"
            .into());
    } else {
        fs::write(&path, want).map_err(|e| format!("scenes/README.md: {e}"))?;
        println!("wrote scenes/README.md");
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("figures") => parse(&args[1..]).and_then(figures_cmd),
        Some("paper") => match &args[1..] {
            [] => paper::run(&root(), false),
            [c] if c == "--check" => paper::run(&root(), true),
            _ => Err(USAGE.to_string()),
        },
        Some("scene-keys") => match &args[1..] {
            [] => scene_keys(false),
            [c] if c == "--check" => scene_keys(true),
            _ => Err(USAGE.to_string()),
        },
        _ => Err(USAGE.to_string()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
