//! The papers' typed decimals: a number with a decimal point or an exponent
//! (`2.5`, `1e-8`, `5.5×10³`, `10⁻⁴`, `10^{-4}`) typed into a template
//! instead of filled from `figures/data/` by a placeholder. `cargo xtask
//! paper [--check]` fails on one that `paper/inputs.csv` does not list.
//!
//! `paper/inputs.csv` (`document,text,count,kind,reason`) lists, per
//! template, each typed decimal the text may hold, how many times, what kind
//! of number it is and why it is typed. The kinds are the inputs a paper
//! states rather than measures (`parameter`: a scene's or a method's
//! setting; `tolerance`; `literature`: a value quoted from a reference;
//! `identifier`: a date, version, section or reference number; `exact`: a
//! closed form's constant) and `pending`: a result typed in an earlier round
//! that no figure's data holds yet, listed so that the check can name how
//! many remain. The counts are exact: a template holding more of a number
//! than listed fails (a new typed result), and one holding fewer fails too
//! (the list must shrink when a number moves to a placeholder).
//!
//! Not scanned: placeholders (`{{...}}`), code spans and fenced code (the
//! commands), link targets and addresses, the template's leading comment,
//! a number right after `§` (a section) and a heading's own number.

use std::collections::BTreeMap;
use std::path::Path;

use fc_csv::table::Table;

/// One typed decimal: its 1-based line in the template and its text.
#[derive(Clone, Debug, PartialEq)]
pub struct Typed {
    pub line: usize,
    pub text: String,
}

/// The kinds of `paper/inputs.csv`; all but `pending` are inputs.
pub const KINDS: [&str; 6] = [
    "parameter",
    "tolerance",
    "literature",
    "identifier",
    "exact",
    "pending",
];

const SUPERSCRIPTS: &str = "⁰¹²³⁴⁵⁶⁷⁸⁹⁻";

/// `text` with every span the scan skips replaced by spaces (line breaks
/// kept, so that line numbers stay right).
fn blank_skipped(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    // The leading editor's comment.
    if let Some(body) = rest.strip_prefix("<!--") {
        if let Some(end) = body.find("-->") {
            blank(&mut out, &rest[..end + 7]);
            rest = &rest[end + 7..];
        }
    }
    // Spans that open and close: placeholders, fenced code, code spans,
    // link targets, bare addresses.
    const SPANS: [(&str, &str); 5] = [
        ("{{", "}}"),
        ("```", "```"),
        ("`", "`"),
        ("](", ")"),
        ("http", " "),
    ];
    while !rest.is_empty() {
        let next = SPANS
            .iter()
            .filter_map(|(open, close)| rest.find(open).map(|i| (i, *open, *close)))
            .min_by_key(|(i, open, _)| (*i, usize::MAX - open.len()));
        let Some((i, open, close)) = next else {
            out.push_str(rest);
            break;
        };
        out.push_str(&rest[..i]);
        let after = &rest[i + open.len()..];
        // A code span does not cross a blank line; an address ends at any
        // white space.
        let end = if close == " " {
            after.find(char::is_whitespace).unwrap_or(after.len())
        } else {
            after.find(close).map_or(after.len(), |e| e + close.len())
        };
        let skipped_len = open.len() + end;
        blank(&mut out, &rest[i..i + skipped_len]);
        rest = &rest[i + skipped_len..];
    }
    out
}

fn blank(out: &mut String, span: &str) {
    out.extend(span.chars().map(|c| if c == '\n' { '\n' } else { ' ' }));
}

/// The typed decimals of a template, in order.
pub fn scan(template: &str) -> Vec<Typed> {
    let text = blank_skipped(template);
    let mut found = vec![];
    for (k, line) in text.lines().enumerate() {
        let chars: Vec<char> = line.chars().collect();
        let heading = line.starts_with('#');
        let mut first_in_heading = heading;
        let mut i = 0;
        while i < chars.len() {
            if !chars[i].is_ascii_digit() {
                i += 1;
                continue;
            }
            let prev = if i > 0 { Some(chars[i - 1]) } else { None };
            let (end, typed) = token(&chars, i);
            let joined = prev.is_some_and(|p| p.is_alphanumeric() || p == '_' || p == '.');
            let section = prev == Some('§');
            let dots = chars[i..end].iter().filter(|&&c| c == '.').count();
            let skip = joined || section || first_in_heading || dots > 1;
            first_in_heading = false;
            if typed && !skip {
                found.push(Typed {
                    line: k + 1,
                    text: chars[i..end].iter().collect(),
                });
            }
            i = end.max(i + 1);
        }
    }
    found
}

/// The number starting at `chars[i]`: where it ends and whether it has a
/// decimal point or an exponent.
fn token(chars: &[char], i: usize) -> (usize, bool) {
    let digits = |mut j: usize| {
        while j < chars.len() && chars[j].is_ascii_digit() {
            j += 1;
        }
        j
    };
    let at = |j: usize| chars.get(j).copied();
    let mut j = digits(i);
    let mantissa: String = chars[i..j].iter().collect();
    let mut typed = false;
    // Decimal points (a second one makes a version or an identifier).
    while at(j) == Some('.') && at(j + 1).is_some_and(|c| c.is_ascii_digit()) {
        j = digits(j + 1);
        typed = true;
    }
    // 1e-8, 2E5
    if matches!(at(j), Some('e' | 'E')) {
        let mut e = j + 1;
        if matches!(at(e), Some('-' | '+')) {
            e += 1;
        }
        if at(e).is_some_and(|c| c.is_ascii_digit()) {
            let end = digits(e);
            if !at(end).is_some_and(char::is_alphabetic) {
                return (end, true);
            }
        }
    }
    // 5.5×10³, 1.2 × 10<sup>-5</sup>, and a bare 10⁻⁴, 10<sup>4</sup>, 10^{-4}.
    let mut power_at = None;
    let mut k = j;
    while at(k) == Some(' ') {
        k += 1;
    }
    if matches!(at(k), Some('×' | 'x')) {
        let mut m = k + 1;
        while at(m) == Some(' ') {
            m += 1;
        }
        if at(m) == Some('1') && at(m + 1) == Some('0') {
            power_at = Some(m + 2);
        }
    } else if mantissa == "10" && !typed {
        power_at = Some(j);
    }
    if let Some(p) = power_at {
        if let Some(end) = exponent(chars, p) {
            return (end, true);
        }
    }
    (j, typed)
}

/// The end of an exponent written `⁻⁴`, `<sup>-4</sup>` or `^{-4}`/`^4`
/// at `chars[p]`.
fn exponent(chars: &[char], p: usize) -> Option<usize> {
    let rest: String = chars[p..].iter().take(16).collect();
    let sup = chars[p..]
        .iter()
        .take_while(|c| SUPERSCRIPTS.contains(**c))
        .count();
    if sup > 0 {
        return Some(p + sup);
    }
    for (open, close) in [("<sup>", "</sup>"), ("^{", "}")] {
        if let Some(body) = rest.strip_prefix(open) {
            let n = body.find(close)?;
            return Some(p + open.chars().count() + body[..n].chars().count() + close.len());
        }
    }
    let after_caret = rest.strip_prefix('^')?;
    let n = after_caret
        .chars()
        .enumerate()
        .take_while(|(k, c)| c.is_ascii_digit() || (*k == 0 && *c == '-'))
        .count();
    (n > 0).then_some(p + 1 + n)
}

/// One row of `paper/inputs.csv`.
#[derive(Clone, Debug)]
pub struct Allowed {
    pub document: String,
    pub text: String,
    pub count: usize,
    pub kind: String,
}

/// Reads `paper/inputs.csv`, checking every row's kind and reason.
pub fn read_inputs(path: &Path) -> Result<Vec<Allowed>, String> {
    let t = Table::read(path)?;
    let (d, x, n, k, r) = (
        t.col("document")?,
        t.col("text")?,
        t.col("count")?,
        t.col("kind")?,
        t.col("reason")?,
    );
    t.rows
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let line = i + 2;
            let count = row[n]
                .parse::<usize>()
                .ok()
                .filter(|&c| c > 0)
                .ok_or(format!(
                    "paper/inputs.csv line {line}: count must be a whole number >= 1"
                ))?;
            if !KINDS.contains(&row[k].as_str()) {
                return Err(format!(
                    "paper/inputs.csv line {line}: kind '{}' is not one of {}",
                    row[k],
                    KINDS.join(", ")
                ));
            }
            if row[r].trim().is_empty() {
                return Err(format!("paper/inputs.csv line {line}: no reason"));
            }
            Ok(Allowed {
                document: row[d].clone(),
                text: row[x].clone(),
                count,
                kind: row[k].clone(),
            })
        })
        .collect()
}

/// What one template's check found: how many typed decimals it holds and
/// how many of them are still `pending` results.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub typed: usize,
    pub pending: usize,
}

/// Checks the typed decimals of `document`'s template against the list:
/// every one listed, every count exact.
pub fn check(document: &str, template: &str, allowed: &[Allowed]) -> Result<Summary, String> {
    let found = scan(template);
    let mut lines: BTreeMap<&str, Vec<usize>> = BTreeMap::new();
    for t in &found {
        lines.entry(t.text.as_str()).or_default().push(t.line);
    }
    let mut listed: BTreeMap<&str, usize> = BTreeMap::new();
    let mut pending = 0;
    for a in allowed.iter().filter(|a| a.document == document) {
        *listed.entry(a.text.as_str()).or_default() += a.count;
        if a.kind == "pending" {
            pending += a.count;
        }
    }
    let mut errors = vec![];
    for (text, at) in &lines {
        let n = listed.get(text).copied().unwrap_or(0);
        if at.len() > n {
            let where_: Vec<String> = at.iter().map(usize::to_string).collect();
            errors.push(format!(
                "paper/{document}.tmpl.md: '{text}' is typed {} times (lines {}), paper/inputs.csv \
                 lists it {n} times: fill a result from figures/data with a placeholder, or list \
                 an input with its reason",
                at.len(),
                where_.join(", ")
            ));
        }
    }
    for (text, n) in &listed {
        let have = lines.get(text).map_or(0, Vec::len);
        if have < *n {
            errors.push(format!(
                "paper/inputs.csv: '{text}' in {document} is listed {n} times, the template types \
                 it {have} times: lower its count"
            ));
        }
    }
    if errors.is_empty() {
        Ok(Summary {
            typed: found.len(),
            pending,
        })
    } else {
        Err(errors.join("\n"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(t: &str) -> Vec<String> {
        scan(t).into_iter().map(|t| t.text).collect()
    }

    #[test]
    fn the_scan_finds_decimals_and_exponents_only() {
        assert_eq!(
            texts("speed 3.52 at n = 100, rtol 1e-8, EA 5.5×10³ and 2 × 10<sup>-4</sup>; 10⁻⁴, $10^{-3}$."),
            vec!["3.52", "1e-8", "5.5×10³", "2 × 10<sup>-4</sup>", "10⁻⁴", "10^{-3}"]
        );
        // Whole numbers, words with digits, versions, sections, headings,
        // placeholders, code, links and addresses are not typed decimals.
        assert!(texts(
            "n = 100, fig03, rm09, 0.18.0, §6.6, {{a.csv:*:x:f2}}, `--rtol 1e-8`, \
             [f](../figures/a1.5.png), https://arxiv.org/abs/1910.02523 end.\n### 6.6 Snap"
        )
        .is_empty());
        assert_eq!(scan("a\n\nb 0.5")[0].line, 3);
        assert_eq!(texts("<!-- 1.5 -->\nx 2.5"), vec!["2.5"]);
        // A word that starts with e is not an exponent.
        assert_eq!(texts("2 each, 2.5em"), vec!["2.5"]);
    }

    fn allow(text: &str, count: usize, kind: &str) -> Allowed {
        Allowed {
            document: "paper".into(),
            text: text.into(),
            count,
            kind: kind.into(),
        }
    }

    /// A typed result fails, a listed input passes, and a list that allows
    /// more than the template types fails too.
    #[test]
    fn the_check_catches_a_typed_result() {
        let inputs = [allow("0.2", 1, "parameter"), allow("1e-8", 1, "tolerance")];
        let template = "tilt 0.2 rad, rtol 1e-8, largest speed {{s.csv:*:v:f3}}";
        assert_eq!(
            check("paper", template, &inputs),
            Ok(Summary {
                typed: 2,
                pending: 0
            })
        );
        let typed = "tilt 0.2 rad, rtol 1e-8, largest speed 3.520";
        let e = check("paper", typed, &inputs).unwrap_err();
        assert!(e.contains("'3.520' is typed 1 times (lines 1)"), "{e}");
        // The input's number typed once more, as a result, fails as well.
        let again = "tilt 0.2 rad, rtol 1e-8, a spread of 0.2";
        assert!(check("paper", again, &inputs)
            .unwrap_err()
            .contains("'0.2'"));
        // Another document's list does not cover this one.
        assert!(check("methods", template, &inputs).is_err());
        let fewer = "tilt 0.2 rad";
        assert!(check("paper", fewer, &inputs)
            .unwrap_err()
            .contains("lower its count"));
        let pending = [allow("3.520", 1, "pending")];
        assert_eq!(
            check("paper", "speed 3.520", &pending),
            Ok(Summary {
                typed: 1,
                pending: 1
            })
        );
    }

    #[test]
    fn the_list_needs_a_kind_and_a_reason() {
        let dir = std::env::temp_dir().join(format!("paper-inputs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("inputs.csv");
        let head = "document,text,count,kind,reason\n";
        std::fs::write(
            &path,
            format!("{head}paper,0.2,1,parameter,\"the tilt, rad\"\n"),
        )
        .unwrap();
        assert_eq!(read_inputs(&path).unwrap()[0].text, "0.2");
        std::fs::write(&path, format!("{head}paper,0.2,1,parameter,\n")).unwrap();
        assert!(read_inputs(&path).unwrap_err().contains("no reason"));
        std::fs::write(&path, format!("{head}paper,0.2,1,result,x\n")).unwrap();
        assert!(read_inputs(&path).unwrap_err().contains("kind 'result'"));
        std::fs::write(&path, format!("{head}paper,0.2,0,parameter,x\n")).unwrap();
        assert!(read_inputs(&path).unwrap_err().contains("count"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
