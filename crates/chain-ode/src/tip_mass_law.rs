//! The folded chain with a point mass `M` at its free end, in the
//! energy-conserving continuum limit (`docs/model.md`, "A tip mass"): the
//! closed form the simulations are checked against, and the figure
//! `tip-mass-fall` draws.
//!
//! With chain mass `m_c`, `lambda = m_c / L`, `k = M / m_c` and `x` the
//! distance the free end has fallen,
//! `v^2 = g x [lambda (2L - x)/2 + 2M] / [M + lambda (L - x)/2]`.

/// `v(x)` (length / time) of the law, for `0 <= x <= L`; `k = M / m_c > 0`.
pub fn speed(x: f64, length: f64, gravity: f64, k: f64) -> f64 {
    let xi = x / length;
    let f = ((2.0 - xi) / 2.0 + 2.0 * k) / (k + (1.0 - xi) / 2.0);
    (gravity * x * f).max(0.0).sqrt()
}

/// The speed at full extension, `sqrt(2 g L (1 + 1 / (4 k)))`.
pub fn final_speed(length: f64, gravity: f64, k: f64) -> f64 {
    (2.0 * gravity * length * (1.0 + 1.0 / (4.0 * k))).sqrt()
}

/// Simpson panels of [`time`]: the integrand is smooth (no singularity
/// for `k > 0`), and 20000 panels put the quadrature error far below 1e-12.
const PANELS: usize = 20_000;

/// The time to fall `xi L` in units of `sqrt(L / g)`, for `0 <= xi <= 1`
/// and `k > 0`: with `x = L u^2`, `dt = 2 sqrt(L/g) du / sqrt(F)`,
/// `F = [(2 - xi)/2 + 2k] / [k + (1 - xi)/2]`, integrated by Simpson's rule.
pub fn time(xi: f64, k: f64) -> f64 {
    let f = |u: f64| {
        let x = u * u;
        let big_f = ((2.0 - x) / 2.0 + 2.0 * k) / (k + (1.0 - x) / 2.0);
        2.0 / big_f.sqrt()
    };
    let (a, b) = (0.0, xi.clamp(0.0, 1.0).sqrt());
    let h = (b - a) / PANELS as f64;
    let inner: f64 = (1..PANELS)
        .map(|j| f(a + j as f64 * h) * if j % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    h / 3.0 * (f(a) + inner + f(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_law_has_its_limits() {
        // A heavy tip is free fall: v^2 = 2 g x, t = sqrt(2 xi).
        let (l, g) = (6.0, 1.0);
        assert!((speed(3.0, l, g, 1e12) - (2.0 * g * 3.0f64).sqrt()).abs() < 1e-9);
        assert!((time(1.0, 1e12) - 2f64.sqrt()).abs() < 1e-9);
        // The end of the fall is the final speed.
        for k in [0.1, 1.0, 10.0] {
            assert!((speed(l, l, g, k) - final_speed(l, g, k)).abs() < 1e-12);
        }
    }
}
