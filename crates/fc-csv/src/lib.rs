//! The CSV layer: the project's one writer of cells ([`field`]) and its one
//! reader ([`Reader`], [`records`], and [`table::Table`] for a table read
//! whole), RFC 4180 both ways, with the number formats of every table
//! ([`format`]) and the types its writer declares for its columns
//! ([`Column`], [`header`]). It knows no chain and no solver: fc-scene writes a run's
//! samples and summary rows with it, fc-batch its sweep rows and merged
//! shards, fc-study and fc-paper-figures their tables, the Python module
//! reads tables back with it, and `paper` fills its numbers from
//! `figures/data/` through [`table::Table`].
//!
//! The dialect: records end in `\n` or `\r\n`; cells are separated by
//! commas; a cell that holds a comma, a quote or a line break is quoted
//! (`"a,b"`, `"say ""hi"""`), and a quoted cell may span lines. An empty
//! line is no record. Every CSV the tool reads back (a run from `simulate
//! --out`, the study's tables, `figures/data/`, the shards `merge` joins,
//! Python's tables) goes through [`Reader`]; a quote inside an unquoted
//! cell, text after a closing quote or a quoted cell never closed is an
//! error naming its line.
//!
//! Its files: `format.rs` (the number formats) and `table.rs` (a table read
//! whole, with columns by name).

pub mod format;
pub mod table;

use std::borrow::Cow;
use std::fmt;
use std::io::{self, BufRead};

/// A text cell, quoted (RFC 4180) if it holds a comma, a quote or a line break.
pub fn field(text: &str) -> Cow<'_, str> {
    if text.contains([',', '"', '\n', '\r']) {
        Cow::Owned(format!("\"{}\"", text.replace('"', "\"\"")))
    } else {
        Cow::Borrowed(text)
    }
}

/// What a column of a table holds, as the table's writer declares it beside
/// its header ([`header`]), so that a reader (Python's numpy columns) takes
/// the column as written rather than guessing from its cells.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// An integer (a count, a 0/1 flag, a run number). A cell may be empty
    /// where there is none (a run not made, the reference's run number): a
    /// reader then takes the column as numbers with the empty cells missing.
    Int,
    /// A number; an empty cell is missing (NaN).
    Float,
    /// Text, whatever its cells look like.
    Text,
}

/// A table's header line (without its line end): the names of `columns`,
/// each a cell ([`field`]).
pub fn header(columns: &[(&str, Column)]) -> String {
    columns
        .iter()
        .map(|(name, _)| field(name))
        .collect::<Vec<_>>()
        .join(",")
}

/// The type that `declared` (writers' column lists, searched in order)
/// gives the column called `name`; `None` if none names it.
pub fn column_type(declared: &[&[(&str, Column)]], name: &str) -> Option<Column> {
    declared
        .iter()
        .flat_map(|cols| cols.iter())
        .find(|(n, _)| *n == name)
        .map(|&(_, c)| c)
}

/// Why a CSV could not be read.
#[derive(Debug)]
pub enum ReadError {
    /// The input failed.
    Io(io::Error),
    /// The text is not CSV as [`Reader`] reads it: `line` (1-based) is the
    /// first line of the record.
    Syntax { line: usize, what: String },
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io(e) => write!(f, "{e}"),
            Self::Syntax { line, what } => write!(f, "line {line}: {what}"),
        }
    }
}

impl std::error::Error for ReadError {}

/// One record read by [`Reader`]: its cells, its text as it stood in the
/// input (without the line end) and the line it starts on. Reused from
/// record to record, so that reading allocates only when a record is longer
/// than any before it.
#[derive(Clone, Debug, Default)]
pub struct Record {
    /// The cells' text, one after the other.
    text: String,
    /// Where each cell ends in `text`.
    ends: Vec<usize>,
    /// The record as in the input.
    raw: String,
    /// The record's first line (1-based).
    line: usize,
    /// Where the record starts in the input (bytes).
    start: usize,
}

impl Record {
    /// The number of cells.
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// Whether it has no cell (never, for a record read).
    pub fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// Cell `i`, unquoted.
    pub fn get(&self, i: usize) -> Option<&str> {
        let end = *self.ends.get(i)?;
        let start = if i == 0 { 0 } else { self.ends[i - 1] };
        self.text.get(start..end)
    }

    /// The cells in order, unquoted.
    pub fn iter(&self) -> impl Iterator<Item = &str> + '_ {
        (0..self.len()).filter_map(|i| self.get(i))
    }

    /// The cells as owned text.
    pub fn to_vec(&self) -> Vec<String> {
        self.iter().map(str::to_string).collect()
    }

    /// The record's text as it stood in the input, quotes and embedded
    /// line breaks included, without its line end.
    pub fn raw(&self) -> &str {
        &self.raw
    }

    /// The line (1-based) the record starts on.
    pub fn line(&self) -> usize {
        self.line
    }

    /// Where [`Record::raw`] stands in the input (bytes).
    pub fn span(&self) -> std::ops::Range<usize> {
        self.start..self.start + self.raw.len()
    }
}

/// The most cells of a record a [`Reader`] takes unless told otherwise
/// ([`Reader::max_cells`]): a trajectory of 10^6 rods with its forces has
/// about 3 * 10^6 columns.
pub const MAX_CELLS: usize = 1 << 23;

/// The RFC 4180 reader (see the module's dialect) over any buffered input,
/// one record at a time: a file is never held whole.
pub struct Reader<R> {
    input: R,
    /// Lines read so far.
    line: usize,
    /// Bytes read so far.
    pos: usize,
    max_cells: usize,
}

impl<R: BufRead> Reader<R> {
    /// A reader of `input`, taking at most [`MAX_CELLS`] cells a record.
    pub fn new(input: R) -> Self {
        Self {
            input,
            line: 0,
            pos: 0,
            max_cells: MAX_CELLS,
        }
    }

    /// At most `max` cells a record (a record with more is an error).
    #[must_use]
    pub fn max_cells(mut self, max: usize) -> Self {
        self.max_cells = max;
        self
    }

    /// Reads the next record into `record` (empty lines are skipped);
    /// `false` at the end of the input.
    pub fn read(&mut self, record: &mut Record) -> Result<bool, ReadError> {
        let mut line = String::new();
        loop {
            record.raw.clear();
            record.text.clear();
            record.ends.clear();
            record.line = self.line + 1;
            record.start = self.pos;
            let mut state = State::Start;
            loop {
                line.clear();
                let got = self.input.read_line(&mut line).map_err(ReadError::Io)?;
                if got == 0 {
                    if state == State::Quoted {
                        return Err(record.error(NOT_CLOSED));
                    }
                    return Ok(false);
                }
                self.line += 1;
                self.pos += got;
                let body = line
                    .strip_suffix('\n')
                    .map_or(line.as_str(), |l| l.strip_suffix('\r').unwrap_or(l));
                record.raw.push_str(body);
                state = record.scan(body, state, self.max_cells)?;
                if state != State::Quoted {
                    break;
                }
                // A line break inside a quoted cell is the cell's.
                let end = &line[body.len()..];
                record.raw.push_str(end);
                record.text.push_str(end);
            }
            if record.raw.is_empty() {
                continue;
            }
            record.end_cell(self.max_cells)?;
            return Ok(true);
        }
    }
}

const NOT_CLOSED: &str = "a quoted cell is not closed (a '\"' is missing)";

/// Where [`Record::scan`] is in a record.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    /// At the start of a cell.
    Start,
    /// In a cell that is not quoted.
    Plain,
    /// In a quoted cell.
    Quoted,
    /// Just after a `"` in a quoted cell: its end, or the first of `""`.
    QuoteSeen,
}

impl Record {
    fn error(&self, what: &str) -> ReadError {
        ReadError::Syntax {
            line: self.line,
            what: what.to_string(),
        }
    }

    fn end_cell(&mut self, max_cells: usize) -> Result<(), ReadError> {
        if self.ends.len() == max_cells {
            return Err(self.error(&format!("more than {max_cells} cells")));
        }
        self.ends.push(self.text.len());
        Ok(())
    }

    /// Reads the cells of one line (without its line end) from `state`;
    /// returns the state at its end.
    fn scan(&mut self, body: &str, mut state: State, max_cells: usize) -> Result<State, ReadError> {
        let b = body.as_bytes();
        let mut i = 0;
        while i < b.len() {
            match state {
                State::Start if b[i] == b'"' => {
                    state = State::Quoted;
                    i += 1;
                }
                State::Start => state = State::Plain,
                State::Plain => {
                    let j = body[i..].find([',', '"']).map_or(b.len(), |j| i + j);
                    self.text.push_str(&body[i..j]);
                    match b.get(j) {
                        None => i = j,
                        Some(b',') => {
                            self.end_cell(max_cells)?;
                            state = State::Start;
                            i = j + 1;
                        }
                        Some(_) => {
                            return Err(self.error(
                                "a '\"' inside a cell that is not quoted (such a cell is \
                                 written \"...\" with the quote doubled)",
                            ))
                        }
                    }
                }
                State::Quoted => {
                    let j = body[i..].find('"').map_or(b.len(), |j| i + j);
                    self.text.push_str(&body[i..j]);
                    if j < b.len() {
                        state = State::QuoteSeen;
                        i = j + 1;
                    } else {
                        i = j;
                    }
                }
                State::QuoteSeen => match b[i] {
                    b'"' => {
                        self.text.push('"');
                        state = State::Quoted;
                        i += 1;
                    }
                    b',' => {
                        self.end_cell(max_cells)?;
                        state = State::Start;
                        i += 1;
                    }
                    _ => {
                        return Err(self.error(
                            "text after a quoted cell's closing '\"' (a quote inside a cell \
                             is written twice)",
                        ))
                    }
                },
            }
        }
        Ok(state)
    }
}

/// Every record of `text`, as owned cells.
pub fn records(text: &str) -> Result<Vec<Vec<String>>, ReadError> {
    let mut reader = Reader::new(text.as_bytes());
    let mut record = Record::default();
    let mut out = vec![];
    while reader.read(&mut record)? {
        out.push(record.to_vec());
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_quoted_only_when_needed() {
        assert_eq!(field("span-d3"), "span-d3");
        assert_eq!(field("a,b"), "\"a,b\"");
        assert_eq!(field("say \"hi\""), "\"say \"\"hi\"\"\"");
    }

    #[test]
    fn headers_and_declared_types() {
        let a = [("run", Column::Int), ("a,b", Column::Text)];
        let b = [("run", Column::Float), ("x", Column::Float)];
        assert_eq!(header(&a), "run,\"a,b\"");
        assert_eq!(column_type(&[&a, &b], "run"), Some(Column::Int));
        assert_eq!(column_type(&[&a, &b], "x"), Some(Column::Float));
        assert_eq!(column_type(&[&a, &b], "y"), None);
    }

    fn read(text: &str) -> Result<Vec<(usize, Vec<String>, String)>, ReadError> {
        let mut reader = Reader::new(text.as_bytes());
        let mut r = Record::default();
        let mut out = vec![];
        while reader.read(&mut r)? {
            out.push((r.line(), r.to_vec(), r.raw().to_string()));
        }
        Ok(out)
    }

    #[test]
    fn what_is_written_reads_back() {
        let nasty = [
            "",
            "plain",
            "a,b",
            "say \"hi\"",
            "two\nlines",
            "cr\r\nlf",
            ",\"\n\",",
        ];
        let line = nasty.iter().map(|c| field(c)).collect::<Vec<_>>().join(",");
        let text = format!("h\n{line}\r\n\nlast\n");
        let got = read(&text).unwrap();
        assert_eq!(got.len(), 3, "{got:?}");
        assert_eq!(got[1].1, nasty);
        assert_eq!(got[1].2, line);
        let mut reader = Reader::new(text.as_bytes());
        let mut r = Record::default();
        while reader.read(&mut r).unwrap() {
            assert_eq!(&text[r.span()], r.raw());
        }
        assert_eq!((got[0].0, got[1].0, got[2].0), (1, 2, 7));
        assert_eq!(got[2].1, ["last"]);
        assert_eq!(records("a,,\n").unwrap(), [["a", "", ""]]);
        assert_eq!(records("x").unwrap(), [["x"]]);
        assert!(records("").unwrap().is_empty());
    }

    #[test]
    fn malformed_quotes_name_their_line() {
        for (text, line, what) in [
            ("a\nb\"c\n", 2, "not quoted"),
            ("a\n\"b\"c\n", 2, "after a quoted cell"),
            ("a\n\"b\n\nc\n", 2, "not closed"),
            ("a\n\"b\"\"\n", 2, "not closed"),
        ] {
            match read(text) {
                Err(ReadError::Syntax { line: l, what: w }) => {
                    assert_eq!(l, line, "{text:?}: {w}");
                    assert!(w.contains(what), "{text:?}: {w}");
                }
                other => panic!("{text:?}: {other:?}"),
            }
        }
        let mut reader = Reader::new("a,b,c\n".as_bytes()).max_cells(2);
        let e = reader.read(&mut Record::default()).unwrap_err().to_string();
        assert_eq!(e, "line 1: more than 2 cells");
    }
}
