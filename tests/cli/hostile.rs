//! Issue 24's reproductions run through the CLI: every size a user controls
//! is refused before anything runs (exit 2, one line naming the flag or
//! key, no file written); errors stay on one line; outputs never replace a
//! FIFO, a directory or a link; a signal leaves no temporary file behind.

use std::fs;
use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use crate::common::*;

/// A case that used to hang finishes within 10x of the nearby case that
/// did not (plus a second for process start-up): a liveness bound, not a
/// benchmark.
fn assert_ends_near(near: Duration, far: Duration) {
    assert!(
        far < near * 10 + Duration::from_secs(1),
        "{far:?} vs {near:?}"
    );
}

fn mkfifo(path: &Path) {
    let made = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(made.success());
}

fn is_fifo(path: &Path) -> bool {
    use std::os::unix::fs::FileTypeExt as _;
    fs::symlink_metadata(path)
        .map(|m| m.file_type().is_fifo())
        .unwrap_or(false)
}

/// Scene text with `extra` lines added to `[run]` of a small span scene.
fn small_scene(dir: &Path, name: &str, body: &str) -> String {
    let path = dir.join(name);
    fs::write(&path, body).unwrap();
    path.to_string_lossy().into_owned()
}

const FOLDED: &str =
    "name = \"f\"\n[chain]\nlinks = 4\n[start]\nkind = \"folded\"\n[run]\nt_end = 0.1\n";

#[test]
fn a_sweep_grid_beyond_its_cap_is_refused_unbuilt() {
    let dir = scratch("hostile-grid");
    let out_csv = dir.join("rows.csv");
    let out_arg = out_csv.to_str().unwrap();
    let s = scene("span-d3");
    for vary in [
        // 10^10 runs: the product alone would be 7.9 GB of values.
        &["chain.damping=0:1:100000", "chain.mass=1:2:100000"][..],
        // "capacity overflow" before: one COUNT of 10^14.
        &["start.p1.0=1:5:100000000000000"][..],
        // Products that overflow usize.
        &[
            "chain.damping=0:1:1000000",
            "chain.mass=1:2:1000000",
            "chain.gravity=1:2:1000000",
            "chain.length=6:7:1000000",
        ][..],
    ] {
        let mut args = vec!["sweep", s.as_str(), "--quiet", "--out", out_arg];
        for v in vary {
            args.extend(["--vary", v]);
        }
        let e = refused(&run_quick(&args), "--vary: ");
        assert!(e.contains("1000000"), "the cap is stated: {e}");
    }
    assert!(names_in(&dir).is_empty(), "{:?}", names_in(&dir));
}

#[test]
fn a_key_varied_twice_is_refused() {
    let dir = scratch("hostile-twice");
    let out_csv = dir.join("rows.csv");
    let s = scene("span-d3");
    for (a, b) in [
        ("chain.damping=0:1:2", "chain.damping=3"),
        ("start.p1=[2.0,0.0],[3.0,0.0]", "start.p1.0=2.5"),
    ] {
        let out = run_quick(&[
            "sweep",
            &s,
            "--vary",
            a,
            "--vary",
            b,
            "--out",
            out_csv.to_str().unwrap(),
        ]);
        refused(&out, "--vary: ");
    }
    // A bad value found after the output was begun: its temporary file goes.
    let out = run_quick(&[
        "sweep",
        &s,
        "--vary",
        "chain.links=5,0",
        "--out",
        out_csv.to_str().unwrap(),
    ]);
    refused(&out, "chain.links: ");
    assert!(names_in(&dir).is_empty(), "{:?}", names_in(&dir));
}

#[test]
fn jobs_are_bounded_and_never_more_than_the_runs() {
    let s = scene("span-d3");
    for command in ["sweep", "converge"] {
        for jobs in ["100000", "0", "257"] {
            let mut args = vec![command, s.as_str(), "--jobs", jobs];
            if command == "sweep" {
                args.extend(["--vary", "chain.damping=0,1", "--quiet"]);
            } else {
                args.extend(["--tol", "0.1", "--links", "4,8"]);
            }
            let e = refused(&run_quick(&args), "--jobs: ");
            assert!(e.contains("1..=256"), "{e}");
        }
    }
    // 256 threads asked for two runs: no slower than 10x one thread (the
    // pool has no more threads than runs).
    let sweep = |jobs: &str| {
        let start = Instant::now();
        let out = run_quick(&[
            "sweep",
            &s,
            "--vary",
            "chain.damping=0,0.0001",
            "--set",
            "run.t_end=0.2",
            "--quiet",
            "--jobs",
            jobs,
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        assert_eq!(stdout(&out).lines().count(), 3);
        start.elapsed()
    };
    let near = sweep("1");
    let far = sweep("256");
    assert_ends_near(near, far);
}

#[test]
fn counts_are_capped_before_anything_is_computed() {
    let dir = scratch("hostile-counts");
    for links in ["100000000", "1000000000", "18446744073709551615"] {
        let out = run_quick(&[
            "catenary", "--p1", "3,0", "--length", "6", "--links", links, "--json",
        ]);
        let e = refused(&out, "--links: ");
        assert!(e.contains("1..=1000000"), "{e}");
    }
    let png = dir.join("p.png");
    let out = run_quick(&[
        "plot",
        &scene("span-d3"),
        "-o",
        png.to_str().unwrap(),
        "--snapshots",
        "100000000",
    ]);
    refused(&out, "--snapshots: ");
    assert!(names_in(&dir).is_empty());
}

#[test]
fn catenary_inputs_of_extreme_magnitude_name_the_input() {
    // Finite inputs whose span overflows, or whose parameter underflows:
    // one line about the input, never "must be finite (got inf)" of a
    // finite point or a solver's internal failure.
    for (p0, p1, length, subject) in [
        ("-1e308,0", "1e308,0", "1.7e308", "--p0: "),
        ("0,0", "1e308,1e308", "1.7e308", "--p1: "),
        ("0,0", "1e-200,0", "2e-200", "--length: "),
    ] {
        let out = run_quick(&["catenary", "--p0", p0, "--p1", p1, "--length", length]);
        let e = refused(&out, subject);
        assert!(e.contains("1e150"), "{e}");
    }
}

#[test]
fn a_chain_of_extreme_length_is_drawn_without_a_panic() {
    // Found by the fuzzer: L = 1.8e308, its span overflows the axis range,
    // whose ticks were a capacity-overflow panic (exit 101).
    let dir = scratch("hostile-huge-plot");
    let s = small_scene(
        &dir,
        "huge.toml",
        "[chain]\nlength = 1.7976931348623157e308\nlinks = 33\n[start]\nkind = \"stretched\"\n\
         p1 = [1.0704309583493595e308, 1.444256961395157e308]\n[run]\nt_end = 0.9\n",
    );
    let png = dir.join("p.png");
    let out = run_quick(&["plot", &s, "-o", png.to_str().unwrap(), "--snapshots", "5"]);
    assert!(matches!(out.status.code(), Some(0 | 1)), "{}", stderr(&out));
    assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
}

#[test]
fn a_scene_must_be_a_small_regular_file() {
    let dir = scratch("hostile-scene-file");
    let fifo = dir.join("scene.toml");
    mkfifo(&fifo);
    let big = dir.join("big.toml");
    // 2 MB of comments: valid TOML, too large a scene.
    fs::write(&big, "# padding padding padding padding\n".repeat(60_000)).unwrap();
    for path in [
        Path::new("/dev/zero"),
        fifo.as_path(),
        dir.as_path(),
        big.as_path(),
    ] {
        let out = run_quick(&["simulate", path.to_str().unwrap()]);
        refused(&out, "scene: cannot read '");
    }
    assert!(is_fifo(&fifo));
}

#[test]
fn errors_are_one_line_whatever_the_input() {
    let dir = scratch("hostile-one-line");
    let s = scene("span-d3");
    let e = refused(
        &run_quick(&["simulate", &s, "--set", "chain.li\nnks=5"]),
        "chain.li\\nnks: ",
    );
    assert!(e.contains("unknown key"), "{e}");
    let key = small_scene(&dir, "key.toml", "\"a\\nb\" = 1\n");
    refused(&run_quick(&["simulate", &key]), "a\\nb: ");
    // An output path with a newline, in a directory that is not there.
    let out = run_quick(&["simulate", &s, "--out", "no\nsuch/a\nb.csv"]);
    let e = refused(&out, "--out: cannot write 'no\\nsuch/a\\nb.csv'");
    assert!(e.contains("directory"), "{e}");
    // A p1 of 100000 numbers (a scene file of ~0.5 MB) is echoed short.
    let long: Vec<String> = (0..100_000).map(|i| format!("{i}.5")).collect();
    let text = format!(
        "[chain]\nlinks = 4\n[start]\nkind = \"stretched\"\np1 = [{}]\n[run]\nt_end = 1\n",
        long.join(", ")
    );
    let big = small_scene(&dir, "p1.toml", &text);
    let e = refused(&run_quick(&["simulate", &big]), "start.p1: ");
    assert!(e.len() < 300, "{} characters: {}", e.len(), &e[..300]);
    assert!(e.contains("100000 elements"), "{e}");
    // A flag's long bad value (clap's own error) is cut too.
    let jobs = "9".repeat(100_000);
    let out = run_quick(&["sweep", &s, "--vary", "chain.damping=0,1", "--jobs", &jobs]);
    let e = refused(&out, "invalid value");
    assert!(e.len() < 800, "{}", e.len());
    // A long --set value is cut too.
    let arg = format!("run.method={}", "x".repeat(100_000));
    let e = refused(&run_quick(&["simulate", &s, "--set", &arg]), "run.method: ");
    assert!(e.len() < 400, "{}", e.len());
}

#[test]
fn messages_say_what_is_really_wrong() {
    let dir = scratch("hostile-messages");
    let text =
        "[chain]\nlinks = 4\n[start]\nkind = \"folded\"\n[run]\nt_end = 1\nmax_steps = 9.2e18\n";
    let e = refused(
        &run_quick(&["simulate", &small_scene(&dir, "m.toml", text)]),
        "run.max_steps: ",
    );
    assert!(e.contains("9200000000000000000"), "{e}");
    // Given through --set, the same number is an integer and runs.
    let f = small_scene(&dir, "f.toml", FOLDED);
    let out = run_quick(&["simulate", &f, "--set", "run.max_steps=9.2e18", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    // Beyond i64: the range in numbers.
    let e = refused(
        &run_quick(&["simulate", &f, "--set", "run.max_steps=1e19"]),
        "run.max_steps: ",
    );
    assert!(e.contains("1..=9223372036854775807"), "{e}");
    // A folded chain of one rod: the rods are wrong, not start.down.
    refused(
        &run_quick(&["simulate", &f, "--set", "chain.links=1"]),
        "chain.links: ",
    );
    let e = refused(
        &run_quick(&["simulate", &f, "--set", "chain.links=1.5"]),
        "chain.links: ",
    );
    assert!(e.contains("1..=1000000"), "{e}");
    let angles = small_scene(
        &dir,
        "angles.toml",
        "[chain]\nlinks = 4\n[start]\nkind = \"angles\"\nangles = [1, 2, 3]\n[run]\nt_end = 1\n",
    );
    let e = refused(&run_quick(&["simulate", &angles]), "start.angles: ");
    assert!(e.contains("chain.links = 4"), "{e}");
    let e = refused(
        &run_quick(&["simulate", &f, "--set", "start.down=4"]),
        "start.down: ",
    );
    assert!(e.contains("0..=3"), "{e}");
}

#[test]
fn converge_agrees_at_zero_gravity_where_nothing_moves() {
    // At g = 0 a chain at rest stays at rest: every level's tip speed is
    // zero and its tip stays at P1, so every n agrees and the smallest is
    // adequate.
    let out = run_quick(&[
        "converge",
        &scene("span-d3"),
        "--set",
        "chain.gravity=0",
        "--set",
        "run.t_end=0.5",
        "--tol",
        "1e-6",
        "--links",
        "4,8,16",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = json(&out);
    assert_eq!(report["adequate_links"], 4, "{report}");
    for level in report["levels"].as_array().unwrap() {
        for key in ["tip_speed_max", "tip_end", "tip_path"] {
            let d = level["deviation"][key].as_f64().unwrap_or(f64::NAN);
            assert!(d.is_finite() && d < 1e-6, "{key} = {d} in {level}");
        }
    }
    let table = run_quick(&[
        "converge",
        &scene("span-d3"),
        "--set",
        "chain.gravity=0",
        "--set",
        "run.t_end=0.5",
        "--tol",
        "1e-6",
        "--links",
        "4,8",
    ]);
    let text = stdout(&table);
    assert!(
        !text.contains("NaN") && text.contains("smallest adequate n = 4"),
        "{text}"
    );
}

/// A run long enough that it never ends within these tests by itself (and
/// whose samples, with the joint forces they may give, fit the 1 GiB cap).
fn long_run(scene_path: &str) -> Vec<String> {
    [
        "simulate",
        scene_path,
        "--set",
        "run.t_end=5e5",
        "--set",
        "run.max_steps=1000000000000",
        "--set",
        "run.output_dt=1",
    ]
    .map(String::from)
    .to_vec()
}

#[test]
fn outputs_refuse_fifos_and_directories_before_the_run() {
    let dir = scratch("hostile-fifo");
    let fifo = dir.join("out.csv");
    mkfifo(&fifo);
    let sub = dir.join("sub.csv");
    fs::create_dir(&sub).unwrap();
    let s = scene("span-d3");
    let png = dir.join("p.png");
    let gif = dir.join("a.gif");
    mkfifo(&png);
    mkfifo(&gif);
    for target in [&fifo, &sub] {
        let t = target.to_str().unwrap();
        let mut sim = long_run(&s);
        sim.extend(["--out".into(), t.into()]);
        let sim: Vec<&str> = sim.iter().map(String::as_str).collect();
        let e = refused(&run_quick(&sim), "--out: cannot write '");
        assert!(e.contains("FIFO") || e.contains("directory"), "{e}");
        let sweep = run_quick(&[
            "sweep",
            &s,
            "--vary",
            "run.t_end=1e6",
            "--set",
            "run.max_steps=1000000000000",
            "--quiet",
            "--out",
            t,
        ]);
        refused(&sweep, "--out: ");
    }
    for (command, path) in [("plot", &png), ("animate", &gif)] {
        let out = run_quick(&[
            command,
            &s,
            "--set",
            "run.t_end=1e6",
            "--set",
            "run.max_steps=1000000000000",
            "-o",
            path.to_str().unwrap(),
        ]);
        refused(&out, "--out: cannot write '");
    }
    assert!(is_fifo(&fifo) && is_fifo(&png) && is_fifo(&gif));
    assert!(sub.is_dir());
    assert_eq!(names_in(&dir), ["a.gif", "out.csv", "p.png", "sub.csv"]);
}

#[test]
fn an_output_link_is_written_through_and_stays_a_link() {
    let dir = scratch("hostile-link");
    let real = dir.join("real.csv");
    fs::write(&real, "old\n").unwrap();
    let link = dir.join("link.csv");
    std::os::unix::fs::symlink("real.csv", &link).unwrap();
    let out = run_quick(&[
        "simulate",
        &scene("span-d3"),
        "--set",
        "run.t_end=0.2",
        "--out",
        link.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(fs::symlink_metadata(&link)
        .unwrap()
        .file_type()
        .is_symlink());
    let text = fs::read_to_string(&real).unwrap();
    assert!(text.starts_with("t,tip_x,tip_y,"), "{}", &text[..20]);
    // A link to nothing is refused, and left as it is.
    let dangling = dir.join("dangling.csv");
    std::os::unix::fs::symlink("none.csv", &dangling).unwrap();
    let out = run_quick(&[
        "simulate",
        &scene("span-d3"),
        "--out",
        dangling.to_str().unwrap(),
    ]);
    refused(&out, "--out: ");
    assert_eq!(names_in(&dir), ["dangling.csv", "link.csv", "real.csv"]);
}

/// Starts a long `simulate --out`, waits for its hidden temporary file,
/// sends `signal` with kill(1) and checks that the process ends with
/// `code` and leaves the directory empty.
fn signal_removes_the_temporary_file(tag: &str, signal: &str, code: i32) {
    let dir = scratch(tag);
    let out = dir.join("long.csv");
    let mut args = long_run(&scene("span-d3"));
    args.extend(["--out".into(), out.to_string_lossy().into_owned()]);
    let mut child = Command::new(BIN)
        .args(&args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !names_in(&dir)
        .iter()
        .any(|n| n.starts_with(".long.csv.tmp-"))
    {
        assert!(
            start.elapsed() < QUICK,
            "no temporary file: {:?}",
            names_in(&dir)
        );
        assert!(child.try_wait().unwrap().is_none(), "ended early");
        std::thread::sleep(Duration::from_millis(5));
    }
    let sent = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > QUICK * 2 {
            let _ = child.kill();
            panic!("still running after {signal}");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    assert_eq!(status.code(), Some(code), "{status:?}");
    assert!(names_in(&dir).is_empty(), "{:?}", names_in(&dir));
}

#[test]
fn sigterm_removes_the_temporary_output() {
    signal_removes_the_temporary_file("hostile-sigterm", "-TERM", 143);
}

#[test]
fn sigint_removes_the_temporary_output() {
    signal_removes_the_temporary_file("hostile-sigint", "-INT", 130);
}

#[test]
fn explicit_methods_hint_at_bdf_on_stiff_scenes_and_go_on() {
    // chain.damping = 1 on 50 rods: r/(m l^2) ~ 350, stiff for DOPRI5.
    let s = scene("span-d3");
    for method in ["dopri5", "dop853"] {
        let out = run_quick(&[
            "simulate",
            &s,
            "--method",
            method,
            "--set",
            "chain.damping=1",
            "--t-end",
            "1",
            "--json",
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with(&format!("hint: {method} detected stiffness")),
            "{err}"
        );
        assert!(err.contains("bdf") && err.contains("auto"), "{err}");
        assert_eq!(json(&out)["status"], "ok");
    }
    // A sweep says it once, for all its runs.
    let out = run_quick(&[
        "sweep",
        &s,
        "--vary",
        "chain.damping=1,2,3",
        "--set",
        "run.method=dopri5",
        "--set",
        "run.t_end=1",
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("hint: 3 of 3 runs"), "{err}");
    // No hint where nothing is stiff, nor for an implicit method.
    for method in ["dopri5", "bdf"] {
        let damping = if method == "bdf" { "1" } else { "0.0005" };
        let out = run_quick(&[
            "simulate",
            &s,
            "--method",
            method,
            "--set",
            &format!("chain.damping={damping}"),
            "--t-end",
            "1",
        ]);
        assert!(out.status.success());
        assert!(out.stderr.is_empty(), "{}", stderr(&out));
    }
}

/// The hangs and aborts of issue 24 that chain-ode ends (the core branch of
/// issue 24: the observer's iteration cap, BDF's step floor, the step and
/// output budgets checked before the run). Each must end within 10x its near
/// case (or 20 s) with a status or a one-line refusal. They fail on the CLI
/// branch alone and pass once chain-ode's half is merged.
mod core {
    use super::*;

    fn ends(args: &[&str]) -> Output {
        run_within(args, QUICK).unwrap_or_else(|| panic!("hangs: {args:?}"))
    }

    #[test]
    fn the_tip_speed_search_ends_at_large_t() {
        let s = scene("span-d3");
        let case = |t_end: &str| {
            let start = Instant::now();
            let out = ends(&[
                "simulate",
                &s,
                "--set",
                "chain.links=2",
                "--method",
                "rk4",
                "--dt",
                "1e-3",
                "--t-end",
                t_end,
                "--json",
            ]);
            assert!(matches!(out.status.code(), Some(0 | 1)), "{}", stderr(&out));
            start.elapsed()
        };
        let near = case("500");
        let far = case("1000");
        assert_ends_near(near, far);
    }

    #[test]
    fn tiny_tolerances_end_at_once() {
        let s = scene("span-d3");
        for method in ["bdf", "bdf-dense"] {
            for rtol in ["1e-20", "1e-300"] {
                let out = ends(&[
                    "simulate", &s, "--method", method, "--rtol", rtol, "--atol", "1e-20",
                ]);
                assert!(matches!(out.status.code(), Some(1 | 2)), "{}", stderr(&out));
            }
        }
    }

    #[test]
    fn impossible_budgets_are_refused_before_the_run() {
        let s = scene("span-d3");
        for set in ["run.dt=1e-300", "run.output_dt=1e-9"] {
            // RK4, whose step run.dt is (the scene runs DOPRI5).
            let out = ends(&["simulate", &s, "--method", "rk4", "--set", set]);
            assert_eq!(out.status.code(), Some(2), "{set}: {}", stderr(&out));
            assert_eq!(stderr(&out).lines().count(), 1);
        }
        let out = ends(&[
            "simulate",
            &s,
            "--method",
            "bdf-dense",
            "--set",
            "chain.links=30000",
        ]);
        assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
        // One RK4 step of 1e300: not `ok`.
        let out = ends(&[
            "simulate",
            &s,
            "--method",
            "rk4",
            "--set",
            "run.dt=1e300",
            "--json",
        ]);
        assert_ne!(out.status.code(), Some(0), "{}", stdout(&out));
    }
}
