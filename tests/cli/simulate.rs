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
    assert_eq!(v["method"], "rk4");
    assert_eq!(v["links"], 50);
    assert_eq!(num(&v, "t_reached"), 0.5);
    assert!(v["steps"].as_u64().unwrap() >= 50, "dt = 0.01 over 0.5");
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
    // Starting at rest from P1 = (3, 0), the chain's tip stays on a chain of
    // length 6 hung from the origin and has started to fall.
    let tip = pair(&v, "tip_end");
    assert!(tip[0].hypot(tip[1]) <= 6.0 && tip[1] < 0.0, "{tip:?}");
    let vmax = num(&v, "tip_speed_max");
    let t_vmax = num(&v, "t_tip_speed_max");
    assert!(vmax > 0.0 && (0.0..=0.5).contains(&t_vmax));
    let v_end = pair(&v, "tip_velocity_end");
    assert!(v_end[0].hypot(v_end[1]) <= vmax * (1.0 + 1e-12));
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
        (vec![&span, "--dt", "0"], "run.dt"),
        (vec![&span, "--t-end", "-1"], "run.t_end"),
    ];
    let out = dir.join("out.csv");
    for (args, field) in cases {
        let mut all = vec!["simulate"];
        all.extend(&args);
        all.extend(["--json", "--out", out.to_str().unwrap()]);
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
    let dir = scratch("diverged");
    let out = dir.join("diverged.csv");
    // gamma = r / (m l^2) = 0.1 / (0.2 * 0.12^2) = 34.7: a spectral radius
    // near 48 gamma is far beyond RK4's stability limit 2.8 / dt at dt = 0.01.
    let o = run(&[
        "simulate",
        &scene("span-d3"),
        "--set",
        "chain.damping=0.1",
        "--dt",
        "0.01",
        "--t-end",
        "20",
        "--json",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["status"], "diverged");
    let t_reached = num(&v, "t_reached");
    assert!(t_reached < 20.0, "{t_reached}");
    assert!(num(&v, "t_failed") > t_reached);
    for key in CONTRACT_KEYS {
        assert!(v.get(key).is_some(), "missing '{key}' in {v}");
    }

    let text = fs::read_to_string(&out).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse::<f64>().unwrap()).collect())
        .collect();
    assert!(!rows.is_empty());
    assert!(
        rows.iter().flatten().all(|x| x.is_finite()),
        "only finite states"
    );
    let last_t = rows.last().unwrap()[0];
    assert!(
        (last_t - t_reached).abs() < 1e-12,
        "{last_t} vs {t_reached}"
    );
    assert_eq!(names_in(&dir), ["diverged.csv"]);
    fs::remove_dir_all(&dir).unwrap();
}
