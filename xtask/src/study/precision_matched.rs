//! `wp-matched`: speed-ups at matched accuracy, derived from the
//! work-precision data (no run of its own).
//!
//! Method. For each work-precision scene (`wp-span-d3`, `wp-folded`,
//! `wp-stiff-rope`) a method's runs are its rows of `wp-<scene>.csv` with
//! status `ok`, in the order of its accuracy parameter (loosest first), each
//! with the error `max(err_tip, err_vmax)` and the wall median of the same
//! `(method, param)` row of `wp-<scene>-timing.csv`. A method's wall time at
//! an error level `E` is interpolated linearly in `log(error)`-`log(time)`
//! between the first two consecutive runs whose errors bracket `E`; a method
//! that does not bracket `E` has no time there (never extrapolated).
//! `explicit-best` is, at each level, the least such time among RK4, DOPRI5
//! and DOP853 (the one chosen is named). A row is written only where both
//! methods of a pair have a time. Since it is derived from timing files it
//! is itself a timing file, rewritten only by `--timings` (after the
//! work-precision figures, which come before it in the registry); it is a
//! pure function of the committed files.

use std::fmt::Write as _;

use falling_chain::study::matched;
use figures::{palette, LinePlot, Series, Style};

use crate::ctx::Ctx;
use crate::data::{distinct, exp, exp_digits, fixed};
use crate::registry::{Figure, Make};

/// The work-precision scenes.
const SCENES: [&str; 3] = ["wp-span-d3", "wp-folded", "wp-stiff-rope"];
/// The pairs compared: `(a, b)`, the ratio is `wall_b / wall_a`.
const PAIRS: [(&str, &str); 4] = [
    ("dop853", "dopri5"),
    ("bdf", "dopri5"),
    ("bdf", "bdf-dense"),
    ("explicit-best", "bdf"),
];
/// The error levels.
const LEVELS: [f64; 5] = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12];

/// `(error, wall)` of each `ok` run of `method`, loosest first.
fn runs(ctx: &Ctx, scene: &str, method: &str) -> Result<Vec<(f64, f64)>, String> {
    let wp = ctx.read(&format!("{scene}.csv"))?;
    let tm = ctx.read(&format!("{scene}-timing.csv"))?;
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

/// `(method, wall)` of `name` at `level` (`explicit-best` resolved).
fn at(ctx: &Ctx, scene: &str, name: &str, level: f64) -> Result<Option<(String, f64)>, String> {
    matched::at(name, level, |m| runs(ctx, scene, m))
}

pub struct MatchedTiming;

impl Make for MatchedTiming {
    /// `wp-matched-timing.csv`:
    /// `scene,pair,error,a,a_method,wall_a,b,b_method,wall_b,b_over_a`
    /// (`pair` is `a/b`; `b_over_a` = `wall_b / wall_a`, how many times
    /// faster `a` is at that error).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let mut csv =
            String::from("scene,pair,error,a,a_method,wall_a,b,b_method,wall_b,b_over_a\n");
        for scene in SCENES {
            for (a, b) in PAIRS {
                for level in LEVELS {
                    if let (Some((am, ta)), Some((bm, tb))) =
                        (at(ctx, scene, a, level)?, at(ctx, scene, b, level)?)
                    {
                        writeln!(
                            csv,
                            "{scene},{a}/{b},{},{a},{am},{},{b},{bm},{},{}",
                            exp(level),
                            exp_digits(ta, 3),
                            exp_digits(tb, 3),
                            fixed(tb / ta, 2)
                        )
                        .unwrap();
                    }
                }
            }
        }
        Ok(vec![ctx.write(&format!("{}-timing.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}-timing.csv", fig.id))?;
        let (scene, pair, err, ratio) = (
            t.strs("scene")?,
            t.strs("pair")?,
            t.nums("error")?,
            t.nums("b_over_a")?,
        );
        let mut p = LinePlot::new(
            "wp-matched: speed-up at matched error (wall_b / wall_a)",
            "error max(err_tip, err_vmax)",
            "wall_b / wall_a",
        );
        p.log_x = true;
        p.log_y = true;
        let styles = [Style::LinePoints, Style::Dashed, Style::Line];
        for (i, pr) in distinct(&pair).into_iter().enumerate() {
            for (j, sc) in distinct(&scene).into_iter().enumerate() {
                let pts: Vec<(f64, f64)> = (0..t.len())
                    .filter(|&k| pair[k] == pr && scene[k] == sc)
                    .map(|k| (err[k], ratio[k]))
                    .collect();
                if pts.is_empty() {
                    continue;
                }
                p.series.push(
                    Series::new(format!("{pr}, {sc}"), pts, styles[j % styles.len()])
                        .with_color(palette(i)),
                );
            }
        }
        figures::line_plot(&p, &ctx.stem(fig.id))
            .map(|o| ctx.drawn(&o))
            .map_err(|e| format!("{}: {e}", fig.id))
    }
}
