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
    let (y1, f1) = scratch;
    let d0 = rms_norm(y0, y0, y0, o);
    let d1 = rms_norm(f0, y0, y0, o);
    let mut h0 = if d0 < 1e-10 || d1 < 1e-10 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    h0 = h0.min(span);
    for i in 0..y0.len() {
        y1[i] = y0[i] + h0 * f0[i];
    }
    sys.rhs(t0 + h0, y1, f1);
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
    (100.0 * h0).min(h1).min(span)
}
