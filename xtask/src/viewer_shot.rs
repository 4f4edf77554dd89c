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

use falling_chain::viewer::{self, DATA_BUDGET_BYTES};
use falling_chain::RunSummary;
use serde_json::Value;

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// The summary fields the page's table shows.
const SHOWN: [&str; 10] = [
    "status",
    "method",
    "links",
    "steps",
    "tip_speed_max",
    "t_tip_speed_max",
    "t_reached",
    "t_failed",
    "tip_end",
    "energy_balance_error",
];

/// The page's size in CSS pixels: the chain, the curves and the table.
const SIZE: (u32, u32) = (1180, 700);

pub struct ViewerPeak;

impl Make for ViewerPeak {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scene = ctx.scene("folded", &["run.output_dt=0.02"])?;
        let run = scene.prepare().map_err(|e| e.to_string())?;
        let traj = run.solve().map_err(|e| e.to_string())?;
        let mut csv = Vec::new();
        falling_chain::csv::write_trajectory(&mut csv, &traj).map_err(|e| e.to_string())?;
        let csv = String::from_utf8(csv).map_err(|e| e.to_string())?;
        let summary = serde_json::to_value(RunSummary::from_trajectory(scene.name(), &traj))
            .map_err(|e| e.to_string())?;
        let mut shown = String::from("key,value\n");
        for key in SHOWN {
            // A point is two rows, `<key>_x` and `<key>_y`: no commas in cells.
            match &summary[key] {
                Value::Array(xy) => {
                    for (axis, v) in ["x", "y"].iter().zip(xy) {
                        shown.push_str(&format!("{key}_{axis},{v}\n"));
                    }
                }
                v => shown.push_str(&format!("{key},{v}\n")),
            }
        }
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
        let mut run =
            falling_chain::run_csv::read_run_csv(&ctx.data.join(fig.data[0]), DATA_BUDGET_BYTES)
                .map_err(|e| e.to_string())?;
        let table = ctx.read(fig.data[1])?;
        let mut summary = serde_json::Map::new();
        for (key, value) in table.strs("key")?.iter().zip(table.strs("value")?) {
            let value: Value = serde_json::from_str(value).map_err(|e| format!("{key}: {e}"))?;
            summary.insert((*key).to_string(), value);
        }
        for key in SHOWN {
            if let (Some(x), Some(y)) = (
                summary.remove(&format!("{key}_x")),
                summary.remove(&format!("{key}_y")),
            ) {
                summary.insert(key.to_string(), Value::Array(vec![x, y]));
            }
        }
        let peak = summary["t_tip_speed_max"]
            .as_f64()
            .ok_or("no t_tip_speed_max")?;
        run.label = "folded".into();
        run.status = summary["status"].as_str().unwrap_or("ok").to_string();
        run.t_failed = summary["t_failed"].as_f64();
        run.summary = Value::Object(summary);
        run.source = None;
        let page = viewer::page("folded chain, n = 50, at its peak tip speed", &[run]);
        let scratch =
            std::env::temp_dir().join(format!("falling-chain-{}-{}", fig.id, std::process::id()));
        std::fs::create_dir_all(&scratch).map_err(|e| e.to_string())?;
        let html = scratch.join("page.html");
        std::fs::write(&html, page).map_err(|e| e.to_string())?;
        let shot = (|| {
            let mut b = browser::Browser::launch(&chromium, &scratch, SIZE.0, SIZE.1)?;
            b.open(&html)?;
            b.eval(&format!("fallingChain.seekTime({peak}); 0"))?;
            let errors = b.errors();
            if !errors.is_empty() {
                return Err(format!("the page logged errors: {errors:?}"));
            }
            b.screenshot()
        })();
        let _ = std::fs::remove_dir_all(&scratch);
        let shot = shot?;
        let png = ctx.out.join(format!("{}.png", fig.id));
        falling_chain::atomic::write_atomic("figure", &png, |w| w.write_all(&shot))
            .map_err(|e| e.to_string())?;
        Ok(vec![ctx.relative(&png)])
    }
}
