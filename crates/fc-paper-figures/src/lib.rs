//! The study modules that only the paper's figures use: `cargo xtask
//! figures` (xtask) chooses the scenes and calls these, and nothing else
//! does. Each computes the rows of one or more of the paper's tables
//! (`figures/data/*.csv`: the accuracy of the methods, BEAM's
//! work-precision, the convergence in n, the folded chain, friction, the
//! report's scenes and model, the stiffness crossovers, the timing tables,
//! the tip mass, the tapered whip, Cayley's scale, the viewer's peak, ...), with the
//! drawings of those tables in [`plot`].
//!
//! It builds on the studies of any scene (fc-study, with its drawings),
//! fc-batch, fc-viewer and fc-scene; neither the CLI nor Python depends on
//! it.
//!
//! Its files:
//! * `accuracy.rs`: Is a scene's run converged? The table behind `report-scenes-accuracy`: each scene run at its own settings and by RK4 at a ladder of steps ...
//! * `beam.rs`: BEAM, the study's one external benchmark (`chain_ode::beam`: the IVP test set's stiff beam of 40 segments on `[0, 5]`): every method over a range of its accuracy parameter ...
//! * `cayley.rs`: Cayley's scale as an ensemble: the chain of `scenes/cayley-scale.toml` (hanging straight down, its lower end on the floor ...
//! * `convergence.rs`: Convergence in the number of rods, as a table: each level of a ladder (`converge::run_level`, the continuum held fixed) with its deviation from the finest ...
//! * `divergence.rs`: When two runs of a scene separate: two DOPRI5 runs at the reference tolerance, one from angles perturbed by `PERTURBATION` ...
//! * `floor_checks.rs`: Two of the floor's closed forms as a figure (`floor-checks`), each run through chain-ode's elastic model (`docs/model.md`, "The floor"):
//! * `floor_u.rs`: The report's U onto a floor (`scenes/span-d3-floor.toml`): the chain at a few times with the floor's line ...
//! * `folded.rs`: The folded chain with r = 0 against the energy-conserving law (Calkin & March 1989): its fall against the law's speed and times, the force on the pivot ...
//! * `force_precision.rs`: `force-precision`: the work-precision of the snap's forces beside the tip's (issue 49): every method's largest pivot force and joint tension across rtol on the steel rope cut short ...
//! * `friction.rs`: How much the maximum tip speed depends on the joint friction `r`: each scene over a range of `r` bracketing its own, at its own `n` (the report's convention ...
//! * `layout_order.rs`: `elastic-layout-order`: how the elastic chain converges to the continuum rope as `n` grows at fixed `EA` and mass per length (`docs/model.md`, "Where the compliance sits").
//! * `machine.rs`: The machine wall times are measured on: `figures/data/machine-timing.csv` (one row: the date, whether a virtual or physical machine, the CPU, its cores, the memory ...
//! * `matched.rs`: Speed-ups at matched accuracy, from work-precision tables: a method's wall time at an error level ...
//! * `plan.rs`: Work-precision lines whose points are chosen by their cost, and so by wall times, made reproducible: a timed study records its decision, the plan ...
//! * `plot/`: The drawings of the paper's own tables, one module per study module, each reading its tables through a `Reader`, and the paper's work-precision figure (`wp_figure`).
//! * `report.rs`: The tables of the report's figures (fig02 to fig12).
//! * `report_model.rs`: The tables of the report's own model as a control (`model.report = true`, `docs/model.md`, "The report's model"): its Figs. 3, 4 ...
//! * `report_model_tip.rs`: The report's Figs. 8 and 11 in its own model (`model.report = true`, `docs/model.md`, "The report's model") ...
//! * `rhs_cost.rs`: `rhs-cost`: the cost of one right-hand side against n, the O(n) recursion (a whole `ChainSystem::rhs`) against the dense reference (assemble `A` and `b`, faer's Cholesky) ...
//! * `rigid_order.rs`: An independent check of the dynamics: the elastic chain (maximal coordinates, joints as stiff damped springs, `chain_ode::elastic`) and the rigid chain (minimal coordinates ...
//! * `scene_run.rs`: A scene run as the report's figures take it: sampled `FINE` times finer than the scene's own `output_dt` (so that speed curves are smooth; snapshots keep the scene's spacing) ...
//! * `snap_precision.rs`: `snap-precision` and `snap-damping`: the work-precision of the folded elastic snap across the axial stiffness (5% damping) and across the damping (at `EA = 1e7`) ...
//! * `snap_sweep.rs`: The snap against `n`: `snap::measure` of a few scenes, each refined at fixed total mass and bending viscosity (`converge::refined_scene` ...
//! * `snap_tension.rs`: The tables of the snap's tension wave (`snap-tension`, drawn by `super::plot::elastic::snap_tension`) from one measured run of `fc_study::snap::measure` ...
//! * `span_check.rs`: Fig. 9's claims, each from runs: where the 50-rod curve of the maximum tip speed against the span agrees with the refined chain's within `AGREEMENT` (the 50-rod chain run at the ...
//! * `stiffness.rs`: `stiffness`: where the implicit method pays, at matched accuracy.
//! * `tip_mass.rs`: The folded chain with a point mass at its free end against the energy-conserving law (`chain_ode::tip_mass_law`, derived in `docs/model.md`, "A tip mass") ...
//! * `validation.rs`: Tables that check the model against physics: the energy budget of runs (`E + W` conserved ...
//! * `viewer_peak.rs`: The tables of the `viewer-peak` figure (a screenshot of `falling-chain view`'s page at a run's peak tip speed) and the page's run read back from them.
//! * `whip_taper.rs`: The tapered whip: the largest tip speed of the chain released from the U of span d = 3 against the taper of its mass per length (`chain.taper`, base to tip) ...
//!
//! `cayley_single.rs`: one run's reading of Cayley's scale on the
//! constraint floor.

pub mod accuracy;
pub mod beam;
pub mod cayley;
pub mod cayley_single;
pub mod convergence;
pub mod divergence;
pub mod floor_checks;
pub mod floor_u;
pub mod folded;
pub mod force_precision;
pub mod friction;
pub mod layout_order;
pub mod machine;
pub mod matched;
pub mod plan;
pub mod plot;
pub mod report;
pub mod report_model;
pub mod report_model_tip;
pub mod rhs_cost;
pub mod rigid_order;
pub mod scene_run;
pub mod snap_precision;
pub mod snap_sweep;
pub mod snap_tension;
pub mod span_check;
pub mod stiffness;
pub mod tip_mass;
pub mod validation;
pub mod viewer_peak;
pub mod whip_taper;

/// The methods the paper's work-precision, stability and BEAM figures
/// compare, in their order: every method but `gen-alpha`, whose figures
/// are the elastic snap's (`precision` on that scene with every method).
/// A figure's tables keep their rows when a method is added to the
/// registry; a new method joins a figure by joining this list.
pub const PAPER_METHODS: [chain_ode::Method; 6] = [
    chain_ode::Method::Rk4,
    chain_ode::Method::Dopri5,
    chain_ode::Method::Dop853,
    chain_ode::Method::Bdf,
    chain_ode::Method::BdfDense,
    chain_ode::Method::Auto,
];
