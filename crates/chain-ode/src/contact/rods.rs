//! The rods in maximal coordinates: each rod `i` a body with its centre
//! `c_i = (x_i, y_i)` (relative to the start's anchor `P0`) and its angle
//! `theta_i`, velocities `(vx_i, vy_i, w_i)`, the diagonal mass
//! `(m_i, m_i, J_i = m_i h_i² / 3)` (`h_i` the half length), its two ends
//! `c_i ∓ h_i u_i` and their Jacobians, and the forces on the rods as
//! loads each summed into the generalised force (gravity, the joints'
//! friction, bending): `docs/model.md`, "The floor as a constraint".

use crate::chain::Chain;
use crate::elastic::{rod_half_length, rod_mass};
use crate::kinematics::Vec2;
use crate::scalar::sin_cos;

/// Coordinates per rod: `x, y, theta`.
pub const BODY: usize = 3;

/// The rods' masses, half lengths and the coefficients of their loads.
#[derive(Clone, Debug, PartialEq)]
pub struct Rods {
    /// `m_i`.
    pub mass: Vec<f64>,
    /// `h_i = l_i / 2`.
    pub half: Vec<f64>,
    /// `g` (along −y).
    pub gravity: f64,
    /// The joints' friction `r` (torque per rate), between neighbours.
    pub friction: f64,
    /// Each joint's bending spring `EI / ((l_{k−1} + l_k) / 2)`, joint
    /// `k >= 1` (index 0 unused: the pivot is free).
    pub bending: Vec<f64>,
}

/// Which end of a rod a point is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum End {
    /// `c − h u`, towards the pivot.
    Start,
    /// `c + h u`, towards the tip.
    End,
}

impl Rods {
    /// The rods of `chain` (equal or profiled).
    pub fn of(chain: &Chain) -> Self {
        let n = chain.links();
        let half: Vec<f64> = (0..n).map(|i| rod_half_length(chain, i)).collect();
        let ei = chain.bending_stiffness();
        Self {
            mass: (0..n).map(|i| rod_mass(chain, i)).collect(),
            bending: (0..n)
                .map(|k| match k {
                    0 => 0.0,
                    _ => ei / (half[k - 1] + half[k]),
                })
                .collect(),
            half,
            gravity: chain.gravity(),
            friction: chain.damping(),
        }
    }

    /// Rods `n`.
    pub fn len(&self) -> usize {
        self.mass.len()
    }

    /// True without rods (never: a chain has one at least).
    pub fn is_empty(&self) -> bool {
        self.mass.is_empty()
    }

    /// `M⁻¹`, per coordinate.
    pub fn inverse_mass(&self, out: &mut [f64]) {
        for (i, (m, h)) in self.mass.iter().zip(&self.half).enumerate() {
            out[BODY * i] = 1.0 / m;
            out[BODY * i + 1] = 1.0 / m;
            out[BODY * i + 2] = 3.0 / (m * h * h);
        }
    }

    /// The point `end` of rod `i` in the coordinates `q`, and its Jacobian
    /// `dp/d(x_i, y_i, theta_i)` (two rows).
    pub fn point(&self, q: &[f64], i: usize, end: End) -> (Vec2, [[f64; BODY]; 2]) {
        let h = match end {
            End::Start => -self.half[i],
            End::End => self.half[i],
        };
        let (s, c) = sin_cos(q[BODY * i + 2]);
        let p = [q[BODY * i] + h * c, q[BODY * i + 1] + h * s];
        (p, [[1.0, 0.0, -h * s], [0.0, 1.0, h * c]])
    }

    /// The generalised force of every load on the rods at `(q, v)`, summed
    /// into `f` (zeroed first): [`Rods::gravity_load`],
    /// [`Rods::friction_load`], [`Rods::bending_load`].
    pub fn forces(&self, q: &[f64], v: &[f64], f: &mut [f64]) {
        f.fill(0.0);
        self.gravity_load(f);
        self.friction_load(v, f);
        self.bending_load(q, f);
    }

    /// Gravity, `−m_i g` on each rod's centre (conservative: its potential
    /// `m_i g y_i` is in the energy).
    pub fn gravity_load(&self, f: &mut [f64]) {
        for (i, m) in self.mass.iter().enumerate() {
            f[BODY * i + 1] -= m * self.gravity;
        }
    }

    /// The joints' friction: the torque `r (w_k − w_{k−1})` on rod `k − 1`
    /// and its opposite on rod `k`, at every joint between two rods (the
    /// pivot is free of it). Dissipative: its power `−r Σ (w_k − w_{k−1})²`.
    pub fn friction_load(&self, v: &[f64], f: &mut [f64]) {
        if self.friction == 0.0 {
            return;
        }
        for k in 1..self.len() {
            let t = self.friction * (v[BODY * k + 2] - v[BODY * (k - 1) + 2]);
            f[BODY * (k - 1) + 2] += t;
            f[BODY * k + 2] -= t;
        }
    }

    /// Bending: the torque `kb_k (theta_k − theta_{k−1})` on rod `k − 1`
    /// and its opposite on rod `k` (conservative: its energy is in `E`).
    pub fn bending_load(&self, q: &[f64], f: &mut [f64]) {
        for k in 1..self.len() {
            let kb = self.bending[k];
            if kb != 0.0 {
                let t = kb * (q[BODY * k + 2] - q[BODY * (k - 1) + 2]);
                f[BODY * (k - 1) + 2] += t;
                f[BODY * k + 2] -= t;
            }
        }
    }

    /// The work the joints' friction took out of the motion over a step
    /// of `h` from the rates `v0` to `v1`, as the step applied it (at `v0`,
    /// against the mean rates): `h r Σ d0_k (d0_k + d1_k) / 2`, `d_k` the
    /// joint's relative rate.
    pub fn friction_work(&self, h: f64, v0: &[f64], v1: &[f64]) -> f64 {
        if self.friction == 0.0 {
            return 0.0;
        }
        let mut w = 0.0;
        for k in 1..self.len() {
            let d0 = v0[BODY * k + 2] - v0[BODY * (k - 1) + 2];
            let d1 = v1[BODY * k + 2] - v1[BODY * (k - 1) + 2];
            w += d0 * 0.5 * (d0 + d1);
        }
        h * self.friction * w
    }
}
