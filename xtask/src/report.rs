//! The kinds of the report's figures (fig01 .. fig12). Each kind is a
//! [`Make`] with its parameters, so a figure of the report is one entry of
//! the registry, never a copy of code: `compute` takes the shared scene
//! runs to `figures/data/<id>*.csv`, `draw` draws from those files.

use falling_chain::study::report;
use figures::{ChainSnapshots, LinePlot, Series, Style};

use crate::ctx::Ctx;
use crate::data::{distinct, Table};
use crate::registry::{Figure, Make};
use crate::runs::SceneRun;

fn title(fig: &Figure, title: &str) -> String {
    format!("{}: {title}", fig.label())
}

fn drawn(
    ctx: &Ctx,
    fig: &Figure,
    out: Result<figures::Output, figures::FigureError>,
) -> Result<Vec<String>, String> {
    out.map(|o| ctx.drawn(&o))
        .map_err(|e| format!("{}: {e}", fig.id))
}

/// The schematic of the problem (no data).
pub struct Sketch;

impl Make for Sketch {
    fn compute(&self, _: &Ctx, _: &Figure) -> Result<Vec<String>, String> {
        Ok(vec![])
    }
    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        drawn(ctx, fig, figures::sketch(&ctx.stem(fig.id)))
    }
}

/// Continuous catenaries from P0 = (0, 0) to `p1` for a range of lengths.
pub struct Catenaries {
    pub title: &'static str,
    pub p1: [f64; 2],
    /// `(first, last, count)` lengths.
    pub lengths: (f64, f64, usize),
}

impl Make for Catenaries {
    /// `<id>.csv`: `kind,length,x,y`, kind `p1`, `curve` (201 points per
    /// length) or `lowest`.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let csv = report::catenaries(self.p1, self.lengths)?;
        Ok(vec![ctx.write(&format!("{}.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let (kind, length, x, y) = (
            t.strs("kind")?,
            t.nums("length")?,
            t.nums("x")?,
            t.nums("y")?,
        );
        let mut p1 = None;
        let mut curves: Vec<(f64, Vec<(f64, f64)>)> = vec![];
        let mut lows = vec![];
        for k in 0..t.len() {
            match kind[k] {
                "p1" => p1 = Some([x[k], y[k]]),
                "lowest" => lows.push((x[k], y[k])),
                _ => match curves.last_mut() {
                    Some((l, pts)) if *l == length[k] => pts.push((x[k], y[k])),
                    _ => curves.push((length[k], vec![(x[k], y[k])])),
                },
            }
        }
        let title = title(fig, self.title);
        let mut f = figures::ColoredCurves::new(&title, curves, [0.0, 0.0]);
        f.p1 = p1;
        f.markers = lows;
        f.markers_label = "lowest point";
        f.colorbar_label = "L";
        drawn(ctx, fig, figures::colored_curves(&f, &ctx.stem(fig.id)))
    }
}

/// Chain snapshots of one scene, coloured by time.
pub struct Snapshots {
    pub title: &'static str,
    pub scene: &'static str,
    /// Draw every `every`-th snapshot (1: all) and always the last, so that
    /// the snapshots of a narrow chain stay apart.
    pub every: usize,
    /// The legend's name of `P1` when it is not the anchor the report calls
    /// P₁ (for the folded chain: where the free end starts).
    pub p1_label: Option<&'static str>,
}

impl Make for Snapshots {
    fn scenes(&self) -> Vec<&'static str> {
        vec![self.scene]
    }

    fn animation(&self) -> Option<&'static str> {
        Some(self.scene)
    }

    /// `<id>.csv`: `point,t,x,y`: the pivot `P0` and the release point `P1`,
    /// then joints `0..=n` of each snapshot (the scene's `output_dt` apart).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let run = ctx.run(self.scene)?;
        let csv = report::snapshots(&run.as_run(), run.snapshot_dt);
        Ok(vec![ctx.write(&format!("{}.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let (point, time, x, y) = (t.strs("point")?, t.nums("t")?, t.nums("x")?, t.nums("y")?);
        let (mut p0, mut p1) = ([0.0, 0.0], None);
        let mut frames: Vec<(f64, Vec<[f64; 2]>)> = vec![];
        for k in 0..t.len() {
            match point[k] {
                "P0" => p0 = [x[k], y[k]],
                "P1" => p1 = Some([x[k], y[k]]),
                "0" => frames.push((time[k], vec![[x[k], y[k]]])),
                _ => frames
                    .last_mut()
                    .ok_or_else(|| format!("{}: a joint before joint 0", t.name))?
                    .1
                    .push([x[k], y[k]]),
            }
        }
        let title = title(fig, self.title);
        let every = self.every.max(1);
        let last = frames.len().saturating_sub(1);
        let frames = frames
            .into_iter()
            .enumerate()
            .filter(|(k, _)| k % every == 0 || *k == last)
            .map(|(_, f)| f)
            .collect();
        let mut f = ChainSnapshots::new(&title, frames, p0);
        f.p1 = p1;
        if let Some(label) = self.p1_label {
            f.p1_label = label;
        }
        drawn(ctx, fig, figures::chain_snapshots(&f, &ctx.stem(fig.id)))
    }
}

/// `<id>.csv` (`table` of the runs of `scenes`) and `<id>-scenes.csv`
/// (where each was released, its continuous maximum tip speed).
fn tip_tables(
    ctx: &Ctx,
    fig: &Figure,
    scenes: &[&str],
    table: fn(&[report::Run]) -> String,
) -> Result<Vec<String>, String> {
    let runs = scenes
        .iter()
        .map(|s| ctx.run(s).map(SceneRun::as_run))
        .collect::<Result<Vec<_>, String>>()?;
    Ok(vec![
        ctx.write(&format!("{}.csv", fig.id), &table(&runs))?,
        ctx.write(&format!("{}-scenes.csv", fig.id), &report::scenes(&runs))?,
    ])
}

/// The legend entry of a scene: its name and where it was released.
fn scene_label(scene: &str, p1: (f64, f64)) -> String {
    format!("{scene} (P1 = ({:.3}, {:.3}))", p1.0, p1.1).replace(".000", "")
}

/// A scene of a tip figure: (name, legend label, (t_max, v_max)).
type SceneRow = (String, String, (f64, f64));

/// The scenes of `<id>-scenes.csv`.
fn read_scenes(ctx: &Ctx, fig: &Figure) -> Result<Vec<SceneRow>, String> {
    let t = ctx.read(&format!("{}-scenes.csv", fig.id))?;
    let (name, x, y) = (t.strs("scene")?, t.nums("p1_x")?, t.nums("p1_y")?);
    let (tm, vm) = (t.nums("t_tip_speed_max")?, t.nums("tip_speed_max")?);
    Ok((0..t.len())
        .map(|k| {
            (
                name[k].to_string(),
                scene_label(name[k], (x[k], y[k])),
                (tm[k], vm[k]),
            )
        })
        .collect())
}

/// The samples of column pair `(a, b)` of `t` for each scene in `scenes`.
fn per_scene(
    t: &Table,
    scenes: &[SceneRow],
    a: &str,
    b: &str,
) -> Result<Vec<Vec<(f64, f64)>>, String> {
    let (scene, a, b) = (t.strs("scene")?, t.nums(a)?, t.nums(b)?);
    let names = distinct(&scene);
    if names.len() != scenes.len() || names.iter().zip(scenes).any(|(n, s)| *n != s.0) {
        return Err(format!("{}: its scenes differ from the legend's", t.name));
    }
    Ok(names
        .iter()
        .map(|n| {
            (0..t.len())
                .filter(|&k| scene[k] == *n)
                .map(|k| (a[k], b[k]))
                .collect()
        })
        .collect())
}

/// Tip speed against time, one line per scene.
pub struct TipSpeed {
    pub title: &'static str,
    pub scenes: &'static [&'static str],
}

impl Make for TipSpeed {
    fn scenes(&self) -> Vec<&'static str> {
        self.scenes.to_vec()
    }

    /// `<id>.csv`: `scene,t,tip_speed` at every sample (32 per snapshot
    /// spacing), and `<id>-scenes.csv` (the continuous maxima).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        tip_tables(ctx, fig, self.scenes, report::tip_speed)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes = read_scenes(ctx, fig)?;
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let lines = per_scene(&t, &scenes, "t", "tip_speed")?;
        let title = title(fig, self.title);
        let mut p = LinePlot::new(&title, "t", "tip speed |v|");
        for (s, pts) in scenes.iter().zip(lines) {
            p.series.push(Series::line(s.1.clone(), pts));
        }
        // The continuous maxima, located between steps.
        p.series.push(
            Series::new(
                "maximum (continuous)",
                scenes.iter().map(|s| s.2).collect(),
                Style::Points,
            )
            .with_color(figures::RGBColor(0, 0, 0)),
        );
        drawn(ctx, fig, figures::line_plot(&p, &ctx.stem(fig.id)))
    }
}

/// Tip velocity `v_y` against `v_x`, one line per scene.
pub struct TipVelocity {
    pub title: &'static str,
    pub scenes: &'static [&'static str],
}

impl Make for TipVelocity {
    fn scenes(&self) -> Vec<&'static str> {
        self.scenes.to_vec()
    }

    /// `<id>.csv`: `scene,v_x,v_y` at every sample, and `<id>-scenes.csv`.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        tip_tables(ctx, fig, self.scenes, report::tip_velocity)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes = read_scenes(ctx, fig)?;
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let lines = per_scene(&t, &scenes, "v_x", "v_y")?;
        let title = title(fig, self.title);
        let mut p = LinePlot::new(&title, "v_x", "v_y");
        p.equal_aspect = true;
        for (s, pts) in scenes.iter().zip(lines) {
            p.series.push(Series::line(s.1.clone(), pts));
        }
        drawn(ctx, fig, figures::line_plot(&p, &ctx.stem(fig.id)))
    }
}

/// Maximum tip speed against the span d: the report's spans as points and a
/// dense sweep as a line (catenary starts), plus the stretched d = L.
pub struct VmaxVsSpan {
    pub title: &'static str,
    /// The scene the spans are varied from.
    pub scene: &'static str,
    /// The stretched scene (d = L).
    pub stretched: &'static str,
    /// The report's spans.
    pub report_spans: LinspaceSlice,
    /// `linspace(a, b, n)`.
    pub dense: (f64, f64, usize),
    /// The refined curve: `(links, linspace(a, b, count))`, the continuum
    /// held fixed as `falling-chain converge` holds it (`m = M/n`,
    /// `r = eta n / L`), method `auto` at rtol 1e-8.
    pub refined: (usize, f64, f64, usize),
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

impl Make for VmaxVsSpan {
    fn scenes(&self) -> Vec<&'static str> {
        vec![self.scene, self.stretched]
    }

    /// `<id>.csv`: `set,d,tip_speed_max,t_tip_speed_max,status` for the
    /// sets `report` (this model at the report's 14 spans, n = 50), `dense`
    /// (n = 50), `stretched` (n = 50, d = L), `n200` and `stretched-n200`
    /// (the refined chain), and `switch-before` / `switch-after` (and
    /// `-n200`): the two neighbouring spans of the dense curve between
    /// which the time of the maximum jumps (the whip switch).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let r = self.report_spans;
        let (links, a, b, count) = self.refined;
        let spans = report::Spans {
            report: report::linspace(r.start, r.stop, r.num)[r.from..r.to].to_vec(),
            dense: report::linspace(self.dense.0, self.dense.1, self.dense.2),
            refined: (links, report::linspace(a, b, count)),
        };
        let stretched = ctx.run(self.stretched)?;
        let csv = report::vmax_vs_span(
            &ctx.run(self.scene)?.scene,
            (&stretched.scene, &stretched.as_run()),
            &spans,
            ctx.jobs,
        )?;
        Ok(vec![ctx.write(&format!("{}.csv", fig.id), &csv)?])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let (set, d, v, status) = (
            t.strs("set")?,
            t.nums("d")?,
            t.nums("tip_speed_max")?,
            t.strs("status")?,
        );
        let ok = |which: &str| -> Vec<(f64, f64)> {
            (0..t.len())
                .filter(|&k| set[k] == which && status[k] == "ok")
                .map(|k| (d[k], v[k]))
                .collect()
        };
        let dense_count = set.iter().filter(|s| **s == "dense").count();
        let (links, ..) = self.refined;
        let fine = format!("n{links}");
        let fine_count = set.iter().filter(|s| **s == fine).count();
        let title = title(fig, self.title);
        let mut p = LinePlot::new(&title, "span d", "maximum tip speed");
        p.x_tick_step = Some(0.5);
        p.series.push(Series::line(
            format!("n = 50: {dense_count} spans (DOPRI5, rtol 1e-8)"),
            ok("dense"),
        ));
        p.series.push(Series::new(
            format!("n = {links}, continuum fixed: {fine_count} spans (auto, rtol 1e-8)"),
            ok(&fine),
            Style::LinePoints,
        ));
        p.series.push(Series::points(
            "this model at the report's 14 spans (n = 50)",
            ok("report"),
        ));
        let mut full = ok("stretched");
        full.extend(ok(&format!("stretched-{fine}")));
        p.series
            .push(Series::points("stretched, d = L (n = 50, n = 200)", full));
        // The whip switch of the n = 50 curve: a dashed line between the two
        // spans where the time of the maximum jumps.
        let before = ok("switch-before");
        let after = ok("switch-after");
        if let (Some(a), Some(b)) = (before.first(), after.first()) {
            let (lo, hi) = v
                .iter()
                .copied()
                .filter(|x| x.is_finite())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
                    (l.min(x), h.max(x))
                });
            let at = 0.5 * (a.0 + b.0);
            let times = |k: &str| {
                (0..t.len())
                    .find(|&i| set[i] == k)
                    .map(|i| t.nums("t_tip_speed_max").map(|c| c[i]))
            };
            let (ta, tb) = match (times("switch-before"), times("switch-after")) {
                (Some(a), Some(b)) => (a?, b?),
                _ => (f64::NAN, f64::NAN),
            };
            p.series.push(
                Series::new(
                    format!("whip switch, d = {at:.2}: t of max {ta:.2} -> {tb:.2}"),
                    vec![(at, lo), (at, hi)],
                    Style::Dashed,
                )
                .with_color(figures::RGBColor(90, 90, 90)),
            );
        }
        drawn(ctx, fig, figures::line_plot(&p, &ctx.stem(fig.id)))
    }
}
