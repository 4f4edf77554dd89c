//! Long work that Ctrl-C stops: the work runs on a worker thread with the
//! GIL released, while the calling thread wakes every [`POLL`] to run
//! Python's signal handlers (`Python::check_signals`, with the GIL for just
//! that). When a handler raises (KeyboardInterrupt), the work's
//! [`Cancel`] flag is set, the worker is waited for (a run stops at its next
//! step, a sweep starts no more runs), and the exception is returned.

use std::sync::mpsc;
use std::time::Duration;

use chain_ode::Cancel;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How often the calling thread looks for signals while the work runs.
pub const POLL: Duration = Duration::from_millis(20);

/// Runs `work(cancel)` to its end, or until a Python signal handler raises.
///
/// `work` runs on a new thread without the GIL; it must stop soon once
/// `cancel` is set. Its result comes back as it is; a signal's exception
/// (KeyboardInterrupt) is returned instead once the worker has stopped. A
/// panic in `work` is a RuntimeError (a bug), never an abort of the
/// interpreter. From a thread other than the main thread no signal handler
/// runs (Python runs them only in the main thread), so the work runs to its
/// end.
pub fn run_interruptible<T, W>(py: Python<'_>, work: W) -> PyResult<T>
where
    T: Send,
    W: FnOnce(&Cancel) -> T + Send,
{
    let cancel = Cancel::new();
    py.detach(|| {
        std::thread::scope(|scope| {
            let (done, finished) = mpsc::channel::<()>();
            let flag = &cancel;
            let worker = std::thread::Builder::new()
                .name("falling-chain-run".into())
                .spawn_scoped(scope, move || {
                    let out = work(flag);
                    // The caller may have stopped listening: nothing to do then.
                    let _ = done.send(());
                    out
                })
                .map_err(|e| {
                    PyRuntimeError::new_err(format!("cannot start the run's thread: {e}"))
                })?;
            let mut interrupted = None;
            loop {
                match finished.recv_timeout(POLL) {
                    // Done, or the worker ended without sending (a panic).
                    Ok(()) | Err(mpsc::RecvTimeoutError::Disconnected) => break,
                    Err(mpsc::RecvTimeoutError::Timeout) => {
                        if let Err(e) = Python::attach(|py| py.check_signals()) {
                            cancel.cancel();
                            interrupted = Some(e);
                            break;
                        }
                    }
                }
            }
            let out = worker.join();
            if let Some(e) = interrupted {
                return Err(e);
            }
            out.map_err(|panic| {
                let why = panic
                    .downcast_ref::<&str>()
                    .map(|s| (*s).to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "no message".into());
                PyRuntimeError::new_err(format!(
                    "internal error: the run panicked ({}); please report it",
                    why.split_whitespace().collect::<Vec<_>>().join(" ")
                ))
            })
        })
    })
}
