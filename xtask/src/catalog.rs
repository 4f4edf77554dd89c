//! Every figure of the report, as data: what it shows and what it is made
//! from. The builder chooses the drawing by `Kind`, never by id.

/// How a figure is made.
#[derive(Clone, Copy, Debug)]
pub enum Kind {
    /// The schematic of the problem.
    Sketch,
    /// Continuous catenaries from P0 to P1 for a range of lengths.
    Catenaries {
        p1: [f64; 2],
        lengths: (f64, f64, usize),
    },
    /// Chain snapshots of one scene, coloured by time.
    Snapshots {
        scene: &'static str,
        x_range: Option<(f64, f64)>,
    },
    /// Tip speed against time, one line per scene.
    TipSpeed { scenes: &'static [&'static str] },
    /// Tip velocity v_y against v_x, one line per scene.
    TipVelocity { scenes: &'static [&'static str] },
    /// Maximum tip speed against the span d: the report's spans as points and
    /// a dense sweep as a line (catenary starts), plus the stretched d = L.
    VmaxVsSpan {
        scene: &'static str,
        stretched: &'static str,
        report_spans: LinspaceSlice,
        dense: (f64, f64, usize),
    },
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

/// One figure: `figures/<id>.png` and `.svg`.
#[derive(Clone, Copy, Debug)]
pub struct Figure {
    pub id: &'static str,
    /// The report's figure it reproduces.
    pub report: &'static str,
    /// The title drawn on the figure (short).
    pub title: &'static str,
    /// One line: what it shows.
    pub what: &'static str,
    pub kind: Kind,
}

const SPANS: &[&str] = &["span-d1", "span-d3", "span-d5", "span-d6"];
const HEIGHTS: &[&str] = &["height-hm2", "height-h0", "height-h2", "height-h4"];

const fn snap(
    id: &'static str,
    report: &'static str,
    title: &'static str,
    what: &'static str,
    scene: &'static str,
) -> Figure {
    Figure {
        id,
        report,
        title,
        what,
        kind: Kind::Snapshots {
            scene,
            x_range: None,
        },
    }
}

/// The report's figures, fig01 .. fig12 (`../shared/figures.md`).
pub const FIGURES: &[Figure] = &[
    Figure {
        id: "fig01-sketch",
        title: "the falling chain",
        report: "Fig. 1",
        what: "schematic: P0, P1, L, d, h, g, the released end",
        kind: Kind::Sketch,
    },
    Figure {
        id: "fig02-catenaries",
        title: "catenaries from (0,0) to (5,1)",
        report: "Fig. 2",
        what: "continuous catenaries from P0 (0,0) to P1 (5,1), L = 6 .. 12, coloured by L, lowest points marked",
        kind: Kind::Catenaries {
            p1: [5.0, 1.0],
            lengths: (6.0, 12.0, 13),
        },
    },
    snap("fig03-horizontal-undamped", "Fig. 3", "horizontal start, n = 25, r = 0", "n = 25 stretched horizontal chain, r = 0, t = 4.899", "horizontal-undamped"),
    snap("fig04-horizontal-damped", "Fig. 4", "horizontal start, n = 25, r = 0.001", "n = 25 stretched horizontal chain, r = 0.001, t = 4.899", "horizontal-damped"),
    snap("fig05-horizontal-settling", "Fig. 5", "horizontal start, r = 0.001, to t = 19.6", "as fig04 to t = 19.60: the chain settles to hanging", "horizontal-settling"),
    snap("fig06-catenary-fall", "Fig. 6", "catenary to (5,1), n = 25, r = 0.001", "n = 25 discrete catenary to P1 (5,1), r = 0.001, t = 7.348", "catenary-fall"),
    snap("fig07a-span-d1", "Fig. 7a", "span d = 1, n = 50", "n = 50, P1 = (1, 0), r = 0.0005, t = 4.157", "span-d1"),
    snap("fig07b-span-d3", "Fig. 7b", "span d = 3, n = 50", "n = 50, P1 = (3, 0), r = 0.0005, t = 4.157", "span-d3"),
    snap("fig07c-span-d5", "Fig. 7c", "span d = 5, n = 50", "n = 50, P1 = (5, 0), r = 0.0005, t = 4.157", "span-d5"),
    snap("fig07d-span-d6", "Fig. 7d", "span d = 6 (stretched), n = 50", "n = 50, P1 = (6, 0) (stretched), r = 0.0005, t = 4.157", "span-d6"),
    Figure {
        id: "fig08a-span-tip-speed",
        title: "tip speed, spans d = 1, 3, 5, 6",
        report: "Fig. 8a",
        what: "tip speed against time for the four spans d = 1, 3, 5, 6",
        kind: Kind::TipSpeed { scenes: SPANS },
    },
    Figure {
        id: "fig08b-span-tip-velocity",
        title: "tip velocity, spans d = 1, 3, 5, 6",
        report: "Fig. 8b",
        what: "tip velocity v_y against v_x for the four spans",
        kind: Kind::TipVelocity { scenes: SPANS },
    },
    Figure {
        id: "fig09-vmax-vs-span",
        title: "maximum tip speed against span d",
        report: "Fig. 9",
        what: "maximum tip speed against the span d (n = 50, r = 0.0005, t = 4.157): the report's 14 spans and a dense sweep",
        kind: Kind::VmaxVsSpan {
            scene: "span-d3",
            stretched: "span-d6",
            report_spans: LinspaceSlice {
                start: 0.0,
                stop: 6.0,
                num: 20,
                from: 5,
                to: 19,
            },
            dense: (0.3, 5.97, 120),
        },
    },
    snap("fig10a-height-hm2", "Fig. 10a", "P1 = (3, -2), n = 50", "n = 50, P1 = (3, -2), r = 0.0005, t = 5.196", "height-hm2"),
    snap("fig10b-height-h0", "Fig. 10b", "P1 = (3, 0), n = 50", "n = 50, P1 = (3, 0), r = 0.0005, t = 5.196", "height-h0"),
    snap("fig10c-height-h2", "Fig. 10c", "P1 = (3, 2), n = 50", "n = 50, P1 = (3, 2), r = 0.0005, t = 5.196", "height-h2"),
    snap("fig10d-height-h4", "Fig. 10d", "P1 = (3, 4), n = 50", "n = 50, P1 = (3, 4), r = 0.0005, t = 5.196", "height-h4"),
    Figure {
        id: "fig11a-height-tip-speed",
        title: "tip speed, heights h = -2, 0, 2, 4",
        report: "Fig. 11a",
        what: "tip speed against time for the four heights h = -2, 0, 2, 4",
        kind: Kind::TipSpeed { scenes: HEIGHTS },
    },
    Figure {
        id: "fig11b-height-tip-velocity",
        title: "tip velocity, heights h = -2, 0, 2, 4",
        report: "Fig. 11b",
        what: "tip velocity v_y against v_x for the four heights",
        kind: Kind::TipVelocity { scenes: HEIGHTS },
    },
    Figure {
        id: "fig12-folded",
        title: "folded chain, n = 50, r = 0.001",
        report: "Fig. 12",
        what: "n = 50 folded chain (25 down, 1 across, 24 up), r = 0.001, t = 4.157",
        kind: Kind::Snapshots {
            scene: "folded",
            x_range: Some((-0.25, 0.25)),
        },
    },
];

impl Figure {
    /// The scene files this figure runs (without the sweep's own runs).
    pub fn scenes(&self) -> Vec<&'static str> {
        match self.kind {
            Kind::Sketch | Kind::Catenaries { .. } => vec![],
            Kind::Snapshots { scene, .. } => vec![scene],
            Kind::TipSpeed { scenes } | Kind::TipVelocity { scenes } => scenes.to_vec(),
            Kind::VmaxVsSpan {
                scene, stretched, ..
            } => vec![scene, stretched],
        }
    }
}
