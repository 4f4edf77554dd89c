//! Positions, velocities and energies of a chain state, each in O(n).
//!
//! Angles `phi_i` are measured from the horizontal, counter-clockwise; joint
//! `r_k = P0 + l sum_{j<=k} (cos phi_j, sin phi_j)`; the tip is `r_n`.

use crate::chain::Chain;
use crate::profile::Rods;
use crate::scalar::sin_cos;

/// A point or vector in the plane, `[x, y]`.
pub type Vec2 = [f64; 2];

/// Joint positions `r_0 = p0, r_1, .., r_n`.
/// A profiled chain's rods have lengths `l_i = lambda_i l` ([`Chain::rods`]).
pub fn joints(chain: &Chain, p0: Vec2, phi: &[f64]) -> Vec<Vec2> {
    let l = chain.rod_length();
    let mut r = p0;
    let mut out = Vec::with_capacity(phi.len() + 1);
    out.push(r);
    for (i, &p) in phi.iter().enumerate() {
        let (s, c) = sin_cos(p);
        let li = rod_length_of(chain, i, l);
        r = [r[0] + li * c, r[1] + li * s];
        out.push(r);
    }
    out
}

/// The length of rod `i`: `l` for equal rods, `lambda_i l` for a profile.
#[inline(always)]
fn rod_length_of(chain: &Chain, i: usize, l: f64) -> f64 {
    match chain.rods() {
        Some(rods) => rods.length[i] * l,
        None => l,
    }
}

/// The free tip `r_n`.
pub fn tip(chain: &Chain, p0: Vec2, phi: &[f64]) -> Vec2 {
    let l = chain.rod_length();
    phi.iter().enumerate().fold(p0, |r, (i, &p)| {
        let (s, c) = sin_cos(p);
        let li = rod_length_of(chain, i, l);
        [r[0] + li * c, r[1] + li * s]
    })
}

/// The lever arm of rod `i` (0-based) of `n`, in rod lengths:
/// `q_i = n - i - 1/2` (`n - i + 1/2` with 1-based `i`), the rods below it
/// plus half of itself. It weighs rod `i`'s height in the potential energy,
/// its gravity torque and the off-diagonal mass matrix. Exact in `f64`.
#[inline(always)]
pub fn lever_arm(n: usize, i: usize) -> f64 {
    (n - i - 1) as f64 + 0.5
}

/// Running sums over the rods, from the pivot down, in rod units (lengths
/// in `l`): the velocity of the current joint `sum_j w_j (-sin phi_j, cos phi_j)`
/// and twice the kinetic energy in units of `m l^2`. [`RodSums::add`] is
/// the one per-rod kernel of the tip velocity and the kinetic energy, here
/// and in the models' fused per-step pass (`model/rigid.rs`).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RodSums {
    /// Velocity of the lower joint of the last rod added (the tip once
    /// every rod is in), over `l`.
    pub joint_velocity: Vec2,
    /// `sum_k |v_ck|^2 + w_k^2 / 12` over the rods added, `v_ck` the centre
    /// velocity over `l`: `T = (m l^2 / 2)` times it.
    pub twice_kinetic: f64,
}

impl RodSums {
    /// Adds the next rod, with `(s, c) = (sin phi, cos phi)` and rate `w`.
    #[inline(always)]
    pub(crate) fn add(&mut self, s: f64, c: f64, w: f64) {
        let [jx, jy] = self.joint_velocity;
        let (nx, ny) = (-s * w, c * w);
        let (cx, cy) = (jx + 0.5 * nx, jy + 0.5 * ny);
        self.twice_kinetic += cx * cx + cy * cy + w * w / 12.0;
        self.joint_velocity = [jx + nx, jy + ny];
    }

    /// Adds the next rod of a profiled chain: mass `mu`, length `lam`
    /// (mean-rod units): its centre's velocity `joint + lam w v / 2` and
    /// `mu (|v_c|^2 + lam^2 w^2 / 12)`.
    #[inline(always)]
    pub(crate) fn add_rod(&mut self, s: f64, c: f64, w: f64, mu: f64, lam: f64) {
        let [jx, jy] = self.joint_velocity;
        let (nx, ny) = (-s * w * lam, c * w * lam);
        let (cx, cy) = (jx + 0.5 * nx, jy + 0.5 * ny);
        self.twice_kinetic += mu * (cx * cx + cy * cy + (w * lam) * (w * lam) / 12.0);
        self.joint_velocity = [jx + nx, jy + ny];
    }

    /// The sums over every rod of a profiled chain.
    fn of_rods(rods: &Rods, phi: &[f64], w: &[f64]) -> Self {
        let mut sums = Self::default();
        for (i, (&p, &wk)) in phi.iter().zip(w).enumerate() {
            let (s, c) = sin_cos(p);
            sums.add_rod(s, c, wk, rods.mass[i], rods.length[i]);
        }
        sums
    }

    /// The sums of `chain` (equal or profiled rods).
    fn of_chain(chain: &Chain, phi: &[f64], w: &[f64]) -> Self {
        match chain.rods() {
            Some(rods) => Self::of_rods(rods, phi, w),
            None => Self::of(phi, w),
        }
    }

    /// The sums over every rod of `(phi, w)`.
    fn of(phi: &[f64], w: &[f64]) -> Self {
        let mut sums = Self::default();
        for (&p, &wk) in phi.iter().zip(w) {
            let (s, c) = sin_cos(p);
            sums.add(s, c, wk);
        }
        sums
    }

    /// The tip velocity, for rods of length `l`.
    #[inline(always)]
    pub(crate) fn tip_velocity(&self, l: f64) -> Vec2 {
        [l * self.joint_velocity[0], l * self.joint_velocity[1]]
    }
}

/// The exact tip velocity `l sum_j w_j (-sin phi_j, cos phi_j)`.
pub fn tip_velocity(chain: &Chain, phi: &[f64], w: &[f64]) -> Vec2 {
    RodSums::of_chain(chain, phi, w).tip_velocity(chain.rod_length())
}

/// Kinetic energy: `sum_k (m/2)|v_ck|^2 + (J/2) w_k^2`, `J = m l^2 / 12`,
/// plus `(M_t / 2) |v_tip|^2` for a tip mass (equal to `(m l^2 / 2) w^T A w`).
/// A profiled chain's rods weigh `mu_i m` and measure `lambda_i l`.
pub fn kinetic_energy(chain: &Chain, phi: &[f64], w: &[f64]) -> f64 {
    let sums = RodSums::of_chain(chain, phi, w);
    let t = 0.5 * chain.mass() * chain.rod_length().powi(2) * sums.twice_kinetic;
    if chain.tip_mass() != 0.0 {
        let v = sums.tip_velocity(chain.rod_length());
        t + 0.5 * chain.tip_mass() * (v[0] * v[0] + v[1] * v[1])
    } else {
        t
    }
}

/// Potential energy `m g l sum_i q_i sin phi_i` ([`lever_arm`] `q_i`), plus
/// `M_t g y_tip = M_t g l sum_i sin phi_i` for a tip mass; zero at the
/// height of `P0`.
///
/// A profiled chain's is `m g l sum_i mu_i y_i`, `y_i` the height of rod
/// `i`'s centre in `l`: `sum_{j<i} lambda_j sin phi_j + lambda_i sin phi_i / 2`,
/// plus `M_t g y_tip`, `y_tip = l sum_i lambda_i sin phi_i`, for a tip mass.
pub fn potential_energy(chain: &Chain, phi: &[f64]) -> f64 {
    let n = phi.len();
    if let Some(rods) = chain.rods() {
        let v = chain.mass() * chain.gravity() * chain.rod_length() * rods_height_sum(rods, phi);
        if chain.tip_mass() == 0.0 {
            return v;
        }
        let y_tip = tip(chain, [0.0, 0.0], phi)[1];
        return v + chain.tip_mass() * chain.gravity() * y_tip;
    }
    let sum: f64 = phi
        .iter()
        .enumerate()
        .map(|(i, p)| lever_arm(n, i) * p.sin())
        .sum();
    let v = chain.mass() * chain.gravity() * chain.rod_length() * sum;
    if chain.tip_mass() != 0.0 {
        let y: f64 = phi.iter().map(|p| p.sin()).sum();
        v + chain.tip_mass() * chain.gravity() * chain.rod_length() * y
    } else {
        v
    }
}

/// `sum_i mu_i y_i` of a profiled chain (see [`potential_energy`]), in `l`.
pub(crate) fn rods_height_sum(rods: &Rods, phi: &[f64]) -> f64 {
    let mut joint = 0.0;
    let mut sum = 0.0;
    for (i, p) in phi.iter().enumerate() {
        let dy = rods.length[i] * sin_cos(*p).0;
        sum += rods.mass[i] * (joint + 0.5 * dy);
        joint += dy;
    }
    sum
}

/// Energy of the bending springs `U_b = (EI / 2l) sum_{i>=2} (phi_i - phi_{i-1})^2`
/// (0 for `EI = 0`). Unequal rods' joint `i` has the spring
/// `EI / ((l_{i-1} + l_i) / 2)` ([`Rods::joint`]):
/// `U_b = (EI / 2l) sum_i k_i (phi_i - phi_{i-1})^2`.
pub fn bending_energy(chain: &Chain, phi: &[f64]) -> f64 {
    let loads = crate::load::Loads::of(chain, crate::load::Units::Rod);
    let view = crate::load::Angles { phi, w: &[] };
    loads.potential(&view, 0.0)
}

/// Total mechanical energy `T + V` of the rigid chain, `+ U_b` when it has
/// bending stiffness: the model's one energy ([`crate::model::RigidModel`],
/// fused with the tip's velocity in the runs), which is
/// [`kinetic_energy`] + [`potential_energy`] + [`bending_energy`] to rounding.
pub fn energy(chain: &Chain, phi: &[f64], w: &[f64]) -> f64 {
    let mut y = Vec::with_capacity(2 * phi.len());
    y.extend_from_slice(phi);
    y.extend_from_slice(w);
    crate::model::rigid_energy(chain, &y)
}

/// Dissipation rate `2R = r sum_{i>=2} (w_i - w_{i-1})^2 = -dE/dt` (power, >= 0).
pub fn dissipation_rate(chain: &Chain, w: &[f64]) -> f64 {
    chain.damping() * w.windows(2).map(|p| (p[1] - p[0]).powi(2)).sum::<f64>()
}
