//! `cargo xtask paper [--check]`: fills the templates `paper/<name>.tmpl.md`
//! (`paper`, the physics; `methods`, the solver study; `supplement`, the
//! physics paper's report-model forensics and extensions) with numbers read
//! from the CSVs in `figures/data/` and writes `paper/<name>.md`.
//!
//! A placeholder is `{{FILE:FILTER:EXPR:FORMAT}}`:
//! - `FILE`: a CSV in `figures/data/` (`scenes.csv`); wall times only from
//!   the timing files (`*-timing.csv`, with `machine-timing.csv`);
//! - `FILTER`: `*`, or `col=value` conditions joined by `&`;
//! - `EXPR`: `col` (the one matching row's cell), `min(col)`, `max(col)`
//!   (over the rows whose cell is not empty),
//!   `maxabs(col)`, `at_max(col,other)` / `at_min(col,other)` (`other` in the row where
//!   `col` is largest / smallest), `count`, `ratio(a,b)` (`a / b` in the one
//!   matching row), `over(col,N)` (the one matching row's cell over a whole
//!   number `N` the text states, such as a scene's weight);
//! - `FORMAT`: `s3` (3 significant digits), `f2` (2 decimals), `e2`
//!   (scientific, 2 decimals) or `raw`.
//!
//! `--check` renders in memory and fails if a `paper/<name>.md` differs (a
//! number or the template changed) or if a file it links to is missing.
//! Both fail on a typed decimal that `paper/inputs.csv` does not list
//! ([`crate::typed`]): a result comes from the data, not the keyboard.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use fc_csv::table::Table;

fn col(t: &Table, name: &str) -> Result<usize, String> {
    t.col(name)
}

fn num(s: &str) -> Result<f64, String> {
    s.parse::<f64>()
        .map_err(|_| format!("'{s}' is not a number"))
}

/// Formats `x` as the placeholder asks.
fn format(x: f64, fmt: &str) -> Result<String, String> {
    let digits = |s: &str| -> Result<usize, String> {
        s.parse::<usize>()
            .map_err(|_| format!("bad format '{fmt}'"))
    };
    Ok(match fmt.split_at(1.min(fmt.len())) {
        ("s", d) => {
            let d = digits(d)?.max(1);
            if x == 0.0 {
                "0".to_string()
            } else {
                let mag = x.abs().log10().floor() as i32;
                let decimals = (d as i32 - 1 - mag).max(0) as usize;
                format!("{x:.decimals$}")
            }
        }
        ("f", d) => format!("{x:.*}", digits(d)?),
        ("e", d) => {
            let s = format!("{x:.*e}", digits(d)?);
            // 1.23e-5 -> 1.23 × 10^-5, as the paper prints it.
            match s.split_once('e') {
                Some((m, e)) => format!("{m}×10<sup>{e}</sup>"),
                None => s,
            }
        }
        _ => return Err(format!("bad format '{fmt}' (s3, f2, e2 or raw)")),
    })
}

/// Evaluates one placeholder against the data folder.
fn evaluate(
    spec: &str,
    data: &Path,
    cache: &mut BTreeMap<String, Table>,
) -> Result<String, String> {
    let parts: Vec<&str> = spec.splitn(4, ':').collect();
    let [file, filter, expr, fmt] = parts[..] else {
        return Err("expected FILE:FILTER:EXPR:FORMAT".into());
    };
    if !cache.contains_key(file) {
        cache.insert(file.to_string(), Table::read(&data.join(file))?);
    }
    let t = &cache[file];
    let conds: Vec<(usize, &str)> = if filter == "*" {
        vec![]
    } else {
        filter
            .split('&')
            .map(|c| {
                let (k, v) = c.split_once('=').ok_or(format!("bad filter '{c}'"))?;
                Ok((col(t, k)?, v))
            })
            .collect::<Result<_, String>>()?
    };
    let rows: Vec<&Vec<String>> = t
        .rows
        .iter()
        .filter(|r| {
            conds
                .iter()
                .all(|(i, v)| r.get(*i).map(String::as_str) == Some(*v))
        })
        .collect();
    if rows.is_empty() {
        return Err(format!("no row matches '{filter}'"));
    }
    let one = || -> Result<&Vec<String>, String> {
        if rows.len() == 1 {
            Ok(rows[0])
        } else {
            Err(format!(
                "{} rows match '{filter}', expected one",
                rows.len()
            ))
        }
    };
    let (name, args) = match expr.split_once('(') {
        Some((f, rest)) => (f, rest.trim_end_matches(')').split(',').collect::<Vec<_>>()),
        None if expr == "count" => ("count", vec![]),
        None => ("", vec![expr]),
    };
    let value = |r: &Vec<String>, c: &str| -> Result<String, String> { Ok(r[col(t, c)?].clone()) };
    let extreme = |largest: bool| -> Result<&Vec<String>, String> {
        let c = col(t, args[0])?;
        let mut best: Option<(f64, &Vec<String>)> = None;
        // Empty cells (a failed run's) take no part.
        for r in rows.iter().filter(|r| !r[c].is_empty()) {
            let x = num(&r[c])?;
            if best.is_none_or(|(b, _)| if largest { x > b } else { x < b }) {
                best = Some((x, r));
            }
        }
        best.map(|b| b.1)
            .ok_or_else(|| format!("no number in '{}'", args[0]))
    };
    let text = match (name, args.len()) {
        ("", 1) => value(one()?, args[0])?,
        ("count", _) => rows.len().to_string(),
        ("max", 1) => value(extreme(true)?, args[0])?,
        ("maxabs", 1) => {
            let c = col(t, args[0])?;
            let mut m: f64 = 0.0;
            for r in &rows {
                m = m.max(num(&r[c])?.abs());
            }
            m.to_string()
        }
        ("min", 1) => value(extreme(false)?, args[0])?,
        ("at_max", 2) => value(extreme(true)?, args[1])?,
        ("at_min", 2) => value(extreme(false)?, args[1])?,
        ("over", 2) => {
            let n = args[1]
                .parse::<u64>()
                .map_err(|_| format!("over(): '{}' is not a whole number", args[1]))?;
            (num(&value(one()?, args[0])?)? / n as f64).to_string()
        }
        ("ratio", 2) => {
            let r = one()?;
            (num(&value(r, args[0])?)? / num(&value(r, args[1])?)?).to_string()
        }
        _ => return Err(format!("unknown expression '{expr}'")),
    };
    if fmt == "raw" {
        Ok(text)
    } else {
        format(num(&text)?, fmt)
    }
}

/// The paper with every placeholder filled in.
pub fn render(template: &str, data: &Path) -> Result<String, String> {
    let mut out = String::with_capacity(template.len());
    let mut cache = BTreeMap::new();
    let mut rest = template;
    let mut errors = vec![];
    while let Some(start) = rest.find("{{") {
        out.push_str(&rest[..start]);
        let Some(len) = rest[start..].find("}}") else {
            return Err("a '{{' without its '}}'".into());
        };
        let spec = &rest[start + 2..start + len];
        match evaluate(spec.trim(), data, &mut cache) {
            Ok(v) => out.push_str(&v),
            Err(e) => errors.push(format!("{{{{{spec}}}}}: {e}")),
        }
        rest = &rest[start + len + 2..];
    }
    out.push_str(rest);
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors.join("\n"))
    }
}

/// Relative links to figures (`](../figures/...)`) that do not exist.
pub fn missing_links(paper: &str, paper_dir: &Path) -> Vec<String> {
    paper
        .split("](")
        .skip(1)
        .filter_map(|s| s.split(')').next())
        .filter(|l| !l.starts_with("http") && !l.starts_with('#'))
        .filter(|l| !paper_dir.join(l).exists())
        .map(str::to_string)
        .collect()
}

/// The template without its leading comment (`<!-- ... -->`, a note to
/// the template's editors that the generated paper must not carry).
fn source(template: &str) -> &str {
    match template
        .strip_prefix("<!--")
        .and_then(|rest| rest.split_once("-->"))
    {
        Some((_, body)) => body.trim_start_matches(['\r', '\n']),
        None => template,
    }
}

/// `cargo xtask paper [--check]`: fills every document of
/// [`crate::pdf::DOCUMENTS`] whose template `paper/<name>.tmpl.md` exists
/// (the physics in `paper.md`, the solver study in `methods.md`). Links are
/// checked once every document is rendered, so that the two may link to
/// each other.
pub fn run(root: &Path, check: bool) -> Result<(), String> {
    let dir = root.join("paper");
    let data = root.join("figures").join("data");
    let inputs_path = dir.join("inputs.csv");
    let inputs = if inputs_path.exists() {
        crate::typed::read_inputs(&inputs_path)?
    } else {
        vec![]
    };
    let mut rendered = Vec::new();
    let mut typed_errors = vec![];
    for name in crate::pdf::DOCUMENTS {
        let template_path = dir.join(format!("{name}.tmpl.md"));
        if !template_path.exists() {
            continue;
        }
        let template =
            fs::read_to_string(&template_path).map_err(|e| format!("paper/{name}.tmpl.md: {e}"))?;
        let text =
            render(source(&template), &data).map_err(|e| format!("paper/{name}.tmpl.md: {e}"))?;
        match crate::typed::check(name, &template, &inputs) {
            Ok(s) => println!(
                "paper/{name}.tmpl.md: {} typed decimals, each listed in paper/inputs.csv \
                 ({} of them results still pending data)",
                s.typed, s.pending
            ),
            Err(e) => typed_errors.push(e),
        }
        rendered.push((name, text));
    }
    if !typed_errors.is_empty() {
        return Err(typed_errors.join("\n"));
    }
    if rendered.is_empty() {
        return Err("paper/: no template (paper.tmpl.md) to fill".into());
    }
    let written: Vec<String> = rendered.iter().map(|(n, _)| format!("{n}.md")).collect();
    for (name, text) in &rendered {
        let missing: Vec<String> = missing_links(text, &dir)
            .into_iter()
            .filter(|l| !written.contains(l))
            .collect();
        if !missing.is_empty() {
            return Err(format!(
                "paper/{name}.md links to missing files: {}",
                missing.join(", ")
            ));
        }
    }
    for (name, text) in &rendered {
        let target = dir.join(format!("{name}.md"));
        if check {
            let current = fs::read_to_string(&target).unwrap_or_default();
            if current != *text {
                return Err(format!(
                    "paper/{name}.md is stale: its numbers or text differ from the \
                     template filled with figures/data/ (run `cargo xtask paper`)"
                ));
            }
            println!("paper/{name}.md is current ({} bytes)", text.len());
        } else {
            write_text(&target, text)?;
            println!("wrote paper/{name}.md");
        }
    }
    Ok(())
}

/// Writes `text` to `path` atomically.
fn write_text(path: &Path, text: &str) -> Result<(), String> {
    fc_atomic::write_atomic(path, |w| w.write_all(text.as_bytes()))
        .map_err(|e| format!("paper: cannot write '{}': {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholders_read_the_csv() {
        let dir = std::env::temp_dir().join(format!("xtask-paper-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join("a.csv"), "k,x,y\np,1.23456,10\nq,2.5,20\n").unwrap();
        let t = "{{a.csv:k=p:x:s3}} {{a.csv:*:max(x):f1}} {{a.csv:*:at_max(x,k):raw}} \
                 {{a.csv:*:count:raw}} {{a.csv:k=q:ratio(y,x):f0}} {{a.csv:k=p:y:e1}} \
                 {{a.csv:k=q:over(y,8):f1}}";
        assert_eq!(
            render(t, &dir).unwrap(),
            "1.23 2.5 q 2 8 1.0×10<sup>1</sup> 2.5"
        );
        assert!(render("{{a.csv:k=q:over(y,0.5):f1}}", &dir)
            .unwrap_err()
            .contains("whole number"));
        assert!(render("{{a.csv:k=z:x:s3}}", &dir).is_err());
        assert!(render("{{a.csv:*:x:s3}}", &dir)
            .unwrap_err()
            .contains("2 rows"));
        assert!(render("{{b.csv:*:x:s3}}", &dir).is_err());
        fs::remove_dir_all(&dir).unwrap();
    }

    /// Both documents are filled, may link to each other, and `--check`
    /// names the stale one.
    #[test]
    fn every_document_is_filled_and_checked() {
        let root = std::env::temp_dir().join(format!("paper-docs-{}", std::process::id()));
        fs::create_dir_all(root.join("paper")).unwrap();
        fs::create_dir_all(root.join("figures/data")).unwrap();
        fs::write(root.join("figures/data/a.csv"), "k,x\np,2.5\n").unwrap();
        fs::write(
            root.join("paper/paper.tmpl.md"),
            "<!-- note -->\n# P\nx = {{a.csv:k=p:x:f1}}, see [methods](methods.md)\n",
        )
        .unwrap();
        fs::write(
            root.join("paper/methods.tmpl.md"),
            "# M\nsee [the paper](paper.md)\n",
        )
        .unwrap();
        assert!(run(&root, true)
            .unwrap_err()
            .contains("paper/paper.md is stale"));
        run(&root, false).unwrap();
        assert_eq!(
            fs::read_to_string(root.join("paper/paper.md")).unwrap(),
            "# P\nx = 2.5, see [methods](methods.md)\n"
        );
        assert_eq!(
            fs::read_to_string(root.join("paper/methods.md")).unwrap(),
            "# M\nsee [the paper](paper.md)\n"
        );
        run(&root, true).unwrap();
        fs::write(root.join("paper/methods.md"), "# M\nold\n").unwrap();
        assert!(run(&root, true)
            .unwrap_err()
            .contains("paper/methods.md is stale"));
        fs::write(root.join("paper/methods.tmpl.md"), "# M\n[x](nowhere.md)\n").unwrap();
        assert!(run(&root, false).unwrap_err().contains("nowhere.md"));
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn the_generated_paper_drops_the_template_note() {
        assert_eq!(source("<!-- note\n -->\n# Title\ntext"), "# Title\ntext");
        assert_eq!(source("# Title\n<!-- kept -->"), "# Title\n<!-- kept -->");
    }
}
