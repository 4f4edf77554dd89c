//! `falling-chain catenary`: the hanging chain between two anchors.

use crate::common::*;

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
fn catenary_with_links_ends_at_p1_with_tangents_in_arithmetic_progression() {
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
    // (Consecutive joints one rod apart holds by construction in angle
    // coordinates: not a check.)
    assert_eq!(v["joints"].as_array().unwrap().len(), 51);
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

#[test]
fn catenary_bad_input_exits_2_with_one_line_naming_the_flag() {
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
}
