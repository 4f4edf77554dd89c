//! `falling-chain simulate`: one run of a scene, its summary and its samples.

use std::fs;
use std::path::Path;

use crate::common::*;

#[test]
fn simulate_json_keeps_the_contract_and_balances_energy() {
    let o = run(&["simulate", &scene("span-d3"), "--json", "--t-end", "0.5"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    for key in CONTRACT_KEYS {
        assert!(v.get(key).is_some(), "missing '{key}' in {v}");
    }
    assert_eq!(v["status"], "ok");
    assert_eq!(v["method"], "dopri5");
    assert_eq!(v["model"], "rigid");
    assert_eq!(v["links"], 50);
    assert_eq!(num(&v, "t_reached"), 0.5);
    assert!(v["steps"].as_u64().unwrap() >= 1);
    // Energy: E(0) + 0 = E(t) + W up to the reported balance error, which is
    // small against M g L = n m g L.
    let scale = 50.0 * 0.2 * 1.0 * 6.0;
    let balance = num(&v, "energy_balance_error");
    assert!(balance.abs() < 1e-6 * scale, "{balance}");
    let (e0, e1, w) = (
        num(&v, "energy_start"),
        num(&v, "energy_end"),
        num(&v, "dissipated"),
    );
    assert!((e1 + w - e0).abs() <= balance + 1e-12 * scale);
    assert!(w >= 0.0 && e1 <= e0 + balance, "friction only takes energy");
    // The tip's end and its speed against an independent run: DOPRI5 at
    // rtol 1e-11. RK4's error at dt = 0.01 is O(dt^4): measured 1.1e-11 in
    // the tip and 7e-12 in vmax (3e-13 and 3e-13 at dt = 0.005, the
    // fourth-order ratio), so 1e-9 fails for any error above RK4's own.
    let reference = run(&[
        "simulate",
        &scene("span-d3"),
        "--json",
        "--t-end",
        "0.5",
        "--method",
        "dopri5",
        "--rtol",
        "1e-11",
        "--atol",
        "1e-13",
    ]);
    assert_eq!(reference.status.code(), Some(0), "{}", stderr(&reference));
    let r = json(&reference);
    let (tip, tip_ref) = (pair(&v, "tip_end"), pair(&r, "tip_end"));
    assert!(
        (tip[0] - tip_ref[0]).hypot(tip[1] - tip_ref[1]) < 1e-9,
        "{tip:?} vs {tip_ref:?}"
    );
    let vmax = num(&v, "tip_speed_max");
    assert!((vmax - num(&r, "tip_speed_max")).abs() < 1e-9, "{vmax}");
    // Released at rest, long before the whip (t ~ 3), the free end speeds
    // up the whole time: its fastest is at the end, at the end's speed.
    assert_eq!(num(&v, "t_tip_speed_max"), 0.5);
    let v_end = pair(&v, "tip_velocity_end");
    assert!((v_end[0].hypot(v_end[1]) - vmax).abs() < 1e-12 * vmax);
    // And it has fallen below where it was let go (3, 0).
    assert!(tip[1] < -0.1, "{tip:?}");
}

#[test]
fn set_overrides_scene_keys_and_flags_come_last() {
    let o = run(&[
        "simulate",
        &scene("span-d3"),
        "--json",
        "--t-end",
        "0.1",
        "--set",
        "chain.links=10",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(json(&o)["links"], 10);

    // A bad method in --set is replaced by the --method flag.
    let o = run(&[
        "simulate",
        &scene("span-d3"),
        "--json",
        "--t-end",
        "0.1",
        "--set",
        "run.method=nonesuch",
        "--method",
        "rk4",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));

    // An array element by index: P1 = (2.5, 0) is still a valid catenary.
    let o = run(&[
        "simulate",
        &scene("span-d3"),
        "--json",
        "--t-end",
        "0.1",
        "--set",
        "start.p1.0=2.5",
        "--set",
        "run.t_end=3",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(
        num(&v, "t_reached"),
        0.1,
        "--t-end wins over --set run.t_end"
    );
    // Released at rest from (2.5, 0): after 0.1 the tip is still near there.
    let tip = pair(&v, "tip_end");
    assert!((tip[0] - 2.5).hypot(tip[1]) < 0.05, "{tip:?}");
}

#[test]
fn out_writes_a_csv_whose_tip_columns_follow_from_its_angles() {
    let dir = scratch("csv");
    let out = dir.join("run.csv");
    let o = run(&[
        "simulate",
        &scene("span-d3"),
        "--t-end",
        "0.4",
        "--set",
        "chain.links=12",
        "--set",
        "run.output_dt=0.05",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("ok"),
        "readable summary: {}",
        stdout(&o)
    );
    assert_eq!(names_in(&dir), ["run.csv"], "no temporary file left");

    let text = fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut want = vec![
        "t",
        "tip_x",
        "tip_y",
        "tip_vx",
        "tip_vy",
        "energy",
        "dissipated",
    ];
    let phis: Vec<String> = (1..=12).map(|i| format!("phi_{i}")).collect();
    want.extend(phis.iter().map(String::as_str));
    assert_eq!(header, want);

    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    // Samples at 0, 0.05, .., 0.4.
    assert_eq!(rows.len(), 9);
    let e0 = rows[0][5];
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(r.len(), 7 + 12);
        assert!((r[0] - 0.05 * k as f64).abs() < 1e-12, "t = {}", r[0]);
        let t = tip_by_hand([0.0, 0.0], 6.0, &r[7..]);
        assert!(
            (t[0] - r[1]).abs() < 1e-12 && (t[1] - r[2]).abs() < 1e-12,
            "row {k}: tip {t:?} vs ({}, {})",
            r[1],
            r[2]
        );
        // Energy balance on every sample.
        assert!((r[5] + r[6] - e0).abs() < 1e-6, "row {k}");
    }
    // The tip starts at rest at P1 = (3, 0).
    assert!((rows[0][1] - 3.0).abs() < 1e-10 && rows[0][2].abs() < 1e-10);
    assert!(rows[0][3] == 0.0 && rows[0][4] == 0.0);
    fs::remove_dir_all(&dir).unwrap();
}

/// An elastic chain's run writes tip and energy columns of its own model
/// (the energy balance holds on every row, which the rigid formulas of its
/// angles would break) and, with `--forces`, one row of joint forces per
/// sample: `t`, then tension and shear of the pivot, .., of the free tip
/// (zero). At the start the pivot carries the weight and the holder's pull
/// of the span's catenary.
#[test]
fn forces_writes_the_joint_forces_of_an_elastic_run_beside_its_samples() {
    let dir = scratch("forces");
    let (out, forces) = (dir.join("run.csv"), dir.join("forces.csv"));
    let o = run(&[
        "simulate",
        &scene("span-d3"),
        "--t-end",
        "0.4",
        // The scene's RK4 at dt = 0.01 is past the axial modes' stability
        // limit (it ends `inaccurate`): an adaptive method.
        "--method",
        "dopri5",
        "--set",
        "chain.links=12",
        "--set",
        "chain.axial_stiffness=2e3",
        "--set",
        "chain.axial_damping=0.01",
        "--set",
        "chain.bending_stiffness=0.01",
        "--set",
        "run.output_dt=0.05",
        "--json",
        "--out",
        out.to_str().unwrap(),
        "--forces",
        forces.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(names_in(&dir), ["forces.csv", "run.csv"]);
    let rows = |path: &Path| -> (Vec<String>, Vec<Vec<f64>>) {
        let text = fs::read_to_string(path).unwrap();
        let mut lines = text.lines();
        let header = lines.next().unwrap().split(',').map(String::from).collect();
        let rows = lines
            .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
            .collect();
        (header, rows)
    };
    let (_, samples) = rows(&out);
    let (header, f) = rows(&forces);
    assert_eq!(header.len(), 1 + 2 * 13);
    assert_eq!(
        (&header[..3], &header[25..]),
        (
            &["t".to_string(), "tension_0".into(), "shear_0".into()][..],
            &["tension_12".to_string(), "shear_12".into()][..]
        )
    );
    assert_eq!(f.len(), samples.len());
    assert_eq!(f.len(), 9);
    let e0 = samples[0][5];
    for (r, s) in f.iter().zip(&samples) {
        assert_eq!(r[0], s[0]);
        assert_eq!((r[25], r[26]), (0.0, 0.0), "the free tip carries nothing");
        assert!((s[5] + s[6] - e0).abs() < 1e-6 * e0.abs(), "t = {}", s[0]);
    }
    // At t = 0 the chain is still the symmetric span held at both ends:
    // each end carries half the weight M g = 12 * 0.2 = 2.4 and the
    // horizontal pull, so the pivot's tension lies between half the weight
    // and the weight (d = 3 of L = 6 is a shallow pull), with little shear.
    assert!(f[0][1] > 1.2 && f[0][1] < 2.4, "{:?}", &f[0][..3]);
    assert!(f[0][2].abs() < 0.05 * f[0][1], "{:?}", &f[0][..3]);
    fs::remove_dir_all(&dir).unwrap();
}

/// A scene file with an unknown key, written for the test.
fn scene_with_unknown_key(dir: &Path) -> String {
    let text = fs::read_to_string(scene("span-d3"))
        .unwrap()
        .replace("damping = ", "colour = \"red\"\ndamping = ");
    let path = dir.join("unknown-key.toml");
    fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn bad_input_exits_2_with_one_line_naming_the_field_and_writes_nothing() {
    let dir = scratch("bad");
    let inputs = dir.join("inputs");
    fs::create_dir_all(&inputs).unwrap();
    let unknown = scene_with_unknown_key(&inputs);
    let span = scene("span-d3");
    let horizontal = scene("horizontal-undamped");
    let missing = inputs.join("no-such-scene.toml");
    let missing = missing.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec![&span, "--set", "chain.length=2"], "chain.length"),
        (vec![&span, "--set", "chain.links=0"], "chain.links"),
        (vec![&span, "--set", "chain.mass=-0.2"], "chain.mass"),
        (vec![&span, "--set", "chain.mass=nan"], "chain.mass"),
        (vec![&span, "--set", "chain.damping=-1e-3"], "chain.damping"),
        (vec![&span, "--set", "chain.damping=nan"], "chain.damping"),
        (vec![&span, "--set", "chain.length=-6"], "chain.length"),
        (vec![&span, "--set", "chain.length=nan"], "chain.length"),
        (vec![&unknown], "chain.colour"),
        (vec![missing], "no-such-scene.toml"),
        (vec![&horizontal, "--set", "start.p1=[5.0,0.0]"], "start.p1"),
        (vec![&span, "--set", "start.kind=stretched"], "start.p1"),
        (vec![&span, "--set", "start.down=3"], "start.down"),
        (vec![&span, "--set", "chain.lenght=6"], "chain.lenght"),
        (vec![&span, "--set", "start.p1.2=1"], "start.p1.2"),
        (vec![&span, "--set", "colour=1"], "colour"),
        (vec![&span, "--method", "nonesuch"], "run.method"),
        (vec![&span, "--set", "run.method=nonesuch"], "run.method"),
        (vec![&span, "--dt", "0"], "--dt"),
        (vec![&span, "--t-end", "-1"], "--t-end"),
        (
            vec![&span, "--set", "chain.axial_stiffness=-1e4"],
            "chain.axial_stiffness",
        ),
        (
            vec![&span, "--set", "chain.axial_stiffness=0"],
            "chain.axial_stiffness",
        ),
        (
            vec![&span, "--set", "chain.axial_stiffness=inf"],
            "chain.axial_stiffness",
        ),
        (
            vec![&span, "--set", "chain.axial_stiffness=nan"],
            "chain.axial_stiffness",
        ),
        (
            vec![&span, "--set", "chain.axial_damping=-1"],
            "chain.axial_damping",
        ),
        (
            vec![&span, "--set", "chain.axial_damping=nan"],
            "chain.axial_damping",
        ),
        (
            vec![&span, "--set", "chain.bending_stiffness=-0.01"],
            "chain.bending_stiffness",
        ),
        (
            vec![&span, "--set", "chain.bending_stiffness=inf"],
            "chain.bending_stiffness",
        ),
        (
            vec![&span, "--set", "chain.bending_stiffness=nan"],
            "chain.bending_stiffness",
        ),
    ];
    let out = dir.join("out.csv");
    let forces = dir.join("forces.csv");
    for (args, field) in cases {
        let mut all = vec!["simulate"];
        all.extend(&args);
        all.extend(["--json", "--out", out.to_str().unwrap()]);
        all.extend(["--forces", forces.to_str().unwrap()]);
        let o = run(&all);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(field), "{args:?}: '{field}' not in {err}");
        assert!(stdout(&o).is_empty(), "{args:?}");
        assert!(!out.exists(), "{args:?} created the output");
        assert_eq!(names_in(&dir), ["inputs"], "{args:?} left a file");
    }

    // An output in a directory that does not exist is refused before the run.
    let nowhere = dir.join("no-such-dir").join("out.csv");
    let o = run(&[
        "simulate",
        &span,
        "--json",
        "--out",
        nowhere.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).starts_with("error: --out: "), "{}", stderr(&o));
    assert!(stdout(&o).is_empty(), "refused before running");
    assert_eq!(names_in(&dir), ["inputs"]);

    // An existing output is left as it was by a rejected run.
    fs::write(&out, "before\n").unwrap();
    let o = run(&[
        "simulate",
        &span,
        "--set",
        "chain.links=0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(fs::read_to_string(&out).unwrap(), "before\n");
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn missing_scene_error_names_the_path() {
    let o = run(&["simulate", "no-such-scene.toml"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr(&o).trim_end(),
        "error: scene: cannot read 'no-such-scene.toml': No such file or directory"
    );
}

#[test]
fn a_diverging_run_exits_1_and_still_writes_what_it_computed() {
    // gamma = r / (m l^2) = 0.1 / (0.2 * 0.12^2) = 34.7: a spectral radius
    // near 48 gamma is far beyond RK4's stability limit 2.8 / dt at dt = 0.01.
    let span = scene("span-d3");
    let args = [
        &span,
        "--set",
        "chain.damping=0.1",
        "--method",
        "rk4",
        "--dt",
        "0.01",
        "--t-end",
        "20",
    ];
    let (v, _) = failing_run("diverged", &args);
    assert_eq!(v["status"], "diverged");
    let t_reached = num(&v, "t_reached");
    assert!(t_reached < 20.0, "{t_reached}");
    assert!(num(&v, "t_failed") > t_reached);
    for key in CONTRACT_KEYS {
        assert!(v.get(key).is_some(), "missing '{key}' in {v}");
    }
}

/// Runs `simulate --json --out` on a run that must fail: checks exit 1, that
/// the CSV is the only file written, that it holds finite states only and
/// ends at `t_reached`; returns the summary and the CSV's rows.
fn failing_run(name: &str, args: &[&str]) -> (serde_json::Value, Vec<Vec<f64>>) {
    let dir = scratch(name);
    let file = format!("{name}.csv");
    let out = dir.join(&file);
    let mut all = vec!["simulate"];
    all.extend_from_slice(args);
    all.extend(["--json", "--out", out.to_str().unwrap()]);
    let o = run(&all);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    let rows: Vec<Vec<f64>> = fs::read_to_string(&out)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    assert!(!rows.is_empty());
    assert!(
        rows.iter().flatten().all(|x| x.is_finite()),
        "only finite states"
    );
    let (last_t, t_reached) = (rows.last().unwrap()[0], num(&v, "t_reached"));
    assert!(
        (last_t - t_reached).abs() < 1e-12,
        "{last_t} vs {t_reached}"
    );
    assert_eq!(names_in(&dir), [file]);
    fs::remove_dir_all(&dir).unwrap();
    (v, rows)
}

#[test]
fn a_step_budget_exits_1_and_still_writes_what_it_computed() {
    // DOPRI5 with a budget of 30 steps stops short of t_end. (An adaptive
    // method: RK4's step count is known before the run, so a budget it
    // cannot meet is refused up front, issue 24.)
    let span = scene("span-d3");
    let args = [
        &span,
        "--method",
        "dopri5",
        "--set",
        "run.max_steps=30",
        "--set",
        "run.output_dt=0.05",
    ];
    let (v, rows) = failing_run("max-steps", &args);
    assert_eq!(v["status"], "max_steps");
    assert_eq!(v["steps"], 30);
    let t_reached = num(&v, "t_reached");
    assert!(t_reached > 0.0 && t_reached < 4.157, "{t_reached}");
    // Samples on the output grid, then the end reached.
    let times: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    let (last, grid) = times.split_last().unwrap();
    for (k, t) in grid.iter().enumerate() {
        assert!((t - 0.05 * k as f64).abs() < 1e-12, "{times:?}");
    }
    assert_eq!(*last, t_reached);
    assert!(grid.len() as f64 >= (t_reached / 0.05).floor(), "{times:?}");
    // The last row is the summary's end.
    let tip = pair(&v, "tip_end");
    let end = rows.last().unwrap();
    assert!((end[1] - tip[0]).abs() < 1e-12 && (end[2] - tip[1]).abs() < 1e-12);
}

#[test]
fn a_step_floor_the_folded_whip_needs_exits_1_and_still_writes_what_it_computed() {
    // The folded chain's free end speeds up without bound as it nears the
    // bottom (v^2 = g x (2L - x)/(L - x)); DOPRI5 at rtol 1e-4 takes steps
    // above 3e-3 until the whip, then needs shorter ones.
    let folded = scene("folded");
    let args = [
        &folded,
        "--method",
        "dopri5",
        "--rtol",
        "1e-4",
        "--atol",
        "1e-6",
        "--set",
        "run.h_min=3e-3",
    ];
    let (v, _) = failing_run("h-min", &args);
    assert_eq!(v["status"], "step_size_too_small");
    let (t_reached, t_failed) = (num(&v, "t_reached"), num(&v, "t_failed"));
    assert!(t_failed > t_reached && t_failed - t_reached < 3e-3);
    // In the whip: after the law's time for 85% of the fall (measured: it
    // stops at 2.919), before its total fall time plus the 1% the discrete
    // chain lags it.
    let law = |xi: f64| chain_ode::analysis::folded_law::time(xi * 6.0, 6.0, 1.0);
    assert!(
        t_reached > law(0.85) && t_reached < 1.01 * law(1.0),
        "{t_reached} vs {} .. {}",
        law(0.85),
        law(1.0)
    );
}

#[test]
fn a_summary_that_is_not_finite_exits_1_and_json_says_diverged() {
    // Every rod spinning at 1e152 rad per time unit: one RK4 step of 1e-152
    // keeps the state finite, but the kinetic energy overflows f64. The
    // run must not pass as ok.
    let dir = scratch("nonfinite");
    let n = 50;
    let list = |x: &str| vec![x; n].join(", ");
    let text = format!(
        "name = \"spin\"\n[chain]\nlinks = {n}\n[start]\nkind = \"angles\"\nangles = [{}]\nrates = [{}]\n[run]\nmethod = \"rk4\"\nt_end = 1e-152\ndt = 1e-152\n",
        list("-0.5"),
        list("1e152")
    );
    let path = dir.join("spin.toml");
    fs::write(&path, text).unwrap();
    let o = run(&["simulate", path.to_str().unwrap(), "--json"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["status"], "diverged");
    assert!((num(&v, "t_reached") / 1e-152 - 1.0).abs() < 1e-12, "{v}");
    assert_eq!(num(&v, "t_failed"), 0.0);
    // JSON has no infinity or NaN: the fields that are not finite are null.
    assert!(v["energy_start"].is_null(), "{v}");
    assert!(v["energy_balance_error"].is_null(), "{v}");
    fs::remove_dir_all(&dir).unwrap();
}

/// The summary says which model ran: the one the scene's keys choose.
#[test]
fn simulate_json_names_the_model_that_ran() {
    for (set, model) in [
        (None, "rigid"),
        (Some("chain.axial_stiffness=1e5"), "elastic"),
        (Some("model.report=true"), "report"),
    ] {
        let mut args = vec!["simulate", "--json", "--t-end", "0.2"];
        let path = scene("span-d3");
        args.push(&path);
        if let Some(s) = set {
            args.extend(["--set", s]);
        }
        let o = run(&args);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        assert_eq!(json(&o)["model"], model, "{set:?}");
    }
}
