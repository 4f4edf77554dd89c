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
    for row in &whole {
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(cells[4], "ok");
        assert_eq!(cells[2], cells[6], "links column matches the varied value");
    }
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
