//! `cargo xtask paper --pdf`: typesets `paper/*.md` as PDF.
//!
//! The route is pandoc, then headless Chromium:
//! - pandoc reads the Markdown (the filled paper, never the template) and
//!   writes one self-contained HTML page: TeX mathematics (`$...$`,
//!   `$$...$$`) becomes MathML, the figures are embedded, and the stylesheet
//!   `paper/print.css` sets the page;
//! - Chromium, which renders MathML natively, prints that page to PDF
//!   through the DevTools protocol (the `browser` crate, as the viewer's
//!   tests and the `viewer-peak` figure already use it).
//!
//! Why this route: both tools are one `apt-get install` away on Debian
//! (`pandoc`, `chromium`), neither needs a TeX installation (several
//! hundred MB) or a font download, and the same HTML can be read in a
//! browser. typst would be a single binary but is not packaged by Debian
//! 12, and building it from crates.io would add minutes to every cold
//! build for one document.
//!
//! The PDFs are not committed: Chromium stamps a creation date into each,
//! so they cannot be byte-stable, and a fresh machine with only the Rust
//! toolchain can still run `cargo xtask figures`. CI installs pandoc and
//! Chromium, builds them, and checks their text with `pdftotext`
//! (`.ci/run`). `paper/*.pdf` is ignored by git.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The documents typeset, in order: each `paper/<name>.md` that exists.
pub const DOCUMENTS: [&str; 2] = ["paper", "methods"];

/// The title Chromium shows for a document: its first `# ` heading.
fn title(markdown: &str) -> &str {
    markdown
        .lines()
        .find_map(|l| l.strip_prefix("# "))
        .map_or("falling-chain", str::trim)
}

/// `pandoc` on `PATH`, or a one-line error saying how to install it.
fn pandoc() -> Result<PathBuf, String> {
    let dirs = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&dirs)
        .map(|d| d.join("pandoc"))
        .find(|p| p.is_file())
        .ok_or_else(|| "paper --pdf needs pandoc on PATH (apt-get install pandoc)".to_string())
}

/// Typesets every document of `paper/` that exists into `paper/`; returns
/// the PDFs written.
pub fn build(root: &Path) -> Result<Vec<PathBuf>, String> {
    build_into(root, &root.join("paper"))
}

/// Typesets every document of `root/paper/` that exists into `out`; returns
/// the PDFs written.
pub fn build_into(root: &Path, out: &Path) -> Result<Vec<PathBuf>, String> {
    let pandoc = pandoc()?;
    let chromium = browser::find()
        .ok_or("paper --pdf needs chromium on PATH or in $CHROMIUM (apt-get install chromium)")?;
    let dir = root.join("paper");
    let scratch = std::env::temp_dir().join(format!("falling-chain-pdf-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    let result = (|| {
        let mut written = Vec::new();
        for name in DOCUMENTS {
            let source = dir.join(format!("{name}.md"));
            if !source.exists() {
                continue;
            }
            let markdown =
                std::fs::read_to_string(&source).map_err(|e| format!("paper/{name}.md: {e}"))?;
            let html = scratch.join(format!("{name}.html"));
            let ran = Command::new(&pandoc)
                .arg(&source)
                .args(["--from", "markdown", "--to", "html5", "--standalone"])
                .args(["--mathml", "--self-contained"])
                .arg("--css")
                .arg(dir.join("print.css"))
                .arg("--resource-path")
                .arg(&dir)
                .arg("--metadata")
                .arg(format!("pagetitle={}", title(&markdown)))
                .arg("--output")
                .arg(&html)
                .output()
                .map_err(|e| format!("cannot run pandoc: {e}"))?;
            if !ran.status.success() {
                return Err(format!(
                    "pandoc failed on paper/{name}.md: {}",
                    String::from_utf8_lossy(&ran.stderr).trim()
                ));
            }
            let profile = scratch.join(format!("{name}-profile"));
            std::fs::create_dir_all(&profile).map_err(|e| e.to_string())?;
            let pdf = {
                let mut b = browser::Browser::launch(&chromium, &profile, 900, 1200)?;
                b.open(&html)?;
                let errors = b.errors();
                if !errors.is_empty() {
                    return Err(format!("paper/{name}: the page logged errors: {errors:?}"));
                }
                b.print_pdf()?
            };
            let target = out.join(format!("{name}.pdf"));
            fc_atomic::write_atomic(&target, |w| w.write_all(&pdf))
                .map_err(|e| format!("pdf: cannot write '{}': {e}", target.display()))?;
            println!("wrote {} ({} kB)", target.display(), pdf.len() / 1000);
            written.push(target);
        }
        Ok(written)
    })();
    let _ = std::fs::remove_dir_all(&scratch);
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether the tools are here; under CI (`CI=true`) they must be.
    fn tools() -> bool {
        let here = pandoc().is_ok()
            && browser::find().is_some()
            && Command::new("pdftotext").arg("-v").output().is_ok();
        if !here {
            assert!(
                std::env::var("CI").is_err(),
                "CI=true but pandoc, chromium or pdftotext (poppler-utils) is missing"
            );
            eprintln!("skipped: needs pandoc, chromium and pdftotext (poppler-utils)");
        }
        here
    }

    /// The committed paper typeset: every section heading is in the PDF's
    /// text, and the TeX mathematics came out as typeset symbols, not as
    /// TeX source (which is what pandoc leaves without `--mathml`).
    #[test]
    fn the_paper_is_typeset_with_its_mathematics() {
        if !tools() {
            return;
        }
        let root = Path::new(env!("CARGO_MANIFEST_DIR"))
            .parent()
            .and_then(Path::parent)
            .unwrap();
        let out = std::env::temp_dir().join(format!("xtask-pdf-{}", std::process::id()));
        std::fs::create_dir_all(&out).unwrap();
        let written = build_into(root, &out).unwrap();
        assert!(!written.is_empty());
        for pdf in &written {
            let text = Command::new("pdftotext")
                .args(["-enc", "UTF-8"])
                .arg(pdf)
                .arg("-")
                .output()
                .unwrap();
            let text = String::from_utf8_lossy(&text.stdout).into_owned();
            let name = pdf.file_stem().unwrap().to_str().unwrap();
            let markdown = std::fs::read_to_string(root.join(format!("paper/{name}.md"))).unwrap();
            // Headings as they print: inline code and emphasis marks
            // dropped, pandoc's typographic quotes made straight.
            let squash = |s: &str| {
                s.replace(['\u{2018}', '\u{2019}'], "'")
                    .replace(['\u{201c}', '\u{201d}'], "\"")
                    .split_whitespace()
                    .collect::<String>()
            };
            let flat = squash(&text);
            for heading in markdown.lines().filter_map(|l| l.strip_prefix("## ")) {
                let want = squash(&heading.replace(['`', '*'], ""));
                assert!(
                    flat.contains(&want),
                    "{name}.pdf lacks the heading '{heading}'"
                );
            }
            for tex in ["\\varphi", "\\frac", "\\sum", "$$"] {
                assert!(!text.contains(tex), "{name}.pdf shows TeX source '{tex}'");
            }
            if markdown.contains("\\varphi") {
                // MathML sets a lone letter in mathematical italic (U+1D711).
                assert!(
                    text.contains('\u{1d711}') || text.contains('φ'),
                    "{name}.pdf: no typeset φ"
                );
            }
        }
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn the_title_is_the_first_top_heading() {
        assert_eq!(title("<!-- x -->\n## a\n# The chain \nmore"), "The chain");
        assert_eq!(title("no heading"), "falling-chain");
    }
}
