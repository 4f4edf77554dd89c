//! Issue 38's model-side defects, each a run a hostile user made, checked
//! against the physics: a profile's stiffest rod (H2), a pivot motion
//! shorter than a step (W1), a start angle too large to turn (W2), a span
//! or a release shorter than the step floor (W3), the report's model where
//! it has no meaning (P1, P2) and the stiffness hint under it (U3).

use std::fs;
use std::time::Duration;

use crate::common::*;

fn ok_json(args: &[&str]) -> serde_json::Value {
    let o = run(args);
    assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
    json(&o)
}

fn first_method(v: &serde_json::Value) -> String {
    v["segments"][0]["method"]
        .as_str()
        .unwrap_or_else(|| panic!("no segments in {v}"))
        .to_string()
}

/// Refused before any run: exit 2, one line naming `key` (`common::refused`).
fn refused(args: &[&str], key: &str) -> String {
    crate::common::refused(&run_quick(args), key)
}

/// H2: the folded scene (n = 50, L = 6, m = 0.2, r = 0.001) with its first
/// rod 1e6 times the others: those 49 rods are `l_i = 6 / (1e6 + 49)` long,
/// and, the mass per length being uniform, as light: `m_i = M l_i / L`
/// (`M = n m = 10`). The friction damps them at `r / (m_i l_i^2)`, 1e13
/// times the mean rod's rate. `auto` must see that rate (and run BDF, which takes a
/// fraction of a second, where DOPRI5 ran past two minutes) and so must
/// the summary's `damping_rate`.
#[test]
fn auto_and_the_damping_rate_see_the_stiffest_rod_of_a_profile() {
    let ones = ["1"; 49].join(",");
    let lengths = format!("chain.rod_lengths=[1e6,{ones}]");
    let path = scene("folded");
    let args = [
        "simulate", &path, "--json", "--method", "auto", "--t-end", "1e-6", "--set", &lengths,
    ];
    let o = run_within(&args, Duration::from_secs(60)).expect("auto ends within 60 s");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    let l_short = 6.0 / (1e6 + 49.0);
    let m_short = 10.0 * l_short / 6.0;
    let expected = 0.001 / (m_short * l_short * l_short);
    let rate = num(&v, "damping_rate");
    assert!(
        (rate / expected - 1.0).abs() < 1e-9,
        "{rate} against {expected}"
    );
    assert_eq!(first_method(&v), "bdf", "{v}");
}

/// H2: a taper of 1000 puts the lightest rod at the tip:
/// `m_n = m * 2 (1 + (k - 1) / (2 n)) / (k + 1)` (the linear mass per
/// length `k - (k - 1) s / L` over the last rod, against its mean
/// `(k + 1) / 2`), so the stiffest rate is `r / (m_n l^2)`; with
/// `r = 0.02` it is past auto's crossover and auto runs BDF from the start.
#[test]
fn a_taper_makes_auto_run_bdf_at_the_tip_rods_damping_rate() {
    let path = scene("folded");
    let v = ok_json(&[
        "simulate",
        &path,
        "--json",
        "--method",
        "auto",
        "--set",
        "chain.taper=1000",
        "--set",
        "chain.damping=0.02",
        "--t-end",
        "0.5",
    ]);
    let (k, n, m, l) = (1000.0_f64, 50.0_f64, 0.2_f64, 6.0 / 50.0);
    let m_tip = m * 2.0 * (1.0 + (k - 1.0) / (2.0 * n)) / (k + 1.0);
    let expected = 0.02 / (m_tip * l * l);
    let rate = num(&v, "damping_rate");
    assert!(
        (rate / expected - 1.0).abs() < 1e-9,
        "{rate} against {expected}"
    );
    assert_eq!(first_method(&v), "bdf", "{v}");
}

/// A chain hanging straight down at rest, its pivot jerked straight up by
/// `D = 0.5` in `tau`: an inextensible chain moves as one rigid body, so
/// the support does the work `M g D` (the kinetic energy is zero again at
/// the jerk's end), `W = -M g D`, and `E(t) - E(0) = M g D`.
fn hanging_jerked_up(dir: &std::path::Path, tau: f64) -> String {
    let down = ["-1.5707963267948966"; 10].join(", ");
    let text = format!(
        "name = \"hanging-jerked-up\"\n\
         [chain]\nlength = 2.0\nlinks = 10\nmass = 0.1\ngravity = 1.0\ndamping = 0.001\n\
         [pivot]\njerk = [0.0, 0.5]\njerk_time = {tau}\n\
         [start]\nkind = \"angles\"\np0 = [0.0, 0.0]\nangles = [{down}]\n\
         [run]\nt_end = 0.1\nmethod = \"dopri5\"\nrtol = 1e-8\natol = 1e-10\n"
    );
    let path = dir.join("hanging.toml");
    fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// W1: a jerk shorter than the first step the controller would take (from
/// rest at equilibrium the drive is zero at `t = 0`, and every stage past
/// `tau` sees it zero again). Every adaptive explicit method must resolve
/// it: the support's work `M g D = 0.5` must be in `W`. (BDF is not capped:
/// it finds the jerk from its own first steps, and its `W` is 1% off here.)
#[test]
fn a_jerk_shorter_than_the_first_step_is_resolved() {
    let dir = scratch("hostile-model-jerk");
    let path = hanging_jerked_up(&dir, 1e-2);
    let mgd = 10.0 * 0.1 * 1.0 * 0.5;
    for method in ["dopri5", "dop853", "auto"] {
        let v = ok_json(&["simulate", &path, "--json", "--method", method]);
        assert_eq!(v["status"], "ok", "{method}: {v}");
        let w = num(&v, "dissipated");
        assert!(
            (w + mgd).abs() < 1e-3 * mgd,
            "{method}: W = {w}, not -{mgd}"
        );
        let rise = num(&v, "energy_end") - num(&v, "energy_start");
        assert!((rise - mgd).abs() < 1e-6, "{method}: E rose by {rise}");
        let tip = pair(&v, "tip_end");
        assert!((tip[1] + 1.5).abs() < 1e-9, "{method}: tip at {tip:?}");
    }
    let _ = fs::remove_dir_all(&dir);
}

/// W1: RK4's fixed step must resolve the jerk too: a step longer than
/// `tau / 16` is refused, naming the flag (`--dt`) and `pivot.jerk_time`.
#[test]
fn rk4_refuses_a_step_longer_than_the_jerk_allows() {
    let dir = scratch("hostile-model-rk4-jerk");
    let path = hanging_jerked_up(&dir, 1e-2);
    let e = refused(
        &["simulate", &path, "--method", "rk4", "--dt", "1e-3"],
        "--dt",
    );
    assert!(
        e.contains("pivot.jerk_time") && e.contains("6.25e-4"),
        "{e}"
    );
    let v = ok_json(&[
        "simulate", &path, "--json", "--method", "rk4", "--dt", "5e-4",
    ]);
    let w = num(&v, "dissipated");
    assert!((w + 0.5).abs() < 1e-3 * 0.5, "rk4: W = {w}");
    let _ = fs::remove_dir_all(&dir);
}

/// W1: BDF is not capped; a jerk of 1e-6 on the jerked support is stepped
/// over (the drive's work is missing, a balance error of about 5 against a
/// work of almost nothing): the run must not be `ok`.
#[test]
fn a_stepped_over_drive_is_not_ok() {
    let path = scene("jerked-support");
    let o = run(&[
        "simulate",
        &path,
        "--json",
        "--method",
        "bdf",
        "--set",
        "pivot.jerk_time=1e-6",
    ]);
    let v = json(&o);
    assert_ne!(v["status"], "ok", "{v}");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

fn angles_scene(dir: &std::path::Path, name: &str, angles: &[f64]) -> String {
    let list: Vec<String> = angles.iter().map(|a| format!("{a:e}")).collect();
    let text = format!(
        "name = \"{name}\"\n\
         [chain]\nlength = 4.0\nlinks = 4\nmass = 1.0\ngravity = 1.0\ndamping = 0.01\n\
         [start]\nkind = \"angles\"\np0 = [0.0, 0.0]\nangles = [{}]\n\
         [run]\nt_end = 2.0\nmethod = \"dop853\"\nrtol = 1e-10\natol = 1e-12\n",
        list.join(", ")
    );
    let path = dir.join(format!("{name}.toml"));
    fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// W2: an angle is defined modulo 2 pi, so a start with one angle turned
/// by a whole turn is the same motion (the tip to 1e-9 L); an angle past
/// two turns (1e300 froze its rod) is refused by name.
#[test]
fn start_angles_are_bounded_and_a_turn_changes_nothing() {
    let dir = scratch("hostile-model-angles");
    let tau = std::f64::consts::TAU;
    let base = angles_scene(&dir, "base", &[0.0, -0.3, 0.4, -1.0]);
    let turned = angles_scene(&dir, "turned", &[0.0, -0.3, 0.4 + tau, -1.0 - tau]);
    let a = ok_json(&["simulate", &base, "--json"]);
    let b = ok_json(&["simulate", &turned, "--json"]);
    let (ta, tb) = (pair(&a, "tip_end"), pair(&b, "tip_end"));
    assert!(
        (ta[0] - tb[0]).abs() < 4e-9 && (ta[1] - tb[1]).abs() < 4e-9,
        "{ta:?} against {tb:?}"
    );
    for bad in [1e300, 13.0, -13.0] {
        let path = angles_scene(&dir, "bad", &[0.0, 0.0, bad, 0.0]);
        let e = refused(&["simulate", &path], "start.angles");
        assert!(e.contains("4 pi"), "{e}");
    }
    let _ = fs::remove_dir_all(&dir);
}

/// W3: a span or a release shorter than the rounding floor of the step
/// (1e-14) is still a well-posed run. Both ends let go at once: every rod
/// falls freely, so the tip's speed at `t_end` is `g t_end` (span d = 3,
/// at rest).
#[test]
fn spans_and_releases_below_the_step_floor_run() {
    let path = scene("span-d3");
    for method in ["dopri5", "dop853", "auto"] {
        for t_end in ["1e-15", "1e-300"] {
            let v = ok_json(&[
                "simulate", &path, "--json", "--method", method, "--t-end", t_end,
            ]);
            assert_eq!(v["status"], "ok", "{method} t_end {t_end}: {v}");
            assert_eq!(num(&v, "t_reached"), t_end.parse::<f64>().unwrap());
        }
        for release in ["pivot.release=1e-15", "pivot.release=1e-300"] {
            let v = ok_json(&[
                "simulate", &path, "--json", "--method", method, "--t-end", "2", "--set", release,
            ]);
            assert_eq!(v["status"], "ok", "{method} {release}: {v}");
            let vy = pair(&v, "tip_velocity_end")[1];
            assert!((vy + 2.0).abs() < 1e-9, "{method} {release}: {vy}");
        }
    }
}

/// P1: the report's model has a time unit `sqrt(l / g)` that changes with
/// n, so its ladder is not one problem refined: converge refuses it.
#[test]
fn converge_refuses_the_reports_model() {
    let path = scene("span-d3");
    refused(
        &[
            "converge",
            &path,
            "--tol",
            "0.01",
            "--set",
            "model.report=true",
        ],
        "model.report",
    );
}

/// P2: the report's clock unit `sqrt(l / g)` is infinite at g = 0.
#[test]
fn the_reports_model_refuses_zero_gravity() {
    let path = scene("span-d3");
    for g in ["0", "0.0"] {
        let set = format!("chain.gravity={g}");
        refused(
            &[
                "simulate",
                &path,
                "--set",
                "model.report=true",
                "--set",
                &set,
            ],
            "chain.gravity",
        );
    }
    // The corrected model runs at g = 0 as before.
    let v = ok_json(&[
        "simulate",
        &path,
        "--json",
        "--set",
        "chain.gravity=0",
        "--t-end",
        "0.5",
    ]);
    assert_eq!(v["status"], "ok");
}

/// U3: under the report's model the hint may not suggest `--method bdf or
/// auto` as if they ran there: it names the report's methods and the way
/// out (`model.report = false`).
#[test]
fn the_stiffness_hint_under_the_reports_model_names_its_methods() {
    let path = scene("span-d3");
    let o = run(&[
        "simulate",
        &path,
        "--set",
        "model.report=true",
        "--set",
        "chain.damping=0.5",
        "--method",
        "dopri5",
        "--t-end",
        "2",
    ]);
    let e = stderr(&o);
    let hint = e
        .lines()
        .find(|l| l.starts_with("hint:"))
        .unwrap_or_else(|| panic!("no hint: {e}"));
    assert!(hint.contains("only rk4, dopri5 and dop853"), "{hint}");
    assert!(hint.contains("model.report = false"), "{hint}");
}
