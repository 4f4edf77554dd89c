//! The elastic chain: rods in maximal coordinates joined by stiff springs.
//!
//! Each rod `i` (0-based) has its centre `c_i` (relative to the pivot `P0`),
//! its angle `theta_i` from the horizontal and their rates, and the diagonal
//! mass `m` (translation) and `J = m l^2 / 12` (rotation about the centre).
//! With `u_i = (cos theta_i, sin theta_i)`, `v_i = (-sin theta_i, cos theta_i)`
//! and `h = l / 2`, rod `i` starts at `c_i - h u_i` and ends at `c_i + h u_i`.
//! Joint `k` (`k = 0..n-1`; joint 0 is the pivot) joins the end of rod `k - 1`
//! (the pivot, at the origin, for `k = 0`) to the start of rod `k` by a
//! spring-damper with the gap
//!
//! ```text
//! d_k = (c_k - h u_k) - (c_{k-1} + h u_{k-1})        (d_0 = c_0 - h u_0)
//! F_k = -K d_k - C d_k'                              force of joint k on rod k
//! ```
//!
//! with `K = EA / l` and `C = eta / l` (`eta = chain.axial_damping`), and rod
//! `k - 1` gets `-F_k`. The tip (joint `n`) is free: `F_n = 0`. The equations
//! of motion, each rod coupled only to its two neighbours, are
//!
//! ```text
//! m c_i'' = F_i - F_{i+1} - m g (0, 1)
//! J theta_i'' = -h u_i x (F_i + F_{i+1}) + r D_i(w) + (EI / l) D_i(theta)
//! ```
//!
//! (`a x b = a_x b_y - a_y b_x`; `D_i` the neighbours' stencil of the rigid
//! model: friction `r` and bending `EI` act between neighbouring rods only).
//! The energy `E = T + V + U_el + U_b` with `T = sum m |c_i'|^2 / 2 + J w_i^2 / 2`,
//! `V = m g sum c_i.y`, `U_el = (K / 2) sum |d_k|^2`,
//! `U_b = (EI / 2l) sum (theta_{i+1} - theta_i)^2` balances the work
//! `W' = 2R = C sum |d_k'|^2 + r sum (w_{i+1} - w_i)^2`. As `EA -> inf` at
//! fixed `n` the gaps close and this is the rigid pinned chain.
//!
//! The state is laid out `[theta (n), w (n), W, x (n), y (n), vx (n), vy (n)]`
//! (`6 n + 1` numbers): its first `2 n + 1` mean what the rigid chain's do
//! (angles, rates, dissipated work), so that a sample of either model reads
//! its angles the same way.

use std::cell::RefCell;

use crate::chain::Chain;
use crate::dae::ChainDae;
use crate::dynamics::{damping_stencil, Workspace};
use crate::kinematics::Vec2;
use crate::ode::{BandedDae, OdeSystem, Problem, SemiExplicitDae};
use crate::scalar::{sin_cos, Dual, Scalar};
use crate::state::State;

/// The constants of the elastic chain's right-hand side.
#[derive(Clone, Copy, Debug)]
struct Springs {
    n: usize,
    /// Half the rod length `h = l / 2`.
    h: f64,
    /// `1 / m`.
    inv_m: f64,
    /// `1 / J`, `J = m l^2 / 12`.
    inv_j: f64,
    g: f64,
    /// Joint spring `K = EA / l`.
    k: f64,
    /// Joint dashpot `C = eta / l`.
    c: f64,
    /// Joint friction `r`.
    r: f64,
    /// Bending spring `EI / l`.
    kb: f64,
}

impl Springs {
    fn of(chain: &Chain) -> Self {
        let l = chain.rod_length();
        let m = chain.mass();
        Self {
            n: chain.links(),
            h: 0.5 * l,
            inv_m: 1.0 / m,
            inv_j: 12.0 / (m * l * l),
            g: chain.gravity(),
            // A rigid chain has no springs: K = 0 makes this a free fall,
            // and no caller builds one (see `ElasticSystem::new`).
            k: chain.joint_stiffness().unwrap_or(0.0),
            c: chain.joint_damping(),
            r: chain.damping(),
            kb: chain.bending_spring(),
        }
    }
}

/// The state's blocks, by offset.
fn offsets(n: usize) -> [usize; 7] {
    // theta, w, W, x, y, vx, vy
    [0, n, 2 * n, 2 * n + 1, 3 * n + 1, 4 * n + 1, 5 * n + 1]
}

/// `dy = f(y)` for the elastic chain, over any scalar (`f64`, or a dual
/// number for the exact Jacobian-vector product). One pass over the joints,
/// no allocation: `sc` holds `(sin, cos)` of the angles.
fn rhs_generic<T: Scalar>(p: &Springs, y: &[T], dy: &mut [T], sc: &mut [(T, T)]) {
    let n = p.n;
    let [_, ow, owk, ox, oy, ovx, ovy] = offsets(n);
    let theta = &y[..n];
    let w = &y[ow..owk];
    T::sin_cos_all(theta, sc);
    let zero = T::cst(0.0);
    // Force of joint k on rod k, from the previous iteration: F_{k-1}.
    let (mut fpx, mut fpy) = (zero, zero);
    // End of rod k - 1 and its velocity (the pivot for k = 0).
    let (mut ex, mut ey, mut evx, mut evy) = (zero, zero, zero, zero);
    let mut dissipated = zero;
    for k in 0..=n {
        // The force of joint k on rod k (zero at the free tip, k = n).
        let (fx, fy) = if k < n {
            let (s, c) = sc[k];
            let (hs, hc) = (s * p.h, c * p.h);
            let (hsw, hcw) = (hs * w[k], hc * w[k]);
            let (x, yy, vx, vy) = (y[ox + k], y[oy + k], y[ovx + k], y[ovy + k]);
            let (dx, dyy) = (x - hc - ex, yy - hs - ey);
            let (ddx, ddy) = ((vx + hsw) - evx, (vy - hcw) - evy);
            dissipated += (ddx * ddx + ddy * ddy) * p.c;
            // This rod's end, for the next joint.
            (ex, ey, evx, evy) = (x + hc, yy + hs, vx - hsw, vy + hcw);
            (-(dx * p.k) - ddx * p.c, -(dyy * p.k) - ddy * p.c)
        } else {
            (zero, zero)
        };
        if k > 0 {
            // Rod i = k - 1 is complete: F_i at its start, -F_{i+1} at its end.
            let i = k - 1;
            let (s, c) = sc[i];
            let (sx, sy) = (fpx + fx, fpy + fy);
            let torque = -((c * sy - s * sx) * p.h)
                + damping_stencil(w, i) * p.r
                + damping_stencil(theta, i) * p.kb;
            dy[i] = w[i];
            dy[ow + i] = torque * p.inv_j;
            dy[ox + i] = y[ovx + i];
            dy[oy + i] = y[ovy + i];
            dy[ovx + i] = (fpx - fx) * p.inv_m;
            dy[ovy + i] = (fpy - fy) * p.inv_m - T::cst(p.g);
        }
        (fpx, fpy) = (fx, fy);
    }
    let mut friction = zero;
    for i in 1..n {
        let dw = w[i] - w[i - 1];
        friction += dw * dw;
    }
    dy[owk] = dissipated + friction * p.r;
}

/// The elastic chain as `y' = f(y)`, with preallocated scratch.
#[derive(Clone, Debug)]
pub struct ElasticSystem {
    chain: Chain,
    springs: Springs,
    sc: Vec<(f64, f64)>,
    dual_y: Vec<Dual>,
    dual_dy: Vec<Dual>,
    dual_sc: Vec<(Dual, Dual)>,
}

impl ElasticSystem {
    /// The system of a validated chain with elastic links.
    pub fn new(chain: &Chain) -> Self {
        let n = chain.links();
        let dim = 6 * n + 1;
        Self {
            chain: chain.clone(),
            springs: Springs::of(chain),
            sc: vec![(0.0, 0.0); n],
            dual_y: vec![Dual::default(); dim],
            dual_dy: vec![Dual::default(); dim],
            dual_sc: vec![(Dual::default(), Dual::default()); n],
        }
    }

    /// The chain.
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// Length of the state, `6 n + 1`.
    pub fn dim(&self) -> usize {
        6 * self.chain.links() + 1
    }

    /// `dy = f(y)`: O(n), allocation-free. Autonomous: `t` is unused.
    pub fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        rhs_generic(&self.springs, y, dy, &mut self.sc);
    }

    /// The exact Jacobian-vector product, by dual numbers through the same
    /// right-hand side.
    pub fn jvp(&mut self, _t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        for ((d, &yi), &vi) in self.dual_y.iter_mut().zip(y).zip(v) {
            *d = Dual::new(yi, vi);
        }
        rhs_generic(
            &self.springs,
            &self.dual_y,
            &mut self.dual_dy,
            &mut self.dual_sc,
        );
        for (o, d) in jv.iter_mut().zip(&self.dual_dy) {
            *o = d.d;
        }
    }
}

impl OdeSystem for ElasticSystem {
    fn dim(&self) -> usize {
        ElasticSystem::dim(self)
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        ElasticSystem::rhs(self, t, y, dy)
    }
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        ElasticSystem::jvp(self, t, y, v, jv)
    }
}

/// Every method runs the elastic chain: `bdf` on [`ElasticDae`] (an ODE is
/// a DAE without algebraic unknowns), `auto` starting explicit and handing
/// over at its first stiffness detection if the joints are damped enough
/// (`solve::auto_elastic`: the rigid chain's crossover in the damping rate
/// does not place an axial stiffness).
impl Problem for ElasticSystem {
    fn banded_dae(&self, _t0: f64, y0: &[f64]) -> Option<BandedDae> {
        Some(BandedDae {
            dae: Box::new(ElasticDae::new(&self.chain)),
            y0: y0.to_vec(),
        })
    }

    fn chain(&self) -> Option<&Chain> {
        Some(&self.chain)
    }
}

/// Scratch of [`ElasticDae`]: its trait's methods take `&self`.
#[derive(Clone, Debug)]
struct DaeScratch {
    sc: Vec<(f64, f64)>,
    dual_y: Vec<Dual>,
    dual_dy: Vec<Dual>,
    dual_sc: Vec<(Dual, Dual)>,
}

/// The elastic chain for the O(n) sparse BDF: every unknown differential,
/// and the Jacobian's banded pattern (each rod's accelerations depend on
/// its own and its two neighbours' coordinates and rates) filled exactly by
/// 18 dual-number sweeps of the right-hand side, one per kind of
/// coordinate and per rod modulo 3 (rods three apart share no row).
#[derive(Debug)]
pub struct ElasticDae {
    springs: Springs,
    scratch: RefCell<DaeScratch>,
}

impl ElasticDae {
    /// The DAE of a validated chain with elastic links.
    pub fn new(chain: &Chain) -> Self {
        let n = chain.links();
        let dim = 6 * n + 1;
        Self {
            springs: Springs::of(chain),
            scratch: RefCell::new(DaeScratch {
                sc: vec![(0.0, 0.0); n],
                dual_y: vec![Dual::default(); dim],
                dual_dy: vec![Dual::default(); dim],
                dual_sc: vec![(Dual::default(), Dual::default()); n],
            }),
        }
    }
}

impl SemiExplicitDae for ElasticDae {
    fn dim(&self) -> usize {
        6 * self.springs.n + 1
    }
    fn differential_dim(&self) -> usize {
        6 * self.springs.n + 1
    }
    fn rhs(&self, _t: f64, y: &[f64], out: &mut [f64]) {
        ElasticDae::rhs(self, y, out)
    }
    fn jacobian_entries(&self, _t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        ElasticDae::jacobian_entries(self, y, emit)
    }
    /// Rod `i` holds `theta_i, w_i, x_i, y_i, vx_i, vy_i` (and rod 0 `W`):
    /// each rod's accelerations read only its neighbours.
    fn blocks(&self) -> Option<Vec<usize>> {
        let n = self.springs.n;
        Some(
            (0..6 * n + 1)
                .map(|u| match u {
                    _ if u < 2 * n => u % n,
                    _ if u == 2 * n => 0,
                    _ => (u - (2 * n + 1)) % n,
                })
                .collect(),
        )
    }
}

impl ElasticDae {
    /// `out = f(y)`, as [`ElasticSystem::rhs`].
    pub fn rhs(&self, y: &[f64], out: &mut [f64]) {
        let mut s = self.scratch.borrow_mut();
        rhs_generic(&self.springs, y, out, &mut s.sc);
    }

    /// Every entry of `df/dy` at `y` but the row of `W` (dense, and read by
    /// no other equation: left out of the Newton matrix as in `ChainDae`),
    /// as `emit(row, column, value)`; the entries and their order depend
    /// on `n` only.
    pub fn jacobian_entries(&self, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        let n = self.springs.n;
        let [_, ow, _, ox, oy, ovx, ovy] = offsets(n);
        // theta' = w, x' = vx, y' = vy.
        for i in 0..n {
            emit(i, ow + i, 1.0);
            emit(ox + i, ovx + i, 1.0);
            emit(oy + i, ovy + i, 1.0);
        }
        let kinds = [0, ow, ox, oy, ovx, ovy];
        let rows = [ow, ovx, ovy];
        let mut guard = self.scratch.borrow_mut();
        let s = &mut *guard;
        for colour in 0..3 {
            for &kind in &kinds {
                for (d, &yi) in s.dual_y.iter_mut().zip(y) {
                    *d = Dual::new(yi, 0.0);
                }
                for j in (colour..n).step_by(3) {
                    s.dual_y[kind + j].d = 1.0;
                }
                rhs_generic(&self.springs, &s.dual_y, &mut s.dual_dy, &mut s.dual_sc);
                for j in (colour..n).step_by(3) {
                    for i in j.saturating_sub(1)..(j + 2).min(n) {
                        for &row in &rows {
                            emit(row + i, kind + j, s.dual_dy[row + i].d);
                        }
                    }
                }
            }
        }
    }
}

/// The rigid chain's static joint forces `F_k` (force of joint `k` on rod
/// `k`, physical units) in the shape `phi`, the tip held by the force that
/// balances the rods' moments best (least squares over the rods; exact for
/// a shape in static equilibrium, such as the catenary, the hanging and the
/// folded starts). Returns the forces and the holding force `H` on the tip.
fn static_forces(chain: &Chain, phi: &[f64]) -> (Vec<Vec2>, Vec2) {
    let n = phi.len();
    let (l, m, g) = (chain.rod_length(), chain.mass(), chain.gravity());
    let kb = chain.bending_spring();
    // F_i = -H + (n - i) m g (0, 1); the moment of rod i about its centre,
    // -(l/2) u_i x (F_i + F_{i+1}) + (EI/l) D_i(phi) = 0, is linear in H:
    // l (s_i Hx - c_i Hy) = (EI/l) D_i - (l/2) c_i (2n - 2i - 1) m g.
    let (mut nxx, mut nxy, mut nyy, mut rx, mut ry) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (i, &p) in phi.iter().enumerate() {
        let (s, c) = sin_cos(p);
        let (ax, ay) = (l * s, -l * c);
        let b = kb * damping_stencil(phi, i) - 0.5 * l * c * (2 * (n - i) - 1) as f64 * m * g;
        nxx += ax * ax;
        nxy += ax * ay;
        nyy += ay * ay;
        rx += ax * b;
        ry += ay * b;
    }
    let tr = nxx + nyy;
    let det = nxx * nyy - nxy * nxy;
    let h = if det > 1e-12 * tr * tr {
        [(nyy * rx - nxy * ry) / det, (nxx * ry - nxy * rx) / det]
    } else if tr > 0.0 {
        // Rank one (every rod parallel): the least-norm solution.
        [rx / tr, ry / tr]
    } else {
        [0.0, 0.0]
    };
    let forces = (0..n)
        .map(|i| [-h[0], -h[1] + (n - i) as f64 * m * g])
        .collect();
    (forces, h)
}

/// The elastic chain's state at the start `state` (angles and rates of the
/// rigid description): the rods at the angles and rates given, each gap
/// pre-stretched by the static force of its joint, `d_k = -F_k / K`
/// (`static_forces`: the tip held as the start holds it), with zero gap
/// rates. A start in static equilibrium (hanging, catenary, folded) is then
/// the elastic chain's own equilibrium, held at the tip by the same force.
///
/// Panics unless `chain` is elastic and `state` has `chain.links` angles and
/// rates (as `solve` checks first).
pub fn start_state(chain: &Chain, state: &State) -> Vec<f64> {
    let n = chain.links();
    let k = chain.joint_stiffness().unwrap_or(f64::INFINITY);
    let h = 0.5 * chain.rod_length();
    let (forces, _) = static_forces(chain, &state.angles);
    let [_, ow, owk, ox, oy, ovx, ovy] = offsets(n);
    let mut y = vec![0.0; 6 * n + 1];
    y[..n].copy_from_slice(&state.angles);
    y[ow..owk].copy_from_slice(&state.rates);
    let (mut ex, mut ey, mut evx, mut evy) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..n {
        let (s, c) = sin_cos(state.angles[i]);
        let w = state.rates[i];
        let [fx, fy] = forces[i];
        let (x, yy) = (ex - fx / k + h * c, ey - fy / k + h * s);
        let (vx, vy) = (evx - h * s * w, evy + h * c * w);
        (y[ox + i], y[oy + i], y[ovx + i], y[ovy + i]) = (x, yy, vx, vy);
        (ex, ey, evx, evy) = (x + h * c, yy + h * s, vx - h * s * w, vy + h * c * w);
    }
    y
}

/// The force that holds the tip of the start `state` still (physical
/// units): what [`start_state`]'s pre-stretch assumes. A chain released at
/// `t = 0` starts without it.
pub fn holding_force(chain: &Chain, state: &State) -> Vec2 {
    static_forces(chain, &state.angles).1
}

/// The joints `r_0 = p0, r_1, .., r_n` of an elastic state `y` with the pivot
/// at `p0`: `r_0` is the pivot, `r_k` (`0 < k < n`) the midpoint of the gap
/// between rods `k - 1` and `k`, `r_n` the end of the last rod (the tip).
pub fn joints(chain: &Chain, p0: Vec2, y: &[f64]) -> Vec<Vec2> {
    let n = chain.links();
    let h = 0.5 * chain.rod_length();
    let [_, _, _, ox, oy, _, _] = offsets(n);
    let mut out = Vec::with_capacity(n + 1);
    out.push(p0);
    for k in 1..=n {
        let (s0, c0) = sin_cos(y[k - 1]);
        let end = [y[ox + k - 1] + h * c0, y[oy + k - 1] + h * s0];
        let r = if k < n {
            let (s1, c1) = sin_cos(y[k]);
            let start = [y[ox + k] - h * c1, y[oy + k] - h * s1];
            [0.5 * (end[0] + start[0]), 0.5 * (end[1] + start[1])]
        } else {
            end
        };
        out.push([p0[0] + r[0], p0[1] + r[1]]);
    }
    out
}

/// The tip, the end of the last rod, for the pivot at `p0`.
pub fn tip(chain: &Chain, p0: Vec2, y: &[f64]) -> Vec2 {
    let n = chain.links();
    let h = 0.5 * chain.rod_length();
    let [_, _, _, ox, oy, _, _] = offsets(n);
    let (s, c) = sin_cos(y[n - 1]);
    [p0[0] + y[ox + n - 1] + h * c, p0[1] + y[oy + n - 1] + h * s]
}

/// The tip velocity `c_{n-1}' + h w_{n-1} v_{n-1}`.
pub fn tip_velocity(chain: &Chain, y: &[f64]) -> Vec2 {
    let n = chain.links();
    let h = 0.5 * chain.rod_length();
    let [_, ow, _, _, _, ovx, ovy] = offsets(n);
    let (s, c) = sin_cos(y[n - 1]);
    let w = y[ow + n - 1];
    [y[ovx + n - 1] - h * s * w, y[ovy + n - 1] + h * c * w]
}

/// The tip acceleration, from the state `y` and its derivative `f`.
pub fn tip_acceleration(chain: &Chain, y: &[f64], f: &[f64]) -> Vec2 {
    let n = chain.links();
    let h = 0.5 * chain.rod_length();
    let [_, ow, _, _, _, ovx, ovy] = offsets(n);
    let (s, c) = sin_cos(y[n - 1]);
    let (w, a) = (y[ow + n - 1], f[ow + n - 1]);
    [
        f[ovx + n - 1] + h * (-a * s - w * w * c),
        f[ovy + n - 1] + h * (a * c - w * w * s),
    ]
}

/// The forces of the joints `0..=n` on the rod after each (physical units;
/// joint `n`, the free tip, is zero): the springs' `F_k = -K d_k - C d_k'`.
pub fn joint_forces(chain: &Chain, y: &[f64]) -> Vec<Vec2> {
    let n = chain.links();
    let p = Springs::of(chain);
    let [_, ow, _, ox, oy, ovx, ovy] = offsets(n);
    let mut out = Vec::with_capacity(n + 1);
    let (mut ex, mut ey, mut evx, mut evy) = (0.0, 0.0, 0.0, 0.0);
    for k in 0..n {
        let (s, c) = sin_cos(y[k]);
        let (hs, hc) = (p.h * s, p.h * c);
        let w = y[ow + k];
        let (x, yy, vx, vy) = (y[ox + k], y[oy + k], y[ovx + k], y[ovy + k]);
        let (dx, dyy) = (x - hc - ex, yy - hs - ey);
        let (ddx, ddy) = (vx + hs * w - evx, vy - hc * w - evy);
        out.push([-p.k * dx - p.c * ddx, -p.k * dyy - p.c * ddy]);
        (ex, ey, evx, evy) = (x + hc, yy + hs, vx - hs * w, vy + hc * w);
    }
    out.push([0.0, 0.0]);
    out
}

/// The force of the pivot on the first rod, `F_1 = -K d_1 - C d_1'`
/// (physical units; the support feels `-F_1`): joint 0 of
/// [`joint_forces`], in O(1).
pub fn pivot_force(chain: &Chain, y: &[f64]) -> Vec2 {
    let n = chain.links();
    let p = Springs::of(chain);
    let [_, ow, _, ox, oy, ovx, ovy] = offsets(n);
    let (s, c) = sin_cos(y[0]);
    let (hs, hc) = (p.h * s, p.h * c);
    let w = y[ow];
    let (dx, dyy) = (y[ox] - hc, y[oy] - hs);
    let (ddx, ddy) = (y[ovx] + hs * w, y[ovy] - hc * w);
    [-p.k * dx - p.c * ddx, -p.k * dyy - p.c * ddy]
}

/// The energy `T + V + U_el + U_b` of the elastic state `y` (zero
/// potential at the pivot's height).
pub fn energy(chain: &Chain, y: &[f64]) -> f64 {
    let n = chain.links();
    let p = Springs::of(chain);
    let m = chain.mass();
    let [_, ow, _, ox, oy, ovx, ovy] = offsets(n);
    let (mut t, mut v, mut u) = (0.0, 0.0, 0.0);
    let (mut ex, mut ey) = (0.0, 0.0);
    for i in 0..n {
        let (s, c) = sin_cos(y[i]);
        let w = y[ow + i];
        let (x, yy, vx, vy) = (y[ox + i], y[oy + i], y[ovx + i], y[ovy + i]);
        t += m * (vx * vx + vy * vy) + w * w / p.inv_j;
        v += yy;
        let (dx, dyy) = (x - p.h * c - ex, yy - p.h * s - ey);
        u += dx * dx + dyy * dyy;
        (ex, ey) = (x + p.h * c, yy + p.h * s);
    }
    let bend: f64 = y[..n].windows(2).map(|q| (q[1] - q[0]).powi(2)).sum();
    0.5 * t + m * p.g * v + 0.5 * p.k * u + 0.5 * p.kb * bend
}

/// The rigid chain's joint forces in the state `[phi, w, ..]` (physical
/// units, joint `0..=n` on the rod after it; the tip's is zero): the banded
/// DAE's algebraic unknowns, made consistent by the O(n) recursion.
pub fn rigid_joint_forces(chain: &Chain, y: &[f64]) -> Vec<Vec2> {
    rigid_joint_forces_at(chain, 0.0, false, y)
}

/// [`rigid_joint_forces`] at time `t` (which places a moving pivot), the
/// pivot let go (`free`: its force is zero) or held.
pub fn rigid_joint_forces_at(chain: &Chain, t: f64, free: bool, y: &[f64]) -> Vec<Vec2> {
    let n = chain.links();
    let dae = ChainDae::new(chain).released(free);
    let mut full = vec![0.0; dae.dim()];
    full[..2 * n].copy_from_slice(&y[..2 * n]);
    dae.make_consistent_at(t, &mut full, &mut Workspace::new(n));
    let ml = chain.mass() * chain.rod_length();
    let mut out: Vec<Vec2> = dae
        .joint_forces(&full)
        .into_iter()
        .map(|[fx, fy]| [ml * fx, ml * fy])
        .collect();
    out.push([0.0, 0.0]);
    out
}

/// Joint forces as `[tension, shear]` in the frame of the rod after each
/// joint: tension `-F_k . u_k` (positive when the joint pulls rod `k` back
/// toward rod `k - 1` or the pivot), shear `F_k . v_k` (`v_k` the rod's
/// normal, `u_k` rotated by +90 degrees). Joint `n` (the free tip) is
/// `[0, 0]`. `phi` are the rods' angles.
pub fn tension_shear(phi: &[f64], forces: &[Vec2]) -> Vec<Vec2> {
    forces
        .iter()
        .enumerate()
        .map(|(k, f)| match phi.get(k) {
            Some(&p) => {
                let (s, c) = sin_cos(p);
                [-(f[0] * c + f[1] * s), -f[0] * s + f[1] * c]
            }
            None => [0.0, 0.0],
        })
        .collect()
}
