//! Fig. 9's claims, each from runs: where the 50-rod curve of the maximum
//! tip speed against the span agrees with the refined chain's within
//! [`AGREEMENT`] (the 50-rod chain run at the refined chain's own spans, so
//! nothing is interpolated), and the refined chain's peak at narrow spans
//! on finer spans, at the refined `n` and at twice it.

use std::fmt::Write as _;

use fc_batch::sweep::{self, Vary};
use fc_csv::format::num;
use fc_csv::table::Table;
use fc_scene::scene::Scene;
use fc_study::converge;

/// The relative agreement Fig. 9's text states a range for.
pub const AGREEMENT: f64 = 0.01;

/// The header of [`agreement`].
pub const AGREEMENT_HEADER: &str = "kind,d,d_to,spans,vmax_n50,vmax_fine,rel_diff\n";
/// The header of [`peak`].
pub const PEAK_HEADER: &str = "links,d,tip_speed_max,t_tip_speed_max,status\n";

/// `(d, tip_speed_max, t_tip_speed_max, status)` of each span of `scene`.
fn sweep_spans(
    scene: &Scene,
    spans: &[f64],
    jobs: usize,
) -> Result<Vec<(f64, f64, f64, String)>, String> {
    let rows = sweep::run(
        scene,
        &[Vary::floats("start.p1.0", spans)],
        None,
        jobs,
        &|_, _| {},
    )
    .map_err(|e| e.to_string())?;
    Ok(rows
        .iter()
        .zip(spans)
        .map(|(r, &d)| {
            let s = &r.summary;
            (d, s.tip_speed_max, s.t_tip_speed_max, s.status.clone())
        })
        .collect())
}

/// `base` at `links` rods with the continuum held fixed (`m = M/n`,
/// `r = eta n / L`, as `falling-chain converge`), `auto` at rtol 1e-8: the
/// refined chain of Fig. 9.
pub fn refined(base: &Scene, links: usize) -> Result<Scene, String> {
    converge::refined_scene(base, links)
        .and_then(|s| s.with_overrides(&["run.method=auto", "run.rtol=1e-8", "run.atol=1e-10"]))
        .map_err(|e| e.to_string())
}

/// The 50-rod scene `base` (DOPRI5 at rtol 1e-8, as Fig. 9's dense curve)
/// at the spans of the set `n<links>` of `fig09` (the table of
/// `report::vmax_vs_span`), against that set: a `span` row per span with
/// both maxima and `rel_diff = v_50 / v_fine - 1`, then a `within` row per
/// maximal run of neighbouring spans with `|rel_diff| <= AGREEMENT` (its
/// first and last span, and how many), and a `longest` row repeating the
/// longest such run.
pub fn agreement(base: &Scene, fig09: &Table, links: usize, jobs: usize) -> Result<String, String> {
    let set = format!("n{links}");
    let (s, d, v, st) = (
        fig09.strs("set")?,
        fig09.nums("d")?,
        fig09.nums("tip_speed_max")?,
        fig09.strs("status")?,
    );
    let mut fine: Vec<(f64, f64)> = (0..fig09.len())
        .filter(|&k| s[k] == set && st[k] == "ok")
        .map(|k| (d[k], v[k]))
        .collect();
    fine.sort_by(|a, b| a.0.total_cmp(&b.0));
    let spans: Vec<f64> = fine.iter().map(|p| p.0).collect();
    let coarse = base
        .with_overrides(&["run.method=dopri5", "run.rtol=1e-8", "run.atol=1e-10"])
        .map_err(|e| e.to_string())?;
    let rows = sweep_spans(&coarse, &spans, jobs)?;
    let mut csv = String::from(AGREEMENT_HEADER);
    let mut marks = vec![];
    for ((d, v50, _, status), &(_, vf)) in rows.iter().zip(&fine) {
        let rel = v50 / vf - 1.0;
        let _ = writeln!(
            csv,
            "span,{},,,{},{},{}",
            num(*d),
            num(*v50),
            num(vf),
            num(rel)
        );
        marks.push((*d, status == "ok" && rel.abs() <= AGREEMENT));
    }
    let runs = within_runs(&marks);
    for (a, b, k) in &runs {
        let _ = writeln!(csv, "within,{},{},{k},,,", num(*a), num(*b));
    }
    if let Some((a, b, k)) = runs.iter().max_by_key(|r| r.2) {
        let _ = writeln!(csv, "longest,{},{},{k},,,", num(*a), num(*b));
    }
    Ok(csv)
}

/// The maximal runs of neighbouring spans marked `true` in `marks`
/// (`(d, within)`, in order of `d`): each run's first and last `d` and its
/// length.
pub fn within_runs(marks: &[(f64, bool)]) -> Vec<(f64, f64, usize)> {
    let mut runs = vec![];
    let mut open: Option<(f64, f64, usize)> = None;
    for &(d, within) in marks {
        open = match (open, within) {
            (Some((a, _, k)), true) => Some((a, d, k + 1)),
            (None, true) => Some((d, d, 1)),
            (Some(r), false) => {
                runs.push(r);
                None
            }
            (None, false) => None,
        };
    }
    runs.extend(open);
    runs
}

/// The refined chain of `base` at each of `links` over `spans`.
pub fn peak(base: &Scene, links: &[usize], spans: &[f64], jobs: usize) -> Result<String, String> {
    let mut csv = String::from(PEAK_HEADER);
    for &n in links {
        for (d, v, t, status) in sweep_spans(&refined(base, n)?, spans, jobs)? {
            let _ = writeln!(csv, "{n},{},{},{},{status}", num(d), num(v), num(t));
        }
    }
    Ok(csv)
}

#[cfg(test)]
mod tests {
    use super::within_runs;

    #[test]
    fn runs_of_agreement_are_maximal_and_keep_their_ends() {
        let marks = [
            (1.0, false),
            (2.0, true),
            (3.0, true),
            (4.0, false),
            (5.0, true),
        ];
        assert_eq!(within_runs(&marks), vec![(2.0, 3.0, 2), (5.0, 5.0, 1)]);
        assert!(within_runs(&[(1.0, false)]).is_empty());
    }
}
