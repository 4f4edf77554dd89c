//! Every figure, one entry each: the one place to add a figure.
//!
//! An entry names the figure (`figures/<id>.png` and `.svg`), says in one
//! line what it shows (for `figures/README.md`), lists the data files it
//! writes in `figures/data/`, and gives a [`Make`]: `compute` runs what it
//! needs and writes those files, `draw` reads only those files and draws.
//! So `cargo xtask figures --draw-only` redraws every figure from the
//! committed data, and `cargo xtask figures` is `compute` then `draw`.

use crate::ctx::Ctx;
use crate::report::{Catenaries, Sketch, Snapshots, TipSpeed, TipVelocity, VmaxVsSpan};
use crate::report_model::{ReportSnapshots, ReportTip, ReportVmax};
use crate::study;
use fc_paper_figures::report::{LinspaceSlice, SpanParams};
use paper::catalogue::Entry;

/// How a figure makes its data and draws itself.
pub trait Make: Sync {
    /// The scene files of `scenes/` it runs through the shared scene runs
    /// ([`Ctx::run`]), made once before any figure is computed.
    fn scenes(&self) -> Vec<&'static str> {
        Vec::new()
    }
    /// The scene animated to `figures/anim/<scene>.gif` beside the figure,
    /// if any (animations are made from the runs, not from data).
    fn animation(&self) -> Option<&'static str> {
        None
    }
    /// Runs what the figure needs and writes its data files; returns the
    /// files written (relative to the workspace root). Without `--timings`
    /// it writes no timing file.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String>;
    /// Draws `figures/<id>.png` and `.svg` from the figure's data files
    /// only; returns the files written.
    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String>;
}

/// Whether a figure measures wall times (`None`, `Alongside`, `Only`).
pub use paper::catalogue::Timing;

/// One figure.
pub struct Figure {
    pub id: &'static str,
    /// The report's figure it reproduces (`Fig. 7a`), if any.
    pub report: Option<&'static str>,
    /// One line: what it shows.
    pub what: &'static str,
    /// Its data files in `figures/data/` (timing files end in `-timing.csv`).
    pub data: &'static [&'static str],
    pub timing: Timing,
    pub make: &'static dyn Make,
}

impl Figure {
    /// The title prefix: `Fig. 7a` for a report figure, else the id.
    pub fn label(&self) -> &'static str {
        self.report.unwrap_or(self.id)
    }

    /// The figure as the catalogue lists it.
    pub fn entry(&self) -> Entry<'static> {
        Entry {
            id: self.id,
            report: self.report,
            what: self.what,
            scenes: self.make.scenes(),
            data: self.data,
            timing: self.timing,
        }
    }
}

const SPANS: &[&str] = &["span-d1", "span-d3", "span-d5", "span-d6"];
const HEIGHTS: &[&str] = &["height-hm2", "height-h0", "height-h2", "height-h4"];

/// A report figure of chain snapshots of one scene.
macro_rules! snapshots {
    ($id:literal, $report:literal, $title:literal, $what:literal, $scene:literal) => {
        Figure {
            id: $id,
            report: Some($report),
            what: $what,
            data: &[concat!($id, ".csv")],
            timing: Timing::None,
            make: &Snapshots {
                title: $title,
                scene: $scene,
                every: 1,
                shift: 0.0,
                p1_label: None,
            },
        }
    };
}

/// A report figure's scene run in the report's own model.
macro_rules! report_model {
    ($id:literal, $title:literal, $what:literal, $scene:literal, $t:literal) => {
        Figure {
            id: $id,
            report: None,
            what: $what,
            data: &[concat!($id, ".csv")],
            timing: Timing::None,
            make: &ReportSnapshots {
                title: $title,
                scene: $scene,
                t_report: $t,
            },
        }
    };
}

/// Every figure: the report's (fig01 .. fig12, `docs/figures.md`), then the
/// study's, in the order of `docs/figures.md`.
pub static FIGURES: &[Figure] = &[
    Figure {
        id: "fig01-sketch",
        report: Some("Fig. 1"),
        what: "schematic: P0, P1, L, d, h, g, the released end",
        data: &[],
        timing: Timing::None,
        make: &Sketch,
    },
    Figure {
        id: "fig02-catenaries",
        report: Some("Fig. 2"),
        what: "continuous catenaries from P0 (0,0) to P1 (5,1), L = 6 .. 12, coloured by L, lowest points marked",
        data: &["fig02-catenaries.csv"],
        timing: Timing::None,
        make: &Catenaries {
            title: "catenaries from (0,0) to (5,1)",
            p1: [5.0, 1.0],
            lengths: (6.0, 12.0, 13),
        },
    },
    snapshots!("fig03-horizontal-undamped", "Fig. 3", "horizontal start, n = 25, r = 0", "n = 25 stretched horizontal chain, r = 0, t = 4.899", "horizontal-undamped"),
    snapshots!("fig04-horizontal-damped", "Fig. 4", "horizontal start, n = 25, r = 0.001", "n = 25 stretched horizontal chain, r = 0.001, t = 4.899", "horizontal-damped"),
    snapshots!("fig05-horizontal-settling", "Fig. 5", "horizontal start, r = 0.001, to t = 19.6", "as fig04 to t = 19.60: at this r the chain does not settle (the report's did)", "horizontal-settling"),
    snapshots!("fig05b-horizontal-settling-report-damping", "Fig. 5b", "as Fig. 5 at the report's effective damping r = 0.00204", "as fig05 at r = 0.001/sqrt(0.24) = 0.00204, the damping the report's code effectively used (erratum 3); DOPRI5, rtol 1e-8: still not settled at t = 19.60", "horizontal-settling-report-damping"),
    snapshots!("fig06-catenary-fall", "Fig. 6", "catenary to (5,1), n = 25, r = 0.001", "n = 25 discrete catenary to P1 (5,1), r = 0.001, t = 7.348", "catenary-fall"),
    snapshots!("fig07a-span-d1", "Fig. 7a", "span d = 1, n = 50", "n = 50, P1 = (1, 0), r = 0.0005, t = 4.157", "span-d1"),
    snapshots!("fig07b-span-d3", "Fig. 7b", "span d = 3, n = 50", "n = 50, P1 = (3, 0), r = 0.0005, t = 4.157", "span-d3"),
    snapshots!("fig07c-span-d5", "Fig. 7c", "span d = 5, n = 50", "n = 50, P1 = (5, 0), r = 0.0005, t = 4.157", "span-d5"),
    snapshots!("fig07d-span-d6", "Fig. 7d", "span d = 6 (stretched), n = 50", "n = 50, P1 = (6, 0) (stretched), r = 0.0005, t = 4.157", "span-d6"),
    Figure {
        id: "fig08a-span-tip-speed",
        report: Some("Fig. 8a"),
        what: "tip speed against time for the four spans d = 1, 3, 5, 6",
        data: &["fig08a-span-tip-speed.csv", "fig08a-span-tip-speed-scenes.csv"],
        timing: Timing::None,
        make: &TipSpeed {
            title: "tip speed, spans d = 1, 3, 5, 6",
            scenes: SPANS,
        },
    },
    Figure {
        id: "fig08b-span-tip-velocity",
        report: Some("Fig. 8b"),
        what: "tip velocity v_y against v_x for the four spans",
        data: &["fig08b-span-tip-velocity.csv", "fig08b-span-tip-velocity-scenes.csv"],
        timing: Timing::None,
        make: &TipVelocity {
            title: "tip velocity, spans d = 1, 3, 5, 6",
            scenes: SPANS,
        },
    },
    Figure {
        id: "fig09-vmax-vs-span",
        report: Some("Fig. 9"),
        what: "maximum tip speed against the span d (n = 50, r = 0.0005, t = 4.157): this model at the report's 14 spans, a dense sweep, the same at n = 200 with the continuum fixed, both whip switches, the spans where n = 50 is within 1% of n = 200, and the narrow-span peak at n = 200 and 400 on finer spans",
        data: &[
            "fig09-vmax-vs-span.csv",
            "fig09-vmax-vs-span-agreement.csv",
            "fig09-vmax-vs-span-peak.csv",
        ],
        timing: Timing::None,
        make: &VmaxVsSpan {
            title: "maximum tip speed against span d",
            scene: "span-d3",
            stretched: "span-d6",
            spans: SpanParams {
                report: LinspaceSlice {
                    start: 0.0,
                    stop: 6.0,
                    num: 20,
                    from: 5,
                    to: 19,
                },
                dense: (0.3, 5.97, 120),
                refined: (200, 0.25, 5.95, 39),
                peak: (&[200, 400], 0.1, 0.8, 15),
            },
        },
    },
    snapshots!("fig10a-height-hm2", "Fig. 10a", "P1 = (3, -2), n = 50", "n = 50, P1 = (3, -2), r = 0.0005, t = 5.196", "height-hm2"),
    snapshots!("fig10b-height-h0", "Fig. 10b", "P1 = (3, 0), n = 50: Fig. 7b's scene run on to t = 5.196", "n = 50, P1 = (3, 0), r = 0.0005, t = 5.196: the scene of fig07b (which stops at 4.157) run on to the report's t = 15, as the report's Fig. 10b is", "height-h0"),
    snapshots!("fig10c-height-h2", "Fig. 10c", "P1 = (3, 2), n = 50", "n = 50, P1 = (3, 2), r = 0.0005, t = 5.196", "height-h2"),
    snapshots!("fig10d-height-h4", "Fig. 10d", "P1 = (3, 4), n = 50", "n = 50, P1 = (3, 4), r = 0.0005, t = 5.196", "height-h4"),
    Figure {
        id: "fig11a-height-tip-speed",
        report: Some("Fig. 11a"),
        what: "tip speed against time for the four heights h = -2, 0, 2, 4",
        data: &["fig11a-height-tip-speed.csv", "fig11a-height-tip-speed-scenes.csv"],
        timing: Timing::None,
        make: &TipSpeed {
            title: "tip speed, heights h = -2, 0, 2, 4",
            scenes: HEIGHTS,
        },
    },
    Figure {
        id: "fig11b-height-tip-velocity",
        report: Some("Fig. 11b"),
        what: "tip velocity v_y against v_x for the four heights",
        data: &["fig11b-height-tip-velocity.csv", "fig11b-height-tip-velocity-scenes.csv"],
        timing: Timing::None,
        make: &TipVelocity {
            title: "tip velocity, heights h = -2, 0, 2, 4",
            scenes: HEIGHTS,
        },
    },
    Figure {
        id: "fig12-folded",
        report: Some("Fig. 12"),
        what: "n = 50 folded chain (25 down, 1 across, 24 up), r = 0.001, t = 4.157; a snapshot every 0.48, side by side",
        data: &["fig12-folded.csv"],
        timing: Timing::None,
        make: &Snapshots {
            title: "folded chain, n = 50, r = 0.001",
            scene: "folded",
            every: 6,
            shift: 0.6,
            p1_label: Some("free end at t = 0"),
        },
    },
    // The study's figures.
    Figure {
        id: "wp-span-d3",
        report: None,
        what: "work-precision of the span d = 3 scene: tip position and maximum tip speed error \
               vs wall time and vs RHS evaluations, RK4 over dt, the adaptive methods over rtol, \
               against a DOPRI5 rtol 1e-13 reference checked by RK4 and BDF",
        data: &["wp-span-d3.csv", "wp-span-d3-timing.csv", "wp-span-d3-cost-timing.csv"],
        timing: Timing::Alongside,
        make: &study::precision_wp::SPAN_D3,
    },
    Figure {
        id: "wp-folded",
        report: None,
        what: "work-precision of the folded scene (r = 0.001), evaluated at the last time before \
               two runs 1e-10 apart separate 1000-fold: its end, as they never do (its r = 0 \
               variant does after the whip; `data/wp-folded-divergence.csv`)",
        data: &["wp-folded.csv", "wp-folded-divergence.csv", "wp-folded-timing.csv", "wp-folded-cost-timing.csv"],
        timing: Timing::Alongside,
        make: &study::precision_wp::FOLDED,
    },
    Figure {
        id: "wp-stiff-rope",
        report: None,
        what: "work-precision of the stiff rope (n = 100, r = 1): explicit methods held at their \
               stability limit, BDF not",
        data: &["wp-stiff-rope.csv", "wp-stiff-rope-timing.csv", "wp-stiff-rope-cost-timing.csv"],
        timing: Timing::Alongside,
        make: &study::precision_wp::STIFF_ROPE,
    },
    Figure {
        id: "wp-matched",
        report: None,
        what: "speed-ups at matched accuracy, from the three work-precision diagrams: for \
               dop853/dopri5, bdf/dopri5, bdf/bdf-dense and explicit-best/bdf, each method's \
               wall time at errors 1e-4 .. 1e-12 (max(err_tip, err_vmax)), log-log \
               interpolated between its bracketing runs, and their ratio",
        data: &["wp-matched-timing.csv"],
        timing: Timing::Only,
        make: &study::precision_matched::MatchedTiming,
    },
    Figure {
        id: "stability-map",
        report: None,
        what: "where each method fails: method x dt / rtol x scene -> completed, energy-balance \
               error above 1% of M g L, diverged, step size too small, step budget exhausted",
        data: &["stability-map.csv", "stability-map-timing.csv"],
        timing: Timing::Alongside,
        make: &study::precision_map::StabilityMap,
    },
    Figure {
        id: "stiffness",
        report: None,
        what: "where BDF pays, at matched accuracy: DOPRI5's cost over the O(n) BDF's at the \
               same error (1e-6) against the damping rate gamma, a quarter decade apart, for \
               n = 25 to 1600 (span d = 3 to t = 3, past the whip), and the crossover gamma for \
               each n beside auto's rule",
        data: &["stiffness-timing.csv", "stiffness-crossover-timing.csv"],
        timing: Timing::Only,
        make: &study::precision_stiffness::Stiffness,
    },
    Figure {
        id: "rhs-cost",
        report: None,
        what: "cost of one right-hand side vs n: the O(n) recursion against the dense Cholesky \
               solve, measured slopes against n and n^3",
        data: &["rhs-cost-timing.csv", "rhs-cost-fit-timing.csv"],
        timing: Timing::Only,
        make: &study::precision_cost::RhsCost,
    },
    Figure {
        id: "convergence-n",
        report: None,
        what: "max tip speed and tip path vs n (25 .. 1600, and 3200 where the last doubling \
               still mattered) for the span scenes at fixed total mass and bending viscosity: \
               the n each scene needs for 1% and 0.1%",
        data: &["convergence-n.csv", "convergence-n-summary.csv"],
        timing: Timing::None,
        make: &study::validation_convergence::Convergence,
    },
    Figure {
        id: "folded-vs-analytic",
        report: None,
        what: "folded chain, r = 0, n = 50 .. 400: tip speed vs fall distance against \
               v^2 = g x (2L - x)/(L - x) and free fall; times to L/2 and 0.9 L against the law",
        data: &[
            "folded-vs-analytic.csv",
            "folded-vs-analytic-times.csv",
            "folded-vs-analytic-law.csv",
        ],
        timing: Timing::None,
        make: &study::validation_folded::FoldedVsAnalytic,
    },
    Figure {
        id: "folded-tip-acceleration",
        report: None,
        what: "why the tip beats g: the folded chain's (r = 0, n = 100 and 400) downward tip \
               acceleration against x/L, from the dynamics at each sample, against the law \
               a = g [1 + xi (2 - xi)/(2 (1 - xi)^2)] and free fall",
        data: &["folded-tip-acceleration.csv", "folded-tip-acceleration-at.csv"],
        timing: Timing::None,
        make: &study::validation_folded::FoldedTipAcceleration,
    },
    Figure {
        id: "energy-budget",
        report: None,
        what: "E(t), the dissipated work W(t) and E + W for r = 0 and r > 0 (span d = 3)",
        data: &["energy-budget.csv"],
        timing: Timing::None,
        make: &study::validation_energy::EnergyBudget,
    },
    Figure {
        id: "report-scenes-accuracy",
        report: None,
        what: "each report scene by RK4 at dt = 0.01 .. 0.00125 and at its own settings, \
               against DOP853 at rtol 1e-12: is each report figure converged?",
        data: &["report-scenes-accuracy.csv"],
        timing: Timing::None,
        make: &crate::report_accuracy::ReportAccuracy,
    },
    Figure {
        id: "normal-modes",
        report: None,
        what: "relative error of the lowest five frequencies of the linearised hanging chain \
               vs n from (j_0k / 2) sqrt(g/L), with the fitted C / n^p",
        data: &["normal-modes.csv", "normal-modes-fit.csv"],
        timing: Timing::None,
        make: &study::validation_modes::NormalModes,
    },
    Figure {
        id: "support-force",
        report: None,
        what: "force on the pivot P0 in units of M g, one experiment per panel: the folded \
               fall (r = 0) against xi and the law (M g / 4)(2 + 2 xi - 3 xi^2)/(1 - xi), and \
               the span d = 3 fall against t",
        data: &["support-force.csv", "support-force-law.csv"],
        timing: Timing::None,
        make: &study::validation_folded::SupportForce,
    },
    Figure {
        id: "elastic-rigid-limit",
        report: None,
        what: "when the rigid model will do: for each report scene at its own n, the elastic \
               chain's tip path and maximum tip speed against the rigid chain's vs EA, and the \
               EA above which both agree within 1e-3 (about 5 min on two cores: computed only by \
               --timings)",
        data: &[
            "elastic-rigid-limit-timing.csv",
            "elastic-rigid-limit-threshold-timing.csv",
        ],
        timing: Timing::Only,
        make: &study::elastic_rigid_limit::RigidLimit,
    },
    Figure {
        id: "elastic-rigid-order",
        report: None,
        what: "an independent check of the dynamics: the elastic chain (maximal coordinates) \
               against the rigid one (the angles) on span d = 3, the folded chain and the \
               catenary fall before their whips, tip path and tip at the end vs EA = 1e3 .. \
               1e5, and the order in 1/EA",
        data: &["elastic-rigid-order.csv", "elastic-rigid-order-fit.csv"],
        timing: Timing::None,
        make: &study::elastic_rigid_order::RigidOrder,
    },
    Figure {
        id: "elastic-layout-order",
        report: None,
        what: "the elastic chain against the continuum rope as n grows (a rope of unit length, \
               mass and gravity, EA = 1e4): the lowest three axial frequencies and the \
               self-weight stretch (without and with a tip mass M_t = M), n = 5 .. 320, the \
               fitted orders, and the layout before as its closed forms",
        data: &[
            "elastic-layout-order.csv",
            "elastic-layout-order-stretch.csv",
            "elastic-layout-order-fit.csv",
        ],
        timing: Timing::None,
        make: &study::elastic_layout_order::LayoutOrder,
    },
    Figure {
        id: "snap-precision",
        report: None,
        what: "work-precision of the folded elastic snap (n = 20, 5% damping, t = 3.2) at EA = \
               1e4 .. 1e8: DOPRI5, DOP853, BDF, gen-alpha and auto against DOP853 at rtol 1e-10; \
               error against wall time at EA = 1e8 and each method's least time to an error of \
               1e-4 against EA (timing only: run with --timings)",
        data: &["snap-precision-timing.csv", "snap-precision-best-timing.csv"],
        timing: Timing::Only,
        make: &study::elastic_snap_precision::BY_STIFFNESS,
    },
    Figure {
        id: "snap-damping",
        report: None,
        what: "work-precision of the folded elastic snap (n = 20, EA = 1e7, t = 3.2) at axial \
               damping ratios 0.05 .. 1: error against wall time at zeta = 1 and the speed-up \
               of gen-alpha and BDF over the explicit pairs at an error of 1e-4 (timing only: \
               run with --timings)",
        data: &["snap-damping-timing.csv", "snap-damping-best-timing.csv"],
        timing: Timing::Only,
        make: &study::elastic_snap_precision::BY_DAMPING,
    },
    Figure {
        id: "force-precision",
        report: None,
        what: "work-precision of the snap's forces beside the tip (issue 49's steel rope, \
               span d = 3 at EA = 1e8 with 5% damping, cut to n = 10 rods, t = 3.2): the \
               relative errors of the largest pivot force, the largest joint tension and the \
               tip at the end against rtol 1e-3 .. 1e-8 for DOPRI5, DOP853, BDF, gen-alpha and \
               auto, against DOP853 at rtol 1e-10 confirmed by DOPRI5 at 1e-9; the runs that \
               say forces_resolved = false ringed",
        data: &["force-precision.csv", "force-precision-reference.csv"],
        timing: Timing::None,
        make: &study::force_precision::ForcePrecision,
    },
    Figure {
        id: "span-friction",
        report: None,
        what: "sensitivity of the maximum tip speed to the joint friction r for the span \
               scenes: r = 0 and 1e-5 .. 1e-2 (bracketing the report's 1e-4 .. 1e-3), at n = 50 \
               (DOPRI5, rtol 1e-10) and on 200 rods with the continuum fixed (auto, rtol 1e-8)",
        data: &["span-friction.csv", "span-friction-summary.csv"],
        timing: Timing::None,
        make: &study::span_friction::SpanFriction,
    },
    Figure {
        id: "snap-force",
        report: None,
        what: "the snap: peak support force and impulse against n (25 .. 400, total mass fixed) \
               for span d = 3, d = 1 and the folded chain, rigid and elastic (EA 1e4 with and \
               without EI 0.1 and friction to n = 200; EA 1e5 to n = 100) (minutes: computed only by \
               --timings); span d = 3 with EA 1e6 and 1e7 to n = 100 (the -stiff file, every run)",
        data: &["snap-force-stiff.csv", "snap-force-timing.csv"],
        timing: Timing::Alongside,
        make: &study::elastic_snap_force::SnapForce,
    },
    Figure {
        id: "snap-tension",
        report: None,
        what: "the snap's wave: the tension along the chain at six times, five from the tip's \
               arrest to the support's peak and one 0.05 after it, and the support force against \
               time (span d = 3, n = 100, total mass 10, EA = 1e4)",
        data: &["snap-tension.csv", "snap-tension-force.csv", "snap-tension-summary.csv"],
        timing: Timing::None,
        make: &study::elastic_snap_tension::SnapTension,
    },
    Figure {
        id: "beam-precision",
        report: None,
        what: "work-precision of BEAM, the IVP test set's stiff beam (40 segments, t = 0 .. 5): \
               every method's error at t = 5 against the published reference vs wall time and \
               vs accepted steps",
        data: &[
            "beam-precision.csv",
            "beam-precision-timing.csv",
            "beam-precision-machine-timing.csv",
        ],
        timing: Timing::Alongside,
        make: &study::precision_beam::BeamPrecision,
    },
    Figure {
        id: "tip-mass-fall",
        report: None,
        what: "folded chain with a tip mass M (n = 400, r = 0), M/m_c = 0.1 .. 10: fall time over \
               free fall and tip speed at the end of the fall against the energy-conserving law",
        data: &["tip-mass-fall.csv", "tip-mass-fall-law.csv"],
        timing: Timing::None,
        make: &study::tip_mass_fall::TipMassFall,
    },
    Figure {
        id: "whip-taper",
        report: None,
        what: "the tapered whip (span d = 3 released, r l fixed): the largest tip speed against \
               the taper of the mass per length 1:1 .. 100:1, n = 50, 100, 200 refined by the \
               profile, and its gain over the uniform chain; the whip's animation beside it",
        data: &["whip-taper.csv"],
        timing: Timing::None,
        make: &study::whip_taper::WhipTaper,
    },
    Figure {
        id: "floor-checks",
        report: None,
        what: "the floor against its closed forms: one rod's plastic impact (the far end's \
               speed against 6 v cos^2 th / (1 + 3 cos^2 th)) over the contact stiffness at \
               three angles, and a chain laid on a level floor and on slopes below and above \
               the friction angle (creep and slide)",
        data: &["floor-checks.csv", "floor-checks-slope.csv"],
        timing: Timing::None,
        make: &study::floor_checks::FloorChecks,
    },
    Figure {
        id: "floor-span-d3",
        report: None,
        what: "the report's U (span d = 3, n = 50) released over a floor at y = -3: the chain \
               at t = 0 .. 4.157 over the floor, and the released end's speed beside the same \
               U without a floor (the whip does not form)",
        data: &["floor-span-d3.csv", "floor-span-d3-series.csv"],
        timing: Timing::None,
        make: &study::floor_span_d3::FloorSpanD3,
    },
    Figure {
        id: "cayley-scale",
        report: None,
        what: "Cayley's scale as an ensemble: a chain hanging onto a plastic floor, let go at the \
               top, 16 starts perturbed by up to 1e-3 rad each; the mean reading over 3 mu g x \
               against time for n = 10, 20, 40, 80, and at mid-fall against n with the other \
               floors, tilts and a smaller perturbation at n = 40",
        data: &["cayley-scale.csv", "cayley-scale-midfall.csv"],
        timing: Timing::None,
        make: &study::cayley_scale::CayleyScale,
    },
    Figure {
        id: "cayley-floors",
        report: None,
        what: "Cayley's scale at n = 160 as single runs: the floor's force averaged over 19 \
               windows of 0.05 in t = 0.3 .. 1.2 on the constraint floor (Moreau-Jean, \
               dt = 2.5e-3) and on the penalty floor (DOP853, rtol 1e-4), beside the ideal \
               3 mu g x, and each window's reading",
        data: &["cayley-floors.csv", "cayley-floors-summary.csv"],
        timing: Timing::None,
        make: &study::cayley_floors::CayleyFloors,
    },
    Figure {
        id: "cayley-top",
        report: None,
        what: "faster than g? The top of Cayley's falling chain over free fall against time, \
               ensembles of 16 perturbed starts: n = 10 .. 80 on a plastic floor, and at \
               n = 40 an elastic floor, joint friction and floor friction",
        data: &["cayley-top.csv"],
        timing: Timing::None,
        make: &study::cayley_scale::CayleyTop,
    },
    Figure {
        id: "viewer-peak",
        report: None,
        what: "`falling-chain view`'s page for the folded chain (n = 50, r = 0.001) at its peak \
               tip speed, as headless Chromium draws it (skipped, and kept, without Chromium)",
        data: &["viewer-peak.csv", "viewer-peak-summary.csv"],
        timing: Timing::None,
        make: &crate::viewer_shot::ViewerPeak,
    },
    // The report's own model, as a control (`docs/model.md`).
    report_model!("rm03-horizontal-undamped", "Fig. 3, report's model, n = 25, r = 0", "the report's Fig. 3 from the report's model (`model.report = true`: its equations, clock and stepper; n = 25, r = 0, its dt = 0.01001 to its t = 10, every 25th step), beside fig03", "horizontal-undamped", 10.0),
    report_model!("rm04-horizontal-damped", "Fig. 4, report's model, n = 25, r = 0.001", "the report's Fig. 4 from the report's model (n = 25, r = 0.001, to its t = 10), beside fig04", "horizontal-damped", 10.0),
    report_model!("rm05-horizontal-settling", "Fig. 5, report's model, n = 25, r = 0.001", "the report's Fig. 5 from the report's model (n = 25, r = 0.001, to its t = 40), beside fig05", "horizontal-settling", 40.0),
    report_model!("rm06-catenary-fall", "Fig. 6, report's model, n = 25, r = 0.001", "the report's Fig. 6 from the report's model (n = 25, r = 0.001, catenary to (5, 1), to its t = 15), beside fig06", "catenary-fall", 15.0),
    report_model!("rm07a-span-d1", "Fig. 7a, report's model", "the report's Fig. 7a from the report's model (n = 50, r = 0.0005, d = 1, to its t = 12), beside fig07a", "span-d1", 12.0),
    report_model!("rm07b-span-d3", "Fig. 7b, report's model", "the report's Fig. 7b from the report's model (n = 50, d = 3, to its t = 12), beside fig07b", "span-d3", 12.0),
    report_model!("rm07c-span-d5", "Fig. 7c, report's model", "the report's Fig. 7c from the report's model (n = 50, d = 5, to its t = 12), beside fig07c", "span-d5", 12.0),
    report_model!("rm07d-span-d6", "Fig. 7d, report's model", "the report's Fig. 7d from the report's model (n = 50, d = 6, stretched, to its t = 12), beside fig07d", "span-d6", 12.0),
    Figure {
        id: "rm08-span-tip-speed",
        report: None,
        what: "the report's Fig. 8 from the report's model (spans d = 1, 3, 5, 6, n = 50, to its t = 12): its own tip speed and velocity in its clock, and per span the run with RK4 for its stepper (the -cases file)",
        data: &["rm08-span-tip-speed.csv", "rm08-span-tip-speed-cases.csv"],
        timing: Timing::None,
        make: &ReportTip {
            title: "Fig. 8 from the report's model (n = 50, r = 0.0005)",
            scenes: SPANS,
            t_report: 12.0,
        },
    },
    Figure {
        id: "rm09-vmax-vs-span",
        report: None,
        what: "Fig. 9 in the report's model (its 14 spans, n = 50, r = 0.0005, its dt = 0.01001 to its t = 12): its maximum tip speed in its clock, by its finite differences, in our units, and the corrected model's; with a pair of runs per erratum (the -errata file) and each erratum undone at each span (the -errata-spans file, drawn)",
        data: &[
            "rm09-vmax-vs-span.csv",
            "rm09-vmax-vs-span-errata.csv",
            "rm09-vmax-vs-span-errata-spans.csv",
        ],
        timing: Timing::None,
        make: &ReportVmax {
            title: "Fig. 9 from the report's model",
            scene: "span-d3",
            t_report: 12.0,
        },
    },
    report_model!("rm10a-height-hm2", "Fig. 10a, report's model", "the report's Fig. 10a from the report's model (n = 50, r = 0.0005, P1 = (3, -2), to its t = 15), beside fig10a", "height-hm2", 15.0),
    report_model!("rm10b-height-h0", "Fig. 10b, report's model", "the report's Fig. 10b from the report's model (P1 = (3, 0), to its t = 15), beside fig10b", "height-h0", 15.0),
    report_model!("rm10c-height-h2", "Fig. 10c, report's model", "the report's Fig. 10c from the report's model (P1 = (3, 2), to its t = 15), beside fig10c", "height-h2", 15.0),
    report_model!("rm10d-height-h4", "Fig. 10d, report's model", "the report's Fig. 10d from the report's model (P1 = (3, 4), to its t = 15), beside fig10d", "height-h4", 15.0),
    Figure {
        id: "rm11-height-tip-speed",
        report: None,
        what: "the report's Fig. 11 from the report's model (heights h = -2, 0, 2, 4, n = 50, to its t = 15): its own tip speed and velocity in its clock, and per height the run with RK4 for its stepper (the -cases file)",
        data: &["rm11-height-tip-speed.csv", "rm11-height-tip-speed-cases.csv"],
        timing: Timing::None,
        make: &ReportTip {
            title: "Fig. 11 from the report's model (n = 50, r = 0.0005)",
            scenes: HEIGHTS,
            t_report: 15.0,
        },
    },
    Figure {
        id: "rm12-folded",
        report: None,
        what: "the report's Fig. 12 from the report's model (the folded chain, n = 50, r = 0.001, to its t = 12), beside fig12, and the run with RK4 for its stepper (the -cases file)",
        data: &["rm12-folded.csv", "rm12-folded-cases.csv"],
        timing: Timing::None,
        make: &ReportSnapshots {
            title: "Fig. 12, report's model",
            scene: "folded",
            t_report: 12.0,
        },
    },
];

/// The catalogue of every figure, in the registry's order.
pub fn entries() -> Vec<Entry<'static>> {
    FIGURES.iter().map(Figure::entry).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_keeps_the_catalogue_conventions() {
        assert_eq!(paper::catalogue::check(&entries()), Ok(()));
        assert_eq!(FIGURES.iter().filter(|f| f.report.is_some()).count(), 21);
        assert_eq!(FIGURES.len(), 69);
    }

    /// The lines of xtask's code (`src/`) each registered figure may take:
    /// its registry entry and its `Make` (the choice of its scenes and
    /// files, a call of the library that computes its tables). xtask grows
    /// with the figures, so its bound is per figure (at 67 figures, 50 is
    /// 3,350 lines; it holds 44 a figure): a figure whose glue outgrows it
    /// holds a computation that belongs to `fc_paper_figures`.
    const LINES_PER_FIGURE: usize = 50;

    /// xtask stays glue: its source within [`LINES_PER_FIGURE`] lines per figure.
    #[test]
    fn xtask_stays_glue() {
        let mut dirs = vec![crate::root().join("xtask").join("src")];
        let mut lines = 0;
        while let Some(dir) = dirs.pop() {
            for entry in std::fs::read_dir(dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    dirs.push(path);
                } else if path.extension().is_some_and(|e| e == "rs") {
                    lines += std::fs::read_to_string(&path).unwrap().lines().count();
                }
            }
        }
        let bound = LINES_PER_FIGURE * FIGURES.len();
        assert!(lines <= bound, "xtask holds {lines} lines, past {bound}");
    }

    /// The panels of the registry's line plots and pairs.
    const PANELS: usize = 67;

    /// Every figure drawn from the committed data (into a scratch folder)
    /// whose drawing reports its layout (the line plots and pairs): its
    /// data span at least half of each axis (decades on a log axis; the
    /// wider axis under equal scales), and no legend or note box covers a
    /// data point (`figures::PanelLayout::problems`). The viewer's
    /// screenshot, drawn by Chromium, has no axes and is left out.
    #[test]
    fn every_figure_fills_its_axes_and_no_box_hides_its_data() {
        let root = crate::root();
        let mut ctx = Ctx::new(&root, 1, false);
        let scratch = std::env::temp_dir().join(format!("xtask-layout-{}", std::process::id()));
        std::fs::create_dir_all(&scratch).unwrap();
        ctx.out = scratch.clone();
        let mut reported = 0;
        for f in FIGURES.iter().filter(|f| f.id != "viewer-peak") {
            f.make
                .draw(&ctx, f)
                .unwrap_or_else(|e| panic!("{}: {e}", f.id));
            reported += 1;
        }
        std::fs::remove_dir_all(&scratch).unwrap();
        let problems = ctx.layout_problems.lock().unwrap().clone();
        assert_eq!(problems, vec![], "figures whose layout hides their data");
        assert_eq!(reported, FIGURES.len() - 1);
        // The line plots and pairs of the registry, each panel checked.
        let panels = ctx
            .panels_checked
            .load(std::sync::atomic::Ordering::Relaxed);
        assert_eq!(panels, PANELS, "panels that reported their layout");
    }
}
