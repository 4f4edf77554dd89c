//! Issue 38's files and messages, run through the CLI: two outputs of one
//! command on one file are refused before any run (F1); what `sweep` and
//! the studies write reads back through `merge` whatever the scene's name
//! holds (F2); a shard whose rows were not run for its `--budget` is not
//! merged (F3); `view` writes only `FILE.html` (F4) and keeps its page's
//! data within the documented 1.8 MB with `--forces` (F5); a date-time in
//! a number key says so, naming the key (U6); numbers in messages are
//! short (1e300, never 301 digits).

use std::fs;
use std::path::Path;

use crate::common::*;

fn path(p: &Path) -> String {
    p.to_string_lossy().into_owned()
}

/// A scene name with a comma, a quote and a line break (TOML-escaped for
/// `--set`), and the text it stands for.
const NASTY_SET: &str = r#"name="a,b \"q\"\nc""#;
const NASTY: &str = "a,b \"q\"\nc";

/// A heavy run (10^5 rods to t = 10^3, ten samples): refused outputs must
/// not wait for it.
const HEAVY: [&str; 6] = [
    "--set",
    "chain.links=100000",
    "--set",
    "run.t_end=1000",
    "--set",
    "run.output_dt=100",
];

/// A study of minutes (2000 rods, two explicit methods).
const SLOW_STUDY: [&str; 4] = ["--set", "chain.links=2000", "--methods", "rk4,dopri5"];

#[test]
fn two_outputs_on_one_file_are_refused_before_any_run() {
    let dir = scratch("files-same-output");
    let d = path(&dir);
    let s = scene("span-d3");
    std::os::unix::fs::symlink(&dir, dir.join("here")).unwrap();
    // The same path; `./x` and `x`; through a link to the directory.
    for (out, forces) in [
        (format!("{d}/same.csv"), format!("{d}/same.csv")),
        (format!("{d}/same.csv"), format!("{d}/./same.csv")),
        (format!("{d}/here/same.csv"), format!("{d}/same.csv")),
    ] {
        let mut args = vec!["simulate", &s, "--out", &out, "--forces", &forces];
        args.extend(HEAVY);
        let e = refused(&run_quick(&args), "--forces");
        assert!(e.contains("same file as --out"), "{e}");
        assert_eq!(names_in(&dir), ["here"], "{e}");
    }
    // An existing file and a link to it.
    fs::write(dir.join("old.csv"), "keep\n").unwrap();
    std::os::unix::fs::symlink(dir.join("old.csv"), dir.join("link.csv")).unwrap();
    let (old, link) = (format!("{d}/old.csv"), format!("{d}/link.csv"));
    let mut args = vec!["simulate", &s, "--out", &link, "--forces", &old];
    args.extend(HEAVY);
    refused(&run_quick(&args), "--forces");
    assert_eq!(fs::read_to_string(dir.join("old.csv")).unwrap(), "keep\n");
    // precision and stability: --out and --plot.
    for command in ["precision", "stability"] {
        let (out, plot) = (format!("{d}/t.svg"), format!("{d}/./t.svg"));
        let mut args = vec![command, &s, "--out", &out, "--plot", &plot, "--quiet"];
        args.extend(SLOW_STUDY);
        let e = refused(&run_quick(&args), "--plot");
        assert!(e.contains("same file as --out"), "{e}");
        assert!(!dir.join("t.svg").exists(), "{command}");
    }
    // Two files of their own are fine.
    let (a, b) = (format!("{d}/a.csv"), format!("{d}/b.csv"));
    let o = run(&[
        "simulate",
        &s,
        "--set",
        "run.t_end=0.1",
        "--out",
        &a,
        "--forces",
        &b,
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(fs::read_to_string(&a).unwrap().starts_with("t,tip_x"));
    assert!(fs::read_to_string(&b).unwrap().starts_with("t,tension_0"));
    fs::remove_dir_all(&dir).unwrap();
}

/// The table's records as cells, read by the project's one reader.
fn records(file: &Path) -> Vec<Vec<String>> {
    fc_csv::records(&fs::read_to_string(file).unwrap()).unwrap()
}

/// `records` without the column `wall_seconds` (which differs run to run).
fn without_wall(rows: Vec<Vec<String>>) -> Vec<Vec<String>> {
    let wall = rows[0].iter().position(|c| c == "wall_seconds");
    rows.into_iter()
        .map(|mut r| {
            if let Some(w) = wall {
                r.remove(w);
            }
            r
        })
        .collect()
}

#[test]
fn merge_joins_shards_of_a_scene_named_with_commas_quotes_and_newlines() {
    let dir = scratch("files-nasty-merge");
    let s = scene("span-d3");
    let file = |name: &str| path(&dir.join(name));
    // sweep: two shards, then the whole sweep in one.
    let sweep = |extra: &[&str], out: &str| {
        let mut args = vec![
            "sweep",
            &s,
            "--set",
            NASTY_SET,
            "--set",
            "run.t_end=0.2",
            "--vary",
            "chain.damping=0,0.001,0.002",
            "--quiet",
            "--out",
            out,
        ];
        args.extend(extra);
        let o = run(&args);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    };
    sweep(&["--shard", "0/2"], &file("s0.csv"));
    sweep(&["--shard", "1/2"], &file("s1.csv"));
    sweep(&[], &file("whole.csv"));
    let o = run(&[
        "merge",
        &file("s1.csv"),
        &file("s0.csv"),
        "--out",
        &file("m.csv"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("wrote 3 rows"), "{}", stderr(&o));
    let merged = records(&dir.join("m.csv"));
    let name = merged[0].iter().position(|c| c == "name").unwrap();
    assert!(merged[1..].iter().all(|r| r[name] == NASTY), "{merged:?}");
    assert_eq!(
        without_wall(merged),
        without_wall(records(&dir.join("whole.csv")))
    );
    // stability: the scene's name is its rows' key.
    let small = dir.join("small.toml");
    fs::write(
        &small,
        "[chain]\nlinks = 4\n[start]\nkind = \"folded\"\n[run]\nt_end = 0.2\n",
    )
    .unwrap();
    let small = path(&small);
    for (shard, out) in [("0/2", "t0.csv"), ("1/2", "t1.csv")] {
        let o = run(&[
            "stability",
            &small,
            "--set",
            NASTY_SET,
            "--methods",
            "rk4,dopri5",
            "--shard",
            shard,
            "--quiet",
            "--out",
            &file(out),
        ]);
        assert!(o.status.code() == Some(0), "{}", stderr(&o));
    }
    let o = run(&[
        "merge",
        &file("t0.csv"),
        &file("t1.csv"),
        "--out",
        &file("tm.csv"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let merged = records(&dir.join("tm.csv"));
    let scene_col = merged[0].iter().position(|c| c == "scene").unwrap();
    assert!(
        merged[1..].iter().all(|r| r[scene_col] == NASTY),
        "{merged:?}"
    );
    // A table that is not CSV is named with its line.
    fs::write(dir.join("bad.csv"), "run,runs,scene_hash\n0,\"1,h\n").unwrap();
    let e = refused(
        &run(&["merge", &file("bad.csv"), "--out", &file("x.csv")]),
        "merge",
    );
    assert!(
        e.contains("bad.csv: line 2: a quoted cell is not closed"),
        "{e}"
    );
    assert!(!dir.join("x.csv").exists());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn merge_refuses_a_shard_whose_rows_were_not_run_for_its_budget() {
    let dir = scratch("files-budget-merge");
    let s = scene("span-d3");
    let file = |name: &str| path(&dir.join(name));
    // A millisecond of budget: some cells (at least the last) are not run.
    for (shard, out) in [("0/2", "b0.csv"), ("1/2", "b1.csv")] {
        let o = run(&[
            "stability",
            &s,
            "--set",
            "chain.links=400",
            "--methods",
            "rk4,dopri5",
            "--budget",
            "0.001",
            "--shard",
            shard,
            "--quiet",
            "--out",
            &file(out),
        ]);
        assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    }
    let table = records(&dir.join("b0.csv"));
    let note = table[0].iter().position(|c| c == "note").unwrap();
    let run_col = table[0].iter().position(|c| c == "run").unwrap();
    let unrun: Vec<&str> = table[1..]
        .iter()
        .filter(|r| r[note].starts_with("budget"))
        .map(|r| r[run_col].as_str())
        .collect();
    assert!(!unrun.is_empty(), "{table:?}");
    let e = refused(
        &run(&[
            "merge",
            &file("b0.csv"),
            &file("b1.csv"),
            "--out",
            &file("m.csv"),
        ]),
        "merge",
    );
    assert!(e.contains("b0.csv: run"), "{e}");
    assert!(e.contains(unrun[0]) && e.contains("--budget"), "{e}");
    assert!(!dir.join("m.csv").exists());
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_page_ends_in_html_exactly() {
    let dir = scratch("files-html");
    let s = scene("span-d3");
    for name in ["run.htm", "run.HTML", "run.Html", "run.html.txt", "run"] {
        let out = path(&dir.join(name));
        let e = refused(&run(&["view", &s, "-o", &out]), "--out");
        assert!(e.contains("must end in .html"), "{e}");
        assert!(names_in(&dir).is_empty(), "{name}");
    }
    let help = stdout(&run(&["view", "--help"]));
    assert!(help.contains("FILE.html"), "{help}");
    let out = path(&dir.join("run.html"));
    let o = run(&["view", &s, "--set", "run.t_end=0.1", "-o", &out]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    fs::remove_dir_all(&dir).unwrap();
}

/// The page's data (`#fc-data`), as the page holds it.
fn page_data(page: &str) -> &str {
    let start = page.find("type=\"application/json\">").unwrap() + 24;
    let end = start + page[start..].find("</script>").unwrap();
    &page[start..end]
}

#[test]
fn view_with_forces_keeps_the_documented_data_cap() {
    let dir = scratch("files-view-cap");
    let s = scene("span-d3");
    let cap = fc_viewer::DATA_BUDGET_BYTES;
    let out = path(&dir.join("v.html"));
    let eight = |links: &str, t_end: &str| {
        let mut args: Vec<String> = vec!["view".into()];
        args.extend(std::iter::repeat_n(s.clone(), 8));
        for set in [
            format!("chain.links={links}"),
            format!("run.t_end={t_end}"),
            "run.method=\"bdf\"".into(),
        ] {
            args.extend(["--set".into(), set]);
        }
        args.extend(["--forces".into(), "-o".into(), out.clone()]);
        args
    };
    // 8 runs of 5000 rods with forces: the first and last frames alone are
    // 2.5 MB. Refused before any run, naming --forces and the bound.
    let args = eight("5000", "10");
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let e = refused(&run_quick(&refs), "--forces");
    assert!(e.contains("at most 3511 rods"), "{e}");
    assert!(names_in(&dir).is_empty());
    // The most rods that fit: written, its data within the cap.
    let args = eight("3511", "0.001");
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = run(&refs);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let page = fs::read_to_string(&out).unwrap();
    let data = page_data(&page);
    assert!(data.len() <= cap, "{} bytes of data", data.len());
    let json: serde_json::Value = serde_json::from_str(data).unwrap();
    let runs = json["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 8);
    assert_eq!(
        runs[0]["forces"]["tension"].as_array().unwrap().len() % 3512,
        0
    );
    // --help says the bound.
    let help = stdout(&run(&["view", "--help"]));
    assert!(help.contains("3511 rods"), "{help}");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_date_time_in_a_number_key_names_the_key() {
    let dir = scratch("files-datetime");
    let file = dir.join("d.toml");
    fs::write(
        &file,
        "[chain]\nlinks = 1979-05-27T07:32:00Z\n[start]\nkind = \"folded\"\n",
    )
    .unwrap();
    let e = refused(&run(&["simulate", &path(&file)]), "chain.links");
    assert!(
        e.contains("1979-05-27T07:32:00Z") && e.contains("not a number"),
        "{e}"
    );
    let s = scene("span-d3");
    for (set, key) in [
        ("chain.damping=1979-05-27", "chain.damping"),
        ("chain.links=07:32:00", "chain.links"),
        ("run.t_end=1979-05-27T07:32:00", "run.t_end"),
        ("start.p1=[1979-05-27, 0]", "start.p1"),
        ("chain.rod_lengths=[1, 1979-05-27]", "chain.rod_lengths"),
    ] {
        let e = refused(&run(&["simulate", &s, "--set", set]), key);
        assert!(!e.contains("toml_private"), "{e}");
        assert!(e.contains("number"), "{e}");
        assert!(e.contains("1979-05-27") || e.contains("07:32:00"), "{e}");
    }
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn numbers_in_messages_are_printed_short() {
    let s = scene("span-d3");
    for (args, subject, shown) in [
        (&["--set", "chain.links=1e300"][..], "chain.links", "1e300"),
        (&["--method", "rk4", "--dt", "1e300"][..], "--dt", "1e300"),
        (
            &["--set", "run.t_end=1e300"][..],
            "run.output_dt",
            "t_end = 1e300",
        ),
        (
            &["--method", "rk4", "--set", "run.t_end=1e-300"][..],
            "run.dt",
            "run.t_end = 1e-300",
        ),
        (&["--progress", "1e-300"][..], "--progress", "1e-300"),
    ] {
        let mut all = vec!["simulate", &s];
        all.extend(args);
        let e = refused(&run(&all), subject);
        assert!(e.contains(shown), "{e}");
        // No run of 20 digits: a number is never written out in full.
        let longest = e
            .split(|c: char| !c.is_ascii_digit())
            .map(str::len)
            .max()
            .unwrap_or(0);
        assert!(longest < 20, "{e}");
    }
}
