//! The figure catalogue as plain data: what `cargo xtask figures` needs to
//! know about its figures apart from how each is made. The registry
//! (`xtask/src/registry.rs`) lists its figures as [`Entry`]s; this module
//! writes `figures/README.md` from them ([`readme`]), checks the registry's
//! conventions ([`check`]), checks what a figure wrote against what it
//! declares ([`check_written`]) and finds the data files no figure lists
//! ([`strays`]).
//!
//! Conventions: a figure `id` writes `figures/<id>.png` and `.svg` and its
//! data files `figures/data/<id>*.csv`; wall times go only to the files
//! whose names end in [`SUFFIX`], with [`MACHINE`] (the machine they were
//! measured on) and [`RUN`] (the steps of the last full timed run).

use std::fmt::Write as _;
use std::fs;
use std::path::Path;

/// The end of every timing file's name.
pub const SUFFIX: &str = "-timing.csv";
/// The machine the timing files were measured on.
pub const MACHINE: &str = "machine-timing.csv";
/// The steps of the last full `cargo xtask figures --timings`.
pub const RUN: &str = "run-timing.csv";
/// The summary of the report's scene runs, written by the full run.
pub const SCENES: &str = "scenes.csv";

/// Whether `file` (a name in `figures/data/`) holds wall times.
pub fn is_timing(file: &str) -> bool {
    file.ends_with(SUFFIX)
}

/// Whether a figure measures wall times.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Timing {
    /// No wall times: its data reproduce to the byte.
    None,
    /// Reproducible data in `<id>*.csv`, wall times beside them in
    /// `<id>*-timing.csv`, rewritten only by `--timings`.
    Alongside,
    /// Nothing but wall times: computed only by `--timings`; otherwise
    /// drawn from the committed timing files.
    Only,
}

/// One figure of the catalogue.
#[derive(Clone, Debug)]
pub struct Entry<'a> {
    pub id: &'a str,
    /// The report's figure it reproduces (`Fig. 7a`), if any.
    pub report: Option<&'a str>,
    /// One line: what it shows.
    pub what: &'a str,
    /// The scene files of `scenes/` it runs through the shared scene runs.
    pub scenes: Vec<&'a str>,
    /// Its data files in `figures/data/`.
    pub data: &'a [&'a str],
    pub timing: Timing,
}

/// The registry's conventions: every id once, every data file named
/// `<id>*.csv`, and the timing files as the figure's [`Timing`] says (none;
/// some but not all; all).
pub fn check(entries: &[Entry]) -> Result<(), String> {
    for (k, f) in entries.iter().enumerate() {
        if entries[..k].iter().any(|g| g.id == f.id) {
            return Err(format!("{}: listed twice", f.id));
        }
        if let Some(d) = f
            .data
            .iter()
            .find(|d| !d.starts_with(f.id) || !d.ends_with(".csv"))
        {
            return Err(format!(
                "{}: data file {d} is not named {}*.csv",
                f.id, f.id
            ));
        }
        let timed = f.data.iter().filter(|d| is_timing(d)).count();
        let ok = match f.timing {
            Timing::None => timed == 0,
            Timing::Alongside => timed > 0 && timed < f.data.len(),
            Timing::Only => timed == f.data.len(),
        };
        if !ok {
            return Err(format!(
                "{}: {timed} of its {} data files are timing files, against {:?}",
                f.id,
                f.data.len(),
                f.timing
            ));
        }
    }
    Ok(())
}

/// The data files a figure's `compute` wrote (paths relative to the
/// workspace root) must be its declared ones: all of them, the timing files
/// only with `--timings`.
pub fn check_written(entry: &Entry, files: &[String], timings: bool) -> Result<(), String> {
    let data: Vec<&str> = files
        .iter()
        .filter_map(|f| f.strip_prefix("figures/data/"))
        .collect();
    if let Some(d) = data.iter().find(|d| !entry.data.contains(d)) {
        return Err(format!("wrote {d}, which the registry does not list"));
    }
    for d in entry.data {
        let expected = timings || !is_timing(d);
        if expected != data.contains(d) {
            let what = if expected {
                "did not write"
            } else {
                "wrote without --timings"
            };
            return Err(format!("{what} {d}"));
        }
    }
    Ok(())
}

/// Checks `--only`: every id names an entry or is `extra` (`anim`).
pub fn check_only(entries: &[Entry], only: &[String], extra: &str) -> Result<(), String> {
    let known = |id: &str| id == extra || entries.iter().any(|e| e.id == id);
    match only.iter().find(|id| !known(id)) {
        Some(id) => {
            let ids: Vec<&str> = entries.iter().map(|e| e.id).collect();
            let ids = ids.join(", ");
            Err(format!(
                "--only: unknown figure '{id}' (known: {ids}, {extra})"
            ))
        }
        None => Ok(()),
    }
}

/// [`RUN`]: `step,seconds,cpu_seconds`, the wall time of each step of a
/// full timed run (seconds, to a tenth) and the CPU time the process spent
/// in it (all its threads; empty where unknown or where steps overlapped):
/// its compute, whatever else held the cores.
pub fn run_timing(steps: &[(String, f64, Option<f64>)]) -> String {
    let mut csv = String::from("step,seconds,cpu_seconds\n");
    for (step, secs, cpu) in steps {
        let cpu = cpu.map_or(String::new(), |c| fc_csv::format::fixed(c, 1));
        let _ = writeln!(csv, "{step},{},{cpu}", fc_csv::format::fixed(*secs, 1));
    }
    csv
}

/// The CSV files in `dir` (`figures/data/`) that no entry lists, sorted
/// (left from an older layout).
pub fn strays(dir: &Path, entries: &[Entry]) -> Result<Vec<String>, String> {
    let known = |name: &str| {
        [SCENES, MACHINE, RUN].contains(&name) || entries.iter().any(|f| f.data.contains(&name))
    };
    let mut out = vec![];
    for item in fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))? {
        let name = item.map_err(|e| e.to_string())?.file_name();
        let name = name.to_string_lossy();
        if name.ends_with(".csv") && !known(&name) {
            out.push(name.into_owned());
        }
    }
    out.sort();
    Ok(out)
}

/// The data files of `entry`, in a README cell: timing files in italics.
fn data_cell(entry: &Entry) -> String {
    if entry.data.is_empty() {
        return "—".into();
    }
    let cells: Vec<String> = entry
        .data
        .iter()
        .map(|f| {
            if is_timing(f) {
                format!("*[`{f}`](data/{f})*")
            } else {
                format!("[`{f}`](data/{f})")
            }
        })
        .collect();
    cells.join(", ")
}

/// `figures/README.md`: every figure, what it shows, where it comes from;
/// the report's figures (those with a `report` label) first, then the
/// study's, each in the order of `entries`.
pub fn readme(entries: &[Entry]) -> String {
    let mut s = String::from(
        "# Figures\n\n\
         Written by `cargo xtask figures` (this file too, from the figure registry \
         `xtask/src/registry.rs`) from the scene files in `scenes/` and the model of \
         `docs/model.md`; the catalogue is `docs/figures.md`. Every figure has its data in \
         `data/`: `cargo xtask figures` computes the data and draws each figure from it; \
         `cargo xtask figures --draw-only` redraws every figure from the data as committed, \
         without running anything. One figure alone: `cargo xtask figures --only ID` \
         (with `--draw-only` too).\n\n\
         **Wall times** are kept apart, in the files whose names end in `-timing.csv` \
         (in italics below), with `data/machine-timing.csv` (the machine, its CPU and \
         cores, the date and the Rust compiler they were measured with) and \
         `data/run-timing.csv` (each step of the last full timed run, every figure \
         one: its wall time and the CPU time spent in it; a run without `--timings` \
         writes the same table to `target/run-timing.csv`). \
         `cargo xtask figures` reads them and never rewrites them, so on an unchanged \
         checkout it leaves `git status` clean; `cargo xtask figures --timings` measures \
         them again and rewrites them (run it whole, so that every timing file comes from \
         one machine). The figures marked *timing only* are computed only then; the \
         work-precision diagrams choose their points by cost when timed, and otherwise run \
         the points their timing file lists (column `plan`), untimed.\n\n\
         Animations of the report scenes (`anim/<scene>.gif`) are made from the scene runs \
         by `cargo xtask figures` (not by `--draw-only`; `--no-anim` skips them).\n\n\
         ## The report's figures\n\n\
         | id | report | what it shows | scene files | data |\n|---|---|---|---|---|\n",
    );
    for f in entries {
        let Some(report) = f.report else { continue };
        let scenes: Vec<String> = f
            .scenes
            .iter()
            .map(|s| format!("[`{s}`](../scenes/{s}.toml)"))
            .collect();
        let scenes = if scenes.is_empty() {
            "—".to_string()
        } else {
            scenes.join(", ")
        };
        let (id, what, data) = (f.id, f.what, data_cell(f));
        let _ = writeln!(
            s,
            "| [{id}]({id}.png) | {report} | {what} | {scenes} | {data} |"
        );
    }
    s.push_str(
        "\nThe report's scene runs are summarised in [`data/scenes.csv`](data/scenes.csv).\n\n\
         ## The study's figures\n\n| id | what it shows | data |\n|---|---|---|\n",
    );
    for f in entries.iter().filter(|f| f.report.is_none()) {
        let note = match f.timing {
            Timing::Only => " (*timing only*)",
            _ => "",
        };
        let (id, what, data) = (f.id, f.what, data_cell(f));
        let _ = writeln!(s, "| [{id}]({id}.png) | {what}{note} | {data} |");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn entry<'a>(id: &'a str, data: &'a [&'a str], timing: Timing) -> Entry<'a> {
        Entry {
            id,
            report: None,
            what: "w",
            scenes: vec![],
            data,
            timing,
        }
    }

    #[test]
    fn conventions_are_checked() {
        let ok = [
            entry("a", &["a.csv"], Timing::None),
            entry("b", &["b.csv", "b-timing.csv"], Timing::Alongside),
            entry("c", &["c-timing.csv"], Timing::Only),
        ];
        assert_eq!(check(&ok), Ok(()));
        let twice = [ok[0].clone(), ok[0].clone()];
        assert!(check(&twice).unwrap_err().contains("twice"));
        let misnamed = [entry("a", &["b.csv"], Timing::None)];
        assert!(check(&misnamed).unwrap_err().contains("not named"));
        let untimed = [entry("b", &["b.csv"], Timing::Alongside)];
        assert!(check(&untimed).unwrap_err().contains("timing files"));
        let timed = [entry("a", &["a-timing.csv"], Timing::None)];
        assert!(check(&timed).is_err());
    }

    #[test]
    fn written_files_must_be_the_declared_ones() {
        let e = entry("b", &["b.csv", "b-timing.csv"], Timing::Alongside);
        let w = |fs: &[&str]| -> Vec<String> {
            fs.iter().map(|f| format!("figures/data/{f}")).collect()
        };
        assert_eq!(check_written(&e, &w(&["b.csv"]), false), Ok(()));
        assert_eq!(
            check_written(&e, &w(&["b.csv", "b-timing.csv"]), true),
            Ok(())
        );
        let missing = check_written(&e, &w(&["b.csv"]), true).unwrap_err();
        assert_eq!(missing, "did not write b-timing.csv");
        let timed = check_written(&e, &w(&["b.csv", "b-timing.csv"]), false).unwrap_err();
        assert_eq!(timed, "wrote without --timings b-timing.csv");
        let extra = check_written(&e, &w(&["b.csv", "x.csv"]), false).unwrap_err();
        assert!(extra.contains("x.csv"), "{extra}");
    }

    #[test]
    fn only_names_known_figures() {
        let es = [entry("a", &["a.csv"], Timing::None)];
        let only = |ids: &[&str]| -> Vec<String> { ids.iter().map(|s| s.to_string()).collect() };
        assert_eq!(check_only(&es, &only(&["a", "anim"]), "anim"), Ok(()));
        let e = check_only(&es, &only(&["a", "b"]), "anim").unwrap_err();
        assert_eq!(e, "--only: unknown figure 'b' (known: a, anim)");
    }

    #[test]
    fn strays_are_the_unlisted_csv_files() {
        let dir = std::env::temp_dir().join(format!("catalogue-strays-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        for f in ["a.csv", "old.csv", "scenes.csv", "notes.txt", MACHINE] {
            fs::write(dir.join(f), "x\n").unwrap();
        }
        let found = strays(&dir, &[entry("a", &["a.csv"], Timing::None)]);
        fs::remove_dir_all(&dir).unwrap();
        assert_eq!(found.unwrap(), vec!["old.csv".to_string()]);
    }

    #[test]
    fn the_readme_lists_each_figure_once_in_its_table() {
        let mut report = entry("fig01", &["fig01.csv"], Timing::None);
        report.report = Some("Fig. 1");
        report.scenes = vec!["span-d3"];
        let study = entry("c", &["c-timing.csv"], Timing::Only);
        let text = readme(&[report, study]);
        let (head, tail) = text.split_once("## The study's figures").unwrap();
        assert!(head.contains(
            "| [fig01](fig01.png) | Fig. 1 | w | [`span-d3`](../scenes/span-d3.toml) | [`fig01.csv`](data/fig01.csv) |"
        ));
        assert!(!tail.contains("fig01"));
        assert!(tail.contains(
            "| [c](c.png) | w (*timing only*) | *[`c-timing.csv`](data/c-timing.csv)* |"
        ));
    }
}
