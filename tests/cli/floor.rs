//! The floor through the CLI (issue 36): a floor scene's summary carries
//! its floor force, a scene without `[floor]` has none, and bad floor
//! input is one line naming its key; on the constraint floor, Cayley's
//! scale read from `simulate --out` and `needs`.

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
/// report's model: exit 2, one line naming the key, on either law (a
/// floor without penalty keys is a constraint; `auto` runs both); a law
/// that is neither, restitution out of [0, 1] or on a penalty floor, a
/// constraint under elastic links, and a method that cannot run the
/// scene's floor (or `moreau-jean` without one) likewise.
#[test]
fn bad_floor_input_is_one_line_naming_its_key() {
    let span = scene("span-d3");
    for law in ["penalty", "constraint"] {
        for (set, key) in [
            ("floor.height=1", "floor.height"),
            ("floor.friction=-0.5", "floor.friction"),
            ("floor.angle=2", "floor.angle"),
        ] {
            let o = run(&[
                "simulate",
                &span,
                "--set",
                &format!("floor.law={law}"),
                "--set",
                "run.method=auto",
                "--set",
                set,
            ]);
            let line = refused(&o, key);
            assert!(!line.is_empty(), "{law}");
        }
    }
    for sets in [
        &["floor.stiffness=0"][..],
        &["floor.law=soft"],
        &["floor.restitution=1.5"],
        &["floor.restitution=-0.1"],
        &["floor.restitution=0.5", "floor.stiffness=1e4"],
        &["floor.law=constraint", "chain.axial_stiffness=1e5"],
        &["floor.height=-5", "run.method=dopri5"],
        &["run.method=moreau-jean"],
    ] {
        let mut args = vec!["simulate".to_string(), span.clone()];
        for s in sets {
            args.extend(["--set".to_string(), s.to_string()]);
        }
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = run(&args);
        let key = match sets[0] {
            "floor.height=-5" | "run.method=moreau-jean" => "run.method",
            "floor.law=constraint" => "floor.law",
            s => s.split('=').next().unwrap(),
        };
        refused(&o, key);
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

/// `simulate --out` of a scene with a floor ends each row with the floor's
/// total force and the weight resting on it: a chain laid on the floor
/// (the horizontal start, both ends let go, a floor damped to rest) has
/// the floor carrying its whole weight `n m g = 25 x 0.2 = 5`, straight up,
/// once it has settled; a scene without a floor keeps its columns.
#[test]
fn out_ends_each_row_with_the_floor_force_and_the_landed_weight() {
    let dir = scratch("floor-out");
    let csv = dir.join("rest.csv");
    let o = run(&[
        "simulate",
        &scene("horizontal-undamped"),
        "--set",
        "pivot.release=0",
        "--set",
        "floor.stiffness=1e4",
        "--set",
        "floor.damping=1e3",
        "--set",
        "run.t_end=2",
        "--set",
        "run.rtol=1e-10",
        "--set",
        "run.atol=1e-12",
        "--set",
        "run.output_dt=0.5",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    let head = &rows[0];
    assert_eq!(head.len(), 7 + 25 + 3, "{head:?}");
    assert_eq!(head[32..], ["floor_x", "floor_y", "landed_weight"]);
    let last: Vec<f64> = rows[rows.len() - 1]
        .iter()
        .map(|c| c.parse().unwrap())
        .collect();
    let (fx, fy, landed) = (last[32], last[33], last[34]);
    // Measured 1e-15 of the weight (dopri5, rtol 1e-10).
    assert!((fy / 5.0 - 1.0).abs() < 1e-6, "floor_y {fy}");
    assert!(fx.abs() < 1e-9, "floor_x {fx}");
    assert!((landed / 5.0 - 1.0).abs() < 1e-12, "landed_weight {landed}");

    let plain = dir.join("plain.csv");
    let o = run(&[
        "simulate",
        &scene("horizontal-undamped"),
        "--set",
        "run.t_end=0.2",
        "--out",
        plain.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let head = std::fs::read_to_string(&plain).unwrap();
    let head = head.lines().next().unwrap();
    assert!(head.ends_with(",phi_25"), "{head}");
}

/// The same on a constraint floor: `simulate --out`'s floor columns are
/// the floor's force averaged over the step that ends at each sample (an
/// impulse over the step's length), exactly the chain's weight once it
/// lies on the floor (it lies there from the start, the floor touching
/// it), with the landed weight beside it; and `--json` carries the
/// contact statistics of `moreau-jean`.
#[test]
fn a_constraint_floors_columns_are_its_impulses_over_the_step() {
    let dir = scratch("floor-out-constraint");
    let csv = dir.join("rest.csv");
    let sets = [
        "pivot.release=0",
        "floor.law=constraint",
        "run.method=moreau-jean",
        "run.dt=0.01",
        "run.t_end=1",
        "run.output_dt=0.25",
    ];
    let mut args = vec!["simulate".to_string(), scene("horizontal-undamped")];
    for s in sets {
        args.extend(["--set".to_string(), s.to_string()]);
    }
    args.extend(["--out".to_string(), csv.to_str().unwrap().to_string()]);
    args.push("--json".to_string());
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["status"], "ok");
    assert_eq!(num(&v, "contacts_max"), 26.0, "{v}");
    assert!(num(&v, "complementarity_residual") < 1e-12, "{v}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 5);
    // Before the first step there was no impulse; from then on the floor
    // carries the weight n m g = 25 x 0.2 = 5, straight up, to rounding.
    assert_eq!(rows[0][32..], [0.0, 0.0, 0.0]);
    for r in &rows[1..] {
        let (fx, fy, landed) = (r[32], r[33], r[34]);
        assert!((fy / 5.0 - 1.0).abs() < 1e-13, "floor_y {fy}");
        assert!(fx.abs() < 1e-13, "floor_x {fx}");
        assert!((landed / 5.0 - 1.0).abs() < 1e-13, "landed_weight {landed}");
    }
}

/// `view --from` refuses a floor run's CSV with one line naming `--from`
/// and saying why (a floor runs the elastic model, whose stretched rods a
/// CSV does not hold) and what to do instead, rather than a misfit of its
/// tip against equal rods.
#[test]
fn view_refuses_a_floor_runs_csv_and_says_to_view_its_scene() {
    let dir = scratch("floor-view-from");
    let csv = dir.join("floor.csv");
    let o = run(&[
        "simulate",
        &scene("span-d3-floor"),
        "--set",
        "run.t_end=0.2",
        "--set",
        "run.output_dt=0.02",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let (page, o) = crate::view::view(&dir, "from.html", &["--from", csv.to_str().unwrap()]);
    let line = refused(&o, "--from");
    assert!(
        line.contains("floor_x") && line.contains("view SCENE.toml"),
        "{line}"
    );
    assert!(!page.exists(), "no page is written for a refused run");
}

/// `needs` on a constraint floor (the U onto a floor, `floor.law =
/// "constraint"`): its one method is moreau-jean at the scene's step (no
/// method study: the smooth methods' reference refuses the floor), its
/// ladder in n and its terms run on the floor, and the floor's friction
/// is judged like any term (off, the tip's path moves by 0.126 of L at
/// n = 50, more than --tol 0.1: needed).
#[test]
fn needs_on_a_constraint_floor_names_its_one_method_and_judges_its_friction() {
    let o = run(&[
        "needs",
        &scene("span-d3-floor"),
        "--set",
        "floor.law=\"constraint\"",
        "--set",
        "run.method=\"auto\"",
        "--tol",
        "0.1",
        "--links",
        "25,50,100",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v = json(&o);
    assert_eq!(v["links"], 50);
    let one = v["one_method"].as_str().unwrap();
    assert!(one.starts_with("moreau-jean at run.dt = "), "{one}");
    let term = |name: &str| {
        v["terms"]
            .as_array()
            .unwrap()
            .iter()
            .find(|t| t["term"] == name)
            .unwrap()
            .clone()
    };
    assert_eq!(term("floor friction")["needed"], true);
    assert!(term("penalty floor")["needed"].is_null());
    assert!(v["fastest"].is_null());
}

/// Cayley's scale at n = 160 as a user runs it from the CLI: the scene at
/// 160 rods (its total mass kept, its ±0.02 rad zigzag given as
/// `start.angles`) on the constraint floor, `auto`, sampled at every step,
/// so that each row's `floor_y` is the step's impulse over the step and
/// a window's force is their mean. Over the 19 windows of 0.05 in
/// `t = 0.3 .. 1.2` the force over the ideal `3 mu g x` (`x = g t²/2`,
/// averaged over the window) reads 1 within 1% (measured 1.0023), with a
/// scatter below three times the ideal sequence's 0.045 (equal rods each
/// stopped at its free-fall landing time; measured 0.091); a floor column
/// off by a step (an impulse not divided by its own step, a column from
/// another sample) or a contact law that is not plastic moves the mean.
#[test]
fn cayleys_scale_at_n_160_reads_three_mu_g_x_from_simulates_floor_column() {
    let n = 160;
    let dt = 2.5e-3;
    let dir = scratch("floor-cayley-160");
    let csv = dir.join("cayley.csv");
    let angles: Vec<String> = (0..n)
        .map(|i| {
            if i % 2 == 0 {
                "-1.550796326795"
            } else {
                "-1.590796326795"
            }
            .to_string()
        })
        .collect();
    let sets = [
        "floor.law=\"constraint\"".to_string(),
        "run.method=\"auto\"".to_string(),
        format!("chain.links={n}"),
        format!("chain.mass={}", 1.0 / n as f64),
        format!("start.angles=[{}]", angles.join(",")),
        format!("run.dt={dt}"),
        format!("run.output_dt={dt}"),
        "run.t_end=1.25".to_string(),
    ];
    let mut args = vec!["simulate".to_string(), scene("cayley-scale")];
    for s in &sets {
        args.extend(["--set".to_string(), s.clone()]);
    }
    args.extend(["--out".to_string(), csv.to_str().unwrap().to_string()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (ct, cy) = (col("t"), col("floor_y"));
    let rows: Vec<(f64, f64)> = lines
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            (c[ct].parse().unwrap(), c[cy].parse().unwrap())
        })
        .collect();
    let d = 0.025;
    let readings: Vec<f64> = (0..19)
        .map(|j| {
            let c = 0.3 + 0.05 * j as f64;
            let impulse: f64 = (rows.iter())
                .filter(|(t, _)| *t > c - d + 1e-9 && *t <= c + d + 1e-9)
                .map(|(_, f)| f * dt)
                .sum();
            impulse / (2.0 * d) / (1.5 * (c * c + d * d / 3.0))
        })
        .collect();
    let mean = readings.iter().sum::<f64>() / 19.0;
    let scatter = (readings.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / 18.0).sqrt();
    assert!((mean - 1.0).abs() < 0.01, "reading {mean}");
    assert!(scatter < 3.0 * 0.045, "scatter {scatter}");
}
