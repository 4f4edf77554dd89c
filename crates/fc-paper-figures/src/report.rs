//! The tables of the report's figures (fig02 .. fig12 of `docs/figures.md`)
//! from scene runs: catenaries, chain snapshots, tip speed and velocity
//! against time, and the maximum tip speed against the span. `cargo xtask
//! figures` chooses the scenes, writes these tables to `figures/data/` and
//! draws them.

use std::fmt::Write as _;

use catenary::Catenary;
use chain_ode::{Trajectory, Vec2};

use fc_batch::sweep::{self, Vary};
use fc_csv::format::{fixed, num};
use fc_csv::table::Table;
use fc_scene::scene::Scene;
use fc_study::converge;
use fc_study::render;

/// A finished run of a named scene and where its free end was held (P1).
pub struct Run<'a> {
    pub name: &'a str,
    pub traj: &'a Trajectory,
    pub release: Vec2,
}

/// Continuous catenaries from P0 = (0, 0) to `p1` for `count` lengths from
/// `l0` to `l1`: `kind,length,x,y`, kind `p1`, `curve` (201 points per
/// length) or `lowest`.
pub fn catenaries(p1: [f64; 2], (l0, l1, count): (f64, f64, usize)) -> Result<String, String> {
    let mut csv = format!("kind,length,x,y\np1,,{},{}\n", num(p1[0]), num(p1[1]));
    for k in 0..count {
        let length = l0 + (l1 - l0) * k as f64 / (count.max(2) - 1) as f64;
        let c = Catenary::through([0.0, 0.0], p1, length).map_err(|e| e.to_string())?;
        for i in 0..=200 {
            let x = p1[0] * i as f64 / 200.0;
            let _ = writeln!(
                csv,
                "curve,{},{},{}",
                num(length),
                fixed(x, 6),
                fixed(c.y(x), 6)
            );
        }
        let low = c.lowest_point();
        let _ = writeln!(
            csv,
            "lowest,{},{},{}",
            num(length),
            num(low[0]),
            num(low[1])
        );
    }
    Ok(csv)
}

/// Chain snapshots `snapshot_dt` apart: `point,t,x,y`, the pivot `P0` and
/// the release point `P1`, then joints `0..=n` of each snapshot.
pub fn snapshots(run: &Run, snapshot_dt: f64) -> String {
    let (p0, p1) = (run.traj.anchor, run.release);
    let mut csv = format!(
        "point,t,x,y\nP0,,{},{}\nP1,,{},{}\n",
        num(p0[0]),
        num(p0[1]),
        num(p1[0]),
        num(p1[1])
    );
    for (t, joints) in render::frames(run.traj, Some(snapshot_dt)) {
        for (i, p) in joints.iter().enumerate() {
            let _ = writeln!(csv, "{i},{},{},{}", num(t), fixed(p[0], 6), fixed(p[1], 6));
        }
    }
    csv
}

/// `scene,p1_x,p1_y,t_tip_speed_max,tip_speed_max`, one row per run (the
/// legend order).
pub fn scenes(runs: &[Run]) -> String {
    let mut csv = String::from("scene,p1_x,p1_y,t_tip_speed_max,tip_speed_max\n");
    for run in runs {
        let sm = &run.traj.summary;
        let _ = writeln!(
            csv,
            "{},{},{},{},{}",
            run.name,
            num(run.release[0]),
            num(run.release[1]),
            num(sm.t_tip_speed_max),
            num(sm.tip_speed_max)
        );
    }
    csv
}

/// `scene,t,tip_speed` at every sample of each run.
pub fn tip_speed(runs: &[Run]) -> String {
    let mut csv = String::from("scene,t,tip_speed\n");
    for run in runs {
        for (t, v) in render::tip_speed(run.traj) {
            let _ = writeln!(csv, "{},{},{}", run.name, fixed(t, 6), fixed(v, 6));
        }
    }
    csv
}

/// The tip velocity's path is kept to within this share of its largest
/// speed ([`simplify`]): well under a pixel of the figure.
pub const VELOCITY_TOLERANCE: f64 = 5e-4;

/// `scene,v_x,v_y` along each run's tip velocity: its samples, thinned to
/// those the path needs to stay within [`VELOCITY_TOLERANCE`] of the
/// run's largest speed ([`simplify`]), so that a run sampled finely
/// through its whip draws a smooth loop from a table of modest size.
pub fn tip_velocity(runs: &[Run]) -> String {
    let mut csv = String::from("scene,v_x,v_y\n");
    for run in runs {
        let path = render::tip_velocity_path(run.traj);
        let top = path.iter().map(|p| p.0.hypot(p.1)).fold(0.0, f64::max);
        for (vx, vy) in simplify(&path, VELOCITY_TOLERANCE * top) {
            let _ = writeln!(csv, "{},{},{}", run.name, fixed(vx, 6), fixed(vy, 6));
        }
    }
    csv
}

/// The points of the polyline `path` that keep it within `tol` of every
/// point dropped (Douglas and Peucker's simplification; the ends kept).
pub fn simplify(path: &[(f64, f64)], tol: f64) -> Vec<(f64, f64)> {
    if path.len() < 3 {
        return path.to_vec();
    }
    let mut keep = vec![false; path.len()];
    let (first, last) = (0, path.len() - 1);
    keep[first] = true;
    keep[last] = true;
    let mut stack = vec![(first, last)];
    while let Some((a, b)) = stack.pop() {
        let (p, q) = (path[a], path[b]);
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        let len = dx.hypot(dy);
        let dist = |r: (f64, f64)| {
            if len > 0.0 {
                ((r.0 - p.0) * dy - (r.1 - p.1) * dx).abs() / len
            } else {
                (r.0 - p.0).hypot(r.1 - p.1)
            }
        };
        let far = (a + 1..b)
            .map(|k| (k, dist(path[k])))
            .fold((a, -1.0), |m, c| if c.1 > m.1 { c } else { m });
        if far.1 > tol {
            keep[far.0] = true;
            stack.push((a, far.0));
            stack.push((far.0, b));
        }
    }
    path.iter()
        .zip(keep)
        .filter(|(_, k)| *k)
        .map(|(p, _)| *p)
        .collect()
}

/// A row per named run: its method, chain, status, work, energy balance
/// and tip (no wall times).
pub fn summary(runs: &[(&str, &Trajectory)]) -> String {
    let mut s = String::from(
        "scene,method,links,damping,t_end,status,steps,rejected_steps,rhs_evals,\
         energy_start,energy_end,dissipated,energy_balance_error,energy_scale,\
         tip_speed_max,t_tip_speed_max,tip_end_x,tip_end_y\n",
    );
    for (name, t) in runs {
        let m = &t.summary;
        let _ = writeln!(
            s,
            "{name},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            t.method,
            t.chain().links(),
            num(t.chain().damping()),
            num(t.t_end),
            t.status,
            t.stats.steps,
            t.stats.rejected_steps,
            t.stats.rhs_evals,
            num(m.energy_start),
            num(m.energy_end),
            num(m.dissipated),
            num(m.energy_balance_error),
            num(t.chain().energy_scale()),
            num(m.tip_speed_max),
            num(m.t_tip_speed_max),
            num(m.tip_end[0]),
            num(m.tip_end[1]),
        );
    }
    s
}

/// `n` points from `a` to `b`.
pub fn linspace(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n.max(2) - 1) as f64)
        .collect()
}

/// The spans of [`vmax_vs_span`].
pub struct Spans {
    /// The report's spans (n = 50).
    pub report: Vec<f64>,
    /// A dense sweep (n = 50).
    pub dense: Vec<f64>,
    /// The refined chain's rods and spans, the continuum held fixed as
    /// `falling-chain converge` holds it (`m = M/n`, `r = eta n / L`),
    /// method `auto` at rtol 1e-8.
    pub refined: (usize, Vec<f64>),
}

/// A span's `(d, tip_speed_max, t_tip_speed_max)`.
type SpanMax = (f64, f64, f64);

/// The largest jump of `t_tip_speed_max` between neighbouring spans of
/// `rows` (`(d, v, t)`, sorted by `d`) at spans above `from`: where the
/// maximum switches from one whip event to another. Returns the two rows.
fn whip_switch(rows: &[SpanMax], from: f64) -> Option<(SpanMax, SpanMax)> {
    rows.windows(2)
        .filter(|w| w[0].0 >= from && w[0].2.is_finite() && w[1].2.is_finite())
        .max_by(|a, b| (a[1].2 - a[0].2).abs().total_cmp(&(b[1].2 - b[0].2).abs()))
        .map(|w| (w[0], w[1]))
}

/// Spans above which [`whip_switch`] looks for the switch (the curve's
/// minimum near `d = 5.3`; below it the maximum's time moves smoothly).
const SWITCH_FROM: f64 = 4.0;

/// The maximum tip speed against the span `d` (`start.p1.0`) of `base`:
/// `set,d,tip_speed_max,t_tip_speed_max,status` for the sets `report`,
/// `dense`, `stretched` (the run `stretched` of the scene `stretched_scene`,
/// d = L), `n<links>` and `stretched-n<links>` (the refined chain), and
/// `switch-before` / `switch-after` (and `-n<links>`): the two
/// neighbouring spans of the dense curve between which the time of the
/// maximum jumps (the whip switch). Every span runs adaptive DOPRI5 at
/// rtol 1e-8 (RK4 at the report's dt diverges near d = 1), `jobs` at once.
pub fn vmax_vs_span(
    base: &Scene,
    (stretched_scene, stretched): (&Scene, &Run),
    spans: &Spans,
    jobs: usize,
) -> Result<String, String> {
    let base = base
        .with_overrides(&["run.method=dopri5", "run.rtol=1e-8", "run.atol=1e-10"])
        .map_err(|e| e.to_string())?;
    let mut csv = String::from("set,d,tip_speed_max,t_tip_speed_max,status\n");
    for (set, spans) in [("report", &spans.report), ("dense", &spans.dense)] {
        let vary = [Vary::floats("start.p1.0", spans)];
        let rows = sweep::run(&base, &vary, None, jobs, &|_, _| {}).map_err(|e| e.to_string())?;
        for (r, &d) in rows.iter().zip(spans.iter()) {
            let s = &r.summary;
            let _ = writeln!(
                csv,
                "{set},{},{},{},{}",
                num(d),
                num(s.tip_speed_max),
                num(s.t_tip_speed_max),
                s.status
            );
        }
    }
    let full = stretched;
    let s = &full.traj.summary;
    let span_full = full.release[0] - full.traj.anchor[0];
    let _ = writeln!(
        csv,
        "stretched,{},{},{},{}",
        num(span_full),
        num(s.tip_speed_max),
        num(s.t_tip_speed_max),
        full.traj.status
    );
    // The refined chain: the n = 50 scene at `links` rods with the
    // continuum fixed, over fewer spans, and its stretched chain.
    let (links, fine_spans) = &spans.refined;
    let links = *links;
    let refine = |scene: &Scene| {
        converge::refined_scene(scene, links)
            .and_then(|s| s.with_overrides(&["run.method=auto", "run.rtol=1e-8", "run.atol=1e-10"]))
            .map_err(|e| e.to_string())
    };
    let fine = refine(&base)?;
    let rows = sweep::run(
        &fine,
        &[Vary::floats("start.p1.0", fine_spans)],
        None,
        jobs,
        &|_, _| {},
    )
    .map_err(|e| e.to_string())?;
    let set = format!("n{links}");
    for (r, &d) in rows.iter().zip(fine_spans.iter()) {
        let s = &r.summary;
        let _ = writeln!(
            csv,
            "{set},{},{},{},{}",
            num(d),
            num(s.tip_speed_max),
            num(s.t_tip_speed_max),
            s.status
        );
    }
    let stretched = refine(stretched_scene)?;
    let mut prepared = stretched.prepare().map_err(|e| e.to_string())?;
    prepared.options.output_dt = None;
    let traj = prepared.solve().map_err(|e| e.to_string())?;
    let _ = writeln!(
        csv,
        "stretched-{set},{},{},{},{}",
        num(span_full),
        num(traj.summary.tip_speed_max),
        num(traj.summary.t_tip_speed_max),
        traj.status
    );
    // The whip switch of each curve, from the data just written.
    let table = Table::parse("vmax-vs-span", &csv)?;
    let (tset, td, tv, tt, tst) = (
        table.strs("set")?,
        table.nums("d")?,
        table.nums("tip_speed_max")?,
        table.nums("t_tip_speed_max")?,
        table.strs("status")?,
    );
    let mut extra = String::new();
    for (which, suffix) in [("dense", String::new()), (set.as_str(), format!("-{set}"))] {
        let mut pts: Vec<SpanMax> = (0..table.len())
            .filter(|&k| tset[k] == which && tst[k] == "ok")
            .map(|k| (td[k], tv[k], tt[k]))
            .collect();
        pts.sort_by(|x, y| x.0.total_cmp(&y.0));
        if let Some((lo, hi)) = whip_switch(&pts, SWITCH_FROM) {
            for (name, p) in [("switch-before", lo), ("switch-after", hi)] {
                let _ = writeln!(
                    extra,
                    "{name}{suffix},{},{},{},ok",
                    num(p.0),
                    num(p.1),
                    num(p.2)
                );
            }
        }
    }
    csv.push_str(&extra);
    Ok(csv)
}

/// The values `linspace(start, stop, num)[from..to]`: `num` evenly spaced
/// values from `start` to `stop` (both included), of which those at the
/// indices `from..to` are kept.
#[derive(Clone, Copy, Debug)]
pub struct LinspaceSlice {
    pub start: f64,
    pub stop: f64,
    pub num: usize,
    pub from: usize,
    pub to: usize,
}

impl LinspaceSlice {
    /// The values kept; errs if `from..to` is not within `0..num`.
    pub fn values(&self) -> Result<Vec<f64>, String> {
        let all = linspace(self.start, self.stop, self.num);
        (all.get(self.from..self.to).map(<[f64]>::to_vec))
            .ok_or_else(|| format!("spans {}..{} of {}", self.from, self.to, self.num))
    }
}

/// The spans of Fig. 9 ([`vmax_tables`]).
#[derive(Clone, Copy, Debug)]
pub struct SpanParams {
    /// The report's spans (n = 50).
    pub report: LinspaceSlice,
    /// `linspace(a, b, n)` (n = 50).
    pub dense: (f64, f64, usize),
    /// The refined curve: `(links, linspace(a, b, count))`, the continuum
    /// held fixed as `falling-chain converge` holds it (`m = M/n`,
    /// `r = eta n / L`), method `auto` at rtol 1e-8.
    pub refined: (usize, f64, f64, usize),
    /// The refined chain's peak at narrow spans: its rods and twice them,
    /// over `linspace(a, b, count)` ([`super::span_check::peak`]).
    pub peak: (&'static [usize], f64, f64, usize),
}

/// Fig. 9's tables, as `(suffix, csv)`: [`vmax_vs_span`] of `base` (`""`),
/// where the 50-rod curve agrees with the refined one
/// ([`super::span_check::agreement`], `-agreement`) and the refined chain's
/// narrow-span peak ([`super::span_check::peak`], `-peak`), `jobs` runs at
/// once.
pub fn vmax_tables(
    base: &Scene,
    stretched: (&Scene, &Run),
    p: &SpanParams,
    jobs: usize,
) -> Result<Vec<(&'static str, String)>, String> {
    let (links, a, b, count) = p.refined;
    let spans = Spans {
        report: p.report.values()?,
        dense: linspace(p.dense.0, p.dense.1, p.dense.2),
        refined: (links, linspace(a, b, count)),
    };
    let csv = vmax_vs_span(base, stretched, &spans, jobs)?;
    let table = Table::parse("vmax-vs-span", &csv)?;
    let agreement = super::span_check::agreement(base, &table, links, jobs)?;
    let (rods, pa, pb, pc) = p.peak;
    let peak = super::span_check::peak(base, rods, &linspace(pa, pb, pc), jobs)?;
    Ok(vec![("", csv), ("-agreement", agreement), ("-peak", peak)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_simplified_path_stays_within_its_tolerance_and_keeps_the_corners() {
        // A square traced by 400 points: its four corners and ends remain.
        let mut path = vec![];
        for k in 0..400 {
            let s = f64::from(k) / 100.0;
            path.push(match k / 100 {
                0 => (s, 0.0),
                1 => (1.0, s - 1.0),
                2 => (3.0 - s, 1.0),
                _ => (0.0, 4.0 - s),
            });
        }
        let kept = simplify(&path, 1e-3);
        assert!(kept.len() <= 8, "{kept:?}");
        for corner in [(1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            assert!(
                kept.iter()
                    .any(|p| (p.0 - corner.0).hypot(p.1 - corner.1) < 0.02),
                "{corner:?} dropped"
            );
        }
        // A circle: the kept chords stay within the tolerance of the arc.
        let circle: Vec<(f64, f64)> = (0..=2000)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::TAU / 2000.0;
                (a.cos(), a.sin())
            })
            .collect();
        let kept = simplify(&circle, 1e-3);
        assert!(kept.len() < 200 && kept.len() > 20, "{}", kept.len());
        for w in kept.windows(2) {
            let half = (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1) / 2.0;
            // The sagitta of a chord of the unit circle.
            let sagitta = 1.0 - (1.0 - half * half).sqrt();
            assert!(sagitta <= 1.1e-3, "{sagitta}");
        }
    }
}
