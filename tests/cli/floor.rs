//! The floor through the CLI (issue 36): a floor scene's summary carries
//! its floor force, a scene without `[floor]` has none, and bad floor
//! input is one line naming its key.

use crate::common::*;

/// `scenes/span-d3-floor.toml`: the whip reaches the floor (its peak force
/// is an impact's, far above the chain's weight `n m g = 10`), the run's
/// energy balance holds with the floor's energy and work in it, and
/// span-d3 without a floor reports no floor at all.
#[test]
fn a_floor_scene_reports_its_floor_force_and_a_scene_without_one_none() {
    let floor = scene("span-d3-floor");
    let o = run(&["simulate", &floor, "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["status"], "ok");
    let peak = num(&v, "floor_force_max");
    let t = num(&v, "t_floor_force_max");
    assert!(peak > 10.0, "peak floor force {peak}");
    assert!(t > 0.0 && t <= num(&v, "t_end"), "{t}");
    assert!(num(&v, "floor_force_over_landed_weight") > 1.0);
    // Measured 1.1e-6 of M g L (bdf, rtol 1e-6).
    let balance = num(&v, "energy_balance_error") / num(&v, "energy_scale");
    assert!(balance < 1e-5, "{balance}");
    let plain = run(&[
        "simulate",
        &scene("span-d3"),
        "--set",
        "run.t_end=0.1",
        "--json",
    ]);
    assert!(plain.status.success(), "{}", stderr(&plain));
    let v = json(&plain);
    assert!(v.get("floor_force_max").is_none(), "{v}");
}

/// A floor above the start, a key out of its range, and a floor under the
/// report's model: exit 2, one line naming the key.
#[test]
fn bad_floor_input_is_one_line_naming_its_key() {
    let span = scene("span-d3");
    for (set, key) in [
        ("floor.height=1", "floor.height"),
        ("floor.stiffness=0", "floor.stiffness"),
        ("floor.friction=-0.5", "floor.friction"),
        ("floor.angle=2", "floor.angle"),
    ] {
        let o = run(&["simulate", &span, "--set", set]);
        let line = refused(&o, key);
        assert!(!line.is_empty());
    }
    let o = run(&[
        "simulate",
        &span,
        "--set",
        "floor.height=-5",
        "--set",
        "model.report=true",
        "--set",
        "run.method=dopri5",
    ]);
    refused(&o, "floor.height");
}
