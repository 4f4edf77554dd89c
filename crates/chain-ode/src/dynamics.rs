//! The O(n) solve of the equations of motion: an articulated-body recursion.
//!
//! Each rod `k` sees the rods beyond it (`k+1..n`) as an articulated body whose
//! reaction at joint `k` is `f_k = M_k a_k + beta_k`: a 2x2 symmetric
//! "articulated mass" `M_k` times the joint's acceleration, plus a bias.
//! A backward sweep from the free tip (`M_n = 0`, `beta_n = 0`) builds them; a
//! forward sweep from the fixed pivot (`a_0 = 0`) then gives every angular
//! acceleration. Both sweeps are O(n) and allocate nothing: all per-rod storage
//! lives in a [`Workspace`]. The sweeps work in rod units (`m = l = 1`, gravity
//! `g/l`, damping `r/(m l^2)`); the returned forces are converted back.
//!
//! The result solves `A(phi) phi'' = b(phi, w)` of `physics.md` exactly (to
//! rounding); [`crate::dense`] keeps the O(n^3) Cholesky solve as the reference.

use crate::chain::Chain;
use crate::scalar::Scalar;

/// Per-rod scratch of the recursion, sized once for `n` rods.
#[derive(Clone, Debug)]
pub struct Workspace<T> {
    /// `(sin phi_k, cos phi_k)`.
    sc: Vec<(T, T)>,
    /// `h_k = n_k / 2 + M_k n_k` (rod units).
    h: Vec<[T; 2]>,
    /// `1 / D_k`, `D_k = 1/3 + n_k . M_k n_k`.
    dinv: Vec<T>,
    /// The generalized-force numerator `e_k`.
    e: Vec<T>,
}

impl<T: Scalar> Workspace<T> {
    /// Scratch for `n` rods.
    pub fn new(n: usize) -> Self {
        let z = T::cst(0.0);
        Self {
            sc: vec![(z, z); n],
            h: vec![[z, z]; n],
            dinv: vec![z; n],
            e: vec![z; n],
        }
    }

    /// The number of rods this workspace serves.
    pub fn len(&self) -> usize {
        self.e.len()
    }

    /// True for a workspace of zero rods.
    pub fn is_empty(&self) -> bool {
        self.e.is_empty()
    }
}

/// Forces and accelerations the recursion yields besides `phi''`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reactions<T> {
    /// Force of the pivot on rod 1 (physical units; `(0, M g)` for a chain at rest).
    pub pivot_force: [T; 2],
    /// Acceleration of the free tip `r_n''` (physical units).
    pub tip_acceleration: [T; 2],
}

/// Generalized damping force of rod `i` over `r`: `D_i(w)` of `physics.md`
/// (friction in the `n - 1` joints between rods; the pivot is frictionless).
#[inline(always)]
pub fn damping_stencil<T: Scalar>(w: &[T], i: usize) -> T {
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

/// Angular accelerations `acc = phi''` for angles `phi` and rates `w`, in O(n)
/// without allocation. Returns the pivot force and the tip acceleration.
///
/// Panics if the slices' lengths differ from `chain.links` or the workspace's.
pub fn accelerations<T: Scalar>(
    chain: &Chain,
    phi: &[T],
    w: &[T],
    acc: &mut [T],
    ws: &mut Workspace<T>,
) -> Reactions<T> {
    let n = chain.links;
    assert!(phi.len() == n && w.len() == n && acc.len() == n && ws.len() == n);
    let g = chain.gravity_rate();
    let gamma = chain.damping_rate();
    let zero = T::cst(0.0);
    let (mut mxx, mut mxy, mut myy) = (zero, zero, zero);
    let (mut bx, mut by) = (zero, zero);

    for i in (0..n).rev() {
        let (s, c) = phi[i].sin_cos();
        let wi = w[i];
        let w2 = wi * wi;
        // Unit vectors along (u) and normal to (nv) the rod.
        let (ux, uy) = (c, s);
        let (nx, ny) = (-s, c);
        let mnx = mxx * nx + mxy * ny;
        let mny = mxy * nx + myy * ny;
        let mux = mxx * ux + mxy * uy;
        let muy = mxy * ux + myy * uy;
        let d = nx * mnx + ny * mny + T::cst(1.0 / 3.0);
        let dinv = T::cst(1.0) / d;
        let hx = nx * 0.5 + mnx;
        let hy = ny * 0.5 + mny;
        let tau = damping_stencil(w, i) * gamma;
        let e = tau - c * (0.5 * g) + w2 * (nx * mux + ny * muy) - (nx * bx + ny * by);
        ws.sc[i] = (s, c);
        ws.h[i] = [hx, hy];
        ws.dinv[i] = dinv;
        ws.e[i] = e;
        // The articulated body seen from joint i-1 (rod i and all beyond it).
        let hxd = hx * dinv;
        let hyd = hy * dinv;
        mxx = mxx - hx * hxd + T::cst(1.0);
        mxy = mxy - hx * hyd;
        myy = myy - hy * hyd + T::cst(1.0);
        bx = bx + hxd * e - w2 * (ux * 0.5 + mux);
        by = by + hyd * e - w2 * (uy * 0.5 + muy) + T::cst(g);
    }

    let (mut ax, mut ay) = (zero, zero);
    for i in 0..n {
        let (s, c) = ws.sc[i];
        let [hx, hy] = ws.h[i];
        let wdot = (ws.e[i] - hx * ax - hy * ay) * ws.dinv[i];
        acc[i] = wdot;
        let w2 = w[i] * w[i];
        ax = ax - wdot * s - w2 * c;
        ay = ay + wdot * c - w2 * s;
    }

    let l = chain.rod_length();
    let ml = chain.mass * l;
    Reactions {
        pivot_force: [bx * ml, by * ml],
        tip_acceleration: [ax * l, ay * l],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_rod_is_a_physical_pendulum() {
        // phi'' = -(3 g / 2 l) cos phi for a uniform rod about its end.
        let chain = Chain::new(2.0, 1, 1.0, 9.81, 0.3).unwrap();
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
