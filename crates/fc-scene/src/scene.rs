//! Scenes: a chain, how it starts, and how to run it, as a TOML file.
//!
//! ```toml
//! name = "span-d3"
//! description = "Report Fig. 7b"
//!
//! [chain]
//! links = 50
//! damping = 0.0005
//!
//! [start]
//! kind = "catenary"
//! p1 = [3.0, 0.0]
//!
//! [run]
//! t_end = 4.157
//! ```
//!
//! The keys, their types, defaults and the start kinds that take them are
//! the rows of [`crate::schema::KEYS`] (rendered in `scenes/README.md`).
//! Loading checks the tree against that table ([`schema::check`]: unknown
//! keys, keys of another start kind, types, required keys; defaults filled
//! in), then reads it into the serde structs below; ranges are checked by
//! chain-ode when the chain-ode types are built ([`Scene::chain`],
//! [`Scene::options`], ...).

use std::path::Path;
use std::str::FromStr;

use chain_ode::load::Coefficients;
use chain_ode::report::ReportModel;
use chain_ode::{
    solve, Chain, ChainParams, Floor, FloorLaw, Method, ModelKind, Pivot, Profile, SolveOptions,
    Start, State, Trajectory,
};
use serde::{Deserialize, Serialize};

use crate::error::Error;
use crate::overrides;
use crate::schema::{self, StartKind};

/// A scene file after [`schema::check`]: one field per row of
/// [`schema::KEYS`] (a test keeps them equal). Keys with a default are
/// plain values; the others are options.
#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    name: Option<String>,
    description: String,
    chain: ChainSection,
    pivot: PivotSection,
    start: StartSection,
    run: RunSection,
    model: ModelSection,
    /// Absent from most scenes: every `[floor]` key is optional.
    #[serde(default)]
    floor: FloorSection,
}

/// `[floor]`: a floor the chain falls onto ([`chain_ode::Floor`]); any key
/// given makes one, the others take their defaults.
#[derive(Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct FloorSection {
    height: Option<f64>,
    angle: Option<f64>,
    stiffness: Option<f64>,
    damping: Option<f64>,
    friction: Option<f64>,
    slip_speed: Option<f64>,
    law: Option<String>,
    restitution: Option<f64>,
}

impl FloorSection {
    /// The floor, if any key is given, with the defaults of the schema for
    /// the chain `c` (its `m`, `g`, `l = L / n`, `L`, and whether it has
    /// elastic links): the law `penalty` when the scene gives one of the
    /// penalty's keys or elastic links, else `constraint`.
    fn floor(&self, c: &ChainParams) -> Result<Option<Floor>, Error> {
        let FloorSection {
            height,
            angle,
            stiffness,
            damping,
            friction,
            slip_speed,
            ref law,
            restitution,
        } = *self;
        let any = [
            height,
            angle,
            stiffness,
            damping,
            friction,
            slip_speed,
            restitution,
        ]
        .iter()
        .any(Option::is_some)
            || law.is_some();
        if !any {
            return Ok(None);
        }
        let penalty_keys = stiffness.is_some() || damping.is_some() || slip_speed.is_some();
        let law = match law.as_deref() {
            Some(name) => FloorLaw::ALL
                .into_iter()
                .find(|l| l.as_str() == name)
                .ok_or_else(|| chain_ode::InvalidParameter {
                    field: "floor.law",
                    accepted: "one of penalty, constraint".into(),
                    got: name.to_string(),
                })?,
            None if penalty_keys || c.axial_stiffness.is_some() => FloorLaw::Penalty,
            None => FloorLaw::Constraint,
        };
        let l = c.length / c.links.max(1) as f64;
        let g = if c.gravity > 0.0 { c.gravity } else { 1.0 };
        Ok(Some(Floor {
            height,
            angle: angle.unwrap_or(0.0),
            stiffness: stiffness.unwrap_or(1e4 * c.mass * g / l),
            damping: damping.unwrap_or(0.0),
            friction: friction.unwrap_or(0.0),
            slip_speed: slip_speed.unwrap_or(1e-3 * (g * c.length).sqrt()),
            law,
            restitution: restitution.unwrap_or(0.0),
        }))
    }
}

/// `[model]`: which equations a scene runs.
#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ModelSection {
    report: bool,
}

/// `[chain]`: the chain's fields, and the loads' coefficients by key (the
/// rows of [`chain_ode::load::coefficient_keys`], such as `air_drag`; any
/// other key `schema::check` has refused already).
#[derive(Debug, Deserialize, Serialize)]
struct ChainSection {
    length: f64,
    links: usize,
    mass: f64,
    gravity: f64,
    damping: f64,
    axial_stiffness: Option<f64>,
    axial_damping: f64,
    bending_stiffness: f64,
    tip_mass: f64,
    taper: f64,
    rod_masses: Option<Vec<f64>>,
    rod_lengths: Option<Vec<f64>>,
    #[serde(flatten)]
    loads: std::collections::BTreeMap<String, f64>,
}

/// The pivot's motion ([`chain_ode::Pivot`]).
#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct PivotSection {
    acceleration: [f64; 2],
    amplitude: [f64; 2],
    frequency: f64,
    jerk: [f64; 2],
    jerk_time: f64,
    release: Option<f64>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct StartSection {
    kind: StartKind,
    p0: [f64; 2],
    p1: Option<[f64; 2]>,
    down: Option<usize>,
    angles: Option<Vec<f64>>,
    rates: Option<Vec<f64>>,
}

#[derive(Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct RunSection {
    t_end: f64,
    method: String,
    dt: f64,
    rtol: f64,
    atol: f64,
    output_dt: f64,
    max_steps: u64,
    h_min: f64,
    rho_inf: f64,
}

impl SceneFile {
    /// Checks `tree` against the schema and reads it.
    fn read(tree: &toml::Table) -> Result<Self, Error> {
        // After the check, serde cannot fail but on a key missing from
        // these structs (a test keeps them and the table equal).
        schema::check(tree)?
            .try_into()
            .map_err(|e: toml::de::Error| Error::field("scene", e.message()))
    }
}

/// A scene: its TOML tree (kept, so that overrides can be applied to it) and
/// the values read from it with defaults filled in.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    tree: toml::Table,
    name: String,
    description: String,
    /// As read; checked when a [`Chain`] is built ([`Scene::chain`]).
    chain: ChainParams,
    start: Start,
    method: String,
    options: SolveOptions,
    /// `model.report`: the report's own model instead of the corrected one.
    report: bool,
}

/// Everything a run needs, validated.
#[derive(Clone, Debug, PartialEq)]
pub struct Prepared {
    pub chain: Chain,
    pub state: State,
    pub method: Method,
    pub options: SolveOptions,
    /// `Some` with `model.report = true`: the report's model
    /// ([`ReportModel::AS_CODED`]), run by [`chain_ode::solve`] on [`chain_ode::ReportChain`] in
    /// its own clock; `None`, the corrected model.
    pub report: Option<ReportModel>,
}

impl Prepared {
    /// Refuses `concurrent` runs of it at once (a study's `--jobs`) that
    /// would not fit in the memory the machine can give
    /// ([`SolveOptions::check_memory`]; one run is checked by
    /// [`Scene::prepare`] already); `samples`: whether each keeps the
    /// scene's recorded samples.
    pub fn check_memory(&self, concurrent: usize, samples: bool) -> Result<(), Error> {
        let mut options = self.options.clone();
        if !samples {
            options.output_dt = None;
        }
        options.check_memory(&self.chain, self.method, concurrent)?;
        Ok(())
    }

    /// Runs it.
    pub fn solve(&self) -> Result<Trajectory, Error> {
        Ok(solve(
            self.model(),
            &self.state,
            self.method,
            &self.options,
        )?)
    }

    /// [`Prepared::solve`], tracking the peaks of the pivot's force and the
    /// tensions only with `track_forces` (else
    /// `chain_ode::Solve::without_force_peaks`: a study that does not
    /// measure them does not pay for them).
    pub fn solve_measuring(&self, track_forces: bool) -> Result<Trajectory, Error> {
        let solve = chain_ode::Solve::new(self.model(), &self.state, self.method, &self.options);
        Ok(if track_forces {
            solve.run()
        } else {
            solve.without_force_peaks().run()
        }?)
    }

    /// The model the run runs ([`ModelKind::choose`]: the report's with
    /// `model.report = true`, else the chain's rigid or elastic one).
    pub fn model(&self) -> ModelKind {
        ModelKind::choose(&self.chain, self.report)
    }

    /// Checks the start as the run would, without running: the start the
    /// model builds (a floor's start overlap, the angles' bounds) is the
    /// one [`Prepared::solve`] would refuse (O(n), no integrator).
    pub fn check_start(&self) -> Result<(), Error> {
        use chain_ode::Model as _;
        let mut model = self.model();
        model.initial_state(&self.state)?;
        Ok(())
    }

    /// [`Prepared::solve`] with `cancel` in its options: the caller can stop
    /// the run, and read the time it has reached ([`Cancel::reached`]) from
    /// another thread.
    pub fn solve_with(&self, cancel: chain_ode::Cancel) -> Result<Trajectory, Error> {
        let options = SolveOptions {
            cancel: Some(cancel),
            ..self.options.clone()
        };
        Ok(solve(self.model(), &self.state, self.method, &options)?)
    }

    /// An error naming `model.report` if this is the report's model: for
    /// the commands that run the corrected model only (`what`).
    pub fn require_corrected(&self, what: &str) -> Result<(), Error> {
        if self.report.is_some() {
            return Err(Error::field(
                "model.report",
                format!("must be false for {what} (it runs the corrected model only)"),
            ));
        }
        Ok(())
    }
}

impl Scene {
    /// Reads and parses a scene file. A missing `name` becomes the file's stem.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, Error> {
        let path = path.as_ref();
        let text = read_scene_text(path)?;
        let mut tree = parse_tree(&text, &format!("'{}'", crate::error::echo_path(path)))?;
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
        let SceneFile {
            name,
            description,
            chain,
            pivot,
            start,
            run,
            model,
            floor,
        } = SceneFile::read(&tree)?;
        // Exhaustive both ways: a field of `ChainParams` without its key
        // here, or a key without its field, does not compile.
        let ChainSection {
            length,
            links,
            mass,
            gravity,
            damping,
            axial_stiffness,
            axial_damping,
            bending_stiffness,
            tip_mass,
            taper,
            rod_masses,
            rod_lengths,
            loads,
        } = chain;
        let PivotSection {
            acceleration,
            amplitude,
            frequency,
            jerk,
            jerk_time,
            release,
        } = pivot;
        let mut chain = ChainParams {
            length,
            links,
            mass,
            gravity,
            damping,
            axial_stiffness,
            axial_damping,
            bending_stiffness,
            tip_mass,
            pivot: Pivot {
                acceleration,
                amplitude,
                frequency,
                jerk,
                jerk_time,
                release,
            },
            profile: Profile {
                taper,
                masses: rod_masses,
                lengths: rod_lengths,
            },
            floor: None,
            coefficients: Coefficients::default(),
        };
        chain.floor = floor.floor(&chain)?;
        for (name, x) in loads {
            let key = chain_ode::load::coefficient_keys()
                .find(|k| k.split_once('.').map(|(_, field)| field) == Some(name.as_str()))
                .ok_or_else(|| Error::field("chain", format!("'{name}' is no load's key")))?;
            chain.coefficients.set(key, x);
        }
        // `schema::check` has made sure that each kind's required keys are there.
        let p0 = start.p0;
        let start = match (start.kind, start.p1, start.angles) {
            (StartKind::Stretched, Some(p1), _) => Start::Stretched { p0, p1 },
            (StartKind::Catenary, Some(p1), _) => Start::Catenary { p0, p1 },
            (StartKind::Folded, ..) => Start::Folded {
                p0,
                down: start.down,
            },
            (StartKind::Angles, _, Some(angles)) => Start::Angles {
                p0,
                angles,
                rates: start.rates,
            },
            (kind, ..) => {
                return Err(Error::field(
                    "start",
                    format!("incomplete {} start", kind.as_str()),
                ))
            }
        };
        let options = SolveOptions {
            t_end: run.t_end,
            dt: run.dt,
            rtol: run.rtol,
            atol: run.atol,
            output_dt: Some(run.output_dt),
            max_steps: run.max_steps,
            h_min: run.h_min,
            cancel: None,
            rho_inf: run.rho_inf,
        };
        Ok(Self {
            name: name.unwrap_or_else(|| "scene".into()),
            description,
            chain,
            start,
            method: run.method,
            options,
            report: model.report,
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

    /// This scene with several values replaced at once, in order, checked
    /// together: how a start's kind changes with its own keys
    /// (`[("start.kind", "angles"), ("start.angles", [...])]`), which one
    /// value at a time cannot do.
    pub fn with_values(&self, values: &[(&str, toml::Value)]) -> Result<Self, Error> {
        let mut tree = self.tree.clone();
        for (path, value) in values {
            overrides::set_path(&mut tree, path, value.clone())?;
        }
        Self::from_tree(tree)
    }

    /// This scene without the key at `path`, which takes its default again
    /// ([`overrides::unset_path`]; a required key is refused).
    pub fn without(&self, path: &str) -> Result<Self, Error> {
        let mut tree = self.tree.clone();
        overrides::unset_path(&mut tree, path)?;
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
        Chain::new(self.chain.clone()).map_err(|e| self.named_as_given(e))
    }

    /// `e`, where it is about a floor key the scene does not set: that
    /// key's default is derived from the chain (`floor.stiffness = 1e4 m g
    /// / l`, `floor.slip_speed = 1e-3 sqrt(g L)`), and the message says so
    /// and names the keys it comes from, not a value the user never gave.
    fn named_as_given(&self, e: chain_ode::InvalidParameter) -> Error {
        let derived = match e.field {
            "floor.stiffness" => {
                "1e4 m g / l (chain.mass, chain.gravity, chain.length / chain.links)"
            }
            "floor.slip_speed" => "1e-3 sqrt(g L) (chain.gravity, chain.length)",
            _ => return e.into(),
        };
        let key = e.field.split_once('.').map_or(e.field, |(_, k)| k);
        let given = match self.tree.get("floor") {
            Some(toml::Value::Table(t)) => t.contains_key(key),
            _ => false,
        };
        if given {
            return e.into();
        }
        Error::field(
            e.field,
            format!(
                "not set, and its default {derived} = {} is out of its range ({}): set {} or \
                 change those keys",
                crate::error::echo(&e.got),
                e.accepted,
                e.field
            ),
        )
    }

    /// The chain's parameters as read, before chain-ode's range checks.
    pub fn chain_params(&self) -> &ChainParams {
        &self.chain
    }

    /// This scene with every `chain.*` key set from `chain` (so that a
    /// chain-ode [`Chain`], such as [`Chain::refined`]'s, becomes a scene
    /// whole: every field is written, none is left at the old scene's value).
    pub fn with_chain(&self, chain: &Chain) -> Result<Self, Error> {
        // Exhaustive: a new field of `ChainParams` does not compile here
        // until it is written to its key.
        let ChainParams {
            length,
            links,
            mass,
            gravity,
            damping,
            axial_stiffness,
            axial_damping,
            bending_stiffness,
            tip_mass,
            pivot,
            profile,
            // The `[floor]` keys are the scene's own: kept as they are.
            floor: _,
            coefficients,
        } = chain.params().clone();
        let links = i64::try_from(links)
            .map_err(|_| Error::field("chain.links", format!("too large (got {links})")))?;
        let mut tree = self.tree.clone();
        for (path, value) in [
            ("chain.length", toml::Value::Float(length)),
            ("chain.links", toml::Value::Integer(links)),
            ("chain.mass", toml::Value::Float(mass)),
            ("chain.gravity", toml::Value::Float(gravity)),
            ("chain.damping", toml::Value::Float(damping)),
            ("chain.axial_damping", toml::Value::Float(axial_damping)),
            (
                "chain.bending_stiffness",
                toml::Value::Float(bending_stiffness),
            ),
        ] {
            overrides::set_path(&mut tree, path, value)?;
        }
        // The pivot's keys are written only where they differ from a fixed
        // pivot's, so that a scene without them reads as it did before.
        let fixed = Pivot::default();
        let point = |p: [f64; 2]| toml::Value::Array(p.map(toml::Value::Float).to_vec());
        let pivot_keys = [
            (
                "acceleration",
                point(pivot.acceleration),
                pivot.acceleration != fixed.acceleration,
            ),
            (
                "amplitude",
                point(pivot.amplitude),
                pivot.amplitude != fixed.amplitude,
            ),
            (
                "frequency",
                toml::Value::Float(pivot.frequency),
                pivot.frequency != fixed.frequency,
            ),
            ("jerk", point(pivot.jerk), pivot.jerk != fixed.jerk),
            (
                "jerk_time",
                toml::Value::Float(pivot.jerk_time),
                pivot.jerk_time != fixed.jerk_time,
            ),
            (
                "release",
                toml::Value::Float(pivot.release.unwrap_or(0.0)),
                pivot.release.is_some(),
            ),
        ];
        for (name, value, given) in pivot_keys {
            if given {
                overrides::set_path(&mut tree, &format!("pivot.{name}"), value)?;
            } else if let Some(toml::Value::Table(section)) = tree.get_mut("pivot") {
                section.remove(name);
            }
        }
        // The tip mass is written only when there is one, so that a scene
        // without it reads as it did before the key existed.
        if tip_mass != 0.0 {
            overrides::set_path(&mut tree, "chain.tip_mass", toml::Value::Float(tip_mass))?;
        } else if let Some(toml::Value::Table(section)) = tree.get_mut("chain") {
            section.remove("tip_mass");
        }
        // The profile's keys are written only when given, so that a scene
        // of equal rods reads as it did before they existed.
        let numbers =
            |v: Vec<f64>| toml::Value::Array(v.into_iter().map(toml::Value::Float).collect());
        let Profile {
            taper,
            masses,
            lengths,
        } = profile;
        for (name, value) in [
            ("taper", (taper != 1.0).then_some(toml::Value::Float(taper))),
            ("rod_masses", masses.map(numbers)),
            ("rod_lengths", lengths.map(numbers)),
        ] {
            match value {
                Some(v) => overrides::set_path(&mut tree, &format!("chain.{name}"), v)?,
                None => {
                    if let Some(toml::Value::Table(section)) = tree.get_mut("chain") {
                        section.remove(name);
                    }
                }
            }
        }
        // The loads' coefficients are written only when on, so that a scene
        // without them reads as it did before the keys existed.
        for key in chain_ode::load::coefficient_keys() {
            match coefficients.get(key) {
                x if x != 0.0 => overrides::set_path(&mut tree, key, toml::Value::Float(x))?,
                _ => {
                    if let Some(toml::Value::Table(section)) = tree.get_mut("chain") {
                        section.remove(key.split_once('.').map_or(key, |(_, field)| field));
                    }
                }
            }
        }
        // Absent is rigid links: the key goes when the chain has none.
        match axial_stiffness {
            Some(ea) => {
                overrides::set_path(&mut tree, "chain.axial_stiffness", toml::Value::Float(ea))?
            }
            None => {
                if let Some(toml::Value::Table(section)) = tree.get_mut("chain") {
                    section.remove("axial_stiffness");
                }
            }
        }
        Self::from_tree(tree)
    }

    /// The start as written (built into a state by [`Scene::state`]).
    pub fn start(&self) -> Start {
        self.start.clone()
    }

    /// The initial state of the scene's chain (validated).
    pub fn state(&self) -> Result<State, Error> {
        let chain = self.chain()?;
        self.check_start(&chain)?;
        Ok(self.start.state(&chain)?)
    }

    /// What chain-ode's own check of an angles start would not say: how
    /// many numbers `start.angles` and `start.rates` must hold.
    fn check_start(&self, chain: &Chain) -> Result<(), Error> {
        if let Start::Angles { angles, rates, .. } = &self.start {
            let n = chain.links();
            let lists = [
                ("start.angles", Some(angles)),
                ("start.rates", rates.as_ref()),
            ];
            for (field, list) in lists {
                if let Some(list) = list.filter(|l| l.len() != n) {
                    return Err(Error::field(
                        field,
                        format!(
                            "must be a list of chain.links = {n} numbers (got {} values)",
                            list.len()
                        ),
                    ));
                }
            }
        }
        Ok(())
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
        self.check_start(&chain)?;
        let state = self.start.state(&chain)?;
        let method = self.method()?;
        // Every bound of the run (tolerances, RK4's step count, the samples'
        // memory, bdf-dense's size) before anything is allocated or spawned.
        let report = self.report.then_some(ReportModel::AS_CODED);
        if let Some(model) = report {
            model.validate(&chain)?;
            if !chain_ode::REPORT_METHODS.contains(&method) {
                return Err(Error::field(
                    "run.method",
                    format!(
                        "must be one of rk4, dopri5, dop853 with model.report = true (got {method})"
                    ),
                ));
            }
        }
        self.options.validate_for(&chain, method)?;
        Ok(Prepared {
            chain,
            state,
            method,
            options: self.options.clone(),
            report,
        })
    }
}

/// The largest scene file read (bytes): a scene is a few hundred bytes; an
/// `angles` start of 10^4 rods is about 200 kB.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// Reads a scene file: a regular file (a device such as `/dev/zero`, a FIFO
/// or a directory is refused before it is opened) of at most
/// [`MAX_SCENE_BYTES`], read through a limit so that a file that grows
/// meanwhile is refused too.
fn read_scene_text(path: &Path) -> Result<String, Error> {
    use std::io::Read as _;
    let read = |e| Error::read("scene", path, e);
    let too_big = || {
        Error::read(
            "scene",
            path,
            std::io::Error::other(format!(
                "larger than {MAX_SCENE_BYTES} bytes (1 MiB, the largest scene file)"
            )),
        )
    };
    let meta = std::fs::metadata(path).map_err(read)?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file (a device, FIFO or socket)"
        };
        return Err(read(std::io::Error::other(format!("it is {kind}"))));
    }
    if meta.len() > MAX_SCENE_BYTES {
        return Err(too_big());
    }
    let file = std::fs::File::open(path).map_err(read)?;
    let mut bytes = Vec::new();
    file.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(read)?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(too_big());
    }
    String::from_utf8(bytes).map_err(|_| {
        read(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "stream did not contain valid UTF-8",
        ))
    })
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
        assert_eq!(
            (c.length(), c.links(), c.mass(), c.gravity()),
            (6.0, 10, 0.2, 1.0)
        );
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

    /// A value of `k`'s type unlike any default, as `--set` text.
    fn sample(k: &schema::Key, kind: StartKind) -> &'static str {
        match k.ty {
            schema::Type::Number => "0.375",
            schema::Type::Integer => "7",
            schema::Type::Point => "[1.5, -0.5]",
            schema::Type::Numbers => "[0.25, 0.5]",
            schema::Type::Text => "sample",
            schema::Type::OneOf(_) => kind.as_str(),
            schema::Type::Bool => "true",
        }
    }

    /// The kinds of start under which a key can be set.
    fn kinds_taking(k: &schema::Key) -> Vec<StartKind> {
        match k.kinds {
            schema::Kinds::Any => vec![StartKind::Catenary],
            schema::Kinds::Only(kinds) => kinds.to_vec(),
        }
    }

    fn at<'a>(v: &'a serde_json::Value, path: &str) -> &'a serde_json::Value {
        path.split('.').fold(v, |v, part| &v[part])
    }

    /// Every leaf path of a JSON object (arrays are leaves).
    fn leaves(v: &serde_json::Value, prefix: &str, out: &mut Vec<String>) {
        match v {
            serde_json::Value::Object(map) => {
                for (k, v) in map {
                    let path = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    leaves(v, &path, out);
                }
            }
            _ => out.push(prefix.to_string()),
        }
    }

    #[test]
    fn the_serde_structs_have_exactly_the_table_keys() {
        // Every row set at once (kinds mixed: this bypasses schema::check).
        let mut tree = toml::Table::new();
        for k in schema::KEYS {
            let value = overrides::parse_value(sample(k, StartKind::Catenary)).unwrap();
            overrides::set_path(&mut tree, k.path, value).unwrap();
        }
        // A row missing from the structs is an unknown field here...
        let file: SceneFile = tree.try_into().unwrap_or_else(|e| panic!("{e}"));
        // ...and a field missing from the table is a path too many here.
        let mut paths = vec![];
        leaves(&serde_json::to_value(&file).unwrap(), "", &mut paths);
        paths.sort();
        let mut rows: Vec<&str> = schema::KEYS.iter().map(|k| k.path).collect();
        rows.sort();
        assert_eq!(paths, rows);
    }

    /// Every load of chain-ode whose strength is a coefficient has its row
    /// (a number, 0 by default: off), and every row of `[chain]` that is no
    /// field of the serde struct is such a load's: a load added without its
    /// row, or a row no load reads, fails here.
    #[test]
    fn every_load_coefficient_is_a_row_and_back() {
        let keys: Vec<&str> = chain_ode::load::coefficient_keys().collect();
        for key in &keys {
            let row = schema::key(key).unwrap_or_else(|| panic!("{key}: no row in schema::KEYS"));
            assert_eq!(row.ty, schema::Type::Number, "{key}");
            assert_eq!(
                row.default,
                schema::DefaultValue::Value(schema::Literal::Number(0.0)),
                "{key}"
            );
        }
        let mut tree = valid_base(StartKind::Catenary);
        for key in &keys {
            overrides::set_path(&mut tree, key, toml::Value::Float(0.5)).unwrap();
        }
        let file = SceneFile::read(&tree).unwrap();
        let mut loads: Vec<String> = file
            .chain
            .loads
            .keys()
            .map(|k| format!("chain.{k}"))
            .collect();
        loads.sort();
        let mut want: Vec<String> = keys.iter().map(|k| k.to_string()).collect();
        want.sort();
        assert_eq!(loads, want);
        // And the chain carries them, and a scene rewritten from it keeps them.
        let scene = Scene::from_tree(tree).unwrap();
        for key in &keys {
            assert_eq!(scene.chain_params().coefficients.get(key), 0.5, "{key}");
        }
        let chain = scene.chain().unwrap();
        let again = scene.with_chain(&chain).unwrap();
        assert_eq!(again.chain_params(), scene.chain_params());
    }

    #[test]
    fn every_row_round_trips_through_set() {
        for k in schema::KEYS {
            for kind in kinds_taking(k) {
                let mut tree = valid_base(kind);
                let text = sample(k, kind);
                overrides::apply(&mut tree, &[format!("{}={text}", k.path)])
                    .unwrap_or_else(|e| panic!("{}: {e}", k.path));
                let file = SceneFile::read(&tree).unwrap_or_else(|e| panic!("{}: {e}", k.path));
                let got = serde_json::to_value(&file).unwrap();
                let want = serde_json::to_value(overrides::parse_value(text).unwrap()).unwrap();
                assert_eq!(at(&got, k.path), &want, "{} ({kind:?})", k.path);
            }
        }
    }

    /// A scene of each start kind that `prepare` accepts, with every key
    /// it leaves out at its default.
    fn valid_base(kind: StartKind) -> toml::Table {
        let extra = match kind {
            StartKind::Stretched => "p1 = [6, 0]",
            StartKind::Catenary => "p1 = [3, 0]",
            StartKind::Folded => "",
            StartKind::Angles => "angles = [0, 0, 0, 0]",
        };
        format!(
            "[chain]\nlinks = 4\n[start]\nkind = \"{}\"\n{extra}\n[run]\nt_end = 1\n",
            kind.as_str()
        )
        .parse()
        .unwrap()
    }

    /// Everything a scene builds: its name and description, and the
    /// chain-ode values of `prepare` (`Chain`, `State`, `Method`,
    /// `SolveOptions`).
    fn model(tree: toml::Table) -> Result<(String, String, Prepared), Error> {
        let s = Scene::from_tree(tree)?;
        let prepared = s.prepare()?;
        Ok((s.name().to_string(), s.description().to_string(), prepared))
    }

    /// [`valid_base`] for the key at `path`: a `[floor]` key's scene runs
    /// `auto`, which runs either floor law (its example may make a
    /// constraint floor, which the default `rk4` does not run).
    fn base_for(path: &str, kind: StartKind) -> toml::Table {
        let base = valid_base(kind);
        if path.starts_with("floor.") {
            set(base, "run.method", "auto")
        } else {
            base
        }
    }

    /// `base` with `path` set to the `--set` text `text`.
    fn set(mut base: toml::Table, path: &str, text: &str) -> toml::Table {
        overrides::apply(&mut base, &[format!("{path}={text}")])
            .unwrap_or_else(|e| panic!("{path}={text}: {e}"));
        base
    }

    /// Each key of the schema reaches the model: its row's `example` (a
    /// valid value other than the default) changes what the scene builds.
    /// A key read into the serde structs but never used when the scene is
    /// built, or a row whose example is not accepted anywhere, fails here.
    #[test]
    fn every_key_reaches_the_model() {
        for k in schema::KEYS {
            if k.path == schema::START_KIND {
                // The start kind cannot be set alone (each kind has its own
                // keys): each kind's scene must build a start of its own.
                let starts: Vec<Start> = StartKind::ALL
                    .iter()
                    .map(|&kind| {
                        model(valid_base(kind)).unwrap_or_else(|e| panic!("{kind:?}: {e}"));
                        Scene::from_tree(valid_base(kind)).unwrap().start()
                    })
                    .collect();
                for (i, a) in starts.iter().enumerate() {
                    for b in &starts[..i] {
                        assert!(std::mem::discriminant(a) != std::mem::discriminant(b));
                    }
                }
                continue;
            }
            let mut accepted = 0;
            for kind in kinds_taking(k) {
                let before =
                    model(base_for(k.path, kind)).unwrap_or_else(|e| panic!("{kind:?}: {e}"));
                let Ok(after) = model(set(base_for(k.path, kind), k.path, k.example)) else {
                    continue;
                };
                accepted += 1;
                assert!(
                    after != before,
                    "{}={} ({kind:?}) changes nothing in the built scene: the key does not \
                     reach the model (or the example is its default)",
                    k.path,
                    k.example
                );
            }
            assert!(
                accepted > 0,
                "{}={}: the example is rejected for every start kind",
                k.path,
                k.example
            );
        }
    }

    /// Each key with a range has it checked: its row's `out_of_range`
    /// value (of the right type) is rejected by an error that names the
    /// key, wherever the row's `example` is accepted. A range check removed
    /// (a damping of -1e-3 let through) fails here.
    #[test]
    fn every_range_is_checked_by_its_key() {
        let mut checked = 0;
        for k in schema::KEYS {
            let Some(bad) = k.out_of_range else {
                continue;
            };
            // The bad value has the key's type: the type check passes it, so
            // only a range check can reject it.
            if let Ok(v) = overrides::parse_value(bad) {
                if k.path != schema::START_KIND {
                    k.check(&k.coerce(v))
                        .unwrap_or_else(|e| panic!("{}={bad} is not of its type: {e}", k.path));
                }
            }
            for kind in kinds_taking(k) {
                if model(set(base_for(k.path, kind), k.path, k.example)).is_err() {
                    continue;
                }
                match model(set(base_for(k.path, kind), k.path, bad)) {
                    Ok(_) => panic!("{}={bad} ({kind:?}) is accepted: no range check", k.path),
                    Err(e) => assert_eq!(e.subject(), k.path, "{}={bad}: {e}", k.path),
                }
                checked += 1;
            }
        }
        assert!(checked >= 15, "only {checked} ranges checked");
    }

    #[test]
    fn every_error_names_a_table_key() {
        let bad: &[(schema::Type, &[&str])] = &[
            (
                schema::Type::Number,
                &["-1", "0", "nan", "inf", "1e300", "true"],
            ),
            (
                schema::Type::Integer,
                &["0", "1", "4", "100000000000", "-1", "2.5"],
            ),
            (
                schema::Type::Point,
                &["[nan, 0]", "[100, 0]", "[0, 0]", "[1]"],
            ),
            (
                schema::Type::Numbers,
                &["[nan, 0, 0, 0]", "[]", "[1, 2]", "1"],
            ),
            (schema::Type::Text, &["nonesuch", "1"]),
            (schema::Type::OneOf(&[]), &["nonesuch", "1"]),
            (schema::Type::Bool, &["1", "\"yes\""]),
        ];
        let names = crate::CatenaryNames::SCENE;
        for k in schema::KEYS {
            for kind in kinds_taking(k) {
                let values = bad
                    .iter()
                    .find(|(t, _)| std::mem::discriminant(t) == std::mem::discriminant(&k.ty))
                    .map_or(&[][..], |b| b.1);
                // Some bad values are in range for some keys (0 for a
                // damping); every key must reject at least one of them, so
                // the check below never passes for want of an error.
                let mut rejected = 0;
                for text in values {
                    let mut tree = valid_base(kind);
                    overrides::apply(&mut tree, &[format!("{}={text}", k.path)]).unwrap();
                    if let Err(e) = Scene::from_tree(tree).and_then(|s| s.prepare()) {
                        rejected += 1;
                        let subject = e.subject();
                        assert!(
                            schema::key(subject).is_some() || subject == names.other,
                            "{}={text}: {e}",
                            k.path
                        );
                    }
                }
                assert!(rejected > 0, "{} ({kind:?}): no bad value rejected", k.path);
            }
        }
        for name in [names.p0, names.p1, names.length, names.links] {
            assert!(schema::key(name).is_some(), "{name}");
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
        assert_eq!(t.chain().unwrap().links(), 100);
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
