//! Helpers shared by the end-to-end tests: the binary, the scene files,
//! scratch directories and reading outputs.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Duration;

use serde_json::Value;

pub const BIN: &str = env!("CARGO_BIN_EXE_falling-chain");

/// The contract keys of `simulate --json`.
pub const CONTRACT_KEYS: [&str; 16] = [
    "status",
    "method",
    "links",
    "t_reached",
    "steps",
    "rejected_steps",
    "rhs_evals",
    "jacobian_evals",
    "wall_seconds",
    "energy_start",
    "energy_end",
    "dissipated",
    "energy_balance_error",
    "tip_end",
    "tip_speed_max",
    "t_tip_speed_max",
];

pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

pub fn scene(name: &str) -> String {
    scenes_dir()
        .join(format!("{name}.toml"))
        .to_string_lossy()
        .into_owned()
}

/// A fresh, empty directory for one test.
pub fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("falling-chain-cli-{test}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

pub fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("the binary runs")
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

pub fn json(o: &Output) -> Value {
    serde_json::from_str(stdout(o).trim())
        .unwrap_or_else(|e| panic!("not one JSON object ({e}): {}", stdout(o)))
}

pub fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("'{key}' is not a number in {v}"))
}

pub fn pair(v: &Value, key: &str) -> [f64; 2] {
    let a = v[key]
        .as_array()
        .unwrap_or_else(|| panic!("'{key}' in {v}"));
    assert_eq!(a.len(), 2, "{key}");
    [a[0].as_f64().unwrap(), a[1].as_f64().unwrap()]
}

/// The tip from the angles, summed here: `P0 + l sum (cos phi, sin phi)`.
pub fn tip_by_hand(p0: [f64; 2], length: f64, angles: &[f64]) -> [f64; 2] {
    let l = length / angles.len() as f64;
    angles
        .iter()
        .fold(p0, |r, phi| [r[0] + l * phi.cos(), r[1] + l * phi.sin()])
}

pub fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Runs the binary with a wall-clock limit: `None` if it had to be stopped
/// at `limit` (a hang: SIGTERM, then SIGKILL), else its output.
pub fn run_within(args: &[&str], limit: std::time::Duration) -> Option<Output> {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = Command::new(BIN)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    let out = child.stdout.take().unwrap();
    let err = child.stderr.take().unwrap();
    let reader = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = vec![];
            let _ = pipe.read_to_end(&mut bytes);
            bytes
        })
    };
    let (out_thread, err_thread) = (reader(Box::new(out)), reader(Box::new(err)));
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break Some(status);
        }
        if start.elapsed() > limit {
            // SIGTERM first, so that the CLI removes its temporary file;
            // SIGKILL if it does not end within two seconds.
            let _ = Command::new("kill")
                .args(["-TERM", &child.id().to_string()])
                .status();
            let term = std::time::Instant::now();
            while child.try_wait().unwrap().is_none()
                && term.elapsed() < std::time::Duration::from_secs(2)
            {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    };
    let stdout = out_thread.join().unwrap();
    let stderr = err_thread.join().unwrap();
    status.map(|status| Output {
        status,
        stdout,
        stderr,
    })
}

/// The liveness bound of a refusal: it must come before any run, so in far
/// less than this (a run these tests would start takes minutes or more).
pub const QUICK: Duration = Duration::from_secs(20);

pub fn run_quick(args: &[&str]) -> Output {
    run_within(args, QUICK).unwrap_or_else(|| panic!("still running after {QUICK:?}: {args:?}"))
}

/// Exit 2 with exactly one line on stderr, `error: SUBJECT: ...`.
#[track_caller]
pub fn refused(out: &Output, subject: &str) -> String {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "not one line: {err:?}");
    assert!(err.ends_with('\n'), "{err:?}");
    let prefix = format!("error: {subject}");
    assert!(err.starts_with(&prefix), "want '{prefix}...', got {err:?}");
    assert!(out.stdout.is_empty(), "{}", stdout(out));
    err.trim_end().to_string()
}
