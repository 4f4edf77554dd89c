//! The chain as a banded, index-1 DAE with a constant mass matrix: the form
//! in which an implicit step costs O(n).
//!
//! Besides the angles `phi_i` and rates `w_i`, every rod `i` (0-based) carries
//! its angular acceleration `alpha_i` and the force `F_i` that joint `i` (the
//! rod's start; joint 0 is the pivot) exerts on it. Forces are in rod units,
//! `f = F / (m l)` (1/time^2), like accelerations; `F_n = 0` at the free tip.
//! With `u_i = (cos phi_i, sin phi_i)`, `v_i = (-sin phi_i, cos phi_i)` and the
//! half-rod acceleration `h_i = (alpha_i v_i - w_i^2 u_i) / 2`, the equations,
//! each coupling rod `i` only to rods `i - 1` and `i + 1`, are
//!
//! ```text
//! phi_i' = w_i,   w_i' = alpha_i,   W' = 2R = r sum_i (w_i - w_{i-1})^2
//! 0 = -alpha_i / 12 - v_i . (f_i + f_{i+1}) / 2 + gamma D_i(w) + kappa D_i(phi)   moment
//! 0 = f_0 - f_1 + (0, -g/l) - h_0                                   translation of rod 0
//! 0 = -f_{i-1} + 2 f_i - f_{i+1} - h_{i-1} - h_i      (i >= 1)      rod i minus rod i-1
//! ```
//!
//! A tip mass `mu = M_t / m` at the free end makes `f_n` nonzero: its
//! balance `mu a_n = f_n - mu (0, g/l)` less rod `n`'s (`a_n - c_n''/l = h_n`)
//! gives `f_n = tip (f_{n-1} + h_{n-1})` (0-based rods), `tip = mu / (1 + mu)`,
//! which is substituted in the last rod's two rows: the unknowns stay the same.
//! (Unequal rods, the last of mass `mu_l`: `f_n = tip (f_{n-1} + mu_l h_{n-1})`,
//! `tip = mu / (mu_l + mu)`.)
//!
//! A moving pivot (`pivot.*`, [`crate::pivot`]) adds its acceleration
//! `a_0 = P0''(t) / l` to rod 0's centre (`- a_0` in rod 0's translation
//! row), and the work row counts its power, `W' = 2R - m l f_0 . P0'(t)`. A
//! released pivot has `f_0 = 0`: the unknown in `f_0`'s place is then
//! `a_0`, entering rod 0's translation row as `- a_0` and nothing else
//! (the Jacobian's pattern stays the same; only values change).
//!
//! The last line is the difference of the translational balances of two
//! neighbours (`m c_i'' = F_i - F_{i+1} + m g`), in which the joint
//! accelerations cancel: `c_i'' - c_{i-1}'' = l (h_{i-1} + h_i)`. The mass
//! matrix is `diag(1, .., 1, 0, .., 0)` over the differential unknowns
//! `[phi, w, W]` and the algebraic ones `[alpha, f]`. For given `phi, w` the
//! algebraic equations are linear in `alpha, f` and equivalent to
//! `A(phi) alpha = b(phi, w)` with `A` SPD, so their block is nonsingular and
//! the DAE has index 1.
//!
//! The unknowns are laid out `[phi (n), w (n), W, alpha (n), (fx, fy) (n)]`,
//! so that the first `2n + 1` are exactly [`crate::ChainSystem`]'s state. The
//! Jacobian has at most 30 entries per rod (the dense row of `W` is left out
//! of the Newton matrix; see [`ChainDae::jacobian_entries`]).

use std::cell::RefCell;

use crate::chain::Chain;
use crate::dynamics::{accelerations_under, Base, Workspace};
use crate::load::{Kinematics, Loads, RodForce, RodSlices, Units};
use crate::pivot::Pivot;
use crate::scalar::{sin_cos, Dual, Scalar};
use fc_methods::SemiExplicitDae;

/// The falling chain as `M y' = f(y)` with algebraic unknowns; see the module doc.
#[derive(Clone, Debug)]
pub struct ChainDae {
    chain: Chain,
    n: usize,
    /// The chain's loads in rod units; the field `(0, -g/l)` among them.
    loads: Loads,
    /// The tip mass in rod masses, `mu = M_t / m`.
    mu: f64,
    /// `mu / (mu_l + mu)`: the tip mass's force on its joint,
    /// `f_n = tip (f_{n-1} + mu_l h_{n-1})`, `mu_l` the last rod's mass
    /// (1 for equal rods).
    tip: f64,
    /// `mu_l`, the last rod's mass in mean-rod masses (1 for equal rods).
    last_mass: f64,
    /// The pivot's prescribed motion (used while not released).
    pivot: Pivot,
    /// The pivot is free: `f_0 = 0`, and `f_0`'s unknowns hold `a_0`.
    free: bool,
    /// Scratch of [`ChainDae::rhs_at`]: `(sin phi_i, cos phi_i)` of every
    /// rod, in one pass that vectorises (bit for bit [`sin_cos`]), and the
    /// loads' kinematics and forces.
    trig: RefCell<Vec<(f64, f64)>>,
    scratch: RefCell<LoadScratch>,
}

/// What the loads of a [`ChainDae`] need between calls: the rods' centres
/// and their velocities and each rod's load force (for loads that read
/// centres: empty otherwise), and the dual numbers of the Jacobian's columns.
#[derive(Clone, Debug, Default)]
struct LoadScratch {
    centre: Vec<[f64; 2]>,
    velocity: Vec<[f64; 2]>,
    force: Vec<[f64; 2]>,
    dual_phi: Vec<Dual>,
    dual_w: Vec<Dual>,
}

impl ChainDae {
    /// The DAE of a validated chain.
    pub fn new(chain: &Chain) -> Self {
        let last_mass = chain
            .rods()
            .and_then(|r| r.mass.last().copied())
            .unwrap_or(1.0);
        let n = chain.links();
        let loads = Loads::of(chain, Units::Rod);
        let scratch = LoadScratch {
            dual_phi: vec![Dual::default(); n],
            dual_w: vec![Dual::default(); n],
            ..LoadScratch::default()
        };
        let scratch = if loads.reads_centres() {
            LoadScratch {
                centre: vec![[0.0; 2]; n],
                velocity: vec![[0.0; 2]; n],
                force: vec![[0.0; 2]; n],
                ..scratch
            }
        } else {
            scratch
        };
        Self {
            chain: chain.clone(),
            n,
            loads,
            mu: chain.tip_mass_ratio(),
            tip: chain.tip_mass_ratio() / (last_mass + chain.tip_mass_ratio()),
            last_mass,
            pivot: *chain.pivot(),
            free: false,
            trig: RefCell::new(vec![(0.0, 0.0); chain.links()]),
            scratch: RefCell::new(scratch),
        }
    }

    /// This DAE with the pivot let go (`true`) or held.
    pub fn released(mut self, free: bool) -> Self {
        self.free = free;
        self
    }

    /// How joint 0 is held at `t`.
    fn base_at(&self, t: f64) -> Base {
        if self.free {
            Base::Free
        } else if self.pivot.is_driven() {
            Base::Driven(self.pivot.acceleration_at(t))
        } else {
            Base::Fixed
        }
    }

    /// The prescribed `a_0 = P0''(t) / l` (rod units), zero when fixed or free.
    fn driven_acceleration(&self, t: f64) -> (f64, f64) {
        match self.base_at(t) {
            Base::Driven([ax, ay]) => {
                let l = self.chain.rod_length();
                (ax / l, ay / l)
            }
            _ => (0.0, 0.0),
        }
    }

    /// Rod `i`'s `(mu_i lambda_i^2, lambda_i)` and `1 / mu_i` (mean-rod
    /// units; `(1, 1)` and `1` for equal rods, whose arithmetic these
    /// factors leave bit for bit unchanged).
    #[inline(always)]
    fn rod(&self, i: usize) -> (f64, f64, f64) {
        match self.chain.rods() {
            Some(r) => (
                r.mass[i] * r.length[i] * r.length[i],
                r.length[i],
                r.inv_mass[i],
            ),
            None => (1.0, 1.0, 1.0),
        }
    }

    /// The pivot's velocity at `t` (physical units): the prescribed one
    /// while driven, else zero (a released pivot's is not in the state: the
    /// loads that read it are refused then).
    fn pivot_velocity(&self, t: f64) -> [f64; 2] {
        match self.base_at(t) {
            Base::Driven(_) => self.pivot.drive(t)[1],
            _ => [0.0, 0.0],
        }
    }

    /// The rods' centres and their velocities (rod units, inertial frame)
    /// into `scratch`, from the rates `w` and every rod's `(sin, cos)`.
    fn centres(&self, t: f64, w: &[f64], trig: &[(f64, f64)], scratch: &mut LoadScratch) {
        let l = self.chain.rod_length();
        let v = self.pivot_velocity(t);
        let v0 = [v[0] / l, v[1] / l];
        let LoadScratch {
            centre, velocity, ..
        } = scratch;
        match self.chain.rods() {
            Some(r) => crate::dynamics::centres(r, v0, w, trig, centre, velocity),
            None => {
                crate::dynamics::centres(crate::dynamics::EqualRods, v0, w, trig, centre, velocity)
            }
        }
    }

    /// The loads' view of `(phi, w)` with its `(sin, cos)`, centres and
    /// their velocities (rod units; empty where no load reads them).
    fn view<'a>(
        &'a self,
        phi: &'a [f64],
        w: &'a [f64],
        trig: &'a [(f64, f64)],
        centre: &'a [[f64; 2]],
        velocity: &'a [[f64; 2]],
    ) -> RodSlices<'a> {
        let rods = self.chain.rods();
        RodSlices {
            phi,
            w,
            trig,
            length: rods.map(|r| &r.length[..]),
            mass: rods.map(|r| &r.mass[..]),
            centre,
            velocity,
        }
    }

    /// Each rod's load force (rod units) into `scratch.force`, and the
    /// power the loads draw at the rods (physical units).
    fn load_forces(&self, t: f64, phi: &[f64], w: &[f64], scratch: &mut LoadScratch) -> f64 {
        let mut trig = self.trig.borrow_mut();
        f64::sin_cos_all(phi, &mut trig[..self.n]);
        self.centres(t, w, &trig, scratch);
        let mut power = 0.0;
        for i in 0..self.n {
            let view = self.view(phi, w, &trig, &scratch.centre, &scratch.velocity);
            let mut load = RodForce::zero();
            self.loads.add_to_rod(i, &view, &mut load);
            scratch.force[i] = load.force;
            power += load.power;
        }
        power
    }

    /// `W'`: the power the loads draw through the joints (friction's `2R`)
    /// and at the rods, physical units (less a driven pivot's power, which
    /// [`ChainDae::derivatives_at`] subtracts).
    fn work_rate(&self, t: f64, phi: &[f64], w: &[f64]) -> f64 {
        let view = self.view(phi, w, &[], &[], &[]);
        let p = self.loads.joint_power(&view, 0.0);
        if self.loads.reads_centres() {
            p + self.load_forces(t, phi, w, &mut self.scratch.borrow_mut())
        } else {
            p
        }
    }

    /// Number of rods.
    pub fn links(&self) -> usize {
        self.n
    }

    /// Number of unknowns, `5 n + 1`.
    pub fn dim(&self) -> usize {
        5 * self.n + 1
    }

    /// Number of differential unknowns `[phi, w, W]`, `2 n + 1`: the first
    /// rows and columns; the mass matrix is the identity on them.
    pub fn differential_dim(&self) -> usize {
        2 * self.n + 1
    }

    /// Index of `alpha_i`.
    fn alpha(&self, i: usize) -> usize {
        2 * self.n + 1 + i
    }

    /// Index of `f_i`'s x component (y is the next one).
    fn force(&self, i: usize) -> usize {
        3 * self.n + 1 + 2 * i
    }

    /// The pivot force `F_0` in rod units (multiply by `m l` for physical
    /// units); zero for a released pivot.
    pub fn pivot_force(&self, y: &[f64]) -> [f64; 2] {
        if self.free {
            return [0.0, 0.0];
        }
        let k = self.force(0);
        [y[k], y[k + 1]]
    }

    /// The joint forces `f_0 .. f_{n-1}` of a consistent `y` in rod units,
    /// as pairs (`f_0 = 0` for a released pivot).
    pub fn joint_forces(&self, y: &[f64]) -> Vec<[f64; 2]> {
        let k = self.force(0);
        let mut out: Vec<[f64; 2]> = (0..self.n)
            .map(|i| [y[k + 2 * i], y[k + 2 * i + 1]])
            .collect();
        if self.free {
            out[0] = [0.0, 0.0];
        }
        out
    }

    /// [`ChainDae::make_consistent_at`] at `t = 0`.
    pub fn make_consistent(&self, y: &mut [f64], ws: &mut Workspace<f64>) {
        self.make_consistent_at(0.0, y, ws)
    }

    /// Fills the algebraic unknowns of `y` at time `t` from its `phi` and
    /// `w`: `alpha` by the O(n) recursion, the forces by summing the rods'
    /// translational balances back from the free tip (for a released
    /// pivot, `a_0` in `f_0`'s place). Allocation-free given the workspace.
    pub fn make_consistent_at(&self, t: f64, y: &mut [f64], ws: &mut Workspace<f64>) {
        let n = self.n;
        let (diff, alg) = y.split_at_mut(2 * n + 1);
        let (alpha, f) = alg.split_at_mut(n);
        let base = self.base_at(t);
        let r = accelerations_under(
            &self.chain,
            &self.loads,
            base,
            self.pivot_velocity(t),
            &diff[..n],
            &diff[n..2 * n],
            alpha,
            ws,
        );
        let l = self.chain.rod_length();
        let a0 = match base {
            Base::Fixed => (0.0, 0.0),
            _ => (r.pivot_acceleration[0] / l, r.pivot_acceleration[1] / l),
        };
        // Forward: the centre acceleration c_i'' / l = a_{i-1} + h_i, stored in f_i.
        let (mut ax, mut ay) = a0;
        for i in 0..n {
            let (s, c) = sin_cos(diff[i]);
            let w2 = diff[n + i] * diff[n + i];
            let half = 0.5 * self.rod(i).1;
            let hx = half * (-alpha[i] * s - w2 * c);
            let hy = half * (alpha[i] * c - w2 * s);
            f[2 * i] = ax + hx;
            f[2 * i + 1] = ay + hy;
            ax += 2.0 * hx;
            ay += 2.0 * hy;
        }
        // Backward: f_i = f_{i+1} + c_i'' / l - a - F_i (the field `a =
        // (0, -g/l)`, the loads' force `F_i` at rod i's centre), with
        // f_n = 0, or `mu (a_n - a)` that the tip mass needs (a_n = (ax, ay)).
        let field = self.loads.field.y();
        let (mut fx, mut fy) = if self.mu != 0.0 {
            (self.mu * ax, self.mu * (ay - field))
        } else {
            (0.0, 0.0)
        };
        let forces = self.loads.reads_centres();
        let mut scratch = self.scratch.borrow_mut();
        if forces {
            self.load_forces(t, &diff[..n], &diff[n..2 * n], &mut scratch);
        }
        if let Some(rods) = self.chain.rods() {
            // Rod i's weight and inertia are mu_i times a mean rod's.
            for i in (0..n).rev() {
                fx += rods.mass[i] * f[2 * i];
                fy += rods.mass[i] * (f[2 * i + 1] - field);
                if forces {
                    fx -= scratch.force[i][0];
                    fy -= scratch.force[i][1];
                }
                f[2 * i] = fx;
                f[2 * i + 1] = fy;
            }
        } else {
            for i in (0..n).rev() {
                fx += f[2 * i];
                fy += f[2 * i + 1] - field;
                if forces {
                    fx -= scratch.force[i][0];
                    fy -= scratch.force[i][1];
                }
                f[2 * i] = fx;
                f[2 * i + 1] = fy;
            }
        }
        if self.free {
            // f_0 vanishes (to rounding); its place holds a_0.
            f[0] = a0.0;
            f[1] = a0.1;
        }
    }

    /// `out = f(y)`: the derivatives of the differential unknowns, then the
    /// residuals of the algebraic equations. O(n), no allocation.
    pub fn rhs(&self, y: &[f64], out: &mut [f64]) {
        self.rhs_at(0.0, y, out)
    }

    /// The first `2n + 1` entries of `f(t, y)` ([`ChainDae::rhs_at`]), the
    /// derivatives `[w, alpha, W']` of the differential unknowns, read off
    /// `y` without the algebraic residuals: `w` and `alpha` are unknowns,
    /// and `W'` is the dissipation rate (less a driven pivot's power). The
    /// same arithmetic as `rhs_at`, which calls it. O(n), no trigonometry.
    pub fn derivatives_at(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let n = self.n;
        let w = &y[n..2 * n];
        let alpha = &y[2 * n + 1..3 * n + 1];
        let f = &y[3 * n + 1..];
        out[..n].copy_from_slice(w);
        out[n..2 * n].copy_from_slice(alpha);
        out[2 * n] = self.work_rate(t, &y[..n], w);
        // A driven pivot's power.
        if !self.free && self.pivot.is_driven() {
            let v0 = self.pivot.drive(t)[1];
            let ml = self.chain.mass() * self.chain.rod_length();
            out[2 * n] -= ml * (f[0] * v0[0] + f[1] * v0[1]);
        }
    }

    /// `out = f(t, y)` (see [`ChainDae::rhs`]); `t` places a moving pivot.
    pub fn rhs_at(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let n = self.n;
        let (phi, w) = (&y[..n], &y[n..2 * n]);
        let alpha = &y[2 * n + 1..3 * n + 1];
        let f = &y[3 * n + 1..];
        self.derivatives_at(t, y, out);
        // The pivot's acceleration a_0 (rod units).
        let (a0x, a0y) = if self.free {
            (f[0], f[1])
        } else {
            self.driven_acceleration(t)
        };
        // f_j with f_0 = 0 for a free pivot.
        let force = |j: usize| {
            if j == 0 && self.free {
                (0.0, 0.0)
            } else {
                (f[2 * j], f[2 * j + 1])
            }
        };
        let (moment, trans) = out[2 * n + 1..].split_at_mut(n);
        let (mut px, mut py) = (0.0, 0.0); // h_{i-1}
        let mut inv_prev = 1.0; // 1 / mu_{i-1}
        let mut trig = self.trig.borrow_mut();
        f64::sin_cos_all(phi, &mut trig[..n]);
        let forces = self.loads.reads_centres();
        let mut scratch = self.scratch.borrow_mut();
        if forces {
            self.centres(t, w, &trig, &mut scratch);
        }
        let scratch = &*scratch;
        let view = self.view(phi, w, &trig, &scratch.centre, &scratch.velocity);
        // The loads' force on rod i - 1 over its mass (rod units).
        let (mut qx, mut qy) = (0.0, 0.0);
        for i in 0..n {
            let (s, c) = trig[i];
            let (fx, fy) = force(i);
            let w2 = w[i] * w[i];
            // Rod i's mu lambda^2, lambda and 1 / mu (all 1 for equal rods).
            let (inertia, lam, inv_mu) = self.rod(i);
            let half = 0.5 * lam;
            let (hx, hy) = (
                half * (-alpha[i] * s - w2 * c),
                half * (alpha[i] * c - w2 * s),
            );
            let (gx, gy) = if i + 1 < n {
                (f[2 * i + 2], f[2 * i + 3])
            } else if self.tip != 0.0 && forces {
                // The tip mass's joint with a load force F on the last rod:
                // `f_n = tip (f_{n-1} + F + mu_l h_{n-1})`.
                let mut load = RodForce::zero();
                self.loads.add_to_rod(i, &view, &mut load);
                let [lx, ly] = load.force;
                (
                    self.tip * (fx + lx + self.last_mass * hx),
                    self.tip * (fy + ly + self.last_mass * hy),
                )
            } else if self.tip != 0.0 {
                // The tip mass's joint: `f_n = tip (f_{n-1} + mu_l h_{n-1})`.
                (
                    self.tip * (fx + self.last_mass * hx),
                    self.tip * (fy + self.last_mass * hy),
                )
            } else {
                (0.0, 0.0)
            };
            // The moment about the centre, then the loads' torques.
            let mut load = RodForce {
                torque: -(alpha[i] * inertia) / 12.0 - half * (-s * (fx + gx) + c * (fy + gy)),
                ..RodForce::zero()
            };
            self.loads.add_to_rod(i, &view, &mut load);
            moment[i] = load.torque;
            // Rod i's balance over mu_i, less rod i-1's over mu_{i-1}; the
            // field cancels but in rod 0's.
            if i == 0 {
                trans[0] = (fx - gx) * inv_mu - hx - a0x;
                trans[1] = (fy - gy) * inv_mu + self.loads.field.y() - hy - a0y;
            } else {
                let (ex, ey) = force(i - 1);
                let both = inv_prev + inv_mu;
                trans[2 * i] = -ex * inv_prev + fx * both - gx * inv_mu - px - hx;
                trans[2 * i + 1] = -ey * inv_prev + fy * both - gy * inv_mu - py - hy;
            }
            if forces {
                let (fx, fy) = (load.force[0] * inv_mu, load.force[1] * inv_mu);
                trans[2 * i] += fx - qx;
                trans[2 * i + 1] += fy - qy;
                (qx, qy) = (fx, fy);
            }
            (px, py) = (hx, hy);
            inv_prev = inv_mu;
        }
    }

    /// Every entry of the Jacobian `df/dy` at `y` except the row of `W`, as
    /// `emit(row, column, value)`. The entries, and their order, depend on `n`
    /// only (a zero value is still emitted), so a pattern built from one call
    /// serves every `y`.
    ///
    /// The row of `W' = 2R(w)` is left out on purpose: it is dense (`n`
    /// entries) and no other equation depends on `W`, so a Newton iteration
    /// without it still converges (`W` follows the converging `w`), while with
    /// it the sparse LU's fill-reducing ordering breaks down (measured on the
    /// stiff rope: 76 against 16 ms at n = 100, 8.4 against 0.45 s at
    /// n = 1600). [`Self::dissipation_row`] gives the row for checks.
    pub fn jacobian_entries(&self, y: &[f64], emit: impl FnMut(usize, usize, f64)) {
        self.jacobian_entries_at(0.0, y, emit)
    }

    /// [`ChainDae::jacobian_entries`] at `t` (which places a moving pivot,
    /// whose velocity the loads that read the centres see). The loads'
    /// entries are their derivatives within the band: a centre's velocity
    /// reads every rod above it, and what a rod's force reads of the rods
    /// more than one above it is left out of the Newton matrix (in the
    /// difference of two neighbours' balances it nearly cancels).
    pub fn jacobian_entries_at(&self, t: f64, y: &[f64], mut emit: impl FnMut(usize, usize, f64)) {
        let n = self.n;
        let (phi, w) = (&y[..n], &y[n..2 * n]);
        let alpha = &y[2 * n + 1..3 * n + 1];
        // A free pivot: f_0 = 0, and its columns are a_0's (`- a_0` in rod
        // 0's translation row only); the pattern stays the same.
        let f = &y[3 * n + 1..];
        let fr = |j: usize| -> f64 {
            if self.free && j < 2 {
                0.0
            } else {
                f[j]
            }
        };
        let free = self.free;
        // The loads' columns: each load's derivatives by dual numbers.
        let reads = self.loads.reads();
        let (by_angle, by_rate) = (reads.angles || reads.centres, reads.rates || reads.centres);
        let forces = reads.centres;
        let mut trig = self.trig.borrow_mut();
        f64::sin_cos_all(phi, &mut trig[..n]);
        let mut scratch = self.scratch.borrow_mut();
        for j in 0..n {
            scratch.dual_phi[j] = Dual::new(phi[j], 0.0);
            scratch.dual_w[j] = Dual::new(w[j], 0.0);
        }
        if forces {
            self.centres(t, w, &trig, &mut scratch);
        }
        // phi' = w, w' = alpha.
        for i in 0..n {
            emit(i, n + i, 1.0);
            emit(n + i, self.alpha(i), 1.0);
        }
        let row_m = |i: usize| 2 * n + 1 + i;
        let row_t = |i: usize| 3 * n + 1 + 2 * i;
        for i in 0..n {
            let (s, c) = sin_cos(phi[i]);
            let cos_i = c;
            let w2 = w[i] * w[i];
            let (inertia, lam, inv_mu) = self.rod(i);
            let half = 0.5 * lam;
            let inv_prev = if i > 0 { self.rod(i - 1).2 } else { 1.0 };
            // The tip mass enters the last rod's rows through
            // `f_n = tip (f_i + h_i)`: `f_i` and `h_i` weigh `1 + tip` there.
            let tipped = i + 1 == n && self.tip != 0.0;
            // Moment of rod i.
            let (sx, sy) = if i + 1 < n {
                (fr(2 * i) + f[2 * i + 2], fr(2 * i + 1) + f[2 * i + 3])
            } else if tipped {
                (
                    (1.0 + self.tip) * fr(2 * i),
                    (1.0 + self.tip) * fr(2 * i + 1),
                )
            } else {
                (fr(2 * i), fr(2 * i + 1))
            };
            // d/d(f_i) of rod i's rows is zero for a free pivot's f_0.
            let own_force = if free && i == 0 { 0.0 } else { 1.0 };
            let m = row_m(i);
            // The loads' torques (friction, bending), by dual numbers along
            // each column they read, in the order the pattern always had:
            // the angles' columns around the inertia's, then the rates'.
            let cols = i.saturating_sub(1)..(i + 2).min(n);
            // A load force F on the tip mass's rod reaches its moment through
            // `f_n = tip (f_i + F + mu_i h_i)`: `-half v_i . tip F`, whose
            // derivative along `phi_i` turns `v_i` too.
            let tip_moment = |d: &RodForce<Dual>, own_angle: bool| {
                if tipped && forces {
                    let (fx, fy) = (d.force[0].d * self.tip, d.force[1].d * self.tip);
                    let turn = if own_angle {
                        half * self.tip * (cos_i * d.force[0].v + s * d.force[1].v)
                    } else {
                        0.0
                    };
                    -half * (-s * fx + cos_i * fy) + turn
                } else {
                    0.0
                }
            };
            for j in cols.clone() {
                let load = by_angle.then(|| {
                    let d = self.load_derivative(i, Column::Phi(j), &trig, &mut scratch);
                    d.torque.d + tip_moment(&d, j == i)
                });
                match (j == i, load) {
                    (true, Some(d)) => emit(m, i, half * (c * sx + s * sy) + d),
                    (true, None) => emit(m, i, half * (c * sx + s * sy)),
                    (false, Some(d)) => emit(m, j, d),
                    (false, None) => {}
                }
            }
            if by_rate {
                for j in cols {
                    let d = self.load_derivative(i, Column::W(j), &trig, &mut scratch);
                    emit(m, n + j, d.torque.d + tip_moment(&d, false));
                }
            }
            let k = self.force(i);
            if tipped {
                // v_i . h_i = lambda_i alpha_i / 2, and f_n = tip (f_i + mu_i h_i).
                if self.chain.rods().is_some() {
                    let tip_h = self.tip * self.last_mass * half * half;
                    emit(m, self.alpha(i), -inertia / 12.0 - tip_h);
                    emit(m, k, own_force * (half * s * (1.0 + self.tip)));
                    emit(m, k + 1, own_force * (-half * c * (1.0 + self.tip)));
                } else {
                    emit(m, self.alpha(i), -1.0 / 12.0 - 0.25 * self.tip);
                    emit(m, k, own_force * (0.5 * s * (1.0 + self.tip)));
                    emit(m, k + 1, own_force * (-0.5 * c * (1.0 + self.tip)));
                }
            } else {
                emit(m, self.alpha(i), -inertia / 12.0);
                emit(m, k, own_force * (half * s));
                emit(m, k + 1, own_force * (-half * c));
            }
            if i + 1 < n {
                emit(m, k + 2, half * s);
                emit(m, k + 3, -half * c);
            }
            // Translation: the terms -h_j of rods j = i-1 and j = i, and the
            // loads' F_i / mu_i less F_{i-1} / mu_{i-1} (on the tip mass's
            // rod F_i's share `tip F_i` goes to f_n), within the band.
            let t = row_t(i);
            let rods = if i == 0 { 0..=0 } else { i - 1..=i };
            let weight = if tipped {
                inv_mu - self.tip * inv_mu
            } else {
                inv_mu
            };
            let mut load = |col: Column| -> [f64; 2] {
                if !forces {
                    return [0.0, 0.0];
                }
                let d = self.load_derivative(i, col, &trig, &mut scratch);
                let mut out = [d.force[0].d * weight, d.force[1].d * weight];
                let j = match col {
                    Column::Phi(j) | Column::W(j) => j,
                };
                if j + 1 == i {
                    let e = self.load_derivative(j, col, &trig, &mut scratch);
                    out[0] -= e.force[0].d * inv_prev;
                    out[1] -= e.force[1].d * inv_prev;
                }
                out
            };
            for j in rods {
                let (sj, cj) = if j == i { (s, c) } else { sin_cos(phi[j]) };
                let wj2 = if j == i { w2 } else { w[j] * w[j] };
                let a = alpha[j];
                let (lp, lw) = (load(Column::Phi(j)), load(Column::W(j)));
                if tipped && j == i && self.chain.rods().is_none() {
                    let k1 = 1.0 + self.tip;
                    emit(t, j, k1 * (0.5 * (a * cj - wj2 * sj)) + lp[0]);
                    emit(t + 1, j, k1 * (0.5 * (a * sj + wj2 * cj)) + lp[1]);
                    emit(t, n + j, k1 * (w[j] * cj) + lw[0]);
                    emit(t + 1, n + j, k1 * (w[j] * sj) + lw[1]);
                    emit(t, self.alpha(j), k1 * (0.5 * sj));
                    emit(t + 1, self.alpha(j), k1 * (-0.5 * cj));
                    continue;
                }
                // The tip mass's `f_n / mu_i = tip (f_i / mu_i + h_i)` on
                // the last of unequal rods: h_i weighs 1 + tip.
                let k1 = if tipped && j == i {
                    1.0 + self.tip
                } else {
                    1.0
                };
                // h_j carries rod j's length lambda_j (1 for equal rods).
                let lj = if j == i { lam } else { self.rod(j).1 };
                let hj = 0.5 * lj;
                let hj = k1 * hj;
                let lj = k1 * lj;
                // d(-h_j)/dphi_j = lambda_j (alpha u_j + w^2 v_j) / 2.
                if forces {
                    emit(t, j, hj * (a * cj - wj2 * sj) + lp[0]);
                    emit(t + 1, j, hj * (a * sj + wj2 * cj) + lp[1]);
                    emit(t, n + j, lj * (w[j] * cj) + lw[0]);
                    emit(t + 1, n + j, lj * (w[j] * sj) + lw[1]);
                } else {
                    emit(t, j, hj * (a * cj - wj2 * sj));
                    emit(t + 1, j, hj * (a * sj + wj2 * cj));
                    // d(-h_j)/dw_j = lambda_j w_j u_j.
                    emit(t, n + j, lj * (w[j] * cj));
                    emit(t + 1, n + j, lj * (w[j] * sj));
                }
                // d(-h_j)/dalpha_j = -lambda_j v_j / 2.
                emit(t, self.alpha(j), hj * sj);
                emit(t + 1, self.alpha(j), -hj * cj);
            }
            // Forces: f_{i-1} (-1), f_i (1 for the pivot's rod, else 2), f_{i+1} (-1).
            // Each over its rod's mass: 1 / mu (all 1 for equal rods).
            if i > 0 {
                // f_{i-1}: zero for a free pivot's f_0.
                let prev = if free && i == 1 { 0.0 } else { -inv_prev };
                emit(t, k - 2, prev);
                emit(t + 1, k - 1, prev);
            }
            let own = if i == 0 { inv_mu } else { inv_prev + inv_mu };
            let own = if tipped { own - self.tip * inv_mu } else { own };
            // A free pivot's columns in f_0's place are a_0's: `- a_0`.
            let own = if free && i == 0 { -1.0 } else { own };
            emit(t, k, own);
            emit(t + 1, k + 1, own);
            if i + 1 < n {
                emit(t, k + 2, -inv_mu);
                emit(t + 1, k + 3, -inv_mu);
            }
        }
    }

    /// The loads' force and torque on rod `i` with their derivatives along
    /// `column` (rod units), `scratch` holding the state's dual numbers
    /// (undisturbed on return) and, for loads that read them, its centres.
    fn load_derivative(
        &self,
        i: usize,
        column: Column,
        trig: &[(f64, f64)],
        scratch: &mut LoadScratch,
    ) -> RodForce<Dual> {
        let seed = |s: &mut LoadScratch, d: f64| match column {
            Column::Phi(j) => s.dual_phi[j].d = d,
            Column::W(j) => s.dual_w[j].d = d,
        };
        seed(scratch, 1.0);
        let view = ColumnView {
            phi: &scratch.dual_phi,
            w: &scratch.dual_w,
            trig,
            length: self.chain.rods().map(|r| &r.length[..]),
            mass: self.chain.rods().map(|r| &r.mass[..]),
            centre: &scratch.centre,
            velocity: &scratch.velocity,
            column,
        };
        let mut out = RodForce::zero();
        self.loads.add_to_rod(i, &view, &mut out);
        seed(scratch, 0.0);
        out
    }

    /// The rod of every unknown (`phi_i, w_i, alpha_i, f_i` belong to rod
    /// `i`; `W`, read by no equation, to rod 0): the Jacobian couples each
    /// rod only to its neighbours, so that the Newton matrices are block
    /// tridiagonal in this grouping.
    pub fn rod_blocks(&self) -> Vec<usize> {
        let n = self.n;
        (0..self.dim())
            .map(|u| match u {
                _ if u < 2 * n => u % n,
                _ if u == 2 * n => 0,
                _ if u < 3 * n + 1 => u - (2 * n + 1),
                _ => (u - (3 * n + 1)) / 2,
            })
            .collect()
    }

    /// The row of `W` left out of [`Self::jacobian_entries`]: `dW'/dw_i`,
    /// written into `out` (length `n`).
    pub fn dissipation_row(&self, w: &[f64], out: &mut [f64]) {
        let n = self.n;
        let r2 = 2.0 * self.chain.damping();
        for i in 0..n {
            let mut d = 0.0;
            if i > 0 {
                d += w[i] - w[i - 1];
            }
            if i + 1 < n {
                d -= w[i + 1] - w[i];
            }
            out[i] = r2 * d;
        }
    }
}

/// One column of the Jacobian: `phi_j` or `w_j`.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Column {
    Phi(usize),
    W(usize),
}

/// [`RodSlices`] over dual numbers whose derivative is along one column:
/// the angles and rates seeded there, every rod's `(sin, cos)`, centre and
/// centre velocity with their exact derivative along it (a centre reads
/// the rods above it: `dc_i/dphi_j = lambda_j v_j` for `j < i`, half that
/// for `j = i`).
struct ColumnView<'a> {
    phi: &'a [Dual],
    w: &'a [Dual],
    trig: &'a [(f64, f64)],
    /// `lambda_i` and `mu_i` (`None`: equal rods), as [`RodSlices`] has them.
    length: Option<&'a [f64]>,
    mass: Option<&'a [f64]>,
    centre: &'a [[f64; 2]],
    velocity: &'a [[f64; 2]],
    column: Column,
}

impl ColumnView<'_> {
    fn length(&self, i: usize) -> f64 {
        self.length.map_or(1.0, |l| l[i])
    }

    /// The share of rod `j`'s `lambda_j` a centre `i` reads: all of it
    /// above `i`, half of it at `i`, none below.
    fn share(&self, i: usize, j: usize) -> f64 {
        match j.cmp(&i) {
            std::cmp::Ordering::Less => self.length(j),
            std::cmp::Ordering::Equal => 0.5 * self.length(j),
            std::cmp::Ordering::Greater => 0.0,
        }
    }
}

impl Kinematics<Dual> for ColumnView<'_> {
    fn angles(&self) -> &[Dual] {
        self.phi
    }
    fn rates(&self) -> &[Dual] {
        self.w
    }
    fn sin_cos(&self, i: usize) -> (Dual, Dual) {
        let (s, c) = self.trig[i];
        let d = self.phi[i].d;
        (Dual::new(s, c * d), Dual::new(c, -s * d))
    }
    fn half_length(&self, i: usize) -> f64 {
        0.5 * self.length(i)
    }
    fn mass(&self, i: usize) -> f64 {
        self.mass.map_or(1.0, |m| m[i])
    }
    fn torque_unit(&self, _i: usize) -> f64 {
        1.0
    }
    fn centre(&self, i: usize) -> [Dual; 2] {
        let [x, y] = self.centre[i];
        let (dx, dy) = match self.column {
            Column::Phi(j) => {
                let (s, c) = self.trig[j];
                let k = self.share(i, j);
                (-s * k, c * k)
            }
            Column::W(_) => (0.0, 0.0),
        };
        [Dual::new(x, dx), Dual::new(y, dy)]
    }
    fn centre_velocity(&self, i: usize) -> [Dual; 2] {
        let [x, y] = self.velocity[i];
        let (dx, dy) = match self.column {
            Column::Phi(j) => {
                let (s, c) = self.trig[j];
                let k = self.share(i, j) * self.w[j].v;
                (-c * k, -s * k)
            }
            Column::W(j) => {
                let (s, c) = self.trig[j];
                let k = self.share(i, j);
                (-s * k, c * k)
            }
        };
        [Dual::new(x, dx), Dual::new(y, dy)]
    }
}

/// The sparse BDF's view of the chain. With a fixed pivot the chain is
/// autonomous; a moving pivot reads `t` (its Jacobian does not: `P0''(t)`
/// does not depend on `y`).
impl SemiExplicitDae for ChainDae {
    fn dim(&self) -> usize {
        ChainDae::dim(self)
    }
    fn differential_dim(&self) -> usize {
        ChainDae::differential_dim(self)
    }
    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) {
        ChainDae::rhs_at(self, t, y, out)
    }
    fn derivatives(&self, t: f64, y: &[f64], out: &mut [f64]) -> bool {
        ChainDae::derivatives_at(self, t, y, out);
        true
    }
    fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        ChainDae::jacobian_entries_at(self, t, y, emit)
    }
    fn blocks(&self) -> Option<Vec<usize>> {
        Some(self.rod_blocks())
    }
}
