//! A scene fuzzer: proptest draws scenes of ordinary and extreme values
//! (lengths, masses, gravity, damping, counts near integer limits, t_end up
//! to 1e6, output_dt down to 1e-12, tolerances, every method and start
//! kind, scene names with commas, quotes and line breaks, start angles of
//! two turns and past them, jerk and release times down to 1e-300, tapers
//! and rod-length ratios at and past their bounds) and runs them
//! through every subcommand (simulate, sweep,
//! converge, plot, animate, catenary, view, and the study's precision,
//! stability, needs and merge, each with `--budget 1`; a test checks that
//! [`COMMANDS`] is every subcommand of `--help`), sometimes with two outputs
//! on one file (`--out` and `--forces` or `--plot`, as `x` and `./x`),
//! or an ensemble's `--out` onto its own scene file, which must be refused, a page not ending in `.html`, and shards to merge
//! whose cells hold the drawn name. Every run has a step budget
//! (`--set run.max_steps=...`, smaller for more rods) and a wall-clock kill
//! timeout. Each must end with exit 0, 1 or 2, never a signal, 101 (panic),
//! 134 (abort) or a hang; an exit 2 says one line, `error: ...`; any other
//! exit says at most one line apart from the stiffness hint (`hint: ...`,
//! allowed: it is the one line the CLI adds on purpose for explicit methods
//! on stiff scenes), converge's progress lines and the `wrote FILE` lines
//! of the study's commands.
//!
//! `FUZZ_CASES` sets the number of cases (default 100, a few seconds),
//! `FUZZ_SEED` the seed (default fixed, so that CI is repeatable),
//! `FUZZ_TIMEOUT` the kill timeout in seconds (default 20). Every failing
//! case is listed, not only the first.

use std::fmt::Write as _;
use std::fs;
use std::path::Path;
use std::time::{Duration, Instant};

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use crate::common::*;

fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// A number: mostly ordinary (in `lo..hi`), sometimes one of `extremes`.
fn number(lo: f64, hi: f64, extremes: &'static [f64]) -> BoxedStrategy<f64> {
    prop_oneof![
        14 => lo..hi,
        1 => proptest::sample::select(extremes),
    ]
    .boxed()
}

const HUGE: &[f64] = &[
    0.0,
    -1.0,
    1e-300,
    1e-12,
    1e12,
    1e300,
    f64::MAX,
    f64::INFINITY,
    f64::NAN,
];

/// TOML for a float (`nan`, `inf` and `-inf` are TOML's names).
fn toml_f(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        format!("{x:?}")
    }
}

/// Counts near the integer limits as well as ordinary ones.
fn count(lo: i128, hi: i128) -> BoxedStrategy<i128> {
    prop_oneof![
        14 => lo..hi,
        1 => proptest::sample::select(&[
            0_i128,
            1,
            2,
            1000,
            20_000,
            1_000_000,
            1_000_001,
            i32::MAX as i128,
            u32::MAX as i128,
            i64::MAX as i128,
            u64::MAX as i128,
            -1,
        ][..]),
    ]
    .boxed()
}

#[derive(Clone, Debug)]
struct Case {
    command: usize,
    length: f64,
    links: i128,
    mass: f64,
    gravity: f64,
    damping: f64,
    kind: usize,
    p1: (f64, f64),
    p1_on_circle: bool,
    down: i128,
    t_end: f64,
    method: usize,
    dt: f64,
    rtol: f64,
    atol: f64,
    output_dt: f64,
    h_min: f64,
    extra: i128,
    with_out: bool,
    /// `run.rho_inf` (gen-alpha's damping; out of range drawn too).
    rho_inf: f64,
    /// `chain.axial_stiffness` (written only when `elastic`),
    /// `chain.axial_damping`, `chain.bending_stiffness`.
    axial_stiffness: f64,
    axial_damping: f64,
    bending_stiffness: f64,
    elastic: bool,
    /// `chain.tip_mass` (refused with elastic links when > 0).
    tip_mass: f64,
    /// `model.report` (refused with elastic links, bending, a tip mass and
    /// the methods it does not run).
    report: bool,
    /// The `[pivot]` section (written only when `moving`): the y parts of
    /// `pivot.acceleration`, `pivot.amplitude` and `pivot.jerk`, then
    /// `pivot.frequency`, `pivot.jerk_time` and `pivot.release`.
    pivot: [f64; 6],
    moving: bool,
    /// `chain.taper`, and the lists `chain.rod_masses`, `chain.rod_lengths`
    /// (all written only when `profiled`; refused with elastic links and
    /// the report's model).
    taper: f64,
    profiled: bool,
    /// The scene's `name`, one of [`NAMES`] (commas, quotes, line breaks).
    name: usize,
    /// Two outputs of the command on one file (simulate's `--out` and
    /// `--forces`, a study's `--out` and `--plot`), or view's page not
    /// ending in `.html`: refused, exit 2.
    same_out: bool,
    /// One start angle of an angles start set to this (0: none): two turns
    /// (`4 pi`, accepted), past them (13, 1e300: refused by name).
    angle_big: f64,
    /// The first rod's relative length in a profile's `chain.rod_lengths`
    /// (1: the drawn list): `1e6`, the largest ratio accepted, and `1e7`,
    /// refused; the other rods are 1.
    rod_ratio: f64,
    /// The `[floor]` section (written only when `floored`): `floor.height`,
    /// `angle`, `stiffness`, `damping`, `friction`, `slip_speed`, each in
    /// and out of its range (a floor above the start is refused by name).
    floor: [f64; 6],
    floored: bool,
    /// `floor.law`: 0 `penalty` (with its keys above), 1 `constraint`
    /// (height, angle, friction and `floor.restitution`, which is drawn in
    /// and out of [0, 1]), 2 a bogus name (refused by name).
    floor_law: usize,
    restitution: f64,
}

/// Scene names the fuzzer draws: plain, and with what CSV quotes.
const NAMES: [&str; 7] = [
    "fuzz",
    "a,b",
    "say \"hi\"",
    "two\nlines",
    "\",\"\n\"\",",
    "cr\r\nlf, \"both\"",
    "",
];

const COMMANDS: [&str; 12] = [
    "simulate",
    "sweep",
    "converge",
    "plot",
    "animate",
    "catenary",
    "precision",
    "stability",
    "needs",
    "ensemble",
    "merge",
    "view",
];
const KINDS: [&str; 4] = ["stretched", "catenary", "folded", "angles"];

fn case() -> impl Strategy<Value = Case> {
    let methods = chain_ode::Method::ALL.len() + 1; // and one bogus name
    (
        (
            0..COMMANDS.len(),
            number(0.1, 20.0, HUGE),
            count(1, 40),
            number(1e-3, 10.0, HUGE),
            number(0.0, 20.0, &[0.0, -9.8, 1e300, f64::NAN, f64::INFINITY]),
            number(0.0, 0.05, &[1.0, 1e6, -1.0, 1e300, f64::NAN]),
            0..KINDS.len(),
        ),
        (
            (number(-10.0, 10.0, HUGE), number(-10.0, 10.0, HUGE)),
            any::<bool>(),
            count(0, 40),
            number(0.01, 3.0, &[1e6, 1e-12, 0.0, -1.0, f64::INFINITY, 1e300]),
            0..methods,
            number(1e-3, 0.05, &[1e-300, 1e300, 0.0, 1e-12, 10.0]),
        ),
        (
            number(1e-10, 1e-3, &[1e-20, 1e-300, 0.999999, 1.0, 0.0, 1e-15]),
            number(1e-12, 1e-4, &[1e-20, 1e300, 0.0, 1e-300]),
            number(0.01, 0.5, &[1e-12, 1e-9, 1e-6, 1e300, 0.0]),
            number(0.0, 1e-300, &[0.0, 1e-300, 1.0, -1.0]),
            count(1, 6),
            any::<bool>(),
            number(0.0, 1.0, &[0.0, 1.0, 1.5, -0.1, f64::NAN]),
        ),
        (
            number(1e2, 1e5, &[0.0, -1.0, 1e300, f64::NAN, f64::INFINITY]),
            number(0.0, 1.0, &[-1.0, 1e300, f64::NAN]),
            number(0.0, 0.1, &[-1.0, 1e300, f64::INFINITY, f64::NAN]),
            any::<bool>(),
            number(0.0, 2.0, &[0.0, -1.0, 1e300, f64::INFINITY, f64::NAN]),
            any::<bool>(),
        ),
        (
            number(-2.0, 2.0, &[0.0, 1e300, f64::NAN]),
            number(-0.2, 0.2, &[0.0, f64::INFINITY]),
            number(-1.0, 1.0, &[0.0, f64::NAN]),
            number(0.0, 50.0, &[0.0, -1.0, 1e300]),
            number(0.01, 2.0, &[0.0, -1.0, f64::INFINITY, 1e-6, 1e-12, 1e-300]),
            number(0.0, 2.0, &[-1.0, f64::NAN, 1e300, 1e-15, 1e-300]),
            any::<bool>(),
            number(
                0.5,
                20.0,
                &[1.0, 0.0, -1.0, 1e300, f64::NAN, 1e-3, 1e3, 1001.0],
            ),
            any::<bool>(),
        ),
        (
            prop_oneof![3 => Just(0usize), 4 => 1..NAMES.len()],
            proptest::bool::weighted(0.2),
            prop_oneof![
                6 => Just(0.0),
                1 => proptest::sample::select(&[4.0 * std::f64::consts::PI, 13.0, 1e300][..]),
            ],
            prop_oneof![
                6 => Just(1.0),
                1 => proptest::sample::select(&[1e6, 1e7][..]),
            ],
        ),
        (
            proptest::bool::weighted(0.3),
            number(-20.0, 1.0, &[1e300, f64::NAN, 0.0, 1e10, 5e8]),
            number(-0.5, 0.5, &[0.0, 1.5, 2.0, f64::NAN]),
            number(
                1e2,
                1e7,
                &[0.0, -1.0, 1e15, 1e16, f64::INFINITY, 1e-8, 1e10],
            ),
            number(0.0, 1e3, &[0.0, -1.0, 1e13, f64::NAN, 1e12, 1e6]),
            number(0.0, 1.0, &[0.0, -0.5, 101.0, f64::NAN]),
            number(1e-4, 1.0, &[0.0, -1.0, 1e7, 1e-300, 1e-12, 1e-9, 2.5e-10]),
            prop_oneof![4 => Just(0usize), 4 => Just(1usize), 1 => Just(2usize)],
            number(0.0, 1.0, &[0.0, 1.0, 1.5, -0.5, f64::NAN]),
        ),
    )
        .prop_map(
            |(
                (command, length, links, mass, gravity, damping, kind),
                (p1, p1_on_circle, down, t_end, method, dt),
                (rtol, atol, output_dt, h_min, extra, with_out, rho_inf),
                (axial_stiffness, axial_damping, bending_stiffness, elastic, tip_mass, report),
                (acc, amp, jerk, freq, jerk_time, release, moving, taper, profiled),
                (name, same_out, angle_big, rod_ratio),
                (
                    floored,
                    height,
                    angle,
                    stiffness,
                    floor_damping,
                    friction,
                    slip_speed,
                    floor_law,
                    restitution,
                ),
            )| Case {
                command,
                length,
                links,
                mass,
                gravity,
                damping,
                kind,
                p1,
                p1_on_circle,
                down,
                t_end,
                method,
                dt,
                rtol,
                atol,
                output_dt,
                h_min,
                extra,
                with_out,
                rho_inf,
                axial_stiffness,
                axial_damping,
                bending_stiffness,
                elastic,
                tip_mass,
                report,
                pivot: [acc, amp, jerk, freq, jerk_time, release],
                moving,
                taper,
                profiled,
                name,
                same_out,
                angle_big,
                rod_ratio,
                floor: [
                    height,
                    angle,
                    stiffness,
                    floor_damping,
                    friction,
                    slip_speed,
                ],
                floored,
                floor_law,
                restitution,
            },
        )
}

impl Case {
    fn method_name(&self) -> String {
        chain_ode::Method::ALL
            .get(self.method)
            .map_or("no-such-method".into(), |m| m.as_str().to_string())
    }

    /// P1: on the circle of radius L about P0 half of the time (so that
    /// stretched starts are valid), else as drawn.
    fn p1(&self) -> (f64, f64) {
        if self.p1_on_circle {
            let a = self.p1.0.atan2(self.p1.1);
            (self.length * a.cos(), self.length * a.sin())
        } else {
            self.p1
        }
    }

    fn scene_text(&self) -> String {
        let (x, y) = self.p1();
        let mut t = String::new();
        let name = toml::Value::String(NAMES[self.name].to_string());
        writeln!(t, "name = {name}\n[chain]").unwrap();
        writeln!(t, "length = {}", toml_f(self.length)).unwrap();
        // Beyond i64, TOML has no integer: a float, which must be refused.
        if i64::try_from(self.links).is_ok() {
            writeln!(t, "links = {}", self.links).unwrap();
        } else {
            writeln!(t, "links = {:?}", self.links as f64).unwrap();
        }
        writeln!(t, "mass = {}", toml_f(self.mass)).unwrap();
        writeln!(t, "gravity = {}", toml_f(self.gravity)).unwrap();
        writeln!(t, "damping = {}", toml_f(self.damping)).unwrap();
        if self.elastic {
            writeln!(t, "axial_stiffness = {}", toml_f(self.axial_stiffness)).unwrap();
        }
        writeln!(t, "axial_damping = {}", toml_f(self.axial_damping)).unwrap();
        writeln!(t, "bending_stiffness = {}", toml_f(self.bending_stiffness)).unwrap();
        writeln!(t, "tip_mass = {}", toml_f(self.tip_mass)).unwrap();
        // Air drag takes the tip mass's draw (its range, out of it too):
        // a proptest tuple has no room left for a field of its own.
        writeln!(t, "air_drag = {}", toml_f(self.tip_mass)).unwrap();
        if self.profiled {
            writeln!(t, "taper = {}", toml_f(self.taper)).unwrap();
            // As many entries as rods where that is small, else a few.
            let n = usize::try_from(self.links).unwrap_or(3).min(50);
            let list = |k: usize| -> String {
                let v: Vec<String> = (0..n).map(|i| format!("{}", 1 + (i * k) % 4)).collect();
                v.join(", ")
            };
            if self.taper == 1.0 {
                writeln!(t, "rod_masses = [{}]", list(3)).unwrap();
            }
            if self.rod_ratio == 1.0 {
                writeln!(t, "rod_lengths = [{}]", list(1)).unwrap();
            } else {
                let mut v = vec!["1".to_string(); n];
                v[0] = toml_f(self.rod_ratio);
                writeln!(t, "rod_lengths = [{}]", v.join(", ")).unwrap();
            }
        }
        if self.moving {
            let [acc, amp, jerk, freq, jerk_time, release] = self.pivot.map(toml_f);
            writeln!(
                t,
                "[pivot]\nacceleration = [0, {acc}]\namplitude = [0, {amp}]"
            )
            .unwrap();
            writeln!(
                t,
                "jerk = [{jerk}, 0]\nfrequency = {freq}\njerk_time = {jerk_time}"
            )
            .unwrap();
            writeln!(t, "release = {release}").unwrap();
        }
        let kind = KINDS[self.kind];
        writeln!(t, "[start]\nkind = \"{kind}\"").unwrap();
        match kind {
            "stretched" | "catenary" => {
                writeln!(t, "p1 = [{}, {}]", toml_f(x), toml_f(y)).unwrap();
            }
            "folded" => {
                if i64::try_from(self.down).is_ok() {
                    writeln!(t, "down = {}", self.down).unwrap();
                }
            }
            _ => {
                // As many angles as rods where that is small, else a few.
                let n = usize::try_from(self.links).unwrap_or(3).min(50);
                let mut angles: Vec<String> =
                    (0..n).map(|i| toml_f(-1.5 + 0.05 * i as f64)).collect();
                if self.angle_big != 0.0 && n > 0 {
                    angles[n / 2] = toml_f(self.angle_big);
                }
                writeln!(t, "angles = [{}]", angles.join(", ")).unwrap();
            }
        }
        writeln!(t, "[run]").unwrap();
        writeln!(t, "t_end = {}", toml_f(self.t_end)).unwrap();
        writeln!(t, "method = \"{}\"", self.method_name()).unwrap();
        writeln!(t, "dt = {}", toml_f(self.dt)).unwrap();
        writeln!(t, "rtol = {}", toml_f(self.rtol)).unwrap();
        writeln!(t, "atol = {}", toml_f(self.atol)).unwrap();
        writeln!(t, "output_dt = {}", toml_f(self.output_dt)).unwrap();
        writeln!(t, "h_min = {}", toml_f(self.h_min)).unwrap();
        writeln!(t, "rho_inf = {}", toml_f(self.rho_inf)).unwrap();
        writeln!(t, "[model]\nreport = {}", self.report).unwrap();
        if self.floored {
            let [h, a, k, c, mu, vs] = self.floor.map(toml_f);
            writeln!(t, "[floor]\nheight = {h}\nangle = {a}\nfriction = {mu}").unwrap();
            match self.floor_law {
                0 => {
                    writeln!(t, "stiffness = {k}\ndamping = {c}\nslip_speed = {vs}").unwrap();
                }
                1 => {
                    let e = toml_f(self.restitution);
                    writeln!(t, "law = \"constraint\"\nrestitution = {e}").unwrap();
                }
                _ => writeln!(t, "law = \"springy\"").unwrap(),
            }
        }
        t
    }

    /// The step budget: at most 2000 steps, fewer for more rods (about
    /// 10^5 rod-steps in all), so that a case is quick whatever it asks.
    fn budget(&self) -> u64 {
        let n = u64::try_from(self.links).unwrap_or(1).max(1);
        (100_000 / n).clamp(1, 2000)
    }

    fn args(&self, dir: &Path) -> Vec<String> {
        let scene = dir.join("fuzz.toml");
        fs::write(&scene, self.scene_text()).unwrap();
        let scene = scene.to_string_lossy().into_owned();
        let budget = format!("run.max_steps={}", self.budget());
        let out = |name: &str| dir.join(name).to_string_lossy().into_owned();
        let command = COMMANDS[self.command];
        let mut a: Vec<String> = vec![command.into()];
        match command {
            "simulate" => {
                a.extend([scene, "--set".into(), budget, "--json".into()]);
                if self.same_out {
                    // One file as `x` and `./x`, or twice the same path.
                    let again = if self.extra % 2 == 0 {
                        out("./out.csv")
                    } else {
                        out("out.csv")
                    };
                    a.extend(["--out".into(), out("out.csv"), "--forces".into(), again]);
                } else if self.with_out {
                    a.extend(["--out".into(), out("out.csv")]);
                }
            }
            "sweep" => {
                // An ordinary sweep of a few runs, or a COUNT near the
                // limits. A valid COUNT is kept small (a sweep of 10^6 runs
                // is long, not wrong); a larger one becomes 10^6 + 1, just
                // past the cap, which must be refused at once.
                let count = match self.extra {
                    _ if self.with_out => 2,
                    c @ ..=8 => c,
                    c if c <= 1_000_000 => 8,
                    c => c,
                };
                a.extend([
                    scene,
                    "--set".into(),
                    budget,
                    "--vary".into(),
                    format!("chain.damping=0:{}:{count}", toml_f(self.damping.abs())),
                    "--jobs".into(),
                    "2".into(),
                    "--quiet".into(),
                ]);
            }
            "converge" => {
                let top = 2 * usize::try_from(self.extra).unwrap_or(2).clamp(2, 4);
                a.extend([
                    scene,
                    "--set".into(),
                    budget,
                    "--tol".into(),
                    "0.1".into(),
                    "--links".into(),
                    format!("2,{top}"),
                    "--method".into(),
                    self.method_name(),
                    "--jobs".into(),
                    "2".into(),
                ]);
            }
            "plot" => {
                let snapshots = if self.with_out {
                    "5".to_string()
                } else {
                    self.extra.to_string()
                };
                a.extend([
                    scene,
                    "--set".into(),
                    budget,
                    "-o".into(),
                    out("p.png"),
                    "--snapshots".into(),
                    snapshots,
                ]);
            }
            "animate" => {
                a.extend([
                    scene,
                    "--set".into(),
                    budget,
                    "-o".into(),
                    out("a.gif"),
                    "--fps".into(),
                    "5".into(),
                    "--seconds".into(),
                    "0.6".into(),
                ]);
            }
            "precision" | "stability" | "needs" => {
                a.extend([
                    scene,
                    "--set".into(),
                    budget,
                    "--methods".into(),
                    self.method_name(),
                    "--budget".into(),
                    "1".into(),
                    "--jobs".into(),
                    "2".into(),
                    "--quiet".into(),
                ]);
                match (command, self.with_out) {
                    ("needs", _) => a.extend([
                        "--tol".into(),
                        "0.1".into(),
                        "--links".into(),
                        format!("2,{}", 2 * self.extra.clamp(2, 4)),
                    ]),
                    (_, true) if self.same_out => a.extend([
                        "--out".into(),
                        out("s.svg"),
                        "--plot".into(),
                        out("./s.svg"),
                    ]),
                    (_, true) => {
                        a.extend(["--out".into(), out("s.csv"), "--plot".into(), out("s.svg")])
                    }
                    // A shard near the limits, or an ordinary one.
                    (_, false) => a.extend(["--shard".into(), format!("{}/3", self.extra)]),
                }
                if command == "stability" && self.extra % 2 == 0 {
                    let top = toml_f(self.damping.abs());
                    a.extend(["--vary".into(), format!("chain.damping=0:{top}:2")]);
                }
            }
            "ensemble" => {
                // Members and spread drawn in and out of their ranges.
                a.extend([
                    scene,
                    "--set".into(),
                    budget,
                    format!("--members={}", self.extra),
                    format!("--spread={}", toml_f(self.damping)),
                    "--budget".into(),
                    "1".into(),
                    "--jobs".into(),
                    "2".into(),
                    "--quiet".into(),
                ]);
                if self.same_out {
                    // The output onto the scene file: refused (issue 47 F1).
                    a.extend([
                        "--out".into(),
                        dir.join("fuzz.toml").to_string_lossy().into_owned(),
                    ]);
                } else if self.with_out {
                    a.extend(["--out".into(), out("e.csv")]);
                }
            }
            "view" => {
                // A page that must end in .html exactly, or one that does.
                let page = if self.same_out { "v.HTML" } else { "v.html" };
                a.extend([scene, "--set".into(), budget, "-o".into(), out(page)]);
                if self.with_out {
                    a.extend(["--method".into(), self.method_name(), "--forces".into()]);
                }
            }
            "merge" => {
                // Shards that are not: the scene file, a table of another
                // shape, and (half of the time) a file that does not exist.
                let table = dir.join("t.csv");
                fs::write(
                    &table,
                    format!("run,x\n{},{}\n", self.extra, toml_f(self.length)),
                )
                .unwrap();
                // A shard of the right shape whose cell holds the drawn
                // name, quoted as the CSV writer quotes it (or, with
                // `same_out`, with its quotes unbalanced).
                let named = dir.join("n.csv");
                let cell = fc_csv::field(NAMES[self.name]).into_owned();
                let cell = if self.same_out {
                    cell.replacen('"', "", 1)
                } else {
                    cell
                };
                fs::write(&named, format!("run,name,runs,scene_hash\n0,{cell},1,h\n")).unwrap();
                if self.extra % 3 == 0 {
                    a.push(named.to_string_lossy().into_owned());
                    a.extend(["--out".into(), out("m.csv")]);
                    return a;
                }
                a.extend([scene, table.to_string_lossy().into_owned()]);
                if self.with_out {
                    a.push(out("missing.csv"));
                }
                a.extend(["--out".into(), out("m.csv")]);
            }
            _ => {
                let (x, y) = self.p1();
                a.extend([
                    "--p1".into(),
                    format!("{x:e},{y:e}"),
                    "--length".into(),
                    format!("{:e}", self.length),
                    "--links".into(),
                    self.links.to_string(),
                ]);
                if self.with_out {
                    a.push("--json".into());
                }
            }
        }
        a
    }
}

impl Case {
    /// The exit code the case must end with, where its draws decide it:
    /// two outputs on one file and a page not ending in `.html` are
    /// refused (2); a shard whose cell holds the drawn name quoted as the
    /// writer quotes it merges (0), and with a quote removed is refused.
    fn expected(&self) -> Option<i32> {
        let command = COMMANDS[self.command];
        match command {
            "simulate" | "view" | "ensemble" if self.same_out => Some(2),
            "precision" | "stability" if self.same_out && self.with_out => Some(2),
            "merge" if self.extra % 3 == 0 => {
                let cell = fc_csv::field(NAMES[self.name]);
                Some(if self.same_out && cell.contains('"') {
                    2
                } else {
                    0
                })
            }
            _ => None,
        }
    }
}

/// A line the CLI prints on purpose besides a result: the stiffness hint,
/// converge's progress, and the files a study command wrote.
fn is_info(line: &str) -> bool {
    line.starts_with("hint: ")
        || (line.starts_with("converge: ") && line.ends_with(" runs done"))
        || line.starts_with("wrote ")
}

/// What is wrong with how a case ended, if anything.
fn judge(out: Option<&std::process::Output>, timeout: Duration) -> Option<String> {
    let Some(out) = out else {
        return Some(format!("hang: killed after {timeout:?}"));
    };
    let err = String::from_utf8_lossy(&out.stderr);
    let code = out.status.code();
    let Some(code) = code else {
        return Some(format!("killed by a signal ({:?}): {err}", out.status));
    };
    if !(0..=2).contains(&code) {
        let head: String = err.chars().take(300).collect();
        return Some(format!("exit {code}: {head}"));
    }
    let lines: Vec<&str> = err.lines().collect();
    if code == 2 {
        if lines.len() != 1 || !lines[0].starts_with("error: ") {
            return Some(format!(
                "exit 2 with {} lines: {:?}",
                lines.len(),
                &lines[..lines.len().min(3)]
            ));
        }
        if lines[0].len() > 800 {
            return Some(format!("exit 2 with a {}-byte line", lines[0].len()));
        }
        return None;
    }
    let other: Vec<&&str> = lines.iter().filter(|l| !is_info(l)).collect();
    if other.len() > 1 {
        return Some(format!(
            "exit {code} with {} lines: {:?}",
            other.len(),
            &other[..other.len().min(3)]
        ));
    }
    None
}

#[test]
fn fuzzed_scenes_end_with_a_status_or_one_line() {
    let cases: u32 = env_or("FUZZ_CASES", 100);
    let seed: u64 = env_or("FUZZ_SEED", 24);
    let timeout = Duration::from_secs(env_or("FUZZ_TIMEOUT", 20));
    let mut seed_bytes = [0u8; 32];
    seed_bytes[..8].copy_from_slice(&seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let strategy = case();
    let dir = scratch("fuzz");
    let start = Instant::now();
    let mut failures = vec![];
    let mut codes = [0usize; 3];
    for i in 0..cases {
        let case = strategy.new_tree(&mut runner).unwrap().current();
        let args = case.args(&dir);
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run_within(&refs, timeout);
        let code = out.as_ref().and_then(|o| o.status.code());
        let verdict = judge(out.as_ref(), timeout).or_else(|| {
            case.expected()
                .filter(|&want| code != Some(want))
                .map(|want| format!("exit {code:?}, not {want}"))
        });
        match verdict {
            Some(why) => failures.push(format!(
                "case {i}: {why}\n  args: {args:?}\n  scene:\n{}",
                case.scene_text()
            )),
            None => {
                if let Some(c) = out.and_then(|o| o.status.code()) {
                    codes[usize::try_from(c).unwrap_or(0).min(2)] += 1;
                }
            }
        }
        for name in names_in(&dir) {
            if name.starts_with('.') {
                failures.push(format!("case {i}: left {name}\n  args: {args:?}"));
            }
            let _ = fs::remove_file(dir.join(name));
        }
    }
    eprintln!(
        "fuzz: {cases} cases (seed {seed}) in {:.1} s: exit 0/1/2 = {codes:?}, {} failures",
        start.elapsed().as_secs_f64(),
        failures.len()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The fuzzer draws every subcommand that `falling-chain --help` lists
/// (but `help`): a command added to the CLI fails here until it is drawn.
#[test]
fn the_fuzzer_draws_every_command() {
    let out = run(&["--help"]);
    let help = String::from_utf8_lossy(&out.stdout);
    let listed: Vec<&str> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert!(listed.len() >= 10, "--help lists {listed:?}");
    for c in &listed {
        assert!(COMMANDS.contains(c), "the fuzzer does not draw `{c}`");
    }
    for c in COMMANDS {
        assert!(listed.contains(&c), "`{c}` is not a command");
    }
}

/// The scene keys the fuzzer leaves at their defaults: free text, the
/// pivot (every start is drawn about `P0 = [0, 0]`; not drawn yet), and the
/// angles start's rates (its angles are drawn). Each must be a key.
const NOT_FUZZED: [&str; 3] = ["description", "start.p0", "start.rates"];

/// The fuzzer draws every key of the scene schema but [`NOT_FUZZED`]: a key
/// added to `schema::KEYS` fails here until the fuzzer draws it (or it is
/// listed above).
#[test]
fn the_fuzzer_draws_every_scene_key() {
    let dir = scratch("fuzz-keys");
    let mut drawn: Vec<String> = vec![];
    for kind in 0..KINDS.len() {
        let case = Case {
            command: 0,
            length: 6.0,
            links: 4,
            mass: 0.2,
            gravity: 1.0,
            damping: 0.0,
            kind,
            p1: (3.0, 0.0),
            p1_on_circle: false,
            down: 2,
            t_end: 1.0,
            method: 0,
            dt: 0.01,
            rtol: 1e-8,
            atol: 1e-10,
            output_dt: 0.01,
            h_min: 0.0,
            extra: 1,
            with_out: false,
            rho_inf: 0.9,
            axial_stiffness: 1e4,
            axial_damping: 0.0,
            bending_stiffness: 0.0,
            elastic: true,
            tip_mass: 0.0,
            report: true,
            pivot: [0.0, 0.0, 0.0, 1.0, 1.0, 0.0],
            moving: true,
            taper: 1.0,
            profiled: true,
            name: 1,
            same_out: false,
            angle_big: 0.0,
            rod_ratio: 1.0,
            floor: [-10.0, 0.0, 1e4, 0.0, 0.0, 0.01],
            floored: true,
            floor_law: kind % 3,
            restitution: 0.0,
        };
        let tree: toml::Table = case.scene_text().parse().unwrap();
        for (top, value) in &tree {
            match value.as_table() {
                Some(section) => drawn.extend(section.keys().map(|k| format!("{top}.{k}"))),
                None => drawn.push(top.clone()),
            }
        }
        // Keys set on the command line.
        let args = case.args(&dir);
        for pair in args.windows(2).filter(|p| p[0] == "--set") {
            drawn.extend(pair[1].split_once('=').map(|(k, _)| k.to_string()));
        }
    }
    fs::remove_dir_all(&dir).unwrap();
    for path in NOT_FUZZED {
        assert!(fc_scene::schema::key(path).is_some(), "{path} is not a key");
        assert!(!drawn.iter().any(|d| d == path), "{path} is fuzzed");
    }
    for k in fc_scene::schema::KEYS {
        assert!(
            NOT_FUZZED.contains(&k.path) || drawn.iter().any(|d| d == k.path),
            "the fuzzer never draws {}",
            k.path
        );
    }
}
