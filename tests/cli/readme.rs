//! The README as a newcomer reads it: at most 200 lines, its two set-up
//! commands word for word, and every command of its "30 seconds" run in
//! order, as written, by a shell whose `PATH` has the binary under test, on
//! a fresh copy of the checkout (its tracked files, in a scratch
//! directory), each exiting 0 and leaving the file it names. The README's
//! Python lines run the same way from the module's tests
//! (`crates/falling-chain-py/tests/test_readme.py`, in `.ci/run`'s venv).
//!
//! `cargo build --release`, the block's first line, is what built the
//! binary under test (this test checks that the binary is
//! `target/release/falling-chain`); of the two set-up commands, `.ci/run`
//! runs `cargo test --workspace --release` (checked here), and
//! `cargo xtask figures` is too long for the suite (3 to 5 minutes).

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{scratch, BIN};

/// The workspace's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn readme() -> String {
    fs::read_to_string(root().join("README.md")).unwrap()
}

/// The README's code block after the heading `heading`, without fences.
pub fn block_after(text: &str, heading: &str) -> String {
    let after = text
        .split_once(&format!("\n{heading}\n"))
        .unwrap_or_else(|| panic!("README.md has no '{heading}'"))
        .1;
    let mut lines = after.lines().skip_while(|l| !l.starts_with("```")).skip(1);
    let mut code = String::new();
    for line in lines.by_ref() {
        if line.starts_with("```") {
            return code;
        }
        code.push_str(line);
        code.push('\n');
    }
    panic!("the code block after '{heading}' never closes")
}

#[test]
fn the_readme_is_at_most_200_lines() {
    let n = readme().lines().count();
    assert!(n <= 200, "README.md has {n} lines: move reference to docs/");
}

#[test]
fn the_readme_keeps_its_two_set_up_commands_word_for_word() {
    let text = readme();
    let setup = text.split_once("\n## Set up\n").unwrap().1;
    assert!(
        setup.contains("\n    cargo xtask figures\n    cargo test --workspace --release\n"),
        "README.md's set-up commands changed"
    );
    let ci = fs::read_to_string(root().join(".ci/run")).unwrap();
    assert!(ci
        .lines()
        .any(|l| l.trim() == "cargo test --workspace --release"));
    // Python and the methods' table within its first screens.
    let line_of = |what: &str| text.lines().position(|l| l.starts_with(what)).unwrap();
    assert!(line_of("## Python") < 80 && line_of("| `gen-alpha` |") < 120);
}

/// The tracked files of the checkout copied under `dir` (a fresh copy: no
/// build output, nothing untracked).
fn fresh_copy(dir: &Path) {
    let listed = Command::new("git")
        .args(["ls-files", "-z"])
        .current_dir(root())
        .output()
        .expect("git runs (the test copies the checkout's tracked files)");
    assert!(listed.status.success());
    for name in listed.stdout.split(|&b| b == 0).filter(|n| !n.is_empty()) {
        let name = std::str::from_utf8(name).unwrap();
        let (from, to) = (root().join(name), dir.join(name));
        if !from.is_file() {
            continue;
        }
        fs::create_dir_all(to.parent().unwrap()).unwrap();
        fs::copy(&from, &to).unwrap();
    }
}

#[test]
fn every_command_of_the_readme_runs_in_order_on_a_fresh_copy() {
    let dir = scratch("readme");
    fresh_copy(&dir);
    assert!(dir.join("scenes/span-d3.toml").is_file());
    let bin = Path::new(BIN);
    let path = std::env::join_paths(std::iter::once(bin.parent().unwrap().to_path_buf()).chain(
        std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default()),
    ))
    .unwrap();
    let block = block_after(&readme(), "## 30 seconds");
    let commands: Vec<&str> = block
        .lines()
        .map(|l| l.strip_prefix("$ ").expect("each line is a `$ ` command"))
        .collect();
    assert!(commands.len() >= 10, "{commands:?}");
    for command in &commands {
        if command.starts_with("cargo build --release") {
            assert!(bin.ends_with("target/release/falling-chain"), "{BIN}");
            continue;
        }
        assert!(command.starts_with("falling-chain "), "{command}");
        let o = Command::new("bash")
            .args(["-c", command])
            .current_dir(&dir)
            .env("PATH", &path)
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "`{command}` exited {:?}: {}",
            o.status.code(),
            String::from_utf8_lossy(&o.stderr)
        );
        // The file it names is there and not empty.
        let words: Vec<&str> = command.split_whitespace().collect();
        for (k, w) in words.iter().enumerate() {
            if ["-o", "--out", "--out-series"].contains(w) {
                let f = dir.join(words[k + 1]);
                assert!(
                    fs::metadata(&f).map(|m| m.len() > 0).unwrap_or(false),
                    "`{command}` wrote no {}",
                    f.display()
                );
            }
        }
    }
}
