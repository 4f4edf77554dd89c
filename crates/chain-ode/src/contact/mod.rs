//! The rigid chain on a constraint floor, as a [`Nonsmooth`] problem for
//! `moreau-jean` (`docs/model.md`, "The floor as a constraint"): the rods
//! in maximal coordinates ([`rods`]), the joints between them (and to the
//! pivot while it holds) as bilateral rows, and the contacts as sets of
//! unilateral rows at the joints ([`ContactSet`]; the floor's is
//! [`floor_set::FloorSet`]).
//!
//! **Blocks.** Block `k` (`k = 0..=n`) is joint `k`: its two bilateral
//! rows (`end(k−1) − start(k) = 0`; the pivot's `start(0) = P0` while it
//! holds; none at the tip), then each contact set's rows at that joint.
//! Block `k` touches rods `k − 1` and `k` only, so the Delassus matrix is
//! block tridiagonal and every solve of a step is O(n)
//! (`fc_methods::Nonsmooth`). A contact at joint `k < n` acts on rod `k`'s
//! start, the tip's on rod `n − 1`'s end: the joint's two rows pass it on.
//!
//! **State** (`10 n + 5`): `[theta, w, W, x, y, vx, vy]` as the elastic
//! chain's (rod centres relative to the start's anchor), then each joint's
//! contact force and joint force averaged over the step that ended there
//! (`2 (n + 1)` each; [`Offsets`]).
//!
//! Its files: `floor_set.rs` (the floor's rows: gaps, normals and tangents
//! at the joints).

pub mod floor_set;
pub mod rods;

use fc_methods::{Nonsmooth, OdeSystem, Problem, Row, RowKind, StepRecord, MAX_BODY};

use crate::chain::Chain;
use crate::kinematics::Vec2;
use floor_set::FloorSet;
use rods::{End, Rods, BODY};

/// A set of unilateral contacts at the chain's joints: the rows it adds to
/// each joint's block. The floor is one ([`FloorSet`]); a pot's walls
/// (the chain fountain) would be another, rows of each joint against the
/// walls it may touch. Contact between two rods far apart along the chain
/// (a pile) is not such a set: its rows would join blocks that are not
/// neighbours (docs/model.md, "What further contacts would take").
pub trait ContactSet {
    /// Rows per joint.
    fn rows_per_joint(&self) -> usize;
    /// Its rows at the joint point `p` whose Jacobian on the rod that
    /// carries it is `jac` (two rows, `dp/d(x, y, theta)`), that rod being
    /// the block's `half` (0: rod `k − 1`, 1: rod `k`).
    fn joint_rows(&self, p: Vec2, jac: &[[f64; BODY]; 2], half: usize, out: &mut [Row]);
    /// The force its rows' `impulses` (one joint's) exert over a step of
    /// `h`, averaged (physical units, the plane's axes).
    fn force(&self, impulses: &[f64], h: f64) -> Vec2;
}

/// Rows of each block: the joint's two, the floor's two.
pub const BLOCK_ROWS: usize = 4;

/// Where the parts of the state are, for `n` rods.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Offsets {
    pub n: usize,
}

impl Offsets {
    /// `theta_i`.
    pub fn theta(self) -> usize {
        0
    }
    /// `w_i`.
    pub fn w(self) -> usize {
        self.n
    }
    /// `W`.
    pub fn work(self) -> usize {
        2 * self.n
    }
    /// `x_i`, then `y_i` at `+ n`.
    pub fn x(self) -> usize {
        2 * self.n + 1
    }
    /// `vx_i`, then `vy_i` at `+ n`.
    pub fn vx(self) -> usize {
        4 * self.n + 1
    }
    /// Each joint's contact force `(Fx, Fy)`, `2 (n + 1)`.
    pub fn contact(self) -> usize {
        6 * self.n + 1
    }
    /// Each joint's force on the rod after it `(Fx, Fy)`, `2 (n + 1)`.
    pub fn joint(self) -> usize {
        8 * self.n + 3
    }
    /// The state's length.
    pub fn dim(self) -> usize {
        10 * self.n + 5
    }
}

/// The chain on its contact sets, as the method sees it.
pub struct ContactChain {
    rods: Rods,
    /// The pivot holds joint 0 (until a release).
    held: bool,
    floor: FloorSet,
    minv: Vec<f64>,
}

impl ContactChain {
    /// The rods of `chain` on `floor`, joint 0 held at the anchor when
    /// `held`.
    pub fn new(chain: &Chain, floor: FloorSet, held: bool) -> Self {
        let rods = Rods::of(chain);
        let mut minv = vec![0.0; BODY * rods.len()];
        rods.inverse_mass(&mut minv);
        Self {
            rods,
            held,
            floor,
            minv,
        }
    }

    fn offsets(&self) -> Offsets {
        Offsets { n: self.rods.len() }
    }

    /// `q` and `v` of the state `y` (rod by rod: `x, y, theta`).
    fn load(&self, y: &[f64], q: &mut [f64], v: &mut [f64]) {
        let o = self.offsets();
        let n = o.n;
        for i in 0..n {
            q[BODY * i] = y[o.x() + i];
            q[BODY * i + 1] = y[o.x() + n + i];
            q[BODY * i + 2] = y[o.theta() + i];
            v[BODY * i] = y[o.vx() + i];
            v[BODY * i + 1] = y[o.vx() + n + i];
            v[BODY * i + 2] = y[o.w() + i];
        }
    }
}

impl Nonsmooth for ContactChain {
    fn bodies(&self) -> usize {
        self.rods.len()
    }

    fn body_dim(&self) -> usize {
        BODY
    }

    fn block_rows(&self) -> usize {
        BLOCK_ROWS
    }

    fn inverse_mass(&self, out: &mut [f64]) {
        out.copy_from_slice(&self.minv);
    }

    fn coordinates(&self, y: &[f64], q: &mut [f64], v: &mut [f64]) {
        self.load(y, q, v);
    }

    fn forces(&mut self, _t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        self.rods.forces(q, v, f);
    }

    fn rows(&mut self, _t: f64, q: &[f64], rows: &mut [Row]) {
        let n = self.rods.len();
        for k in 0..=n {
            let block = &mut rows[BLOCK_ROWS * k..BLOCK_ROWS * (k + 1)];
            // The joint: end(k − 1) − start(k) = 0 (the pivot's
            // start(0) − P0 = 0, P0 the frame's origin).
            let start = (k < n).then(|| self.rods.point(q, k, End::Start));
            let end = k.checked_sub(1).map(|i| self.rods.point(q, i, End::End));
            let joint = match (end, start) {
                (Some((pe, je)), Some((ps, js))) => Some(([pe[0] - ps[0], pe[1] - ps[1]], je, js)),
                (None, Some((ps, js))) if self.held => Some((ps, [[0.0; BODY]; 2], js)),
                _ => None,
            };
            for d in 0..2 {
                block[d] = match joint {
                    Some((g, je, js)) => {
                        // The pivot's row reads +start(0), the others
                        // end(k − 1) − start(k).
                        let sign = if k == 0 { 1.0 } else { -1.0 };
                        let mut jac = [0.0; 2 * MAX_BODY];
                        jac[..BODY].copy_from_slice(&je[d]);
                        for (j, s) in jac[MAX_BODY..MAX_BODY + BODY].iter_mut().zip(&js[d]) {
                            *j = sign * s;
                        }
                        Row {
                            kind: RowKind::Bilateral,
                            jac,
                            gap: g[d],
                        }
                    }
                    None => Row::OFF,
                };
            }
            // The contact point: rod k's start, or the tip (rod n − 1's end).
            let (p, jac, half) = match (start, end) {
                (Some((p, j)), _) => (p, j, 1),
                (None, Some((p, j))) => (p, j, 0),
                (None, None) => ([0.0, 0.0], [[0.0; BODY]; 2], 1),
            };
            self.floor.joint_rows(p, &jac, half, &mut block[2..4]);
        }
    }

    fn state(&mut self, step: &StepRecord<'_>, y: &mut [f64]) {
        let o = self.offsets();
        let n = o.n;
        for i in 0..n {
            y[o.x() + i] = step.q[BODY * i];
            y[o.x() + n + i] = step.q[BODY * i + 1];
            y[o.theta() + i] = step.q[BODY * i + 2];
            y[o.vx() + i] = step.v[BODY * i];
            y[o.vx() + n + i] = step.v[BODY * i + 1];
            y[o.w() + i] = step.v[BODY * i + 2];
        }
        y[o.work()] += step.contact_work + self.rods.friction_work(step.h, step.v0, step.v);
        for k in 0..=n {
            let p = &step.impulses[BLOCK_ROWS * k..BLOCK_ROWS * (k + 1)];
            let f = self.floor.force(&p[2..4], step.h);
            y[o.contact() + 2 * k] = f[0];
            y[o.contact() + 2 * k + 1] = f[1];
            // Joint k's force on rod k: `−P / h` of the row
            // end(k − 1) − start(k); the pivot's row reads +start(0).
            let sign = if k == 0 { 1.0 } else { -1.0 };
            y[o.joint() + 2 * k] = sign * p[0] / step.h;
            y[o.joint() + 2 * k + 1] = sign * p[1] / step.h;
        }
    }
}

/// The smooth part alone (`q' = v`, `M v' = f`): what a method of smooth
/// problems would integrate, without the joints and the contacts. Only
/// `moreau-jean` runs this problem (the model refuses the others); its
/// right-hand side gives the observer the free motion's derivative at the
/// start.
impl OdeSystem for ContactChain {
    fn dim(&self) -> usize {
        self.offsets().dim()
    }

    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        self.smooth(y, dy, true);
    }

    /// Exact: gravity is constant, bending linear in the angles and the
    /// joints' friction in the rates.
    fn jvp(&mut self, _t: f64, _y: &[f64], v: &[f64], jv: &mut [f64]) {
        self.smooth(v, jv, false);
    }
}

impl ContactChain {
    /// `dy = (v, M⁻¹ f)` of `y` (`gravity`: with gravity; without, the
    /// linear part alone, the Jacobian's product).
    fn smooth(&self, y: &[f64], dy: &mut [f64], gravity: bool) {
        let o = self.offsets();
        let n = o.n;
        let (mut q, mut v, mut f) = (
            vec![0.0; BODY * n],
            vec![0.0; BODY * n],
            vec![0.0; BODY * n],
        );
        self.load(y, &mut q, &mut v);
        if gravity {
            self.rods.gravity_load(&mut f);
        }
        self.rods.friction_load(&v, &mut f);
        self.rods.bending_load(&q, &mut f);
        dy.fill(0.0);
        for i in 0..n {
            dy[o.theta() + i] = v[BODY * i + 2];
            dy[o.x() + i] = v[BODY * i];
            dy[o.x() + n + i] = v[BODY * i + 1];
            dy[o.w() + i] = self.minv[BODY * i + 2] * f[BODY * i + 2];
            dy[o.vx() + i] = self.minv[BODY * i] * f[BODY * i];
            dy[o.vx() + n + i] = self.minv[BODY * i + 1] * f[BODY * i + 1];
        }
    }
}

impl Problem for ContactChain {
    fn nonsmooth(&mut self) -> Option<&mut dyn Nonsmooth> {
        Some(self)
    }
}
