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

use fc_paper_figures::matched;
use fc_paper_figures::plot;

use crate::ctx::Ctx;
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

pub struct MatchedTiming;

impl Make for MatchedTiming {
    /// `wp-matched-timing.csv`:
    /// `scene,pair,error,a,a_method,wall_a,b,b_method,wall_b,b_over_a`
    /// (`pair` is `a/b`; `b_over_a` = `wall_b / wall_a`, how many times
    /// faster `a` is at that error).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let read = |file: &str| ctx.read(&format!("{file}.csv"));
        let csv = matched::table(&SCENES, &PAIRS, &LEVELS, &read)?;
        Ok(vec![ctx.write(&format!("{}-timing.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, plot::timing::matched)
    }
}
