//! gen-alpha's checks on small problems with closed forms (the chains'
//! are chain-ode's).

use super::*;
use crate::integrator::{Settings, TimeScales};
use crate::testing::Quiet;

/// Damped linear oscillators `x_k'' + 2 zeta_k w_k x_k' + w_k^2 x_k = 0`
/// (or, with `mu`, van der Pol's `x'' = mu (1 - x^2) x' - x`), as a
/// problem with the state `[x_1, v_1, x_2, v_2, ..]` and a banded DAE
/// whose algebraic unknowns are the accelerations.
#[derive(Clone)]
struct Oscillators {
    modes: Vec<(f64, f64)>,
    mu: Option<f64>,
}

impl Oscillators {
    fn accel(&self, k: usize, x: f64, v: f64) -> f64 {
        match self.mu {
            Some(mu) => mu * (1.0 - x * x) * v - x,
            None => {
                let (w, z) = self.modes[k];
                -2.0 * z * w * v - w * w * x
            }
        }
    }
}

impl OdeSystem for Oscillators {
    fn dim(&self) -> usize {
        2 * self.modes.len()
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        for k in 0..self.modes.len() {
            dy[2 * k] = y[2 * k + 1];
            dy[2 * k + 1] = self.accel(k, y[2 * k], y[2 * k + 1]);
        }
    }
    fn jvp(&mut self, _t: f64, _y: &[f64], _v: &[f64], jv: &mut [f64]) {
        jv.fill(0.0);
    }
}

struct OscillatorsDae(Oscillators);

impl SemiExplicitDae for OscillatorsDae {
    fn dim(&self) -> usize {
        3 * self.0.modes.len()
    }
    fn differential_dim(&self) -> usize {
        2 * self.0.modes.len()
    }
    fn rhs(&self, _t: f64, y: &[f64], out: &mut [f64]) {
        let m = self.0.modes.len();
        for k in 0..m {
            let (x, v, a) = (y[2 * k], y[2 * k + 1], y[2 * m + k]);
            out[2 * k] = v;
            out[2 * k + 1] = a;
            out[2 * m + k] = a - self.0.accel(k, x, v);
        }
    }
    fn jacobian_entries(&self, _t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        let m = self.0.modes.len();
        for k in 0..m {
            let (x, v) = (y[2 * k], y[2 * k + 1]);
            let (dx, dv) = match self.0.mu {
                Some(mu) => (2.0 * mu * x * v + 1.0, -mu * (1.0 - x * x)),
                None => {
                    let (w, z) = self.0.modes[k];
                    (w * w, 2.0 * z * w)
                }
            };
            emit(2 * k, 2 * k + 1, 1.0);
            emit(2 * k + 1, 2 * m + k, 1.0);
            emit(2 * m + k, 2 * m + k, 1.0);
            emit(2 * m + k, 2 * k, dx);
            emit(2 * m + k, 2 * k + 1, dv);
        }
    }
}

impl Problem for Oscillators {
    fn banded_dae(&self, t0: f64, y0: &[f64]) -> Option<BandedDae> {
        let m = self.modes.len();
        let mut full = y0.to_vec();
        let mut f = vec![0.0; 2 * m];
        self.clone().rhs(t0, y0, &mut f);
        full.extend((0..m).map(|k| f[2 * k + 1]));
        Some(BandedDae {
            dae: Box::new(OscillatorsDae(self.clone())),
            y0: full,
        })
    }
    fn configuration(&self) -> Vec<std::ops::Range<usize>> {
        (0..self.modes.len()).map(|k| 2 * k..2 * k + 1).collect()
    }
}

fn settings(rtol: f64) -> Settings {
    Settings {
        dt: 0.01,
        rtol,
        atol: rtol * 1e-2,
        h_min: 0.0,
        max_steps: 10_000_000,
        h0: None,
        scales: TimeScales::NONE,
        rho_inf: crate::DEFAULT_RHO_INF,
    }
}

fn run(p: &mut Oscillators, y0: &[f64], t_end: f64, s: &Settings) -> Outcome {
    integrate(
        p,
        &Span {
            t0: 0.0,
            y0,
            t_end,
            settings: s,
        },
        &mut Quiet,
    )
}

/// The scheme's coefficients: second order (`gamma = 1/2 + a_m - a_f`),
/// and the roots of the two-step method at `h lambda -> infinity` (of
/// `sigma`) are `-rho`; at `rho = 1` it is the trapezoidal rule, whose
/// error constant is `-1/12`.
#[test]
fn the_coefficients_are_second_order_with_the_spectral_radius_rho() {
    for rho in [0.0, 0.3, 0.6, 0.9, 1.0] {
        let k = Coefficients::of(rho);
        assert!((k.gamma - (0.5 + k.a_m - k.a_f)).abs() < 1e-15);
        assert!((-(1.0 - k.gamma) / k.gamma + rho).abs() < 1e-12, "{rho}");
        assert!((-(1.0 - k.a_f) / k.a_f + rho).abs() < 1e-12, "{rho}");
    }
    assert!((Coefficients::of(1.0).c3 + 1.0 / 12.0).abs() < 1e-15);
}

/// On `x'' = -x` the error at `t = 10` falls at second order in the
/// steps (the log-log slope between rtol 1e-4 and 1e-8 is -2 to within
/// 0.3), and it tracks the tolerance as a second-order method with
/// local error control should (`err ~ rtol^(2/3)`, within a factor 10
/// over four decades): an estimate of the wrong order or constant, or
/// one that does not see the error, fails one of them.
#[test]
fn the_error_is_second_order_and_tracks_the_tolerance() {
    let mut p = Oscillators {
        modes: vec![(1.0, 0.0)],
        mu: None,
    };
    let exact = [10f64.cos(), -10f64.sin()];
    let mut pts = vec![];
    for rtol in [1e-4, 1e-5, 1e-6, 1e-7, 1e-8] {
        let out = run(&mut p, &[1.0, 0.0], 10.0, &settings(rtol));
        assert_eq!(out.status, Status::Ok);
        let e = (out.y_end[0] - exact[0]).hypot(out.y_end[1] - exact[1]);
        pts.push((rtol, out.stats.steps as f64, e));
    }
    let (first, last) = (pts[0], pts[pts.len() - 1]);
    let slope = (last.2 / first.2).ln() / (last.1 / first.1).ln();
    assert!((slope + 2.0).abs() < 0.3, "slope {slope}: {pts:?}");
    let c: Vec<f64> = pts.iter().map(|p| p.2 / p.0.powf(2.0 / 3.0)).collect();
    let (lo, hi) = c
        .iter()
        .fold((f64::MAX, 0.0f64), |a, &x| (a.0.min(x), a.1.max(x)));
    assert!(hi / lo < 10.0, "{c:?}");
}

/// A slow mode beside a stiff, lightly damped one (`w = 1e5`, 1%
/// damping, excited at the start): the stiff mode is damped instead of
/// followed (following it would take some 3e5 steps to `t = 10`): the
/// run takes less than a twentieth of that (6,224 steps when written,
/// against 779 for the slow mode alone: the stiff transient's position
/// is in the error norm until it is damped below the tolerance), the
/// slow one is accurate, and the stiff one is gone.
#[test]
fn a_stiff_mode_is_stepped_over_and_the_slow_one_kept() {
    let mut p = Oscillators {
        modes: vec![(1.0, 0.0), (1e5, 0.01)],
        mu: None,
    };
    let out = run(&mut p, &[1.0, 0.0, 1e-3, 0.0], 10.0, &settings(1e-6));
    assert_eq!(out.status, Status::Ok);
    // Following the mode: about `w t / pi` steps at least.
    let follow = 1e5 * 10.0 / std::f64::consts::PI;
    assert!((out.stats.steps as f64) < follow / 20.0, "{:?}", out.stats);
    let e = (out.y_end[0] - 10f64.cos()).hypot(out.y_end[1] + 10f64.sin());
    // 3.2e-4 when written: the transient's many step changes cost the
    // slow mode accuracy (alone it ends within 2e-5 at this rtol).
    assert!(e < 1e-3, "{e:e}");
    assert!(out.y_end[2].abs() < 1e-9, "{:?}", out.y_end);
}

/// A first step far too large for Newton on stiff van der Pol
/// (`mu = 1000`, started off its slow manifold at `x' = 1000`: from
/// `x' = 0` Newton with a Jacobian evaluated at the predictor converges
/// even at `h = 400`, and only the error test cuts it) is retried smaller, never accepted: the run counts its
/// Newton failures and still lands on the same state as a run with a
/// fine start, to the tolerance.
#[test]
fn a_step_whose_newton_fails_is_retried_smaller() {
    let mut p = Oscillators {
        modes: vec![(1.0, 0.0)],
        mu: Some(1000.0),
    };
    let y0 = [2.0, 1000.0];
    let fine = run(&mut p, &y0, 500.0, &settings(1e-8));
    let big = Settings {
        h0: Some(400.0),
        ..settings(1e-6)
    };
    let out = run(&mut p, &y0, 500.0, &big);
    assert_eq!((fine.status, out.status), (Status::Ok, Status::Ok));
    assert!(out.stats.newton_failures > 0, "{:?}", out.stats);
    assert_eq!(
        out.stats.rejected_steps,
        out.stats.newton_failures + out.stats.error_test_failures
    );
    assert!(
        (out.y_end[0] - fine.y_end[0]).abs() < 1e-3,
        "{:?} {:?}",
        out.y_end,
        fine.y_end
    );
}
