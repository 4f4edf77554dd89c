//! The studies (`precision`, `stability`, `needs`) and their budgets under
//! hostile input (issue 38): `--budget` bounds every phase, the verdicts
//! are true of the tables, what did not run says why, every bound is
//! checked before any run, and every numeric flag of every subcommand has
//! a range, in its `--help` and in a one-line error naming the flag.
//! Expectations come from the contract (exit codes, the budget, the
//! table's own cells), never from earlier output.

use std::collections::BTreeMap;
use std::fs;
use std::time::{Duration, Instant};

use crate::common::*;

/// A CSV table of ours as rows of cells by column name (no quoted cells
/// in the columns read here).
fn table(text: &str) -> Vec<BTreeMap<String, String>> {
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .filter(|l| !l.is_empty())
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

/// The slack a budget of `b` seconds is allowed, generous for a machine
/// shared with other builds: `3 b + 5` s.
fn slack(b: f64) -> f64 {
    3.0 * b + 5.0
}

/// Runs the binary with `--budget b` among `args`, killed at four times
/// the slack: its output and wall time, after checking that it ended
/// within the slack and with a status, never a panic.
fn within_budget(args: &[&str], b: f64) -> (std::process::Output, f64) {
    let start = Instant::now();
    let o = run_within(args, Duration::from_secs_f64(4.0 * slack(b)))
        .unwrap_or_else(|| panic!("{args:?}: still running at {} s", 4.0 * slack(b)));
    let wall = start.elapsed().as_secs_f64();
    assert!(
        wall < slack(b),
        "{args:?}: {wall:.1} s for --budget {b} (slack {})",
        slack(b)
    );
    let e = stderr(&o);
    assert!(!e.contains("panicked"), "{args:?}: {e}");
    assert!(!stdout(&o).contains("NaN"), "{args:?}: {}", stdout(&o));
    (o, wall)
}

/// `precision`'s budget bounds each phase: the reference (a stiff elastic
/// chain whose reference alone runs for minutes), its RK4 check (10^7 steps
/// after a reference of milliseconds) and the methods' points (bdf-dense at
/// 400 rods, seconds a point). Each run ends within the slack, exit 1 where
/// nothing could be measured, and the table says which phase the budget
/// stopped: that row `budget: stopped at t = ...`, the rows after it not
/// run for the budget, never "every method failed".
#[test]
fn the_budget_bounds_every_phase_of_precision() {
    let dir = scratch("hostile-precision-budget");
    let out = dir.join("p.csv");
    let out_s = out.to_str().unwrap();
    let folded = scene("folded");
    let span = scene("span-d3");
    // The reference.
    let (o, _) = within_budget(
        &[
            "precision",
            &folded,
            "--set",
            "chain.axial_stiffness=600",
            "--set",
            "chain.axial_damping=1e6",
            "--quiet",
            "--budget",
            "2",
            "--out",
            out_s,
        ],
        2.0,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let rows = table(&fs::read_to_string(&out).unwrap());
    assert_eq!(rows[0]["method"], "reference-dopri5");
    assert_eq!(rows[0]["status"], "interrupted");
    assert!(
        rows[0]["note"].starts_with("budget: stopped at t = "),
        "{:?}",
        rows[0]
    );
    let points: Vec<_> = rows.iter().filter(|r| !r["run"].is_empty()).collect();
    // 11 RK4 steps, 10 tolerances of each of five adaptive methods and 6 of
    // gen-alpha's.
    assert_eq!(points.len(), 67, "every point of the ladder has its row");
    for r in &points {
        assert_eq!(r["status"], "not_run", "{r:?}");
        assert!(r["note"].contains("the reference did not finish"), "{r:?}");
    }
    let e = stderr(&o);
    assert!(e.contains("--budget stopped the reference run"), "{e}");
    assert!(!e.contains("every method failed"), "{e}");
    assert!(stdout(&o).contains("ended interrupted"), "{}", stdout(&o));

    // The reference's RK4 check: 10^7 steps of 20 rods, after a reference
    // of milliseconds.
    let (o, _) = within_budget(
        &[
            "precision",
            &span,
            "--set",
            "chain.links=20",
            "--set",
            "run.t_end=1",
            "--check-dt",
            "1e-7",
            "--methods",
            "rk4",
            "--quiet",
            "--budget",
            "2",
            "--out",
            out_s,
        ],
        2.0,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let rows = table(&fs::read_to_string(&out).unwrap());
    let by = |m: &str| rows.iter().find(|r| r["method"] == m).unwrap();
    assert_eq!(by("reference-dopri5")["status"], "ok");
    assert_eq!(by("check-rk4")["status"], "interrupted");
    assert!(by("check-rk4")["note"].starts_with("budget: stopped"));
    assert_eq!(by("check-bdf")["status"], "not_run");
    let e = stderr(&o);
    assert!(e.contains("--budget stopped its checks"), "{e}");
    assert!(!e.contains("every method failed"), "{e}");
    assert!(
        stdout(&o).contains("to - (the check did not finish)"),
        "{}",
        stdout(&o)
    );

    // The methods' points: bdf-dense at 400 rods, after a reference and
    // checks of under a second.
    let (o, _) = within_budget(
        &[
            "precision",
            &span,
            "--set",
            "chain.links=400",
            "--set",
            "run.t_end=0.3",
            "--methods",
            "bdf-dense",
            "--quiet",
            "--budget",
            "6",
            "--out",
            out_s,
        ],
        6.0,
    );
    let rows = table(&fs::read_to_string(&out).unwrap());
    let points: Vec<_> = rows.iter().filter(|r| !r["run"].is_empty()).collect();
    assert_eq!(points.len(), 10);
    assert!(
        points.iter().any(|r| r["note"].starts_with("budget")),
        "the budget stopped no point: {points:?}"
    );
    assert!(
        stdout(&o).contains("not run for --budget: bdf-dense rtol"),
        "{}",
        stdout(&o)
    );
    assert!(
        !stderr(&o).contains("every method failed"),
        "{}",
        stderr(&o)
    );
}

/// A check whose cost is known before it runs is refused when it is too
/// costly: Richardson at --check-dt 4.157e-8 (3e8 RK4 steps on span-d3),
/// and a step of 1e-300, fail at once naming `--check-dt`, its range and
/// the step bound; nothing is written.
#[test]
fn a_check_dt_past_the_step_bound_is_refused_before_any_run() {
    let dir = scratch("hostile-check-dt");
    let out = dir.join("p.csv");
    for dt in ["4.157e-8", "1e-300", "4e-7"] {
        let start = Instant::now();
        let o = run_within(
            &[
                "precision",
                &scene("span-d3"),
                "--richardson",
                "--check-dt",
                dt,
                "--methods",
                "rk4",
                "--quiet",
                "--budget",
                "2",
                "--out",
                out.to_str().unwrap(),
            ],
            Duration::from_secs(30),
        )
        .unwrap_or_else(|| panic!("--check-dt {dt}: still running after 30 s"));
        assert!(start.elapsed() < Duration::from_secs(2), "dt {dt}: ran");
        assert_eq!(o.status.code(), Some(2), "{dt}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(
            e.starts_with("error: --check-dt: must be a step in ["),
            "{e}"
        );
        assert!(e.contains("at most 1e7"), "{e}");
        assert!(!out.exists());
    }
}

/// Every bound of every method, and of the reference, is checked before
/// any run, in all three studies: bdf-dense on 1000 rods (above its 500)
/// is refused in well under a second (the reference alone takes 11 s),
/// naming `--methods` and `chain.links` with its bound.
#[test]
fn every_bound_is_checked_before_any_run() {
    let span = scene("span-d3");
    let cases: [Vec<&str>; 3] = [
        vec![
            "precision",
            &span,
            "--set",
            "chain.links=1000",
            "--methods",
            "bdf-dense",
            "--budget",
            "5",
            "--quiet",
        ],
        vec![
            "stability",
            &span,
            "--set",
            "chain.links=1000",
            "--methods",
            "bdf-dense",
            "--quiet",
        ],
        vec![
            "needs",
            &span,
            "--links",
            "25,600,1000",
            "--tol",
            "0.1",
            "--methods",
            "bdf-dense",
            "--quiet",
        ],
    ];
    for args in cases {
        let start = Instant::now();
        let o = run_within(&args, Duration::from_secs(60)).expect("it ends");
        assert!(
            start.elapsed() < Duration::from_secs(2),
            "{args:?}: {:?} before the refusal",
            start.elapsed()
        );
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(
            e.starts_with("error: --methods: bdf-dense cannot run"),
            "{e}"
        );
        assert!(e.contains("chain.links: must be at most 500"), "{e}");
    }
}

/// One claim of a verdict group, `rtol <= 1e-10`, `dt >= 5e-4`, `rtol
/// 1e-6 to 1e-4`, `rtol 1e-3` or `every dt tried`: whether accuracy `x`
/// falls in it.
fn in_group(group: &str, name: &str, x: f64) -> bool {
    let g = group.trim();
    if g == format!("every {name} tried") {
        return true;
    }
    let rest = g
        .strip_prefix(name)
        .unwrap_or_else(|| panic!("'{g}'"))
        .trim();
    if let Some(v) = rest.strip_prefix("<= ") {
        return x <= v.parse::<f64>().unwrap();
    }
    if let Some(v) = rest.strip_prefix(">= ") {
        return x >= v.parse::<f64>().unwrap();
    }
    if let Some((a, b)) = rest.split_once(" to ") {
        return x >= a.parse::<f64>().unwrap() && x <= b.parse::<f64>().unwrap();
    }
    x == rest.parse::<f64>().unwrap()
}

/// Checks that `method`'s verdict line in `out` is true of its cells in
/// `rows`: at every accuracy it says "completes every row", every row of
/// the table completed; at every accuracy it says "fails", some row
/// failed; and each claim covers at least one accuracy of the table.
fn verdict_is_true(out: &str, rows: &[BTreeMap<String, String>], method: &str) -> String {
    let prefix = format!("{method}: ");
    let line = out
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with(&prefix))
        .unwrap_or_else(|| panic!("no verdict for {method}: {out}"))
        .trim_start_matches(&prefix)
        .to_string();
    let mine: Vec<_> = rows.iter().filter(|r| r["method"] == method).collect();
    let name = mine[0]["param_name"].clone();
    let mut params: Vec<f64> = mine.iter().map(|r| r["param"].parse().unwrap()).collect();
    params.sort_by(f64::total_cmp);
    params.dedup();
    let at = |x: f64| {
        mine.iter()
            .filter(move |r| r["param"].parse::<f64>().unwrap() == x)
    };
    let passes = |x: f64| at(x).all(|r| r["outcome"] == "completed");
    let fails = |x: f64| at(x).any(|r| r["outcome"] != "completed" && r["outcome"] != "not_run");
    for part in line.split("; ") {
        let (claim, test): (&str, &dyn Fn(f64) -> bool) =
            if let Some(c) = part.strip_prefix("completes every row at ") {
                (c, &passes)
            } else if let Some(c) = part.strip_prefix("fails at ") {
                (c, &fails)
            } else {
                continue;
            };
        for group in claim.split(" and ") {
            let covered: Vec<f64> = params
                .iter()
                .copied()
                .filter(|&x| in_group(group, &name, x))
                .collect();
            assert!(!covered.is_empty(), "'{group}' covers no {name}: {line}");
            for x in covered {
                assert!(test(x), "{method}: '{part}' is false at {name} {x}: {line}");
            }
        }
    }
    line
}

/// The stability verdict is derived from the rows: with a profile whose
/// first rod is 10^6 times the rest, BDF completes at loose tolerances and
/// fails at tight ones, and the line says so (the old one said "completes
/// every row at rtol <= 1e-2; fails at rtol >= 1e-12", both false of the
/// CSV); RK4's limit on a damped chain is true of its table as well.
#[test]
fn the_stability_verdict_is_true_of_its_table() {
    let dir = scratch("hostile-stability-verdict");
    let out = dir.join("s.csv");
    let ones = vec!["1"; 49].join(",");
    let profile = format!("chain.rod_lengths=[1e6,{ones}]");
    let o = run(&[
        "stability",
        &scene("folded"),
        "--set",
        &profile,
        "--methods",
        "bdf",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.code() == Some(0), "{}", stderr(&o));
    let rows = table(&fs::read_to_string(&out).unwrap());
    let line = verdict_is_true(&stdout(&o), &rows, "bdf");
    // The table has both kinds here, and the line both claims.
    assert!(rows.iter().any(|r| r["outcome"] == "completed"), "{rows:?}");
    assert!(rows.iter().any(|r| r["outcome"] != "completed"), "{rows:?}");
    assert!(
        line.contains("completes every row at") && line.contains("fails at"),
        "{line}"
    );

    let o = run(&[
        "stability",
        &scene("span-d3"),
        "--set",
        "chain.links=10",
        "--set",
        "run.t_end=1",
        "--methods",
        "rk4,dopri5",
        "--vary",
        "chain.damping=1,4",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = table(&fs::read_to_string(&out).unwrap());
    verdict_is_true(&stdout(&o), &rows, "rk4");
    verdict_is_true(&stdout(&o), &rows, "dopri5");
}

/// Rows not run say why, and the verdict never says "none tried" or
/// "fails nowhere" of a method that did not run: a spent budget gives
/// "not run (budget: ...)" and exit 1 ("no cell ran within --budget"); a
/// method whose every run failed (RK4 on a chain damped so hard that every
/// step diverges) "fails everywhere tried", and "every method failed" is
/// said only then, when every cell ran.
#[test]
fn cells_not_run_say_why_and_a_method_failing_everywhere_says_so() {
    let dir = scratch("hostile-stability-not-run");
    let out = dir.join("s.csv");
    let small = [
        "--set",
        "chain.links=10",
        "--set",
        "run.t_end=1",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    let span = scene("span-d3");
    let o = run(&[
        &[
            "stability",
            &span,
            "--methods",
            "dopri5,rk4",
            "--budget",
            "1e-9",
        ][..],
        &small,
    ]
    .concat());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let s = stdout(&o);
    assert!(
        !s.contains("none tried") && !s.contains("fails nowhere"),
        "{s}"
    );
    assert!(s.contains("dopri5: not run (budget: "), "{s}");
    assert_eq!(
        stderr(&o).lines().last(),
        Some("no cell ran within --budget")
    );
    for r in table(&fs::read_to_string(&out).unwrap()) {
        assert_eq!(r["outcome"], "not_run");
        assert!(r["note"].starts_with("budget"), "{r:?}");
    }

    let o = run(&[
        &[
            "stability",
            &span,
            "--methods",
            "rk4",
            "--set",
            "chain.damping=1000",
        ][..],
        &small,
    ]
    .concat());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let rows = table(&fs::read_to_string(&out).unwrap());
    assert!(rows.iter().all(|r| r["outcome"] != "completed"), "{rows:?}");
    let s = stdout(&o);
    assert!(s.contains("rk4: fails everywhere tried"), "{s}");
    assert!(!s.contains("none tried"), "{s}");
    assert_eq!(
        stderr(&o).lines().last(),
        Some("every method failed on this scene at every step and tolerance")
    );
}

/// `stability`'s budget bounds its cells: DOPRI5 on 50 rods up to t = 2000
/// (up to the step budget, seconds a cell: at t = 200 every cell finished
/// within the 2 s on an idle machine, so the budget stopped nothing, measured
/// 2026-12-04) ends within the slack, and
/// what it stopped is listed; never "every method failed" for cells never
/// run.
#[test]
fn the_budget_bounds_stability() {
    let dir = scratch("hostile-stability-budget");
    let out = dir.join("s.csv");
    let (o, _) = within_budget(
        &[
            "stability",
            &scene("span-d3"),
            "--set",
            "run.t_end=2000",
            "--methods",
            "dopri5",
            "--quiet",
            "--budget",
            "2",
            "--out",
            out.to_str().unwrap(),
        ],
        2.0,
    );
    assert!(matches!(o.status.code(), Some(0 | 1)), "{}", stderr(&o));
    let rows = table(&fs::read_to_string(&out).unwrap());
    assert!(
        rows.iter().any(|r| r["note"].starts_with("budget")),
        "the budget stopped nothing: {rows:?}"
    );
    assert!(
        stdout(&o).contains("not run for --budget: dopri5"),
        "{}",
        stdout(&o)
    );
    let e = stderr(&o);
    assert!(!e.contains("every method failed"), "{e}");
}

/// `needs`' budget bounds each phase: the ladder of n (2000 rods to t =
/// 100, stiff: minutes), and the reference (a ladder of 4 and 8 damped
/// rods in a fraction of a second, then a reference and its RK4 check of
/// 3e7 steps to t = 3000). Each ends within the slack, exit 1, and says
/// what the budget stopped: never "no method reaches --tol" when no
/// method ran, never NaN.
#[test]
fn the_budget_bounds_every_phase_of_needs() {
    let span = scene("span-d3");
    let (o, _) = within_budget(
        &[
            "needs",
            &span,
            "--set",
            "run.t_end=100",
            "--links",
            "100,2000",
            "--tol",
            "1e-3",
            "--budget",
            "2",
            "--quiet",
            "--json",
        ],
        2.0,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    assert!(v["links"].is_null(), "{v}");
    let e = stderr(&o);
    assert!(e.contains("--budget stopped the ladder"), "{e}");

    let damped = [
        "needs",
        &span,
        "--set",
        "chain.links=4",
        "--set",
        "chain.damping=1",
        "--set",
        "run.t_end=3000",
        "--links",
        "4,8",
        "--tol",
        "0.5",
        "--budget",
        "3",
        "--quiet",
    ];
    let (o, _) = within_budget(&[&damped[..], &["--json"]].concat(), 3.0);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["links"].as_u64(), Some(4), "{v}");
    assert!(v["fastest"].is_null(), "{v}");
    let skipped: Vec<&str> = v["skipped"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    assert!(
        skipped.iter().any(|s| s.starts_with("the reference")),
        "{skipped:?}"
    );
    let e = stderr(&o);
    assert!(!e.contains("no method reaches"), "{e}");
    assert!(
        e.contains("--budget stopped the reference") || e.contains("no method ran within --budget"),
        "{e}"
    );
    // The table says the same, with no NaN (`within_budget` checks).
    let (o, _) = within_budget(&damped, 3.0);
    let s = stdout(&o);
    assert!(!s.contains("no method reaches"), "{s}");
    assert!(!s.contains("does not reach"), "{s}");
}

/// `--methods ""` names no method: refused by every study with one line
/// naming the flag and listing the names, rather than running them all.
#[test]
fn an_empty_methods_list_is_refused() {
    let span = scene("span-d3");
    for cmd in ["precision", "stability", "needs"] {
        let mut args = vec![cmd, &span, "--methods", "", "--quiet"];
        if cmd == "needs" {
            args.extend(["--tol", "0.1"]);
        }
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{cmd}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.starts_with("error: --methods: names no method"), "{e}");
        assert!(
            e.contains("rk4, dopri5, dop853, bdf, bdf-dense, auto"),
            "{e}"
        );
    }
}

/// The numeric flags of every subcommand, each with the other arguments
/// it needs (a tiny scene, so that a value in range runs in a moment).
fn numeric_flags() -> Vec<(Vec<String>, &'static str)> {
    let span = scene("span-d3");
    let tiny = [
        "--set",
        "chain.links=3",
        "--set",
        "run.t_end=0.05",
        "--quiet",
    ];
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    let with = |cmd: &str, extra: &[&str]| {
        let mut v = s(&[cmd, &span]);
        v.extend(s(&tiny[..4]));
        v.extend(s(extra));
        v
    };
    let quiet = |cmd: &str, extra: &[&str]| {
        let mut v = with(cmd, extra);
        v.push("--quiet".into());
        v
    };
    vec![
        (s(&["catenary", "--p1", "3,0"]), "--length"),
        (s(&["catenary", "--p1", "3,0", "--length", "6"]), "--links"),
        (s(&["catenary", "--length", "6"]), "--p1"),
        (s(&["catenary", "--p1", "3,0", "--length", "6"]), "--p0"),
        (with("simulate", &["--method", "rk4"]), "--dt"),
        (with("simulate", &[]), "--rtol"),
        (with("simulate", &[]), "--atol"),
        (with("simulate", &[]), "--t-end"),
        (with("simulate", &[]), "--progress"),
        (with("sweep", &["--vary", "start.p1.0=2,3"]), "--jobs"),
        (with("sweep", &["--vary", "start.p1.0=2,3"]), "--shard"),
        (with("plot", &["-o", "x.svg"]), "--snapshots"),
        (with("animate", &["-o", "x.gif"]), "--fps"),
        (with("animate", &["-o", "x.gif"]), "--seconds"),
        (with("converge", &["--links", "3,4"]), "--tol"),
        (with("converge", &["--tol", "0.1"]), "--links"),
        (
            with("converge", &["--tol", "0.1", "--links", "3,4"]),
            "--rtol",
        ),
        (
            with("converge", &["--tol", "0.1", "--links", "3,4"]),
            "--jobs",
        ),
        (quiet("precision", &["--methods", "rk4"]), "--budget"),
        (quiet("precision", &["--methods", "rk4"]), "--check-dt"),
        (quiet("precision", &["--methods", "rk4"]), "--jobs"),
        (quiet("precision", &["--methods", "rk4"]), "--shard"),
        (quiet("stability", &["--methods", "rk4"]), "--budget"),
        (quiet("stability", &["--methods", "rk4"]), "--jobs"),
        (
            quiet("needs", &["--links", "3,4", "--methods", "rk4"]),
            "--tol",
        ),
        (
            quiet("needs", &["--tol", "0.5", "--methods", "rk4"]),
            "--links",
        ),
        (
            quiet(
                "needs",
                &["--tol", "0.5", "--links", "3,4", "--methods", "rk4"],
            ),
            "--budget",
        ),
        (
            quiet(
                "needs",
                &["--tol", "0.5", "--links", "3,4", "--methods", "rk4"],
            ),
            "--jobs",
        ),
    ]
}

/// Every numeric flag of every subcommand has a range: given 1e300,
/// 1e-300, 0, -1, nan or inf it either refuses with one line naming the
/// flag (exit 2, nothing written), or, where the value is in its range
/// (a budget of 1e-300 s, a tolerance of 1e-300 in `--rtol`'s...), runs
/// to a status within a minute, never a panic, a hang or a NaN. And the
/// range is in the flag's `--help`.
#[test]
fn every_numeric_flag_has_a_range_in_its_error_and_its_help() {
    let dir = scratch("hostile-flags");
    for (args, flag) in numeric_flags() {
        for value in ["1e300", "1e-300", "0", "-1", "nan", "inf"] {
            let mut a: Vec<String> = args
                .iter()
                .map(|x| match x.as_str() {
                    "x.svg" | "x.gif" => dir.join(x).to_str().unwrap().to_string(),
                    _ => x.clone(),
                })
                .collect();
            a.extend([flag.to_string(), value.to_string()]);
            let refs: Vec<&str> = a.iter().map(String::as_str).collect();
            let o = run_within(&refs, Duration::from_secs(60))
                .unwrap_or_else(|| panic!("{refs:?}: still running after 60 s"));
            let e = stderr(&o);
            assert!(!e.contains("panicked"), "{refs:?}: {e}");
            match o.status.code() {
                Some(2) => {
                    assert_eq!(e.lines().count(), 1, "{refs:?}: {e}");
                    let named = e.starts_with(&format!("error: {flag}: "))
                        || e.contains(&format!("for '{flag} <"));
                    assert!(named, "{refs:?}: the error does not name {flag}: {e}");
                    assert!(
                        names_in(&dir).is_empty(),
                        "{refs:?}: wrote {:?}",
                        names_in(&dir)
                    );
                }
                Some(0 | 1) => {
                    let s = stdout(&o);
                    assert!(!s.contains("NaN") && !s.contains("nan"), "{refs:?}: {s}");
                    for f in names_in(&dir) {
                        fs::remove_file(dir.join(f)).unwrap();
                    }
                }
                other => panic!("{refs:?}: exit {other:?}: {e}"),
            }
        }
        // Its range, in its help: a number or an interval after it.
        let cmd = args[0].as_str();
        let help = stdout(&run(&[cmd, "--help"]));
        // The flag's entry: its line and the lines after it, to a blank one.
        let lines: Vec<&str> = help.lines().collect();
        let start = lines
            .iter()
            .position(|l| {
                let l = l.trim_start();
                l.starts_with(&format!("{flag} ")) || l.contains(&format!(", {flag} "))
            })
            .unwrap_or_else(|| panic!("{cmd} --help has no {flag}: {help}"));
        let text: String = lines[start..]
            .iter()
            .take_while(|l| !l.trim().is_empty())
            .copied()
            .collect::<Vec<_>>()
            .join(" ");
        let ranged = ["..=", "in (", "in [", "in 1..", "0 <= I < N", "at most"]
            .iter()
            .any(|r| text.contains(r));
        assert!(ranged, "{cmd} --help gives no range for {flag}: {text}");
    }
}
