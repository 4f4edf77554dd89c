//! `--budget SECONDS`: a deadline for a study. A point predicted to end
//! after it is not started, and a run still going at the deadline is
//! stopped through its [`Cancel`] (it then ends `interrupted` and the study
//! lists it as not run for the budget).

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use chain_ode::Cancel;

use fc_scene::error::Error;

/// The largest budget (s): 30 days.
pub const MAX_BUDGET: f64 = 30.0 * 86_400.0;

/// Checks `--budget`: a number in (0, [`MAX_BUDGET`]]; `what` names it.
pub fn check_budget(what: &str, seconds: f64) -> Result<f64, Error> {
    if seconds.is_finite() && seconds > 0.0 && seconds <= MAX_BUDGET {
        Ok(seconds)
    } else {
        Err(Error::field(
            what,
            format!(
                "must be a number of seconds in (0, {MAX_BUDGET}] (got {})",
                fc_scene::error::number(seconds)
            ),
        ))
    }
}

/// A deadline (or none) and the flag that stops the runs in progress when
/// it passes (or when `outer`, the caller's cancel, is set).
pub struct Budget {
    deadline: Option<Instant>,
    cancel: Cancel,
    outer: Option<Cancel>,
}

impl Budget {
    /// Whether a point predicted to take `seconds` may start now.
    pub fn fits(&self, seconds: f64) -> bool {
        if self.outer.as_ref().is_some_and(Cancel::is_cancelled) || self.cancel.is_cancelled() {
            return false;
        }
        match self.deadline {
            None => true,
            Some(d) => {
                let now = Instant::now();
                now < d && now + Duration::from_secs_f64(seconds.clamp(0.0, MAX_BUDGET)) <= d
            }
        }
    }

    /// The flag that runs should carry in their `SolveOptions::cancel`.
    pub fn cancel(&self) -> &Cancel {
        &self.cancel
    }

    /// Whether the caller's cancel was set (the study is then interrupted,
    /// not out of budget).
    pub fn interrupted(&self) -> bool {
        self.outer.as_ref().is_some_and(Cancel::is_cancelled)
    }

    /// Runs `work` with a budget of `seconds` (none: unlimited), stopping
    /// its runs at the deadline or when `outer` is set: a watcher thread
    /// polls every 20 ms until `work` returns.
    pub fn run<R>(
        seconds: Option<f64>,
        outer: Option<&Cancel>,
        work: impl FnOnce(&Budget) -> R,
    ) -> R {
        let budget = Budget {
            deadline: seconds
                .map(|s| Instant::now() + Duration::from_secs_f64(s.clamp(0.0, MAX_BUDGET))),
            cancel: Cancel::new(),
            outer: outer.cloned(),
        };
        // A budget spent already stops the first run at its start, not when
        // the watcher first wakes.
        if budget.deadline.is_some_and(|d| Instant::now() >= d) {
            budget.cancel.cancel();
        }
        let finished = AtomicBool::new(false);
        std::thread::scope(|scope| {
            scope.spawn(|| {
                // Ends when the work has, or once it set the flag.
                while !finished.load(Ordering::Relaxed) {
                    let late = budget.deadline.is_some_and(|d| Instant::now() >= d);
                    if late || budget.interrupted() {
                        budget.cancel.cancel();
                        break;
                    }
                    std::thread::sleep(Duration::from_millis(20));
                }
            });
            let out = work(&budget);
            finished.store(true, Ordering::Relaxed);
            out
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The deadline's prediction, apart from the watcher: with a minute
    /// left, a point predicted to take a second fits and one predicted to
    /// take two minutes does not (a budget that ignored its deadline would
    /// start it).
    #[test]
    fn a_point_predicted_past_the_deadline_does_not_fit() {
        Budget::run(Some(60.0), None, |b| {
            assert!(b.fits(1.0));
            assert!(!b.fits(120.0));
            assert!(!b.cancel().is_cancelled());
        });
        Budget::run(None, None, |b| assert!(b.fits(MAX_BUDGET)));
    }
}
