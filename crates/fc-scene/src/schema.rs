//! The scene schema: [`KEYS`], one row per scene key, is the single source
//! of each key's dotted path, type, default, the start kinds that take it,
//! and its doc line.
//!
//! Everything else derives from it: the loader's checks ([`check`]: unknown
//! keys, wrong types, keys of another start kind, required keys, defaults),
//! `--set` and `sweep --vary` (which paths exist, which keys take integers:
//! [`Key::coerce`]), the key names in error messages, and the table in
//! `scenes/README.md` ([`markdown_table`], checked by a test and rewritten by
//! `cargo xtask scene-keys`).
//!
//! Adding a key: add its row here, then read its value where a scene is
//! built (`scene.rs`, a field of the serde section struct). The tests fail
//! until the row, the serde struct and the README agree.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use crate::error::Error;

/// The kinds of start a scene can ask for (`start.kind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum StartKind {
    Stretched,
    Catenary,
    Folded,
    Angles,
}

impl StartKind {
    /// Every kind.
    pub const ALL: [StartKind; 4] = [
        StartKind::Stretched,
        StartKind::Catenary,
        StartKind::Folded,
        StartKind::Angles,
    ];

    /// Their names in a scene file, in the order of [`StartKind::ALL`].
    pub const NAMES: [&'static str; 4] = ["stretched", "catenary", "folded", "angles"];

    /// Its name in a scene file.
    pub fn as_str(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// The `[start]` keys this kind takes (their names within `[start]`),
    /// in table order.
    pub fn keys(self) -> Vec<&'static str> {
        section_rows("start")
            .filter(|k| k.kinds.accepts(self))
            .map(Key::name)
            .collect()
    }
}

/// What a key's value is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Type {
    /// A number; an integer is accepted (`t_end = 4`).
    Number,
    /// An integer >= 0. `--set` and `--vary` turn a whole float into one.
    Integer,
    /// A point `[x, y]` of two numbers; elements are set by index (`start.p1.0`).
    Point,
    /// A list of numbers; elements are set by index.
    Numbers,
    /// A string.
    Text,
    /// One of these strings.
    OneOf(&'static [&'static str]),
    /// `true` or `false`.
    Bool,
}

/// A default as a constant (turned into TOML by [`Literal::to_toml`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Literal {
    Number(f64),
    Integer(i64),
    Point([f64; 2]),
    Text(&'static str),
    Bool(bool),
}

/// What an omitted key is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DefaultValue {
    /// It must be given (by every start kind that takes it).
    Required,
    /// This value, filled in by [`check`].
    Value(Literal),
    /// Worked out from other values when the scene is built (by the loader
    /// or by chain-ode); the text says how.
    Computed(&'static str),
}

/// Which start kinds take a key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kinds {
    /// Not a `[start]` key: whatever the start.
    Any,
    /// A `[start]` key taken by these kinds only.
    Only(&'static [StartKind]),
}

impl Kinds {
    /// Whether a scene whose start is `kind` takes the key.
    pub fn accepts(self, kind: StartKind) -> bool {
        match self {
            Self::Any => true,
            Self::Only(kinds) => kinds.contains(&kind),
        }
    }
}

/// One scene key: a row of [`KEYS`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key {
    /// Dotted path: `name`, `chain.links`, `start.p1`, `run.rtol`.
    pub path: &'static str,
    pub ty: Type,
    pub default: DefaultValue,
    pub kinds: Kinds,
    /// One line (markdown) for the README table; it states the accepted
    /// range where there is one.
    pub doc: &'static str,
    /// A valid value other than the default, as `--set` text. Setting it
    /// must change what the scene builds (its name or description, or the
    /// `Chain`, `State`, `Method` or `SolveOptions` of `Scene::prepare`):
    /// `scene::tests::every_key_reaches_the_model` sets it.
    pub example: &'static str,
    /// A value of the key's type outside its accepted range, as `--set`
    /// text (`None`: every value of the type is accepted, as for `name`).
    /// `scene::tests::every_range_is_checked_by_its_key` sets it and wants
    /// an error naming the key: a missing range check fails it.
    pub out_of_range: Option<&'static str>,
}

const ALL_KINDS: Kinds = Kinds::Only(&StartKind::ALL);

/// Every scene key, in the order of the README table. The sections
/// (`chain`, `pivot`, `start`, `run`, `model`) are the first parts of the dotted paths.
const ROWS: &[Key] = &[
    Key {
        path: "name",
        ty: Type::Text,
        default: DefaultValue::Computed("the file's stem"),
        kinds: Kinds::Any,
        doc: "the scene's name (in summaries)",
        example: "sample",
        out_of_range: None,
    },
    Key {
        path: "description",
        ty: Type::Text,
        default: DefaultValue::Value(Literal::Text("")),
        kinds: Kinds::Any,
        doc: "free text: which report figure, what it shows",
        example: "sample",
        out_of_range: None,
    },
    Key {
        path: "chain.length",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(6.0)),
        kinds: Kinds::Any,
        doc: "total length `L`, finite and > 0",
        example: "7.5",
        out_of_range: Some("-1"),
    },
    Key {
        path: "chain.links",
        ty: Type::Integer,
        default: DefaultValue::Required,
        kinds: Kinds::Any,
        doc: "number of rods `n`, in 1..=1000000, and no more than the run's memory allows: its estimate (64 MiB plus the bytes a rod measured for its model and method, `docs/speed.md`, \"Memory at large n\", plus its samples) must fit in `MemAvailable`, or in `FC_MEMORY_AVAILABLE` bytes when that is set, else the run is refused before it starts (`docs/cli.md`, \"Input bounds\"); `chain.mass` and `chain.damping` are per rod, so setting it alone changes the chain: `--refine N` (Python `Scene.refine(n)`) cuts the same chain into `N` rods as `converge` does, total mass, length, `r l`, EA, EI and the tip mass kept",
        example: "6",
        out_of_range: Some("0"),
    },
    Key {
        path: "chain.mass",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.2)),
        kinds: Kinds::Any,
        doc: "mass of **one rod** `m`, finite and > 0",
        example: "0.375",
        out_of_range: Some("0"),
    },
    Key {
        path: "chain.gravity",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(1.0)),
        kinds: Kinds::Any,
        doc: "`g`, along -y, finite and >= 0",
        example: "2.5",
        out_of_range: Some("-1"),
    },
    Key {
        path: "chain.damping",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.0)),
        kinds: Kinds::Any,
        doc: "joint friction `r`, finite and >= 0",
        example: "0.001",
        out_of_range: Some("-1e-3"),
    },
    Key {
        path: "chain.axial_stiffness",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: rigid links (the pinned chain)"),
        kinds: Kinds::Any,
        doc: "axial stiffness `EA` (force), finite and > 0: each joint a spring `K = EA / l`, the pivot's `2 EA / l` (it carries half a rod; the elastic model, `docs/model.md`)",
        example: "1e4",
        out_of_range: Some("-1e4"),
    },
    Key {
        path: "chain.axial_damping",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.0)),
        kinds: Kinds::Any,
        doc: "axial viscosity `eta` (force x time), finite and >= 0: a dashpot `eta / l` beside each joint spring (`2 eta / l` at the pivot); acts only with `chain.axial_stiffness`",
        example: "0.5",
        out_of_range: Some("-1"),
    },
    Key {
        path: "chain.bending_stiffness",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.0)),
        kinds: Kinds::Any,
        doc: "bending stiffness `EI` (force x length^2), finite and >= 0: a torque `(EI / l) (phi_{i+1} - phi_i)` between neighbouring rods",
        example: "0.01",
        out_of_range: Some("-0.01"),
    },
    Key {
        path: "chain.tip_mass",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.0)),
        kinds: Kinds::Any,
        doc: "a point mass `M_t` (mass) at the free end, finite and >= 0; rigid or elastic links",
        example: "1.0",
        out_of_range: Some("-1"),
    },
    Key {
        path: "chain.air_drag",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.0)),
        kinds: Kinds::Any,
        doc: "quadratic air drag `c` (mass / length^2), in 0..=1e9: a force `-c l_i s_i v_i` at each rod's centre, `v_i` its velocity, `s_i` its speed; not with pivot.release on rigid links",
        example: "0.05",
        out_of_range: Some("-1"),
    },
    Key {
        path: "chain.taper",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(1.0)),
        kinds: Kinds::Any,
        doc: "the ratio of the mass per length at the pivot to that at the tip, in 0.001..=1000 (`10`: tapered 10:1): the mass per length falls linearly in arc length, the total mass stays `n m`; `1` is equal rods; rigid or elastic links, with any tip mass, bending stiffness and pivot",
        example: "10",
        out_of_range: Some("0"),
    },
    Key {
        path: "chain.rod_masses",
        ty: Type::Numbers,
        default: DefaultValue::Computed("absent: equal rods (or `chain.taper`'s)"),
        kinds: Kinds::Any,
        doc: "relative masses of the rods from the pivot to the tip, `chain.links` finite numbers > 0 within a factor 1e6, scaled to sum to `n m`; not with a `chain.taper` other than 1",
        example: "[4, 3, 2, 1]",
        out_of_range: Some("[1, 0, 1, 1]"),
    },
    Key {
        path: "chain.rod_lengths",
        ty: Type::Numbers,
        default: DefaultValue::Computed("absent: equal rods"),
        kinds: Kinds::Any,
        doc: "relative lengths of the rods from the pivot to the tip, `chain.links` finite numbers > 0 within a factor 1e6, scaled to sum to `L`",
        example: "[1, 2, 1, 2]",
        out_of_range: Some("[1, -1, 1, 1]"),
    },
    Key {
        path: "pivot.acceleration",
        ty: Type::Point,
        default: DefaultValue::Value(Literal::Point([0.0, 0.0])),
        kinds: Kinds::Any,
        doc: "a constant acceleration `a` of the pivot `P0` (`P0 + a t^2 / 2`), finite; `[0, -g]` is a support falling freely; rigid or elastic links",
        example: "[0.0, -0.5]",
        out_of_range: Some("[nan, 0]"),
    },
    Key {
        path: "pivot.amplitude",
        ty: Type::Point,
        default: DefaultValue::Value(Literal::Point([0.0, 0.0])),
        kinds: Kinds::Any,
        doc: "the amplitude `A` (length) of a harmonic motion `A sin(Omega t)` of the pivot, finite; rigid or elastic links",
        example: "[0.0, 0.05]",
        out_of_range: Some("[inf, 0]"),
    },
    Key {
        path: "pivot.frequency",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(1.0)),
        kinds: Kinds::Any,
        doc: "its angular frequency `Omega` (rad/time), finite and >= 0",
        example: "30",
        out_of_range: Some("-1"),
    },
    Key {
        path: "pivot.jerk",
        ty: Type::Point,
        default: DefaultValue::Value(Literal::Point([0.0, 0.0])),
        kinds: Kinds::Any,
        doc: "a smooth jerk: the pivot moves by `D` (length) from `t = 0` over `pivot.jerk_time` on the minimum-jerk path `10u^3 - 15u^4 + 6u^5`, finite; rigid or elastic links",
        example: "[0.5, 0.0]",
        out_of_range: Some("[0, nan]"),
    },
    Key {
        path: "pivot.jerk_time",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(1.0)),
        kinds: Kinds::Any,
        doc: "the duration `tau` of the smooth jerk (time), finite and > 0",
        example: "0.25",
        out_of_range: Some("0"),
    },
    Key {
        path: "pivot.release",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: never (the pivot stays pinned)"),
        kinds: Kinds::Any,
        doc: "the time the pivot is let go too, finite and >= 0 (`0`: both ends let go at `t = 0`); the pivot moves as the keys above until then; rigid or elastic links",
        example: "0",
        out_of_range: Some("-1"),
    },
    Key {
        path: "start.kind",
        ty: Type::OneOf(&StartKind::NAMES),
        default: DefaultValue::Required,
        kinds: ALL_KINDS,
        doc: "how the chain lies at `t = 0` (see Starts below)",
        example: "folded",
        out_of_range: Some("zigzag"),
    },
    Key {
        path: "start.p0",
        ty: Type::Point,
        default: DefaultValue::Value(Literal::Point([0.0, 0.0])),
        kinds: ALL_KINDS,
        doc: "the pivot `P0`",
        example: "[0.5, -0.5]",
        out_of_range: Some("[nan, 0]"),
    },
    Key {
        path: "start.p1",
        ty: Type::Point,
        default: DefaultValue::Required,
        kinds: Kinds::Only(&[StartKind::Stretched, StartKind::Catenary]),
        doc: "where the free end is held, `P1`",
        example: "[3.6, -4.8]",
        out_of_range: Some("[nan, 0]"),
    },
    Key {
        path: "start.down",
        ty: Type::Integer,
        default: DefaultValue::Computed("`links / 2`, rounded down"),
        kinds: Kinds::Only(&[StartKind::Folded]),
        doc: "rods hanging down from `P0`",
        example: "1",
        out_of_range: Some("1000000"),
    },
    Key {
        path: "start.angles",
        ty: Type::Numbers,
        default: DefaultValue::Required,
        kinds: Kinds::Only(&[StartKind::Angles]),
        doc: "`phi_1..phi_n` in rad from the horizontal, each within +-4 pi",
        example: "[0.1, 0.2, 0.3, 0.4]",
        out_of_range: Some("[nan, 0, 0, 0]"),
    },
    Key {
        path: "start.rates",
        ty: Type::Numbers,
        default: DefaultValue::Computed("all `0`"),
        kinds: Kinds::Only(&[StartKind::Angles]),
        doc: "`w_1..w_n` in rad/time",
        example: "[0.5, 0.5, 0.5, 0.5]",
        out_of_range: Some("[nan, 0, 0, 0]"),
    },
    Key {
        path: "run.t_end",
        ty: Type::Number,
        default: DefaultValue::Required,
        kinds: Kinds::Any,
        doc: "end time, finite and > 0",
        example: "2.5",
        out_of_range: Some("-1"),
    },
    Key {
        path: "run.method",
        ty: Type::Text,
        default: DefaultValue::Value(Literal::Text("rk4")),
        kinds: Kinds::Any,
        doc: "integration method: any name chain-ode's `Method` parses (`rk4`, `dopri5`, ...)",
        example: "dopri5",
        out_of_range: Some("nonesuch"),
    },
    Key {
        path: "run.dt",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.01)),
        kinds: Kinds::Any,
        doc: "fixed step of RK4 and of `moreau-jean` (the constraint floor's method, which `auto` runs there: its step is set by the smooth motion, not by the impacts it steps over): at most `run.t_end`, at least `run.t_end / run.max_steps`",
        example: "0.005",
        out_of_range: Some("-1"),
    },
    Key {
        path: "run.rtol",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(1e-8)),
        kinds: Kinds::Any,
        doc: "relative tolerance of the adaptive methods, in [1e-14, 0.1] (`gen-alpha`: [1e-10, 0.1], below which its error stops following it)",
        example: "1e-6",
        out_of_range: Some("1"),
    },
    Key {
        path: "run.atol",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(1e-10)),
        kinds: Kinds::Any,
        doc: "absolute tolerance of the adaptive methods, in [1e-20, 1]",
        example: "1e-9",
        out_of_range: Some("2"),
    },
    Key {
        path: "run.output_dt",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.01)),
        kinds: Kinds::Any,
        doc: "spacing of recorded samples (`--out` rows); at least what keeps the samples within 1 GiB (the error says how much)",
        example: "0.02",
        out_of_range: Some("-1"),
    },
    Key {
        path: "run.max_steps",
        ty: Type::Integer,
        default: DefaultValue::Value(Literal::Integer(100_000_000)),
        kinds: Kinds::Any,
        doc: "step budget, >= 1 (the run ends with status `max_steps`)",
        example: "1000",
        out_of_range: Some("0"),
    },
    Key {
        path: "run.h_min",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.0)),
        kinds: Kinds::Any,
        doc: "smallest adaptive step, finite and >= 0 (0: the rounding limit)",
        example: "1e-9",
        out_of_range: Some("-1"),
    },
    Key {
        path: "run.rho_inf",
        ty: Type::Number,
        default: DefaultValue::Value(Literal::Number(0.9)),
        kinds: Kinds::Any,
        doc: "`gen-alpha`'s spectral radius at infinity, in [0, 1]: the share of a mode its step does not resolve that survives a step (1: the trapezoidal rule, no damping; 0: gone in one step, and the forces of the elastic links' stepped-over axial modes their quasi-static values, as `auto` runs it; above 0 those forces are not resolved: `forces_resolved`); the other methods ignore it",
        example: "0.6",
        out_of_range: Some("1.5"),
    },
    Key {
        path: "model.report",
        ty: Type::Bool,
        default: DefaultValue::Value(Literal::Bool(false)),
        kinds: Kinds::Any,
        doc: "`true`: the report's own model, as a control (its equations, clock and stepper as its code has them, `docs/model.md`); rigid links only, at most 200 rods, `run.method` one of `rk4` (the report's stepper), `dopri5`, `dop853`; times and speeds in its clock's unit",
        example: "true",
        out_of_range: None,
    },
    Key {
        path: "floor.height",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: touching the start's lowest rod end (any `[floor]` key makes a floor)"),
        kinds: Kinds::Any,
        doc: "height `h` of the floor line at `x = 0` (length), in -1e9..=1e9, at or below the start (the penalty law: within `n m g / k` summed over the contact points inside, and at most `L / 100`; the constraint law: within `1e-12 L`); the penalty floor runs the elastic chain (`chain.axial_stiffness = 1e4 n m g` when it is absent), the constraint floor the rigid one (`docs/model.md`, \"The floor\"); not with a moving pivot",
        example: "-7",
        out_of_range: Some("1e300"),
    },
    Key {
        path: "floor.law",
        ty: Type::Text,
        default: DefaultValue::Computed("absent: `penalty` when the scene gives `floor.stiffness`, `floor.damping`, `floor.slip_speed` or `chain.axial_stiffness`, else `constraint`"),
        kinds: Kinds::Any,
        doc: "how the floor pushes, one of `penalty`, `constraint`: `penalty`, a stiff spring-damper at each rod end of the elastic chain (issue 36); `constraint`, a unilateral constraint at each joint of the rigid chain with Newton's restitution and Coulomb's friction, run by `run.method = \"moreau-jean\"` (or `auto`) at the step `run.dt` (`docs/model.md`, \"The floor as a constraint\"); each law reads only its own keys",
        example: "constraint",
        out_of_range: Some("soft"),
    },
    Key {
        path: "floor.restitution",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: 0 (plastic)"),
        kinds: Kinds::Any,
        doc: "the constraint floor's coefficient of restitution `e` in [0, 1]: Newton's law `u+ = -e u-` on a joint's normal velocity at an impact; only with `floor.law = \"constraint\"` (the penalty's bounce is `floor.damping`'s)",
        example: "0.5",
        out_of_range: Some("1.5"),
    },
    Key {
        path: "floor.angle",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: 0 (level)"),
        kinds: Kinds::Any,
        doc: "the floor's slope `a` from the horizontal (rad, rising to +x), in -1.5..=1.5",
        example: "0.2",
        out_of_range: Some("2"),
    },
    Key {
        path: "floor.stiffness",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: `1e4 m g / l`"),
        kinds: Kinds::Any,
        doc: "normal stiffness `k` of each contact point, a rod's two ends (force / length), in (0, 1e15]",
        example: "1e5",
        out_of_range: Some("0"),
    },
    Key {
        path: "floor.damping",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: 0"),
        kinds: Kinds::Any,
        doc: "Hunt-Crossley damping `c` (time / length): normal force `max(0, k delta (1 + c delta'))`; `c v >> 1` at an impact speed `v` is plastic; in 0..=1e12",
        example: "100",
        out_of_range: Some("-1"),
    },
    Key {
        path: "floor.friction",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: 0"),
        kinds: Kinds::Any,
        doc: "Coulomb friction coefficient `mu`, regularised as `-mu N tanh(v_t / v_s)`, in 0..=100",
        example: "0.5",
        out_of_range: Some("-0.5"),
    },
    Key {
        path: "floor.slip_speed",
        ty: Type::Number,
        default: DefaultValue::Computed("absent: `1e-3 sqrt(g L)` (`sqrt(L)` at `g = 0`)"),
        kinds: Kinds::Any,
        doc: "the friction's regularisation speed `v_s` (length / time), in (0, 1e6]",
        example: "0.01",
        out_of_range: Some("0"),
    },
];

/// Every scene key, in the order of the README table ([`ROWS`], checked
/// as the crate compiles: a doc is one line without a `|`, which would
/// split its cell of the README's table).
pub static KEYS: &[Key] = ROWS;

/// True when no row's doc holds a line break or a `|`.
const fn docs_are_cells(rows: &[Key]) -> bool {
    let mut i = 0;
    while i < rows.len() {
        let doc = rows[i].doc.as_bytes();
        if doc.is_empty() {
            return false;
        }
        let mut j = 0;
        while j < doc.len() {
            if doc[j] == b'|' || doc[j] == b'\n' {
                return false;
            }
            j += 1;
        }
        i += 1;
    }
    true
}

const _: () = assert!(
    docs_are_cells(ROWS),
    "a scene key's doc must be one non-empty line without '|' (it is a cell of scenes/README.md's table)"
);

/// The row of the key at `path` (`chain.links`), if it is one.
pub fn key(path: &str) -> Option<&'static Key> {
    KEYS.iter().find(|k| k.path == path)
}

/// The names a scene file may have at its top: the top-level keys and the
/// sections, in table order (`name, description, chain, start, run, model`).
pub fn top_names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = vec![];
    for k in KEYS {
        let top = k.section().unwrap_or(k.path);
        if !names.contains(&top) {
            names.push(top);
        }
    }
    names
}

/// Whether `name` is a section (`chain`, `start`, `run`, `model`).
pub fn is_section(name: &str) -> bool {
    KEYS.iter().any(|k| k.section() == Some(name))
}

/// The rows of `section`, in table order.
pub fn section_rows(section: &str) -> impl Iterator<Item = &'static Key> + '_ {
    KEYS.iter().filter(move |k| k.section() == Some(section))
}

/// The names of the keys of `section` (`length, links, ...`).
pub fn section_keys(section: &str) -> Vec<&'static str> {
    section_rows(section).map(Key::name).collect()
}

/// The error for a path that names no key: it says which keys there are.
pub fn unknown_key(path: &str) -> Error {
    let (top, rest) = path.split_once('.').unwrap_or((path, ""));
    let hint = if rest.is_empty() || !top_names().contains(&top) {
        format!("a scene has the keys {}", top_names().join(", "))
    } else if !is_section(top) {
        format!("'{top}' is not a table")
    } else {
        format!("[{top}] has the keys {}", section_keys(top).join(", "))
    };
    Error::field(path, format!("unknown key: {hint}"))
}

impl Key {
    /// The section (`chain` of `chain.links`); `None` for a top-level key.
    pub fn section(&self) -> Option<&'static str> {
        self.path.split_once('.').map(|(s, _)| s)
    }

    /// The name within its section (`links` of `chain.links`).
    pub fn name(&self) -> &'static str {
        self.path.split_once('.').map_or(self.path, |(_, n)| n)
    }

    /// `value` in the form the key takes: a whole float becomes an integer
    /// for an integer key (`--vary chain.links=50:200:4` gives floats).
    /// Anything else is returned as it is, for [`check`] to judge.
    pub fn coerce(&self, value: toml::Value) -> toml::Value {
        match (self.ty, value) {
            (Type::Integer, toml::Value::Float(x)) if whole_i64(x) => {
                toml::Value::Integer(x as i64)
            }
            (_, v) => v,
        }
    }

    /// Checks the type of `value`; the error names the key and what it takes.
    pub fn check(&self, value: &toml::Value) -> Result<(), Error> {
        if let (Type::Integer, toml::Value::Float(x)) = (self.ty, value) {
            if whole_i64(*x) && *x >= 0.0 {
                return Err(Error::field(
                    self.path,
                    format!(
                        "must be an integer, written without a decimal point or exponent \
                         in a scene file (got {x:e}: write {})",
                        *x as i64
                    ),
                ));
            }
        }
        use toml::Value as V;
        let number = |v: &V| matches!(v, V::Integer(_) | V::Float(_));
        let ok = match (self.ty, value) {
            (Type::Number, v) => number(v),
            (Type::Integer, V::Integer(i)) => *i >= 0,
            (Type::Point, V::Array(a)) => a.len() == 2 && a.iter().all(number),
            (Type::Numbers, V::Array(a)) => a.iter().all(number),
            (Type::Text, V::String(_)) => true,
            (Type::OneOf(names), V::String(s)) => names.contains(&s.as_str()),
            (Type::Bool, V::Boolean(_)) => true,
            _ => false,
        };
        let accepted = match self.ty {
            Type::Integer => format!("an integer in {}", integer_range(self.path)),
            ty => ty.accepted(),
        };
        // A date-time, a string, a table or a bool where a number goes:
        // said so, in the words of a number key.
        let numeric = matches!(
            self.ty,
            Type::Number | Type::Integer | Type::Point | Type::Numbers
        );
        let kind = match value {
            V::Datetime(_) if numeric => "the date-time ",
            V::String(_) if numeric => "the string ",
            V::Table(_) if numeric => "the table ",
            V::Boolean(_) if numeric => "the bool ",
            _ => "",
        };
        let not_number = if self.ty == Type::Integer && !kind.is_empty() {
            ", not a number"
        } else {
            ""
        };
        if ok {
            Ok(())
        } else {
            Err(Error::field(
                self.path,
                format!(
                    "must be {accepted} (got {kind}{}{not_number})",
                    crate::error::echo_value(value)
                ),
            ))
        }
    }

    /// The error for this key missing; `kind` is the scene's start kind.
    fn missing(&self, kind: Option<StartKind>) -> Error {
        let why = match (self.ty, self.kinds, kind) {
            (Type::OneOf(names), _, _) => format!("required (one of {})", names.join(", ")),
            (_, Kinds::Only(kinds), Some(kind)) if kinds.len() < StartKind::ALL.len() => {
                format!("required for kind = \"{}\"", kind.as_str())
            }
            _ => format!("required ({}, no default)", self.doc.replace('`', "")),
        };
        Error::field(self.path, why)
    }
}

impl Type {
    /// What a value of this type is, for error messages.
    pub fn accepted(self) -> String {
        match self {
            Self::Number => "a number".into(),
            Self::Integer => format!("an integer in 0..={}", i64::MAX),
            Self::Point => "a point [x, y] of two numbers".into(),
            Self::Numbers => "a list of numbers [a, b, ...]".into(),
            Self::Text => "a string".into(),
            Self::OneOf(names) => format!("one of {}", names.join(", ")),
            Self::Bool => "true or false".into(),
        }
    }

    /// Its name in the README table.
    fn markdown(self) -> String {
        match self {
            Self::Number => "number".into(),
            Self::Integer => "integer".into(),
            Self::Point => "`[x, y]`".into(),
            Self::Numbers => "list of numbers".into(),
            Self::Text => "string".into(),
            Self::OneOf(names) => {
                let quoted: Vec<String> = names.iter().map(|n| format!("`\"{n}\"`")).collect();
                quoted.join(", ")
            }
            Self::Bool => "boolean".into(),
        }
    }
}

impl Literal {
    /// The value in a scene's TOML tree.
    pub fn to_toml(self) -> toml::Value {
        match self {
            Self::Number(x) => toml::Value::Float(x),
            Self::Integer(i) => toml::Value::Integer(i),
            Self::Point(p) => toml::Value::Array(p.map(toml::Value::Float).to_vec()),
            Self::Text(s) => toml::Value::String(s.into()),
            Self::Bool(b) => toml::Value::Boolean(b),
        }
    }

    fn markdown(self) -> String {
        match self {
            Self::Number(x) => format!("`{}`", number_text(x)),
            Self::Integer(i) => format!("`{i}`"),
            Self::Point([x, y]) => format!("`[{}, {}]`", number_text(x), number_text(y)),
            Self::Text(s) => format!("`\"{s}\"`"),
            Self::Bool(b) => format!("`{b}`"),
        }
    }
}

/// The range of an integer key, as its error states it (chain-ode checks
/// the ranges; the type check names them too, so that a 1.5 or a -3 gets
/// the same range as a 0 or a 10^7).
fn integer_range(path: &str) -> String {
    match path {
        "chain.links" => "1..=1000000".into(),
        "start.down" => "0..=chain.links-1".into(),
        "run.max_steps" => format!("1..={}", i64::MAX),
        _ => format!("0..={}", i64::MAX),
    }
}

/// Whether `x` is a whole number that an `i64` holds exactly.
fn whole_i64(x: f64) -> bool {
    // `i64::MAX as f64` is 2^63, the first float above i64::MAX.
    let bound = i64::MAX as f64;
    x.fract() == 0.0 && x > -bound && x < bound
}

/// `6`, `0.2`, `1e-8`: a number as a person writes it.
fn number_text(x: f64) -> String {
    if x != 0.0 && (x.abs() < 1e-3 || x.abs() >= 1e7) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The key whose value says which start kind a scene has, and so which of
/// the [`Kinds::Only`] keys it takes.
pub const START_KIND: &str = "start.kind";

/// The start kind of `tree`, if [`START_KIND`] is given and valid.
fn start_kind(tree: &toml::Table) -> Option<StartKind> {
    let name = lookup(tree, key(START_KIND)?)?.as_str()?;
    StartKind::ALL.into_iter().find(|k| k.as_str() == name)
}

/// Checks a scene's TOML tree against [`KEYS`] and returns it with every
/// omitted key that has a [`DefaultValue::Value`] filled in.
///
/// In order: every key is a row (else "unknown key", listing the keys
/// there are) of the right type; every `[start]` key is taken by the
/// scene's start kind; every required key is given. Ranges are not checked
/// here: chain-ode checks them when its types are built.
pub fn check(tree: &toml::Table) -> Result<toml::Table, Error> {
    for (top, value) in tree {
        if let Some(k) = key(top) {
            k.check(value)?;
        } else if is_section(top) {
            let Some(section) = value.as_table() else {
                return Err(Error::field(
                    top.as_str(),
                    format!(
                        "must be a table ([{top}]) (got {})",
                        crate::error::echo_value(value)
                    ),
                ));
            };
            for (name, value) in section {
                let path = format!("{top}.{name}");
                key(&path).ok_or_else(|| unknown_key(&path))?.check(value)?;
            }
        } else {
            return Err(unknown_key(top));
        }
    }

    let kind = start_kind(tree);
    if let Some(kind) = kind {
        let misplaced = KEYS
            .iter()
            .find(|k| !k.kinds.accepts(kind) && lookup(tree, k).is_some());
        if let Some(k) = misplaced {
            return Err(Error::field(
                k.path,
                format!(
                    "not a key of a {0} start (kind = \"{0}\" takes {1})",
                    kind.as_str(),
                    kind.keys().join(", ")
                ),
            ));
        }
    }

    let mut filled = tree.clone();
    for k in KEYS {
        let taken = match (k.kinds, kind) {
            (Kinds::Any, _) => true,
            // Without a (valid) kind, only the keys every kind takes.
            (Kinds::Only(kinds), None) => kinds.len() == StartKind::ALL.len(),
            (kinds, Some(kind)) => kinds.accepts(kind),
        };
        if !taken || lookup(tree, k).is_some() {
            continue;
        }
        match k.default {
            DefaultValue::Required => return Err(k.missing(kind)),
            DefaultValue::Value(v) => insert(&mut filled, k, v.to_toml()),
            DefaultValue::Computed(_) => {}
        }
    }
    Ok(filled)
}

/// The value of `k` in `tree`, if given.
fn lookup<'a>(tree: &'a toml::Table, k: &Key) -> Option<&'a toml::Value> {
    match k.section() {
        None => tree.get(k.path),
        Some(section) => tree.get(section)?.as_table()?.get(k.name()),
    }
}

/// Sets `k` in `tree`, making its section if needed (the section, if
/// present, has been checked to be a table).
fn insert(tree: &mut toml::Table, k: &Key, value: toml::Value) {
    match k.section() {
        None => {
            tree.insert(k.path.into(), value);
        }
        Some(section) => {
            if let Some(table) = tree
                .entry(section)
                .or_insert_with(|| toml::Value::Table(toml::Table::new()))
                .as_table_mut()
            {
                table.insert(k.name().into(), value);
            }
        }
    }
}

/// The line before the generated table in `scenes/README.md`.
pub const README_BEGIN: &str = "<!-- keys:begin -->";
/// The line after it.
pub const README_END: &str = "<!-- keys:end -->";

/// [`KEYS`] as the markdown table of `scenes/README.md`.
pub fn markdown_table() -> String {
    let mut s =
        String::from("| key | type | default | start kinds | meaning |\n|---|---|---|---|---|\n");
    for k in KEYS {
        let default = match k.default {
            DefaultValue::Required => "required".to_string(),
            DefaultValue::Value(v) => v.markdown(),
            DefaultValue::Computed(how) => how.to_string(),
        };
        let kinds = match k.kinds {
            Kinds::Any => "—".into(),
            Kinds::Only(kinds) if kinds.len() == StartKind::ALL.len() => "all".into(),
            Kinds::Only(kinds) => kinds
                .iter()
                .map(|k| k.as_str())
                .collect::<Vec<_>>()
                .join(", "),
        };
        let _ = writeln!(
            s,
            "| `{}` | {} | {default} | {kinds} | {} |",
            k.path,
            k.ty.markdown(),
            k.doc
        );
    }
    s
}

/// `readme` with the text between [`README_BEGIN`] and [`README_END`]
/// replaced by [`markdown_table`]; an error if the markers are missing.
pub fn with_markdown_table(readme: &str) -> Result<String, String> {
    let begin = readme
        .find(README_BEGIN)
        .ok_or_else(|| format!("no '{README_BEGIN}' line"))?;
    let start = begin + README_BEGIN.len();
    let end = readme[start..]
        .find(README_END)
        .map(|i| start + i)
        .ok_or_else(|| format!("no '{README_END}' line after '{README_BEGIN}'"))?;
    Ok(format!(
        "{}\n{}{}",
        &readme[..start],
        markdown_table(),
        &readme[end..]
    ))
}

/// Brings the key table of the scene README at `path` (`scenes/README.md`)
/// up to date, or with `check` only checks it: returns what was done, an
/// error if it is stale under `check` or cannot be read or written.
pub fn sync_readme(path: &std::path::Path, check: bool) -> Result<&'static str, String> {
    let name = path.display();
    let text = std::fs::read_to_string(path).map_err(|e| format!("{name}: {e}"))?;
    let want = with_markdown_table(&text).map_err(|e| format!("{name}: {e}"))?;
    if want == text {
        Ok("the key table is up to date")
    } else if check {
        Err(format!(
            "{name}: the key table differs from crates/fc-scene/src/schema.rs \
             (run `cargo xtask scene-keys`)"
        ))
    } else {
        std::fs::write(path, want).map_err(|e| format!("{name}: {e}"))?;
        Ok("the key table was rewritten")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_are_unique_and_sections_hold_the_start_kinds() {
        for (i, k) in KEYS.iter().enumerate() {
            assert!(
                KEYS[..i].iter().all(|o| o.path != k.path),
                "{} twice",
                k.path
            );
            assert!(k.path.split('.').count() <= 2, "{}", k.path);
            assert!(
                !k.doc.is_empty() && !k.doc.contains(['\n', '|']),
                "{}",
                k.path
            );
            // Start kinds are said of [start] keys, and only of them.
            let start = k.section() == Some("start");
            assert_eq!(start, matches!(k.kinds, Kinds::Only(_)), "{}", k.path);
            if let DefaultValue::Value(v) = k.default {
                k.check(&v.to_toml())
                    .unwrap_or_else(|e| panic!("default of {}: {e}", k.path));
            }
        }
        assert_eq!(
            top_names(),
            [
                "name",
                "description",
                "chain",
                "pivot",
                "start",
                "run",
                "model",
                "floor"
            ]
        );
        // Every kind takes `kind` and `p0` first; every [start] row is
        // taken by some kind (the rest of each list is the table's).
        for kind in StartKind::ALL {
            assert_eq!(kind.keys()[..2], ["kind", "p0"], "{kind:?}");
        }
        for k in section_rows("start") {
            assert!(
                StartKind::ALL.iter().any(|&kind| k.kinds.accepts(kind)),
                "{}",
                k.path
            );
        }
    }

    #[test]
    fn start_kind_names_are_its_serde_names() {
        for kind in StartKind::ALL {
            let v = toml::Value::try_from(kind).unwrap();
            assert_eq!(v.as_str(), Some(kind.as_str()));
        }
    }

    #[test]
    fn integer_keys_take_whole_floats_and_nothing_else_changes() {
        let links = key("chain.links").unwrap();
        let f = toml::Value::Float;
        assert_eq!(links.coerce(f(100.0)), toml::Value::Integer(100));
        assert_eq!(links.coerce(f(2.5)), f(2.5));
        assert!(links.check(&f(2.5)).is_err());
        assert!(links.check(&toml::Value::Integer(-1)).is_err());
        let damping = key("chain.damping").unwrap();
        assert_eq!(damping.coerce(f(1.0)), f(1.0));
        assert!(damping.check(&toml::Value::Integer(0)).is_ok());
        let three = toml::Value::Array(vec![f(3.0), f(0.0), f(1.0)]);
        let e = key("start.p1").unwrap().check(&three).unwrap_err();
        assert!(
            e.to_string().starts_with("start.p1: must be a point"),
            "{e}"
        );
    }

    #[test]
    fn unknown_keys_say_which_keys_there_are() {
        // The lists are the table's, in its order.
        let chain_keys: Vec<&str> = KEYS
            .iter()
            .filter_map(|k| k.path.strip_prefix("chain."))
            .collect();
        let chain_hint = format!("[chain] has the keys {}", chain_keys.join(", "));
        for (path, hint) in [
            (
                "colour",
                "a scene has the keys name, description, chain, pivot, start, run, model, floor",
            ),
            ("chain.lenght", chain_hint.as_str()),
            ("name.x", "'name' is not a table"),
        ] {
            let e = unknown_key(path).to_string();
            assert_eq!(e, format!("{path}: unknown key: {hint}"));
        }
    }

    #[test]
    fn numbers_are_written_as_people_write_them() {
        assert_eq!(number_text(6.0), "6");
        assert_eq!(number_text(0.2), "0.2");
        assert_eq!(number_text(1e-8), "1e-8");
        assert_eq!(number_text(0.0), "0");
    }

    /// Every scene path the code of the crates over scenes spells out
    /// (outside its tests: in error fields, overrides, flags) is a row of
    /// the table.
    #[test]
    fn every_path_named_in_the_code_is_a_row() {
        let crates = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
        let sections: Vec<String> = top_names()
            .into_iter()
            .filter(|t| is_section(t))
            .map(|s| format!("{s}."))
            .collect();
        let mut seen = 0;
        // The crates' files, their module folders (`plot/`) included.
        let mut files = vec![];
        let mut dirs: Vec<std::path::PathBuf> = [
            "fc-scene",
            "fc-batch",
            "fc-study",
            "fc-viewer",
            "fc-paper-figures",
            "falling-chain",
        ]
        .iter()
        .map(|c| std::path::Path::new(crates).join(c).join("src"))
        .collect();
        while let Some(d) = dirs.pop() {
            for entry in std::fs::read_dir(d).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    dirs.push(path);
                } else {
                    files.push(path);
                }
            }
        }
        for path in files {
            let text = std::fs::read_to_string(&path).unwrap();
            let code = text.split("#[cfg(test)]").next().unwrap_or_default();
            for (i, _) in code.match_indices('"') {
                let rest = &code[i + 1..];
                let end = rest
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '.'))
                    .unwrap_or(rest.len());
                let word = &rest[..end];
                if rest[end..].starts_with('"') && sections.iter().any(|s| word.starts_with(s)) {
                    // An element path (`start.p1.0`) is checked by its key.
                    let key_path: Vec<&str> = word.splitn(3, '.').take(2).collect();
                    assert!(
                        key(&key_path.join(".")).is_some(),
                        "{}: \"{word}\" is not a scene key",
                        path.display()
                    );
                    seen += 1;
                }
            }
        }
        assert!(seen > 10, "the scan found {seen} paths");
    }

    /// `scenes/README.md` carries the table as rendered: it cannot drift.
    /// `cargo xtask scene-keys` rewrites it.
    #[test]
    fn the_readme_table_is_the_rendered_table() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/README.md");
        let readme = std::fs::read_to_string(path).unwrap();
        let want = with_markdown_table(&readme).unwrap();
        assert!(
            readme == want,
            "scenes/README.md's key table differs from crates/fc-scene/src/schema.rs \
             (run `cargo xtask scene-keys`); it should read:\n{}",
            markdown_table()
        );
        for k in KEYS {
            assert!(readme.contains(&format!("| `{}` |", k.path)), "{}", k.path);
        }
    }
}
