//! ARCHITECTURE.md and the module docs, held to the tree: the map stays
//! short, every path it names exists, and every source file of the
//! workspace is named by its module's doc (`//!`), where the per-file
//! detail lives. A file added, moved or removed without its map fails here.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "test code: a failed unwrap is a failed test"
)]

use std::path::{Path, PathBuf};

/// The workspace's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .canonicalize()
        .unwrap()
}

/// The longest ARCHITECTURE.md may be (rust-analyzer's is about this).
const MAX_LINES: usize = 300;

#[test]
fn the_architecture_stays_a_map() {
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let n = text.lines().count();
    assert!(
        n <= MAX_LINES,
        "ARCHITECTURE.md: {n} lines, past {MAX_LINES}"
    );
}

/// Every file below `dir` (recursively), with `keep` deciding on names.
fn files(dir: &Path, keep: &dyn Fn(&Path) -> bool, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if name == "target" || name.starts_with('.') {
            continue;
        }
        if path.is_dir() {
            files(&path, keep, out);
        } else if keep(&path) {
            out.push(path);
        }
    }
}

/// The workspace's `src/` folders: each crate's and xtask's.
fn source_roots() -> Vec<PathBuf> {
    let mut roots: Vec<PathBuf> = std::fs::read_dir(root().join("crates"))
        .unwrap()
        .map(|e| e.unwrap().path().join("src"))
        .filter(|p| p.is_dir())
        .collect();
    roots.push(root().join("xtask").join("src"));
    roots.sort();
    roots
}

/// The module doc of a source file: its `//!` lines, joined.
fn module_doc(path: &Path) -> String {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("//!"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every path ARCHITECTURE.md names (a backquoted word with a `/` or a
/// file's extension) exists: one with a `/` from the root or as the end of
/// a path in the tree (a glob's or a placeholder's folder for `*`, `<id>`),
/// a bare file name somewhere in the workspace.
#[test]
fn every_path_the_architecture_names_exists() {
    let text = std::fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap();
    let mut all = vec![];
    files(&root(), &|_| true, &mut all);
    let names: Vec<String> = all
        .iter()
        .flat_map(|p| {
            let file = p.file_name().unwrap().to_string_lossy().to_string();
            let dir = p.parent().unwrap().file_name().unwrap().to_string_lossy();
            [file, format!("{dir}/")]
        })
        .collect();
    let extensions = [".rs", ".md", ".toml", ".js", ".css", ".html", ".py", ".csv"];
    let mut checked = 0;
    for (k, word) in text.split('`').enumerate() {
        // Odd pieces are inside backquotes; a path has no space.
        if k % 2 == 0 || word.contains(' ') || word.contains("::") {
            continue;
        }
        let is_path = word.contains('/') || extensions.iter().any(|e| word.ends_with(e));
        if !is_path || word.starts_with("--") || word.starts_with("//") || word.contains("{{") {
            continue;
        }
        checked += 1;
        let found = if word.contains('/') {
            // A glob or a placeholder names its folder; a folder ends in
            // `/`. A path is from the root, or the end of a path in the tree.
            let plain = if word.contains(['*', '<', '{']) {
                let head = word.split(['*', '<', '{']).next().unwrap();
                head.trim_end_matches(|c| c != '/')
            } else {
                word
            };
            let plain = Path::new(plain.trim_end_matches('/'));
            !plain.as_os_str().is_empty()
                && (root().join(plain).exists()
                    || all.iter().any(|p| {
                        p.ends_with(plain) || p.parent().is_some_and(|d| d.ends_with(plain))
                    }))
        } else if let Some(end) = word.strip_prefix('*') {
            names.iter().any(|n| n.ends_with(end))
        } else {
            names.iter().any(|n| n == word)
        };
        assert!(
            found,
            "ARCHITECTURE.md names `{word}`, which is not in the tree"
        );
    }
    assert!(checked > 40, "only {checked} paths checked");
}

/// Every source file is named by its module's doc: a crate's top-level
/// files by `lib.rs` (or `main.rs`), a folder's by its `mod.rs`, a folder
/// by its parent's, as `` `name.rs` `` or `` `name/` `` (or a link
/// `` [`name`] ``): the per-file detail is there, not in ARCHITECTURE.md.
#[test]
fn every_source_file_is_named_by_its_modules_doc() {
    let mut missing = vec![];
    for src in source_roots() {
        let mut rs = vec![];
        files(&src, &|p| p.extension().is_some_and(|e| e == "rs"), &mut rs);
        for file in rs {
            let name = file.file_name().unwrap().to_string_lossy().to_string();
            let dir = file.parent().unwrap().to_path_buf();
            let (stem, parent_dir) = if name == "mod.rs" {
                let folder = dir.file_name().unwrap().to_string_lossy().to_string();
                (format!("{folder}/"), dir.parent().unwrap().to_path_buf())
            } else if dir == src && (name == "lib.rs" || name == "main.rs") {
                continue;
            } else {
                (name.clone(), dir.clone())
            };
            let parent = if parent_dir == src {
                ["lib.rs", "main.rs"]
                    .iter()
                    .map(|f| src.join(f))
                    .find(|p| p.exists())
            } else {
                let m = parent_dir.join("mod.rs");
                m.exists().then_some(m)
            };
            let Some(parent) = parent else {
                missing.push(format!("{}: no parent module", file.display()));
                continue;
            };
            let doc = module_doc(&parent);
            let bare = stem.trim_end_matches(".rs").trim_end_matches('/');
            let named = doc.contains(&format!("`{stem}`"))
                || doc.contains(&format!("[`{bare}`]"))
                || doc.contains(&format!("`{bare}.rs`"));
            if !named {
                missing.push(format!("{} (in {})", file.display(), parent.display()));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "source files their module's doc does not name:\n{}",
        missing.join("\n")
    );
}
