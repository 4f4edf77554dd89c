//! `simulate --progress`: the time a long run has reached, on stderr.
//!
//! The run notes the time of each sample it records in its
//! [`chain_ode::Cancel`] (at output samples, never inside a step); a
//! watcher thread reads it every `every` seconds of wall time and prints
//! one line, `simulate: t = T of T_END (P%), W s` (W the wall time), to stderr (never stdout,
//! so `--json` stays one line). The watcher ends with the run.

use std::io::Write as _;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use chain_ode::Trajectory;

use fc_scene::scene::Prepared;
use fc_scene::Error;

/// One progress line: the time reached of `t_end`, after `elapsed` seconds.
pub fn line(t: f64, t_end: f64, elapsed: f64) -> String {
    let percent = if t_end > 0.0 {
        100.0 * t / t_end
    } else {
        100.0
    };
    format!("simulate: t = {t:.6} of {t_end} ({percent:.1}%), {elapsed:.1} s")
}

/// Runs `run`, printing a progress line to stderr every `every` seconds
/// (wall time) until it ends.
pub fn solve_showing(run: &Prepared, every: f64) -> Result<Trajectory, Error> {
    let cancel = run.options.cancel.clone().unwrap_or_default();
    let watched = cancel.clone();
    let t_end = run.options.t_end;
    let (done, ended) = mpsc::channel::<()>();
    let start = Instant::now();
    let period = Duration::from_secs_f64(every);
    std::thread::scope(|s| {
        s.spawn(move || {
            // Wakes every `every` s, or at once when the run ends (the
            // sender is dropped); at most one line per period.
            while let Err(mpsc::RecvTimeoutError::Timeout) = ended.recv_timeout(period) {
                let t = watched.reached();
                let _ = writeln!(
                    std::io::stderr().lock(),
                    "{}",
                    line(t, t_end, start.elapsed().as_secs_f64())
                );
            }
        });
        let traj = run.solve_with(cancel);
        drop(done);
        traj
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_says_the_time_reached_of_the_end_time() {
        assert_eq!(
            line(2.5, 10.0, 3.2),
            "simulate: t = 2.500000 of 10 (25.0%), 3.2 s"
        );
        assert!(!line(1.0, 0.0, 0.0).contains("NaN"));
    }
}
