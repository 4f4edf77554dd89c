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
use fc_paper_figures::plot;
use fc_study::stability::{self, Row, Skip};

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
    /// Runs not made, with the reason.
    skip: Option<Skip>,
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
        skip: Some(Skip {
            methods: &[Method::BdfDense],
            below: 1e-3,
            why: "cost: bdf-dense at n = 400 takes 2.5 to 11 s per run (dense 801 x 801 Jacobian and LU)",
        }),
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
        let skips: Vec<Option<Skip>> = SCENES.iter().map(|s| s.skip).collect();
        // Untimed runs: in parallel, at most `ctx.jobs` at once (their order
        // kept).
        let tables = ctx.pool()?.install(|| {
            stability::map_tables(&rows, &fc_paper_figures::PAPER_METHODS, &skips, ctx.timings)
        });
        ctx.write_tables(fig.id, &tables)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let title = "Where each method fails (each scene run to its end, step budget 2e5)";
        ctx.draw(fig, |r, s| plot::stability_figure(r, s, title))
    }
}
