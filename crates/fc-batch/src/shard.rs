//! Runs split across machines and joined again: a study's runs are numbered,
//! `--shard I/N` takes runs `I, I + N, ...` ([`Shard`]; a sweep's and a
//! study's alike), and
//! every row records where it comes from ([`Provenance`]: the number of runs
//! of the whole study and a hash of its scene and options), so that
//! [`merge`] can refuse shards of different studies, a missing run and a
//! run given twice.
//!
//! The hash is FNV-1a (64 bits) of the scene's TOML text (after `--set`),
//! the command and its options that change what is computed (not `--jobs`,
//! `--shard`, `--out` or `--budget`), written as 16 hex digits: the same on
//! every machine and every build.

use std::collections::BTreeMap;

use fc_csv::Column;
use fc_scene::error::{echo, Error};
use fc_scene::scene::Scene;

/// The most runs a sweep or a study may have (a sweep's: the product of
/// the `--vary` counts).
pub const MAX_RUNS: usize = 1_000_000;

/// A slice of a sweep or a study (`--shard I/N`): runs `index, index + count, ...`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// Parses `I/N` with `0 <= I < N`.
    pub fn parse(spec: &str) -> Result<Self, Error> {
        let bad = || {
            Error::field(
                "--shard",
                format!(
                    "must be I/N with integers 0 <= I < N (got '{}')",
                    echo(spec)
                ),
            )
        };
        let (i, n) = spec.split_once('/').ok_or_else(bad)?;
        let (index, count): (usize, usize) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// Whether run number `run` is this shard's.
    pub fn takes(&self, run: usize) -> bool {
        run % self.count == self.index
    }
}

/// The columns a study's table ends with.
pub const COLUMNS: [(&str, Column); 2] = [("runs", Column::Int), ("scene_hash", Column::Text)];

/// Where a row comes from: the study's size and the hash of what it ran.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Provenance {
    /// The number of numbered runs of the whole (unsharded) study.
    pub runs: usize,
    /// 16 hex digits of FNV-1a over the scene and options.
    pub hash: String,
}

/// FNV-1a, 64 bits, over `parts`, each followed by a zero byte (so that
/// `["ab", "c"]` and `["a", "bc"]` differ).
fn fnv1a(parts: &[&str]) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let mut h = OFFSET;
    for part in parts {
        for &b in part.as_bytes().iter().chain(&[0u8]) {
            h ^= u64::from(b);
            h = h.wrapping_mul(PRIME);
        }
    }
    h
}

impl Provenance {
    /// The provenance of a study of `runs` runs of `command` on `scene` with
    /// `options` (each option as text, in a fixed order).
    pub fn new(scene: &Scene, command: &str, options: &[String], runs: usize) -> Self {
        let toml = scene.to_toml_string();
        let mut parts: Vec<&str> = vec![command, &toml];
        parts.extend(options.iter().map(String::as_str));
        Self {
            runs,
            hash: format!("{:016x}", fnv1a(&parts)),
        }
    }

    /// `,runs,scene_hash` for the end of a header line.
    pub fn header_suffix() -> String {
        format!(",{}", fc_csv::header(&COLUMNS))
    }

    /// `,<runs>,<hash>` for the end of a row.
    pub fn cells(&self) -> String {
        format!(",{},{}", self.runs, self.hash)
    }
}

/// How many run numbers a message names before it says "and K more".
const NAMED_RUNS: usize = 20;

/// "run 3 is" or "runs 2, 5, 8 are", naming at most [`NAMED_RUNS`] of
/// `runs` (ascending) and counting the rest: what a user resubmits.
fn runs_named(runs: &[usize]) -> String {
    let shown: Vec<String> = runs.iter().take(NAMED_RUNS).map(usize::to_string).collect();
    let more = runs.len().saturating_sub(NAMED_RUNS);
    match (runs.len(), more) {
        (1, _) => format!("run {} is", shown.join("")),
        (_, 0) => format!("runs {} are", shown.join(", ")),
        _ => format!("runs {} and {more} more are", shown.join(", ")),
    }
}

/// The largest shard file [`merge`] reads (bytes).
pub const MAX_SHARD_BYTES: u64 = 1 << 30;
/// The most shard files [`merge`] joins.
pub const MAX_SHARDS: usize = 100_000;
/// The most bytes of all shard files together (merge holds them in memory).
pub const MAX_TOTAL_BYTES: u64 = 4 << 30;

/// Reads the shard files `paths` (each a regular file of at most
/// [`MAX_SHARD_BYTES`], at most [`MAX_SHARDS`] of them) as `(name, text)`.
pub fn read(paths: &[std::path::PathBuf]) -> Result<Vec<(String, String)>, Error> {
    if paths.len() > MAX_SHARDS {
        return Err(Error::field(
            "merge",
            format!("at most {MAX_SHARDS} shard files (got {})", paths.len()),
        ));
    }
    let mut total = 0u64;
    paths
        .iter()
        .map(|path| {
            let meta = std::fs::metadata(path).map_err(|e| Error::read("shard", path, e))?;
            total = total.saturating_add(meta.len());
            if total > MAX_TOTAL_BYTES {
                return Err(Error::field(
                    "merge",
                    format!("the shard files hold more than {MAX_TOTAL_BYTES} bytes together"),
                ));
            }
            if !meta.is_file() || meta.len() > MAX_SHARD_BYTES {
                return Err(Error::field(
                    "shard",
                    format!(
                        "'{}' is not a regular file of at most {MAX_SHARD_BYTES} bytes",
                        fc_scene::error::echo_path(path)
                    ),
                ));
            }
            let text = std::fs::read_to_string(path).map_err(|e| Error::read("shard", path, e))?;
            Ok((path.display().to_string(), text))
        })
        .collect()
}

/// The start of the `note` of a row that was not run, or was stopped,
/// within its shard's `--budget` (precision's and stability's tables):
/// [`merge`] refuses such a shard, since its rows are not results.
pub const BUDGET_NOTE: &str = "budget:";

/// Joins the tables of shards `(name, text)` into the table of the whole
/// study: the header, the rows without a run number (a study's shared rows,
/// such as precision's reference, computed by every shard: the first shard's
/// are kept), then every run in run order, each record as it stood in its
/// file. The tables are read as RFC 4180 CSV ([`fc_csv::Reader`]: a
/// scene name with a comma, a quote or a line break is one quoted cell).
/// Refused, with one line naming the file, when a table is not CSV, the
/// headers differ, a table lacks the `run`, `runs` or `scene_hash` column,
/// two shards come from different studies (scene, options or size), a run
/// is missing or given twice, a row was not run or was stopped for the
/// shard's `--budget` (its `note` starts with [`BUDGET_NOTE`]: run that
/// shard again), or shards disagree on the shared rows (wall times aside).
pub fn merge(shards: &[(String, String)]) -> Result<String, Error> {
    use fc_csv::{Reader, Record};
    let err = |what: &str, why: String| Error::field("merge", format!("{}: {why}", echo(what)));
    if shards.is_empty() {
        return Err(Error::field("merge", "no shard files given"));
    }
    if shards.len() > MAX_SHARDS {
        return Err(Error::field(
            "merge",
            format!("at most {MAX_SHARDS} shard files (got {})", shards.len()),
        ));
    }
    let (first_name, first_text) = &shards[0];
    // The first shard's header: the columns, and its text for the output.
    let (cols, header_span) = {
        let mut reader = Reader::new(first_text.as_bytes());
        let mut header = Record::default();
        match reader.read(&mut header) {
            Ok(true) => (header.to_vec(), header.span()),
            Ok(false) => return Err(err(first_name, "the file is empty (no header)".into())),
            Err(e) => return Err(err(first_name, e.to_string())),
        }
    };
    let col = |c: &str| {
        cols.iter().position(|h| *h == c).ok_or_else(|| {
            err(
                first_name,
                format!("no '{c}' column: not a table of sweep, precision or stability"),
            )
        })
    };
    let (c_run, c_runs, c_hash) = (col("run")?, col(COLUMNS[0].0)?, col(COLUMNS[1].0)?);
    let c_wall = cols.iter().position(|h| *h == "wall_seconds");
    let c_note = cols.iter().position(|h| *h == "note");
    let mut study: Option<(String, String)> = None; // (runs, hash)
    let mut shared: Option<Vec<Vec<String>>> = None;
    let mut first_shared = vec![];
    // Run -> (shard, where its record is in the shard's text).
    let mut rows: BTreeMap<usize, (usize, std::ops::Range<usize>)> = BTreeMap::new();
    let mut total = 0usize;
    for (s, (name, text)) in shards.iter().enumerate() {
        let mut reader = Reader::new(text.as_bytes()).max_cells(cols.len());
        let mut record = Record::default();
        let bad = |e: fc_csv::ReadError| match e {
            fc_csv::ReadError::Syntax { line, what } if what.starts_with("more than") => err(
                name,
                format!(
                    "line {line} has more cells than the header's {}",
                    cols.len()
                ),
            ),
            e => err(name, e.to_string()),
        };
        match reader.read(&mut record).map_err(bad)? {
            true if record.iter().eq(cols.iter().map(String::as_str)) => {}
            _ => {
                return Err(err(
                    name,
                    format!("its header differs from '{}'s", echo(first_name)),
                ))
            }
        }
        let mut mine_shared = vec![];
        // Rows marked as not run for the shard's --budget: run numbers, and
        // the lines of shared rows.
        let (mut unrun, mut unrun_shared) = (vec![], vec![]);
        while reader.read(&mut record).map_err(bad)? {
            let line = record.line();
            if record.len() != cols.len() {
                return Err(err(
                    name,
                    format!(
                        "line {line} has {} cells, the header {}",
                        record.len(),
                        cols.len()
                    ),
                ));
            }
            let cell = |c: usize| record.get(c).unwrap_or_default();
            let id = (cell(c_runs).to_string(), cell(c_hash).to_string());
            match &study {
                None => {
                    let n: usize =
                        id.0.parse()
                            .ok()
                            .filter(|&n| n <= MAX_RUNS)
                            .ok_or_else(|| {
                                err(
                                    name,
                                    format!(
                                        "'runs' is not an integer in 0..={MAX_RUNS} (line {line})"
                                    ),
                                )
                            })?;
                    total = n;
                    study = Some(id);
                }
                Some(s) if *s != id => {
                    return Err(err(
                        name,
                        format!(
                            "a shard of another study (runs {}, scene_hash {}; '{}' has runs {}, \
                             scene_hash {}): different scene or options",
                            echo(&id.0),
                            echo(&id.1),
                            echo(first_name),
                            echo(&s.0),
                            echo(&s.1)
                        ),
                    ))
                }
                Some(_) => {}
            }
            let budget = c_note.is_some_and(|c| cell(c).starts_with(BUDGET_NOTE));
            let run = cell(c_run);
            if run.is_empty() {
                let mut c = record.to_vec();
                if let Some(w) = c_wall {
                    c[w].clear();
                }
                mine_shared.push(c);
                if s == 0 {
                    first_shared.push(record.span());
                }
                if budget {
                    unrun_shared.push(line);
                }
                continue;
            }
            let run: usize = run.parse().ok().filter(|&r| r < total).ok_or_else(|| {
                err(
                    name,
                    format!(
                        "run '{}' (line {line}) is not an integer below the study's {total} runs",
                        echo(run)
                    ),
                )
            })?;
            if budget {
                unrun.push(run);
            }
            if let Some((other, _)) = rows.insert(run, (s, record.span())) {
                return Err(err(
                    name,
                    format!(
                        "run {run} is given twice (also in '{}')",
                        echo(&shards[other].0)
                    ),
                ));
            }
        }
        if !unrun.is_empty() || !unrun_shared.is_empty() {
            unrun.sort_unstable();
            let what = if unrun.is_empty() {
                let lines: Vec<String> = unrun_shared.iter().map(usize::to_string).collect();
                format!("the shared rows on lines {} are", lines.join(", "))
            } else {
                runs_named(&unrun)
            };
            return Err(err(
                name,
                format!(
                    "{what} not results: not run, or stopped, within that shard's --budget \
                     (note '{BUDGET_NOTE} ...'); run the shard again with a larger --budget or \
                     none"
                ),
            ));
        }
        match &shared {
            None => shared = Some(mine_shared),
            Some(s) if *s != mine_shared => {
                return Err(err(
                    name,
                    format!(
                        "its shared rows (no run number) differ from '{}'s",
                        echo(first_name)
                    ),
                ))
            }
            Some(_) => {}
        }
    }
    if study.is_none() {
        // Not one row: the study's runs (which each row names) are unknown,
        // so none can be said present; a study has at least one run.
        return Err(Error::field(
            "merge",
            format!(
                "no shard holds a row (the study's runs, which every row names, are unknown; \
                 a shard of more shards than runs is empty): give the shards that ran, {} \
                 shard file(s) had none",
                shards.len()
            ),
        ));
    }
    let missing: Vec<usize> = (0..total).filter(|r| !rows.contains_key(r)).collect();
    if !missing.is_empty() {
        return Err(Error::field(
            "merge",
            format!(
                "{} missing: {} of the study's {total} runs are given",
                runs_named(&missing),
                rows.len()
            ),
        ));
    }
    let mut out = first_text[header_span].to_string();
    out.push('\n');
    // The first shard's shared rows, with their wall times.
    for span in first_shared {
        out.push_str(&first_text[span]);
        out.push('\n');
    }
    for (_, (s, span)) in rows {
        out.push_str(&shards[s].1[span]);
        out.push('\n');
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(rows: &[&str]) -> String {
        let mut t = String::from("run,x,wall_seconds,runs,scene_hash\n");
        for r in rows {
            t.push_str(r);
            t.push('\n');
        }
        t
    }

    #[test]
    fn shards_join_in_run_order_and_bad_sets_are_refused() {
        let a = (
            "a.csv".to_string(),
            table(&[",ref,0.1,3,h", "0,p,0.5,3,h", "2,r,0.2,3,h"]),
        );
        let b = ("b.csv".to_string(), table(&[",ref,0.3,3,h", "1,q,0.7,3,h"]));
        let merged = merge(&[a.clone(), b.clone()]).unwrap();
        assert_eq!(
            merged,
            table(&[",ref,0.1,3,h", "0,p,0.5,3,h", "1,q,0.7,3,h", "2,r,0.2,3,h"])
        );
        let missing = merge(std::slice::from_ref(&a)).unwrap_err().to_string();
        assert!(missing.starts_with("merge: run 1 is missing"), "{missing}");
        let only_first = (
            "g.csv".to_string(),
            table(&[",ref,0.1,5,h", "0,p,0.5,5,h", "3,s,0.5,5,h"]),
        );
        let several = merge(&[only_first]).unwrap_err().to_string();
        assert!(
            several.starts_with("merge: runs 1, 2, 4 are missing"),
            "{several}"
        );
        let many: Vec<usize> = (0..25).collect();
        assert!(runs_named(&many).ends_with("19 and 5 more are"));
        let twice = merge(&[a.clone(), b.clone(), b.clone()])
            .unwrap_err()
            .to_string();
        assert!(twice.contains("run 1 is given twice"), "{twice}");
        let other = ("c.csv".to_string(), table(&[",ref,0.3,3,k", "1,q,0.7,3,k"]));
        let e = merge(&[a.clone(), other]).unwrap_err().to_string();
        assert!(e.contains("another study"), "{e}");
        let bigger = ("d.csv".to_string(), table(&[",ref,0.3,4,h", "1,q,0.7,4,h"]));
        assert!(merge(&[a.clone(), bigger]).is_err());
        let reference = ("e.csv".to_string(), table(&[",REF,0.3,3,h", "1,q,0.7,3,h"]));
        assert!(merge(&[a.clone(), reference])
            .unwrap_err()
            .to_string()
            .contains("shared rows"));
        let header = (
            "f.csv".to_string(),
            "run,y,wall_seconds,runs,scene_hash\n".to_string(),
        );
        assert!(merge(&[a, header])
            .unwrap_err()
            .to_string()
            .contains("header differs"));
        assert!(merge(&[]).is_err());
    }

    #[test]
    fn the_hash_sees_scene_and_options() {
        let s = Scene::from_toml_str(
            "[chain]\nlinks = 4\n[start]\nkind = \"folded\"\n[run]\nt_end = 1\n",
        )
        .unwrap();
        let p = |s: &Scene, o: &str| Provenance::new(s, "sweep", &[o.to_string()], 3);
        assert_eq!(p(&s, "a"), p(&s, "a"));
        assert_ne!(p(&s, "a").hash, p(&s, "b").hash);
        let t = s.with_overrides(&["chain.links=5"]).unwrap();
        assert_ne!(p(&s, "a").hash, p(&t, "a").hash);
        assert_eq!(p(&s, "a").hash.len(), 16);
    }
}
