//! `falling-chain sweep`: one run per value of one or more keys.

use std::fs;

use crate::common::*;

/// The rows of a sweep CSV without the header, each with its `wall_seconds`
/// cell blanked (the only field that differs between identical runs).
fn sweep_rows(text: &str) -> (String, Vec<String>) {
    let mut lines = text.lines();
    let header = lines.next().expect("a header").to_string();
    let wall = header
        .split(',')
        .position(|c| c == "wall_seconds")
        .expect("a wall_seconds column");
    let rows = lines
        .map(|l| {
            let mut cells: Vec<&str> = l.split(',').collect();
            cells[wall] = "";
            cells.join(",")
        })
        .collect();
    (header, rows)
}

#[test]
fn sweep_shards_concatenate_to_the_whole_sweep() {
    let dir = scratch("sweep-shards");
    let common = [
        "sweep",
        &scene("span-d3"),
        "--vary",
        "start.p1.0=1.5:4.5:5",
        "--vary",
        "chain.links=8,12",
        "--set",
        "run.t_end=0.5",
        "--quiet",
    ];
    let whole_path = dir.join("whole.csv");
    let out = run(&[&common[..], &["--out", whole_path.to_str().unwrap()]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (header, whole) = sweep_rows(&fs::read_to_string(&whole_path).unwrap());
    assert_eq!(whole.len(), 10);
    assert!(header.starts_with("run,start.p1.0,chain.links,"));

    let mut merged = vec![];
    for i in 0..3 {
        let path = dir.join(format!("shard{i}.csv"));
        let shard = format!("{i}/3");
        let out = run(&[
            &common[..],
            &["--shard", &shard, "--out", path.to_str().unwrap()],
        ]
        .concat());
        assert!(out.status.success());
        let (h, rows) = sweep_rows(&fs::read_to_string(&path).unwrap());
        assert_eq!(h, header);
        merged.extend(rows);
    }
    let run_of = |r: &String| r.split(',').next().unwrap().parse::<usize>().unwrap();
    merged.sort_by_key(run_of);
    assert_eq!(merged, whole);

    // Each row is the run its values describe: links and the release point.
    let column = |name: &str| header.split(',').position(|c| c == name).unwrap();
    let (tip_x, tip_y) = (column("tip_end_x"), column("tip_end_y"));
    for row in &whole {
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(cells[4], "ok");
        assert_eq!(cells[2], cells[6], "links column matches the varied value");
        // The release point: the same scene run alone from P1 = (d, 0)
        // with those links ends where the row says, to the last digit (the
        // same method on the same start).
        let sim = run(&[
            "simulate",
            &scene("span-d3"),
            "--set",
            &format!("start.p1.0={}", cells[1]),
            "--set",
            &format!("chain.links={}", cells[2]),
            "--set",
            "run.t_end=0.5",
            "--json",
        ]);
        assert_eq!(sim.status.code(), Some(0), "{}", stderr(&sim));
        let end = pair(&json(&sim), "tip_end");
        let row_end = [
            cells[tip_x].parse::<f64>().unwrap(),
            cells[tip_y].parse::<f64>().unwrap(),
        ];
        assert!(
            (end[0] - row_end[0]).abs() < 1e-12 && (end[1] - row_end[1]).abs() < 1e-12,
            "run {}: {row_end:?} vs {end:?}",
            cells[0]
        );
        // Released at rest from (d, 0), after 0.5 the free end is still near
        // it: it has fallen (below 0) by less than a free fall's g t^2/2 can
        // explain three times over, and moved sideways less than that.
        let d: f64 = cells[1].parse().unwrap();
        let drop = -row_end[1];
        assert!(
            drop > 0.0 && drop < 3.0 * 0.125 && (row_end[0] - d).abs() < 3.0 * 0.125,
            "run {}: released at ({d}, 0), at {row_end:?} after 0.5",
            cells[0]
        );
    }
}

#[test]
fn a_sweep_with_a_failed_run_exits_1_and_still_writes_every_row() {
    // chain.damping = 0.1 gives gamma = r/(m l^2) = 34.7, a spectral radius
    // near 48 gamma = 1667: RK4 at dt = 0.01 (stable below 2.785/dt = 278)
    // must diverge; r = 0.0005 (gamma = 0.17) completes.
    let dir = scratch("sweep-failed");
    let path = dir.join("rows.csv");
    let out = run(&[
        "sweep",
        &scene("span-d3"),
        "--vary",
        "chain.damping=0.0005,0.1",
        "--set",
        "run.t_end=1",
        "--set",
        "run.method=rk4",
        "--quiet",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("1 of 2 runs failed"),
        "{}",
        stderr(&out)
    );
    let text = fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2, "both rows, the failed one too");
    assert_eq!(rows[0][column("status")], "ok");
    assert_eq!(rows[1][column("status")], "diverged");
    let t_reached: f64 = rows[1][column("t_reached")].parse().unwrap();
    let t_failed: f64 = rows[1][column("t_failed")].parse().unwrap();
    assert!(t_reached < 1.0 && (t_failed - t_reached - 0.01).abs() < 1e-12);
    assert_eq!(names_in(&dir), ["rows.csv"]);
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn sweep_rejects_a_bad_vary_key_in_one_line_naming_it() {
    let dir = scratch("sweep-bad");
    let out_path = dir.join("never.csv");
    for (vary, field) in [
        ("chain.bogus=1,2", "chain.bogus"),
        ("chain.links=2.5,3", "chain.links"),
        ("run.t_end", "--vary"),
        ("chain.damping=-1,0.1", "chain.damping"),
    ] {
        let out = run(&[
            "sweep",
            &scene("span-d3"),
            "--vary",
            vary,
            "--out",
            out_path.to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(2), "{vary}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(err.contains(field), "{vary}: {err}");
        assert!(!out_path.exists());
    }
}

/// A range over an integer key gives floats; the schema makes them integers
/// (and a fraction is an error naming the key, above).
#[test]
fn sweep_ranges_over_an_integer_key() {
    let out = run(&[
        "sweep",
        &scene("span-d3"),
        "--vary",
        "chain.links=8:12:2",
        "--set",
        "run.t_end=0.2",
        "--quiet",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let (header, rows) = sweep_rows(&stdout(&out));
    assert!(header.starts_with("run,chain.links,"), "{header}");
    let links: Vec<&str> = rows.iter().map(|r| r.split(',').nth(1).unwrap()).collect();
    assert_eq!(links, ["8", "12"]);
}
