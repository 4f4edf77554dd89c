//! Scenes: a chain, how it starts, and how to run it, as a TOML file.
//!
//! ```toml
//! name = "span-d3"                 # default: the file's stem ("scene" from a string)
//! description = "Report Fig. 7b"   # default: ""
//!
//! [chain]
//! length = 6.0      # L, default 6
//! links = 50        # n, required
//! mass = 0.2        # m per rod, default 0.2
//! gravity = 1.0     # g, default 1
//! damping = 0.0005  # r, default 0
//!
//! [start]
//! kind = "catenary" # required: "stretched" | "catenary" | "folded" | "angles"
//! p0 = [0.0, 0.0]   # pivot P0, every kind, default [0, 0]
//! p1 = [3.0, 0.0]   # release point P1, stretched and catenary only, required there
//! # down = 25       # folded only: rods hanging down, default links / 2 (rounded down)
//! # angles = [...]  # angles only, required: phi_1..phi_n (rad)
//! # rates = [...]   # angles only: w_1..w_n (rad/time), default all 0
//!
//! [run]
//! t_end = 4.157     # required
//! method = "rk4"    # default "rk4"; any name chain_ode::Method parses
//! dt = 0.01         # fixed step (rk4), default 0.01
//! rtol = 1e-8       # adaptive methods, default 1e-8
//! atol = 1e-10      # adaptive methods, default 1e-10
//! output_dt = 0.01  # spacing of recorded samples, default 0.01
//! max_steps = 100000000  # step budget, default 1e8
//! h_min = 0.0       # smallest adaptive step (0: the rounding limit), default 0
//! ```
//!
//! Unknown keys, and keys of another start kind, are errors naming the key.
//! Integers are accepted wherever a number is expected. Loading checks the
//! structure and the types only; ranges are checked by chain-ode when the
//! chain-ode types are built ([`Scene::chain`], [`Scene::options`], ...).

use std::fmt;
use std::path::Path;
use std::str::FromStr;

use chain_ode::{solve, Chain, Method, SolveOptions, Start, State, Trajectory};
use serde::de::DeserializeOwned;
use serde::Deserialize;

use crate::error::Error;
use crate::overrides;

/// Default `chain.length` (the report's `L`).
pub const DEFAULT_LENGTH: f64 = 6.0;
/// Default `chain.mass` (per rod, the report's `m`).
pub const DEFAULT_MASS: f64 = 0.2;
/// Default `chain.gravity`.
pub const DEFAULT_GRAVITY: f64 = 1.0;
/// Default `chain.damping` (`r`).
pub const DEFAULT_DAMPING: f64 = 0.0;
/// Default `start.p0`.
pub const DEFAULT_P0: [f64; 2] = [0.0, 0.0];
/// Default `run.method`.
pub const DEFAULT_METHOD: &str = "rk4";
/// Default `run.dt`.
pub const DEFAULT_DT: f64 = 0.01;
/// Default `run.rtol`.
pub const DEFAULT_RTOL: f64 = 1e-8;
/// Default `run.atol`.
pub const DEFAULT_ATOL: f64 = 1e-10;
/// Default `run.output_dt`.
pub const DEFAULT_OUTPUT_DT: f64 = 0.01;
/// Default `run.max_steps`.
pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;

/// Keys at the top of a scene file.
pub const TOP_KEYS: [&str; 5] = ["name", "description", "chain", "start", "run"];
/// Keys of `[chain]`.
pub const CHAIN_KEYS: [&str; 5] = ["length", "links", "mass", "gravity", "damping"];
/// Keys of `[start]` (each kind takes a subset, see [`StartKind::keys`]).
pub const START_KEYS: [&str; 6] = ["kind", "p0", "p1", "down", "angles", "rates"];
/// Keys of `[run]`.
pub const RUN_KEYS: [&str; 8] = [
    "t_end",
    "method",
    "dt",
    "rtol",
    "atol",
    "output_dt",
    "max_steps",
    "h_min",
];

/// The keys of the section table `name`, if it is one.
pub fn section_keys(name: &str) -> Option<&'static [&'static str]> {
    match name {
        "chain" => Some(&CHAIN_KEYS),
        "start" => Some(&START_KEYS),
        "run" => Some(&RUN_KEYS),
        _ => None,
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    name: Option<String>,
    description: Option<String>,
    chain: Option<toml::Table>,
    start: Option<toml::Table>,
    run: Option<toml::Table>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ChainSection {
    length: Option<f64>,
    links: Option<usize>,
    mass: Option<f64>,
    gravity: Option<f64>,
    damping: Option<f64>,
}

/// The kinds of start a scene can ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
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

    /// Its name in a scene file.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Stretched => "stretched",
            Self::Catenary => "catenary",
            Self::Folded => "folded",
            Self::Angles => "angles",
        }
    }

    /// The `[start]` keys this kind takes.
    pub fn keys(self) -> &'static [&'static str] {
        match self {
            Self::Stretched | Self::Catenary => &["kind", "p0", "p1"],
            Self::Folded => &["kind", "p0", "down"],
            Self::Angles => &["kind", "p0", "angles", "rates"],
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StartSection {
    kind: Option<StartKind>,
    p0: Option<[f64; 2]>,
    p1: Option<[f64; 2]>,
    down: Option<usize>,
    angles: Option<Vec<f64>>,
    rates: Option<Vec<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RunSection {
    t_end: Option<f64>,
    method: Option<String>,
    dt: Option<f64>,
    rtol: Option<f64>,
    atol: Option<f64>,
    output_dt: Option<f64>,
    max_steps: Option<u64>,
    h_min: Option<f64>,
}

/// A scene: its TOML tree (kept, so that overrides can be applied to it) and
/// the values read from it with defaults filled in.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    tree: toml::Table,
    name: String,
    description: String,
    chain: Chain,
    start: Start,
    method: String,
    options: SolveOptions,
}

/// Everything a run needs, validated.
#[derive(Clone, Debug, PartialEq)]
pub struct Prepared {
    pub chain: Chain,
    pub state: State,
    pub method: Method,
    pub options: SolveOptions,
}

impl Prepared {
    /// Runs it.
    pub fn solve(&self) -> Result<Trajectory, Error> {
        Ok(solve(&self.chain, &self.state, self.method, &self.options)?)
    }
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// Deserialises `table` as `T`. On failure, finds the key whose value alone
/// fails (an unknown key or a wrong type) to name it in the error. Every
/// field of `T` is optional, so a table of a single key fails only because
/// of that key.
fn from_table<T: DeserializeOwned>(table: &toml::Table, prefix: &str) -> Result<T, Error> {
    table.clone().try_into::<T>().map_err(|whole| {
        for (key, value) in table {
            let single: toml::Table = [(key.clone(), value.clone())].into_iter().collect();
            if let Err(e) = single.try_into::<T>() {
                return Error::field(join(prefix, key), e.message());
            }
        }
        let subject = if prefix.is_empty() { "scene" } else { prefix };
        Error::field(subject, whole.message())
    })
}

fn required<T>(value: Option<T>, field: &str, why: impl fmt::Display) -> Result<T, Error> {
    value.ok_or_else(|| Error::field(field, format!("required {why}")))
}

impl Scene {
    /// Reads and parses a scene file. A missing `name` becomes the file's stem.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, Error> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| Error::read("scene", path, e))?;
        let mut tree = parse_tree(&text, &format!("'{}'", path.display()))?;
        if !tree.contains_key("name") {
            let stem = path
                .file_stem()
                .map_or("scene".into(), |s| s.to_string_lossy());
            tree.insert("name".into(), toml::Value::String(stem.into_owned()));
        }
        Self::from_tree(tree)
    }

    /// Parses a scene from TOML text. A missing `name` becomes `"scene"`.
    pub fn from_toml_str(text: &str) -> Result<Self, Error> {
        Self::from_tree(parse_tree(text, "the scene text")?)
    }

    /// Reads a scene from its TOML tree (the form overrides act on).
    pub fn from_tree(tree: toml::Table) -> Result<Self, Error> {
        let file: SceneFile = from_table(&tree, "")?;
        let chain = from_table::<ChainSection>(&file.chain.unwrap_or_default(), "chain")?;
        let start_table = file.start.unwrap_or_default();
        let start = from_table::<StartSection>(&start_table, "start")?;
        let run = from_table::<RunSection>(&file.run.unwrap_or_default(), "run")?;

        let chain = Chain {
            length: chain.length.unwrap_or(DEFAULT_LENGTH),
            links: required(
                chain.links,
                "chain.links",
                "(the number of rods, no default)",
            )?,
            mass: chain.mass.unwrap_or(DEFAULT_MASS),
            gravity: chain.gravity.unwrap_or(DEFAULT_GRAVITY),
            damping: chain.damping.unwrap_or(DEFAULT_DAMPING),
        };

        let kinds = StartKind::ALL.map(StartKind::as_str).join(", ");
        let kind = required(start.kind, "start.kind", format_args!("(one of {kinds})"))?;
        if let Some(key) = start_table
            .keys()
            .find(|k| !kind.keys().contains(&k.as_str()))
        {
            return Err(Error::field(
                format!("start.{key}"),
                format!(
                    "not a key of a {0} start (kind = \"{0}\" takes {1})",
                    kind.as_str(),
                    kind.keys().join(", ")
                ),
            ));
        }
        let p0 = start.p0.unwrap_or(DEFAULT_P0);
        let needed = format!("for kind = \"{}\"", kind.as_str());
        let start = match kind {
            StartKind::Stretched => Start::Stretched {
                p0,
                p1: required(start.p1, "start.p1", &needed)?,
            },
            StartKind::Catenary => Start::Catenary {
                p0,
                p1: required(start.p1, "start.p1", &needed)?,
            },
            StartKind::Folded => Start::Folded {
                p0,
                down: start.down,
            },
            StartKind::Angles => Start::Angles {
                p0,
                angles: required(start.angles, "start.angles", &needed)?,
                rates: start.rates,
            },
        };

        let defaults = SolveOptions::default();
        let options = SolveOptions {
            t_end: required(run.t_end, "run.t_end", "(the end time, no default)")?,
            dt: run.dt.unwrap_or(DEFAULT_DT),
            rtol: run.rtol.unwrap_or(DEFAULT_RTOL),
            atol: run.atol.unwrap_or(DEFAULT_ATOL),
            output_dt: Some(run.output_dt.unwrap_or(DEFAULT_OUTPUT_DT)),
            max_steps: run.max_steps.unwrap_or(DEFAULT_MAX_STEPS),
            h_min: run.h_min.unwrap_or(defaults.h_min),
        };

        Ok(Self {
            name: file.name.unwrap_or_else(|| "scene".into()),
            description: file.description.unwrap_or_default(),
            chain,
            start,
            method: run.method.unwrap_or_else(|| DEFAULT_METHOD.into()),
            options,
            tree,
        })
    }

    /// This scene with `KEY=VALUE` overrides applied to its tree, in order
    /// (see [`crate::overrides`]): `["chain.links=100", "start.p1.0=2.5"]`.
    pub fn with_overrides<S: AsRef<str>>(&self, assignments: &[S]) -> Result<Self, Error> {
        let mut tree = self.tree.clone();
        overrides::apply(&mut tree, assignments)?;
        Self::from_tree(tree)
    }

    /// This scene with the value at one dotted `path` replaced.
    pub fn with_value(&self, path: &str, value: toml::Value) -> Result<Self, Error> {
        let mut tree = self.tree.clone();
        overrides::set_path(&mut tree, path, value)?;
        Self::from_tree(tree)
    }

    /// The scene's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// What the scene is (free text).
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The TOML tree as given (after overrides), without defaults.
    pub fn tree(&self) -> &toml::Table {
        &self.tree
    }

    /// The scene as TOML text (after overrides).
    pub fn to_toml_string(&self) -> String {
        toml::to_string(&self.tree).unwrap_or_default()
    }

    /// The chain, validated by chain-ode (the error names the field).
    pub fn chain(&self) -> Result<Chain, Error> {
        self.chain.validate()?;
        Ok(self.chain.clone())
    }

    /// The start as written (built into a state by [`Scene::state`]).
    pub fn start(&self) -> Start {
        self.start.clone()
    }

    /// The initial state of the scene's chain (validated).
    pub fn state(&self) -> Result<State, Error> {
        Ok(self.start.state(&self.chain()?)?)
    }

    /// The integration method (`run.method` parsed by chain-ode).
    pub fn method(&self) -> Result<Method, Error> {
        Ok(Method::from_str(&self.method)?)
    }

    /// The run's options, validated by chain-ode.
    pub fn options(&self) -> Result<SolveOptions, Error> {
        self.options.validate()?;
        Ok(self.options.clone())
    }

    /// Validates everything a run needs, in the order chain, start, run.
    pub fn prepare(&self) -> Result<Prepared, Error> {
        let chain = self.chain()?;
        let state = self.start.state(&chain)?;
        Ok(Prepared {
            chain,
            state,
            method: self.method()?,
            options: self.options()?,
        })
    }
}

/// Parses TOML text into a tree; a syntax error names the place.
fn parse_tree(text: &str, source: &str) -> Result<toml::Table, Error> {
    toml::from_str::<toml::Table>(text).map_err(|e| {
        let place = e.span().map_or(String::new(), |span| {
            let before = &text[..span.start.min(text.len())];
            let line = before.matches('\n').count() + 1;
            let column = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
            format!(" at line {line}, column {column}")
        });
        Error::field(
            "scene",
            format!("invalid TOML in {source}{place}: {}", e.message()),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPAN: &str = r#"
name = "span-d3"
description = "test"
[chain]
links = 10
damping = 0.0005
[start]
kind = "catenary"
p1 = [3, 0]
[run]
t_end = 4
"#;

    #[test]
    fn defaults_fill_what_is_left_out_and_integers_are_numbers() {
        let s = Scene::from_toml_str(SPAN).unwrap();
        let c = s.chain().unwrap();
        assert_eq!((c.length, c.links, c.mass, c.gravity), (6.0, 10, 0.2, 1.0));
        assert_eq!(
            s.start(),
            Start::Catenary {
                p0: [0.0, 0.0],
                p1: [3.0, 0.0]
            }
        );
        let o = s.options().unwrap();
        assert_eq!((o.t_end, o.dt, o.output_dt), (4.0, 0.01, Some(0.01)));
        assert_eq!(s.method().unwrap().as_str(), "rk4");
        assert_eq!(s.name(), "span-d3");
    }

    #[test]
    fn every_listed_key_is_read() {
        // A key missing from a section struct would fail here as "unknown field".
        for (section, keys) in [
            ("chain", &CHAIN_KEYS[..]),
            ("start", &START_KEYS[..]),
            ("run", &RUN_KEYS[..]),
        ] {
            for key in keys {
                let single: toml::Table = [(key.to_string(), toml::Value::Integer(0))]
                    .into_iter()
                    .collect();
                let e = match section {
                    "chain" => from_table::<ChainSection>(&single, section).err(),
                    "start" => from_table::<StartSection>(&single, section).err(),
                    _ => from_table::<RunSection>(&single, section).err(),
                };
                if let Some(e) = e {
                    assert!(!e.to_string().contains("unknown field"), "{e}");
                }
            }
        }
    }

    #[test]
    fn unknown_and_misplaced_keys_are_named() {
        let cases = [
            (SPAN.replace("damping", "dampnig"), "chain.dampnig: "),
            (
                SPAN.replace("p1 = [3, 0]", "p1 = [3, 0]\ndown = 2"),
                "start.down: ",
            ),
            (format!("colour = 1\n{SPAN}"), "colour: "),
            (SPAN.replace("links = 10", "links = 10.5"), "chain.links: "),
            (SPAN.replace("links = 10", ""), "chain.links: "),
            (SPAN.replace("t_end = 4", ""), "run.t_end: "),
            (SPAN.replace("p1 = [3, 0]", ""), "start.p1: "),
            (SPAN.replace("\"catenary\"", "\"zigzag\""), "start.kind: "),
            (SPAN.replace("p1 = [3, 0]", "p1 = [3, 0, 1]"), "start.p1: "),
            (SPAN.replace("[run]", "[run\n"), "scene: "),
        ];
        for (text, prefix) in cases {
            let e = Scene::from_toml_str(&text).unwrap_err();
            assert!(e.to_string().starts_with(prefix), "{prefix} vs {e}");
            assert!(!e.to_string().contains('\n'), "{e}");
        }
    }

    #[test]
    fn overrides_change_any_key_and_validation_names_fields() {
        let s = Scene::from_toml_str(SPAN).unwrap();
        let t = s
            .with_overrides(&["chain.links=100", "start.p1.0=2.5", "run.t_end=1"])
            .unwrap();
        assert_eq!(t.chain().unwrap().links, 100);
        assert_eq!(
            t.start(),
            Start::Catenary {
                p0: [0.0, 0.0],
                p1: [2.5, 0.0]
            }
        );
        let e = s.with_overrides(&["chain.links=0"]).unwrap().prepare();
        assert!(e.unwrap_err().to_string().starts_with("chain.links: "));
        let e = s.with_overrides(&["chain.length=2"]).unwrap().prepare();
        assert!(e.unwrap_err().to_string().starts_with("chain.length: "));
        let e = s
            .with_overrides(&["run.method=nonesuch"])
            .unwrap()
            .prepare();
        assert!(e.unwrap_err().to_string().starts_with("run.method: "));
        let e = s.with_overrides(&["run.dt=-1"]).unwrap().prepare();
        assert!(e.unwrap_err().to_string().starts_with("run.dt: "));
    }
}
