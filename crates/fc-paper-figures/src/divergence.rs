//! When two runs of a scene separate: two DOPRI5 runs at the reference
//! tolerance, one from angles perturbed by [`PERTURBATION`], and the last
//! time before their tips are [`AMPLIFICATION_MAX`] times further apart
//! (the work-precision figure of the folded chain evaluates its errors
//! there, before chaos amplifies every error alike).

use chain_ode::kinematics::tip;
use chain_ode::{solve, Method};

use fc_csv::table::Table;
use fc_scene::error::Error;
use fc_scene::scene::Prepared;
use fc_study::precision::reference_options;

/// Size of the perturbation of the initial angles in the divergence test.
pub const PERTURBATION: f64 = 1e-10;
/// Two runs have separated once their tips are this many times further
/// apart than the perturbation.
pub const AMPLIFICATION_MAX: f64 = 1e3;

/// How two runs from nearly the same start drift apart.
pub struct Divergence {
    /// `(t, |tip - tip'|)` of two reference-accuracy runs, every 0.01.
    pub curve: Vec<(f64, f64)>,
    /// The reference run's maximum tip speed: the whip.
    pub t_whip: f64,
    /// The last sample time before they separate, or the end.
    pub t_eval: f64,
}

/// When two runs' tips first separate (see [`AMPLIFICATION_MAX`]), if they
/// do: the index into `curve` of `(t, |tip - tip'|)`.
pub fn separation(curve: &[(f64, f64)]) -> Option<usize> {
    let limit = AMPLIFICATION_MAX * PERTURBATION;
    curve.iter().position(|c| c.1 > limit)
}

/// Two DOPRI5 runs at the reference tolerance, one from angles perturbed by
/// [`PERTURBATION`]: how far apart their tips are over the scene's time.
pub fn divergence(p: &Prepared) -> Result<Divergence, Error> {
    p.require_corrected("the divergence study")?;
    let mut opts = reference_options(p.options.t_end);
    opts.output_dt = Some(0.01);
    let a = solve(&p.chain, &p.state, Method::Dopri5, &opts)?;
    let mut state = p.state.clone();
    for (i, phi) in state.angles.iter_mut().enumerate() {
        *phi += PERTURBATION * ((i + 1) as f64).sin();
    }
    let b = solve(&p.chain, &state, Method::Dopri5, &opts)?;
    if !a.status.is_ok() || !b.status.is_ok() {
        return Err(Error::field(
            "divergence",
            format!("the runs ended {} and {}", a.status, b.status),
        ));
    }
    let curve: Vec<(f64, f64)> = a
        .samples()
        .zip(b.samples())
        .map(|(sa, sb)| {
            let ta = tip(&p.chain, a.anchor, sa.angles);
            let tb = tip(&p.chain, b.anchor, sb.angles);
            (sa.t, (ta[0] - tb[0]).hypot(ta[1] - tb[1]))
        })
        .collect();
    let t_eval = match separation(&curve) {
        // Round the sample time to the 0.01 grid it sits on.
        Some(k) => (curve[k.saturating_sub(1)].0 * 100.0).round() / 100.0,
        None => p.options.t_end,
    };
    Ok(Divergence {
        t_whip: a.summary.t_tip_speed_max,
        t_eval,
        curve,
    })
}

/// Where the work-precision study of `p` evaluates its errors when its
/// runs may separate: [`divergence`] of `p` and of `undamped` (the same
/// scene with `r = 0`), their table ([`csv_text`]) and `t_eval`, the last
/// time before `p`'s runs separate. Errs if they separate before the whip
/// (an evaluation there would miss it).
pub fn evaluation(p: &Prepared, undamped: &Prepared) -> Result<(String, f64), String> {
    let div = divergence(p).map_err(|e| e.to_string())?;
    let free = divergence(undamped).map_err(|e| e.to_string())?;
    if div.t_eval < div.t_whip {
        return Err(format!(
            "runs separate (t = {}) before the whip (t = {:.3})",
            div.t_eval, div.t_whip
        ));
    }
    let csv = csv_text(&[(p.chain.damping(), &div), (0.0, &free)]);
    Ok((csv, div.t_eval))
}

/// The table of how runs separate: `damping,t,tip_separation,amplification`
/// for each `(damping, divergence)` (the amplification is the separation
/// over [`PERTURBATION`]).
pub fn csv_text(runs: &[(f64, &Divergence)]) -> String {
    use fc_csv::format::{exp, num};
    let mut csv = String::from("damping,t,tip_separation,amplification\n");
    for (r, d) in runs {
        for &(t, sep) in &d.curve {
            csv.push_str(&format!(
                "{},{},{},{}\n",
                num(*r),
                num(t),
                exp(sep),
                exp(sep / PERTURBATION)
            ));
        }
    }
    csv
}

/// The legend line of a table of [`csv_text`]: how far the scene's runs (its
/// first damping) and the `r = 0` runs separate.
pub fn note(t: &Table) -> Result<String, String> {
    let (damping, time, sep) = (t.strs("damping")?, t.nums("t")?, t.nums("tip_separation")?);
    let fmt = |r: &str| {
        let curve: Vec<(f64, f64)> = (0..t.len())
            .filter(|&k| damping[k] == r)
            .map(|k| (time[k], sep[k]))
            .collect();
        match separation(&curve) {
            Some(k) => format!(
                "×{} by t = {:.2}",
                fc_csv::format::short_err(AMPLIFICATION_MAX),
                curve[k].0
            ),
            None => format!(
                "×{:.0}",
                curve.iter().map(|c| c.1).fold(0.0, f64::max) / PERTURBATION
            ),
        }
    };
    match fc_csv::table::distinct(&damping)[..] {
        [scene, undamped] => Ok(format!(
            "runs {} apart: {} (r = 0: {})",
            fc_csv::format::exp(PERTURBATION),
            fmt(scene),
            fmt(undamped)
        )),
        _ => Err(format!("{}: expected two dampings", t.name)),
    }
}
