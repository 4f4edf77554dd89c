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
//! F_k = -K_k d_k - C_k d_k'                          force of joint k on rod k
//! ```
//!
//! with `K_k = EA / l` and `C_k = eta / l` (`eta = chain.axial_damping`)
//! between two rods and `K_0 = 2 EA / l`, `C_0 = 2 eta / l` at the pivot:
//! each joint carries the rope from centre to centre, the pivot the half rod
//! to rod 0's centre, so that the axial frequencies and the self-weight
//! stretch converge to the rope's at second order in `1/n`
//! (`docs/model.md`, "Where the compliance sits"). Rod `k - 1` gets `-F_k`. The tip (joint `n`) is free: `F_n = 0`. The equations
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
//! `V = m g sum c_i.y`, `U_el = sum (K_k / 2) |d_k|^2`,
//! `U_b = (EI / 2l) sum (theta_{i+1} - theta_i)^2` balances the work
//! `W' = 2R = sum C_k |d_k'|^2 + r sum (w_{i+1} - w_i)^2`. As `EA -> inf` at
//! fixed `n` the gaps close and this is the rigid pinned chain.
//!
//! Every key of issue 18 works here too (`docs/model.md`, "Elastic links
//! with a rod profile, a tip mass and a moving or released pivot"):
//!
//! * a rod profile: rod `i` has `m_i`, `J_i = m_i l_i^2 / 12`, `h_i = l_i / 2`;
//!   joint `k` carries its share `s_k = (l_{k-1} + l_k) / 2` of the rope
//!   (`s_0 = l_0 / 2`), `K_k = EA / s_k`, `C_k = eta / s_k`, and its bending
//!   spring is `EI / s_k`;
//! * a tip mass `M`: the last rod and `M` are one rigid body (`tip_body`);
//! * a driven pivot: positions and velocities are relative to `P0(t)`, every
//!   rod feels `-m_i P0''(t)`, and `W' = 2R - F_0 . P0'` counts the support's
//!   work ([`frame_energy`] turns the energy into the inertial frame's);
//! * a released pivot: joint 0 has no spring (`solve` splits the run at `t_r`).
//!
//! Equal rods with no tip mass and a fixed pivot keep the arithmetic of the
//! scalars above bit for bit.
//!
//! The state is laid out `[theta (n), w (n), W, x (n), y (n), vx (n), vy (n)]`
//! (`6 n + 1` numbers): its first `2 n + 1` mean what the rigid chain's do
//! (angles, rates, dissipated work), so that a sample of either model reads
//! its angles the same way.

use std::cell::RefCell;

use crate::chain::Chain;
use crate::dae::ChainDae;
use crate::dynamics::Workspace;
use crate::floor::FloorTerm;
use crate::kinematics::Vec2;
use crate::load::{Bending, FloorContact, Kinematics, Load, Loads, RodForce, Units};
use crate::pivot::Pivot;
use crate::scalar::{sin_cos, Dual, Lanes, Scalar};
use crate::state::State;
use fc_methods::{BandedDae, Measured, OdeSystem, Problem, SemiExplicitDae};

/// Per-rod values of a profiled elastic chain (physical units): rod `i`'s
/// half length, inverse mass and inverse moment of inertia, and joint `k`'s
/// spring and dashpot.
#[derive(Clone, Debug)]
struct PerRod {
    /// `h_i = l_i / 2`.
    h: Vec<f64>,
    /// `1 / m_i`.
    inv_m: Vec<f64>,
    /// `1 / J_i`, `J_i = m_i l_i^2 / 12`.
    inv_j: Vec<f64>,
    /// Joint `k`'s spring `K_k = EA / s_k`, `s_k = (l_{k-1} + l_k) / 2`
    /// (centre to centre) and `s_0 = l_0 / 2` (pivot to rod 0's centre).
    k: Vec<f64>,
    /// Joint `k`'s dashpot `C_k = eta / s_k`.
    c: Vec<f64>,
}

/// The constants of the elastic chain's right-hand side.
#[derive(Clone, Debug)]
struct Springs {
    n: usize,
    /// Half the rod length `h = l / 2` (equal rods).
    h: f64,
    /// `1 / m` (equal rods).
    inv_m: f64,
    /// `1 / J`, `J = m l^2 / 12` (equal rods).
    inv_j: f64,
    g: f64,
    /// Joint spring `K = EA / l` (equal rods).
    k: f64,
    /// Joint dashpot `C = eta / l` (equal rods).
    c: f64,
    /// The pivot joint's spring `K_0 = 2 EA / l` (equal rods): it carries
    /// half a rod of the rope, from the pivot to rod 0's centre.
    k0: f64,
    /// The pivot joint's dashpot `C_0 = 2 eta / l` (equal rods).
    c0: f64,
    /// The loads (physical units): the field `(0, -g)`, joint friction,
    /// bending springs, the floor (set by the model, placed for its start).
    loads: Loads,
    /// The per-rod values of a profiled chain; `None` for equal rods, whose
    /// arithmetic is then the scalars above, bit for bit.
    rods: Option<std::sync::Arc<PerRod>>,
    /// The last rod's mass `m_{n-1}` (with the tip mass, one rigid body).
    m_last: f64,
    /// The tip mass `M_t` (0: none).
    tip_mass: f64,
    /// The pivot's prescribed motion (read only when `driven`).
    pivot: Pivot,
    /// True when the pivot moves: the state is then relative to `P0(t)`,
    /// and every rod feels the frame's acceleration `-m_i P0''(t)`.
    driven: bool,
    /// True once the pivot is let go: joint 0 has no spring.
    released: bool,
}

impl Springs {
    fn of(chain: &Chain) -> Self {
        let l = chain.rod_length();
        let m = chain.mass();
        let rods = chain.rods().map(|r| {
            let ea = chain.axial_stiffness().unwrap_or(0.0);
            let eta = chain.axial_damping();
            let n = r.length.len();
            let li = |i: usize| l * r.length[i];
            let mi = |i: usize| m * r.mass[i];
            // Joint k's share of the rope: centre to centre, half a rod at
            // the pivot.
            let share = |k: usize| match k {
                0 => 0.5 * li(0),
                _ => 0.5 * (li(k - 1) + li(k)),
            };
            std::sync::Arc::new(PerRod {
                h: (0..n).map(|i| 0.5 * li(i)).collect(),
                inv_m: (0..n).map(|i| 1.0 / mi(i)).collect(),
                inv_j: (0..n).map(|i| 12.0 / (mi(i) * li(i) * li(i))).collect(),
                k: (0..n).map(|k| ea / share(k)).collect(),
                c: (0..n).map(|k| eta / share(k)).collect(),
            })
        });
        let n = chain.links();
        Self {
            n,
            h: 0.5 * l,
            inv_m: 1.0 / m,
            inv_j: 12.0 / (m * l * l),
            g: chain.gravity(),
            // A rigid chain has no springs: K = 0 makes this a free fall,
            // and no caller builds one (see `ElasticSystem::new`).
            k: chain.joint_stiffness().unwrap_or(0.0),
            c: chain.joint_damping(),
            k0: 2.0 * chain.joint_stiffness().unwrap_or(0.0),
            c0: 2.0 * chain.joint_damping(),
            loads: Loads::of(chain, Units::Physical),
            rods,
            m_last: rod_mass(chain, n - 1),
            tip_mass: chain.tip_mass(),
            pivot: *chain.pivot(),
            driven: chain.pivot().is_driven(),
            // Let go at t = 0: no joint-0 spring from the start (a later
            // release is `ElasticSystem::set_released`'s, in `solve`).
            released: chain.pivot().release == Some(0.0),
        }
        .with_floor(
            chain
                .floor()
                .and_then(|f| f.height.map(|h| f.term(h, [0.0, 0.0]))),
        )
    }

    /// These springs with the floor `floor` (in the anchor's frame).
    fn with_floor(mut self, floor: Option<FloorTerm>) -> Self {
        self.loads.floor = floor.map(FloorContact::placed);
        self
    }

    #[inline(always)]
    fn h(&self, i: usize) -> f64 {
        self.rods.as_ref().map_or(self.h, |r| r.h[i])
    }
    #[inline(always)]
    fn inv_m(&self, i: usize) -> f64 {
        self.rods.as_ref().map_or(self.inv_m, |r| r.inv_m[i])
    }
    #[inline(always)]
    fn inv_j(&self, i: usize) -> f64 {
        self.rods.as_ref().map_or(self.inv_j, |r| r.inv_j[i])
    }
    #[inline(always)]
    fn k(&self, i: usize) -> f64 {
        match &self.rods {
            None if i == 0 => self.k0,
            None => self.k,
            Some(r) => r.k[i],
        }
    }
    #[inline(always)]
    fn c(&self, i: usize) -> f64 {
        match &self.rods {
            None if i == 0 => self.c0,
            None => self.c,
            Some(r) => r.c[i],
        }
    }
}

/// Rod `i`'s mass `m_i` (physical units): `m`, or `mu_i m` for a profile.
pub fn rod_mass(chain: &Chain, i: usize) -> f64 {
    match chain.rods() {
        None => chain.mass(),
        Some(r) => chain.mass() * r.mass[i],
    }
}

/// Rod `i`'s half length `h_i = l_i / 2` (physical units).
pub fn rod_half_length(chain: &Chain, i: usize) -> f64 {
    match chain.rods() {
        None => 0.5 * chain.rod_length(),
        Some(r) => 0.5 * (chain.rod_length() * r.length[i]),
    }
}

/// Joint `k`'s spring and dashpot `(K_k, C_k) = (EA, eta) / s_k`: joint
/// `k >= 1` carries the rope between the centres of rods `k - 1` and `k`,
/// `s_k = (l_{k-1} + l_k) / 2`, and the pivot joint the half rod from the
/// pivot to rod 0's centre, `s_0 = l_0 / 2` (`docs/model.md`, "Where the
/// compliance sits"). Equal rods: `K = EA / l`, `K_0 = 2 K`; 0 for rigid
/// links.
pub fn joint_spring(chain: &Chain, k: usize) -> (f64, f64) {
    let share = match chain.rods() {
        None => (if k == 0 { 0.5 } else { 1.0 }) * chain.rod_length(),
        Some(r) => {
            let li = |i: usize| chain.rod_length() * r.length[i];
            match k {
                0 => 0.5 * li(0),
                _ => 0.5 * (li(k - 1) + li(k)),
            }
        }
    };
    match chain.axial_stiffness() {
        None => (0.0, chain.joint_damping()),
        Some(ea) => (ea / share, chain.axial_damping() / share),
    }
}

/// The state's blocks, by offset.
fn offsets(n: usize) -> [usize; 7] {
    // theta, w, W, x, y, vx, vy
    [0, n, 2 * n, 2 * n + 1, 3 * n + 1, 4 * n + 1, 5 * n + 1]
}

/// `dy = f(y)` at `t` for the elastic chain, over any scalar (`f64`, or a
/// dual number for the exact Jacobian-vector product). One pass over the
/// joints, no allocation: `sc` holds `(sin, cos)` of the angles.
fn rhs_generic<T: Scalar>(p: &Springs, t: f64, y: &[T], dy: &mut [T], sc: &mut [(T, T)]) {
    T::sin_cos_all(&y[..p.n], sc);
    rhs_with_trig(p, t, y, dy, sc);
}

/// [`rhs_generic`] with `sc` already `(sin, cos)` of the angles (the
/// Jacobian's sweeps share them: [`ElasticDae::jacobian_values`]).
fn rhs_with_trig<T: Scalar>(p: &Springs, t: f64, y: &[T], dy: &mut [T], sc: &[(T, T)]) {
    let n = p.n;
    let [_, ow, owk, ox, oy, ovx, ovy] = offsets(n);
    let w = &y[ow..owk];
    let zero = T::cst(0.0);
    // The frame's velocity and acceleration `P0'(t), P0''(t)` (driven only).
    let [_, v0, a0] = if p.driven {
        p.pivot.drive(t)
    } else {
        [[0.0; 2]; 3]
    };
    // The support's power on the chain, `F_0 . P0'`.
    let mut support = zero;
    let view = StateView {
        p,
        y,
        sc,
        frame: if p.driven {
            Some(p.pivot.drive(t))
        } else {
            None
        },
    };
    // Force of joint k on rod k, from the previous iteration: F_{k-1}.
    let (mut fpx, mut fpy) = (zero, zero);
    // End of rod k - 1 and its velocity (the pivot for k = 0).
    let (mut ex, mut ey, mut evx, mut evy) = (zero, zero, zero, zero);
    let mut dissipated = zero;
    for k in 0..=n {
        // The force of joint k on rod k (zero at the free tip, k = n, and
        // at a released pivot).
        let (fx, fy) = if k < n {
            let (s, c) = sc[k];
            let h = p.h(k);
            let (hs, hc) = (s * h, c * h);
            let (hsw, hcw) = (hs * w[k], hc * w[k]);
            let (x, yy, vx, vy) = (y[ox + k], y[oy + k], y[ovx + k], y[ovy + k]);
            let (dx, dyy) = (x - hc - ex, yy - hs - ey);
            let (ddx, ddy) = ((vx + hsw) - evx, (vy - hcw) - evy);
            // This rod's end, for the next joint.
            (ex, ey, evx, evy) = (x + hc, yy + hs, vx - hsw, vy + hcw);
            if k == 0 && p.released {
                (zero, zero)
            } else {
                let (kk, cc) = (p.k(k), p.c(k));
                dissipated += (ddx * ddx + ddy * ddy) * cc;
                let f = (-(dx * kk) - ddx * cc, -(dyy * kk) - ddy * cc);
                if k == 0 && p.driven {
                    support = f.0 * v0[0] + f.1 * v0[1];
                }
                f
            }
        } else {
            (zero, zero)
        };
        if k > 0 {
            // Rod i = k - 1 is complete: F_i at its start, -F_{i+1} at its end.
            let i = k - 1;
            let (s, c) = sc[i];
            let (sx, sy) = (fpx + fx, fpy + fy);
            // The joints' moment about the centre, then the loads: their
            // torques, their force joining the force at the rod's start,
            // their power.
            let mut load = RodForce {
                force: [fpx, fpy],
                torque: -((c * sy - s * sx) * p.h(i)),
                power: dissipated,
            };
            p.loads.add_to_rod(i, &view, &mut load);
            let [fpx, fpy] = load.force;
            let torque = load.torque;
            dissipated = load.power;
            dy[i] = w[i];
            dy[ox + i] = y[ovx + i];
            dy[oy + i] = y[ovy + i];
            if k == n && p.tip_mass != 0.0 {
                // The last rod and the tip mass, one rigid body (fx = fy = 0).
                let [ax, ay, al] = tip_body(p, (s, c), w[i], (fpx, fpy), torque, a0);
                dy[ow + i] = al;
                dy[ovx + i] = ax;
                dy[ovy + i] = ay;
            } else {
                let (inv_m, inv_j) = (p.inv_m(i), p.inv_j(i));
                dy[ow + i] = torque * inv_j;
                dy[ovx + i] = (fpx - fx) * inv_m;
                dy[ovy + i] = (fpy - fy) * inv_m - T::cst(-p.loads.field.y());
                if p.driven {
                    dy[ovx + i] -= T::cst(a0[0]);
                    dy[ovy + i] -= T::cst(a0[1]);
                }
            }
        }
        (fpx, fpy) = (fx, fy);
    }
    // The joints' power (friction) after the rods'.
    dy[owk] = p.loads.joint_power(&view, dissipated);
    if p.driven {
        dy[owk] -= support;
    }
}

/// The elastic state's kinematics as the loads read them (physical units;
/// positions relative to the start's anchor, velocities in the inertial
/// frame: a driven pivot's motion added).
struct StateView<'a, T> {
    p: &'a Springs,
    y: &'a [T],
    sc: &'a [(T, T)],
    /// The driven pivot's `[d, v, a]` at `t` (`None`: not driven).
    frame: Option<[Vec2; 3]>,
}

impl<T: Scalar> Kinematics<T> for StateView<'_, T> {
    #[inline(always)]
    fn angles(&self) -> &[T] {
        &self.y[..self.p.n]
    }
    #[inline(always)]
    fn rates(&self) -> &[T] {
        let n = self.p.n;
        &self.y[n..2 * n]
    }
    #[inline(always)]
    fn sin_cos(&self, i: usize) -> (T, T) {
        self.sc[i]
    }
    #[inline(always)]
    fn half_length(&self, i: usize) -> f64 {
        self.p.h(i)
    }
    #[inline(always)]
    fn mass(&self, i: usize) -> f64 {
        1.0 / self.p.inv_m(i)
    }
    #[inline(always)]
    fn torque_unit(&self, _i: usize) -> f64 {
        1.0
    }
    #[inline(always)]
    fn centre(&self, i: usize) -> [T; 2] {
        let [_, _, _, ox, oy, _, _] = offsets(self.p.n);
        let c = [self.y[ox + i], self.y[oy + i]];
        match self.frame {
            None => c,
            Some([d, _, _]) => [c[0] + T::cst(d[0]), c[1] + T::cst(d[1])],
        }
    }
    #[inline(always)]
    fn centre_velocity(&self, i: usize) -> [T; 2] {
        let [_, _, _, _, _, ovx, ovy] = offsets(self.p.n);
        let v = [self.y[ovx + i], self.y[ovy + i]];
        match self.frame {
            None => v,
            Some([_, v0, _]) => [v[0] + T::cst(v0[0]), v[1] + T::cst(v0[1])],
        }
    }
}

/// The last rod (mass `m`, half length `h`, `J = m h^2 / 3`) and the tip
/// mass `M` at its end, one rigid body in the rod's coordinates `(c, theta)`:
/// with `e = M h`, `m_t = m + M`, the field `G = (a0_x, g + a0_y)` (gravity
/// and the frame's acceleration), the force `F` of the last joint on the rod
/// and the joints' torque `tau` about the rod's centre,
///
/// ```text
/// m_t c'' + e (alpha v - w^2 u) = F - m_t G =: Q_c
/// (J + M h^2) alpha + e v . c'' = tau - e G . v =: Q_theta
/// alpha = (Q_theta - e v . Q_c / m_t) / (J + m M h^2 / m_t)
/// c''   = (Q_c + e (w^2 u - alpha v)) / m_t
/// ```
///
/// (Lagrange's equations of `T = m |c'|^2/2 + J w^2/2 + M |c' + h w v|^2/2`;
/// the 3x3 mass matrix solved in closed form). Returns `[c''_x, c''_y, alpha]`.
#[inline(always)]
fn tip_body<T: Scalar>(
    p: &Springs,
    (s, c): (T, T),
    w: T,
    (fx, fy): (T, T),
    torque: T,
    a0: Vec2,
) -> [T; 3] {
    let (m, mm) = (p.m_last, p.tip_mass);
    let h = p.h(p.n - 1);
    let mt = m + mm;
    let e = mm * h;
    let (gx, gy) = (a0[0], -p.loads.field.y() + a0[1]);
    let (qx, qy) = (fx - T::cst(mt * gx), fy - T::cst(mt * gy));
    let q_theta = torque - (c * gy - s * gx) * e;
    let den = m * h * h / 3.0 + m * mm * h * h / mt;
    let alpha = (q_theta - (c * qy - s * qx) * (e / mt)) * (1.0 / den);
    let ew2 = w * w * e;
    let ax = (qx + ew2 * c + alpha * s * e) * (1.0 / mt);
    let ay = (qy + ew2 * s - alpha * c * e) * (1.0 / mt);
    [ax, ay, alpha]
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

    /// Lets the pivot go (`true`: joint 0 has no spring from now on) or
    /// holds it.
    pub fn set_released(&mut self, released: bool) {
        self.springs.released = released;
    }

    /// Sets the floor, placed in the anchor's frame (`crate::floor`;
    /// state positions are relative to `P0`).
    pub fn set_floor(&mut self, floor: Option<FloorTerm>) {
        self.springs.loads.floor = floor.map(FloorContact::placed);
    }

    /// `dy = f(y)` at `t` (`t` read only for a driven pivot): O(n),
    /// allocation-free.
    pub fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        rhs_generic(&self.springs, t, y, dy, &mut self.sc);
    }

    /// The exact Jacobian-vector product, by dual numbers through the same
    /// right-hand side.
    pub fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        for ((d, &yi), &vi) in self.dual_y.iter_mut().zip(y).zip(v) {
            *d = Dual::new(yi, vi);
        }
        rhs_generic(
            &self.springs,
            t,
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
            dae: Box::new(
                ElasticDae::new(&self.chain)
                    .released(self.springs.released)
                    .floor(self.springs.loads.floor.map(|f| f.term)),
            ),
            y0: y0.to_vec(),
        })
    }

    /// The pivot force's magnitude while the pivot holds: the force a
    /// study reads (`Summary::pivot_force_max`, the snap's tension) is
    /// `K d_1 + C d_1'`, so a position error `e` moves it by `K e`, which
    /// the configuration's tolerance (`rtol |x|`) leaves unbounded on a
    /// stiff link (`K e / |F| ~ rtol EA / T`, 1e6 on issue 49's steel
    /// rope): gen-alpha bounds its error too (docs/model.md, "The
    /// generalized-alpha method").
    fn measured(&self) -> Option<Box<dyn Measured>> {
        if self.springs.released {
            return None;
        }
        Some(Box::new(PivotForceMeasure(self.chain.clone())))
    }
}

/// The pivot force's magnitude `|F_1|` ([`pivot_force_at`]) as a quantity
/// gen-alpha's error control bounds ([`Problem::measured`]).
struct PivotForceMeasure(Chain);

impl Measured for PivotForceMeasure {
    fn count(&self) -> usize {
        1
    }
    fn values(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let [a, b] = pivot_force_at(&self.0, t, y);
        out[0] = a.hypot(b);
    }
}

/// Scratch of [`ElasticDae`]: its trait's methods take `&self`. The
/// Jacobian's sweeps carry a lane per kind of coordinate.
#[derive(Clone, Debug)]
struct DaeScratch {
    sc: Vec<(f64, f64)>,
    lanes_y: Vec<Lanes<6>>,
    lanes_dy: Vec<Lanes<6>>,
    lanes_sc: Vec<(Lanes<6>, Lanes<6>)>,
}

/// The elastic chain for the O(n) sparse BDF: every unknown differential,
/// and the Jacobian's banded pattern (each rod's accelerations depend on
/// its own and its two neighbours' coordinates and rates) filled exactly by
/// three sweeps of the right-hand side over dual numbers with six lanes,
/// one sweep per rod modulo 3 (rods three apart share no row) and one lane
/// per kind of coordinate.
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
                lanes_y: vec![Lanes::default(); dim],
                lanes_dy: vec![Lanes::default(); dim],
                lanes_sc: vec![(Lanes::default(), Lanes::default()); n],
            }),
        }
    }

    /// This DAE with the pivot let go (`true`: no joint-0 spring) or held.
    pub fn released(mut self, released: bool) -> Self {
        self.springs.released = released;
        self
    }

    /// This DAE with the floor `floor` (in the anchor's frame).
    pub fn floor(mut self, floor: Option<FloorTerm>) -> Self {
        self.springs.loads.floor = floor.map(FloorContact::placed);
        self
    }
}

impl SemiExplicitDae for ElasticDae {
    fn dim(&self) -> usize {
        6 * self.springs.n + 1
    }
    fn differential_dim(&self) -> usize {
        6 * self.springs.n + 1
    }
    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) {
        ElasticDae::rhs_at(self, t, y, out)
    }
    fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        ElasticDae::jacobian_entries_at(self, t, y, emit)
    }
    /// The entries' values written in order, with no call per entry.
    fn jacobian_values(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let mut k = 0;
        self.sweeps(t, y, |_, _, v| {
            if let Some(o) = out.get_mut(k) {
                *o = v;
            }
            k += 1;
        });
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
    /// `out = f(y)` at `t = 0`, as [`ElasticSystem::rhs`].
    pub fn rhs(&self, y: &[f64], out: &mut [f64]) {
        self.rhs_at(0.0, y, out);
    }

    /// `out = f(y)` at `t`, as [`ElasticSystem::rhs`].
    pub fn rhs_at(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let mut s = self.scratch.borrow_mut();
        rhs_generic(&self.springs, t, y, out, &mut s.sc);
    }

    /// Every entry of `df/dy` at `y` but the row of `W` (dense, and read by
    /// no other equation: left out of the Newton matrix as in `ChainDae`),
    /// as `emit(row, column, value)`; the entries and their order depend
    /// on `n` only.
    pub fn jacobian_entries(&self, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        self.jacobian_entries_at(0.0, y, emit);
    }

    /// [`ElasticDae::jacobian_entries`] at `t` (the entries do not depend
    /// on `t`: a driven pivot's frame adds a force independent of the state).
    pub fn jacobian_entries_at(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        self.sweeps(t, y, emit);
    }

    /// The Jacobian's entries into `emit` (a static call per entry): three
    /// sweeps of the right-hand side, one per rod modulo 3, each over dual
    /// numbers with a lane per kind of coordinate, sharing the angles'
    /// sines and cosines (computed once, their derivatives set in the
    /// lanes that move the angles).
    fn sweeps(&self, t: f64, y: &[f64], mut emit: impl FnMut(usize, usize, f64)) {
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
        f64::sin_cos_all(&y[..n], &mut s.sc);
        for colour in 0..3 {
            // One sweep per colour, a lane per kind: lane `q` moves the
            // coordinate `kinds[q]` of the rods `colour, colour + 3, ..`.
            for (d, &yi) in s.lanes_y.iter_mut().zip(y) {
                *d = Lanes::cst(yi);
            }
            for (q, &kind) in kinds.iter().enumerate() {
                for j in (colour..n).step_by(3) {
                    s.lanes_y[kind + j].d[q] = 1.0;
                }
            }
            // `(sin, cos)` of the angles with their lanes, as
            // `Lanes::sin_cos` gives them (bit for bit).
            for ((ds, &(sn, cs)), yd) in s.lanes_sc.iter_mut().zip(&s.sc).zip(&s.lanes_y) {
                *ds = (
                    Lanes {
                        v: sn,
                        d: yd.d.map(|x| cs * x),
                    },
                    Lanes {
                        v: cs,
                        d: yd.d.map(|x| -sn * x),
                    },
                );
            }
            rhs_with_trig(&self.springs, t, &s.lanes_y, &mut s.lanes_dy, &s.lanes_sc);
            for (q, &kind) in kinds.iter().enumerate() {
                for j in (colour..n).step_by(3) {
                    for i in j.saturating_sub(1)..(j + 2).min(n) {
                        for &row in &rows {
                            emit(row + i, kind + j, s.lanes_dy[row + i].d[q]);
                        }
                    }
                }
            }
        }
    }
}

/// True when `chain` is a plain elastic chain: equal rods, no tip mass, a
/// fixed pivot. Its statics, readers and energy keep the arithmetic they
/// always had, bit for bit.
fn is_plain(chain: &Chain) -> bool {
    chain.rods().is_none() && chain.tip_mass() == 0.0 && chain.pivot().is_fixed()
}

/// The rigid chain's static joint forces `F_k` (force of joint `k` on rod
/// `k`, physical units) in the shape `phi`, the tip held by the force that
/// balances the rods' moments best (least squares over the rods; exact for
/// a shape in static equilibrium, such as the catenary, the hanging and the
/// folded starts). Returns the forces and the holding force `H` on the tip.
fn static_forces(chain: &Chain, phi: &[f64]) -> (Vec<Vec2>, Vec2) {
    if !is_plain(chain) {
        return static_forces_general(chain, phi);
    }
    let n = phi.len();
    let (l, m, g) = (chain.rod_length(), chain.mass(), chain.gravity());
    let loads = Loads::of(chain, Units::Physical);
    // F_i = -H + (n - i) m g (0, 1); the moment of rod i about its centre,
    // -(l/2) u_i x (F_i + F_{i+1}) + (EI/l) D_i(phi) = 0, is linear in H:
    // l (s_i Hx - c_i Hy) = (EI/l) D_i - (l/2) c_i (2n - 2i - 1) m g.
    let (mut nxx, mut nxy, mut nyy, mut rx, mut ry) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (i, &p) in phi.iter().enumerate() {
        let (s, c) = sin_cos(p);
        let (ax, ay) = (l * s, -l * c);
        let b = rest_torque(&loads, phi, i) - 0.5 * l * c * (2 * (n - i) - 1) as f64 * m * g;
        nxx += ax * ax;
        nxy += ax * ay;
        nyy += ay * ay;
        rx += ax * b;
        ry += ay * b;
    }
    let h = least_squares_holding([nxx, nxy, nyy], [rx, ry]);
    let forces = (0..n)
        .map(|i| [-h[0], -h[1] + (n - i) as f64 * m * g])
        .collect();
    (forces, h)
}

/// The loads' torque on rod `i` of a shape `phi` at rest, which the
/// statics balance with the field: the bending springs' (friction's and the
/// drag's vanish at rest; a start's floor contact is not counted).
fn rest_torque(loads: &Loads, phi: &[f64], i: usize) -> f64 {
    let Some(b) = &loads.bending else {
        return 0.0;
    };
    let mut f = RodForce::zero();
    b.add_to_rod(i, &ShapeView(phi), &mut f);
    f.torque
}

/// A shape at rest as a load reads it: its angles alone.
struct ShapeView<'a>(&'a [f64]);

impl Kinematics<f64> for ShapeView<'_> {
    fn angles(&self) -> &[f64] {
        self.0
    }
    fn rates(&self) -> &[f64] {
        &[]
    }
    fn sin_cos(&self, i: usize) -> (f64, f64) {
        sin_cos(self.0[i])
    }
    fn half_length(&self, _i: usize) -> f64 {
        0.0
    }
    fn mass(&self, _i: usize) -> f64 {
        0.0
    }
    fn torque_unit(&self, _i: usize) -> f64 {
        1.0
    }
    fn centre(&self, _i: usize) -> [f64; 2] {
        [0.0, 0.0]
    }
    fn centre_velocity(&self, _i: usize) -> [f64; 2] {
        [0.0, 0.0]
    }
}

/// The 2x2 normal equations `N H = r` of the holding force: `H`, or the
/// least-norm solution when every rod is parallel (rank one).
fn least_squares_holding([nxx, nxy, nyy]: [f64; 3], [rx, ry]: [f64; 2]) -> Vec2 {
    let tr = nxx + nyy;
    let det = nxx * nyy - nxy * nxy;
    if det > 1e-12 * tr * tr {
        [(nyy * rx - nxy * ry) / det, (nxx * ry - nxy * rx) / det]
    } else if tr > 0.0 {
        // Rank one (every rod parallel): the least-norm solution.
        [rx / tr, ry / tr]
    } else {
        [0.0, 0.0]
    }
}

/// [`static_forces`] with per-rod masses `m_i` and lengths `l_i`, a tip
/// mass `M_t`, each joint's bending spring, and the field
/// `G = (a0_x, g + a0_y)` of gravity and the pivot's acceleration at
/// `t = 0` (the rods feel `-m_i G`). With `S_i = M_t + sum_{j >= i} m_j`,
/// `F_i = -H + S_i G`, and rod `i`'s moment about its centre,
/// `-(l_i / 2) u_i x (F_i + F_{i+1}) + tau_i = 0`, reads
/// `l_i (s_i H_x - c_i H_y) = tau_i - (l_i / 2) (S_i + S_{i+1}) (c_i G_y - s_i G_x)`.
/// A pivot let go at `t = 0` holds nothing: every force is zero (the chain
/// falls freely; its unstretched state is its own equilibrium in free fall).
fn static_forces_general(chain: &Chain, phi: &[f64]) -> (Vec<Vec2>, Vec2) {
    let n = phi.len();
    if chain.pivot().release == Some(0.0) {
        return (vec![[0.0, 0.0]; n], [0.0, 0.0]);
    }
    let a0 = chain.pivot().acceleration_at(0.0);
    let gv = [a0[0], chain.gravity() + a0[1]];
    let p = Springs::of(chain);
    // S_i, from the tip.
    let mut beyond = vec![chain.tip_mass(); n + 1];
    for i in (0..n).rev() {
        beyond[i] = beyond[i + 1] + rod_mass(chain, i);
    }
    let (mut nxx, mut nxy, mut nyy, mut rx, mut ry) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (i, &q) in phi.iter().enumerate() {
        let (s, c) = sin_cos(q);
        let l = 2.0 * p.h(i);
        let (ax, ay) = (l * s, -l * c);
        let b = rest_torque(&p.loads, phi, i)
            - 0.5 * l * (beyond[i] + beyond[i + 1]) * (c * gv[1] - s * gv[0]);
        nxx += ax * ax;
        nxy += ax * ay;
        nyy += ay * ay;
        rx += ax * b;
        ry += ay * b;
    }
    let h = least_squares_holding([nxx, nxy, nyy], [rx, ry]);
    let forces = (0..n)
        .map(|i| [-h[0] + beyond[i] * gv[0], -h[1] + beyond[i] * gv[1]])
        .collect();
    (forces, h)
}

/// The elastic chain's state at the start `state` (angles and rates of the
/// rigid description): the rods at the angles and rates given, each gap
/// pre-stretched by the static force of its joint, `d_k = -F_k / K_k`
/// (`static_forces`: the tip held as the start holds it), with zero gap
/// rates. A start in static equilibrium (hanging, catenary, folded) is then
/// the elastic chain's own equilibrium, held at the tip by the same force.
/// Positions and velocities are relative to the pivot `P0(t)` (the start's
/// anchor for a fixed pivot). A pivot let go at `t = 0` starts unstretched.
///
/// Panics unless `chain` is elastic and `state` has `chain.links` angles and
/// rates (as `solve` checks first).
pub fn start_state(chain: &Chain, state: &State) -> Vec<f64> {
    let n = chain.links();
    let (forces, _) = static_forces(chain, &state.angles);
    let [_, ow, owk, ox, oy, ovx, ovy] = offsets(n);
    let mut y = vec![0.0; 6 * n + 1];
    y[..n].copy_from_slice(&state.angles);
    y[ow..owk].copy_from_slice(&state.rates);
    let (mut ex, mut ey, mut evx, mut evy) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..n {
        let h = rod_half_length(chain, i);
        let k = match joint_spring(chain, i).0 {
            k if k > 0.0 => k,
            _ => f64::INFINITY,
        };
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

/// True when joint 0 has no spring at `t`: the pivot let go at `t_r = 0`,
/// or at `t > t_r` (at `t_r` itself the run still holds it).
pub fn pivot_free_at(chain: &Chain, t: f64) -> bool {
    chain.pivot().release.is_some_and(|tr| tr == 0.0 || t > tr)
}

/// The joints `r_0 = p0, r_1, .., r_n` of an elastic state `y` with the pivot
/// at `p0`: `r_0` is the pivot, `r_k` (`0 < k < n`) the midpoint of the gap
/// between rods `k - 1` and `k`, `r_n` the end of the last rod (the tip).
pub fn joints(chain: &Chain, p0: Vec2, y: &[f64]) -> Vec<Vec2> {
    let n = chain.links();
    let [_, _, _, ox, oy, _, _] = offsets(n);
    let mut out = Vec::with_capacity(n + 1);
    out.push(p0);
    for k in 1..=n {
        let h0 = rod_half_length(chain, k - 1);
        let (s0, c0) = sin_cos(y[k - 1]);
        let end = [y[ox + k - 1] + h0 * c0, y[oy + k - 1] + h0 * s0];
        let r = if k < n {
            let h1 = rod_half_length(chain, k);
            let (s1, c1) = sin_cos(y[k]);
            let start = [y[ox + k] - h1 * c1, y[oy + k] - h1 * s1];
            [0.5 * (end[0] + start[0]), 0.5 * (end[1] + start[1])]
        } else {
            end
        };
        out.push([p0[0] + r[0], p0[1] + r[1]]);
    }
    out
}

/// [`joints`] at `t`: once the pivot is let go, `r_0` is the start of the
/// first rod (the free end), not the frame's origin `p0`.
pub fn joints_at(chain: &Chain, t: f64, p0: Vec2, y: &[f64]) -> Vec<Vec2> {
    let mut out = joints(chain, p0, y);
    if pivot_free_at(chain, t) {
        let n = chain.links();
        let h = rod_half_length(chain, 0);
        let (s, c) = sin_cos(y[0]);
        out[0] = [p0[0] + y[2 * n + 1] - h * c, p0[1] + y[3 * n + 1] - h * s];
    }
    out
}

/// The tip, the end of the last rod, for the pivot at `p0`.
pub fn tip(chain: &Chain, p0: Vec2, y: &[f64]) -> Vec2 {
    let n = chain.links();
    let h = rod_half_length(chain, n - 1);
    let [_, _, _, ox, oy, _, _] = offsets(n);
    let (s, c) = sin_cos(y[n - 1]);
    [p0[0] + y[ox + n - 1] + h * c, p0[1] + y[oy + n - 1] + h * s]
}

/// The tip velocity `c_{n-1}' + h w_{n-1} v_{n-1}` (relative to the pivot).
pub fn tip_velocity(chain: &Chain, y: &[f64]) -> Vec2 {
    let n = chain.links();
    let h = rod_half_length(chain, n - 1);
    let [_, ow, _, _, _, ovx, ovy] = offsets(n);
    let (s, c) = sin_cos(y[n - 1]);
    let w = y[ow + n - 1];
    [y[ovx + n - 1] - h * s * w, y[ovy + n - 1] + h * c * w]
}

/// The tip acceleration (relative to the pivot), from the state `y` and its
/// derivative `f`.
pub fn tip_acceleration(chain: &Chain, y: &[f64], f: &[f64]) -> Vec2 {
    let n = chain.links();
    let h = rod_half_length(chain, n - 1);
    let [_, ow, _, _, _, ovx, ovy] = offsets(n);
    let (s, c) = sin_cos(y[n - 1]);
    let (w, a) = (y[ow + n - 1], f[ow + n - 1]);
    [
        f[ovx + n - 1] + h * (-a * s - w * w * c),
        f[ovy + n - 1] + h * (a * c - w * w * s),
    ]
}

/// The forces of the joints `0..=n` on the rod after each (physical units;
/// joint `n`, the free tip, is zero): the springs' `F_k = -K_k d_k - C_k d_k'`.
pub fn joint_forces(chain: &Chain, y: &[f64]) -> Vec<Vec2> {
    let mut out = Vec::with_capacity(chain.links() + 1);
    each_joint_force(chain, y, |_, f, _| out.push(f));
    out.push([0.0, 0.0]);
    out
}

/// Calls `each(k, F_k, (sin phi_k, cos phi_k))` for the joints `0..n` of
/// the elastic state `y` ([`joint_forces`]' springs), in one pass without
/// allocation.
fn each_joint_force(chain: &Chain, y: &[f64], mut each: impl FnMut(usize, Vec2, (f64, f64))) {
    let n = chain.links();
    let [_, ow, _, ox, oy, ovx, ovy] = offsets(n);
    let (mut ex, mut ey, mut evx, mut evy) = (0.0, 0.0, 0.0, 0.0);
    for k in 0..n {
        let h = rod_half_length(chain, k);
        let (kk, cc) = joint_spring(chain, k);
        let (s, c) = sin_cos(y[k]);
        let (hs, hc) = (h * s, h * c);
        let w = y[ow + k];
        let (x, yy, vx, vy) = (y[ox + k], y[oy + k], y[ovx + k], y[ovy + k]);
        let (dx, dyy) = (x - hc - ex, yy - hs - ey);
        let (ddx, ddy) = (vx + hs * w - evx, vy - hc * w - evy);
        each(k, [-kk * dx - cc * ddx, -kk * dyy - cc * ddy], (s, c));
        (ex, ey, evx, evy) = (x + hc, yy + hs, vx - hs * w, vy + hc * w);
    }
}

/// [`joint_forces`] at `t`: joint 0's is zero once the pivot is let go.
pub fn joint_forces_at(chain: &Chain, t: f64, y: &[f64]) -> Vec<Vec2> {
    let mut out = joint_forces(chain, y);
    if pivot_free_at(chain, t) {
        out[0] = [0.0, 0.0];
    }
    out
}

/// The force of the pivot on the first rod, `F_1 = -K d_1 - C d_1'`
/// (physical units; the support feels `-F_1`): joint 0 of
/// [`joint_forces`], in O(1).
pub fn pivot_force(chain: &Chain, y: &[f64]) -> Vec2 {
    let n = chain.links();
    let h = rod_half_length(chain, 0);
    let (kk, cc) = joint_spring(chain, 0);
    let [_, ow, _, ox, oy, ovx, ovy] = offsets(n);
    let (s, c) = sin_cos(y[0]);
    let (hs, hc) = (h * s, h * c);
    let w = y[ow];
    let (dx, dyy) = (y[ox] - hc, y[oy] - hs);
    let (ddx, ddy) = (y[ovx] + hs * w, y[ovy] - hc * w);
    [-kk * dx - cc * ddx, -kk * dyy - cc * ddy]
}

/// The largest tension over the joints of the elastic state `y` at `t`,
/// `max_k T_k` with `T_k = -F_k . u_k` ([`joint_forces`]' `F_k` on rod
/// `k`, [`tension_shear`]'s tension; joint 0's force is zero once the
/// pivot is let go), and the joint `k` that carries it: one pass, no
/// allocation (a run's peak tracking calls it at every step).
pub fn largest_tension(chain: &Chain, t: f64, y: &[f64]) -> (f64, usize) {
    let free = pivot_free_at(chain, t);
    let (mut best, mut at) = (f64::NEG_INFINITY, 0);
    each_joint_force(chain, y, |k, f, (s, c)| {
        let tension = if k == 0 && free {
            0.0
        } else {
            -(f[0] * c + f[1] * s)
        };
        if (tension > best || tension.is_nan()) && !best.is_nan() {
            (best, at) = (tension, k);
        }
    });
    (best, at)
}

/// [`pivot_force`] at `t`: zero once the pivot is let go.
pub fn pivot_force_at(chain: &Chain, t: f64, y: &[f64]) -> Vec2 {
    if pivot_free_at(chain, t) {
        [0.0, 0.0]
    } else {
        pivot_force(chain, y)
    }
}

/// The energy `T + V + U_el + U_b` of the elastic state `y` (zero
/// potential at the pivot's height; positions and velocities relative to
/// the pivot: the frame's own terms are [`frame_energy`]'s). The loads'
/// potentials are the chain's own (bending): a floor's is its model's.
pub fn energy(chain: &Chain, y: &[f64]) -> f64 {
    energy_under(chain, &Loads::of(chain, Units::Physical), y)
}

/// [`energy`] with the potentials of `loads` (the model's, a placed floor
/// among them).
pub(crate) fn energy_under(chain: &Chain, loads: &Loads, y: &[f64]) -> f64 {
    if !is_plain(chain) {
        return energy_general(chain, loads, false, y);
    }
    let n = chain.links();
    let p = Springs::of(chain);
    let m = chain.mass();
    let [_, ow, _, ox, oy, ovx, ovy] = offsets(n);
    let (mut t, mut v, mut u, mut u0) = (0.0, 0.0, 0.0, 0.0);
    let (mut ex, mut ey) = (0.0, 0.0);
    for i in 0..n {
        let (s, c) = sin_cos(y[i]);
        let w = y[ow + i];
        let (x, yy, vx, vy) = (y[ox + i], y[oy + i], y[ovx + i], y[ovy + i]);
        t += m * (vx * vx + vy * vy) + w * w / p.inv_j;
        v += yy;
        let (dx, dyy) = (x - p.h * c - ex, yy - p.h * s - ey);
        if i == 0 {
            u0 = dx * dx + dyy * dyy;
        } else {
            u += dx * dx + dyy * dyy;
        }
        (ex, ey) = (x + p.h * c, yy + p.h * s);
    }
    let e = 0.5 * t + m * p.g * v + 0.5 * (p.k0 * u0 + p.k * u);
    loads.potential(&EnergyView { chain, y }, e)
}

/// [`energy`] at `t`: joint 0's spring energy is left out once the pivot
/// is let go (the run moves it into the work `W` at the release).
pub fn energy_at(chain: &Chain, t: f64, y: &[f64]) -> f64 {
    energy_at_under(chain, &Loads::of(chain, Units::Physical), t, y)
}

/// [`energy_at`] with the potentials of `loads`.
pub(crate) fn energy_at_under(chain: &Chain, loads: &Loads, t: f64, y: &[f64]) -> f64 {
    if pivot_free_at(chain, t) {
        energy_general(chain, loads, true, y)
    } else {
        energy_under(chain, loads, y)
    }
}

/// An elastic state's rods as the loads' potentials read them (physical
/// units, relative to the anchor).
struct EnergyView<'a> {
    chain: &'a Chain,
    y: &'a [f64],
}

impl Kinematics<f64> for EnergyView<'_> {
    fn angles(&self) -> &[f64] {
        &self.y[..self.chain.links()]
    }
    fn rates(&self) -> &[f64] {
        let n = self.chain.links();
        &self.y[n..2 * n]
    }
    fn sin_cos(&self, i: usize) -> (f64, f64) {
        sin_cos(self.y[i])
    }
    fn half_length(&self, i: usize) -> f64 {
        rod_half_length(self.chain, i)
    }
    fn mass(&self, i: usize) -> f64 {
        rod_mass(self.chain, i)
    }
    fn torque_unit(&self, _i: usize) -> f64 {
        1.0
    }
    fn centre(&self, i: usize) -> [f64; 2] {
        let [_, _, _, ox, oy, _, _] = offsets(self.chain.links());
        [self.y[ox + i], self.y[oy + i]]
    }
    fn centre_velocity(&self, i: usize) -> [f64; 2] {
        let [_, _, _, _, _, ovx, ovy] = offsets(self.chain.links());
        [self.y[ovx + i], self.y[ovy + i]]
    }
}

/// [`energy`] for any elastic chain: rod masses `m_i`, inertias `J_i`,
/// joint springs `K_k`, the loads' potentials, the tip mass
/// (`M_t |v_tip|^2 / 2 + M_t g y_tip`, after the bending springs': the
/// order the data were made with); `free0`: no joint-0 spring. One pass,
/// no allocation.
fn energy_general(chain: &Chain, loads: &Loads, free0: bool, y: &[f64]) -> f64 {
    let n = chain.links();
    let g = chain.gravity();
    let [_, ow, _, ox, oy, ovx, ovy] = offsets(n);
    let (mut t, mut v, mut u) = (0.0, 0.0, 0.0);
    let (mut ex, mut ey) = (0.0, 0.0);
    for i in 0..n {
        let (m, h) = (rod_mass(chain, i), rod_half_length(chain, i));
        let kk = joint_spring(chain, i).0;
        let (s, c) = sin_cos(y[i]);
        let w = y[ow + i];
        let (x, yy, vx, vy) = (y[ox + i], y[oy + i], y[ovx + i], y[ovy + i]);
        t += m * (vx * vx + vy * vy) + m * h * h / 3.0 * w * w;
        v += m * yy;
        let (dx, dyy) = (x - h * c - ex, yy - h * s - ey);
        if i > 0 || !free0 {
            u += kk * (dx * dx + dyy * dyy);
        }
        (ex, ey) = (x + h * c, yy + h * s);
    }
    let mt = chain.tip_mass();
    let tip_term = if mt != 0.0 {
        let [tvx, tvy] = tip_velocity(chain, y);
        let tip_y = tip(chain, [0.0, 0.0], y)[1];
        0.5 * mt * (tvx * tvx + tvy * tvy) + mt * g * tip_y
    } else {
        0.0
    };
    let e = 0.5 * t + g * v + 0.5 * u;
    loads.potential_split(&EnergyView { chain, y }, e, Bending::KEY, tip_term)
}

/// Joint 0's spring energy `K_0 |d_0|^2 / 2`: what leaves the chain when
/// the pivot is let go (the run adds it to the work `W` then, so that the
/// balance `E + W = E(0)` holds across the release).
pub fn pivot_spring_energy(chain: &Chain, y: &[f64]) -> f64 {
    let n = chain.links();
    let h = rod_half_length(chain, 0);
    let (s, c) = sin_cos(y[0]);
    let (dx, dy) = (y[2 * n + 1] - h * c, y[3 * n + 1] - h * s);
    0.5 * joint_spring(chain, 0).0 * (dx * dx + dy * dy)
}

/// The momentum `sum m_i c_i' + M_t v_tip` of the elastic state `y`
/// relative to the pivot.
pub fn momentum(chain: &Chain, y: &[f64]) -> Vec2 {
    let n = chain.links();
    let [_, _, _, _, _, ovx, ovy] = offsets(n);
    let mut p = [0.0, 0.0];
    for i in 0..n {
        let m = rod_mass(chain, i);
        p[0] += m * y[ovx + i];
        p[1] += m * y[ovy + i];
    }
    let mt = chain.tip_mass();
    if mt != 0.0 {
        let v = tip_velocity(chain, y);
        p[0] += mt * v[0];
        p[1] += mt * v[1];
    }
    p
}

/// The energy a pivot moved by `d` (from the anchor, at the velocity `v0`)
/// adds to [`energy`] to make it the inertial frame's: with `P` the
/// [`momentum`] relative to the pivot and `M = sum m_i + M_t`,
/// `v0 . P + M |v0|^2 / 2 + M g d_y`.
pub fn frame_energy(chain: &Chain, d: Vec2, v0: Vec2, y: &[f64]) -> f64 {
    let p = momentum(chain, y);
    let m = chain.total_mass() + chain.tip_mass();
    (v0[0] * p[0] + v0[1] * p[1])
        + m * (0.5 * (v0[0] * v0[0] + v0[1] * v0[1]) + chain.gravity() * d[1])
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
