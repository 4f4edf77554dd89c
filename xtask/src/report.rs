//! The kinds of the report's figures (fig01 .. fig12). Each kind is a
//! [`Make`] with its parameters, so a figure of the report is one entry of
//! the registry, never a copy of code: `compute` takes the shared scene
//! runs to `figures/data/<id>*.csv`, `draw` draws from those files.

use fc_paper_figures::plot;
use fc_paper_figures::report::{self, SpanParams};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};
use crate::runs::SceneRun;

fn title(fig: &Figure, title: &str) -> String {
    format!("{}: {title}", fig.label())
}

/// The schematic of the problem (no data).
pub struct Sketch;

impl Make for Sketch {
    fn compute(&self, _: &Ctx, _: &Figure) -> Result<Vec<String>, String> {
        Ok(vec![])
    }
    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, |_, stem| {
            figures::sketch(stem).map_err(|e| e.to_string())
        })
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
        ctx.draw(fig, |r, s| {
            plot::report::catenaries(r, s, &title(fig, self.title))
        })
    }
}

/// Chain snapshots of one scene, coloured by time.
pub struct Snapshots {
    pub title: &'static str,
    pub scene: &'static str,
    /// Draw every `every`-th snapshot (1: all) and always the last, so that
    /// the snapshots of a narrow chain stay apart.
    pub every: usize,
    /// Offset panels: the k-th frame drawn moved right by `k shift` (0:
    /// the frames drawn over each other).
    pub shift: f64,
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
        ctx.draw(fig, |r, s| {
            plot::report::snapshots(
                r,
                s,
                &title(fig, self.title),
                self.every,
                self.shift,
                self.p1_label,
            )
        })
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

/// The tip velocity's runs are sampled this many times finer than their
/// snapshots (the shared runs: 32): at span d = 1 the whip's loop turns
/// through its largest speed between samples 0.0025 apart.
const VELOCITY_FINE: f64 = 256.0;

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
        ctx.draw(fig, |r, s| {
            plot::report::tip_speed(r, s, &title(fig, self.title))
        })
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

    /// `<id>.csv`: `scene,v_x,v_y` along each scene run again sampled
    /// [`VELOCITY_FINE`] times finer than its snapshots (the loops turn
    /// fast in the whip), thinned by `report::tip_velocity`; and
    /// `<id>-scenes.csv`.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let dense = self
            .scenes
            .iter()
            .map(|s| SceneRun::run_sampled(ctx.run(s)?.scene.clone(), VELOCITY_FINE))
            .collect::<Result<Vec<_>, String>>()?;
        let runs: Vec<_> = dense.iter().map(SceneRun::as_run).collect();
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &report::tip_velocity(&runs))?,
            ctx.write(&format!("{}-scenes.csv", fig.id), &report::scenes(&runs))?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, |r, s| {
            plot::report::tip_velocity(r, s, &title(fig, self.title))
        })
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
    pub spans: SpanParams,
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
    /// which the time of the maximum jumps (the whip switch); `-agreement`
    /// and `-peak` ([`report::vmax_tables`]).
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let stretched = ctx.run(self.stretched)?;
        let stretched = (&stretched.scene, &stretched.as_run());
        let base = &ctx.run(self.scene)?.scene;
        let tables = report::vmax_tables(base, stretched, &self.spans, ctx.jobs)?;
        ctx.write_tables(fig.id, &tables)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let title = title(fig, self.title);
        ctx.draw(fig, |r, s| {
            plot::report::vmax_vs_span(r, s, &title, self.spans.refined.0)
        })
    }
}
