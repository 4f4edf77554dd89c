//! A CSV table read whole (the study's tables, `figures/data/`): the
//! header and the rows as text, with columns by name.
//!
//! The dialect is the project's one, RFC 4180 ([`crate::Reader`]): a
//! header record, then one record per row; a text cell holding a comma, a
//! quote or a line break is quoted ([`super::format::text`] writes the
//! figures' labels with semicolons for commas, so their tables need no
//! quotes). An empty cell is a missing number (read as NaN).

use std::fs;
use std::path::Path;

/// A CSV file read whole: the header and the rows, as text.
#[derive(Debug, Clone)]
pub struct Table {
    /// The file name, for messages.
    pub name: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// Reads `path`.
    pub fn read(path: &Path) -> Result<Table, String> {
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into(),
        );
        let text = fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        Table::parse(&name, &text)
    }

    /// Parses the text of a CSV file called `name`.
    pub fn parse(name: &str, text: &str) -> Result<Table, String> {
        let mut reader = crate::Reader::new(text.as_bytes());
        let mut record = crate::Record::default();
        let bad = |e: crate::ReadError| format!("{name}: {e}");
        if !reader.read(&mut record).map_err(bad)? {
            return Err(format!("{name}: empty"));
        }
        let header = record.to_vec();
        let mut rows = vec![];
        while reader.read(&mut record).map_err(bad)? {
            if record.len() != header.len() {
                return Err(format!(
                    "{name}: line {} has {} cells, the header {}",
                    record.line(),
                    record.len(),
                    header.len()
                ));
            }
            rows.push(record.to_vec());
        }
        Ok(Table {
            name: name.to_string(),
            header,
            rows,
        })
    }

    /// The index of column `name`.
    pub fn col(&self, name: &str) -> Result<usize, String> {
        self.header.iter().position(|c| c == name).ok_or_else(|| {
            format!(
                "{}: no column '{name}' (columns: {})",
                self.name,
                self.header.join(", ")
            )
        })
    }

    /// Column `name` as text.
    pub fn strs(&self, name: &str) -> Result<Vec<&str>, String> {
        let c = self.col(name)?;
        Ok(self.rows.iter().map(|r| r[c].as_str()).collect())
    }

    /// Column `name` as numbers (an empty cell is NaN).
    pub fn nums(&self, name: &str) -> Result<Vec<f64>, String> {
        let c = self.col(name)?;
        self.rows
            .iter()
            .enumerate()
            .map(|(k, r)| {
                parse_num(&r[c]).map_err(|e| format!("{}: row {}: {e}", self.name, k + 2))
            })
            .collect()
    }

    /// The number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether it has no row.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }
}

/// A number cell (empty: NaN).
pub fn parse_num(s: &str) -> Result<f64, String> {
    if s.is_empty() {
        return Ok(f64::NAN);
    }
    s.parse::<f64>()
        .map_err(|_| format!("'{s}' is not a number"))
}

/// The distinct values of `column`, in the order they first appear.
pub fn distinct<'a>(column: &[&'a str]) -> Vec<&'a str> {
    let mut out: Vec<&str> = vec![];
    for &v in column {
        if !out.contains(&v) {
            out.push(v);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_by_column() {
        let t = Table::parse("t.csv", "a,b\nx,1.5\ny,\n").unwrap();
        assert_eq!(t.strs("a").unwrap(), vec!["x", "y"]);
        let b = t.nums("b").unwrap();
        assert_eq!(b[0], 1.5);
        assert!(b[1].is_nan());
        assert!(t.col("c").unwrap_err().contains("no column 'c'"));
        assert!(Table::parse("u.csv", "a,b\n1\n").is_err());
        let q = Table::parse("q.csv", "a,b\n\"x, \"\"y\"\"\nz\",2\n").unwrap();
        assert_eq!(q.strs("a").unwrap(), vec!["x, \"y\"\nz"]);
        assert!(Table::parse("v.csv", "a,b\nx\"y,2\n")
            .unwrap_err()
            .starts_with("v.csv: line 2: "));
        assert_eq!(distinct(&["p", "q", "p"]), vec!["p", "q"]);
    }
}
