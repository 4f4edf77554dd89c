//! The cluster recipes of `docs/cluster.md` (once the README's), read out
//! of that page itself, so that the page cannot drift from what the tests
//! run.
//!
//! A recipe is the first fenced code block after a marker line
//! `<!-- recipe: NAME -->`.

use std::path::Path;

/// `docs/cluster.md`, where the recipes live.
pub fn text() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/cluster.md");
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The code of recipe `name` in the page `readme`, without its fences.
pub fn recipe(readme: &str, name: &str) -> String {
    let marker = format!("<!-- recipe: {name} -->");
    let after = readme
        .split_once(&marker)
        .unwrap_or_else(|| panic!("docs/cluster.md has no '{marker}'"))
        .1;
    let mut lines = after
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("```"));
    let fence = lines
        .next()
        .unwrap_or_else(|| panic!("no code block after '{marker}'"));
    assert!(fence.trim_start().starts_with("```"), "{marker}");
    let mut code = String::new();
    for line in lines {
        if line.trim_start().starts_with("```") {
            return code;
        }
        code.push_str(line);
        code.push('\n');
    }
    panic!("the code block after '{marker}' never closes")
}

#[test]
fn a_recipe_is_the_code_block_after_its_marker() {
    let md = "intro\n<!-- recipe: x -->\nSome words.\n```bash\necho 1\necho 2\n```\n```\nnot this\n```\n";
    assert_eq!(recipe(md, "x"), "echo 1\necho 2\n");
}
