//! `simulate --progress`: the time reached, on stderr, while a run goes on;
//! never on stdout (`--json` stays one line), and off when stderr is not a
//! terminal unless asked for.

use crate::common::{run, scene, stderr, stdout};

/// The times of the progress lines in `err`, checked against `t_end`.
fn progress_times(err: &str, t_end: f64) -> Vec<f64> {
    err.lines()
        .filter(|l| l.starts_with("simulate: t = "))
        .map(|l| {
            let rest = &l["simulate: t = ".len()..];
            let (t, tail) = rest.split_once(" of ").unwrap();
            assert!(tail.starts_with(&format!("{t_end} (")), "{l}");
            t.parse::<f64>().unwrap()
        })
        .collect()
}

#[test]
fn progress_lines_go_to_stderr_with_the_time_reached() {
    let folded = scene("folded");
    // The folded chain at n = 200 to t = 8: a few tenths of a second, many
    // periods of 0.01 s.
    let args = [
        "simulate",
        folded.as_str(),
        "--set",
        "chain.links=200",
        "--set",
        "start.down=100",
        "--method",
        "dopri5",
        "--rtol",
        "1e-9",
        "--json",
    ];
    let mut with = args.to_vec();
    with.extend_from_slice(&["--progress", "0.01"]);
    let o = run(&with);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert_eq!(out.lines().count(), 1, "{out}");
    let summary: serde_json::Value = serde_json::from_str(&out).unwrap();
    let t_end = summary["t_reached"].as_f64().unwrap();
    let times = progress_times(&stderr(&o), t_end);
    assert!(!times.is_empty(), "no progress line: {}", stderr(&o));
    assert!(times.windows(2).all(|w| w[0] <= w[1]), "{times:?}");
    assert!(
        times.iter().all(|&t| (0.0..=t_end).contains(&t)),
        "{times:?}"
    );
    // The run moves on while it is watched: the last line is past t = 0.
    assert!(times[times.len() - 1] > 0.0, "{times:?}");
    // Without the flag (stderr is a pipe here): no line, the same run.
    let o = run(&args);
    assert!(
        progress_times(&stderr(&o), t_end).is_empty(),
        "{}",
        stderr(&o)
    );
    let again: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    for key in ["tip_end", "steps", "energy_end"] {
        assert_eq!(again[key], summary[key], "{key}");
    }
}

#[test]
fn a_bad_progress_period_is_one_line_naming_the_flag() {
    for bad in ["0", "-1", "nan", "1e9"] {
        let o = run(&["simulate", &scene("folded"), "--progress", bad]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{bad}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{bad}: {err}");
        assert!(err.contains("--progress"), "{bad}: {err}");
    }
}
