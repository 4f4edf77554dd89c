//! The number type the dynamics is written over: `f64` for the right-hand side,
//! [`Dual`] for its exact directional derivative (forward-mode differentiation),
//! which gives the Jacobian-vector products the implicit solver needs.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// A real scalar as the O(n) recursion needs it.
pub trait Scalar:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + Mul<f64, Output = Self>
{
    /// A constant (zero derivative).
    fn cst(x: f64) -> Self;
    /// `(sin x, cos x)`.
    fn sin_cos(self) -> (Self, Self);
}

impl Scalar for f64 {
    #[inline(always)]
    fn cst(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        f64::sin_cos(self)
    }
}

/// A first-order dual number `v + d ε`, `ε² = 0`: evaluating a function at
/// `y + ε v` gives `f(y) + ε J(y) v`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dual {
    /// The value.
    pub v: f64,
    /// The directional derivative.
    pub d: f64,
}

impl Dual {
    /// `v + d ε`.
    pub const fn new(v: f64, d: f64) -> Self {
        Self { v, d }
    }
}

impl Add for Dual {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Self::new(self.v + o.v, self.d + o.d)
    }
}
impl Sub for Dual {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Self::new(self.v - o.v, self.d - o.d)
    }
}
impl Mul for Dual {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Self::new(self.v * o.v, self.d * o.v + self.v * o.d)
    }
}
impl Div for Dual {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let q = self.v / o.v;
        Self::new(q, (self.d - q * o.d) / o.v)
    }
}
impl Neg for Dual {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Self::new(-self.v, -self.d)
    }
}
impl AddAssign for Dual {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl SubAssign for Dual {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl Mul<f64> for Dual {
    type Output = Self;
    #[inline(always)]
    fn mul(self, k: f64) -> Self {
        Self::new(self.v * k, self.d * k)
    }
}

impl Scalar for Dual {
    #[inline(always)]
    fn cst(x: f64) -> Self {
        Self::new(x, 0.0)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let (s, c) = self.v.sin_cos();
        (Self::new(s, c * self.d), Self::new(c, -s * self.d))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dual_derivatives_match_calculus() {
        let x = Dual::new(0.7, 1.0);
        let f = x * x.sin_cos().0 / (x + Dual::cst(2.0));
        let (s, c) = 0.7f64.sin_cos();
        let g = 0.7 + 2.0;
        let df = ((s + 0.7 * c) * g - 0.7 * s) / (g * g);
        assert!((f.v - 0.7 * s / g).abs() < 1e-15);
        assert!((f.d - df).abs() < 1e-14);
    }
}
