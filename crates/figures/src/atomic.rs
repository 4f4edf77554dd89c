//! Files that appear whole or not at all: the project's one atomic writer.
//!
//! A file is written to a temporary file beside its target (same directory,
//! so the rename cannot cross file systems), flushed, synced and renamed
//! over the target. On any error the temporary file is removed and the
//! target is left as it was. It lives here because this crate depends on
//! nothing of the project: `falling-chain` (its `--out` files) and `xtask`
//! (figure data, README, paper) write through it too.

use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// A written, synced temporary file beside its target; removed on drop
/// unless it was renamed into place.
struct Staged {
    temp: PathBuf,
    committed: bool,
}

impl Staged {
    fn commit(mut self, target: &Path) -> io::Result<()> {
        fs::rename(&self.temp, target)?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_file(&self.temp);
        }
    }
}

/// The directory `path` will be written into (`.` for a bare file name).
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Writes a temporary file beside `path` with `fill` and syncs it.
fn stage<F>(path: &Path, fill: F) -> io::Result<Staged>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    let temp = parent_dir(path).join(format!(
        ".{}.tmp-{}-{}",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let file = File::create_new(&temp)?;
    let staged = Staged {
        temp,
        committed: false,
    };
    let mut w = BufWriter::new(file);
    fill(&mut w)?;
    let file = w.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()?;
    Ok(staged)
}

/// Writes `path` atomically: `fill` writes into a temporary file in the same
/// directory, which is then flushed, synced and renamed over `path`.
pub fn write_atomic<F>(path: &Path, fill: F) -> io::Result<()>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    stage(path, fill)?.commit(path)
}

/// Writes every `(path, bytes)` pair, or none: all are staged first and
/// renamed into place only when every one was written; if a rename fails,
/// the targets already renamed are removed again. The error names the file
/// it is about.
pub fn write_all_atomic(files: &[(&Path, &[u8])]) -> Result<(), (PathBuf, io::Error)> {
    let mut staged = Vec::with_capacity(files.len());
    for (path, bytes) in files {
        let s = stage(path, |w| w.write_all(bytes)).map_err(|e| (path.to_path_buf(), e))?;
        staged.push(s);
    }
    for (i, s) in staged.into_iter().enumerate() {
        let path = files[i].0;
        // The later staged files are removed as `staged` drops.
        if let Err(e) = s.commit(path) {
            for (done, _) in &files[..i] {
                let _ = fs::remove_file(done);
            }
            return Err((path.to_path_buf(), e));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("figures-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    fn names(d: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn whole_files_or_nothing() {
        let d = scratch("atomic-one");
        let out = d.join("a.csv");
        write_atomic(&out, |w| w.write_all(b"x\n")).unwrap();
        assert_eq!(fs::read_to_string(&out).unwrap(), "x\n");
        let e = write_atomic(&out, |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("disk full"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "disk full");
        assert_eq!(fs::read_to_string(&out).unwrap(), "x\n");
        assert_eq!(names(&d), vec!["a.csv"]);
        fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn all_files_or_none() {
        let d = scratch("atomic-all");
        let (a, b) = (d.join("a.png"), d.join("a.svg"));
        write_all_atomic(&[(&a, b"1"), (&b, b"2")]).unwrap();
        assert_eq!(names(&d), vec!["a.png", "a.svg"]);
        // A folder where the second file should go: neither is written.
        let (c, e) = (d.join("c.png"), d.join("c.svg"));
        fs::create_dir(&e).unwrap();
        let (path, _) = write_all_atomic(&[(&c, b"1"), (&e, b"2")]).unwrap_err();
        assert_eq!(path, e);
        assert_eq!(names(&d), vec!["a.png", "a.svg", "c.svg"]);
        fs::remove_dir_all(&d).unwrap();
    }
}
