//! `ensemble`: a scene from perturbed starts. Without a perturbation every
//! member is the scene's own run; before the whip the members' spread is
//! linear in the perturbation (a smooth map of the start); after a landing
//! on a penalty floor it is not (the run is sensitive to its start), on
//! a constraint floor it is; bad input is one line naming its flag, with
//! no file written.

use crate::common::*;

/// `ensemble --json`'s statistics of `quantity`: `(mean, sd)`.
fn stat(v: &serde_json::Value, quantity: &str) -> (f64, f64) {
    let s = &v["stats"][quantity];
    (num(s, "mean"), num(s, "sd"))
}

fn ensemble(scene: &str, args: &[&str]) -> serde_json::Value {
    let mut all = vec!["ensemble", scene, "--quiet", "--json"];
    all.extend_from_slice(args);
    let o = run(&all);
    assert!(o.status.success(), "{}", stderr(&o));
    json(&o)
}

/// Span d = 3 to `t = 1`, before the whip, at `rtol = 1e-10`: with spread
/// 0 the members are `simulate`'s run exactly (spread 0, the mean its
/// value); the same draws scaled by 100 scale the members' standard
/// deviation of the tip's end by 100 to 1% (first order in the start;
/// measured 100.001).
#[test]
fn members_spread_linearly_with_the_perturbation_before_the_whip() {
    let span = scene("span-d3");
    let sets = [
        "--set",
        "run.t_end=1",
        "--set",
        "run.rtol=1e-10",
        "--set",
        "run.atol=1e-12",
    ];
    let mut args = sets.to_vec();
    args.extend(["--members", "4", "--spread", "0"]);
    let still = ensemble(&span, &args);
    let mut sim = vec!["simulate", &span, "--json"];
    sim.extend_from_slice(&sets);
    let o = run(&sim);
    assert!(o.status.success(), "{}", stderr(&o));
    let one = json(&o);
    for q in ["tip_speed_max", "tip_end_x", "tip_end_y", "dissipated"] {
        let (mean, sd) = stat(&still, q);
        assert_eq!(sd, 0.0, "{q}");
        let want = match q {
            "tip_end_x" => pair(&one, "tip_end")[0],
            "tip_end_y" => pair(&one, "tip_end")[1],
            _ => num(&one, q),
        };
        assert_eq!(mean, want, "{q}");
    }
    assert_eq!(still["ok"], 4);
    let sd_at = |spread: &str| {
        let mut a = sets.to_vec();
        a.extend(["--members", "8", "--spread", spread]);
        stat(&ensemble(&span, &a), "tip_end_x").1
    };
    let (big, small) = (sd_at("1e-4"), sd_at("1e-6"));
    assert!(big > 0.0 && small > 0.0);
    assert!((big / small / 100.0 - 1.0).abs() < 0.01, "{big} / {small}");
}

/// The U onto a floor to `t = 2.5`, past its first landings: a spread 100
/// times smaller leaves the members' standard deviation of the tip's
/// largest speed within a factor of 10 (measured: 0.23 at 1e-3, 0.11 at
/// 1e-5 with 16 members), where a smooth map would shrink it 100 times.
#[test]
fn members_do_not_spread_linearly_after_the_landing_on_a_floor() {
    let floor = scene("span-d3-floor");
    let sd_at = |spread: &str| {
        let v = ensemble(
            &floor,
            &[
                "--set",
                "run.t_end=2.5",
                "--members",
                "16",
                "--spread",
                spread,
            ],
        );
        assert_eq!(v["ok"], 16);
        stat(&v, "tip_speed_max").1
    };
    let (big, small) = (sd_at("1e-3"), sd_at("1e-5"));
    assert!(big / small < 10.0, "{big} / {small}");
}

/// `--out` holds a row per member whose numbers give the JSON's mean;
/// bad `--members` and `--spread` exit 2 with one line naming the flag and
/// write no file.
#[test]
fn out_has_a_row_per_member_and_bad_input_is_one_line_naming_its_flag() {
    let dir = scratch("ensemble-out");
    let span = scene("span-d3");
    let csv = dir.join("members.csv");
    let v = ensemble(
        &span,
        &[
            "--set",
            "run.t_end=0.5",
            "--members",
            "3",
            "--out",
            csv.to_str().unwrap(),
        ],
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 4, "{text}");
    assert_eq!(rows[0][..3], ["member", "status", "tip_speed_max"]);
    let mean = rows[1..]
        .iter()
        .map(|r| r[2].parse::<f64>().unwrap())
        .sum::<f64>()
        / 3.0;
    assert!((mean / stat(&v, "tip_speed_max").0 - 1.0).abs() < 1e-12);
    assert!(
        rows[1..].iter().all(|r| r[1] == "ok" && r[8].is_empty()),
        "no floor"
    );
    for (flag, value) in [
        ("--members", "1"),
        ("--members", "5000"),
        ("--spread", "-1e-3"),
        ("--spread", "0.2"),
        ("--spread", "nan"),
    ] {
        let bad = dir.join("bad.csv");
        let set = format!("{flag}={value}");
        let o = run(&["ensemble", &span, &set, "--out", bad.to_str().unwrap()]);
        refused(&o, flag);
        assert!(!bad.exists(), "{flag} {value}: a file was written");
    }
}

/// The U onto a constraint floor (`floor.law = "constraint"`, `auto`: the
/// rigid chain by Moreau–Jean) to `t = 2.5`, past its first landings: with
/// spread 0 the members are `simulate`'s run exactly; the same draws
/// scaled by 100 scale the members' standard deviation of the tip's
/// largest speed and of its end by 100 to 2% (the plastic impacts are a
/// smooth map of the start through the landings; measured 100.0 and
/// 100.2 at spreads 1e-6 and 1e-8), where the penalty floor's do not
/// shrink by 10 (the test above). `docs/model.md`, "Which quantities a
/// single floor run reproduces".
#[test]
fn on_a_constraint_floor_members_spread_linearly_through_the_landings() {
    let floor = scene("span-d3-floor");
    let sets = [
        "--set",
        "floor.law=\"constraint\"",
        "--set",
        "run.method=\"auto\"",
        "--set",
        "run.t_end=2.5",
    ];
    let mut args = sets.to_vec();
    args.extend(["--members", "4", "--spread", "0"]);
    let still = ensemble(&floor, &args);
    let mut sim = vec!["simulate", &floor, "--json"];
    sim.extend_from_slice(&sets);
    let o = run(&sim);
    assert!(o.status.success(), "{}", stderr(&o));
    let one = json(&o);
    // Moreau–Jean's contact statistics: auto ran the constraint floor.
    assert!(num(&one, "contacts_max") > 0.0);
    for q in ["tip_speed_max", "tip_end_x", "dissipated"] {
        let (mean, sd) = stat(&still, q);
        assert_eq!(sd, 0.0, "{q}");
        let want = match q {
            "tip_end_x" => pair(&one, "tip_end")[0],
            _ => num(&one, q),
        };
        assert_eq!(mean, want, "{q}");
    }
    let at = |spread: &str| {
        let mut a = sets.to_vec();
        a.extend(["--members", "8", "--spread", spread]);
        let v = ensemble(&floor, &a);
        assert_eq!(v["ok"], 8);
        v
    };
    let (big, small) = (at("1e-6"), at("1e-8"));
    for q in ["tip_speed_max", "tip_end_x"] {
        let (b, s) = (stat(&big, q).1, stat(&small, q).1);
        assert!(b > 0.0 && s > 0.0, "{q}");
        assert!((b / s / 100.0 - 1.0).abs() < 0.02, "{q}: {b} / {s}");
    }
}
