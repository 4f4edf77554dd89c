//! Issue 47's defects, each run as the hostile run found it: a closed
//! standard output, outputs onto inputs, the ensemble's flags and
//! messages, the stability study on a row that cannot run, a merge of
//! shards without rows, numbers at the ends of their ranges.

use std::process::{Command, Stdio};

use crate::common::*;

/// Every command that prints to standard output, on a pipe whose reader
/// has already gone (`... | head -0`): an ordinary end, exit 0 (the run
/// is fine) with no panic and no "Broken pipe" on stderr. The pipe's
/// read end is closed before the binary starts, so every write fails
/// (the race of `| head -3` made certain).
#[test]
fn a_closed_standard_output_is_an_ordinary_end_for_every_command() {
    let span = scene("span-d3");
    let dir = scratch("closed-stdout");
    let out = dir.join("o.csv");
    let out = out.to_str().unwrap();
    let short = ["--set", "chain.links=6", "--set", "run.t_end=0.2"];
    let cases: Vec<Vec<&str>> = vec![
        vec!["catenary", "--p1", "1,0", "--length", "2", "--links", "50"],
        vec!["catenary", "--p1", "1,0", "--length", "2", "--json"],
        [&["simulate", &span][..], &short].concat(),
        [&["simulate", &span, "--json", "--out", out][..], &short].concat(),
        [
            &["sweep", &span, "--vary", "chain.damping=0,1e-3", "--quiet"][..],
            &short,
        ]
        .concat(),
        [
            &[
                "sweep",
                &span,
                "--vary",
                "chain.damping=0,1e-3",
                "--json",
                "--quiet",
            ][..],
            &short,
        ]
        .concat(),
        [
            &["converge", &span, "--links", "3,6", "--tol", "0.5"][..],
            &short[2..],
        ]
        .concat(),
        [
            &["precision", &span, "--methods", "rk4", "--quiet"][..],
            &short,
        ]
        .concat(),
        [
            &["stability", &span, "--methods", "rk4", "--quiet"][..],
            &short,
        ]
        .concat(),
        [
            &["needs", &span, "--links", "3,6", "--tol", "0.5", "--quiet"][..],
            &short[2..],
        ]
        .concat(),
        [
            &["ensemble", &span, "--members", "2", "--quiet"][..],
            &short,
        ]
        .concat(),
        [
            &["ensemble", &span, "--members", "2", "--json", "--quiet"][..],
            &short,
        ]
        .concat(),
    ];
    for args in cases {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = Command::new(BIN)
            .args(&args)
            .stdin(Stdio::null())
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let err = stderr(&o);
        assert!(
            !err.contains("panicked") && !err.contains("Broken pipe") && !err.contains("error:"),
            "{args:?}: {err}"
        );
        assert!(
            matches!(o.status.code(), Some(0) | Some(141)),
            "{args:?}: {:?} {err}",
            o.status
        );
    }
}
