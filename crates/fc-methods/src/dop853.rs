//! Dormand–Prince 8(5,3) (Hairer & Wanner's DOP853): 12 stages, the
//! combined fifth/third-order error estimate, a PI step-size controller,
//! Hairer's initial step, the seventh-order dense output (3 extra stages,
//! made only for steps that are interpolated) and Hairer's stiffness
//! detection.
//!
//! Stages are numbered as in the literature, `k1..k16`; slot `s` of the
//! stage buffer holds `k_{s+1}`. `k1 = f(t0, y0)` comes from the previous
//! step, `k2..k12` cost 11 evaluations per attempt, `k13 = f(t1, y1)` is
//! evaluated on acceptance and becomes the next `k1` (FSAL), and
//! `k14..k16` feed only the dense output and are evaluated on a step's first
//! interpolation: 12 evaluations per accepted step (15 if it is
//! interpolated), 11 per rejected one.

use std::cell::RefCell;

use super::dop853_tableau::{B, BHH, D, DENSE_STAGES, ER, SLOTS, STAGES};
use super::explicit::{self, lambda_estimate, Control, Pair, Parts, Step};
use super::integrator::{Integrator, Settings};
use crate::ode::{all_finite, Interpolant, Observer, OdeSystem};

/// PI controller: exponents and limits (Hairer's DOP853 defaults), and the
/// stiffness test `h |lambda| > 6.1`.
const BETA: f64 = 0.0;
const CONTROL: Control = Control {
    safety: 0.9,
    beta: BETA,
    expo1: 1.0 / 8.0 - BETA * 0.2,
    fac_min: 0.333, // h_new >= 0.333 h
    fac_max: 6.0,   // h_new <= 6 h
    stiff_hlambda: 6.1,
};

/// `out = sum_j a_j k_j`, every component (`k` holds slots of length
/// `out.len()`): each component's sum in `row`'s order from `-0.0` (as
/// `Iterator::sum` adds), the same bits as summing component by component,
/// but [`BLOCK`] components at a time, slot by slot, their sums held in
/// registers, so that the loads are contiguous and the arithmetic
/// vectorises (component by component, strided over the slots, it was 30%
/// of a DOP853 run on Cayley's chain, `perf`; the order of the additions
/// is unchanged).
fn weighted_into(out: &mut [f64], k: &[f64], row: &[(usize, f64)]) {
    let d = out.len();
    let mut blocks = out.chunks_exact_mut(BLOCK);
    for (b, o) in (&mut blocks).enumerate() {
        let mut acc = [-0.0; BLOCK];
        for &(j, a) in row {
            let at = j * d + b * BLOCK;
            for (s, kj) in acc.iter_mut().zip(&k[at..at + BLOCK]) {
                *s += a * kj;
            }
        }
        o.copy_from_slice(&acc);
    }
    let done = d - d % BLOCK;
    for (i, o) in (done..).zip(blocks.into_remainder()) {
        *o = row.iter().map(|&(j, a)| a * k[j * d + i]).sum();
    }
}

/// The components [`weighted_into`] sums together.
const BLOCK: usize = 8;

/// `out = y + h sum_j a_j k_j`.
fn combine(out: &mut [f64], y: &[f64], h: f64, k: &[f64], row: &[(usize, f64)]) {
    weighted_into(out, k, row);
    for (o, yi) in out.iter_mut().zip(y) {
        *o = yi + h * *o;
    }
}

/// The continuous extension of one step: `y(t0 + theta h)`, seventh order.
///
/// Its three extra stages `k14..k16` cost three right-hand sides, and only
/// some steps are ever interpolated (a sample falls in them, or a maximum of
/// the tip speed): they are computed on the first [`Interpolant::eval`] of
/// the step, not for every step.
struct Dense<'a, S> {
    t0: f64,
    h: f64,
    lazy: RefCell<Lazy<'a, S>>,
}

/// What the dense stages need, and the coefficients once they are made.
struct Lazy<'a, S> {
    ready: bool,
    sys: &'a mut S,
    y: &'a [f64],
    /// Stage slots `k1..k16`; `k14..k16` are written here.
    k: &'a mut [f64],
    ys: &'a mut [f64],
    /// `rcont1..rcont8`, `d` each: `[y0 | y1 - y0 | h k1 - (y1 - y0) |
    /// (y1 - y0) - h k13 - rcont3 | h sum d4_i k_i | ... | h sum d7_i k_i]`;
    /// the first four are set before the step is shown.
    r: &'a mut [f64],
}

impl<S: OdeSystem> Lazy<'_, S> {
    /// The dense stages and the coefficients `rcont5..rcont8`.
    fn prepare(&mut self, t0: f64, h: f64) {
        let d = self.y.len();
        for (slot, &(c, row)) in (13..).zip(&DENSE_STAGES) {
            let (done, rest) = self.k.split_at_mut(slot * d);
            combine(self.ys, self.y, h, done, row);
            self.sys.rhs(t0 + c * h, self.ys, &mut rest[..d]);
        }
        for (m, row) in D.iter().enumerate() {
            let r = &mut self.r[(4 + m) * d..(5 + m) * d];
            weighted_into(r, self.k, row);
            for x in r.iter_mut() {
                *x *= h;
            }
        }
        self.ready = true;
    }
}

impl<S: OdeSystem> Interpolant for Dense<'_, S> {
    fn eval(&self, t: f64, out: &mut [f64]) {
        let mut lazy = self.lazy.borrow_mut();
        if !lazy.ready {
            lazy.prepare(self.t0, self.h);
        }
        let d = out.len();
        let s = (t - self.t0) / self.h;
        let s1 = 1.0 - s;
        let r = |m: usize, i: usize| lazy.r[m * d + i];
        for (i, o) in out.iter_mut().enumerate() {
            let conf = r(4, i) + s * (r(5, i) + s1 * (r(6, i) + s * r(7, i)));
            *o = r(0, i) + s * (r(1, i) + s1 * (r(2, i) + s * (r(3, i) + s1 * conf)));
        }
    }
}

/// The two error estimates of one attempt, as sums over components of
/// `(estimate / (atol + rtol max(|y0|, |y1|)))^2`, without the factor `h`:
/// `sq5` of the fifth-order one (`sum er_i k_i`), `sq3` of the third-order
/// one (`sum (b_i - bhh_i) k_i`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Estimate {
    pub sq5: f64,
    pub sq3: f64,
}

impl Estimate {
    /// Hairer's combined error norm of a step of `h` in dimension `d`:
    /// `err5^2 / sqrt(err5^2 + 0.01 err3^2)`, with `errN` the RMS of `h` times
    /// estimate `N`. The step is accepted when it is at most 1.
    pub fn norm(self, h: f64, d: usize) -> f64 {
        let deno = self.sq5 + 0.01 * self.sq3;
        let deno = if deno > 0.0 { deno } else { 1.0 };
        h * self.sq5 / (d as f64 * deno).sqrt()
    }
}

/// One attempt of a step of `h` from `(t, y)`, with `k1 = f(t, y)` in slot 0:
/// the stages `k2..k12` (slots 1..12; the state of `k12` is left in `ys`),
/// the eighth-order `y1`, and its error estimates. The step loop's own
/// arithmetic; the tests call it to see the estimates.
#[allow(clippy::too_many_arguments)]
pub(crate) fn attempt<S: OdeSystem>(
    sys: &mut S,
    t: f64,
    h: f64,
    y: &[f64],
    k: &mut [f64],
    ys: &mut [f64],
    y1: &mut [f64],
    o: &Settings,
) -> Estimate {
    let d = y.len();
    for (slot, &(c, row)) in (1..).zip(&STAGES) {
        let (done, rest) = k.split_at_mut(slot * d);
        combine(ys, y, h, done, row);
        sys.rhs(t + c * h, ys, &mut rest[..d]);
    }
    // The sums of the solution and of the two estimates, slot by slot; the
    // estimates' in the dense stages' slots `k14`, `k15`, free until a step
    // is interpolated (after it is accepted).
    let (k, free) = k.split_at_mut(13 * d);
    let (bhh, rest) = free.split_at_mut(d);
    let er = &mut rest[..d];
    weighted_into(y1, k, &B);
    weighted_into(bhh, k, &BHH);
    weighted_into(er, k, &ER);
    let (mut sq5, mut sq3) = (0.0, 0.0);
    for i in 0..d {
        let b = y1[i];
        y1[i] = y[i] + h * b;
        let e3 = b - bhh[i];
        let e5 = er[i];
        let sk = o.atol + o.rtol * y[i].abs().max(y1[i].abs());
        sq5 += (e5 / sk).powi(2);
        sq3 += (e3 / sk).powi(2);
    }
    Estimate { sq5, sq3 }
}

/// DOP853's storage: the stage slots `k1..k16` (`k`, one run of `16 d`)
/// and the shared buffers (`ys`: the last stage's state; `aux`: `f1`;
/// eight rows of dense output).
pub(crate) type Stages = explicit::Stages<Vec<f64>>;

/// `dop853`: Dormand–Prince 8(5,3), adaptive, for tight tolerances.
pub(crate) const DOP853: Integrator = explicit::integrator::<Stages>("dop853");

impl Pair for Stages {
    const ORDER: u32 = 8;
    const CONTROL: Control = CONTROL;

    fn new(d: usize) -> Self {
        Self::with(vec![0.0; SLOTS * d], d, 8)
    }

    fn parts(&mut self) -> Parts<'_> {
        let d = self.ys.len();
        (&mut self.k[..d], (&mut self.ys, &mut self.aux))
    }

    fn attempt<S: OdeSystem>(&mut self, sys: &mut S, s: &mut Step<'_>) -> Option<f64> {
        let d = s.y.len();
        let k = &mut self.k;
        let y1 = &mut *s.y1;
        let e = attempt(sys, s.t, s.h, s.y, k, &mut self.ys, y1, s.o).norm(s.h, d);
        // A passing trial also needs a finite k13 before it is accepted.
        let mut finite = e.is_finite() && all_finite(y1);
        if finite && e <= 1.0 {
            sys.rhs(s.t1, y1, &mut k[12 * d..13 * d]);
            finite = all_finite(&k[12 * d..13 * d]);
        }
        finite.then_some(e)
    }

    fn lambda(&self, y1: &[f64]) -> f64 {
        // |lambda| ~ |k13 - k12| / |y1 - Y12|: both stages at the step end (Y12 is in ys).
        let d = y1.len();
        lambda_estimate(
            &self.k[11 * d..12 * d],
            &self.k[12 * d..13 * d],
            y1,
            &self.ys,
        )
    }

    fn show<S: OdeSystem>(&mut self, sys: &mut S, s: &Step<'_>, obs: &mut dyn Observer) {
        let Step { t, h, y, .. } = *s;
        let y1: &[f64] = s.y1;
        let d = y.len();
        let (k, rcont) = (&mut self.k, &mut self.rcont);
        // Dense output: the cheap coefficients now, the stages on demand.
        for i in 0..d {
            let dy = y1[i] - y[i];
            let bspl = h * k[i] - dy;
            rcont[i] = y[i];
            rcont[d + i] = dy;
            rcont[2 * d + i] = bspl;
            rcont[3 * d + i] = dy - h * k[12 * d + i] - bspl;
        }
        self.aux.copy_from_slice(&k[12 * d..13 * d]);
        {
            let dense = Dense {
                t0: t,
                h,
                lazy: RefCell::new(Lazy {
                    ready: false,
                    sys,
                    y,
                    k: &mut *k,
                    ys: &mut self.ys,
                    r: rcont,
                }),
            };
            obs.step(&s.view(&self.aux, &dense));
        }
        k.copy_within(12 * d..13 * d, 0); // FSAL: k13 of this step is k1 of the next.
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrator::Span;
    use crate::ode::{Outcome, Status, StepView};
    use crate::test_problems::{
        kepler, kepler_exact, max_diff, options, oscillator_dense_check, relaxation, slope, toy,
        Probe, Quiet, Toy, ECC,
    };

    /// The slot-by-slot sums ([`weighted_into`]) are the component-by-
    /// component sums in each row's order bit for bit, on every row of the
    /// tableau, stages of mixed magnitudes and signs, signed zeros included
    /// (so that the data every figure draws from DOP853 is unchanged by the
    /// loop order). Starting from `+0.0`, or adding a row backwards, fails.
    #[test]
    fn slot_by_slot_sums_are_the_componentwise_sums_bit_for_bit() {
        let d = 37;
        let mut k = vec![0.0; SLOTS * d];
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for (n, v) in k.iter_mut().enumerate() {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            let mag = 10f64.powi((x % 17) as i32 - 8);
            *v = match n % 11 {
                0 => -0.0,
                1 => 0.0,
                _ => (x as f64 / u64::MAX as f64 - 0.5) * mag,
            };
        }
        let rows = (STAGES.iter().map(|(_, r)| *r))
            .chain(DENSE_STAGES.iter().map(|(_, r)| *r))
            .chain(D.iter().map(|r| &r[..]))
            .chain([&B[..], &BHH[..], &ER[..]]);
        let mut out = vec![0.0; d];
        for row in rows {
            weighted_into(&mut out, &k, row);
            for (i, o) in out.iter().enumerate() {
                let reference: f64 = row.iter().map(|&(j, a)| a * k[j * d + i]).sum();
                assert_eq!(o.to_bits(), reference.to_bits(), "component {i}");
            }
        }
    }

    /// Runs and checks the cost model against the toy's own count:
    /// `1 + [probe] + 11 per attempt + 1 per accepted step + 3 per
    /// interpolated step` (no non-finite trials). `interpolates` says whether
    /// the observer evaluates every step's dense output, none, or (`None`)
    /// some.
    fn run_clean(
        sys: &mut Toy,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        o: &Settings,
        obs: &mut dyn Observer,
        interpolates: Option<bool>,
    ) -> Outcome {
        let span = Span {
            t0,
            y0,
            t_end,
            settings: o,
        };
        let out = explicit::run::<Stages, _>(sys, &span, obs);
        let s = out.stats;
        assert_eq!(s.rhs_evals, sys.rhs_calls);
        let probe = u64::from(o.h0.is_none());
        let base = 1 + probe + 11 * (s.steps + s.rejected_steps) + s.steps;
        match interpolates {
            Some(true) => assert_eq!(s.rhs_evals, base + 3 * s.steps, "{s:?}"),
            Some(false) => assert_eq!(s.rhs_evals, base, "{s:?}"),
            // Some steps: 3 more for each, at most every step.
            None => {
                let extra = s.rhs_evals - base;
                assert!(
                    extra.is_multiple_of(3) && extra > 0 && extra <= 3 * s.steps,
                    "{s:?}"
                );
            }
        }
        out
    }

    #[test]
    fn one_step_integrates_polynomials_up_to_the_order() {
        // y' = q t^(q-1): y = t^q. One step of h = 1, accepted whatever its error.
        let thetas = [0.25, 0.5, 0.9];
        for q in 1..=9 {
            let mut sys = toy(1, move |t, _y, dy| dy[0] = q as f64 * t.powi(q - 1));
            let mut obs = Probe {
                times: thetas.to_vec(),
                ..Probe::default()
            };
            let o = Settings {
                h0: Some(1.0),
                ..options(0.5, 1e3)
            };
            let out = run_clean(&mut sys, 0.0, &[0.0], 1.0, &o, &mut obs, Some(true));
            assert_eq!((out.stats.steps, out.stats.rejected_steps), (1, 0));
            let end = (out.y_end[0] - 1.0).abs();
            let dense = obs
                .values
                .iter()
                .map(|(t, y)| (y[0] - t.powi(q)).abs())
                .fold(0.0, f64::max);
            assert_eq!(obs.values.len(), thetas.len());
            // y1 is exact to degree 8, the interpolant to degree 7.
            if q <= 8 {
                assert!(end < 1e-14, "q = {q}: {end:e}");
            } else {
                assert!(end > 1e-6, "q = {q}: {end:e}");
            }
            if q <= 7 {
                assert!(dense < 1e-14, "q = {q}: {dense:e}");
            } else {
                assert!(dense > 1e-6, "q = {q}: {dense:e}");
            }
        }
    }

    #[test]
    fn oscillator_matches_the_exact_solution_with_dense_output() {
        let o = options(1e-12, 1e-14);
        oscillator_dense_check(1e-10, |sys, t0, y0, t_end, obs| {
            run_clean(sys, t0, y0, t_end, &o, obs, Some(true))
        });
    }

    #[test]
    fn kepler_orbit_closes_after_one_period() {
        let period = 2.0 * std::f64::consts::PI;
        let mut sys = kepler();
        let mut obs = Probe {
            times: (1..40).map(|k| period * k as f64 / 40.0).collect(),
            ..Probe::default()
        };
        let y0 = kepler_exact(0.0);
        let out = run_clean(
            &mut sys,
            0.0,
            &y0,
            period,
            &options(1e-12, 1e-12),
            &mut obs,
            None,
        );
        assert_eq!(out.status, Status::Ok);
        assert_eq!(out.t_reached, period);
        let e = max_diff(&out.y_end, &y0);
        let dense = obs
            .values
            .iter()
            .map(|(t, y)| max_diff(y, &kepler_exact(*t)))
            .fold(0.0, f64::max);
        eprintln!(
            "kepler e = {ECC}: {} steps, {} rejected, end error {e:.1e}, dense {dense:.1e}",
            out.stats.steps, out.stats.rejected_steps
        );
        assert!(obs.values.len() >= 39);
        assert!(e < 1e-9, "end error {e:e}");
        assert!(dense < 1e-9, "dense error {dense:e}");
    }

    #[test]
    fn global_error_falls_like_the_eighth_power_of_the_step_count() {
        let period = 2.0 * std::f64::consts::PI;
        let y0 = kepler_exact(0.0);
        let mut points = Vec::new();
        for k in 6..=13 {
            let tol = 10f64.powi(-k);
            let mut sys = kepler();
            let out = run_clean(
                &mut sys,
                0.0,
                &y0,
                period,
                &options(tol, tol),
                &mut Quiet,
                Some(false),
            );
            assert_eq!(out.status, Status::Ok);
            let e = max_diff(&out.y_end, &y0);
            eprintln!("tol 1e-{k}: {} steps, error {e:.2e}", out.stats.steps);
            points.push((out.stats.steps as f64, e));
        }
        let p = slope(&points);
        eprintln!("fitted slope of log(error) vs log(steps): {p:.2}");
        assert!(points.first().unwrap().0 * 2.0 < points.last().unwrap().0);
        assert!((-9.0..=-7.0).contains(&p), "slope {p}");
    }

    #[test]
    fn one_step_local_errors_show_orders_eight_and_seven() {
        // Single steps of size h from apoapsis (t = pi): the step's error is
        // O(h^9) (order 8), the interpolant's at mid-step O(h^8) (order 7).
        let t0 = std::f64::consts::PI;
        let (mut step, mut dense) = (Vec::new(), Vec::new());
        for m in 0..5 {
            let h = 1.6 / 2f64.powi(m);
            let mut sys = kepler();
            let mut obs = Probe {
                times: vec![t0 + 0.5 * h],
                ..Probe::default()
            };
            let o = Settings {
                h0: Some(h),
                ..options(0.5, 1.0)
            };
            let out = run_clean(
                &mut sys,
                t0,
                &kepler_exact(t0),
                t0 + h,
                &o,
                &mut obs,
                Some(true),
            );
            assert_eq!((out.stats.steps, out.stats.rejected_steps), (1, 0));
            let e = max_diff(&out.y_end, &kepler_exact(t0 + h));
            let (t, y) = &obs.values[0];
            let ed = max_diff(y, &kepler_exact(*t));
            eprintln!("h = {h}: step error {e:.2e}, mid-step dense error {ed:.2e}");
            step.push((h, e));
            dense.push((h, ed));
        }
        let (ps, pd) = (slope(&step), slope(&dense));
        eprintln!("local slopes: step {ps:.2}, dense {pd:.2}");
        assert!((8.5..=9.7).contains(&ps), "step slope {ps}");
        assert!((7.5..=8.7).contains(&pd), "dense slope {pd}");
    }

    #[test]
    fn counters_are_exact_with_rejections() {
        // A first step far too long forces rejections.
        let mut sys = kepler();
        let o = Settings {
            h0: Some(3.0),
            ..options(1e-9, 1e-9)
        };
        let out = run_clean(
            &mut sys,
            0.0,
            &kepler_exact(0.0),
            10.0,
            &o,
            &mut Quiet,
            Some(false),
        );
        assert_eq!(out.status, Status::Ok);
        assert!(out.stats.rejected_steps > 0, "{:?}", out.stats);
        assert_eq!(out.stats.jacobian_evals, 0);
        assert_eq!(out.stats.lu_factorizations, 0);
        assert!(max_diff(&out.y_end, &kepler_exact(10.0)) < 1e-6);
    }

    #[test]
    fn a_non_finite_wall_ends_diverged_just_before_it() {
        // y' = 1 up to t = 0.5, NaN beyond: every trial across the wall is
        // non-finite and retried 5x smaller until the step hits the floor.
        let mut sys = toy(1, |t, _y, dy| dy[0] = if t > 0.5 { f64::NAN } else { 1.0 });
        let span = Span {
            t0: 0.0,
            y0: &[0.0],
            t_end: 1.0,
            settings: &options(1e-8, 1e-10),
        };
        let out = explicit::run::<Stages, _>(&mut sys, &span, &mut Quiet);
        eprintln!("wall: {out:?}");
        assert_eq!(out.status, Status::Diverged);
        assert_eq!(out.stats.rhs_evals, sys.rhs_calls);
        assert!(out.stats.rejected_steps > 0);
        assert!(
            out.t_reached <= 0.5 && out.t_reached > 0.5 - 1e-12,
            "{out:?}"
        );
        assert!(out.t_failed.is_some_and(|t| t > out.t_reached));
        assert!((out.y_end[0] - out.t_reached).abs() < 1e-14);
    }

    /// Stops the run at the first stiffness detection past `switch_lambda`.
    struct StopWhenStiff {
        switch_lambda: f64,
        at: Option<f64>,
    }

    impl Observer for StopWhenStiff {
        fn start(&mut self, _: f64, _: &[f64], _: &[f64]) {}
        fn step(&mut self, _: &StepView<'_>) {}
        fn stiff(&mut self, t: f64, lambda: f64) {
            if lambda > self.switch_lambda && self.at.is_none() {
                self.at = Some(t);
            }
        }
        fn stop(&self) -> bool {
            self.at.is_some()
        }
    }

    #[test]
    fn stiffness_is_detected_and_can_stop_the_run() {
        let t_end = 10.0;
        // The slow solution that y(0) = 1 relaxes onto within ~1/1000.
        let slow = |t: f64| (1e6 * t.cos() + 1e3 * t.sin()) / (1e6 + 1.0);
        let mut sys = relaxation();
        // At this tolerance the step is limited by stability, h |lambda| ~ 6.4;
        // at tighter ones (rtol <~ 1e-6) it cycles around 6.1 and the detector stays quiet.
        let o = options(1e-5, 1e-7);
        let out = run_clean(&mut sys, 0.0, &[1.0], t_end, &o, &mut Quiet, Some(false));
        eprintln!("relaxation: {:?}", out.stats);
        assert_eq!(out.status, Status::Ok);
        assert!(out.stats.stiffness_detections > 0, "{:?}", out.stats);
        let e = (out.y_end[0] - slow(t_end)).abs();
        eprintln!("relaxation end error {e:.1e}");
        assert!(e < 1e-5, "{:?}", out.y_end);

        // The observer hears of every detection, with |lambda| = 1000: one
        // that stops the run at the first past switch_lambda (as `auto`
        // does) stops it there ...
        for (switch_lambda, stops) in [(990.0, true), (1010.0, false)] {
            let mut sys = relaxation();
            let mut obs = StopWhenStiff {
                switch_lambda,
                at: None,
            };
            let stop = run_clean(&mut sys, 0.0, &[1.0], t_end, &o, &mut obs, Some(false));
            if stops {
                let t = obs.at.expect("stopped when stiff");
                assert_eq!(stop.status, Status::Interrupted);
                assert_eq!(stop.t_reached, t);
                assert!(t < t_end);
                assert_eq!(stop.stats.stiffness_detections, 1);
                let e = (stop.y_end[0] - slow(t)).abs();
                eprintln!("stopped when stiff at t = {t:.3}, error {e:.1e}");
                assert!(e < 1e-4, "{e:e}");
            } else {
                // ... and one that does not, not.
                assert_eq!(stop.status, Status::Ok);
                assert_eq!(obs.at, None);
                assert_eq!(stop.t_reached, t_end);
                assert_eq!(stop.stats, out.stats);
            }
        }
    }
}
