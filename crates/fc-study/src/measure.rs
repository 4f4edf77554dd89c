//! What a study measures (`--measure`, Python's `measure=`): the tip (the
//! default, the tip's position at the end and the largest tip speed), or
//! any of the run's scalar results: the largest tip speed, the peak pivot
//! force, the largest joint tension, the floor's largest force, the
//! floor's reading and the work dissipated; several at once.
//!
//! A study's error is the largest relative error over its measures, and
//! each measure's own error is reported beside it:
//!
//! * `tip`: `max(|tip_end - tip_ref| / L, |v_max / v_max_ref - 1|)`;
//! * `tip_speed_max`, `pivot_force_max`, `tension_max`,
//!   `floor_force_max`, `floor_reading`: `|x / x_ref - 1|` (the forces are
//!   the run's peaks, `Summary::peak`, tracked at every step and refined
//!   inside it);
//! * `dissipated`: `|W - W_ref| / E_s`, the chain's energy scale (`M g L`
//!   where `g > 0`), since the work dissipated is a share of the energy and
//!   is zero on an undamped chain.
//!
//! The floor's reading is [`chain_ode::analysis::floor_reading`] over the
//! last window of the run: the floor's normal force averaged over
//! `[t_end - w, t_end]`, `w = t_end / 10` ([`FLOOR_READING_WINDOW`]), over
//! `3 mu g x`, `x` the landed length averaged over the same window. The runs
//! that measure it keep samples every `w / 2`.
//!
//! One rule for the work a study pays: a run tracks the pivot's force and
//! the tensions (`Solve::without_force_peaks` otherwise) exactly when the
//! study measures one of them ([`Measures::tracks_forces`]); the floor's
//! peak is tracked whenever there is a floor.

use chain_ode::{Model, PeakForce, Trajectory};

use fc_scene::error::{echo, Error};
use fc_scene::scene::Prepared;

/// One quantity a study can measure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Measure {
    Tip,
    TipSpeedMax,
    PivotForceMax,
    TensionMax,
    FloorForceMax,
    FloorReading,
    Dissipated,
}

/// How many measures there are (the length of [`Values`]).
pub const COUNT: usize = 7;

/// The floor's reading's window, as a fraction of the run's end time.
pub const FLOOR_READING_WINDOW: f64 = 0.1;

impl Measure {
    pub const ALL: [Measure; COUNT] = [
        Measure::Tip,
        Measure::TipSpeedMax,
        Measure::PivotForceMax,
        Measure::TensionMax,
        Measure::FloorForceMax,
        Measure::FloorReading,
        Measure::Dissipated,
    ];

    /// Its name in `--measure`, the tables and the JSON (a force's is
    /// `simulate --json`'s `<name>_max`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Tip => "tip",
            Self::TipSpeedMax => "tip_speed_max",
            Self::PivotForceMax => "pivot_force_max",
            Self::TensionMax => "tension_max",
            Self::FloorForceMax => "floor_force_max",
            Self::FloorReading => "floor_reading",
            Self::Dissipated => "dissipated",
        }
    }

    fn index(self) -> usize {
        self as usize
    }

    /// The peak force it reads, if it is one.
    pub fn force(self) -> Option<PeakForce> {
        match self {
            Self::PivotForceMax => Some(PeakForce::Pivot),
            Self::TensionMax => Some(PeakForce::Tension),
            Self::FloorForceMax => Some(PeakForce::Floor),
            _ => None,
        }
    }

    /// Whether a run of `chain` has it: the pivot's force and the tensions
    /// on every model but the constraint floor's (whose forces are
    /// impulses), the floor's force on a penalty floor, its reading on any
    /// floor; the tip and the dissipated work always.
    pub fn available(self, chain: &chain_ode::Chain) -> bool {
        let floor = chain.floor().map(|f| f.law);
        let constraint = floor == Some(chain_ode::FloorLaw::Constraint);
        match self {
            Self::Tip | Self::TipSpeedMax | Self::Dissipated => true,
            Self::PivotForceMax | Self::TensionMax => !constraint,
            Self::FloorForceMax => floor == Some(chain_ode::FloorLaw::Penalty),
            Self::FloorReading => floor.is_some(),
        }
    }
}

/// A set of measures (never empty): `tip` alone is the default.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Measures(u8);

impl Default for Measures {
    fn default() -> Self {
        Self::TIP
    }
}

impl Measures {
    /// `tip` alone: today's studies, byte for byte.
    pub const TIP: Measures = Measures(1);

    /// The set of `list` (`tip` if empty).
    pub fn of(list: &[Measure]) -> Self {
        let bits = list.iter().fold(0u8, |b, m| b | (1 << m.index()));
        if bits == 0 {
            Self::TIP
        } else {
            Self(bits)
        }
    }

    /// Whether it holds `m`.
    pub fn has(self, m: Measure) -> bool {
        self.0 & (1 << m.index()) != 0
    }

    /// Its measures, in [`Measure::ALL`]'s order.
    pub fn list(self) -> Vec<Measure> {
        Measure::ALL.into_iter().filter(|&m| self.has(m)).collect()
    }

    /// True for `tip` alone (the default: every table and line as before).
    pub fn is_tip(self) -> bool {
        self == Self::TIP
    }

    /// The names, comma-separated (`--measure`'s form).
    pub fn names(self) -> String {
        self.list()
            .iter()
            .map(|m| m.name())
            .collect::<Vec<_>>()
            .join(",")
    }

    /// Whether its runs must track the pivot's force and the tensions
    /// (one rule for every study: exactly when it measures one of them).
    pub fn tracks_forces(self) -> bool {
        self.has(Measure::PivotForceMax) || self.has(Measure::TensionMax)
    }

    /// The output spacing its runs need up to `t_end`: `w / 2` for the
    /// floor's reading ([`FLOOR_READING_WINDOW`]), else none.
    pub fn output_dt(self, t_end: f64) -> Option<f64> {
        self.has(Measure::FloorReading)
            .then_some(0.5 * FLOOR_READING_WINDOW * t_end)
    }

    /// Parses `what` (`--measure`, Python's `measure`): measure names
    /// separated by commas (`None`: `tip`), each one `chain` has
    /// ([`Measure::available`]). One line names `what` and the values this
    /// scene accepts.
    pub fn parse(what: &str, text: Option<&str>, chain: &chain_ode::Chain) -> Result<Self, Error> {
        let Some(text) = text else {
            return Ok(Self::TIP);
        };
        let accepted: Vec<&str> = Measure::ALL
            .into_iter()
            .filter(|m| m.available(chain))
            .map(Measure::name)
            .collect();
        let refuse = |why: String| {
            Error::field(
                what,
                format!(
                    "{why}: give one or more of {} (this scene's), separated by commas",
                    accepted.join(", ")
                ),
            )
        };
        if text.trim().is_empty() {
            return Err(refuse("names no measure".into()));
        }
        let mut list = vec![];
        for name in text.split(',').map(str::trim) {
            let m = Measure::ALL
                .into_iter()
                .find(|m| m.name() == name)
                .ok_or_else(|| refuse(format!("'{}' is no measure", echo(name))))?;
            if !m.available(chain) {
                return Err(refuse(format!("this scene has no {}", m.name())));
            }
            list.push(m);
        }
        Ok(Self::of(&list))
    }

    /// [`Measures::parse`] on a prepared scene's chain.
    pub fn parse_for(what: &str, text: Option<&str>, p: &Prepared) -> Result<Self, Error> {
        Self::parse(what, text, &p.chain)
    }
}

/// The value and the error scale of each measure of one run, NaN where not
/// measured (indexed as [`Measure::ALL`]; `tip`'s slot is unused, its
/// error being the tip's pair).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Values {
    pub value: [f64; COUNT],
    /// What its error divides by: `|x_ref|`, or `E_s` for `dissipated`.
    pub scale: [f64; COUNT],
}

impl Values {
    /// Nothing measured.
    pub const NONE: Values = Values {
        value: [f64::NAN; COUNT],
        scale: [f64::NAN; COUNT],
    };

    /// The values of `measures` of the finished run `t` (NaN for one the
    /// run does not have: a peak it did not track, a reading with no
    /// landed chain in its window).
    pub fn of<M: Model>(t: &Trajectory<M>, measures: Measures) -> Values {
        let mut out = Values::NONE;
        let s = &t.summary;
        let energy_scale = t.model.chain().map_or(f64::NAN, |c| c.energy_scale());
        for m in measures.list() {
            let v = match m {
                Measure::Tip => f64::NAN,
                Measure::TipSpeedMax => s.tip_speed_max,
                Measure::Dissipated => s.dissipated,
                Measure::FloorReading => floor_reading(t),
                _ => m
                    .force()
                    .and_then(|f| s.peak(f))
                    .map_or(f64::NAN, |p| p.value),
            };
            out.value[m.index()] = v;
            out.scale[m.index()] = if m == Measure::Dissipated {
                energy_scale
            } else {
                v.abs()
            };
        }
        out
    }

    /// The value of `m`.
    pub fn get(&self, m: Measure) -> f64 {
        self.value[m.index()]
    }

    /// The relative error of `m` in `run` against this reference.
    pub fn error(&self, run: &Values, m: Measure) -> f64 {
        let k = m.index();
        (run.value[k] - self.value[k]).abs() / self.scale[k]
    }
}

/// The floor's reading over the run's last window (see the module's doc),
/// NaN without one.
fn floor_reading<M: Model>(t: &Trajectory<M>) -> f64 {
    let window = FLOOR_READING_WINDOW * t.t_reached;
    match chain_ode::analysis::floor_reading(t, window) {
        Some(Ok(r)) => r.reading.last().copied().unwrap_or(f64::NAN),
        _ => f64::NAN,
    }
}

/// The errors of each of `measures` of a run against a reference: `tip`'s
/// is `tip` (the larger of the tip's pair), the others' from `values`
/// against `reference`; and the largest of them, the study's error.
pub fn errors(
    measures: Measures,
    tip: f64,
    reference: &Values,
    values: &Values,
) -> ([f64; COUNT], f64) {
    let mut each = [f64::NAN; COUNT];
    let mut worst: f64 = 0.0;
    for m in measures.list() {
        let e = if m == Measure::Tip {
            tip
        } else {
            reference.error(values, m)
        };
        each[m.index()] = e;
        // NaN (a measure missing) makes the whole error NaN: not `ok`.
        worst = if e.is_nan() { f64::NAN } else { worst.max(e) };
        if worst.is_nan() {
            break;
        }
    }
    (each, worst)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain(extra: &str) -> chain_ode::Chain {
        let text = format!(
            "[chain]\nlength = 6.0\nlinks = 4\nmass = 0.2\n\
             [start]\nkind = \"folded\"\ndown = 2\n[run]\nt_end = 1.0\n{extra}"
        );
        fc_scene::scene::Scene::from_toml_str(&text)
            .unwrap()
            .chain()
            .unwrap()
    }

    /// No `--measure` is `tip`; a list parses in any order; a bad name and
    /// a measure the scene cannot have are refused naming `--measure` and
    /// this scene's accepted values.
    #[test]
    fn parse_and_refuse() {
        let c = chain("");
        assert!(Measures::parse("--measure", None, &c).unwrap().is_tip());
        let m = Measures::parse("--measure", Some("pivot_force_max, tip"), &c).unwrap();
        assert_eq!(m.list(), vec![Measure::Tip, Measure::PivotForceMax]);
        assert!(m.tracks_forces());
        assert!(!Measures::of(&[Measure::Dissipated]).tracks_forces());
        let e = Measures::parse("--measure", Some("floor_force_max"), &c)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--measure") && e.contains("no floor_force_max"),
            "{e}"
        );
        assert!(
            e.contains("tip, tip_speed_max, pivot_force_max, tension_max, dissipated"),
            "{e}"
        );
        assert!(!e.contains('\n'), "{e}");
        let e = Measures::parse("--measure", Some("speed"), &c)
            .unwrap_err()
            .to_string();
        assert!(e.contains("'speed' is no measure"), "{e}");
        let floored = chain("[floor]\nheight = -3.2\nlaw = \"penalty\"\n");
        assert!(
            Measures::parse("--measure", Some("floor_force_max,floor_reading"), &floored).is_ok()
        );
    }
}
