//! `force-precision`: the work-precision of the snap's forces beside the
//! tip's (issue 49). Issue 49's steel rope is `scenes/span-d3.toml` with
//! `n = 50`, `EA = 1e8` and 5% damping of one joint's axial mode; its
//! ladder costs minutes (DOPRI5 takes 245,000 steps at every rtol, DOP853
//! 400,000 at 1e-8, gen-alpha 3.2 million at 1e-8), so the figure runs the
//! same rope cut to [`LINKS`] rods at the same `EA` and damping ratio
//! (`eta = 0.1 sqrt(EA m l)`), to `t = 3.2` past the snap. Every method of
//! [`METHODS`] at every rtol of [`RTOLS`] (`atol = rtol / 100`) gives its
//! largest pivot force and largest joint tension (`Summary::peak`, tracked
//! at every step and refined inside it), its tip at the end, its work and
//! `forces_resolved`; each is compared with the converged run, DOP853 at
//! rtol `1e-8`, which DOPRI5 at `1e-9` confirms (the reference table
//! holds both, and the study refuses a reference they do not agree on to
//! [`AGREEMENT`]).
//!
//! The peaks converge only to the force's rounding floor: a joint's force
//! is its spring's `K = EA / l` times a stretch taken from positions of
//! size `L`, so it carries `K eps L`, `2e-7` of the peak here. Measured
//! once (`falling-chain simulate scenes/span-d3.toml` with these
//! overrides): DOP853 at rtol `1e-6 .. 1e-10` and DOPRI5 at `1e-6, 1e-9,
//! 1e-10` all lie within `3.5e-7` of one another, and DOP853 at `1e-11`
//! (17 million steps, 101 s) moves the peak by `1.1e-7`; a tighter
//! reference buys nothing, so the errors are drawn down to [`AGREEMENT`].
//! Everything it writes is a count or a result, never a wall time: its
//! data is reproducible byte for byte.

use std::fmt::Write as _;

use chain_ode::{Method, PeakForce, Status, Trajectory};
use fc_csv::format::num;
use fc_scene::Prepared;
use rayon::prelude::*;

/// `method,rtol,status,steps,rhs_evals,pivot_force_max,pivot_error,
/// tension_max,tension_joint,tension_error,tip_error,forces_resolved`:
/// the errors relative to the reference's peaks, the tip's distance over
/// `L`.
pub const HEADER: &str = "method,rtol,status,steps,rhs_evals,pivot_force_max,pivot_error,\
                          tension_max,tension_joint,tension_error,tip_error,forces_resolved\n";
/// `run,method,rtol,steps,pivot_force_max,tension_max,tension_joint,
/// tip_x,tip_y`: the reference and its confirmation.
pub const REFERENCE_HEADER: &str =
    "run,method,rtol,steps,pivot_force_max,tension_max,tension_joint,tip_x,tip_y\n";
/// The rope's rods (the steel rope has 50; its ladder costs minutes).
pub const LINKS: usize = 10;
/// The axial stiffness `EA` (force units): the steel rope's.
pub const AXIAL_STIFFNESS: f64 = 1e8;
/// The damping ratio of one joint's axial mode: the steel rope's 5%.
pub const ZETA: f64 = 0.05;
/// The run's end: past the snap (at about 2.76).
pub const T_END: f64 = 3.2;
/// The methods compared, in their order.
pub const METHODS: [Method; 5] = [
    Method::Dopri5,
    Method::Dop853,
    Method::Bdf,
    Method::GenAlpha,
    Method::Auto,
];
/// The tolerances of the ladder.
pub const RTOLS: [f64; 6] = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];
/// The reference (DOP853) and its confirmation (DOPRI5), and their rtol.
pub const REFERENCE: [(Method, f64); 2] = [(Method::Dop853, 1e-8), (Method::Dopri5, 1e-9)];
/// The most the reference and its confirmation may differ in either peak
/// (relative), the force's rounding floor (the module doc): the figure's
/// errors are read down to it.
pub const AGREEMENT: f64 = 3e-7;
/// The chain's length (`scenes/span-d3.toml`).
const LENGTH: f64 = 6.0;
/// Each rod's mass (`scenes/span-d3.toml`).
const ROD_MASS: f64 = 0.2;

/// The scene's overrides for `method` at `rtol` (`atol = rtol / 100`).
pub fn overrides(method: Method, rtol: f64) -> Vec<String> {
    let l = LENGTH / LINKS as f64;
    let eta = 2.0 * ZETA * (AXIAL_STIFFNESS * ROD_MASS * l).sqrt();
    vec![
        format!("chain.links={LINKS}"),
        format!("chain.axial_stiffness={AXIAL_STIFFNESS:e}"),
        format!("chain.axial_damping={eta:e}"),
        format!("run.t_end={T_END}"),
        format!("run.method=\"{method}\""),
        format!("run.rtol={rtol:e}"),
        format!("run.atol={:e}", rtol / 100.0),
    ]
}

/// A run's largest pivot force, largest tension and its joint.
fn peaks(run: &Trajectory) -> Result<(f64, f64, f64), String> {
    let s = &run.summary;
    let pivot = s.peak(PeakForce::Pivot).ok_or("no pivot force tracked")?;
    let tension = s.peak(PeakForce::Tension).ok_or("no tension tracked")?;
    Ok((pivot.value, tension.value, tension.reference))
}

/// Runs the ladder on scenes from `prepare` (`scenes/span-d3.toml` with
/// the given overrides, without output samples): the rows ([`HEADER`])
/// and the reference table ([`REFERENCE_HEADER`]).
pub fn tables(
    prepare: &(dyn Fn(&[String]) -> Result<Prepared, String> + Sync),
) -> Result<[String; 2], String> {
    let solve = |method: Method, rtol: f64| -> Result<Trajectory, String> {
        prepare(&overrides(method, rtol))?
            .solve()
            .map_err(|e| e.to_string())
    };
    let refs: Vec<Trajectory> = REFERENCE
        .par_iter()
        .map(|&(m, r)| solve(m, r))
        .collect::<Result<_, _>>()?;
    let mut reference = REFERENCE_HEADER.to_string();
    for (run, (&(method, rtol), name)) in refs
        .iter()
        .zip(REFERENCE.iter().zip(["reference", "confirmation"]))
    {
        if run.status != Status::Ok {
            return Err(format!("the {name} ({method}) ended {}", run.status));
        }
        let (p, t, j) = peaks(run)?;
        let tip = run.summary.tip_end;
        let _ = writeln!(
            reference,
            "{name},{method},{},{},{},{},{},{},{}",
            num(rtol),
            run.stats.steps,
            num(p),
            num(t),
            j,
            num(tip[0]),
            num(tip[1])
        );
    }
    let (p0, t0, _) = peaks(&refs[0])?;
    let (p1, t1, _) = peaks(&refs[1])?;
    let gap = (p1 / p0 - 1.0).abs().max((t1 / t0 - 1.0).abs());
    if gap.is_nan() || gap > AGREEMENT {
        return Err(format!(
            "the reference and its confirmation differ by {gap:e} in their peaks (at most {AGREEMENT:e})"
        ));
    }
    let tip0 = refs[0].summary.tip_end;
    let cases: Vec<(Method, f64)> = METHODS
        .iter()
        .flat_map(|&m| RTOLS.iter().map(move |&r| (m, r)))
        .collect();
    let rows: Vec<String> = cases
        .par_iter()
        .map(|&(method, rtol)| -> Result<String, String> {
            let run = solve(method, rtol)?;
            let s = &run.summary;
            let rel = |x: f64, want: f64| (x / want - 1.0).abs();
            let (p, t, j) = peaks(&run)?;
            let tip = (s.tip_end[0] - tip0[0]).hypot(s.tip_end[1] - tip0[1]) / LENGTH;
            // An `inaccurate` run reached the end too: its errors are
            // drawn, its status says what it is.
            let ok = run.t_reached >= T_END;
            let opt = |x: f64| if ok { num(x) } else { String::new() };
            Ok(format!(
                "{method},{},{},{},{},{},{},{},{},{},{},{}\n",
                num(rtol),
                run.status,
                run.stats.steps,
                run.stats.rhs_evals,
                num(p),
                opt(rel(p, p0)),
                num(t),
                j,
                opt(rel(t, t0)),
                opt(tip),
                s.forces_resolved
            ))
        })
        .collect::<Result<_, _>>()?;
    Ok([HEADER.to_string() + &rows.concat(), reference])
}

#[cfg(test)]
mod tests {
    use super::*;
    use fc_scene::Scene;

    /// The overrides build the rope the study says: the span-d3 chain on
    /// `LINKS` rods of `m = 0.2` at `EA = 1e8` and a joint damping ratio of
    /// 5%, run to `t = 3.2` by the asked method and tolerances.
    #[test]
    fn the_overrides_give_the_asked_rope() {
        let root =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/span-d3.toml");
        let scene = Scene::load(&root).unwrap();
        let p = scene
            .with_overrides(&overrides(Method::Bdf, 1e-5))
            .unwrap()
            .prepare()
            .unwrap();
        assert_eq!(p.chain.links(), LINKS);
        assert_eq!(p.chain.axial_stiffness(), Some(AXIAL_STIFFNESS));
        let ratio = chain_ode::joint_damping_ratio(&p.chain).unwrap();
        assert!((ratio / ZETA - 1.0).abs() < 1e-12, "{ratio}");
        assert_eq!(p.method, Method::Bdf);
        assert_eq!((p.options.rtol, p.options.atol), (1e-5, 1e-5 / 100.0));
        assert_eq!(p.options.t_end, T_END);
    }
}
