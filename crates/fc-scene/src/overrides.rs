//! `--set KEY=VALUE`: changes to a scene's TOML tree by dotted path, applied
//! before the tree is deserialised, so that every scene key can be changed
//! the same way (and a sweep can vary any of them).
//!
//! A path names a table key (`chain.links`) or an array element by index
//! (`start.p1.0`). The value is parsed as a TOML value (`100`, `2.5`,
//! `[3.0, 0.0]`, `"rk4"`, `nan`); a bare word that is not valid TOML
//! (`dopri5`) is taken as a string.

use crate::error::{echo, Error};
use crate::schema;

/// Splits `KEY=VALUE` and parses the value; the error names the key.
pub fn parse_assignment(assignment: &str) -> Result<(String, toml::Value), Error> {
    let Some((path, text)) = assignment.split_once('=') else {
        return Err(Error::field(
            "--set",
            format!(
                "expected KEY=VALUE, e.g. chain.links=100 (got '{}')",
                echo(assignment)
            ),
        ));
    };
    let path = path.trim();
    let value = parse_value(text).map_err(|m| Error::field(path, m))?;
    Ok((path.to_string(), value))
}

/// Parses the text of a value as TOML; a bare word that is not TOML becomes
/// a string. Text that looks like an array, table or quoted string but does
/// not parse is an error.
pub fn parse_value(text: &str) -> Result<toml::Value, String> {
    let text = text.trim();
    if let Ok(mut table) = format!("v = {text}").parse::<toml::Table>() {
        if table.len() == 1 {
            if let Some(v) = table.remove("v") {
                return Ok(v);
            }
        }
    }
    let structured = text.starts_with(['[', '{', '"', '\'']) || text.contains(['\n', '\r']);
    if structured {
        Err(format!("cannot parse '{}' as a TOML value", echo(text)))
    } else {
        Ok(toml::Value::String(text.to_string()))
    }
}

/// Sets the value at the dotted `path` of `tree`, creating a missing section
/// table or key. The path must name a scene key of [`schema::KEYS`] (whose
/// value is coerced to the key's type, [`schema::Key::coerce`]), a section
/// (set whole), or an element of an array that is set; the error names the
/// path.
pub fn set_path(tree: &mut toml::Table, path: &str, value: toml::Value) -> Result<(), Error> {
    let segments: Vec<&str> = path.split('.').collect();
    let top = segments[0];
    if let Some(key) = schema::key(path) {
        let value = key.coerce(value);
        match key.section() {
            None => {
                tree.insert(top.to_string(), value);
            }
            Some(_) => {
                section(tree, path, top)?.insert(key.name().to_string(), value);
            }
        }
        if path == schema::START_KIND {
            drop_keys_of_other_kinds(tree);
        }
        return Ok(());
    }
    if segments.len() == 1 && schema::is_section(top) {
        tree.insert(top.to_string(), value);
        return Ok(());
    }
    let key = segments.get(1).copied().unwrap_or_default();
    if segments.len() < 3 || schema::key(&format!("{top}.{key}")).is_none() {
        return Err(schema::unknown_key(path));
    }
    let mut node = section(tree, path, top)?.get_mut(key).ok_or_else(|| {
        Error::field(
            path,
            format!("'{top}.{key}' is not set in the scene: set it whole (e.g. {top}.{key}=[...])"),
        )
    })?;
    let mut walked = format!("{top}.{key}");
    for segment in &segments[2..] {
        let toml::Value::Array(items) = node else {
            return Err(Error::field(path, format!("'{walked}' is not an array")));
        };
        let len = items.len();
        let index = segment
            .parse::<usize>()
            .ok()
            .filter(|&i| i < len)
            .ok_or_else(|| {
                Error::field(
                    path,
                    format!(
                        "'{}' is not an index of '{walked}' (it has {len} elements)",
                        echo(segment)
                    ),
                )
            })?;
        node = &mut items[index];
        walked = format!("{walked}.{index}");
    }
    *node = value;
    Ok(())
}

/// After `start.kind` is set: the `[start]` keys that the new kind does
/// not take are removed (`p1` when a catenary start becomes `folded`), so
/// that a start's kind can be changed with its own keys, in one `--set`
/// list or one Python `Scene.set`. Keys both kinds take (`p0`; `p1` from
/// catenary to stretched) stay. An unknown kind removes nothing (the
/// scene's check names it).
fn drop_keys_of_other_kinds(tree: &mut toml::Table) {
    let Some(toml::Value::Table(start)) = tree.get_mut("start") else {
        return;
    };
    let Some(kind) = start
        .get("kind")
        .and_then(toml::Value::as_str)
        .and_then(|k| schema::StartKind::ALL.into_iter().find(|s| s.as_str() == k))
    else {
        return;
    };
    let keep = kind.keys();
    start.retain(|name, _| name == "kind" || keep.contains(&name));
}

/// Removes the key at the dotted `path` from `tree`, so that it takes its
/// default again (`Scene.unset` in Python). The path must name a scene key
/// of [`schema::KEYS`] (not an element, not a section); a key that must be
/// given (`chain.links`, a start's own required keys) cannot be removed.
/// Removing a key that is not set does nothing.
pub fn unset_path(tree: &mut toml::Table, path: &str) -> Result<(), Error> {
    let Some(key) = schema::key(path) else {
        return Err(schema::unknown_key(path));
    };
    if key.default == schema::DefaultValue::Required {
        return Err(Error::field(
            path,
            "is required and has no default: it cannot be unset (set another value instead)",
        ));
    }
    match key.section() {
        None => {
            tree.remove(key.name());
        }
        Some(top) => {
            if let Some(toml::Value::Table(section)) = tree.get_mut(top) {
                section.remove(key.name());
                if section.is_empty() {
                    tree.remove(top);
                }
            }
        }
    }
    Ok(())
}

/// The section table `top` of `tree`, made if missing.
fn section<'a>(
    tree: &'a mut toml::Table,
    path: &str,
    top: &str,
) -> Result<&'a mut toml::Table, Error> {
    tree.entry(top.to_string())
        .or_insert_with(|| toml::Value::Table(toml::Table::new()))
        .as_table_mut()
        .ok_or_else(|| Error::field(path, format!("'{top}' is not a table")))
}

/// Applies `KEY=VALUE` assignments to `tree` in order.
pub fn apply<S: AsRef<str>>(tree: &mut toml::Table, assignments: &[S]) -> Result<(), Error> {
    for a in assignments {
        let (path, value) = parse_assignment(a.as_ref())?;
        set_path(tree, &path, value)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tree() -> toml::Table {
        "[chain]\nlinks = 5\n[start]\nkind = \"catenary\"\np1 = [3.0, 0.0]\n"
            .parse()
            .unwrap()
    }

    #[test]
    fn values_parse_as_toml_with_bare_words_as_strings() {
        assert_eq!(parse_value("100").unwrap(), toml::Value::Integer(100));
        assert_eq!(parse_value(" 2.5 ").unwrap(), toml::Value::Float(2.5));
        assert_eq!(
            parse_value("dopri5").unwrap(),
            toml::Value::String("dopri5".into())
        );
        assert_eq!(
            parse_value("\"rk4\"").unwrap(),
            toml::Value::String("rk4".into())
        );
        assert!(parse_value("[1.0,").is_err());
        assert!(parse_value("1\nw = 2").is_err());
        assert!(parse_value("nan").unwrap().as_float().unwrap().is_nan());
    }

    #[test]
    fn sets_keys_sections_and_array_elements() {
        let mut t = tree();
        apply(
            &mut t,
            &["chain.links=100", "start.p1.0=2.5", "run.method=dopri5"],
        )
        .unwrap();
        assert_eq!(t["chain"]["links"].as_integer(), Some(100));
        assert_eq!(t["start"]["p1"][0].as_float(), Some(2.5));
        assert_eq!(t["run"]["method"].as_str(), Some("dopri5"));
        // Integer keys take whole floats (what a --vary range gives).
        set_path(&mut t, "chain.links", toml::Value::Float(8.0)).unwrap();
        assert_eq!(t["chain"]["links"].as_integer(), Some(8));
    }

    #[test]
    fn a_new_start_kind_drops_the_keys_it_does_not_take() {
        let mut t = tree();
        set_path(&mut t, "start.kind", toml::Value::String("folded".into())).unwrap();
        assert_eq!(t["start"].as_table().unwrap().len(), 1, "{t:?}");
        let mut t = tree();
        apply(
            &mut t,
            &["start.angles=[0, 0, 0, 0, 0]", "start.kind=angles"],
        )
        .unwrap();
        let start = t["start"].as_table().unwrap();
        assert!(
            start.contains_key("angles") && !start.contains_key("p1"),
            "{t:?}"
        );
        // Catenary to stretched: p1 is taken by both and stays.
        let mut t = tree();
        set_path(
            &mut t,
            "start.kind",
            toml::Value::String("stretched".into()),
        )
        .unwrap();
        assert!(t["start"].as_table().unwrap().contains_key("p1"));
        // An unknown kind removes nothing.
        let mut t = tree();
        set_path(&mut t, "start.kind", toml::Value::String("zigzag".into())).unwrap();
        assert!(t["start"].as_table().unwrap().contains_key("p1"));
    }

    #[test]
    fn unset_removes_a_key_with_a_default_only() {
        let mut t = tree();
        apply(&mut t, &["run.method=dopri5"]).unwrap();
        unset_path(&mut t, "run.method").unwrap();
        assert!(!t.contains_key("run"), "{t:?}");
        unset_path(&mut t, "run.rtol").unwrap();
        for (bad, why) in [
            ("chain.links", "required"),
            ("start.p1", "required"),
            ("chain.lenght", "unknown"),
            ("start.p1.0", "unknown"),
            ("chain", "unknown"),
        ] {
            let e = unset_path(&mut t, bad).unwrap_err().to_string();
            assert!(e.starts_with(&format!("{bad}: ")), "{e}");
            if why == "required" {
                assert!(e.contains("required"), "{e}");
            }
        }
    }

    #[test]
    fn bad_paths_name_themselves() {
        for (bad, path) in [
            ("chain.lenght=6", "chain.lenght"),
            ("foo=1", "foo"),
            ("name.x=1", "name.x"),
            ("start.p1.2=1", "start.p1.2"),
            ("start.p1.x=1", "start.p1.x"),
            ("start.p0.0=1", "start.p0.0"),
            ("chain.links.0=1", "chain.links.0"),
            ("chain..links=1", "chain..links"),
        ] {
            let e = apply(&mut tree(), &[bad]).unwrap_err();
            assert!(e.to_string().starts_with(&format!("{path}: ")), "{e}");
            assert!(!e.to_string().contains('\n'));
        }
        let e = apply(&mut tree(), &["chain.links"]).unwrap_err();
        assert!(e.to_string().starts_with("--set: "), "{e}");
    }
}
