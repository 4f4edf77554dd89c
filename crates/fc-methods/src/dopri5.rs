//! Dormand–Prince 5(4) (Hairer & Wanner's DOPRI5): FSAL, the error norm over
//! `rtol`/`atol`, a PI step-size controller, Hairer's initial step, the
//! fourth-order dense output, and Hairer's stiffness detection.

use super::explicit::{self, lambda_estimate, Control, Pair, Parts, Step};
use super::integrator::Integrator;
use super::step_size::rms_norm;
use crate::ode::{all_finite, Interpolant, Observer, OdeSystem};

const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
// Error estimate: fifth minus fourth order weights.
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
// Dense output (Shampine's fourth-order continuous extension).
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// PI controller: exponents and limits (Hairer's defaults), and the
/// stiffness test `h |lambda| > 3.25`.
const BETA: f64 = 0.04;
const CONTROL: Control = Control {
    safety: 0.9,
    beta: BETA,
    expo1: 0.2 - BETA * 0.75,
    fac_min: 0.2,  // h_new >= 0.2 h
    fac_max: 10.0, // h_new <= 10 h
    stiff_hlambda: 3.25,
};

/// The continuous extension of one step: `y(t0 + theta h)`.
struct Dense<'a> {
    t0: f64,
    h: f64,
    /// `[y0 | y1 - y0 | h k1 - (y1 - y0) | (y1 - y0) - h k7 - r3 | h sum d_i k_i]`.
    r: &'a [f64],
}

impl Interpolant for Dense<'_> {
    fn eval(&self, t: f64, out: &mut [f64]) {
        let d = out.len();
        let th = (t - self.t0) / self.h;
        let th1 = 1.0 - th;
        let r = self.r;
        for i in 0..d {
            out[i] = r[i]
                + th * (r[d + i] + th1 * (r[2 * d + i] + th * (r[3 * d + i] + th1 * r[4 * d + i])));
        }
    }
}

/// One attempt of a step of `h` from `(t, y)` to `t1` (`t + h`, or `t_end`
/// exactly on the last step), with `k[0] = f(t, y)`: the stages `k[1..7]`
/// (`k[6] = f(t1, y1)`, FSAL), the fifth-order `y1`, the
/// sixth stage's state in `ys` (for the stiffness test), and the error
/// estimate `err = y1 - y1_hat` against the embedded fourth-order solution.
/// The step loop's own arithmetic; the tests call it to see `err`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn attempt<S: OdeSystem>(
    sys: &mut S,
    t: f64,
    t1: f64,
    h: f64,
    y: &[f64],
    k: &mut [Vec<f64>],
    ys: &mut [f64],
    y1: &mut [f64],
    err: &mut [f64],
) {
    let d = y.len();
    let stage = |ys: &mut [f64], y: &[f64], terms: &[(f64, &[f64])]| {
        for i in 0..ys.len() {
            let mut s = 0.0;
            for (a, ki) in terms {
                s += a * ki[i];
            }
            ys[i] = y[i] + h * s;
        }
    };
    let (k1, rest) = k.split_at_mut(1);
    let k1 = &k1[0];
    let (k2, rest) = rest.split_at_mut(1);
    let (k3, rest) = rest.split_at_mut(1);
    let (k4, rest) = rest.split_at_mut(1);
    let (k5, rest) = rest.split_at_mut(1);
    let (k6, k7) = rest.split_at_mut(1);
    let (k2, k3, k4, k5, k6, k7) = (
        &mut k2[0], &mut k3[0], &mut k4[0], &mut k5[0], &mut k6[0], &mut k7[0],
    );
    stage(ys, y, &[(A21, k1)]);
    sys.rhs(t + C2 * h, ys, k2);
    stage(ys, y, &[(A31, k1), (A32, k2)]);
    sys.rhs(t + C3 * h, ys, k3);
    stage(ys, y, &[(A41, k1), (A42, k2), (A43, k3)]);
    sys.rhs(t + C4 * h, ys, k4);
    stage(ys, y, &[(A51, k1), (A52, k2), (A53, k3), (A54, k4)]);
    sys.rhs(t + C5 * h, ys, k5);
    stage(
        ys,
        y,
        &[(A61, k1), (A62, k2), (A63, k3), (A64, k4), (A65, k5)],
    );
    sys.rhs(t1, ys, k6);
    stage(
        y1,
        y,
        &[(A71, k1), (A73, k3), (A74, k4), (A75, k5), (A76, k6)],
    );
    sys.rhs(t1, y1, k7);
    for i in 0..d {
        err[i] = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
    }
}

/// DOPRI5's storage: the stages `k1..k7` (`k`) and the shared buffers (`ys`: the
/// sixth stage's state; `aux`: the error estimate; five rows of dense
/// output).
pub(crate) type Stages = explicit::Stages<Vec<Vec<f64>>>;

/// `dopri5`: Dormand–Prince 5(4), adaptive.
pub(crate) const DOPRI5: Integrator = explicit::integrator::<Stages>("dopri5");

impl Pair for Stages {
    const ORDER: u32 = 5;
    const CONTROL: Control = CONTROL;

    fn new(d: usize) -> Self {
        Self::with(vec![vec![0.0; d]; 7], d, 5)
    }

    fn parts(&mut self) -> Parts<'_> {
        (&mut self.k[0], (&mut self.ys, &mut self.aux))
    }

    fn attempt<S: OdeSystem>(&mut self, sys: &mut S, s: &mut Step<'_>) -> Option<f64> {
        let Step { t, t1, h, y, .. } = *s;
        let (ys, err) = (&mut self.ys, &mut self.aux);
        attempt(sys, t, t1, h, y, &mut self.k, ys, s.y1, err);
        let e = rms_norm(err, y, s.y1, s.o);
        (e.is_finite() && all_finite(s.y1) && all_finite(&self.k[6])).then_some(e)
    }

    fn lambda(&self, y1: &[f64]) -> f64 {
        // h |lambda| ~ h |k7 - k6| / |y1 - y_stage6|.
        lambda_estimate(&self.k[5], &self.k[6], y1, &self.ys)
    }

    fn show<S: OdeSystem>(&mut self, _sys: &mut S, s: &Step<'_>, obs: &mut dyn Observer) {
        let Step { t, h, y, .. } = *s;
        let y1: &[f64] = s.y1;
        let (k, rcont) = (&self.k, &mut self.rcont);
        let d = y.len();
        // Dense output coefficients.
        for i in 0..d {
            let dy = y1[i] - y[i];
            let bspl = h * k[0][i] - dy;
            rcont[i] = y[i];
            rcont[d + i] = dy;
            rcont[2 * d + i] = bspl;
            rcont[3 * d + i] = dy - h * k[6][i] - bspl;
            rcont[4 * d + i] = h
                * (D1 * k[0][i]
                    + D3 * k[2][i]
                    + D4 * k[3][i]
                    + D5 * k[4][i]
                    + D6 * k[5][i]
                    + D7 * k[6][i]);
        }
        obs.step(&s.view(&k[6], &Dense { t0: t, h, r: rcont }));
        self.k.swap(0, 6); // FSAL: k7 of this step is k1 of the next.
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The embedded fourth-order weights as Dormand and Prince published
    /// them (1980; Hairer, Nørsett & Wanner, Table II.5.2): an independent
    /// source for `E = b - b_hat`. The order conditions alone cannot pin
    /// `E`: any multiple of it is the difference to another valid
    /// fourth-order embedding.
    const B_HAT: [f64; 7] = [
        5179.0 / 57600.0,
        0.0,
        7571.0 / 16695.0,
        393.0 / 640.0,
        -92097.0 / 339200.0,
        187.0 / 2100.0,
        1.0 / 40.0,
    ];

    #[test]
    fn the_tableau_meets_its_order_conditions_and_the_published_embedding() {
        let c = [0.0, C2, C3, C4, C5, 1.0, 1.0];
        let a: [&[f64]; 7] = [
            &[],
            &[A21],
            &[A31, A32],
            &[A41, A42, A43],
            &[A51, A52, A53, A54],
            &[A61, A62, A63, A64, A65],
            &[A71, 0.0, A73, A74, A75, A76],
        ];
        // Each row sums to its node (a wrong c_i fails here too).
        for (i, row) in a.iter().enumerate() {
            let sum: f64 = row.iter().sum();
            assert!(
                (sum - c[i]).abs() < 1e-15,
                "row {}: {sum} vs {}",
                i + 1,
                c[i]
            );
        }
        let b = [A71, 0.0, A73, A74, A75, A76, 0.0];
        // sum_i w_i g_i for stage values g.
        let dot = |w: &[f64], g: &[f64]| -> f64 { w.iter().zip(g).map(|(x, y)| x * y).sum() };
        // (A g)_i: the stage combination of g.
        let apply = |g: &[f64]| -> Vec<f64> { a.iter().map(|row| dot(row, g)).collect() };
        let cq = |q: i32| -> Vec<f64> { c.iter().map(|x| x.powi(q)).collect() };
        let times =
            |u: &[f64], v: &[f64]| -> Vec<f64> { u.iter().zip(v).map(|(x, y)| x * y).collect() };
        // Order conditions up to four for both weight sets, and the
        // quadrature one of order five for b only.
        let b_hat: Vec<f64> = b
            .iter()
            .zip(&[E1, 0.0, E3, E4, E5, E6, E7])
            .map(|(b, e)| b - e)
            .collect();
        for (name, w) in [("b", &b[..]), ("b_hat", &b_hat[..])] {
            let conditions = [
                (dot(w, &cq(0)), 1.0),
                (dot(w, &cq(1)), 1.0 / 2.0),
                (dot(w, &cq(2)), 1.0 / 3.0),
                (dot(w, &apply(&cq(1))), 1.0 / 6.0),
                (dot(w, &cq(3)), 1.0 / 4.0),
                (dot(w, &times(&cq(1), &apply(&cq(1)))), 1.0 / 8.0),
                (dot(w, &apply(&cq(2))), 1.0 / 12.0),
                (dot(w, &apply(&apply(&cq(1)))), 1.0 / 24.0),
            ];
            for (k, (got, want)) in conditions.into_iter().enumerate() {
                assert!(
                    (got - want).abs() < 1e-14,
                    "{name}, condition {k}: {got} vs {want}"
                );
            }
        }
        assert!((dot(&b, &cq(4)) - 0.2).abs() < 1e-14);
        assert!(
            (dot(&b_hat, &cq(4)) - 0.2).abs() > 1e-4,
            "b_hat is only fourth order"
        );
        for (i, (got, want)) in b_hat.iter().zip(B_HAT).enumerate() {
            assert!(
                (got - want).abs() < 1e-15,
                "b_hat_{}: {got} vs {want}",
                i + 1
            );
        }
    }

    /// `y' = lambda y` for a complex `lambda = a + i b`, as a real 2-vector.
    struct Linear {
        a: f64,
        b: f64,
    }

    impl crate::ode::OdeSystem for Linear {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = self.a * y[0] - self.b * y[1];
            dy[1] = self.b * y[0] + self.a * y[1];
        }
        fn jvp(&mut self, t: f64, _y: &[f64], v: &[f64], jv: &mut [f64]) {
            self.rhs(t, v, jv);
        }
    }

    /// `|R(h lambda)|`: the growth of one step of `h` on `y' = lambda y`.
    fn growth(lambda: (f64, f64), h: f64) -> f64 {
        let mut sys = Linear {
            a: lambda.0,
            b: lambda.1,
        };
        let y = [1.0, 0.0];
        let mut k = vec![vec![0.0; 2]; 7];
        crate::ode::OdeSystem::rhs(&mut sys, 0.0, &y, &mut k[0]);
        let (mut ys, mut y1, mut err) = ([0.0; 2], [0.0; 2], [0.0; 2]);
        attempt(&mut sys, 0.0, h, h, &y, &mut k, &mut ys, &mut y1, &mut err);
        y1[0].hypot(y1[1])
    }

    /// Where DOPRI5 is stable, from its own steps. Its stability function
    /// is `R(z) = 1 + z + ... + z^5/120 + z^6/600`: stable on the negative
    /// real axis to `z = -3.307`, on the imaginary axis only to
    /// `|z| = 0.997`. So an undamped oscillation of frequency `omega` holds
    /// the step below about `1/omega`, not `3.3/omega`; a lightly damped
    /// mode such as the chain's `lambda = -24 + 1117 i` (n = 800,
    /// `docs/model.md`) holds it to `h |lambda| = 2.10`. A wrong tableau
    /// moves these limits.
    #[test]
    fn the_stability_limits_on_the_real_and_imaginary_axes() {
        assert!(growth((-1.0, 0.0), 3.30) <= 1.0);
        assert!(growth((-1.0, 0.0), 3.31) > 1.0);
        assert!(growth((0.0, 1.0), 0.99) <= 1.0);
        assert!(growth((0.0, 1.0), 1.0) > 1.0);
        let lambda = (-24.0, 1117.0);
        let size = f64::hypot(lambda.0, lambda.1);
        assert!(growth(lambda, 2.09 / size) <= 1.0);
        assert!(growth(lambda, 2.12 / size) > 1.0);
    }
}
