//! `simulate --json`'s work counters of the implicit methods (the rejections
//! by cause and the Newton iterations), checked against what they count:
//! every attempt runs at least one Newton iteration, every rejection has one
//! of the two causes, and an explicit method runs none.

use crate::common::{json, num, run, scene};

/// `simulate --json` of the stiff rope to `t_end` with `method`.
fn stiff_rope(method: &str, t_end: &str, dt: &str) -> serde_json::Value {
    let path = scene("stiff-rope");
    let set = format!("run.t_end={t_end}");
    let o = run(&[
        "simulate", &path, "--json", "--method", method, "--dt", dt, "--set", &set,
    ]);
    assert_eq!(o.status.code(), Some(0), "{method}");
    json(&o)
}

#[test]
fn the_implicit_methods_count_their_newton_work_and_the_explicit_ones_none() {
    for method in ["bdf", "bdf-dense"] {
        let v = stiff_rope(method, "0.5", "0.01");
        let (steps, etf, nf, nit) = (
            num(&v, "steps"),
            num(&v, "error_test_failures"),
            num(&v, "newton_failures"),
            num(&v, "newton_iterations"),
        );
        assert!(steps > 0.0, "{method}: {v}");
        assert!(nit >= steps + etf + nf, "{method}: {v}");
        assert_eq!(num(&v, "rejected_steps"), etf + nf, "{method}: {v}");
    }
    for method in ["rk4", "dopri5", "dop853"] {
        let v = stiff_rope(method, "0.002", "1e-5");
        assert!(num(&v, "steps") > 0.0, "{method}: {v}");
        for key in [
            "error_test_failures",
            "newton_failures",
            "newton_iterations",
        ] {
            assert_eq!(num(&v, key), 0.0, "{method} {key}: {v}");
        }
    }
}
