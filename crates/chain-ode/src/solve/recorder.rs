//! What every run records, whatever its model: the output samples on the
//! capped grid (the integrator's continuous extension between its steps),
//! the first time a watched value was not finite, the cancel flag and the
//! progress it reports, and the continuous maximum of a scalar along the
//! run ([`ContinuousMax`]). It reads no state: the summary observer
//! (`tally.rs`) asks the model.

use fc_methods::{Cancel, StepView};

/// The samples of a run, its first non-finite time, and its cancel flag.
pub(crate) struct Recorder {
    dim: usize,
    output_dt: Option<f64>,
    t_origin: f64,
    next_sample: u64,
    /// Index of the last sample on the grid (`floor(t_end / dt) + 1`, one
    /// more for rounding): the sampling loop stops there.
    last_sample: u64,
    pub times: Vec<f64>,
    pub states: Vec<f64>,
    /// The first time a watched value was not finite.
    pub t_nonfinite: Option<f64>,
    cancel: Option<Cancel>,
    started: bool,
    buf: Vec<f64>,
}

impl Recorder {
    /// A recorder of states of `dim` numbers every `output_dt` up to
    /// `t_end` (none for `None`), watching `cancel`.
    pub fn new(dim: usize, t_end: f64, output_dt: Option<f64>, cancel: Option<Cancel>) -> Self {
        // Saturating: `solve` has bounded t_end / output_dt already.
        let last_sample = output_dt.map_or(0, |dt| ((t_end / dt).floor() as u64).saturating_add(1));
        Self {
            dim,
            output_dt,
            t_origin: 0.0,
            next_sample: 0,
            last_sample,
            times: Vec::new(),
            states: Vec::new(),
            t_nonfinite: None,
            cancel,
            started: false,
            buf: vec![0.0; dim],
        }
    }

    /// True once the run's cancel flag is set.
    pub fn cancelled(&self) -> bool {
        self.cancel.as_ref().is_some_and(Cancel::is_cancelled)
    }

    /// Notes `t` if any of `values` is not finite (the first such time).
    pub fn note_finite(&mut self, t: f64, values: &[f64]) {
        if self.t_nonfinite.is_none() && !values.iter().all(|v| v.is_finite()) {
            self.t_nonfinite = Some(t);
        }
    }

    fn record(&mut self, t: f64, y: &[f64]) {
        self.times.push(t);
        self.states.extend_from_slice(y);
        // Progress for a caller watching from another thread (per sample).
        if let Some(c) = &self.cancel {
            c.report(t);
        }
    }

    /// The run's start at `t0` (a continuation after a cut or a handover
    /// goes on with the record).
    pub fn start(&mut self, t0: f64, y0: &[f64]) {
        debug_assert_eq!(y0.len(), self.dim);
        if self.started {
            return;
        }
        self.started = true;
        self.t_origin = t0;
        if self.output_dt.is_some() {
            self.record(t0, y0);
            self.next_sample = 1;
        }
    }

    /// The samples of the grid in the accepted step (`t0, t1]`.
    pub fn step(&mut self, step: &StepView<'_>) {
        let Some(dt) = self.output_dt else {
            return;
        };
        while self.next_sample <= self.last_sample {
            let ts = self.t_origin + self.next_sample as f64 * dt;
            if ts > step.t1 + 1e-9 * dt {
                break;
            }
            if (ts - step.t1).abs() <= 1e-9 * dt {
                self.times.push(step.t1);
                self.states.extend_from_slice(step.y1);
            } else {
                step.interpolant.eval(ts, &mut self.buf);
                self.times.push(ts);
                self.states.extend_from_slice(&self.buf);
            }
            self.next_sample += 1;
            // Progress for a caller watching from another thread.
            if let Some(c) = &self.cancel {
                c.report(ts);
            }
        }
    }

    /// The run's end at `t` in `y`: the last sample, if the grid did not
    /// end there.
    pub fn finish(&mut self, t: f64, y: &[f64]) {
        if self.output_dt.is_some() && self.times.last().is_none_or(|&tl| tl < t) {
            self.record(t, y);
        }
    }
}

/// The continuous maximum of a scalar `s(t)` along a run: at each accepted
/// step's end its value and slope; where the slope turns from rising to
/// falling, a golden-section search on the step's continuous extension.
/// NaN propagates (a NaN is never hidden by `max`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ContinuousMax {
    /// The largest value so far.
    pub value: f64,
    /// Where it was.
    pub t: f64,
    slope: f64,
}

impl ContinuousMax {
    /// The start: `value` and `slope` at `t0`.
    pub fn start(&mut self, t0: f64, value: f64, slope: f64) {
        self.value = value;
        self.t = t0;
        self.slope = slope;
    }

    /// An accepted step `[t0, t1]` ending at `value` with `slope`; `eval`
    /// gives the scalar at any time in the step.
    pub fn step(&mut self, t0: f64, t1: f64, value: f64, slope: f64, eval: impl FnMut(f64) -> f64) {
        if self.slope > 0.0 && slope < 0.0 {
            let tol = golden_width(t0, t1);
            let (t, v, _) = golden_max(t0, t1, tol, eval);
            if v > self.value || v.is_nan() {
                self.value = v;
                self.t = t;
            }
        }
        if value > self.value || value.is_nan() {
            self.value = value;
            self.t = t1;
        }
        self.slope = slope;
    }
}

/// Iteration cap of [`golden_max`]: the width `1e-10 h + 1e-15` of
/// [`golden_width`] is reached within 48 iterations (`R^48 < 1e-10`) wherever
/// floats are dense enough to reach it, so the cap binds only where a
/// bracket stalls at one or two ulps of `t`.
pub(crate) const GOLDEN_MAX_ITERS: u32 = 100;

/// The spacing of floats at `|x|` (one ulp; `inf` for `inf` or the largest float).
fn ulp(x: f64) -> f64 {
    let x = x.abs();
    if x.is_finite() {
        f64::from_bits(x.to_bits() + 1) - x
    } else {
        x
    }
}

/// The width at which the maximum search in a step `[t0, t1]` (time units)
/// stops: `1e-10 h + 1e-15`, but never below the spacing of floats in the
/// step (one ulp of the smaller `|t|`), the narrowest bracket of distinct
/// times. Below `|t| = 8` that spacing is under `1e-15` and the width is
/// `1e-10 h + 1e-15` exactly; where it is not, the narrower width could
/// only be met by a bracket of zero width, and the search could stall.
pub(crate) fn golden_width(t0: f64, t1: f64) -> f64 {
    let width = 1e-10 * (t1 - t0) + 1e-15;
    width.max(ulp(t0.abs().min(t1.abs())))
}

/// Golden-section search for the maximum of `f` on `[t0, t1]`: narrows the
/// bracket until it is at most `tol` wide, or for [`GOLDEN_MAX_ITERS`]
/// iterations, whichever comes first. Returns the better inner point, its
/// value and the iterations taken. The point always lies in `[t0, t1]`.
pub(crate) fn golden_max(
    t0: f64,
    t1: f64,
    tol: f64,
    mut f: impl FnMut(f64) -> f64,
) -> (f64, f64, u32) {
    const R: f64 = 0.618_033_988_749_895;
    let (mut a, mut b) = (t0, t1);
    let mut c = b - R * (b - a);
    let mut d = a + R * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    let mut iterations = 0;
    while b - a > tol && iterations < GOLDEN_MAX_ITERS {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - R * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + R * (b - a);
            fd = f(d);
        }
        iterations += 1;
    }
    let (t, v) = if fc > fd { (c, fc) } else { (d, fd) };
    (t.max(t0).min(t1), v, iterations)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::sync::mpsc;
    use std::time::Duration;

    /// Runs `f` on its own thread and fails if it has not returned within
    /// `secs`: a liveness bound (a hang fails the test instead of the suite).
    fn within<T: Send + 'static>(secs: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(f());
        });
        rx.recv_timeout(Duration::from_secs(secs))
            .expect("did not finish: a loop without a bound")
    }

    proptest! {
        /// Steps at any time up to 1e9 and of any length down to 1e-12 (far
        /// below one ulp of t there): the search ends by its width, not its
        /// cap, and the time it returns lies in the step and within the
        /// final width of the true maximum of a known interpolant (a
        /// parabola peaking at a known point of the step, or at an end).
        #[test]
        fn the_maximum_search_ends_and_brackets_the_maximum(
            t_exp in -3.0f64..9.0,
            h_exp in -12.0f64..0.0,
            frac in -0.2f64..1.2,
            curvature in 1e-3f64..1e3,
        ) {
            let t0 = 10f64.powf(t_exp);
            let t1 = t0 + 10f64.powf(h_exp);
            // The true maximum of f on [t0, t1]: the vertex, or the nearer end.
            let vertex = t0 + frac * (t1 - t0);
            let t_max = vertex.max(t0).min(t1);
            let tol = golden_width(t0, t1);
            let (t, v, iterations) = within(20, move || {
                golden_max(t0, t1, tol, |t| -curvature * (t - vertex) * (t - vertex))
            });
            prop_assert!(iterations < GOLDEN_MAX_ITERS, "{iterations} iterations");
            prop_assert!(t0 <= t && t <= t1, "{t} outside [{t0}, {t1}]");
            // The final bracket (at most tol wide, plus the rounding of its
            // inner points) holds the maximum.
            let ulp = f64::EPSILON * t1.abs();
            prop_assert!((t - t_max).abs() <= tol + 4.0 * ulp,
                "t = {t}, true maximum at {t_max}, tol {tol:e}");
            prop_assert!(v <= 0.0 && v.is_finite());
        }
    }

    #[test]
    fn the_width_never_falls_below_one_ulp_of_t() {
        for t in [1.0, 8.0, 1e3, 1e6, 1e9, 1e15] {
            let w = golden_width(t, t + 1e-12);
            // A bracket [t, t + w] holds two distinct floats.
            assert!(t + w > t, "t = {t}: {w:e}");
            assert!(w >= 1e-15, "t = {t}: {w:e}");
        }
        assert_eq!(golden_width(1e9, 1e9 + 1e-12), 1.1920928955078125e-7);
        // Below |t| = 8 the width is the step's 1e-10 plus 1e-15, exactly.
        for (t0, h) in [(0.0, 1e-9), (1.0, 0.01), (7.99, 1e-12), (-3.0, 1e-6)] {
            assert_eq!(golden_width(t0, t0 + h), 1e-10 * (t0 + h - t0) + 1e-15);
        }
    }

    #[test]
    fn the_search_stops_at_its_cap_when_the_width_cannot_be_reached() {
        // A negative width can never be reached (a bracket of floats at
        // t = 1e9 stalls at an ulp anyway): only the iteration cap ends it.
        let (t, _, iterations) = within(20, || {
            golden_max(1e9, 1e9 + 1e-3, -1.0, |t| -(t - 1e9 - 5e-4).powi(2))
        });
        assert_eq!(iterations, GOLDEN_MAX_ITERS);
        assert!((1e9..=1e9 + 1e-3).contains(&t));
        assert!((t - (1e9 + 5e-4)).abs() < 1e-6, "{t}");
    }

    #[test]
    fn the_sampling_loop_stops_at_the_last_sample_of_the_run() {
        let rec = Recorder::new(5, 1.0, Some(0.3), None);
        // Samples at 0, 0.3, 0.6, 0.9 (index 3), and one more for rounding.
        assert_eq!(rec.last_sample, 4);
        // Counts near the limits of u64 saturate instead of overflowing.
        let rec = Recorder::new(5, 1e300, Some(1e-300), None);
        assert_eq!(rec.last_sample, u64::MAX);
    }
}
