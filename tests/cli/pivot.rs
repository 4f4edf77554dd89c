//! The shipped scenes of a moving or released pivot (issue 18) through the
//! command line: `both-ends-let-go` falls as one rigid body at `g`, and
//! `jerked-support` runs with its energy balance kept (the support's work
//! counted), and each `pivot.*` error is one line naming its key.

use crate::common::*;

fn simulate_json(name: &str, extra: &[&str]) -> serde_json::Value {
    let path = scene(name);
    let mut args = vec!["simulate", path.as_str(), "--json"];
    args.extend(extra);
    let o = run(&args);
    assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
    json(&o)
}

#[test]
fn both_ends_let_go_fall_as_one_body_at_g() {
    let v = simulate_json("both-ends-let-go", &[]);
    assert_eq!(v["status"], "ok");
    // P1 = (3, 0) at rest, g = 1, t_end = 2: the tip falls g t^2 / 2 = 2.
    let tip = &v["tip_end"];
    let (x, y) = (tip[0].as_f64().unwrap(), tip[1].as_f64().unwrap());
    assert!((x - 3.0).abs() < 1e-9 && (y + 2.0).abs() < 1e-9, "{tip}");
    let vy = v["tip_velocity_end"][1].as_f64().unwrap();
    assert!((vy + 2.0).abs() < 1e-9, "{vy}");
}

#[test]
fn the_jerked_support_keeps_its_energy_balance() {
    let v = simulate_json("jerked-support", &[]);
    assert_eq!(v["status"], "ok");
    let err = v["energy_balance_error"].as_f64().unwrap();
    // M g L = 10 * 1 * 6 = 60; DOPRI5 at rtol 1e-8.
    assert!(err < 1e-5 * 60.0, "{err}");
}

/// Both scenes with elastic links (`chain.axial_stiffness`): both ends let
/// go, the unstretched chain falls as one body (the tip `g t^2 / 2` below
/// `P1`); the jerked support keeps its balance with the support's work
/// counted.
#[test]
fn the_pivot_scenes_run_with_elastic_links() {
    let v = simulate_json("both-ends-let-go", &["--set", "chain.axial_stiffness=1e4"]);
    assert_eq!(v["status"], "ok");
    let tip = &v["tip_end"];
    let (x, y) = (tip[0].as_f64().unwrap(), tip[1].as_f64().unwrap());
    assert!((x - 3.0).abs() < 1e-9 && (y + 2.0).abs() < 1e-9, "{tip}");
    let v = simulate_json("jerked-support", &["--set", "chain.axial_stiffness=1e4"]);
    assert_eq!(v["status"], "ok");
    let err = v["energy_balance_error"].as_f64().unwrap();
    assert!(err < 1e-5 * 60.0, "{err}");
}

#[test]
fn pivot_keys_are_checked_by_name_in_one_line() {
    let path = scene("jerked-support");
    for (set, key) in [
        ("pivot.jerk_time=0", "pivot.jerk_time"),
        ("pivot.release=-1", "pivot.release"),
        ("pivot.frequency=-2", "pivot.frequency"),
    ] {
        let o = run(&["simulate", path.as_str(), "--json", "--set", set]);
        assert_eq!(o.status.code(), Some(2), "{set}");
        let e = stderr(&o);
        assert_eq!(e.trim_end().lines().count(), 1, "{set}: {e}");
        assert!(e.contains(key), "{set}: {e}");
    }
}

/// `view` of a released pivot gives the page the pivot's place per kept
/// sample: it starts at the anchor and falls `g t^2 / 2` with the chain
/// (the page builds each frame's joints from it).
#[test]
fn the_viewer_gets_the_released_pivots_place_per_frame() {
    let dir = scratch("pivot-view");
    let out = dir.join("both.html");
    let o = run(&[
        "view",
        &scene("both-ends-let-go"),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let page = std::fs::read_to_string(&out).unwrap();
    let at = page.find("\"pivot\":[").expect("a pivot array") + "\"pivot\":[".len();
    let end = at + page[at..].find(']').unwrap();
    let p: Vec<f64> = page[at..end]
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert!(p.len() >= 4 && p.len().is_multiple_of(2));
    assert!(p[0].abs() < 1e-12 && p[1].abs() < 1e-12, "{:?}", &p[..2]);
    // The last kept sample is t_end = 2: the pivot has fallen g t^2 / 2 = 2.
    let (x, y) = (p[p.len() - 2], p[p.len() - 1]);
    assert!(x.abs() < 1e-9 && (y + 2.0).abs() < 1e-9, "{x}, {y}");
    // A fixed pivot has none.
    let fixed = dir.join("span.html");
    let o = run(&["view", &scene("span-d3"), "-o", fixed.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(std::fs::read_to_string(&fixed)
        .unwrap()
        .contains("\"pivot\":null"));
    std::fs::remove_dir_all(&dir).unwrap();
}
