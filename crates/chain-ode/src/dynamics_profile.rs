//! The O(n) recursion of [`crate::dynamics`] for rods of unequal mass and
//! length ([`Rods`]): the same backward and forward sweeps with rod `i`'s
//! mass `mu_i` and length `lambda_i` (mean-rod units, `m = l = 1`) in its
//! terms. Only a profiled chain runs it; equal rods keep the arithmetic of
//! [`crate::dynamics::accelerations_with`] bit for bit.
//!
//! Rod `i` between joint accelerations `a_{i-1}` and `a_i`, with `u = (c, s)`,
//! `v = (-s, c)`, its reaction on the body beyond joint `i`
//! `f_i = M_i a_i + beta_i`, its moment about joint `i - 1` gives
//!
//! ```text
//! alpha_i = (E_i - H_i . a_{i-1}) / (lambda_i D_i),
//! D_i = mu_i / 3 + v . M_i v,      H_i = (M_i + mu_i / 2) v,
//! E_i = tau_i / lambda_i - mu_i (g/l) c / 2 + lambda_i w_i^2 v . M_i u - v . beta_i,
//! ```
//!
//! (`tau_i`, the joint torques, in `m l^2` units) and the articulated body
//! seen from joint `i - 1`,
//!
//! ```text
//! M_{i-1} = M_i + mu_i I - H_i H_i^T / D_i,
//! beta_{i-1} = beta_i + mu_i (0, g/l) - lambda_i w_i^2 (M_i + mu_i / 2) u + H_i E_i / D_i,
//! a_i = a_{i-1} + lambda_i (alpha_i v - w_i^2 u).
//! ```
//!
//! With `mu_i = lambda_i = 1` these are the equal rods' sweeps.
//!
//! A tip mass `mu_t = M_t / m` is the articulated body beyond the last rod,
//! `M_n = mu_t I`, `beta_n = mu_t (0, g/l)` (zero without one), as for equal
//! rods. Bending adds the joint springs' torque to `tau_i`:
//! `kappa (k_i (phi_{i-1} - phi_i) + k_{i+1} (phi_{i+1} - phi_i))`, each
//! joint's spring `k_i = 2 / (lambda_{i-1} + lambda_i)` in units of the mean
//! rod's `EI / l` ([`Rods::joint`]). Neither is evaluated when absent: a
//! profile without them runs the arithmetic it ran before they were added.

use crate::chain::Chain;
use crate::dynamics::{damping_stencil, joint_stencil, Base, Reactions, Workspace};
use crate::profile::Rods;
use crate::scalar::Scalar;

/// [`crate::dynamics::accelerations_with`] for a profiled chain, with its
/// tip mass and bending springs.
pub(crate) fn accelerations<T: Scalar>(
    chain: &Chain,
    rods: &Rods,
    base: Base,
    phi: &[T],
    w: &[T],
    acc: &mut [T],
    ws: &mut Workspace<T>,
) -> Reactions<T> {
    let n = chain.links();
    assert!(rods.mass.len() == n && rods.length.len() == n);
    let g = chain.gravity_rate();
    let gamma = chain.damping_rate();
    let kappa = chain.bending_rate();
    let bend = kappa != 0.0;
    let zero = T::cst(0.0);
    let one = T::cst(1.0);
    // The tip mass `mu_t` (zero without one: the same arithmetic as before).
    let mu_t = chain.tip_mass_ratio();
    let (mut mxx, mut mxy, mut myy) = (T::cst(mu_t), zero, T::cst(mu_t));
    let (mut bx, mut by) = (zero, T::cst(mu_t * g));
    T::sin_cos_all(phi, &mut ws.sc);
    for i in (0..n).rev() {
        let (s, c) = ws.sc[i];
        let (mu, lam, inv_lam) = (rods.mass[i], rods.length[i], rods.inv_length[i]);
        let wi = w[i];
        let w2 = wi * wi;
        let lw2 = w2 * lam;
        let (nx, ny) = (-s, c);
        let (nxx, nxy2, nyy) = (nx * nx, (nx * ny) * 2.0, ny * ny);
        let d = (mxx * nxx + T::cst(mu * (1.0 / 3.0))) + (mxy * nxy2 + myy * nyy);
        let hx = mxx * nx + (mxy * ny + nx * (0.5 * mu));
        let hy = mxy * nx + (myy * ny + ny * (0.5 * mu));
        let mux = mxx * c + mxy * s;
        let muy = mxy * c + myy * s;
        let dinv = one / d;
        let torques = if bend {
            damping_stencil(w, i) * (gamma * inv_lam)
                + joint_stencil(phi, &rods.joint, i) * (kappa * inv_lam)
        } else {
            damping_stencil(w, i) * (gamma * inv_lam)
        };
        let e_fixed = torques - c * (0.5 * mu * g) + lw2 * (nx * mux + ny * muy);
        let e = e_fixed - (nx * bx + ny * by);
        let qi = e * dinv;
        let (gx, gy) = (hx * dinv, hy * dinv);
        let (hxx, hxy, hyy) = (hx * hx, hx * hy, hy * hy);
        mxx = (mxx + T::cst(mu)) - hxx * dinv;
        mxy -= hxy * dinv;
        myy = (myy + T::cst(mu)) - hyy * dinv;
        bx = (bx - lw2 * (c * (0.5 * mu) + mux)) + hx * qi;
        by = (by + T::cst(mu * g) - lw2 * (s * (0.5 * mu) + muy)) + hy * qi;
        // alpha_i = q_i - g_i . a_{i-1}, both over lambda_i.
        let (qa, gxa, gya) = (qi * inv_lam, gx * inv_lam, gy * inv_lam);
        ws.g[i] = [gxa, gya];
        ws.q[i] = qa;
        // a_i = a_{i-1} + lambda_i (alpha_i v - w_i^2 u), alpha_i = qa - ga . a_{i-1}.
        ws.map[i] = [
            one + s * (gxa * lam),
            s * (gya * lam),
            -(c * (gxa * lam)),
            one - c * (gya * lam),
            -(s * qi) - lw2 * c,
            c * qi - lw2 * s,
        ];
    }
    crate::dynamics::forward_sweep(chain, base, [mxx, mxy, myy], [bx, by], acc, ws)
}
