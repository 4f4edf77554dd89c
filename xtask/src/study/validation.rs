//! Validation against physics: convergence in n, the folded chain against
//! its analytic law, the energy budget, normal modes and the support force.

#[path = "validation_convergence.rs"]
mod convergence;
#[path = "validation_energy.rs"]
mod energy;
#[path = "validation_folded.rs"]
mod folded;
#[path = "validation_modes.rs"]
mod modes;

use std::fs;

use falling_chain::Scene;

use super::{Ctx, Study};

pub const STUDIES: &[Study] = &[
    Study {
        id: "convergence-n",
        what: "max tip speed and tip path vs n (25 .. 800) for the span scenes at fixed total \
               mass and bending viscosity: the n each scene needs for 1% and 0.1%",
        make: convergence::make,
    },
    Study {
        id: "folded-vs-analytic",
        what: "folded chain, r = 0, n = 50 .. 400: tip speed vs fall distance against \
               v^2 = g x (2L - x)/(L - x) and free fall; times to L/2 and 0.9 L against the law",
        make: folded::make_folded,
    },
    Study {
        id: "energy-budget",
        what: "E(t), the dissipated work W(t) and E + W for r = 0 and r > 0 (span d = 3)",
        make: energy::make,
    },
    Study {
        id: "normal-modes",
        what: "lowest five frequencies of the linearised hanging chain vs n against \
               (j_0k / 2) sqrt(g/L), with the fitted convergence order",
        make: modes::make,
    },
    Study {
        id: "support-force",
        what: "force on the pivot P0 in units of M g during the fall: folded (r = 0) against \
               the law (M g / 4)(2 + 2 xi - 3 xi^2)/(1 - xi), and the span d = 3 scene",
        make: folded::make_support,
    },
];

/// A scene file of `scenes/`.
fn scene(ctx: &Ctx, name: &str) -> Result<Scene, String> {
    Scene::load(ctx.root.join("scenes").join(format!("{name}.toml"))).map_err(|e| e.to_string())
}

/// Writes `figures/data/<file>` and returns its path relative to the root.
fn write_data(ctx: &Ctx, file: &str, text: &str) -> Result<String, String> {
    fs::create_dir_all(&ctx.data).map_err(|e| e.to_string())?;
    fs::write(ctx.data.join(file), text).map_err(|e| format!("figures/data/{file}: {e}"))?;
    Ok(format!("figures/data/{file}"))
}

/// The figure files of `id`, relative to the root.
fn figure_files(id: &str) -> [String; 2] {
    [format!("figures/{id}.png"), format!("figures/{id}.svg")]
}

/// `figures/<id>` (the stem the figures crate appends `.png`, `.svg` to).
fn stem(ctx: &Ctx, id: &str) -> std::path::PathBuf {
    ctx.out.join(id)
}

/// A worker pool of `ctx.jobs` threads.
fn pool(ctx: &Ctx) -> Result<rayon::ThreadPool, String> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(ctx.jobs.max(1))
        .build()
        .map_err(|e| e.to_string())
}

/// A CSV cell of a float: full precision, deterministic.
fn num(x: f64) -> String {
    x.to_string()
}

/// A CSV cell of a float of order one with six decimals, for long
/// per-sample tables (deterministic).
fn short(x: f64) -> String {
    format!("{x:.6}")
}
