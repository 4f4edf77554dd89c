//! An independent check of the dynamics: the elastic chain (maximal
//! coordinates, joints as stiff damped springs, `chain_ode::elastic`) and
//! the rigid chain (minimal coordinates, the angles, `chain_ode::dynamics`)
//! share no equation of motion, so the one's limit as `EA` grows must be
//! the other. Both move the tip by `O(F / EA)` (the static stretch and the
//! axial ringing), so the distance between them must fall like `1/EA`: a
//! wrong term in either leaves an offset that does not fall, and the
//! measured order drops towards 0.
//!
//! Each scene runs before any whip (its `t_end` set below the whip), rigid
//! and then elastic on a ladder of `EA` (5% damping of one joint, as
//! `rigid_limit`), every run by DOP853 at [`RTOL`] so that the integration
//! error is far below the distance measured. The table gives, per rung, the
//! distances ([`Deviation`]: the tip path's maximum over the samples and the
//! tip's distance at `t_end`, over `L`, and the maximum tip speed's,
//! relative) and the local order `-d log(deviation) / d log(EA)` of the
//! first two against the rung before; the fit table gives the
//! least-squares order over the ladder's upper half. (The maximum tip speed
//! before the whip is the speed at a moment the axial ringing moves, so its
//! distance is not smooth in `EA`, and no order is fitted to it.)

use std::fmt::Write as _;

use fc_csv::format::{exp, exp_digits, fixed};
use fc_scene::error::Error;
use fc_scene::scene::Scene;
use fc_study::converge::{run_level, Deviation};
use fc_study::log_slope;
use fc_study::rigid_limit::{elastic, rigid};

/// DOP853's `rtol` for every run (`atol = rtol / 100`).
pub const RTOL: f64 = 1e-10;
/// Damping ratio of one joint's axial mode.
pub const ZETA: f64 = 0.05;

/// The header of [`rungs_csv`].
pub const HEADER: &str = "scene,links,t_end,axial_stiffness,tip_path,tip_end,tip_speed_max,\
                          order_tip_path,order_tip_end\n";
/// The header of [`fit_csv`].
pub const FIT_HEADER: &str = "scene,links,t_end,ea_from,ea_to,order_tip_path,order_tip_end\n";

/// One scene's ladder: `(EA, deviation)`, lowest `EA` first.
pub struct Ladder {
    pub scene: String,
    pub links: usize,
    pub t_end: f64,
    pub rungs: Vec<(f64, Deviation)>,
}

/// Runs `scene` (its own `n`) to `t_end`, rigid and at each `EA` of
/// `ladder` (increasing).
pub fn ladder(scene: &Scene, t_end: f64, ladder: &[f64]) -> Result<Ladder, Error> {
    let s = scene.with_value("run.t_end", toml::Value::Float(t_end))?;
    let n = s.chain_params().links;
    let run = |sc: &Scene| run_level(sc, n, Some("dop853"), Some(RTOL));
    let reference = run(&rigid(&s)?)?;
    let mut rungs = vec![];
    for &ea in ladder {
        let (e, _) = elastic(&s, ea, ZETA)?;
        let level = run(&e)?;
        if level.summary.status != "ok" {
            return Err(Error::field(
                "chain.axial_stiffness",
                format!(
                    "the elastic run at EA = {ea:e} ended {}",
                    level.summary.status
                ),
            ));
        }
        rungs.push((ea, Deviation::between(&level, &reference)));
    }
    Ok(Ladder {
        scene: scene.name().to_string(),
        links: n,
        t_end,
        rungs,
    })
}

/// `-d log(b) / d log(a)` between two points.
fn order(a: (f64, f64), b: (f64, f64)) -> f64 {
    -(b.1 / a.1).ln() / (b.0 / a.0).ln()
}

/// The rows of one ladder (under [`HEADER`]).
pub fn rungs_csv(l: &Ladder) -> String {
    let mut out = String::new();
    for (k, (ea, d)) in l.rungs.iter().enumerate() {
        let (op, ov) = match k.checked_sub(1).map(|j| &l.rungs[j]) {
            Some((ea0, d0)) => (
                fixed(order((*ea0, d0.tip_path), (*ea, d.tip_path)), 3),
                fixed(order((*ea0, d0.tip_end), (*ea, d.tip_end)), 3),
            ),
            None => (String::new(), String::new()),
        };
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{op},{ov}",
            l.scene,
            l.links,
            exp(l.t_end),
            exp(*ea),
            exp_digits(d.tip_path, 3),
            exp_digits(d.tip_end, 3),
            exp_digits(d.tip_speed_max, 3)
        );
    }
    out
}

/// The least-squares order of the ladder's upper half (at least its last
/// two rungs), for the tip path and the tip at `t_end`.
pub fn fit(l: &Ladder) -> (f64, f64, f64, f64) {
    let from = l.rungs.len() / 2;
    let upper = &l.rungs[from.min(l.rungs.len().saturating_sub(2))..];
    let slope = |f: fn(&Deviation) -> f64| {
        -log_slope(&upper.iter().map(|(ea, d)| (*ea, f(d))).collect::<Vec<_>>())
    };
    let ea_from = upper.first().map_or(f64::NAN, |r| r.0);
    let ea_to = upper.last().map_or(f64::NAN, |r| r.0);
    (ea_from, ea_to, slope(|d| d.tip_path), slope(|d| d.tip_end))
}

/// The fit's row (under [`FIT_HEADER`]).
pub fn fit_csv(l: &Ladder) -> String {
    let (a, b, op, ov) = fit(l);
    format!(
        "{},{},{},{},{},{},{}\n",
        l.scene,
        l.links,
        exp(l.t_end),
        exp(a),
        exp(b),
        fixed(op, 3),
        fixed(ov, 3)
    )
}
