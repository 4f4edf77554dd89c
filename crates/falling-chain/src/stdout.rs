//! Standard output as a pipe's reader may close it: `falling-chain ... |
//! head -3` is an ordinary end. Every command prints its results through
//! [`text`] (the [`say!`] and [`say_raw!`] macros), never `println!`,
//! which panics with "Broken pipe" once the reader has gone.
//!
//! A closed pipe ends nothing else: the command goes on with its files
//! (`--out`, `--plot`) and its exit status, as if its printed lines had
//! been read. Any other failure to write is an error naming the output
//! (exit 2).

use std::io::{ErrorKind, Write as _};

use fc_scene::Error;

/// Writes `text` to standard output and flushes it; a closed pipe is
/// ignored (see the module's doc).
pub fn text(text: &str) -> Result<(), Error> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(Error::field(
            "standard output",
            format!("cannot be written: {e}"),
        )),
    }
}

/// `println!` through [`text`]: returns the error with `?`.
macro_rules! say {
    ($($arg:tt)*) => {
        $crate::stdout::text(&format!("{}\n", format_args!($($arg)*)))?
    };
}

/// `print!` through [`text`].
macro_rules! say_raw {
    ($($arg:tt)*) => {
        $crate::stdout::text(&format!($($arg)*))?
    };
}

pub(crate) use {say, say_raw};
