//! The one error type of this crate: every failure is one line that starts
//! with the field (or file role) it is about.

use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use catenary::{CatenaryError, Input};
use chain_ode::{InvalidParameter, StartError};

/// Why a scene, an override, a computation's input or an output failed.
///
/// `Display` is always a single line that starts with the field path as a
/// scene would spell it (`chain.links: ...`, `start.p1: ...`), or with the
/// role of a file (`scene: cannot read 'x.toml': ...`).
#[derive(Debug)]
pub enum Error {
    /// A file could not be read. `what` is its role (`"scene"`).
    Read {
        what: &'static str,
        path: PathBuf,
        source: io::Error,
    },
    /// An output could not be written. `what` is its role (`"--out"`).
    Write {
        what: &'static str,
        path: PathBuf,
        source: io::Error,
    },
    /// A value is wrong: syntax, unknown key, wrong type, missing, or out of range.
    Field { field: String, message: String },
    /// The work was stopped from outside (a [`chain_ode::Cancel`] was set:
    /// Ctrl-C in Python, SIGINT or SIGTERM in the CLI) before it finished.
    Interrupted,
}

impl Error {
    /// An error about the value at `field` (a dotted scene path or a flag).
    pub fn field(field: impl Into<String>, message: impl fmt::Display) -> Self {
        Self::Field {
            field: field.into(),
            message: message.to_string(),
        }
    }

    /// A read failure of the file at `path` in role `what`.
    pub fn read(what: &'static str, path: &Path, source: io::Error) -> Self {
        Self::Read {
            what,
            path: path.to_path_buf(),
            source,
        }
    }

    /// A write failure of the file at `path` in role `what`.
    pub fn write(what: &'static str, path: &Path, source: io::Error) -> Self {
        Self::Write {
            what,
            path: path.to_path_buf(),
            source,
        }
    }

    /// The field path or file role the error is about (what `Display` starts with).
    pub fn subject(&self) -> &str {
        match self {
            Self::Read { what, .. } | Self::Write { what, .. } => what,
            Self::Field { field, .. } => field,
            Self::Interrupted => "interrupted",
        }
    }

    /// Maps a catenary error onto the names the caller uses for the
    /// catenary's inputs (`p0`, `p1`, `length`, `links`; an error about no
    /// input, such as a solver failure, is reported under `other`), and
    /// points a vertical chain to the scene's folded start.
    pub fn from_catenary(e: &CatenaryError, names: &CatenaryNames) -> Self {
        let name = match e.input() {
            Some(Input::P0) => names.p0,
            Some(Input::P1) => names.p1,
            Some(Input::Length) => names.length,
            Some(Input::Links) => names.links,
            None => names.other,
        };
        let mut message = e.reason();
        if let CatenaryError::Vertical { .. } = e {
            message.push_str(" (start.kind = \"folded\")");
        }
        Self::field(name, message)
    }
}

/// What the inputs of a catenary are called where they came from.
#[derive(Clone, Copy, Debug)]
pub struct CatenaryNames {
    pub p0: &'static str,
    pub p1: &'static str,
    pub length: &'static str,
    pub links: &'static str,
    /// For errors not about one input (a solver that did not converge).
    pub other: &'static str,
}

impl CatenaryNames {
    /// The names in a scene file.
    pub const SCENE: Self = Self {
        p0: "start.p0",
        p1: "start.p1",
        length: "chain.length",
        links: "chain.links",
        other: "start",
    };
}

/// `io::Error`'s text without the trailing ` (os error N)`.
fn io_reason(e: &io::Error) -> String {
    let text = e.to_string();
    match text.rfind(" (os error ") {
        Some(i) if text.ends_with(')') => text[..i].to_string(),
        _ => text,
    }
}

/// The longest echo of a user's value in a message (characters), before
/// it is cut with an ellipsis and its length.
pub const ECHO_MAX: usize = 80;

/// The longest message line before its middle is cut (a net under
/// [`echo`]: no message echoes a whole large input).
const MESSAGE_MAX: usize = 600;

/// `text` with every control character escaped (`\n`, `\t`, `\u{1b}`), so
/// that it stays on one line; other characters are kept.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    out
}

/// A user's text as a message echoes it: control characters escaped, and
/// cut after [`ECHO_MAX`] characters with an ellipsis and the length
/// (`[1, 2, 3, ...… (25000001 characters)`).
pub fn echo(text: &str) -> String {
    let count = text.chars().count();
    if count <= ECHO_MAX {
        return escape(text);
    }
    let head: String = text.chars().take(ECHO_MAX).collect();
    format!("{}… ({count} characters)", escape(&head))
}

/// A number as a message shows it, in the shortest form that reads back
/// to it, as a person writes it: `0.5`, `4.157`, `1e300` (not the 301
/// digits of `f64`'s `Display`), `1e-9`, `NaN`, `inf`.
pub fn number(x: f64) -> String {
    fc_csv::format::short(x)
}

/// A TOML value as a message echoes it ([`echo`]): numbers by [`number`],
/// a date-time as written (`1979-05-27T07:32:00Z`, never the parser's
/// private key); a long array is shown by its first elements and its
/// length, without writing it out whole.
pub fn echo_value(value: &toml::Value) -> String {
    echo(&value_text(value))
}

/// `value` as TOML writes it, numbers by [`number`], long arrays and
/// tables cut.
fn value_text(value: &toml::Value) -> String {
    use toml::Value as V;
    match value {
        V::Float(x) if x.is_nan() => "nan".into(),
        V::Float(x) if x.is_infinite() => if *x > 0.0 { "inf" } else { "-inf" }.into(),
        V::Float(x) => number(*x),
        V::Integer(i) => i.to_string(),
        V::Boolean(b) => b.to_string(),
        V::Datetime(d) => d.to_string(),
        V::String(_) => value.to_string(),
        V::Array(items) if items.len() > 8 => {
            let head: Vec<String> = items[..4].iter().map(value_text).collect();
            format!("[{}, … ({} elements)]", head.join(", "), items.len())
        }
        V::Array(items) => {
            let all: Vec<String> = items.iter().map(value_text).collect();
            format!("[{}]", all.join(", "))
        }
        V::Table(t) if t.len() > 8 => format!("a table of {} keys", t.len()),
        V::Table(t) => {
            let all: Vec<String> = t
                .iter()
                .map(|(k, v)| format!("{k} = {}", value_text(v)))
                .collect();
            format!("{{ {} }}", all.join(", "))
        }
    }
}

/// A path as a message echoes it: escaped, and cut when very long.
pub fn echo_path(path: &Path) -> String {
    let text = path.to_string_lossy();
    if text.chars().count() <= 4 * ECHO_MAX {
        escape(&text)
    } else {
        let head: String = text.chars().take(4 * ECHO_MAX).collect();
        format!("{}…", escape(&head))
    }
}

/// A message on one line: control characters escaped, and (a net under
/// [`echo`]) a very long one cut in the middle.
fn one_line(text: &str) -> String {
    let text = escape(text);
    let count = text.chars().count();
    if count <= MESSAGE_MAX {
        return text;
    }
    let head: String = text.chars().take(MESSAGE_MAX - 100).collect();
    let tail: String = text.chars().skip(count - 100).collect();
    format!("{head} … {tail}")
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Read { what, path, source } => write!(
                f,
                "{what}: cannot read '{}': {}",
                echo_path(path),
                one_line(&io_reason(source))
            ),
            Self::Write { what, path, source } => write!(
                f,
                "{what}: cannot write '{}': {}",
                echo_path(path),
                one_line(&io_reason(source))
            ),
            Self::Field { field, message } => {
                write!(f, "{}: {}", echo(field), one_line(message))
            }
            Self::Interrupted => f.write_str("interrupted: stopped before the work was done"),
        }
    }
}

impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Read { source, .. } | Self::Write { source, .. } => Some(source),
            Self::Field { .. } | Self::Interrupted => None,
        }
    }
}

impl From<InvalidParameter> for Error {
    fn from(e: InvalidParameter) -> Self {
        Self::field(
            e.field,
            format!("must be {} (got {})", e.accepted, echo(&e.got)),
        )
    }
}

impl From<StartError> for Error {
    fn from(e: StartError) -> Self {
        match e {
            StartError::Parameter(p) => p.into(),
            StartError::Catenary(c) => Self::from_catenary(&c, &CatenaryNames::SCENE),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_are_one_line_and_start_with_the_subject() {
        let e = Error::read(
            "scene",
            Path::new("x.toml"),
            io::Error::from(io::ErrorKind::NotFound),
        );
        assert!(e.to_string().starts_with("scene: cannot read 'x.toml': "));
        let e = Error::field("chain.links", "bad\n  value");
        assert_eq!(e.to_string(), "chain.links: bad\\n  value");
        assert_eq!(e.subject(), "chain.links");
        let e = Error::field("chain.li\nnks", "unknown key");
        assert_eq!(e.to_string(), "chain.li\\nnks: unknown key");
    }

    #[test]
    fn echoes_are_short_and_escaped() {
        let long = toml::Value::Array((0..5_000_000).map(toml::Value::Integer).collect());
        let e = echo_value(&long);
        assert!(e.chars().count() < 2 * ECHO_MAX, "{e}");
        assert!(e.contains("5000000 elements"), "{e}");
        assert_eq!(echo_value(&toml::Value::Float(1e300)), "1e300");
        assert_eq!(
            echo_value(&"v = [1e-300, 0.5, 2]".parse::<toml::Table>().unwrap()["v"]),
            "[1e-300, 0.5, 2]"
        );
        let date = "v = 1979-05-27T07:32:00Z".parse::<toml::Table>().unwrap();
        assert_eq!(echo_value(&date["v"]), "1979-05-27T07:32:00Z");
        assert_eq!(number(4.157), "4.157");
        assert_eq!(number(-2.5e-7), "-2.5e-7");
        assert_eq!(number(f64::NAN), "NaN");
        let text = "x".repeat(10_000);
        let e = echo(&text);
        assert!(e.ends_with("… (10000 characters)"), "{e}");
        assert_eq!(escape("a\tb\u{1b}c"), "a\\tb\\u{1b}c");
        let e = Error::write("--out", Path::new("a\nb.csv"), io::Error::other("x"));
        assert_eq!(e.to_string(), "--out: cannot write 'a\\nb.csv': x");
        let e = Error::field("x", "y".repeat(100_000)).to_string();
        assert!(e.len() < 1000, "{}", e.len());
    }

    #[test]
    fn os_error_suffix_is_dropped() {
        let e = io::Error::from_raw_os_error(2);
        assert!(!io_reason(&e).contains("os error"), "{}", io_reason(&e));
    }

    #[test]
    fn catenary_fields_become_scene_paths() {
        let c = catenary::Catenary::through([0.0, 0.0], [5.0, 1.0], 4.0).unwrap_err();
        let e = Error::from_catenary(&c, &CatenaryNames::SCENE);
        assert!(e.to_string().starts_with("chain.length: "), "{e}");
    }

    #[test]
    fn every_catenary_input_has_its_scene_path() {
        let nan = f64::NAN;
        for (p1, length, links, subject) in [
            ([nan, 0.0], 2.0, 5, "start.p1"),
            ([1.0, 0.0], -1.0, 5, "chain.length"),
            ([1.0, 0.0], 2.0, 0, "chain.links"),
            ([1.0, 0.0], 2.0, 1, "chain.links"),
            ([0.0, -1.0], 2.0, 5, "start.p1"),
        ] {
            let c = catenary::discrete_equilibrium([0.0, 0.0], p1, length, links).unwrap_err();
            let e = Error::from_catenary(&c, &CatenaryNames::SCENE);
            assert_eq!(e.subject(), subject, "{c:?}");
            let expect = format!("{subject}: {}", c.reason());
            assert!(e.to_string().starts_with(&expect), "{e}");
        }
        // Where the folded start is chosen is the scene's business.
        let c = catenary::discrete_equilibrium([0.0, 0.0], [0.0, -1.0], 2.0, 5).unwrap_err();
        let e = Error::from_catenary(&c, &CatenaryNames::SCENE).to_string();
        assert!(
            e.ends_with("use the folded start (start.kind = \"folded\")"),
            "{e}"
        );
        // An error about no input is reported under `other`.
        let c = CatenaryError::NoConvergence {
            solver: "Newton",
            iterations: 3,
            residual: 1.0,
        };
        let e = Error::from_catenary(&c, &CatenaryNames::SCENE);
        assert_eq!(
            e.to_string(),
            "start: Newton did not converge after 3 iterations (residual 1e0)"
        );
    }
}
