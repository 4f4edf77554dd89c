//! `falling-chain view` without a browser: the page is self-contained and
//! within its size, its data are the run's (geometry checked against the
//! scene), a run read back from `--out`'s CSV recovers the chain, a failed
//! run is written with exit 1, and bad input is one line, exit 2, no file.

use std::fs;
use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::common::{json, num, pair, run, scene, scratch, stderr};

/// The page's data object (`#fc-data`).
pub fn page_data(path: &Path) -> Value {
    let page = fs::read_to_string(path).unwrap();
    let open = "<script id=\"fc-data\" type=\"application/json\">";
    let start = page.find(open).unwrap() + open.len();
    let end = start + page[start..].find("</script>").unwrap();
    serde_json::from_str(&page[start..end]).unwrap()
}

/// Runs `view` with `args` then `-o dir/name`; returns the page's path.
pub fn view(dir: &Path, name: &str, args: &[&str]) -> (PathBuf, std::process::Output) {
    let out = dir.join(name);
    let mut all = vec!["view"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", out.to_str().unwrap()]);
    let o = run(&all);
    (out, o)
}

/// The joints of `phi` (absolute angles) from `p0` with rods of `l`.
fn tip_of(p0: [f64; 2], l: f64, phi: &[f64]) -> [f64; 2] {
    phi.iter()
        .fold(p0, |[x, y], a| [x + l * a.cos(), y + l * a.sin()])
}

#[test]
fn a_page_is_self_contained_and_its_frames_are_the_runs() {
    let dir = scratch("view-inline");
    let (page, o) = view(&dir, "fall.html", &[&scene("span-d3")]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = fs::read_to_string(&page).unwrap();
    // Nothing is fetched: no URL, no external script, style or image.
    for needle in ["http:", "https:", "src=", "<link", "@import", "url("] {
        assert!(!text.contains(needle), "the page holds '{needle}'");
    }
    let data = page_data(&page);
    let r = &data["runs"][0];
    let n = 50;
    assert_eq!(r["links"], n);
    // The scene: L = 6, n = 50, P0 = (0, 0); t_end 4.157 at output_dt 0.08.
    assert!((num(r, "rod") - 6.0 / 50.0).abs() < 1e-15);
    assert_eq!(pair(r, "anchor"), [0.0, 0.0]);
    let t = r["t"].as_array().unwrap();
    let phi: Vec<f64> = r["phi"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(phi.len(), t.len() * n);
    assert_eq!(r["stride"], 1);
    // The last frame's tip, from the page's 6-decimal angles, is the run's
    // tip_end to the rounding of the angles (n l 5e-7 = 3e-6).
    let sim = json(&run(&["simulate", &scene("span-d3"), "--json"]));
    let tip = tip_of([0.0, 0.0], 0.12, &phi[phi.len() - n..]);
    let end = pair(&sim, "tip_end");
    assert!(
        (tip[0] - end[0]).hypot(tip[1] - end[1]) < 3e-6,
        "{tip:?} {end:?}"
    );
    // At t = 0 the chain hangs from P0 to P1 = (3, 0).
    let start = tip_of([0.0, 0.0], 0.12, &phi[..n]);
    assert!((start[0] - 3.0).hypot(start[1]) < 3e-6, "{start:?}");
}

#[test]
fn a_50_rod_8_s_run_fits_2_mb_unthinned_and_a_long_run_is_thinned() {
    let dir = scratch("view-size");
    let eight = ["--set", "run.t_end=8", "--set", "run.output_dt=0.01"];
    let mut args = vec![scene("span-d3")];
    args.extend(eight.iter().map(|s| s.to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (page, o) = view(&dir, "fifty.html", &args);
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = fs::metadata(&page).unwrap().len();
    assert!(bytes <= 2_000_000, "{bytes} bytes");
    let r = &page_data(&page)["runs"][0];
    assert_eq!(
        (r["stride"].as_u64(), r["samples"].as_u64()),
        (Some(1), Some(801))
    );
    // 2000 rods over 801 samples cannot fit: every k-th sample and the last.
    let (page, o) = view(
        &dir,
        "long.html",
        &[
            &scene("span-d3"),
            "--set",
            "chain.links=2000",
            "--set",
            "run.t_end=0.05",
            "--set",
            "run.output_dt=0.0001",
            "--set",
            "run.dt=0.0001",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = fs::metadata(&page).unwrap().len();
    assert!(bytes <= 2_000_000, "{bytes} bytes");
    let r = &page_data(&page)["runs"][0];
    let stride = r["stride"].as_u64().unwrap();
    let samples = r["samples"].as_u64().unwrap();
    let t: Vec<f64> = r["t"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(stride > 1 && samples == 501, "{stride} {samples}");
    assert_eq!(t.len() as u64, (samples - 1).div_ceil(stride) + 1);
    assert!((t[1] - stride as f64 * 1e-4).abs() < 1e-12 && (t[t.len() - 1] - 0.05).abs() < 1e-12);
}

#[test]
fn a_run_read_from_its_csv_recovers_the_chain_and_its_forces() {
    let dir = scratch("view-from");
    let csv = dir.join("run.csv");
    let o = run(&[
        "simulate",
        &scene("span-d3"),
        "--json",
        "--set",
        "run.output_dt=0.01",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let sim = json(&o);
    let (page, o) = view(&dir, "from.html", &["--from", csv.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = &page_data(&page)["runs"][0];
    // The least squares over the rows give back the scene's l and P0.
    assert!((num(r, "rod") - 0.12).abs() < 1e-12, "{}", r["rod"]);
    let p0 = pair(r, "anchor");
    assert!(p0[0].abs() < 1e-12 && p0[1].abs() < 1e-12, "{p0:?}");
    let s = &r["summary"];
    assert_eq!(pair(s, "tip_end"), pair(&sim, "tip_end"));
    // The maximum over samples 0.01 apart is at most the continuous one,
    // and within 1% of it (the whip's peak is 10.6 at t = 2.76).
    let (sampled, continuous) = (num(s, "tip_speed_max"), num(&sim, "tip_speed_max"));
    assert!(
        sampled <= continuous && sampled > 0.99 * continuous,
        "{sampled} {continuous}"
    );
    assert_eq!(r["forces"], Value::Null);

    // Joint forces as extra columns: tension_j = j + k (row k), shear = -j.
    let text = fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let mut out = lines.next().unwrap().to_string();
    for j in 0..=50 {
        out.push_str(&format!(",tension_{j}"));
    }
    for j in 0..=50 {
        out.push_str(&format!(",shear_{j}"));
    }
    out.push('\n');
    for (k, line) in lines.enumerate() {
        out.push_str(line);
        for j in 0..=50 {
            out.push_str(&format!(",{}", j + k));
        }
        for j in 0..=50 {
            out.push_str(&format!(",{}", -(j as f64)));
        }
        out.push('\n');
    }
    let forced = dir.join("forced.csv");
    fs::write(&forced, out).unwrap();
    let (page, o) = view(&dir, "forced.html", &["--from", forced.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = &page_data(&page)["runs"][0];
    let tension = r["forces"]["tension"].as_array().unwrap();
    let frames = r["t"].as_array().unwrap().len();
    assert_eq!(tension.len(), frames * 51);
    assert_eq!(tension[51 + 7].as_f64(), Some(8.0), "row 1, joint 7");
    assert_eq!(r["forces"]["shear"][3].as_f64(), Some(-3.0));
}

#[test]
fn a_failed_run_is_written_with_its_status_and_exit_1() {
    // The folded whip diverges under RK4 at dt = 0.01 (scenes/folded.toml).
    let dir = scratch("view-failed");
    let (page, o) = view(&dir, "failed.html", &[&scene("folded"), "--method", "rk4"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let r = &page_data(&page)["runs"][0];
    assert_ne!(r["status"], "ok");
    let t_failed = num(r, "t_failed");
    let t: Vec<f64> = r["t"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(t_failed < 4.157 && *t.last().unwrap() <= t_failed);
}

#[test]
fn bad_input_is_one_line_exit_2_and_no_file() {
    let dir = scratch("view-bad");
    let sim = dir.join("run.csv");
    assert!(run(&[
        "simulate",
        &scene("span-d3"),
        "--out",
        sim.to_str().unwrap()
    ])
    .status
    .success());
    let good = fs::read_to_string(&sim).unwrap();
    let header = good.lines().next().unwrap().to_string();
    let row = |k: usize| good.lines().nth(k).unwrap().to_string();
    let write = |name: &str, text: String| {
        let p = dir.join(name);
        fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    };
    // A row whose tip is moved off the angles' chain by 1e-3.
    let moved = {
        let mut cells: Vec<String> = row(3).split(',').map(String::from).collect();
        cells[1] = (cells[1].parse::<f64>().unwrap() + 1e-3).to_string();
        cells.join(",")
    };
    let cases: Vec<(Vec<String>, &str, &str)> = vec![
        (
            vec![
                "--from".into(),
                dir.join("absent.csv").to_str().unwrap().into(),
            ],
            "--from",
            "absent",
        ),
        (
            vec!["--from".into(), write("empty.csv", String::new())],
            "--from",
            "empty",
        ),
        (
            vec!["--from".into(), write("header.csv", "t,x\n1,2\n".into())],
            "--from",
            "header",
        ),
        (
            vec![
                "--from".into(),
                write(
                    "nan.csv",
                    format!(
                        "{header}\n{}\n{}\n",
                        row(1),
                        row(2).replacen(',', ",nan,", 1)
                    ),
                ),
            ],
            "--from",
            "finite",
        ),
        (
            vec![
                "--from".into(),
                write("short.csv", format!("{header}\n{}\n1,2\n", row(1))),
            ],
            "--from",
            "cells",
        ),
        (
            vec![
                "--from".into(),
                write("back.csv", format!("{header}\n{}\n{}\n", row(2), row(1))),
            ],
            "--from",
            "increase",
        ),
        (
            vec![
                "--from".into(),
                write(
                    "moved.csv",
                    format!("{header}\n{}\n{}\n{moved}\n", row(1), row(2)),
                ),
            ],
            "--from",
            "do not match",
        ),
        (
            vec![
                "--from".into(),
                write("one.csv", format!("{header}\n{}\n", row(1))),
            ],
            "--from",
            "at least 2",
        ),
        (
            vec![
                "--from".into(),
                write("extra.csv", format!("{header},x\n{},1\n", row(1))),
            ],
            "--from",
            "unexpected column",
        ),
        (
            vec!["--from".into(), dir.to_str().unwrap().into()],
            "--from",
            "regular file",
        ),
        (
            (0..9).map(|_| scene("span-d3")).collect(),
            "SCENE.toml/--from",
            "1 to 8",
        ),
        (vec![], "SCENE.toml/--from", "1 to 8"),
        (
            vec![
                scene("span-d3"),
                "--set".into(),
                "chain.links=5001".into(),
                "--set".into(),
                "chain.taper=10".into(),
            ],
            "chain.links",
            "5000 rods of unequal",
        ),
        (
            vec![scene("span-d3"), "--method".into(), "rk4,nonesuch".into()],
            "run.method",
            "one of",
        ),
        (
            vec![scene("span-d3"), "--set".into(), "chain.links=20000".into()],
            "chain.links",
            "10000",
        ),
    ];
    for (args, field, says) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (page, o) = view(&dir, "bad.html", &args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(field) && err.contains(says), "{args:?}: {err}");
        assert!(!page.exists(), "{args:?} wrote a page");
    }
    // Outputs that cannot be written: a missing directory, a directory, a
    // name that is not .html.
    let target = dir.join("a-directory.html");
    fs::create_dir_all(&target).unwrap();
    for out in [dir.join("absent/fall.html"), target, dir.join("fall.png")] {
        let o = run(&["view", &scene("span-d3"), "-o", out.to_str().unwrap()]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{out:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("--out"), "{err}");
    }
    let left: Vec<_> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.contains("html") && n != "a-directory.html")
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// `view --forces` carries each run's joint forces, the very ones
/// `simulate --forces` writes (to the page's 5 significant digits), for
/// an elastic chain; without the flag a page has none.
#[test]
fn view_forces_carries_the_runs_joint_forces() {
    let dir = scratch("view-forces");
    let set = [
        "--set",
        "chain.links=8",
        "--set",
        "chain.axial_stiffness=1e4",
        "--set",
        "run.t_end=0.5",
        "--set",
        "run.output_dt=0.05",
        "--set",
        "run.method=dopri5",
    ];
    let span = scene("span-d3");
    let forces_csv = dir.join("forces.csv");
    let mut args = vec!["simulate", &span];
    args.extend(set);
    args.extend(["--forces", forces_csv.to_str().unwrap()]);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut args = vec![span.as_str()];
    args.extend(set);
    let (plain, o) = view(&dir, "plain.html", &args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(page_data(&plain)["runs"][0]["forces"], Value::Null);
    args.push("--forces");
    let (page, o) = view(&dir, "forces.html", &args);
    assert!(o.status.success(), "{}", stderr(&o));
    let r = &page_data(&page)["runs"][0];
    let tension = r["forces"]["tension"].as_array().unwrap();
    let shear = r["forces"]["shear"].as_array().unwrap();
    let text = fs::read_to_string(&forces_csv).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(r["t"].as_array().unwrap().len(), rows.len());
    assert_eq!(tension.len(), rows.len() * 9);
    let scale = rows
        .iter()
        .flat_map(|row| row[1..].iter())
        .fold(0.0f64, |m, v| m.max(v.abs()));
    for (k, row) in rows.iter().enumerate() {
        for j in 0..=8 {
            let (t, s) = (row[1 + 2 * j], row[2 + 2 * j]);
            let (pt, ps) = (
                tension[k * 9 + j].as_f64().unwrap(),
                shear[k * 9 + j].as_f64().unwrap(),
            );
            assert!(
                (pt - t).abs() <= 1e-4 * t.abs() + 1e-9 * scale,
                "row {k} joint {j}: {pt} {t}"
            );
            assert!(
                (ps - s).abs() <= 1e-4 * s.abs() + 1e-9 * scale,
                "row {k} joint {j}: {ps} {s}"
            );
        }
    }
}
