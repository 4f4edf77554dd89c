//! The continuous catenary `y = a cosh((x - x0)/a) + c` through two anchors.
//!
//! Units are those of the inputs (lengths); `y` points up, gravity down.

use crate::error::{check_inputs, CatenaryError, TAUT};
use crate::Point;
use argmin::core::{CostFunction, Executor, State, TerminationReason, TerminationStatus};
use argmin::solver::brent::BrentRoot;

/// Iteration cap of the Brent root finder.
const MAX_BRENT_ITERS: u64 = 200;

/// Continuous catenary `y = a cosh((x - x0)/a) + c` through `p0`, `p1` with
/// arc length `length` (all in length units).
#[derive(Debug, Clone, PartialEq)]
pub struct Catenary {
    /// Catenary parameter `a = H / (rho g) > 0` (length).
    pub a: f64,
    /// Abscissa of the vertex (may lie outside the span).
    pub x0: f64,
    /// Offset: `y = a cosh((x - x0)/a) + c`. Evaluate the curve with
    /// [`Catenary::y`], which works relative to `p0` and keeps full accuracy
    /// even for a nearly taut chain, where `a` and `c` are huge.
    pub c: f64,
    /// First anchor (the chain starts here; arc length is measured from it).
    pub p0: Point,
    /// Second anchor.
    pub p1: Point,
    /// Arc length between the anchors.
    pub length: f64,
    /// Brent iterations used to solve for `a`.
    pub iterations: u64,
}

impl Catenary {
    /// The catenary through `p0` and `p1` with arc length `length`.
    ///
    /// Needs finite inputs within the crate's bounds ([`crate::MAX_MAGNITUDE`],
    /// [`crate::MIN_LENGTH`]), `x1 != x0` and `length > |p1 - p0| (1 + 1e-12)`.
    /// Solves `2 a sinh(d/(2a)) = sqrt(L^2 - h^2)` (`d = |x1 - x0|`,
    /// `h = y1 - y0`) for `a` with argmin's `BrentRoot`, in the overflow-free
    /// form `ln(sinh(u)/u - 1) = ln(sqrt(L^2 - h^2)/d - 1)`, `u = d/(2a)`.
    pub fn through(p0: Point, p1: Point, length: f64) -> Result<Catenary, CatenaryError> {
        let distance = check_inputs(p0, p1, length)?;
        if length - distance <= TAUT * length {
            return Err(CatenaryError::TooShort { length, distance });
        }
        let dx = p1[0] - p0[0];
        let h = p1[1] - p0[1];
        let d = dx.abs();
        if d == 0.0 {
            return Err(CatenaryError::Vertical { length, distance });
        }
        let ell = chord_of_level_span(length, h);
        // q = ell/d - 1 = (L - D)(L + D) / ((ell + d) d), accurate for taut chains.
        let ln_q = (length - distance).ln() + (length + distance).ln() - (ell + d).ln() - d.ln();
        let (u, iterations) = solve_u(ln_q)?;
        let a = d / (2.0 * u);
        let x0 = 0.5 * (p0[0] + p1[0]) - dx.signum() * a * (h / ell).asinh();
        let mut cat = Catenary {
            a,
            x0,
            c: 0.0,
            p0,
            p1,
            length,
            iterations,
        };
        cat.c = p0[1] - a * cat.t0().cosh();
        Ok(cat)
    }

    /// Height of the curve at `x`.
    pub fn y(&self, x: f64) -> f64 {
        let half = (x - self.p0[0]) / (2.0 * self.a);
        self.p0[1] + 2.0 * self.a * (self.t0() + half).sinh() * half.sinh()
    }

    /// The vertex `(x0, a + c)` of the full curve (may lie outside the span).
    pub fn vertex(&self) -> Point {
        let s = (0.5 * self.t0()).sinh();
        [self.x0, self.p0[1] - 2.0 * self.a * s * s]
    }

    /// Lowest point of the hanging segment between the anchors: the vertex if
    /// it lies in the span, else the lower anchor.
    pub fn lowest_point(&self) -> Point {
        let (lo, hi) = if self.p0[0] <= self.p1[0] {
            (self.p0[0], self.p1[0])
        } else {
            (self.p1[0], self.p0[0])
        };
        if (lo..=hi).contains(&self.x0) {
            self.vertex()
        } else if self.p0[1] <= self.p1[1] {
            self.p0
        } else {
            self.p1
        }
    }

    /// Signed arc length along the curve from abscissa `xa` to `xb`
    /// (positive for `xb > xa`).
    pub fn arc_length(&self, xa: f64, xb: f64) -> f64 {
        let mid = ((xa - self.p0[0]) + (xb - self.p0[0])) / (2.0 * self.a) + self.t0();
        2.0 * self.a * mid.cosh() * ((xb - xa) / (2.0 * self.a)).sinh()
    }

    /// The point at arc length `s` from `p0` towards `p1` (`0 <= s <= length`;
    /// other `s` continue the curve beyond the anchors).
    pub fn point_at_arc_length(&self, s: f64) -> Point {
        let b = self.slope_at_p0();
        let delta = self.direction() * s / self.a;
        // (x - x0_anchor)/a = asinh(b + delta) - asinh(b), without cancellation.
        let t = asinh_difference(b, delta);
        let half = 0.5 * t;
        [
            self.p0[0] + self.a * t,
            self.p0[1] + 2.0 * self.a * (self.t0() + half).sinh() * half.sinh(),
        ]
    }

    /// `dy/dx` at `p0`. Along the chain (in the frame where it runs towards
    /// `+x`), `tan(phi(s)) = slope_at_p0 + s / a`.
    pub(crate) fn slope_at_p0(&self) -> f64 {
        self.t0().sinh()
    }

    /// `+1` if the chain runs towards `+x`, `-1` otherwise.
    fn direction(&self) -> f64 {
        (self.p1[0] - self.p0[0]).signum()
    }

    /// `(x_p0 - x0)/a`, computed from the anchors (accurate even when `a` is huge).
    fn t0(&self) -> f64 {
        let dx = self.p1[0] - self.p0[0];
        let h = self.p1[1] - self.p0[1];
        let ell = chord_of_level_span(self.length, h);
        -dx / (2.0 * self.a) + dx.signum() * (h / ell).asinh()
    }
}

/// `sqrt(L^2 - h^2)`: the chord a chain of length `L` would span if level.
fn chord_of_level_span(length: f64, h: f64) -> f64 {
    (length - h.abs()).sqrt() * (length + h.abs()).sqrt()
}

/// `asinh(b + delta) - asinh(b)` without cancellation.
fn asinh_difference(b: f64, delta: f64) -> f64 {
    let a = b + delta;
    if a * b <= 0.0 {
        a.asinh() - b.asinh()
    } else {
        let den = a * (1.0 + b * b).sqrt() + b * (1.0 + a * a).sqrt();
        (delta * (a + b) / den).asinh()
    }
}

/// `ln(sinh(u)/u - 1)` for `u > 0`, accurate for small `u` and free of overflow.
fn ln_excess(u: f64) -> f64 {
    if u < 1.0 {
        // sinh(u)/u - 1 = sum_{k>=1} u^(2k) / (2k+1)!
        let u2 = u * u;
        let mut term = u2 / 6.0;
        let mut sum = term;
        let mut k = 1.0;
        // The terms fall by u^2 / 20 or faster: under 30 of them reach
        // 1e-18 of the sum; the cap only stops a NaN-free loop early.
        while term > 1e-18 * sum && k < 60.0 {
            term *= u2 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
            sum += term;
            k += 1.0;
        }
        sum.ln()
    } else if u < 20.0 {
        (u.sinh() / u - 1.0).ln()
    } else {
        // sinh(u)/u - 1 = e^u/(2u) (1 - e^(-2u) - 2u e^(-u))
        u - (2.0 * u).ln() + (-(-2.0 * u).exp() - 2.0 * u * (-u).exp()).ln_1p()
    }
}

/// `ln(sinh(u)/u - 1) - ln q`, increasing in `u`.
struct ExcessEquation {
    ln_q: f64,
}

impl CostFunction for ExcessEquation {
    type Param = f64;
    type Output = f64;

    fn cost(&self, u: &f64) -> Result<f64, argmin::core::Error> {
        Ok(ln_excess(*u) - self.ln_q)
    }
}

/// Root `u > 0` of `sinh(u)/u - 1 = q`, given `ln q`; returns `(u, iterations)`.
fn solve_u(ln_q: f64) -> Result<(f64, u64), CatenaryError> {
    let eq = ExcessEquation { ln_q };
    let f = |u: f64| ln_excess(u) - ln_q;
    let fail = |iterations, residual| CatenaryError::NoConvergence {
        solver: "catenary parameter",
        iterations,
        residual,
    };
    // Upper bounds: sinh(u)/u - 1 >= u^2/6, and >= e^(u/2)/4 - 1 for u >= 0.35.
    let ln_1p_q = if ln_q > 0.0 {
        ln_q + (-ln_q).exp().ln_1p()
    } else {
        ln_q.exp().ln_1p()
    };
    let mut hi = (0.5 * (6f64.ln() + ln_q))
        .exp()
        .min(2.0 * (4f64.ln() + ln_1p_q));
    let mut lo = 0.5 * hi;
    for _ in 0..2100 {
        if f(hi) >= 0.0 {
            break;
        }
        (lo, hi) = (hi, 2.0 * hi);
    }
    for _ in 0..2100 {
        if f(lo) <= 0.0 {
            break;
        }
        (lo, hi) = (0.5 * lo, lo);
    }
    let (flo, fhi) = (f(lo), f(hi));
    if !(flo <= 0.0 && fhi >= 0.0) {
        return Err(fail(0, flo.abs().min(fhi.abs())));
    }
    if flo == 0.0 {
        return Ok((lo, 0));
    }
    let result = Executor::new(eq, BrentRoot::new(lo, hi, 0.0))
        .configure(|s| s.max_iters(MAX_BRENT_ITERS))
        .run()
        .map_err(|_| fail(0, f64::NAN))?;
    let state = result.state();
    let iterations = state.get_iter();
    let u = state.get_best_param().copied().unwrap_or(f64::NAN);
    let converged = matches!(
        state.get_termination_status(),
        TerminationStatus::Terminated(TerminationReason::SolverConverged)
    );
    if !(converged && u > 0.0 && u.is_finite()) {
        return Err(fail(iterations, state.get_best_cost()));
    }
    Ok((u, iterations))
}
