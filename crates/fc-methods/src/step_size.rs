//! Step-size helpers shared by the explicit adaptive pairs (DOPRI5, DOP853).

use super::integrator::Settings;
use crate::ode::OdeSystem;

/// RMS over components of `x / (atol + rtol max(|y0|, |y1|))`.
pub(crate) fn rms_norm(x: &[f64], y0: &[f64], y1: &[f64], o: &Settings) -> f64 {
    let s: f64 = x
        .iter()
        .zip(y0.iter().zip(y1))
        .map(|(e, (a, b))| {
            let sk = o.atol + o.rtol * a.abs().max(b.abs());
            (e / sk).powi(2)
        })
        .sum();
    (s / x.len() as f64).sqrt()
}

/// Hairer's starting step for a method whose local error is
/// `O(h^order)` (5 for DOPRI5, 8 for DOP853): from `|y0|`, `|f0|` and a trial
/// Euler step (one RHS evaluation).
///
/// Hairer's `h = min(100 h0, h1)` trusts the trial step `h0 = 0.01 |y0| /
/// |f0|`, which a start at rest makes tiny: the rates are 0, so their
/// weights are `atol` and `|f0|` is the accelerations over `atol`. On a
/// very stiff start (a large `g` or stiffness) that put `h` below the
/// rounding floor and every method stopped at `t = 0` with
/// `step_size_too_small`. Only then (so that every other run keeps its
/// first step bit for bit), the trial is repeated from `100 h0` while
/// the estimate `h1` from the trial's second derivative stays above
/// `100 h0`: at most [`GROWTHS`] more RHS evaluations, once per run; a
/// step still below the floor is raised to it (the error test judges it).
#[allow(clippy::too_many_arguments)]
pub(crate) fn initial_step<S: OdeSystem>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    f0: &[f64],
    span: f64,
    o: &Settings,
    order: u32,
    scratch: (&mut [f64], &mut [f64]),
) -> f64 {
    initial_step_with(
        &mut |t, y, f| sys.rhs(t, y, f),
        (t0, y0, f0),
        span,
        o,
        order,
        scratch,
    )
}

/// The most times [`initial_step_with`] grows its trial step (100 times
/// each: 10^40 in all).
pub(crate) const GROWTHS: u32 = 20;

/// A right-hand side as a closure `rhs(t, y, f)`: `f = y'(t, y)`.
pub(crate) type RhsFn<'a> = dyn FnMut(f64, &[f64], &mut [f64]) + 'a;

/// [`initial_step`] with the right-hand side as a closure `rhs(t, y, f)`
/// (diffsol's BDF, whose own guess has the same flaw, calls it when that
/// guess is below the floor).
pub(crate) fn initial_step_with(
    rhs: &mut RhsFn<'_>,
    (t0, y0, f0): (f64, &[f64], &[f64]),
    span: f64,
    o: &Settings,
    order: u32,
    scratch: (&mut [f64], &mut [f64]),
) -> f64 {
    let (y1, f1) = scratch;
    let d0 = rms_norm(y0, y0, y0, o);
    let d1 = rms_norm(f0, y0, y0, o);
    let mut h0 = if d0 < 1e-10 || d1 < 1e-10 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    h0 = h0.min(span);
    // The rounding floor only: a user's h_min stays a bound the run's
    // steps must meet, not a first step it is given.
    let floor = o
        .floor_towards(t0, t0 + span)
        .min(1e-14 * t0.abs().max(1.0));
    let mut growths = 0;
    loop {
        for i in 0..y0.len() {
            y1[i] = y0[i] + h0 * f0[i];
        }
        rhs(t0 + h0, y1, f1);
        for i in 0..y0.len() {
            y1[i] = f1[i] - f0[i];
        }
        let d2 = rms_norm(y1, y0, y0, o) / h0;
        let dm = d1.max(d2);
        let h1 = if dm <= 1e-15 || !dm.is_finite() {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / dm).powf(1.0 / f64::from(order))
        };
        let h = (100.0 * h0).min(h1).min(span);
        // Grown only where Hairer's choice is below the floor and its own
        // estimate h1 says a larger trial is sound.
        if h >= floor || h1 <= 100.0 * h0 || h0 >= span || growths == GROWTHS {
            // Never below the floor: the smallest step the run may take,
            // which the error test then accepts or rejects.
            return h.max(floor);
        }
        h0 = (100.0 * h0).min(span);
        growths += 1;
    }
}
