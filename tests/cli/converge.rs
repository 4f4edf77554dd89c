//! `falling-chain converge`: refinement in the number of rods.

use crate::common::*;

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

#[test]
fn converge_with_a_failed_run_exits_1_with_no_answer_and_every_level_reported() {
    // The refinement keeps eta = r l and M, so gamma = r/(m l^2) grows like
    // n^4: 0.17 at n = 50, 44.4 at n = 200, where the spectral radius near
    // 48 gamma = 2133 is far past RK4's 2.785 / dt = 278 at dt = 0.01.
    let out = run(&[
        "converge",
        &scene("span-d3"),
        "--tol",
        "0.01",
        "--method",
        "rk4",
        "--links",
        "25,50,200",
        "--set",
        "run.t_end=0.5",
        "--json",
        "--jobs",
        "2",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let v = json(&out);
    let status: Vec<&str> = v["levels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["status"].as_str().unwrap())
        .collect();
    assert_eq!(status, ["ok", "ok", "diverged"]);
    assert!(v["adequate_links"].is_null(), "no answer: {v}");
}
