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
pub const DOCUMENTS: [&str; 3] = ["paper", "methods", "supplement"];

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

/// pandoc's HTML of `paper/<name>.md` (in `dir`), ready to print
/// ([`prepare`]): one self-contained page with MathML and
/// `paper/print.css`, figures as the Markdown places them (no implicit
/// `<figure>`, whose caption would repeat the alt text above the paper's
/// own bold caption paragraph). `scratch` holds pandoc's output.
pub fn html(dir: &Path, name: &str, scratch: &Path) -> Result<String, String> {
    let pandoc = pandoc()?;
    let source = dir.join(format!("{name}.md"));
    let markdown = std::fs::read_to_string(&source).map_err(|e| format!("paper/{name}.md: {e}"))?;
    let out = scratch.join(format!("{name}.pandoc.html"));
    let ran = Command::new(&pandoc)
        .arg(&source)
        .args(["--from", "markdown-implicit_figures", "--to", "html5"])
        .args(["--standalone", "--mathml", "--self-contained"])
        .arg("--css")
        .arg(dir.join("print.css"))
        .arg("--resource-path")
        .arg(dir)
        .arg("--metadata")
        .arg(format!("pagetitle={}", title(&markdown)))
        .arg("--output")
        .arg(&out)
        .output()
        .map_err(|e| format!("cannot run pandoc: {e}"))?;
    if !ran.status.success() {
        return Err(format!(
            "pandoc failed on paper/{name}.md: {}",
            String::from_utf8_lossy(&ran.stderr).trim()
        ));
    }
    let page = std::fs::read_to_string(&out).map_err(|e| format!("{}: {e}", out.display()))?;
    Ok(prepare(&page))
}

/// What pandoc's HTML needs before Chromium prints it:
/// - accents over their base: pandoc writes `\\dot\\varphi` as
///   `<mover><mi>φ</mi><mo accent="true">U+0307</mo></mover>`, a combining
///   dot alone in its `<mo>`, which Chromium sets beside the letter, up and
///   to its left, so that the equation of motion does not read as second
///   order. The mark becomes its spacing form (U+02D9 for the dot, U+00A8
///   for two, U+02DC, U+02C6, U+2192 for the tilde, hat and vector arrow)
///   in a plain `<mo>`, which Chromium centres over the base. (Marking the
///   `<mover>` `accent="true"` instead sets the mark at the font's accent
///   height, which with DejaVu Math TeX Gyre runs it into a tall letter
///   such as φ: looked at in the printed PDF, both ways.)
/// - inline code that breaks only at its spaces: each word of an inline
///   `<code>` that holds a hyphen is wrapped in `<span class="nobr">`
///   (`white-space: nowrap` in `print.css`), so that a flag such as
///   `--json` is never split at its hyphens, and a command copied from the
///   PDF runs. Code blocks (`<pre>`) keep their own wrapping.
pub fn prepare(html: &str) -> String {
    wrap_code_words(&accents_over(html))
}

/// The spacing form of a combining accent (as [`prepare`] lists them).
fn spacing_accent(c: char) -> char {
    match c {
        '\u{0307}' => '\u{02D9}',
        '\u{0308}' => '\u{00A8}',
        '\u{0303}' => '\u{02DC}',
        '\u{0302}' => '\u{02C6}',
        '\u{20D7}' => '\u{2192}',
        other => other,
    }
}

/// [`prepare`]'s accents: every accent `<mo>` pandoc writes (marked
/// `accent="true"`, holding a combining mark) becomes a plain `<mo>` of the
/// mark's spacing form, an over-script that Chromium centres above its
/// base.
fn accents_over(html: &str) -> String {
    const ACCENT: &str = "<mo accent=\"true\">";
    let mut out = String::with_capacity(html.len());
    let mut rest = html;
    while let Some(k) = rest.find(ACCENT) {
        out.push_str(&rest[..k]);
        let body = &rest[k + ACCENT.len()..];
        let end = body.find("</mo>").unwrap_or(body.len());
        out.push_str("<mo>");
        out.extend(body[..end].chars().map(spacing_accent));
        rest = &body[end..];
    }
    out.push_str(rest);
    out
}

/// [`prepare`]'s inline code: the words holding a hyphen of every `<code>`
/// outside `<pre>` wrapped so that they do not break.
fn wrap_code_words(html: &str) -> String {
    let mut out = String::with_capacity(html.len() + 4096);
    let mut rest = html;
    loop {
        let (Some(code), pre) = (rest.find("<code>"), rest.find("<pre")) else {
            out.push_str(rest);
            return out;
        };
        if let Some(pre) = pre.filter(|&p| p < code) {
            // A code block: copied as it is, to its end.
            let end = rest[pre..]
                .find("</pre>")
                .map_or(rest.len(), |e| pre + e + "</pre>".len());
            out.push_str(&rest[..end]);
            rest = &rest[end..];
            continue;
        }
        let start = code + "<code>".len();
        let end = rest[start..]
            .find("</code>")
            .map_or(rest.len(), |e| start + e);
        out.push_str(&rest[..start]);
        let words: Vec<String> = rest[start..end]
            .split(' ')
            .map(|w| {
                if w.contains('-') && !w.contains('<') {
                    format!("<span class=\"nobr\">{w}</span>")
                } else {
                    w.to_string()
                }
            })
            .collect();
        out.push_str(&words.join(" "));
        rest = &rest[end..];
    }
}

/// Typesets every document of `root/paper/` that exists into `out`; returns
/// the PDFs written.
pub fn build_into(root: &Path, out: &Path) -> Result<Vec<PathBuf>, String> {
    pandoc()?;
    let chromium = browser::find()
        .ok_or("paper --pdf needs chromium on PATH or in $CHROMIUM (apt-get install chromium)")?;
    let dir = root.join("paper");
    let scratch = std::env::temp_dir().join(format!("falling-chain-pdf-{}", std::process::id()));
    std::fs::create_dir_all(&scratch).map_err(|e| format!("{}: {e}", scratch.display()))?;
    let result = (|| {
        let mut written = Vec::new();
        for name in DOCUMENTS {
            if !dir.join(format!("{name}.md")).exists() {
                continue;
            }
            let page = scratch.join(format!("{name}.html"));
            std::fs::write(&page, html(&dir, name, &scratch)?)
                .map_err(|e| format!("{}: {e}", page.display()))?;
            let profile = scratch.join(format!("{name}-profile"));
            std::fs::create_dir_all(&profile).map_err(|e| e.to_string())?;
            let pdf = {
                let mut b = browser::Browser::launch(&chromium, &profile, 900, 1200)?;
                b.open(&page)?;
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
            // The accents: in the page, none left as pandoc's combining mark
            // beside its base, every one a spacing mark over it; in the
            // PDF, the dots printed.
            let page = html(&root.join("paper"), name, &out).unwrap();
            assert!(
                !page.contains("<mo accent=\"true\">"),
                "{name}: an accent left as pandoc wrote it"
            );
            for combining in ['\u{0307}', '\u{0308}', '\u{0303}'] {
                assert!(
                    !page.contains(combining),
                    "{name}: a combining {combining:?} left in the MathML"
                );
            }
            if markdown.contains("\\ddot") {
                let over = |mark: char| page.matches(&format!("<mo>{mark}</mo></mover>")).count();
                assert!(
                    over('\u{02D9}') >= 2 && over('\u{00A8}') >= 1,
                    "{name}: accents"
                );
                for dots in ['\u{02D9}', '\u{00A8}'] {
                    assert!(text.contains(dots), "{name}.pdf: no {dots} printed");
                }
            }
            // No flag of the inline code split across lines at a hyphen:
            // no line ends with a flag's head where the next begins with its
            // tail. Every flag is printed whole at least once.
            let flags = code_flags(&markdown);
            assert!(
                !flags.is_empty() || !markdown.contains(" --"),
                "{name}: no flags found"
            );
            for f in &flags {
                assert!(
                    text.contains(f.as_str()),
                    "{name}.pdf never prints {f} whole"
                );
            }
            assert_eq!(
                split_flags(&text, &flags),
                Vec::<String>::new(),
                "{name}.pdf"
            );
        }
        std::fs::remove_dir_all(&out).unwrap();
    }

    /// The flags of `flags` that `text` (pdftotext's, line by line) splits
    /// at a hyphen: a line ending with a flag's head where the next begins
    /// with its tail; each as `head / tail` with the two lines.
    fn split_flags(text: &str, flags: &std::collections::BTreeSet<String>) -> Vec<String> {
        let lines: Vec<&str> = text.lines().map(str::trim).collect();
        let mut found = vec![];
        for f in flags {
            let b = f.as_bytes();
            for j in (1..f.len()).filter(|&j| b[j - 1] == b'-' || b[j] == b'-') {
                let (head, tail) = f.split_at(j);
                for w in lines.windows(2) {
                    if w[0].ends_with(head) && w[1].starts_with(tail) {
                        found.push(format!("{f}: '{}' / '{}'", w[0], w[1]));
                    }
                }
            }
        }
        found
    }

    #[test]
    fn a_flag_split_at_a_hyphen_is_found() {
        let flags =
            code_flags("run `falling-chain simulate x.toml --json --set a=1` and `-p paper`");
        let want: Vec<&str> = vec!["--json", "--set", "-p"];
        assert_eq!(flags.iter().map(String::as_str).collect::<Vec<_>>(), {
            let mut w = want.clone();
            w.sort_unstable();
            w
        });
        assert_eq!(
            split_flags("simulate x.toml -\n-json and --set", &flags),
            vec!["--json: 'simulate x.toml -' / '-json and --set'".to_string()]
        );
        assert_eq!(
            split_flags("with --\nset a=1", &flags),
            vec!["--set: 'with --' / 'set a=1'".to_string()]
        );
        assert!(split_flags("simulate x.toml --json\nand --set a=1", &flags).is_empty());
    }

    /// The flags (`--json`, `-p`) in the inline code of `markdown`.
    fn code_flags(markdown: &str) -> std::collections::BTreeSet<String> {
        markdown
            .split('`')
            .skip(1)
            .step_by(2)
            .flat_map(str::split_whitespace)
            .filter(|w| {
                let rest = w.trim_start_matches('-');
                w.starts_with('-')
                    && !rest.is_empty()
                    && rest.starts_with(|c: char| c.is_ascii_alphabetic())
            })
            .map(|w| {
                w.trim_end_matches(|c: char| !c.is_ascii_alphanumeric())
                    .to_string()
            })
            .collect()
    }

    #[test]
    fn accents_are_spacing_marks_over_their_base() {
        let pandoc = "<msub><mover><mi>φ</mi><mo accent=\"true\">\u{0307}</mo></mover><mi>i</mi></msub>\
                      <mover><mover><mi>m</mi><mo accent=\"true\">\u{0303}</mo></mover><mo accent=\"true\">\u{0308}</mo></mover>\
                      <mover><mi>x</mi><mo>→</mo></mover>";
        assert_eq!(
            accents_over(pandoc),
            "<msub><mover><mi>φ</mi><mo>\u{02D9}</mo></mover><mi>i</mi></msub>\
             <mover><mover><mi>m</mi><mo>\u{02DC}</mo></mover><mo>\u{00A8}</mo></mover>\
             <mover><mi>x</mi><mo>→</mo></mover>"
        );
    }

    #[test]
    fn inline_code_breaks_only_at_its_spaces() {
        let page = "<p><code>falling-chain simulate a.toml --json</code> and \
                    <code>x</code></p><pre><code>--keep as-is</code></pre><code>-p</code>";
        assert_eq!(
            wrap_code_words(page),
            "<p><code><span class=\"nobr\">falling-chain</span> simulate a.toml \
             <span class=\"nobr\">--json</span></code> and <code>x</code></p>\
             <pre><code>--keep as-is</code></pre><code><span class=\"nobr\">-p</span></code>"
        );
    }

    #[test]
    fn the_title_is_the_first_top_heading() {
        assert_eq!(title("<!-- x -->\n## a\n# The chain \nmore"), "The chain");
        assert_eq!(title("no heading"), "falling-chain");
    }
}
