//! `falling-chain precision`, `stability`, `needs` and `merge`: the study on
//! any scene. Small scenes (n = 10, t_end = 1) keep each test to a second
//! or so; the expectations are the methods' orders, RK4's stability limit
//! and the refinement, never earlier output.

use std::collections::BTreeMap;
use std::fs;

use crate::common::*;

/// A CSV table as columns of text by name.
fn table(text: &str) -> (Vec<String>, Vec<BTreeMap<String, String>>) {
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .filter(|l| !l.is_empty())
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect();
    (header, rows)
}

fn f(row: &BTreeMap<String, String>, col: &str) -> f64 {
    row[col].parse().unwrap_or(f64::NAN)
}

const SMALL: [&str; 4] = ["--set", "chain.links=10", "--set", "run.t_end=1"];

/// The least work (RHS evaluations + JVPs) at which `method` reaches an
/// error of `level`, if it does.
fn least_work(rows: &[BTreeMap<String, String>], method: &str, level: f64) -> Option<f64> {
    rows.iter()
        .filter(|r| r["method"] == method && r["status"] == "ok" && !r["run"].is_empty())
        .filter(|r| f(r, "err_tip").max(f(r, "err_vmax")) <= level)
        .map(|r| f(r, "rhs_equiv"))
        .min_by(f64::total_cmp)
}

/// An eighth-order pair needs fewer evaluations than a fifth-order one once
/// the error is small: at every level from 1e-8 to 1e-10 DOP853's least
/// work is below DOPRI5's, and its work grows more slowly as the error
/// falls (slope of log work against log error: about -1/8 against -1/5).
#[test]
fn precision_ranks_dop853_ahead_of_dopri5_at_tight_error() {
    let dir = scratch("precision-rank");
    let out = dir.join("p.csv");
    let o = run(&[
        &["precision", &scene("span-d3")][..],
        &SMALL,
        &[
            "--methods",
            "dopri5,dop853",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ],
    ]
    .concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("reference: DOPRI5 rtol 1e-13"),
        "{}",
        stdout(&o)
    );
    let (header, rows) = table(&fs::read_to_string(&out).unwrap());
    assert!(header.ends_with(&["wall_seconds", "run", "runs", "scene_hash"].map(String::from)));
    for level in [1e-8, 1e-9, 1e-10] {
        let (a, b) = (
            least_work(&rows, "dop853", level).unwrap(),
            least_work(&rows, "dopri5", level).unwrap(),
        );
        assert!(a < b, "at {level:e}: dop853 {a} vs dopri5 {b}");
    }
    let slope = |m: &str| {
        let pts: Vec<(f64, f64)> = [1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
            .iter()
            .map(|&l: &f64| (l.ln(), least_work(&rows, m, l).unwrap().ln()))
            .collect();
        let k = pts.len() as f64;
        let (mx, my) = pts
            .iter()
            .fold((0.0, 0.0), |a, p| (a.0 + p.0 / k, a.1 + p.1 / k));
        let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
        sxy / sxx
    };
    let (s8, s5) = (slope("dop853"), slope("dopri5"));
    assert!(
        s8 > s5 && s8 < 0.0 && s5 < -0.1,
        "slopes {s8} (dop853), {s5} (dopri5)"
    );
}

/// RK4 on a chain with strong joint friction is limited by the damping
/// eigenvalues, which grow like r: the step where it starts to diverge
/// falls like 1/r. For r = 1, 4, 16 the bracket [largest step that
/// completed, smallest that diverged], times r, is one interval for all.
#[test]
fn stability_finds_rk4_diverging_above_a_step_that_falls_like_one_over_r() {
    let dir = scratch("stability-rk4");
    let out = dir.join("s.csv");
    let o = run(&[
        &["stability", &scene("span-d3")][..],
        &SMALL,
        &[
            "--methods",
            "rk4",
            "--vary",
            "chain.damping=1,4,16",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ],
    ]
    .concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let (_, rows) = table(&fs::read_to_string(&out).unwrap());
    assert_eq!(rows.len(), 3 * 8);
    let mut scaled = vec![];
    for r in [1.0, 4.0, 16.0] {
        let mine: Vec<_> = rows.iter().filter(|x| f(x, "damping") == r).collect();
        let ok = mine
            .iter()
            .filter(|x| x["outcome"] == "completed")
            .map(|x| f(x, "param"))
            .fold(0.0, f64::max);
        let bad = mine
            .iter()
            .filter(|x| x["outcome"] == "diverged")
            .map(|x| f(x, "param"))
            .fold(f64::INFINITY, f64::min);
        assert!(
            ok > 0.0 && bad.is_finite() && ok < bad,
            "r = {r}: {ok} {bad}"
        );
        // Diverged above, completed below: a limit, not noise.
        for x in &mine {
            let dt = f(x, "param");
            let want = if dt <= ok { "completed" } else { "diverged" };
            assert_eq!(x["outcome"], want, "r = {r}, dt = {dt}");
        }
        scaled.push((ok * r, bad * r));
    }
    let lo = scaled.iter().map(|s| s.0).fold(0.0, f64::max);
    let hi = scaled.iter().map(|s| s.1).fold(f64::INFINITY, f64::min);
    assert!(lo < hi, "r dt brackets do not overlap: {scaled:?}");
    assert!(
        stdout(&o).contains("rk4: completes every row at dt <= 2e-4"),
        "{}",
        stdout(&o)
    );
}

/// `needs` and `converge` share the ladder: on the same ladder, method and
/// tolerance they find the same n; the friction of a nearly frictionless
/// chain is a term it does not need, that of a strongly damped one is.
#[test]
fn needs_finds_the_n_that_converge_finds_and_the_terms_it_needs() {
    let ladder = ["--links", "5,10,20,40"];
    let conv = run(&[
        &["converge", &scene("span-d3")][..],
        &SMALL,
        &ladder,
        &[
            "--tol", "1e-2", "--method", "auto", "--rtol", "1e-5", "--json",
        ],
    ]
    .concat());
    assert!(conv.status.success(), "{}", stderr(&conv));
    let want = json(&conv)["adequate_links"].as_u64().unwrap();
    let o = run(&[
        &["needs", &scene("span-d3")][..],
        &SMALL,
        &ladder,
        &["--tol", "1e-2", "--json", "--quiet"],
    ]
    .concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["links"].as_u64().unwrap(), want, "{v}");
    assert_eq!(v["ladder"]["adequate_links"].as_u64().unwrap(), want);
    let fastest = &v["fastest"];
    assert!(fastest["error"].as_f64().unwrap() <= 1e-2, "{fastest}");
    let term = |damping: &str| {
        let o = run(&[
            &["needs", &scene("span-d3")][..],
            &SMALL,
            &ladder,
            &["--set", damping, "--tol", "1e-2", "--json", "--quiet"],
        ]
        .concat());
        assert!(o.status.success(), "{}", stderr(&o));
        let t = json(&o)["terms"][0].clone();
        assert_eq!(t["key"], "chain.damping");
        t["needed"].as_bool().unwrap()
    };
    assert!(!term("chain.damping=1e-8"));
    assert!(term("chain.damping=2"));
}

/// A sweep run in three shards and merged is the unsharded sweep, byte for
/// byte but for wall times; merge refuses a missing run, a run given twice
/// and shards of another scene, with one line, exit 2 and no output.
#[test]
fn a_sweep_in_three_shards_merges_to_the_unsharded_sweep() {
    let dir = scratch("merge");
    let common = [
        "sweep",
        &scene("span-d3"),
        "--vary",
        "start.p1.0=1.5:4.5:4",
        "--vary",
        "chain.links=8,12",
        "--set",
        "run.t_end=0.5",
        "--quiet",
    ];
    let p = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let o = run(&[&common[..], &["--out", &p("whole.csv")]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    for i in 0..3 {
        let shard = format!("{i}/3");
        let o = run(&[
            &common[..],
            &["--shard", &shard, "--out", &p(&format!("s{i}.csv"))],
        ]
        .concat());
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let o = run(&[
        "merge",
        &p("s2.csv"),
        &p("s0.csv"),
        &p("s1.csv"),
        "--out",
        &p("all.csv"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let blank_walls = |text: String| {
        let (header, _) = table(&text);
        let w = header.iter().position(|c| c == "wall_seconds").unwrap();
        let rows: Vec<String> = text
            .lines()
            .skip(1)
            .map(|l| {
                let mut c: Vec<&str> = l.split(',').collect();
                c[w] = "";
                c.join(",")
            })
            .collect();
        assert_eq!(rows.len(), 8);
        (header, rows)
    };
    assert_eq!(
        blank_walls(fs::read_to_string(p("all.csv")).unwrap()),
        blank_walls(fs::read_to_string(p("whole.csv")).unwrap())
    );
    // Another scene's shard: the same runs of a different t_end.
    let mut other = common.to_vec();
    other[7] = "run.t_end=0.4";
    let o = run(&[&other[..], &["--shard", "1/3", "--out", &p("other1.csv")]].concat());
    assert!(o.status.success());
    for (files, why) in [
        (vec![p("s0.csv"), p("s1.csv")], "runs 2, 5 are missing"),
        (
            vec![p("s0.csv"), p("s1.csv"), p("s2.csv"), p("s1.csv")],
            "given twice",
        ),
        (
            vec![p("s0.csv"), p("other1.csv"), p("s2.csv")],
            "another study",
        ),
    ] {
        let out = p("bad.csv");
        let mut args: Vec<&str> = vec!["merge"];
        args.extend(files.iter().map(String::as_str));
        args.extend(["--out", &out]);
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.starts_with("error: merge: ") && e.contains(why), "{e}");
        assert!(!dir.join("bad.csv").exists());
    }
}

/// `precision` on the report's span d = 3 runs the points of the study's
/// `wp-span-d3` figure: its table, without the CLI's wall time, run and
/// provenance columns, is `figures/data/wp-span-d3.csv` byte for byte (the
/// figure's plan runs every point there but RK4's two finest, past the
/// floor, which the CLI's lines skip by the same rule). A parity check of
/// the two callers of the one study, not a physics test.
#[test]
fn precision_on_the_report_scene_is_its_figure_data() {
    let dir = scratch("precision-wp");
    let out = dir.join("p.csv");
    // The figure's methods (fc_paper_figures::PAPER_METHODS).
    let o = run(&[
        "precision",
        &scene("span-d3"),
        "--quiet",
        "--methods",
        "rk4,dopri5,dop853,bdf,bdf-dense,auto",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mine: String = fs::read_to_string(&out)
        .unwrap()
        .lines()
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            format!("{}\n", c[..c.len() - 4].join(","))
        })
        .collect();
    let data = fs::read_to_string(scenes_dir().join("../figures/data/wp-span-d3.csv")).unwrap();
    assert_eq!(mine, data);
}

/// Bad flags: one line naming the flag, exit 2, no output file.
#[test]
fn study_flags_are_checked_by_name() {
    let dir = scratch("study-flags");
    let out = dir.join("x.csv");
    let out = out.to_str().unwrap();
    let span = scene("span-d3");
    for (args, flag) in [
        (
            vec!["precision", &span, "--budget", "-1", "--out", out],
            "--budget",
        ),
        (
            vec!["precision", &span, "--methods", "rk5", "--out", out],
            "--methods",
        ),
        (
            vec!["precision", &span, "--check-dt", "0", "--out", out],
            "--check-dt",
        ),
        (
            vec!["precision", &span, "--shard", "3/3", "--out", out],
            "--shard",
        ),
        (
            vec!["precision", &span, "--plot", "x.txt", "--out", out],
            "--plot",
        ),
        (
            vec![
                "stability",
                &span,
                "--vary",
                "chain.links=0:1:2000",
                "--out",
                out,
            ],
            "--vary",
        ),
        (
            vec!["stability", &span, "--budget", "nan", "--out", out],
            "--budget",
        ),
        (vec!["needs", &span, "--tol", "2"], "--tol"),
        (
            vec!["needs", &span, "--tol", "0.1", "--links", "7"],
            "--links",
        ),
    ] {
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.lines().count(), 1, "{e}");
        assert!(e.starts_with(&format!("error: {flag}: ")), "{args:?}: {e}");
        assert!(!dir.join("x.csv").exists());
    }
}

/// A budget too small for any run: the budget holds from the reference
/// on, so the reference is stopped at once (its row says where), every
/// point is listed as not run for the budget with that reason, exit 1, the
/// table still written.
#[test]
fn a_spent_budget_skips_and_lists_the_points() {
    let dir = scratch("budget");
    let out = dir.join("b.csv");
    let o = run(&[
        &["precision", &scene("span-d3")][..],
        &SMALL,
        &[
            "--methods",
            "bdf",
            "--budget",
            "1e-9",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ],
    ]
    .concat());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("not run for --budget: reference-dopri5 rtol 1e-13, bdf rtol 1e-3"),
        "{}",
        stdout(&o)
    );
    assert!(
        stderr(&o)
            .lines()
            .last()
            .unwrap()
            .starts_with("--budget stopped the reference run (DOPRI5 rtol 1e-13) at t = 0"),
        "{}",
        stderr(&o)
    );
    let (_, rows) = table(&fs::read_to_string(&out).unwrap());
    assert_eq!(rows[0]["status"], "interrupted");
    // None was started: past the deadline, no point is predicted to fit.
    let budget: Vec<_> = rows
        .iter()
        .filter(|r| r["note"] == "budget: not run: the reference did not finish within --budget")
        .collect();
    assert_eq!(budget.len(), 10);
}

/// The CLI's `--plot` is the paper's drawing (`study::plot`) of the table
/// it writes: the work-precision pair with the reference's agreement note
/// and a legend line per method, the stability map with a panel per
/// method and the paper's cell legend.
#[test]
fn the_plots_are_the_papers_drawing_of_the_table() {
    let dir = scratch("plots");
    let wp = dir.join("wp.svg");
    let o = run(&[
        &["precision", &scene("span-d3")][..],
        &SMALL,
        &[
            "--methods",
            "dopri5,dop853",
            "--quiet",
            "--plot",
            wp.to_str().unwrap(),
        ],
    ]
    .concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let svg = fs::read_to_string(&wp).unwrap();
    for text in [
        "Work-precision: span-d3 (n = 10)",
        "reference: DOPRI5 rtol 1e-13; checks:",
        "DOPRI5 (rtol 1e-3",
        "DOP853 (rtol 1e-3",
    ] {
        assert!(svg.contains(text), "no '{text}' in the plot");
    }
    let map = dir.join("map.svg");
    let o = run(&[
        &["stability", &scene("span-d3")][..],
        &SMALL,
        &[
            "--methods",
            "rk4",
            "--quiet",
            "--plot",
            map.to_str().unwrap(),
        ],
    ]
    .concat());
    assert!(
        o.status.code() == Some(0) || o.status.code() == Some(1),
        "{}",
        stderr(&o)
    );
    let svg = fs::read_to_string(&map).unwrap();
    for text in [
        "RK4: step dt",
        "completed, energy error",
        "(−5: 1e-5 to 1e-4)",
    ] {
        assert!(svg.contains(text), "no '{text}' in the map");
    }
    fs::remove_dir_all(&dir).unwrap();
}

/// needs' budget holds in every phase, the ladder of n first: a budget
/// spent at the start stops the ladder's runs (which without it answer n,
/// as the test above shows), lists them as not run, and gives no n.
#[test]
fn a_spent_budget_stops_the_ladder_of_needs() {
    let o = run(&[
        &["needs", &scene("span-d3")][..],
        &SMALL,
        &[
            "--links",
            "5,10,20,80",
            "--tol",
            "1e-2",
            "--budget",
            "1e-9",
            "--json",
            "--quiet",
        ],
    ]
    .concat());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    assert!(v["links"].is_null(), "{v}");
    let skipped: Vec<&str> = v["skipped"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|s| s.as_str())
        .collect();
    assert!(
        skipped.iter().any(|s| s.starts_with("rods n = ")),
        "{skipped:?}"
    );
}

/// precision in three shards, merged, is the unsharded table but for wall
/// times, RK4's floor rule included: a shard decides it from the coarser
/// steps it does not own, so its later points are `not_run` as in the
/// whole (a scene where RK4 reaches the reference's level early).
#[test]
fn precision_in_three_shards_merges_to_the_unsharded_table_floor_included() {
    let dir = scratch("precision-shards");
    let p = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let span = scene("span-d3");
    let common = [
        "precision",
        &span,
        "--set",
        "chain.links=10",
        "--set",
        "run.t_end=1",
        "--methods",
        "rk4,dopri5",
        "--quiet",
    ];
    let o = run(&[&common[..], &["--out", &p("whole.csv")]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let mut merge = vec!["merge".to_string()];
    for i in 0..3 {
        let (shard, out) = (format!("{i}/3"), p(&format!("s{i}.csv")));
        let o = run(&[&common[..], &["--shard", &shard, "--out", &out]].concat());
        assert!(o.status.success(), "{}", stderr(&o));
        merge.push(out);
    }
    merge.extend(["--out".to_string(), p("all.csv")]);
    let o = run(&merge.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(o.status.success(), "{}", stderr(&o));
    let blank_walls = |text: String| -> Vec<String> {
        let (header, _) = table(&text);
        let w = header.iter().position(|c| c == "wall_seconds").unwrap();
        text.lines()
            .map(|l| {
                let mut c: Vec<&str> = l.split(',').collect();
                c[w] = "";
                c.join(",")
            })
            .collect()
    };
    let whole = blank_walls(fs::read_to_string(p("whole.csv")).unwrap());
    let floored = whole.iter().filter(|l| l.contains("a coarser dt")).count();
    assert!(
        floored >= 3,
        "RK4 never reached the floor: the test tests nothing"
    );
    assert_eq!(
        blank_walls(fs::read_to_string(p("all.csv")).unwrap()),
        whole
    );
}

/// `--measure tip` is the default, byte for byte: the same table (but the
/// wall times) and the same lines (but the timed ones) as no `--measure`.
#[test]
fn measure_tip_is_the_default() {
    let dir = scratch("measure-tip");
    let sc = scene("span-d3");
    let go = |extra: &[&str], out: &std::path::Path| {
        let mut args = vec![
            "precision",
            sc.as_str(),
            "--set",
            "chain.links=6",
            "--set",
            "run.t_end=1.0",
            "--quiet",
            "--methods",
            "dopri5,bdf",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = run(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let table: Vec<String> = fs::read_to_string(out)
            .unwrap()
            .lines()
            .map(|l| {
                let mut c: Vec<&str> = l.split(',').collect();
                c.remove(20); // wall_seconds
                c.join(",")
            })
            .collect();
        let text = String::from_utf8(o.stdout).unwrap();
        let lines: Vec<String> = text.lines().take(2).map(str::to_string).collect();
        (table, lines)
    };
    let plain = go(&[], &dir.join("a.csv"));
    let tip = go(&["--measure", "tip"], &dir.join("b.csv"));
    assert_eq!(plain, tip);
    // A force measured: its error and reference value are the last columns;
    // the tip's errors stay `err_tip` and `err_vmax`, each one column.
    let force = go(&["--measure", "pivot_force_max,tip"], &dir.join("c.csv"));
    let header = &force.0[0];
    assert!(
        header.ends_with(",scene_hash,err_pivot_force_max,pivot_force_max_ref"),
        "{header}"
    );
    assert_eq!(
        header.split(',').filter(|c| *c == "err_tip").count(),
        1,
        "{header}"
    );
}

/// A measure the scene cannot have, or no measure at all, is refused by
/// every study with one line naming `--measure` and this scene's accepted
/// values, exit 2, and no output file.
#[test]
fn a_bad_measure_is_refused_by_every_study() {
    let dir = scratch("measure-bad");
    let out = dir.join("x.csv");
    let sc = scene("span-d3");
    let o_ = out.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "precision",
            &sc,
            "--measure",
            "floor_force_max",
            "--out",
            o_,
        ],
        vec!["stability", &sc, "--measure", "floor_reading", "--out", o_],
        vec!["needs", &sc, "--tol", "1e-3", "--measure", "speed"],
        vec!["ensemble", &sc, "--measure", "", "--out", o_],
        vec![
            "converge",
            &sc,
            "--tol",
            "1e-3",
            "--measure",
            "floor_force_max",
        ],
    ];
    for args in cases {
        let o = run(&args);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
        assert_eq!(e.trim().lines().count(), 1, "{args:?}: {e}");
        assert!(e.contains("--measure"), "{args:?}: {e}");
        assert!(
            e.contains("tip, tip_speed_max, pivot_force_max, tension_max, dissipated"),
            "{args:?}: {e}"
        );
        assert!(!out.exists(), "{args:?}");
    }
}
