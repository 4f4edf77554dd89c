//! Files that appear whole or not at all.

use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::Error;

/// A temporary file beside the target, removed on drop unless committed.
struct Pending {
    temp: PathBuf,
    committed: bool,
}

impl Drop for Pending {
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

/// Checks, before any work is done, that `path` can be an output file: its
/// directory exists and it is not itself a directory. `what` names the
/// output in the error (e.g. `"--out"`).
pub fn check_writable(what: &'static str, path: &Path) -> Result<(), Error> {
    let dir = parent_dir(path);
    if !dir.is_dir() {
        return Err(Error::write(
            what,
            path,
            io::Error::new(io::ErrorKind::NotFound, "its directory does not exist"),
        ));
    }
    if path.is_dir() {
        return Err(Error::write(
            what,
            path,
            io::Error::new(io::ErrorKind::InvalidInput, "it is a directory"),
        ));
    }
    Ok(())
}

/// Writes `path` atomically: `fill` writes into a temporary file in the same
/// directory, which is then flushed, synced and renamed over `path`. On any
/// error the temporary file is removed and `path` is left as it was.
pub fn write_atomic<F>(what: &'static str, path: &Path, fill: F) -> Result<(), Error>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path.file_name().ok_or_else(|| {
        Error::write(
            what,
            path,
            io::Error::new(io::ErrorKind::InvalidInput, "not a file name"),
        )
    })?;
    let temp = parent_dir(path).join(format!(
        ".{}.tmp-{}-{}",
        name.to_string_lossy(),
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    let fail = |e: io::Error| Error::write(what, path, e);
    let file = File::create_new(&temp).map_err(fail)?;
    let mut pending = Pending {
        temp,
        committed: false,
    };
    let mut w = BufWriter::new(file);
    fill(&mut w).map_err(fail)?;
    let file = w.into_inner().map_err(|e| fail(e.into_error()))?;
    file.sync_all().map_err(fail)?;
    drop(file);
    fs::rename(&pending.temp, path).map_err(fail)?;
    pending.committed = true;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(tag: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("falling-chain-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&d);
        fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn writes_whole_files_and_nothing_on_error() {
        let d = scratch("atomic");
        let out = d.join("a.csv");
        write_atomic("--out", &out, |w| w.write_all(b"x\n")).unwrap();
        assert_eq!(fs::read_to_string(&out).unwrap(), "x\n");
        let e = write_atomic("--out", &out, |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("disk full"))
        })
        .unwrap_err();
        assert!(e.to_string().starts_with("--out: cannot write"), "{e}");
        assert_eq!(fs::read_to_string(&out).unwrap(), "x\n");
        let names: Vec<_> = fs::read_dir(&d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
        assert!(check_writable("--out", &d.join("no/such/dir.csv")).is_err());
        assert!(check_writable("--out", &d).is_err());
        assert!(check_writable("--out", &out).is_ok());
        fs::remove_dir_all(&d).unwrap();
    }
}
