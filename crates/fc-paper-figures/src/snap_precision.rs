//! `snap-precision` and `snap-damping`: the work-precision of the folded
//! elastic snap across the axial stiffness (5% damping) and across the
//! damping (at `EA = 1e7`), for the explicit pairs, BDF, gen-alpha and
//! `auto` (`docs/model.md`, "auto and gen-alpha"). The folded start of
//! `scenes/folded.toml` on 20 rods (`m = 0.2`), a damping ratio `zeta` of a
//! joint's axial mode (`eta = 2 zeta sqrt(EA m l)`), to `t = 3.2`, past the
//! snap at 2.88. Error: the larger of the tip's distance at the end over
//! `L` and the relative error of the largest tip speed, against DOP853 at
//! `rtol = 1e-10`. Wall times: one run each, in sequence (the rows are
//! `*-timing.csv`: run only with `--timings`).

use std::fmt::Write as _;
use std::time::Instant;

use chain_ode::{Method, Status};
use fc_csv::format::num;
use fc_scene::Prepared;

/// `axial_stiffness,zeta,method,rtol,status,steps,error,wall_seconds`.
pub const HEADER: &str = "axial_stiffness,zeta,method,rtol,status,steps,error,wall_seconds\n";
/// `error_level,method,axial_stiffness,zeta,wall_seconds`: each method's
/// least wall time to an error at or below the level, in each case.
pub const BEST_HEADER: &str = "error_level,method,axial_stiffness,zeta,wall_seconds\n";

/// `snap-precision`'s cases `(EA, zeta)`: the axial stiffnesses (force
/// units) at 5% damping.
pub const EAS: [(f64, f64); 5] = [
    (1e4, 0.05),
    (1e5, 0.05),
    (1e6, 0.05),
    (1e7, 0.05),
    (1e8, 0.05),
];
/// `snap-damping`'s cases: the damping ratios at `EA = 1e7`.
pub const ZETAS: [(f64, f64); 4] = [(1e7, 0.05), (1e7, 0.2), (1e7, 0.5), (1e7, 1.0)];
/// The error levels of the best-time table.
pub const LEVELS: [f64; 3] = [1e-3, 1e-4, 1e-5];
const LINKS: usize = 20;
const T_END: f64 = 3.2;

/// Each method and its tolerances (BDF stops at `1e-6`: at `EA = 1e8` it
/// follows the axial modes, 258,000 steps at `1e-6`).
fn ladder() -> Vec<(Method, Vec<f64>)> {
    let all = vec![1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];
    vec![
        (Method::Dopri5, all.clone()),
        (Method::Dop853, vec![1e-4, 1e-6, 1e-8]),
        (Method::Bdf, vec![1e-3, 1e-4, 1e-5, 1e-6]),
        (Method::GenAlpha, all.clone()),
        (Method::Auto, all),
    ]
}

/// The scene's overrides at `ea` and `zeta` for `method` at `rtol`
/// (`atol = rtol / 100`).
pub fn overrides(ea: f64, zeta: f64, method: Method, rtol: f64) -> Vec<String> {
    let l = 6.0 / LINKS as f64;
    let eta = 2.0 * zeta * (ea * 0.2 * l).sqrt();
    vec![
        format!("chain.links={LINKS}"),
        format!("start.down={}", LINKS / 2),
        "chain.mass=0.2".into(),
        format!("chain.axial_stiffness={ea:e}"),
        format!("chain.axial_damping={eta:e}"),
        format!("run.t_end={T_END}"),
        format!("run.method=\"{method}\""),
        format!("run.rtol={rtol:e}"),
        format!("run.atol={:e}", rtol / 100.0),
    ]
}

struct Point {
    case: (f64, f64),
    method: Method,
    error: f64,
    wall: f64,
}

/// Runs the study's `cases` (`(EA, zeta)`) on scenes from `prepare` (the
/// folded scene with the given overrides): the rows and the best-time
/// table.
pub fn tables(
    prepare: &dyn Fn(&[String]) -> Result<Prepared, String>,
    cases: &[(f64, f64)],
) -> Result<[String; 2], String> {
    let mut csv = HEADER.to_string();
    let mut points = vec![];
    for &(ea, zeta) in cases {
        let reference = prepare(&overrides(ea, zeta, Method::Dop853, 1e-10))?
            .solve()
            .map_err(|e| e.to_string())?;
        if reference.status != Status::Ok {
            return Err(format!(
                "EA = {ea:e}, zeta = {zeta}: the reference ended {}",
                reference.status
            ));
        }
        let (tip0, v0) = (reference.summary.tip_end, reference.summary.tip_speed_max);
        for (method, rtols) in ladder() {
            for rtol in rtols {
                let p = prepare(&overrides(ea, zeta, method, rtol))?;
                let clock = Instant::now();
                let run = p.solve().map_err(|e| e.to_string())?;
                let wall = clock.elapsed().as_secs_f64();
                let s = &run.summary;
                let error = if run.status == Status::Ok {
                    let d = (s.tip_end[0] - tip0[0]).hypot(s.tip_end[1] - tip0[1]) / 6.0;
                    d.max((s.tip_speed_max - v0).abs() / v0)
                } else {
                    f64::NAN
                };
                let _ = writeln!(
                    csv,
                    "{},{},{method},{},{},{},{},{}",
                    num(ea),
                    num(zeta),
                    num(rtol),
                    run.status,
                    run.stats.steps,
                    if error.is_finite() {
                        num(error)
                    } else {
                        String::new()
                    },
                    num(wall)
                );
                if error.is_finite() {
                    points.push(Point {
                        case: (ea, zeta),
                        method,
                        error,
                        wall,
                    });
                }
            }
        }
    }
    let mut best = BEST_HEADER.to_string();
    for level in LEVELS {
        for (method, _) in ladder() {
            for &case in cases {
                let t = points
                    .iter()
                    .filter(|p| p.case == case && p.method == method && p.error <= level)
                    .map(|p| p.wall)
                    .fold(f64::INFINITY, f64::min);
                if t.is_finite() {
                    let _ = writeln!(
                        best,
                        "{},{method},{},{},{}",
                        num(level),
                        num(case.0),
                        num(case.1),
                        num(t)
                    );
                }
            }
        }
    }
    Ok([csv, best])
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc_scene::Scene;

    /// The overrides build the chain the study says: 20 rods of `m = 0.2`
    /// on the folded start with 10 down, the asked `EA`, and a joint
    /// damping ratio `C / (2 sqrt(K m))` of `zeta`, run to `t = 3.2` by
    /// the asked method and tolerances.
    #[test]
    fn the_overrides_give_the_asked_stiffness_and_damping_ratio() {
        let root =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/folded.toml");
        let scene = Scene::load(&root).unwrap();
        for (ea, zeta) in [(1e4, 0.05), (1e8, 1.0)] {
            let p = scene
                .with_overrides(&overrides(ea, zeta, Method::GenAlpha, 1e-5))
                .unwrap()
                .prepare()
                .unwrap();
            assert_eq!(p.chain.links(), 20);
            assert_eq!(p.chain.axial_stiffness(), Some(ea));
            let ratio = chain_ode::joint_damping_ratio(&p.chain).unwrap();
            assert!((ratio / zeta - 1.0).abs() < 1e-12, "{ratio} vs {zeta}");
            assert_eq!(p.method, Method::GenAlpha);
            assert_eq!(p.options.rtol, 1e-5);
            assert_eq!(p.options.t_end, 3.2);
        }
    }
}
