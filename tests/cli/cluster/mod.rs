//! The cluster recipes of `docs/cluster.md`, run as written: its Slurm job-array script
//! on a real one-node Slurm (the distribution's slurmctld, slurmd and munge,
//! started here and stopped by PID), and its GNU parallel script with
//! `-j 2` on this machine. Both read the recipe out of docs/cluster.md
//! (`readme::recipe`), so the page cannot drift from what is tested. The
//! shards' merged table must equal the unsharded run byte for byte, wall
//! times aside; a failed array task and a shard of another scene must be
//! refused by `merge`.
//!
//! Without Slurm (or without root, which its daemons need here) or GNU
//! parallel, a plain `cargo test` says in one line that it skipped; with
//! `CI=true` (as in `.ci/run`, which installs them) they fail instead.

mod readme;
mod slurm;

use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

use crate::common::{scene, scratch, stderr, BIN};

/// `Some(why)` when the tool is missing and this is not CI (said once on the
/// terminal, as the harness captures `eprintln!`); a missing tool under
/// `CI=true` fails the test.
fn skip(test: &str, missing: Option<String>) -> bool {
    let Some(why) = missing else {
        return false;
    };
    assert!(
        std::env::var("CI").as_deref() != Ok("true"),
        "CI=true but {test} cannot run: {why} (.ci/run installs it)"
    );
    let _ = writeln!(std::io::stderr().lock(), "skipped {test}: {why}");
    true
}

/// `PATH` with the binary under test first, as a user's `PATH` would hold
/// `falling-chain`.
fn path_with_binary() -> std::ffi::OsString {
    let bin_dir = Path::new(BIN).parent().unwrap().to_path_buf();
    let old = std::env::var_os("PATH").unwrap_or_default();
    std::env::join_paths(std::iter::once(bin_dir).chain(std::env::split_paths(&old))).unwrap()
}

/// The recipe `name` of docs/cluster.md, written to `dir/file`.
fn recipe_file(dir: &Path, name: &str, file: &str) -> PathBuf {
    let path = dir.join(file);
    fs::write(&path, readme::recipe(&readme::text(), name)).unwrap();
    path
}

/// A table's text with the `wall_seconds` cells blanked: the one column two
/// runs of the same study may differ in.
fn without_wall_times(text: &str) -> String {
    let mut lines = text.lines();
    let header = lines.next().unwrap_or_default();
    let wall = header.split(',').position(|c| c == "wall_seconds");
    let mut out = format!("{header}\n");
    for line in lines {
        let mut cells: Vec<&str> = line.split(',').collect();
        if let Some(w) = wall {
            cells[w] = "";
        }
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// Runs the CLI in `dir` and requires exit 0.
fn cli_in(dir: &Path, args: &[&str]) -> Output {
    let o = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    o
}

/// The unsharded run of `study` (a command and its arguments) into
/// `dir/whole.csv`, and the shards' merge `dir/<command>.csv` compared with
/// it, wall times aside.
fn assert_merge_equals_whole(dir: &Path, study: &[&str], shards: usize) {
    let command = study[0];
    let names: Vec<String> = (0..shards).map(|i| format!("{command}-{i}.csv")).collect();
    let mut args = vec!["merge"];
    args.extend(names.iter().map(String::as_str));
    args.extend(["--out", "merged.csv"]);
    cli_in(dir, &args);
    let mut whole: Vec<&str> = study.to_vec();
    whole.extend(["--quiet", "--out", "whole.csv"]);
    cli_in(dir, &whole);
    let read = |f: &str| without_wall_times(&fs::read_to_string(dir.join(f)).unwrap());
    assert_eq!(
        read("merged.csv"),
        read("whole.csv"),
        "{command}: the merged shards differ from the unsharded run"
    );
}

/// The small studies the recipes run: a sweep of 12 runs at n = 10 (three
/// shards of four), and a stability table (two shards).
fn small_sweep(scene_path: &str) -> Vec<String> {
    [
        "sweep",
        scene_path,
        "--set",
        "chain.links=10",
        "--set",
        "run.t_end=1",
        "--vary",
        "start.p1.0=1:4:12",
    ]
    .map(String::from)
    .to_vec()
}

fn small_stability(scene_path: &str) -> Vec<String> {
    [
        "stability",
        scene_path,
        "--set",
        "chain.links=10",
        "--set",
        "run.t_end=1",
        "--methods",
        "rk4,dopri5",
    ]
    .map(String::from)
    .to_vec()
}

fn strs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

/// Submits the array script of docs/cluster.md for `study` in `shards` shards with
/// `--array=<array>`,
/// waits for it (bounded), and returns sbatch's output.
fn submit(
    cluster: &slurm::Slurm,
    dir: &Path,
    array: &str,
    shards: usize,
    study: &[&str],
) -> Output {
    let mut sbatch = cluster.client("sbatch");
    sbatch
        .arg("--wait")
        .arg(format!("--array={array}"))
        .arg(dir.join("shard-array.sh"))
        .arg(shards.to_string())
        .args(study)
        .current_dir(dir)
        .env("PATH", path_with_binary());
    slurm::run_within(sbatch, Duration::from_secs(60))
        .unwrap_or_else(|e| panic!("{e}\nslurmctld.log:\n{}", cluster.log("slurmctld")))
}

#[test]
fn the_readme_job_array_runs_on_a_real_slurm_and_merges_to_the_whole_run() {
    if skip(
        "the Slurm test of docs/cluster.md's job array",
        slurm::missing(),
    ) {
        return;
    }
    let dir = scratch("slurm");
    recipe_file(&dir, "slurm-array", "shard-array.sh");
    let cluster = slurm::Slurm::start(&dir.join("cluster")).unwrap();
    let span = scene("span-d3");

    // A sweep in three shards, and stability in two, as docs/cluster.md submits.
    let sweep = small_sweep(&span);
    let o = submit(&cluster, &dir, "0-2", 3, &strs(&sweep));
    assert!(o.status.success(), "sweep array: {}", stderr(&o));
    assert_merge_equals_whole(&dir, &strs(&sweep), 3);
    let stability = small_stability(&span);
    let o = submit(&cluster, &dir, "0-1", 2, &strs(&stability));
    assert!(o.status.success(), "stability array: {}", stderr(&o));
    assert_merge_equals_whole(&dir, &strs(&stability), 2);

    // A failed task: indices 0, 1 and 3 with three shards make shard 3/3,
    // out of range; the array fails, and merge refuses the two shards it
    // has, naming the runs of the missing shard 2 (2, 5, 8, 11).
    let failed = dir.join("failed");
    fs::create_dir_all(&failed).unwrap();
    fs::copy(dir.join("shard-array.sh"), failed.join("shard-array.sh")).unwrap();
    let o = submit(&cluster, &failed, "0,1,3", 3, &strs(&sweep));
    assert!(!o.status.success(), "an array with a failed task passed");
    let o = Command::new(BIN)
        .args(["merge", "sweep-0.csv", "sweep-1.csv", "--out", "all.csv"])
        .current_dir(&failed)
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("2, 5, 8, 11"),
        "the missing runs are not named: {err}"
    );
    assert!(!failed.join("all.csv").exists());

    // A shard of another scene joins nothing.
    let other = small_sweep(&scene("span-d1"));
    let mut args = strs(&other);
    args.extend(["--quiet", "--shard", "2/3", "--out", "sweep-2.csv"]);
    cli_in(&failed, &args);
    let o = Command::new(BIN)
        .args([
            "merge",
            "sweep-0.csv",
            "sweep-1.csv",
            "sweep-2.csv",
            "--out",
            "all.csv",
        ])
        .current_dir(&failed)
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("another study"), "{err}");
    assert!(!failed.join("all.csv").exists());
    drop(cluster);
}

#[test]
fn the_readme_gnu_parallel_script_merges_to_the_whole_run() {
    let missing = slurm::find("parallel")
        .is_none()
        .then(|| "no GNU parallel (apt-get install parallel)".to_string());
    if skip("the GNU parallel test of docs/cluster.md's script", missing) {
        return;
    }
    let dir = scratch("parallel");
    let script = recipe_file(&dir, "gnu-parallel", "shard-parallel.sh");
    let sweep = small_sweep(&scene("span-d3"));
    let mut cmd = Command::new("bash");
    cmd.arg(&script)
        .arg("3")
        .args(&sweep)
        .current_dir(&dir)
        .env("PATH", path_with_binary())
        .env_remove("HOSTS");
    let o = slurm::run_within(cmd, Duration::from_secs(60)).unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    // The script merges too: its sweep.csv is the whole sweep.
    fs::copy(dir.join("sweep.csv"), dir.join("merged-by-script.csv")).unwrap();
    assert_merge_equals_whole(&dir, &strs(&sweep), 3);
    assert_eq!(
        without_wall_times(&fs::read_to_string(dir.join("merged-by-script.csv")).unwrap()),
        without_wall_times(&fs::read_to_string(dir.join("whole.csv")).unwrap())
    );
}
