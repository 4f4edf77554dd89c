//! `model.report = true`: the report's own model through the CLI, and the
//! one-line refusals of what it does not support.

use crate::common::*;

#[test]
fn the_reports_model_runs_in_its_own_clock() {
    // Span d = 3 to report time 2: its clock is sqrt(l/g) = 0.346 of ours,
    // so the corrected model over the same 2 time units falls further and
    // faster; the report's run balances its own energy.
    let args = |report: &'static str| {
        run(&[
            "simulate",
            &scene("span-d3"),
            "--json",
            "--t-end",
            "2",
            "--set",
            report,
        ])
    };
    let rep = args("model.report=true");
    let cor = args("model.report=false");
    assert_eq!(rep.status.code(), Some(0), "{}", stderr(&rep));
    assert_eq!(cor.status.code(), Some(0), "{}", stderr(&cor));
    let (rep, cor) = (json(&rep), json(&cor));
    assert_eq!(rep["status"], "ok");
    assert!(num(&rep, "energy_balance_error") < 1e-2, "{rep}");
    let (v_rep, v_cor) = (num(&rep, "tip_speed_max"), num(&cor, "tip_speed_max"));
    assert!(v_rep < 0.5 * v_cor, "{v_rep} {v_cor}");
}

#[test]
fn what_the_report_has_not_is_refused_in_one_line() {
    let dir = scratch("report-refusals");
    let out = dir.join("run.csv");
    let out = out.to_str().unwrap();
    for (set, field) in [
        ("run.method=\"bdf\"", "run.method"),
        ("run.method=\"auto\"", "run.method"),
        ("chain.axial_stiffness=1e4", "chain.axial_stiffness"),
        ("chain.bending_stiffness=0.1", "chain.bending_stiffness"),
        ("chain.tip_mass=0.1", "chain.tip_mass"),
        ("chain.links=201", "chain.links"),
        ("pivot.release=0.5", "pivot.release"),
        ("pivot.acceleration=[0, 0.2]", "pivot.acceleration"),
    ] {
        let o = run(&[
            "simulate",
            &scene("span-d3"),
            "--set",
            "model.report=true",
            "--set",
            set,
            "--out",
            out,
        ]);
        assert_eq!(o.status.code(), Some(2), "{set}");
        let e = stderr(&o);
        assert_eq!(e.trim_end().lines().count(), 1, "{set}: {e}");
        assert!(e.contains(field), "{set}: {e}");
        assert!(!std::path::Path::new(out).exists(), "{set}: wrote {out}");
    }
    for study in ["precision", "stability"] {
        let o = run(&[study, &scene("span-d3"), "--set", "model.report=true"]);
        assert_eq!(o.status.code(), Some(2), "{study}");
        assert!(stderr(&o).contains("model.report"), "{study}");
    }
}
