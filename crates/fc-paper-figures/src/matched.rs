//! Speed-ups at matched accuracy, from work-precision tables: a method's
//! wall time at an error level, interpolated linearly in `log(error)` -
//! `log(time)` between the first two consecutive runs (loosest first) whose
//! errors bracket the level, never extrapolated; `explicit-best` is, at each
//! level, the least such time among [`EXPLICIT`].

use std::fmt::Write as _;

use fc_csv::format::{exp, exp_digits, fixed};
use fc_csv::table::Table;

/// The explicit methods `explicit-best` chooses from.
pub const EXPLICIT: [&str; 3] = ["rk4", "dopri5", "dop853"];

/// The wall time at error `level` of `runs` (`(error, wall)`, loosest
/// first), log-log between the first bracketing pair; `None` if no pair
/// brackets it.
pub fn time_at(runs: &[(f64, f64)], level: f64) -> Option<f64> {
    runs.windows(2).find_map(|w| {
        let ((e0, t0), (e1, t1)) = (w[0], w[1]);
        let (lo, hi) = (e0.min(e1), e0.max(e1));
        if !(lo <= level && level <= hi) {
            return None;
        }
        if hi == lo {
            return Some(t0.min(t1));
        }
        let s = (level.ln() - e0.ln()) / (e1.ln() - e0.ln());
        Some((t0.ln() + s * (t1.ln() - t0.ln())).exp())
    })
}

/// `(method, wall)` of `name` at `level`, `explicit-best` resolved to the
/// fastest of [`EXPLICIT`]; `runs(method)` gives a method's `(error, wall)`
/// loosest first.
pub fn at<E>(
    name: &str,
    level: f64,
    runs: impl Fn(&str) -> Result<Vec<(f64, f64)>, E>,
) -> Result<Option<(String, f64)>, E> {
    if name == "explicit-best" {
        let mut best: Option<(String, f64)> = None;
        for m in EXPLICIT {
            if let Some(t) = time_at(&runs(m)?, level) {
                if best.as_ref().is_none_or(|b| t < b.1) {
                    best = Some((m.to_string(), t));
                }
            }
        }
        return Ok(best);
    }
    Ok(time_at(&runs(name)?, level).map(|t| (name.to_string(), t)))
}

/// `(error, wall)` of each `ok` run of `method`, loosest first.
fn runs(read: Read, scene: &str, method: &str) -> Result<Vec<(f64, f64)>, String> {
    let wp = read(scene)?;
    let tm = read(&format!("{scene}-timing"))?;
    let (m, param, status) = (wp.strs("method")?, wp.strs("param")?, wp.strs("status")?);
    let (et, ev) = (wp.nums("err_tip")?, wp.nums("err_vmax")?);
    let (tm_m, tm_p, wall) = (
        tm.strs("method")?,
        tm.strs("param")?,
        tm.nums("wall_median")?,
    );
    let mut out: Vec<(f64, f64, f64)> = vec![];
    for k in 0..wp.len() {
        if m[k] != method || status[k] != "ok" {
            continue;
        }
        let Some(j) = (0..tm.len()).find(|&j| tm_m[j] == method && tm_p[j] == param[k]) else {
            continue;
        };
        let p: f64 = param[k]
            .parse()
            .map_err(|_| format!("{scene}: bad param"))?;
        let e = et[k].max(ev[k]);
        if e.is_finite() && e > 0.0 && wall[j].is_finite() && wall[j] > 0.0 {
            out.push((p, e, wall[j]));
        }
    }
    // Loosest first: the largest step or tolerance first.
    out.sort_by(|a, b| b.0.total_cmp(&a.0));
    Ok(out.into_iter().map(|(_, e, w)| (e, w)).collect())
}

/// What [`table`] reads the work-precision tables with: `wp-<scene>` and
/// `wp-<scene>-timing` by name.
pub type Read<'a> = &'a dyn Fn(&str) -> Result<Table, String>;

/// The speed-ups at matched accuracy of each pair `(a, b)` of methods on
/// each work-precision table of `scenes` at each error level:
/// `scene,pair,error,a,a_method,wall_a,b,b_method,wall_b,b_over_a` (`pair`
/// is `a/b`; `b_over_a` = `wall_b / wall_a`, how many times faster `a` is
/// at that error), a row only where both methods have a time.
pub fn table(
    scenes: &[&str],
    pairs: &[(&str, &str)],
    levels: &[f64],
    read: Read,
) -> Result<String, String> {
    let mut csv = String::from("scene,pair,error,a,a_method,wall_a,b,b_method,wall_b,b_over_a\n");
    for &scene in scenes {
        for &(a, b) in pairs {
            for &level in levels {
                if let (Some((am, ta)), Some((bm, tb))) = (
                    at(a, level, |m| runs(read, scene, m))?,
                    at(b, level, |m| runs(read, scene, m))?,
                ) {
                    let _ = writeln!(
                        csv,
                        "{scene},{a}/{b},{},{a},{am},{},{b},{bm},{},{}",
                        exp(level),
                        exp_digits(ta, 3),
                        exp_digits(tb, 3),
                        fixed(tb / ta, 2)
                    );
                }
            }
        }
    }
    Ok(csv)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a power law `t = c e^-k` the log-log interpolation is exact; a
    /// level outside the runs has no time; explicit-best takes the least.
    #[test]
    fn interpolation_is_exact_on_a_power_law_and_never_extrapolates() {
        let law = |e: f64| 3.0 * e.powf(-0.2);
        let runs: Vec<(f64, f64)> = [1e-3, 1e-5, 1e-8].iter().map(|&e| (e, law(e))).collect();
        for level in [1e-4, 3e-6, 1e-7] {
            let t = time_at(&runs, level).unwrap();
            assert!((t / law(level) - 1.0).abs() < 1e-12, "{level}: {t}");
        }
        assert!(time_at(&runs, 1e-2).is_none() && time_at(&runs, 1e-9).is_none());
        let best = at("explicit-best", 1e-4, |m| {
            Ok::<_, ()>(match m {
                "dop853" => runs.iter().map(|&(e, t)| (e, t / 2.0)).collect(),
                _ => runs.clone(),
            })
        })
        .unwrap()
        .unwrap();
        assert_eq!(best.0, "dop853");
        assert!((best.1 - law(1e-4) / 2.0).abs() < 1e-12);
    }
}
