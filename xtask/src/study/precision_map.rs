//! `stability-map`: where each method fails. Every method at every step or
//! tolerance on five scenes, each run to its end under a step budget, sorted
//! into completed / completed with an energy-balance error above 1% of
//! `M g L` / stopped with a status. One panel per method (so that a panel's
//! columns are all steps or all tolerances), one row per scene.
//!
//! The runs are untimed and run in parallel: `stability-map.csv` holds no
//! wall time; with `--timings` each run's wall time (measured beside
//! another run) goes to `stability-map-timing.csv`.

use chain_ode::Method;
use falling_chain::study::plot;
use falling_chain::study::stability::{self, Row};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// One row of every panel.
struct MapScene {
    /// Its name in the CSV.
    key: &'static str,
    /// Row label.
    label: &'static str,
    scene: &'static str,
    overrides: &'static [&'static str],
    /// Runs not made, with the reason: (method, tolerances below which).
    skip: Option<(&'static [Method], f64, &'static str)>,
}

const SCENES: [MapScene; 5] = [
    MapScene {
        key: "span-d3",
        label: "span d = 3 (n 50)",
        scene: "span-d3",
        overrides: &[],
        skip: None,
    },
    MapScene {
        key: "folded",
        label: "folded (r = 1e-3)",
        scene: "folded",
        overrides: &[],
        skip: None,
    },
    MapScene {
        key: "folded-r0",
        label: "folded, r = 0",
        scene: "folded",
        overrides: &["chain.damping=0"],
        skip: None,
    },
    MapScene {
        key: "many-rods-n400",
        label: "n = 400 (d = 3)",
        scene: "span-d3",
        overrides: &["chain.links=400", "chain.damping=5e-4"],
        // bdf-dense: 2.5 s per run at rtol 1e-2, 7 s at 1e-3, 11 s at 1e-4
        // (measured on two shared cores): dense 801 x 801 Jacobians and LU.
        skip: Some((
            &[Method::BdfDense],
            1e-3,
            "cost: bdf-dense at n = 400 takes 2.5 to 11 s per run (dense 801 x 801 Jacobian and LU)",
        )),
    },
    MapScene {
        key: "stiff-rope",
        label: "stiff rope (n 100, r 1)",
        scene: "stiff-rope",
        overrides: &[],
        skip: None,
    },
];

pub struct StabilityMap;

impl Make for StabilityMap {
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let rows: Vec<Row> = SCENES
            .iter()
            .map(|s| {
                Ok(Row {
                    key: s.key.into(),
                    label: s.label.into(),
                    prepared: ctx.prepare(s.scene, s.overrides)?,
                })
            })
            .collect::<Result<_, String>>()?;
        let jobs = stability::jobs(rows.len(), &Method::ALL);
        let skip = |row: usize, method: Method, param: f64| {
            SCENES[row]
                .skip
                .filter(|(ms, below, _)| ms.contains(&method) && param < *below)
                .map(|(_, _, why)| why.to_string())
        };
        // Untimed runs: in parallel, at most `ctx.jobs` at once (the order
        // of `jobs` is kept).
        let cells = ctx
            .pool()?
            .install(|| stability::run_cells(&rows, &jobs, &|_| true, &skip, None, &|| {}));
        let csv = stability::csv_text(&rows, &cells, None);
        let mut files = vec![ctx.write(&format!("{}.csv", fig.id), &csv)?];
        if ctx.timings {
            let timing = stability::timing_text(&rows, &cells);
            files.push(ctx.write(&format!("{}-timing.csv", fig.id), &timing)?);
        }
        Ok(files)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let t = ctx.read(&format!("{}.csv", fig.id))?;
        let title = "Where each method fails (each scene run to its end, step budget 2e5)";
        let map = plot::stability_map(&t, title)?;
        let out = figures::category_map(&map, &ctx.stem(fig.id)).map_err(|e| e.to_string())?;
        Ok(ctx.drawn(&out))
    }
}
