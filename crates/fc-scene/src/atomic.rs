//! Files that appear whole or not at all.

use std::io::{self, Write};
use std::path::Path;

use crate::error::Error;

/// The directory `path` will be written into (`.` for a bare file name).
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Checks, before any work is done, that `path` can be an output file: its
/// directory exists, a file can be created there, and `path` is absent, a
/// regular file or a symbolic link to one (written through: the link stays,
/// its target is replaced). A directory, FIFO, device or socket is refused.
/// `what` names the output in the error (e.g. `"--out"`).
pub fn check_writable(what: &'static str, path: &Path) -> Result<(), Error> {
    let dir = parent_dir(path);
    if !dir.is_dir() {
        return Err(Error::write(
            what,
            path,
            io::Error::new(io::ErrorKind::NotFound, "its directory does not exist"),
        ));
    }
    fc_atomic::check_output(path).map_err(|e| Error::write(what, path, e))
}

/// The file a write to `path` reaches, for telling two outputs apart: the
/// path with its directory resolved and a symbolic link followed (an
/// existing file's canonical path; an absent file's canonical directory
/// and name). `None` when it cannot be resolved (its directory is missing,
/// which [`check_writable`] refuses).
fn target(path: &Path) -> Option<std::path::PathBuf> {
    if let Ok(p) = std::fs::canonicalize(path) {
        return Some(p);
    }
    let dir = std::fs::canonicalize(parent_dir(path)).ok()?;
    Some(dir.join(path.file_name()?))
}

/// Whether two existing paths are one file (a hard link, or a name that a
/// case-folding file system maps to the same file).
#[cfg(unix)]
fn same_inode(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_inode(_: &Path, _: &Path) -> bool {
    false
}

/// Refuses, before any work, two outputs of one command that would write
/// one file: the same path, `./x` and `x`, a path through a symbolic link
/// (to the file or to its directory) and its target, two hard links. Each
/// output is `(flag, path)` (`None`: not asked for); the error names both
/// flags and the later one's path.
pub fn check_distinct(outputs: &[(&'static str, Option<&Path>)]) -> Result<(), Error> {
    let given: Vec<(&str, &Path, Option<std::path::PathBuf>)> = outputs
        .iter()
        .filter_map(|&(flag, path)| path.map(|p| (flag, p, target(p))))
        .collect();
    for (k, (flag, path, resolved)) in given.iter().enumerate() {
        for (earlier, first, first_resolved) in &given[..k] {
            if same_file((path, resolved), (first, first_resolved)) {
                return Err(Error::field(
                    *flag,
                    format!(
                        "'{}' is the same file as {earlier} '{}': give each output a file of \
                         its own",
                        crate::error::echo_path(path),
                        crate::error::echo_path(first)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Whether two paths, each with its [`target`], reach one file.
fn same_file(
    (a, a_target): (&Path, &Option<std::path::PathBuf>),
    (b, b_target): (&Path, &Option<std::path::PathBuf>),
) -> bool {
    (a_target.is_some() && a_target == b_target) || same_inode(a, b)
}

/// Refuses, before any work, an output that would replace one of the
/// command's own inputs (`ensemble in.toml --out in.toml`): the same
/// tests as [`check_distinct`]. Each output is `(flag, path)` (`None`:
/// not asked for), each input `(role, path)`; the error names the output's
/// flag, its path and the input's role.
pub fn check_not_inputs(
    outputs: &[(&'static str, Option<&Path>)],
    inputs: &[(&str, &Path)],
) -> Result<(), Error> {
    for &(flag, path) in outputs {
        let Some(path) = path else { continue };
        let resolved = target(path);
        for &(role, input) in inputs {
            if same_file((path, &resolved), (input, &target(input))) {
                return Err(Error::field(
                    flag,
                    format!(
                        "'{}' is the command's own input ({role} '{}'): an output never \
                         replaces an input; give it a file of its own",
                        crate::error::echo_path(path),
                        crate::error::echo_path(input)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// An output file checked and begun before the work ([`begin`]): its
/// hidden temporary file exists (and is removed on SIGINT/SIGTERM, or when
/// this is dropped); [`PendingOutput::write`] fills it and renames it into
/// place.
pub struct PendingOutput {
    what: &'static str,
    path: std::path::PathBuf,
    pending: fc_atomic::Pending,
}

/// Checks `path` as [`check_writable`] does and creates its temporary file
/// now, before the run, so that an output that cannot be written costs no
/// run.
pub fn begin(what: &'static str, path: &Path) -> Result<PendingOutput, Error> {
    check_writable(what, path)?;
    let pending = fc_atomic::Pending::create(path).map_err(|e| Error::write(what, path, e))?;
    Ok(PendingOutput {
        what,
        path: path.to_path_buf(),
        pending,
    })
}

impl PendingOutput {
    /// Fills the file with `fill` and renames it into place.
    pub fn write<F>(self, fill: F) -> Result<(), Error>
    where
        F: FnOnce(&mut dyn Write) -> io::Result<()>,
    {
        let Self {
            what,
            path,
            pending,
        } = self;
        pending
            .write(fill)
            .map_err(|e| Error::write(what, &path, e))
    }

    /// The output's path as given.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// Writes `path` atomically: `fill` writes into a temporary file in the same
/// directory, which is then flushed, synced and renamed over `path`. On any
/// error the temporary file is removed and `path` is left as it was. The
/// writer is the fc-atomic crate's ([`fc_atomic`], the project's one);
/// this adds the error that names the output (`what`, e.g. `"--out"`).
pub fn write_atomic<F>(what: &'static str, path: &Path, fill: F) -> Result<(), Error>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    fc_atomic::write_atomic(path, fill).map_err(|e| Error::write(what, path, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;
    use std::path::PathBuf;

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

    #[test]
    fn two_outputs_on_one_file_are_refused() {
        let d = scratch("distinct");
        let a = d.join("a.csv");
        let dotted = d.join(".").join("a.csv");
        let other = d.join("b.csv");
        let e = check_distinct(&[("--out", Some(&a)), ("--forces", Some(&dotted))])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("--forces: '") && e.contains("same file as --out"),
            "{e}"
        );
        assert!(check_distinct(&[("--out", Some(&a)), ("--forces", Some(&other))]).is_ok());
        assert!(check_distinct(&[("--out", Some(&a)), ("--forces", None)]).is_ok());
        // Through a link to the directory, and to an existing file.
        std::os::unix::fs::symlink(&d, d.join("here")).unwrap();
        let linked = d.join("here").join("a.csv");
        assert!(check_distinct(&[("--out", Some(&a)), ("--plot", Some(&linked))]).is_err());
        fs::write(&a, "x").unwrap();
        std::os::unix::fs::symlink(&a, d.join("l.csv")).unwrap();
        assert!(
            check_distinct(&[("--out", Some(&d.join("l.csv"))), ("--plot", Some(&a))]).is_err()
        );
        fs::hard_link(&a, d.join("h.csv")).unwrap();
        assert!(
            check_distinct(&[("--out", Some(&d.join("h.csv"))), ("--plot", Some(&a))]).is_err()
        );
        fs::remove_dir_all(&d).unwrap();
    }
}
