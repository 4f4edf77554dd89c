//! The O(n) solve of the equations of motion: an articulated-body recursion.
//!
//! Each rod `k` sees the rods beyond it (`k+1..n`) as an articulated body whose
//! reaction at joint `k` is `f_k = M_k a_k + beta_k`: a 2x2 symmetric
//! "articulated mass" `M_k` times the joint's acceleration, plus a bias.
//! A backward sweep from the free tip (`M_n = mu I`, `beta_n = mu (0, g/l)`
//! for a tip mass `mu = M_t / m`, zero without one) builds them; a
//! forward sweep from the pivot (`a_0 = 0` when it is fixed) then gives
//! every angular acceleration. Both sweeps are O(n) and allocate nothing:
//! all per-rod storage lives in a [`Workspace`]. The sweeps work in rod
//! units (`m = l = 1` for the mean rod, gravity `g/l`, damping
//! `r/(m l^2)`); the returned forces are converted back.
//!
//! One recursion serves equal and unequal rods ([`RodShape`]). Rod `i`
//! between joint accelerations `a_{i-1}` and `a_i`, with mass `mu_i` and
//! length `lambda_i` in mean-rod units, `u = (c, s)`, `v = (-s, c)`, its
//! reaction on the body beyond joint `i` `f_i = M_i a_i + beta_i`, its
//! moment about joint `i - 1` gives
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
//! With `mu_i = lambda_i = 1` ([`EqualRods`]) these are the equal rods'
//! sweeps, and the compiler folds the factors away: equal rods run the
//! arithmetic they always ran. Bending adds the joint springs' torque to
//! `tau_i`: `kappa (k_i (phi_{i-1} - phi_i) + k_{i+1} (phi_{i+1} - phi_i))`,
//! each joint's spring `k_i = 2 / (lambda_{i-1} + lambda_i)` in units of the
//! mean rod's `EI / l` ([`Rods::joint`]); it is not evaluated without `EI`.
//!
//! The result solves `A(phi) phi'' = b(phi, w)` of `docs/model.md` exactly (to
//! rounding); [`crate::dense`] keeps the O(n^3) Cholesky solve as the reference.

use crate::chain::Chain;
use crate::load::{Kinematics, Loads, RodForce, Units};
use crate::profile::Rods;
use crate::scalar::Scalar;

/// Per-rod scratch of the recursion, sized once for `n` rods.
#[derive(Clone, Debug)]
pub struct Workspace<T> {
    /// `(sin phi_k, cos phi_k)`.
    pub(crate) sc: Vec<(T, T)>,
    /// `g_k = h_k / D_k`: `phi_k'' = q_k - g_k . a_{k-1}` (rod units).
    pub(crate) g: Vec<[T; 2]>,
    /// `q_k = e_k / D_k`.
    pub(crate) q: Vec<T>,
    /// The joint acceleration as an affine map of the previous one:
    /// `a_k = T_k a_{k-1} + c_k`, stored `[T11, T12, T21, T22, c1, c2]`.
    pub(crate) map: Vec<[T; 6]>,
    /// The rods' centres and their velocities (rod units, inertial frame),
    /// for the loads that read them; empty until one does.
    pub(crate) centre: Vec<[T; 2]>,
    pub(crate) centre_velocity: Vec<[T; 2]>,
}

impl<T: Scalar> Workspace<T> {
    /// Scratch for `n` rods.
    pub fn new(n: usize) -> Self {
        let z = T::cst(0.0);
        Self {
            sc: vec![(z, z); n],
            g: vec![[z, z]; n],
            q: vec![z; n],
            map: vec![[z; 6]; n],
            centre: Vec::new(),
            centre_velocity: Vec::new(),
        }
    }

    /// Sizes the centres' buffers (for loads that read them), once.
    pub(crate) fn with_centres(mut self) -> Self {
        let z = T::cst(0.0);
        let n = self.len();
        self.centre = vec![[z, z]; n];
        self.centre_velocity = vec![[z, z]; n];
        self
    }

    /// The number of rods this workspace serves.
    pub fn len(&self) -> usize {
        self.q.len()
    }

    /// True for a workspace of zero rods.
    pub fn is_empty(&self) -> bool {
        self.q.is_empty()
    }
}

/// Forces and accelerations the recursion yields besides `phi''`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reactions<T> {
    /// Force of the pivot on rod 1 (physical units; `(0, M g)` for a chain at rest).
    pub pivot_force: [T; 2],
    /// Acceleration of the free tip `r_n''` (physical units).
    pub tip_acceleration: [T; 2],
    /// Acceleration of the pivot `P0''` (physical units): zero for a fixed
    /// pivot, the prescribed one for a driven pivot, and the free end's
    /// for a released one.
    pub pivot_acceleration: [T; 2],
    /// The power the loads draw from the chain at its rods (physical
    /// units; the joints' is [`Loads::joint_power`]'s).
    pub load_power: T,
}

/// What holds joint 0 (the pivot) in the recursion's forward sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Base {
    /// Pinned: `a_0 = 0` (the report's chain).
    Fixed,
    /// Moved with a prescribed acceleration `P0''` (physical units).
    Driven([f64; 2]),
    /// Let go: no force at joint 0, `f_0 = M_0 a_0 + beta_0 = 0`, so
    /// `a_0 = -M_0^{-1} beta_0`.
    Free,
}

/// Generalized damping force of rod `i` over `r`: `D_i(w)` of `docs/model.md`
/// (friction in the `n - 1` joints between rods; the pivot is frictionless).
/// The same stencil of the angles, `D_i(phi)`, times `EI / l` is the bending
/// spring's generalised force (the pivot has no bending spring either).
#[inline(always)]
pub(crate) fn damping_stencil<T: Scalar>(w: &[T], i: usize) -> T {
    let n = w.len();
    let mut d = T::cst(0.0);
    if i > 0 {
        d += w[i - 1] - w[i];
    }
    if i + 1 < n {
        d += w[i + 1] - w[i];
    }
    d
}

/// The rods as the recursion reads them, in units of the mean rod: rod `i`'s
/// mass `mu_i` and length `lambda_i` (and its inverse). [`EqualRods`] is the constant 1 everywhere, so that the
/// one recursion, monomorphised for it, folds to the equal rods' arithmetic
/// (a product by the constant 1 is exact and the compiler drops it); a
/// profile ([`Rods`]) reads its per-rod values.
pub(crate) trait RodShape: Copy {
    /// `mu_i`.
    fn mass(self, i: usize) -> f64;
    /// `lambda_i`.
    fn length(self, i: usize) -> f64;
    /// `1 / lambda_i`.
    fn inv_length(self, i: usize) -> f64;
}

/// Equal rods: every factor is 1.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EqualRods;

impl RodShape for EqualRods {
    #[inline(always)]
    fn mass(self, _: usize) -> f64 {
        1.0
    }
    #[inline(always)]
    fn length(self, _: usize) -> f64 {
        1.0
    }
    #[inline(always)]
    fn inv_length(self, _: usize) -> f64 {
        1.0
    }
}

impl RodShape for &Rods {
    #[inline(always)]
    fn mass(self, i: usize) -> f64 {
        self.mass[i]
    }
    #[inline(always)]
    fn length(self, i: usize) -> f64 {
        self.length[i]
    }
    #[inline(always)]
    fn inv_length(self, i: usize) -> f64 {
        self.inv_length[i]
    }
}

/// Angular accelerations `acc = phi''` for angles `phi` and rates `w`, in O(n)
/// without allocation, the pivot fixed. Returns the pivot force and the tip
/// acceleration.
///
/// Panics if the slices' lengths differ from `chain.links` or the workspace's.
/// `T` is `f64` outside this crate (a dual number inside it, for the exact
/// Jacobian-vector product).
pub fn accelerations<T: Scalar>(
    chain: &Chain,
    phi: &[T],
    w: &[T],
    acc: &mut [T],
    ws: &mut Workspace<T>,
) -> Reactions<T> {
    accelerations_with(chain, Base::Fixed, phi, w, acc, ws)
}

/// [`accelerations`] with the pivot held as `base` says: the forward sweep
/// starts from the pivot's acceleration `a_0` (zero, prescribed, or, for a
/// free pivot, `-M_0^{-1} beta_0` from the backward sweep's articulated
/// body of the whole chain), and the pivot force is `M_0 a_0 + beta_0`.
/// `Base::Fixed` is exactly the arithmetic of a pinned chain.
pub fn accelerations_with<T: Scalar>(
    chain: &Chain,
    base: Base,
    phi: &[T],
    w: &[T],
    acc: &mut [T],
    ws: &mut Workspace<T>,
) -> Reactions<T> {
    let loads = Loads::of(chain, Units::Rod);
    accelerations_under(chain, &loads, base, [0.0, 0.0], phi, w, acc, ws)
}

/// [`accelerations_with`] under `loads` (the chain's, in rod units, built
/// once by the caller), the pivot moving at `pivot_velocity` (physical
/// units; read by loads that read the rods' centres).
#[allow(
    clippy::too_many_arguments,
    reason = "the recursion's inputs, each a slice or a value"
)]
pub(crate) fn accelerations_under<T: Scalar>(
    chain: &Chain,
    loads: &Loads,
    base: Base,
    pivot_velocity: [f64; 2],
    phi: &[T],
    w: &[T],
    acc: &mut [T],
    ws: &mut Workspace<T>,
) -> Reactions<T> {
    let n = chain.links();
    assert!(phi.len() == n && w.len() == n && acc.len() == n && ws.len() == n);
    match chain.rods() {
        None => sweep(
            chain,
            EqualRods,
            loads,
            base,
            pivot_velocity,
            phi,
            w,
            acc,
            ws,
        ),
        Some(rods) => sweep(chain, rods, loads, base, pivot_velocity, phi, w, acc, ws),
    }
}

/// The rigid chain's kinematics as the loads read them in the recursion
/// (rod units: lengths in `l`, velocities in `l` per time unit).
pub(crate) struct RodView<'a, T, R> {
    pub phi: &'a [T],
    pub w: &'a [T],
    pub sc: &'a [(T, T)],
    pub rods: R,
    pub centre: &'a [[T; 2]],
    pub centre_velocity: &'a [[T; 2]],
}

impl<T: Scalar, R: RodShape> Kinematics<T> for RodView<'_, T, R> {
    #[inline(always)]
    fn angles(&self) -> &[T] {
        self.phi
    }
    #[inline(always)]
    fn rates(&self) -> &[T] {
        self.w
    }
    #[inline(always)]
    fn sin_cos(&self, i: usize) -> (T, T) {
        self.sc[i]
    }
    #[inline(always)]
    fn half_length(&self, i: usize) -> f64 {
        0.5 * self.rods.length(i)
    }
    #[inline(always)]
    fn mass(&self, i: usize) -> f64 {
        self.rods.mass(i)
    }
    #[inline(always)]
    fn torque_unit(&self, i: usize) -> f64 {
        self.rods.inv_length(i)
    }
    #[inline(always)]
    fn centre(&self, i: usize) -> [T; 2] {
        self.centre[i]
    }
    #[inline(always)]
    fn centre_velocity(&self, i: usize) -> [T; 2] {
        self.centre_velocity[i]
    }
}

/// The rods' centres and their velocities from the pivot down (rod
/// units), the pivot at the origin moving at `v0`: `c_i = sum_{j<i}
/// lambda_j u_j + lambda_i u_i / 2`, `c_i' = v0 + sum_{j<i} lambda_j w_j v_j
/// + lambda_i w_i v_i / 2`.
#[inline(always)]
pub(crate) fn centres<T: Scalar, R: RodShape>(
    rods: R,
    v0: [f64; 2],
    w: &[T],
    sc: &[(T, T)],
    centre: &mut [[T; 2]],
    velocity: &mut [[T; 2]],
) {
    let (mut px, mut py) = (T::cst(0.0), T::cst(0.0));
    let (mut vx, mut vy) = (T::cst(v0[0]), T::cst(v0[1]));
    for (i, &(s, c)) in sc.iter().enumerate() {
        let lam = rods.length(i);
        let (ux, uy) = (c * lam, s * lam);
        let (nx, ny) = (-(s * (w[i] * lam)), c * (w[i] * lam));
        centre[i] = [px + ux * 0.5, py + uy * 0.5];
        velocity[i] = [vx + nx * 0.5, vy + ny * 0.5];
        (px, py) = (px + ux, py + uy);
        (vx, vy) = (vx + nx, vy + ny);
    }
}

/// The recursion for rods of shape `rods` (see the module doc) under
/// `loads`: the backward sweep from the tip, then [`forward_sweep`] from
/// the pivot. One body for equal and unequal rods; with [`EqualRods`] it is
/// the equal rods' own arithmetic, bit for bit. Each rod's loads come as a
/// torque (already over `lambda_i`), a force at its centre and a power; the
/// field acts on every rod and on the tip mass.
#[allow(
    clippy::too_many_arguments,
    reason = "the recursion's inputs, each a slice or a value"
)]
#[inline(always)]
fn sweep<T: Scalar, R: RodShape>(
    chain: &Chain,
    rods: R,
    loads: &Loads,
    base: Base,
    pivot_velocity: [f64; 2],
    phi: &[T],
    w: &[T],
    acc: &mut [T],
    ws: &mut Workspace<T>,
) -> Reactions<T> {
    let n = chain.links();
    // The field `a` in rod units (`(0, -g/l)`).
    let ay = loads.field.y();
    let zero = T::cst(0.0);
    let one = T::cst(1.0);
    // The tip mass `mu_t = M_t / m` is the articulated body beyond the last
    // rod: `M_n = mu_t I`, `beta_n = -mu_t a` (zero without one, the same
    // arithmetic as before).
    let mu_t = chain.tip_mass_ratio();
    let (mut mxx, mut mxy, mut myy) = (T::cst(mu_t), zero, T::cst(mu_t));
    let (mut bx, mut by) = (zero, T::cst(-(mu_t * ay)));

    // Independent per-rod work first, so that it overlaps freely.
    T::sin_cos_all(phi, &mut ws.sc);
    // The rods' centres, for the loads that read them (the drag).
    let forces = loads.reads_centres();
    if forces {
        if ws.centre.len() != n {
            *ws = std::mem::replace(ws, Workspace::new(0)).with_centres();
        }
        let l = chain.rod_length();
        let v0 = [pivot_velocity[0] / l, pivot_velocity[1] / l];
        centres(rods, v0, w, &ws.sc, &mut ws.centre, &mut ws.centre_velocity);
    }
    let Workspace {
        sc,
        g: gs,
        q: qs,
        map,
        centre,
        centre_velocity,
    } = &mut *ws;
    let view = RodView {
        phi,
        w,
        sc: &sc[..],
        rods,
        centre: &centre[..],
        centre_velocity: &centre_velocity[..],
    };
    let mut load_power = zero;

    // Backward sweep. The loop-carried chain is the Riccati-like update of M
    // (one division per rod); expressions are grouped so that everything not
    // depending on M or beta is computed off that chain.
    for i in (0..n).rev() {
        let (s, c) = sc[i];
        let (mu, lam, inv_lam) = (rods.mass(i), rods.length(i), rods.inv_length(i));
        let wi = w[i];
        let w2 = wi * wi;
        let lw2 = w2 * lam;
        // Unit vectors along (u) and normal to (nv) the rod: u = (c, s), nv = (-s, c).
        let (nx, ny) = (-s, c);
        let (nxx, nxy2, nyy) = (nx * nx, (nx * ny) * 2.0, ny * ny);
        let d = (mxx * nxx + T::cst(mu * (1.0 / 3.0))) + (mxy * nxy2 + myy * nyy);
        let hx = mxx * nx + (mxy * ny + nx * (0.5 * mu));
        let hy = mxy * nx + (myy * ny + ny * (0.5 * mu));
        let mux = mxx * c + mxy * s;
        let muy = mxy * c + myy * s;
        let dinv = one / d;
        // The loads on rod i: the joints' torques (friction, bending) and,
        // for loads that read the centres, a force at the centre.
        let mut f = RodForce::zero();
        loads.add_to_rod(i, &view, &mut f);
        // The field's moment about the upper joint, over lambda_i.
        let e_loads = f.torque + c * (0.5 * (mu * ay));
        let e_loads = if forces {
            load_power += f.power;
            e_loads + (nx * f.force[0] + ny * f.force[1]) * 0.5
        } else {
            e_loads
        };
        let e_fixed = e_loads + lw2 * (nx * mux + ny * muy);
        let e = e_fixed - (nx * bx + ny * by);
        let qi = e * dinv;
        let (gx, gy) = (hx * dinv, hy * dinv);
        // The articulated body seen from joint i-1 (rod i and all beyond it).
        let (hxx, hxy, hyy) = (hx * hx, hx * hy, hy * hy);
        mxx = (mxx + T::cst(mu)) - hxx * dinv;
        mxy -= hxy * dinv;
        myy = (myy + T::cst(mu)) - hyy * dinv;
        // The field's pull, then the loads' force (the bias is minus the
        // applied force); written as the sum the data were made with.
        let (bx0, by0) = if forces {
            (bx - f.force[0], (by + T::cst(-(mu * ay))) - f.force[1])
        } else {
            (bx, by + T::cst(-(mu * ay)))
        };
        bx = (bx0 - lw2 * (c * (0.5 * mu) + mux)) + hx * qi;
        by = (by0 - lw2 * (s * (0.5 * mu) + muy)) + hy * qi;
        // alpha_i = q_i - g_i . a_{i-1}, both over lambda_i.
        let (qa, gxa, gya) = (qi * inv_lam, gx * inv_lam, gy * inv_lam);
        gs[i] = [gxa, gya];
        qs[i] = qa;
        // a_i = a_{i-1} + lambda_i (alpha_i v - w_i^2 u), alpha_i = qa - ga . a_{i-1}.
        map[i] = [
            one + s * (gxa * lam),
            s * (gya * lam),
            -(c * (gxa * lam)),
            one - c * (gya * lam),
            -(s * qi) - lw2 * c,
            c * qi - lw2 * s,
        ];
    }

    let mut r = forward_sweep(chain, base, [mxx, mxy, myy], [bx, by], acc, ws);
    r.load_power = load_power;
    r
}

/// The forward sweep from the pivot, given the articulated body of the
/// whole chain at joint 0 (`M_0 = [mxx, mxy, myy]`, `beta_0`) and the
/// workspace's per-rod maps: every `phi_i''` into `acc`, and the reactions.
#[inline(always)]
pub(crate) fn forward_sweep<T: Scalar>(
    chain: &Chain,
    base: Base,
    [mxx, mxy, myy]: [T; 3],
    [bx, by]: [T; 2],
    acc: &mut [T],
    ws: &Workspace<T>,
) -> Reactions<T> {
    let zero = T::cst(0.0);
    let one = T::cst(1.0);
    let l = chain.rod_length();
    // The pivot's acceleration a_0 (rod units) and force f_0 = M_0 a_0 + beta_0.
    let (a0x, a0y, f0x, f0y) = match base {
        Base::Fixed => (zero, zero, bx, by),
        Base::Driven([px, py]) => {
            let (a0x, a0y) = (T::cst(px / l), T::cst(py / l));
            (
                a0x,
                a0y,
                (mxx * a0x + mxy * a0y) + bx,
                (mxy * a0x + myy * a0y) + by,
            )
        }
        Base::Free => {
            let det = mxx * myy - mxy * mxy;
            let dinv = one / det;
            (
                -((myy * bx - mxy * by) * dinv),
                -((mxx * by - mxy * bx) * dinv),
                zero,
                zero,
            )
        }
    };

    // Forward sweep: the loop-carried chain is one 2x2 affine map per rod.
    let (mut ax, mut ay) = (a0x, a0y);
    for (i, a) in acc.iter_mut().enumerate() {
        let [gx, gy] = ws.g[i];
        *a = ws.q[i] - (gx * ax + gy * ay);
        let [t11, t12, t21, t22, c1, c2] = ws.map[i];
        let ax1 = (t11 * ax + c1) + t12 * ay;
        ay = (t21 * ax + c2) + t22 * ay;
        ax = ax1;
    }

    let ml = chain.mass() * l;
    Reactions {
        pivot_force: [f0x * ml, f0y * ml],
        tip_acceleration: [ax * l, ay * l],
        pivot_acceleration: [a0x * l, a0y * l],
        load_power: zero,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::ChainParams;

    #[test]
    fn single_rod_is_a_physical_pendulum() {
        // phi'' = -(3 g / 2 l) cos phi for a uniform rod about its end.
        let chain = Chain::new(ChainParams {
            length: 2.0,
            links: 1,
            mass: 1.0,
            gravity: 9.81,
            damping: 0.3,
            ..ChainParams::default()
        })
        .unwrap();
        let mut ws = Workspace::new(1);
        let mut acc = [0.0];
        let phi = [0.4];
        accelerations(&chain, &phi, &[1.3], &mut acc, &mut ws);
        let expect = -1.5 * 9.81 / 2.0 * 0.4f64.cos();
        assert!((acc[0] - expect).abs() < 1e-13, "{} vs {expect}", acc[0]);
    }

    #[test]
    fn hanging_chain_at_rest_is_in_equilibrium() {
        let chain = Chain::report(40, 1e-3).unwrap();
        let phi = vec![-std::f64::consts::FRAC_PI_2; 40];
        let w = vec![0.0; 40];
        let mut acc = vec![1.0; 40];
        let mut ws = Workspace::new(40);
        let r = accelerations(&chain, &phi, &w, &mut acc, &mut ws);
        assert!(acc.iter().all(|a| a.abs() < 1e-12));
        assert!(r.pivot_force[0].abs() < 1e-12);
        assert!((r.pivot_force[1] - chain.weight()).abs() < 1e-12 * chain.weight());
    }
}
