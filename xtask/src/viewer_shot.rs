//! `viewer-peak`: a screenshot of `falling-chain view`'s page for the folded
//! chain, at the instant of its peak tip speed, for the README.
//!
//! `compute` runs `scenes/folded.toml` (samples 0.02 apart) and writes its
//! trajectory as `simulate --out` does (`viewer-peak.csv`) and the summary
//! fields the page shows (`viewer-peak-summary.csv`: `key,value`, values as
//! JSON; no wall time, so the data reproduce to the byte). `draw` builds the
//! page from those files (the trajectory read back as `view --from` does),
//! opens it in headless Chromium, moves it to `t_tip_speed_max` and saves
//! the viewport as `figures/viewer-peak.png`. Chromium's rendering of one
//! page is the same bytes from launch to launch with one Chromium build and
//! its fonts, so an unchanged checkout stays `git status` clean on the
//! machine that drew it; another Chromium build may shift anti-aliased
//! pixels, a diff to review like any figure's. Without Chromium the figure
//! is skipped with a line saying so, the committed PNG is kept and the rest
//! of the run goes on.

use fc_paper_figures::viewer_peak;
use fc_viewer as viewer;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The page's size in CSS pixels: the chain, the curves and the table.
const SIZE: (u32, u32) = (1180, 700);

pub struct ViewerPeak;

impl Make for ViewerPeak {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scene = ctx.scene("folded", &["run.output_dt=0.02"])?;
        let traj = scene
            .prepare()
            .and_then(|p| p.solve())
            .map_err(|e| e.to_string())?;
        let (csv, shown) = viewer_peak::tables(scene.name(), &traj)?;
        Ok(vec![
            ctx.write(fig.data[0], &csv)?,
            ctx.write(fig.data[1], &shown)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let Some(chromium) = browser::find() else {
            println!(
                "{}: skipped, no chromium on PATH (apt-get install chromium); \
                 figures/{}.png kept as committed",
                fig.id, fig.id
            );
            return Ok(Vec::new());
        };
        let summary = ctx.read(fig.data[1])?;
        let (run, peak) = viewer_peak::view_run(&ctx.data.join(fig.data[0]), &summary, "folded")?;
        let page = viewer::page("folded chain, n = 50, at its peak tip speed", &[run]);
        let script = format!("fallingChain.seekTime({peak}); 0");
        let shot = browser::screenshot_page(&chromium, fig.id, &page, SIZE, &script)?;
        let png = ctx.out.join(format!("{}.png", fig.id));
        fc_scene::atomic::write_atomic("figure", &png, |w| w.write_all(&shot))
            .map_err(|e| e.to_string())?;
        Ok(vec![ctx.relative(&png)])
    }
}
