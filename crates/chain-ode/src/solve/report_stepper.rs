//! The report's own stepper (erratum 4), which its code calls RK4, and
//! the methods the report's model runs ([`crate::model::ReportChain`]).
//!
//! The stepper advances `y = [phi, w, W]` by `h` as the report's code does
//! (its notebook's step loop):
//!
//! ```text
//! phi1 = phi + h w                               (explicit Euler)
//! k1 = a(phi, w)           k2 = a(phi, w + h/2 k1)
//! k3 = a(phi1, w + h/2 k2) k4 = a(phi1, w + h k3)
//! w1 = w + h/6 (k1 + 2 k2 + 2 k3 + k4)
//! ```
//!
//! RK4's weights on the rates, with the angles frozen at `phi` for the
//! first two stages and at the Euler update `phi1` for the last two (`W`
//! takes the same stages as `w`): a first-order method, measured so by a
//! test. It is a [`FixedStep`] of the one fixed-step loop
//! ([`rk4::integrate`], which owns the step times, the budget, the checks
//! and the observer), registered for this model as [`REPORT_RK4`]; the
//! model chooses it ([`crate::model::Model::integrator`]).

use fc_methods::rk4::{self, FixedStep, Work};
use fc_methods::{Integrator, Method, OdeSystem};

/// The methods the report's model runs: the explicit ones (its code had
/// no implicit method, and `auto` would hand over to one).
pub const REPORT_METHODS: [Method; 3] = [Method::Rk4, Method::Dopri5, Method::Dop853];

/// The report's stepper, on a system whose state is `[q (n), v (n),
/// rest]` with `q' = v`, run by the one fixed-step loop
/// ([`rk4::integrate`]).
pub(crate) struct ReportStepper;

impl FixedStep for ReportStepper {
    fn step<S: OdeSystem>(
        sys: &mut S,
        t: f64,
        t1: f64,
        y: &[f64],
        f: &[f64],
        y1: &mut [f64],
        w: &mut Work,
    ) {
        let d = y.len();
        let n = (d - 1) / 2;
        let h = t1 - t;
        // The angles by explicit Euler first: the last two stages use them.
        for i in 0..n {
            y1[i] = y[i] + h * y[n + i];
        }
        // Stages in the rates (and W) only, at the angles `at`.
        let stage = |out: &mut [f64], at: &[f64], a: f64, k: &[f64]| {
            out[..n].copy_from_slice(&at[..n]);
            for i in n..d {
                out[i] = y[i] + a * k[i];
            }
        };
        stage(&mut w.tmp, y, 0.5 * h, f);
        sys.rhs(t, &w.tmp, &mut w.k2);
        stage(&mut w.tmp, y1, 0.5 * h, &w.k2);
        sys.rhs(t1, &w.tmp, &mut w.k3);
        stage(&mut w.tmp, y1, h, &w.k3);
        sys.rhs(t1, &w.tmp, &mut w.k4);
        for i in n..d {
            y1[i] = y[i] + h / 6.0 * (f[i] + 2.0 * (w.k2[i] + w.k3[i]) + w.k4[i]);
        }
    }
}

/// `rk4` in the report's model with [`ReportModel::stepper`] set: the
/// report's stepper, which its code calls RK4; `dt` sets its accuracy.
pub const REPORT_RK4: Integrator = Integrator {
    name: "rk4",
    adaptive: false,
    nonsmooth: false,
    run: |p, s, obs| rk4::integrate::<ReportStepper, _>(p, s, obs).into(),
};

#[cfg(test)]
mod tests {
    use super::*;
    use fc_methods::testing::Quiet;
    use fc_methods::Status;
    use fc_methods::{Settings, Span, TimeScales};

    /// `q'' = -q` as `[q, v, W]` with `W' = 0`: the layout the stepper reads.
    struct Spring;

    impl OdeSystem for Spring {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = -y[0];
            dy[2] = 0.0;
        }
        fn jvp(&mut self, _t: f64, _y: &[f64], v: &[f64], jv: &mut [f64]) {
            jv[0] = v[1];
            jv[1] = -v[0];
            jv[2] = 0.0;
        }
    }

    #[test]
    fn one_step_is_the_reports_by_hand() {
        // From (q, v) = (1, 1) by h: q1 = q + h v = 1 + h; the rates' stages
        // are -q, -q, -q1, -q1, so v1 = v - h/6 (q + 2 q + 2 q1 + q1)
        // = 1 - h - h^2/2 (at frozen old angles it would be 1 - h).
        let h = 0.1;
        let settings = Settings {
            dt: h,
            rtol: 1e-6,
            atol: 1e-8,
            h_min: 0.0,
            max_steps: 10,
            h0: None,
            scales: TimeScales::NONE,
            rho_inf: fc_methods::DEFAULT_RHO_INF,
        };
        let span = Span {
            t0: 0.0,
            y0: &[1.0, 1.0, 0.0],
            t_end: h,
            settings: &settings,
        };
        let out = rk4::integrate::<ReportStepper, _>(&mut Spring, &span, &mut Quiet);
        assert_eq!(out.status, Status::Ok);
        assert_eq!(out.stats.steps, 1);
        assert!((out.y_end[0] - 1.1).abs() < 1e-15, "{:?}", out.y_end);
        assert!(
            (out.y_end[1] - (1.0 - h - 0.5 * h * h)).abs() < 1e-15,
            "{:?}",
            out.y_end
        );
    }
}
