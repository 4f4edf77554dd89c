//! Positions, velocities and energies of a chain state, each in O(n).
//!
//! Angles `phi_i` are measured from the horizontal, counter-clockwise; joint
//! `r_k = P0 + l sum_{j<=k} (cos phi_j, sin phi_j)`; the tip is `r_n`.

use crate::chain::Chain;
use crate::scalar::sin_cos;

/// A point or vector in the plane, `[x, y]`.
pub type Vec2 = [f64; 2];

/// Joint positions `r_0 = p0, r_1, .., r_n`.
pub fn joints(chain: &Chain, p0: Vec2, phi: &[f64]) -> Vec<Vec2> {
    let l = chain.rod_length();
    let mut r = p0;
    let mut out = Vec::with_capacity(phi.len() + 1);
    out.push(r);
    for &p in phi {
        let (s, c) = sin_cos(p);
        r = [r[0] + l * c, r[1] + l * s];
        out.push(r);
    }
    out
}

/// The free tip `r_n`.
pub fn tip(chain: &Chain, p0: Vec2, phi: &[f64]) -> Vec2 {
    let l = chain.rod_length();
    phi.iter().fold(p0, |r, &p| {
        let (s, c) = sin_cos(p);
        [r[0] + l * c, r[1] + l * s]
    })
}

/// The exact tip velocity `l sum_j w_j (-sin phi_j, cos phi_j)`.
pub fn tip_velocity(chain: &Chain, phi: &[f64], w: &[f64]) -> Vec2 {
    let l = chain.rod_length();
    let (mut vx, mut vy) = (0.0, 0.0);
    for (&p, &wj) in phi.iter().zip(w) {
        let (s, c) = sin_cos(p);
        vx -= wj * s;
        vy += wj * c;
    }
    [l * vx, l * vy]
}

/// Kinetic energy: `sum_k (m/2)|v_ck|^2 + (J/2) w_k^2`, `J = m l^2 / 12`
/// (equal to `(m l^2 / 2) w^T A w`).
pub fn kinetic_energy(chain: &Chain, phi: &[f64], w: &[f64]) -> f64 {
    let (mut jx, mut jy) = (0.0, 0.0); // velocity of the rod's lower joint, rod units
    let mut twice = 0.0;
    for (&p, &wk) in phi.iter().zip(w) {
        let (s, c) = sin_cos(p);
        let (nx, ny) = (-s * wk, c * wk);
        let (cx, cy) = (jx + 0.5 * nx, jy + 0.5 * ny);
        twice += cx * cx + cy * cy + wk * wk / 12.0;
        jx += nx;
        jy += ny;
    }
    0.5 * chain.mass() * chain.rod_length().powi(2) * twice
}

/// Potential energy `m g l sum_i q_i sin phi_i`, zero at the height of `P0`.
pub fn potential_energy(chain: &Chain, phi: &[f64]) -> f64 {
    let n = phi.len();
    let sum: f64 = phi
        .iter()
        .enumerate()
        .map(|(i, p)| ((n - i - 1) as f64 + 0.5) * p.sin())
        .sum();
    chain.mass() * chain.gravity() * chain.rod_length() * sum
}

/// Total mechanical energy `T + V`.
pub fn energy(chain: &Chain, phi: &[f64], w: &[f64]) -> f64 {
    kinetic_energy(chain, phi, w) + potential_energy(chain, phi)
}

/// Dissipation rate `2R = r sum_{i>=2} (w_i - w_{i-1})^2 = -dE/dt` (power, >= 0).
pub fn dissipation_rate(chain: &Chain, w: &[f64]) -> f64 {
    chain.damping() * w.windows(2).map(|p| (p[1] - p[0]).powi(2)).sum::<f64>()
}
