//! Files that appear whole or not at all: the project's one atomic writer.
//!
//! A file is written to a temporary file beside its target (same directory,
//! so the rename cannot cross file systems), flushed, synced and renamed
//! over the target. On any error the temporary file is removed and the
//! target is left as it was. It is a crate of its own, depending on
//! nothing, so that every writer of the project reaches it without a
//! drawing or a solver: the figures crate (its PNG and SVG files),
//! fc-scene (the CLI's and Python's `--out` files), `paper` and `xtask`
//! (figure data, README, paper) all write through it.
//!
//! What a target may be ([`output_target`]): absent, or a regular file, or
//! a symbolic link whose final target is a regular file, which is then
//! written in its place (the link stays a link). A directory, a FIFO, a
//! device, a socket or a dangling link is refused before anything is
//! written. The temporary files in progress are listed, so that a signal
//! handler can remove them ([`remove_temporaries`]).

use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};

/// The temporary files being written (their paths are listed before they
/// are created and unlisted after they are renamed or removed).
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn live() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn unlist(temp: &Path) {
    let mut list = live();
    if let Some(i) = list.iter().position(|p| p == temp) {
        list.swap_remove(i);
    }
}

/// Removes every temporary file in progress and returns the lock on the
/// (now empty) list, so that no new one is started while the caller ends
/// the process: a SIGINT/SIGTERM handler calls this, then exits.
pub fn remove_temporaries() -> MutexGuard<'static, Vec<PathBuf>> {
    let mut list = live();
    for temp in list.drain(..) {
        let _ = fs::remove_file(&temp);
    }
    list
}

/// A written, synced temporary file beside its target; removed on drop
/// unless it was renamed into place.
struct Staged {
    temp: PathBuf,
    /// Where it is renamed to: the path, or a symlink's final target.
    target: PathBuf,
    committed: bool,
}

impl Staged {
    fn commit(mut self) -> io::Result<()> {
        fs::rename(&self.temp, &self.target)?;
        self.committed = true;
        unlist(&self.temp);
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_file(&self.temp);
            unlist(&self.temp);
        }
    }
}

/// What kind of file `meta` is, for the error that refuses it.
fn kind(meta: &fs::Metadata) -> &'static str {
    let t = meta.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a directory"
    } else {
        "not a regular file"
    }
}

fn refuse(why: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, why)
}

/// The file that writing `path` replaces: `path` itself if it is absent or
/// a regular file; a symbolic link's final target if that is a regular
/// file. Anything else (a directory, FIFO, device, socket, or a link to one
/// or to nothing) is an error saying what it is.
pub fn output_target(path: &Path) -> io::Result<PathBuf> {
    let meta = match fs::symlink_metadata(path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(path.to_path_buf()),
        Err(e) => return Err(e),
        Ok(m) => m,
    };
    if meta.is_file() {
        return Ok(path.to_path_buf());
    }
    if meta.file_type().is_symlink() {
        let target = fs::canonicalize(path)
            .map_err(|_| refuse("it is a symbolic link to nothing".into()))?;
        let meta = fs::metadata(&target)?;
        if meta.is_file() {
            return Ok(target);
        }
        return Err(refuse(format!(
            "it is a symbolic link to {}, not to a regular file",
            kind(&meta)
        )));
    }
    Err(refuse(format!(
        "it is {}; an output must be a regular file",
        kind(&meta)
    )))
}

/// The directory of `target` (`.` for a bare file name).
fn dir_of(target: &Path) -> &Path {
    parent_dir(target)
}

/// Checks, before any work, that `path` can be written: it is absent, a
/// regular file or a link to one ([`output_target`]), and a file can be
/// created in its directory (one is made and removed again).
pub fn check_output(path: &Path) -> io::Result<()> {
    static PROBE: AtomicU64 = AtomicU64::new(0);
    let target = output_target(path)?;
    let dir = dir_of(&target);
    let probe = dir.join(format!(
        ".falling-chain-probe-{}-{}",
        std::process::id(),
        PROBE.fetch_add(1, Ordering::Relaxed)
    ));
    live().push(probe.clone());
    let made = File::create_new(&probe);
    let _ = fs::remove_file(&probe);
    unlist(&probe);
    made.map(drop)
}

/// The directory `path` will be written into (`.` for a bare file name).
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// An output whose temporary file exists already (made before a long
/// computation, which so cannot be wasted on an output that cannot be
/// written): [`Pending::write`] fills it and renames it into place;
/// dropping it removes the temporary file.
pub struct Pending {
    staged: Staged,
    file: File,
}

impl Pending {
    /// Creates the temporary file beside `path`'s target ([`output_target`]).
    pub fn create(path: &Path) -> io::Result<Self> {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let target = output_target(path)?;
        let name = target
            .file_name()
            .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
        let temp = dir_of(&target).join(format!(
            ".{}.tmp-{}-{}",
            name.to_string_lossy(),
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        // Listed before it exists, so that a signal between the two cannot miss it.
        live().push(temp.clone());
        let file = match File::create_new(&temp) {
            Ok(f) => f,
            Err(e) => {
                unlist(&temp);
                return Err(e);
            }
        };
        Ok(Self {
            staged: Staged {
                temp,
                target,
                committed: false,
            },
            file,
        })
    }

    /// The hidden temporary file (`.NAME.tmp-PID-K` beside the target).
    pub fn temp_path(&self) -> &Path {
        &self.staged.temp
    }

    /// Fills the temporary file with `fill`, syncs it and renames it over
    /// the target; on any error the temporary file is removed.
    pub fn write<F>(self, fill: F) -> io::Result<()>
    where
        F: FnOnce(&mut dyn Write) -> io::Result<()>,
    {
        self.fill(fill)?.commit()
    }

    fn fill<F>(self, fill: F) -> io::Result<Staged>
    where
        F: FnOnce(&mut dyn Write) -> io::Result<()>,
    {
        let Self { staged, file } = self;
        let mut w = BufWriter::new(file);
        fill(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        Ok(staged)
    }
}

/// Writes a temporary file beside `path`'s target ([`output_target`]) with
/// `fill` and syncs it.
fn stage<F>(path: &Path, fill: F) -> io::Result<Staged>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    Pending::create(path)?.fill(fill)
}

/// Writes `path` atomically: `fill` writes into a temporary file in the same
/// directory, which is then flushed, synced and renamed over `path`.
pub fn write_atomic<F>(path: &Path, fill: F) -> io::Result<()>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    stage(path, fill)?.commit()
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
        if let Err(e) = s.commit() {
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

    #[cfg(unix)]
    #[test]
    fn links_are_written_through_and_special_files_refused() {
        let d = scratch("atomic-kinds");
        let real = d.join("real.csv");
        fs::write(&real, "old").unwrap();
        let link = d.join("link.csv");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_atomic(&link, |w| w.write_all(b"new")).unwrap();
        assert!(fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(fs::read_to_string(&real).unwrap(), "new");
        // A directory, a FIFO, a link to nothing: refused, left as they were.
        let fifo = d.join("fifo");
        let made = std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap();
        assert!(made.success());
        let dangling = d.join("dangling.csv");
        std::os::unix::fs::symlink(d.join("none"), &dangling).unwrap();
        let sub = d.join("sub");
        fs::create_dir(&sub).unwrap();
        for (path, what) in [
            (&fifo, "a FIFO"),
            (&dangling, "to nothing"),
            (&sub, "a directory"),
        ] {
            let e = write_atomic(path, |w| w.write_all(b"x")).unwrap_err();
            assert!(e.to_string().contains(what), "{e}");
            assert!(check_output(path).is_err());
        }
        use std::os::unix::fs::FileTypeExt as _;
        assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
        assert!(check_output(&d.join("new.csv")).is_ok());
        assert!(check_output(&link).is_ok());
        assert!(check_output(&d.join("no/such.csv")).is_err());
        let mut left = names(&d);
        left.sort();
        assert_eq!(
            left,
            vec!["dangling.csv", "fifo", "link.csv", "real.csv", "sub"]
        );
        // The list is the process's: other tests write in parallel, so only
        // this test's directory must have nothing left in it.
        assert!(!live().iter().any(|p| p.starts_with(&d)));
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
