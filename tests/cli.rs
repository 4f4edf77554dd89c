//! End-to-end tests of the `falling-chain` binary, run as a user would, and of
//! the scene files in `scenes/`. Expected values come from the physics
//! (closed forms, energy balance, geometry), never from earlier output.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use chain_ode::kinematics::tip;
use chain_ode::Start;
use falling_chain::Scene;
use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_falling-chain");

/// The contract keys of `simulate --json`.
const CONTRACT_KEYS: [&str; 16] = [
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

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

fn scene(name: &str) -> String {
    scenes_dir()
        .join(format!("{name}.toml"))
        .to_string_lossy()
        .into_owned()
}

/// A fresh, empty directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("falling-chain-cli-{test}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .output()
        .expect("the binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8(o.stderr.clone()).unwrap()
}

fn json(o: &Output) -> Value {
    serde_json::from_str(stdout(o).trim())
        .unwrap_or_else(|e| panic!("not one JSON object ({e}): {}", stdout(o)))
}

fn num(v: &Value, key: &str) -> f64 {
    v[key]
        .as_f64()
        .unwrap_or_else(|| panic!("'{key}' is not a number in {v}"))
}

fn pair(v: &Value, key: &str) -> [f64; 2] {
    let a = v[key]
        .as_array()
        .unwrap_or_else(|| panic!("'{key}' in {v}"));
    assert_eq!(a.len(), 2, "{key}");
    [a[0].as_f64().unwrap(), a[1].as_f64().unwrap()]
}

/// The tip from the angles, summed here: `P0 + l sum (cos phi, sin phi)`.
fn tip_by_hand(p0: [f64; 2], length: f64, angles: &[f64]) -> [f64; 2] {
    let l = length / angles.len() as f64;
    angles
        .iter()
        .fold(p0, |r, phi| [r[0] + l * phi.cos(), r[1] + l * phi.sin()])
}

fn names_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn every_scene_loads_and_starts_where_its_report_figure_does() {
    let expected = [
        "catenary-fall",
        "folded",
        "height-h0",
        "height-h2",
        "height-h4",
        "height-hm2",
        "horizontal-damped",
        "horizontal-settling",
        "horizontal-undamped",
        "span-d1",
        "span-d3",
        "span-d5",
        "span-d6",
    ];
    let mut found: Vec<String> = names_in(&scenes_dir())
        .into_iter()
        .filter_map(|f| f.strip_suffix(".toml").map(str::to_string))
        .collect();
    found.sort();
    for name in expected {
        assert!(
            found.iter().any(|f| f == name),
            "scenes/{name}.toml is missing"
        );
    }
    // Every scene file, report or not, loads and prepares.
    for name in &found {
        Scene::load(scene(name))
            .and_then(|s| s.prepare())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
    }

    for name in expected {
        let s = Scene::load(scene(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(s.name(), name);
        assert!(
            s.description().contains("Fig."),
            "{name}: {}",
            s.description()
        );
        let run = s.prepare().unwrap_or_else(|e| panic!("{name}: {e}"));
        let c = &run.chain;
        // The report's parameters.
        assert_eq!((c.length, c.mass, c.gravity), (6.0, 0.2, 1.0), "{name}");
        // t_end is an integer report time times sqrt(l/g), to the 4 digits kept.
        let l = c.length / c.links as f64;
        let t_report = run.options.t_end / (l / c.gravity).sqrt();
        assert!(
            (t_report - t_report.round()).abs() < 2e-3 * t_report,
            "{name}: t_end {} is report t {t_report}",
            run.options.t_end
        );
        // About as many snapshots as the report draws.
        let snapshots = run.options.t_end / run.options.output_dt.unwrap();
        assert!((40.0..=60.0).contains(&snapshots), "{name}: {snapshots}");

        let at = tip(c, run.state.anchor, &run.state.angles);
        let by_hand = tip_by_hand(run.state.anchor, c.length, &run.state.angles);
        assert!((at[0] - by_hand[0]).abs() < 1e-12 && (at[1] - by_hand[1]).abs() < 1e-12);
        assert!(run.state.rates.iter().all(|w| *w == 0.0), "{name}: at rest");
        match s.start() {
            Start::Catenary { p0, p1 } | Start::Stretched { p0, p1 } => {
                assert_eq!(p0, [0.0, 0.0], "{name}");
                assert!(
                    (at[0] - p1[0]).abs() < 1e-10 && (at[1] - p1[1]).abs() < 1e-10,
                    "{name}: tip {at:?} vs P1 {p1:?}"
                );
            }
            Start::Folded { p0, .. } => {
                let want = [p0[0] + l, p0[1] - l];
                assert!(
                    (at[0] - want[0]).abs() < 1e-12 && (at[1] - want[1]).abs() < 1e-12,
                    "{name}: tip {at:?} vs {want:?}"
                );
            }
            other => panic!("{name}: unexpected start {other:?}"),
        }
    }
}

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

#[test]
fn catenary_json_is_the_closed_form_root() {
    let o = run(&[
        "catenary", "--p0", "0,0", "--p1", "5,1", "--length", "6", "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    let a = num(&v, "a");
    assert!((a - 2.447359627).abs() < 1e-8, "{a}");
    // Plugged back in: 2 a sinh(d / 2a) = sqrt(L^2 - h^2), d = 5, h = 1.
    let lhs = 2.0 * a * (5.0 / (2.0 * a)).sinh();
    assert!((lhs - 35f64.sqrt()).abs() < 1e-10, "{lhs}");
    // The curve passes through both anchors; the vertex is (x0, a + c).
    let (x0, c) = (num(&v, "x0"), num(&v, "c"));
    let y = |x: f64| a * ((x - x0) / a).cosh() + c;
    assert!(y(0.0).abs() < 1e-9 && (y(5.0) - 1.0).abs() < 1e-9);
    let vertex = pair(&v, "vertex");
    assert!((vertex[0] - x0).abs() < 1e-12 && (vertex[1] - (a + c)).abs() < 1e-9);
    assert_eq!(
        pair(&v, "lowest_point"),
        vertex,
        "the vertex lies in the span"
    );
    assert!(
        v.get("angles").is_none(),
        "no discrete part without --links"
    );
}

#[test]
fn catenary_with_links_ends_at_p1_and_keeps_rod_lengths() {
    let o = run(&[
        "catenary", "--p0", "0,0", "--p1", "5,1", "--length", "6", "--links", "50", "--json",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let v = json(&o);
    assert!(num(&v, "end_error") < 1e-12 * 6.0);
    let angles: Vec<f64> = v["angles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(angles.len(), 50);
    let end = tip_by_hand([0.0, 0.0], 6.0, &angles);
    assert!((end[0] - 5.0).abs() < 1e-11 && (end[1] - 1.0).abs() < 1e-11);
    let joints = v["joints"].as_array().unwrap();
    assert_eq!(joints.len(), 51);
    for w in joints.windows(2) {
        let (p, q) = (&w[0], &w[1]);
        let dx = q[0].as_f64().unwrap() - p[0].as_f64().unwrap();
        let dy = q[1].as_f64().unwrap() - p[1].as_f64().unwrap();
        assert!((dx.hypot(dy) - 0.12).abs() < 1e-12);
    }
    // Tangents in arithmetic progression (the discrete equilibrium).
    let tans: Vec<f64> = angles.iter().map(|p| p.tan()).collect();
    let beta = tans[1] - tans[0];
    assert!(beta > 0.0);
    for w in tans.windows(2) {
        assert!((w[1] - w[0] - beta).abs() < 1e-9);
    }
}

#[test]
fn catenary_takes_negative_coordinates_after_the_flag() {
    let spaced = run(&[
        "catenary", "--p0", "-1,2", "--p1", "4,-1", "--length", "8", "--links", "4", "--json",
    ]);
    let joined = run(&[
        "catenary",
        "--p0=-1,2",
        "--p1=4,-1",
        "--length=8",
        "--links=4",
        "--json",
    ]);
    for o in [&spaced, &joined] {
        assert_eq!(o.status.code(), Some(0), "{}", stderr(o));
        let v = json(o);
        assert_eq!(pair(&v, "p0"), [-1.0, 2.0]);
        assert_eq!(pair(&v, "p1"), [4.0, -1.0]);
        let first = &v["joints"][0];
        assert_eq!(
            (first[0].as_f64(), first[1].as_f64()),
            (Some(-1.0), Some(2.0))
        );
    }
    assert_eq!(stdout(&spaced), stdout(&joined));

    let table = run(&["catenary", "--p0", "-1,2", "--p1", "4,-1", "--length", "8"]);
    assert_eq!(table.status.code(), Some(0));
    assert!(stdout(&table)
        .lines()
        .any(|l| l.trim_start().starts_with('a')));
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

    let catenary_cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["--p1", "5,1", "--length", "4"], "--length"),
        (vec!["--p1", "5,1", "--length", "-6"], "--length"),
        (
            vec!["--p1", "5,1", "--length", "6", "--links", "0"],
            "--links",
        ),
        (vec!["--p1", "5,x", "--length", "6"], "--p1"),
        (vec!["--p1", "5,1"], "--length"),
    ];
    for (args, field) in catenary_cases {
        let mut all = vec!["catenary"];
        all.extend(&args);
        let o = run(&all);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(field), "{args:?}: '{field}' not in {err}");
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

#[test]
fn plot_and_animate_write_the_format_asked_for_or_nothing() {
    let dir = scratch("plot");
    let png = dir.join("span.png");
    let out = run(&[
        "plot",
        &scene("span-d3"),
        "-o",
        png.to_str().unwrap(),
        "--set",
        "run.t_end=1",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR: width and height, big-endian, at bytes 16..24.
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert_eq!(h, 900);
    assert!(!dir.join("span.svg").exists(), "only the format asked for");

    let gif = dir.join("fall.gif");
    let out = run(&[
        "animate",
        &scene("span-d3"),
        "-o",
        gif.to_str().unwrap(),
        "--seconds",
        "0.5",
        "--fps",
        "10",
        "--set",
        "run.t_end=0.5",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(&fs::read(&gif).unwrap()[..6], b"GIF89a");

    for (args, field) in [
        (vec!["plot", &scene("span-d3"), "-o", "x.jpg"], "--out"),
        (
            vec!["animate", &scene("span-d3"), "-o", "x.gif", "--fps", "0"],
            "--fps",
        ),
        (vec!["animate", &scene("span-d3"), "-o", "x.png"], "--out"),
    ] {
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(field) && err.trim().lines().count() == 1,
            "{err}"
        );
    }
    assert!(!Path::new("x.gif").exists() && !Path::new("x.jpg").exists());
}

/// `converge` on span-d3 cut short before the whip (t_end = 2), at
/// n = 12 .. 96: the refinement keeps M and eta = r l, every reported
/// deviation follows from the reported values, and the answer is the
/// smallest n from which on all of them are below --tol.
#[test]
fn converge_refines_at_fixed_mass_and_viscosity_and_finds_the_smallest_n() {
    let span = scene("span-d3");
    let tol = 2e-3;
    let out = run(&[
        "converge",
        &span,
        "--tol",
        &tol.to_string(),
        "--links",
        "96,12,24,48",
        "--set",
        "run.t_end=2",
        "--json",
        "--jobs",
        "2",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v = json(&out);
    let levels = v["levels"].as_array().expect("levels");
    let links: Vec<u64> = levels
        .iter()
        .map(|l| l["links"].as_u64().unwrap())
        .collect();
    assert_eq!(links, [12, 24, 48, 96]);
    assert_eq!(v["reference_links"].as_u64(), Some(96));
    // The scene: n = 50, m = 0.2, r = 0.0005, L = 6.
    let (mass, eta, length) = (50.0 * 0.2, 0.0005 * 6.0 / 50.0, 6.0);
    let reference = &levels[3];
    let (v_ref, end_ref) = (num(reference, "tip_speed_max"), pair(reference, "tip_end"));
    let mut below = vec![];
    for l in levels {
        let n = l["links"].as_f64().unwrap();
        assert!((num(l, "mass") * n / mass - 1.0).abs() < 1e-12, "{l}");
        assert!(
            (num(l, "damping") * length / n / eta - 1.0).abs() < 1e-12,
            "{l}"
        );
        let d = &l["deviation"];
        let dv = (num(l, "tip_speed_max") / v_ref - 1.0).abs();
        let end = pair(l, "tip_end");
        let de = (end[0] - end_ref[0]).hypot(end[1] - end_ref[1]) / length;
        assert!((num(d, "tip_speed_max") - dv).abs() < 1e-12, "{l}");
        assert!((num(d, "tip_end") - de).abs() < 1e-12, "{l}");
        assert!(
            num(d, "tip_path") >= de - 1e-12,
            "the path includes the end: {l}"
        );
        below.push((n as u64, dv < tol && de < tol));
    }
    below.pop();
    let expected = below
        .iter()
        .rev()
        .take_while(|(_, ok)| *ok)
        .last()
        .map(|(n, _)| *n);
    assert_eq!(v["adequate_links"].as_u64(), expected, "{v}");
    // At fixed M the start's energy converges to the continuous
    // catenary's, O(1/n^2): each doubling shrinks the gap about fourfold.
    let e: Vec<f64> = levels.iter().map(|l| num(l, "energy_start")).collect();
    for k in 0..2 {
        let ratio = (e[k] - e[3]) / (e[k + 1] - e[3]);
        assert!(ratio > 3.0, "energy gaps {e:?}");
    }
    // The level n = 24 is the scene simulated with m = M/24, r = eta 24/L.
    let sim = run(&[
        "simulate",
        &span,
        "--set",
        "chain.links=24",
        "--set",
        &format!("chain.mass={}", mass / 24.0),
        "--set",
        &format!("chain.damping={}", eta * 24.0 / length),
        "--method",
        "dopri5",
        "--t-end",
        "2",
        "--json",
    ]);
    assert!(sim.status.success(), "{}", stderr(&sim));
    let s = json(&sim);
    assert!((num(&s, "tip_speed_max") / num(&levels[1], "tip_speed_max") - 1.0).abs() < 1e-9);

    // The readable table states the refinement and the answer.
    let text = run(&[
        "converge",
        &span,
        "--tol",
        "0.5",
        "--links",
        "8,16",
        "--set",
        "run.t_end=0.5",
    ]);
    assert!(text.status.success(), "{}", stderr(&text));
    let t = stdout(&text);
    assert!(
        t.contains("eta = r l") && t.contains("smallest adequate n = 8"),
        "{t}"
    );
}

#[test]
fn converge_rejects_a_bad_tol_or_links_in_one_line_naming_it() {
    let span = scene("span-d3");
    for (args, field) in [
        (vec!["--tol", "0"], "--tol"),
        (vec!["--tol", "-0.01"], "--tol"),
        (vec!["--tol", "nan"], "--tol"),
        (vec!["--tol", "NaN"], "--tol"),
        (vec!["--tol", "inf"], "--tol"),
        (vec!["--tol", "abc"], "--tol"),
        (vec!["--tol", "0.01", "--links", "50"], "--links"),
        (vec!["--tol", "0.01", "--links", "25,x"], "--links"),
        (vec!["--tol", "0.01", "--jobs", "0"], "--jobs"),
    ] {
        let mut full = vec!["converge", span.as_str()];
        full.extend(args.iter().copied());
        let out = run(&full);
        assert_eq!(out.status.code(), Some(2), "{full:?}");
        let err = stderr(&out);
        assert!(
            err.contains(field) && err.trim().lines().count() == 1,
            "{full:?}: {err}"
        );
        assert!(stdout(&out).is_empty(), "{full:?}");
    }
    // --tol is required.
    let out = run(&["converge", &span]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--tol"));
}
