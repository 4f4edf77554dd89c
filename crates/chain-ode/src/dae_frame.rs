//! [`ChainDae`] in the rods' frames: the form `bdf` integrates.
//!
//! [`ChainDae`] states its joint forces `f_i` and its translation rows in
//! world components. Both turn with the rods' absolute angles, so its
//! Jacobian does too, and a Newton matrix kept from a few steps back is
//! wrong by the chain's rotation since: diffsol's simplified Newton then
//! stalls on a chain that swings (convergence failures, each a new Jacobian
//! and LU; measured in docs/model.md, "The Newton matrix in the rods'
//! frames"). Here
//! * the force unknowns are `g_i = (f_i . u_i, f_i . v_i)`, the force along
//!   and across rod `i` (`f_i = g_ix u_i + g_iy v_i`), and
//! * the translation row pair of rod `i` is [`ChainDae`]'s turned into rod
//!   `i`'s frame, `(e . u_i, e . v_i)` for its residual `e`.
//!
//! Every coefficient of the Jacobian then reads the rods' relative angles
//! only, except gravity's and the pivot's in rod 0's row. The solution is
//! [`ChainDae`]'s (the rows vanish together, the unknowns map one to one),
//! the unknowns and rods are the same (`g_i` in `f_i`'s place), so the
//! Newton matrices stay block tridiagonal. The Jacobian is [`ChainDae`]'s by
//! the chain rule: `df_i/dg_i = R(phi_i)`, `df_i/dphi_i = (-f_iy, f_ix)`,
//! and a turned row pair's `d/dphi_i` has the extra `(e . v_i, -e . u_i)`,
//! which needs the residual: one evaluation of [`ChainDae`] per Jacobian.

use std::cell::RefCell;
use std::collections::HashMap;

use crate::dae::ChainDae;
use crate::scalar::sin_cos;
use fc_methods::SemiExplicitDae;

/// A factor of one contribution: 1, or `cos`, `sin`, `-sin` of rod `i`'s
/// angle, or rod `i`'s world force's `-f_iy` or `f_ix`.
#[derive(Clone, Copy, Debug)]
enum Factor {
    One,
    Cos(usize),
    Sin(usize),
    NegSin(usize),
    NegFy(usize),
    Fx(usize),
}

/// [`ChainDae`] in the rods' frames; see the module doc.
#[derive(Clone, Debug)]
pub struct RodFrameDae {
    inner: ChainDae,
    n: usize,
    /// The entries this DAE emits, in order; the turned rows' `d/dphi_i`
    /// are `entries[phi_slots[i]]` (row x) and the next one noted there.
    entries: Vec<(usize, usize)>,
    /// For [`ChainDae`]'s `k`-th entry, `contrib[start[k]..start[k + 1]]`:
    /// `(slot, row factor, column factor)`.
    contrib: Vec<(usize, Factor, Factor)>,
    start: Vec<usize>,
    /// Rod `i`'s two slots `(row x, phi_i)`, `(row y, phi_i)`.
    phi_slots: Vec<(usize, usize)>,
    /// Scratch: the world-frame state, `(sin, cos)` of every angle, the
    /// residual, the entries' values.
    world: RefCell<Vec<f64>>,
    trig: RefCell<Vec<(f64, f64)>>,
    residual: RefCell<Vec<f64>>,
    values: RefCell<Vec<f64>>,
}

impl RodFrameDae {
    /// `dae` in the rods' frames.
    pub fn new(dae: ChainDae) -> Self {
        let n = dae.links();
        let base = 3 * n + 1;
        let mut inner_entries = Vec::new();
        let probe = vec![0.0; dae.dim()];
        dae.jacobian_entries(&probe, |r, c, _| inner_entries.push((r, c)));
        let mut entries: Vec<(usize, usize)> = Vec::new();
        let mut slot: HashMap<(usize, usize), usize> = HashMap::new();
        let mut place = |rc: (usize, usize), entries: &mut Vec<(usize, usize)>| -> usize {
            *slot.entry(rc).or_insert_with(|| {
                entries.push(rc);
                entries.len() - 1
            })
        };
        let mut contrib = Vec::new();
        let mut start = Vec::with_capacity(inner_entries.len() + 1);
        for &(r, c) in &inner_entries {
            start.push(contrib.len());
            // A translation row of rod i: x = c ex + s ey, y = -s ex + c ey.
            let rows: Vec<(usize, Factor)> = if r >= base {
                let (i, comp) = ((r - base) / 2, (r - base) % 2);
                let (rx, ry) = (base + 2 * i, base + 2 * i + 1);
                if comp == 0 {
                    vec![(rx, Factor::Cos(i)), (ry, Factor::NegSin(i))]
                } else {
                    vec![(rx, Factor::Sin(i)), (ry, Factor::Cos(i))]
                }
            } else {
                vec![(r, Factor::One)]
            };
            // A force column of rod i: fx = c gx - s gy, fy = s gx + c gy.
            let cols: Vec<(usize, Factor)> = if c >= base {
                let (i, comp) = ((c - base) / 2, (c - base) % 2);
                let (gx, gy) = (base + 2 * i, base + 2 * i + 1);
                if comp == 0 {
                    vec![
                        (gx, Factor::Cos(i)),
                        (gy, Factor::NegSin(i)),
                        (i, Factor::NegFy(i)),
                    ]
                } else {
                    vec![
                        (gx, Factor::Sin(i)),
                        (gy, Factor::Cos(i)),
                        (i, Factor::Fx(i)),
                    ]
                }
            } else {
                vec![(c, Factor::One)]
            };
            for &(row, fr) in &rows {
                for &(col, fc) in &cols {
                    contrib.push((place((row, col), &mut entries), fr, fc));
                }
            }
        }
        start.push(contrib.len());
        let phi_slots = (0..n)
            .map(|i| {
                (
                    place((base + 2 * i, i), &mut entries),
                    place((base + 2 * i + 1, i), &mut entries),
                )
            })
            .collect();
        let dim = dae.dim();
        let len = entries.len();
        Self {
            inner: dae,
            n,
            entries,
            contrib,
            start,
            phi_slots,
            world: RefCell::new(vec![0.0; dim]),
            trig: RefCell::new(vec![(0.0, 1.0); n]),
            residual: RefCell::new(vec![0.0; dim]),
            values: RefCell::new(vec![0.0; len]),
        }
    }

    /// [`ChainDae`]'s state from this DAE's `y` (and every rod's `(sin, cos)`).
    fn to_world(&self, y: &[f64], world: &mut [f64], trig: &mut [(f64, f64)]) {
        let n = self.n;
        world.copy_from_slice(y);
        for i in 0..n {
            let (s, c) = sin_cos(y[i]);
            trig[i] = (s, c);
            let k = 3 * n + 1 + 2 * i;
            let (gx, gy) = (y[k], y[k + 1]);
            world[k] = gx * c - gy * s;
            world[k + 1] = gx * s + gy * c;
        }
    }

    /// This DAE's state from [`ChainDae`]'s `world` one (the consistent start).
    pub fn from_world(&self, world: &[f64]) -> Vec<f64> {
        let n = self.n;
        let mut y = world.to_vec();
        for i in 0..n {
            let (s, c) = sin_cos(world[i]);
            let k = 3 * n + 1 + 2 * i;
            let (fx, fy) = (world[k], world[k + 1]);
            y[k] = fx * c + fy * s;
            y[k + 1] = -fx * s + fy * c;
        }
        y
    }

    /// `out = f(t, y)`, with `world` and `trig` filled for `y`.
    fn rhs_into(
        &self,
        t: f64,
        y: &[f64],
        out: &mut [f64],
        world: &mut [f64],
        trig: &mut [(f64, f64)],
    ) {
        let n = self.n;
        self.to_world(y, world, trig);
        self.inner.rhs_at(t, world, out);
        for (i, &(s, c)) in trig.iter().enumerate() {
            let k = 3 * n + 1 + 2 * i;
            let (ex, ey) = (out[k], out[k + 1]);
            out[k] = c * ex + s * ey;
            out[k + 1] = -s * ex + c * ey;
        }
    }
}

impl SemiExplicitDae for RodFrameDae {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn differential_dim(&self) -> usize {
        self.inner.differential_dim()
    }
    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) {
        let (mut world, mut trig) = (self.world.borrow_mut(), self.trig.borrow_mut());
        self.rhs_into(t, y, out, &mut world, &mut trig);
    }
    fn derivatives(&self, t: f64, y: &[f64], out: &mut [f64]) -> bool {
        let (mut world, mut trig) = (self.world.borrow_mut(), self.trig.borrow_mut());
        self.to_world(y, &mut world, &mut trig);
        SemiExplicitDae::derivatives(&self.inner, t, &world, out)
    }
    fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        let n = self.n;
        let base = 3 * n + 1;
        let (mut world, mut trig) = (self.world.borrow_mut(), self.trig.borrow_mut());
        let mut residual = self.residual.borrow_mut();
        self.rhs_into(t, y, &mut residual, &mut world, &mut trig);
        let (world, trig) = (&*world, &*trig);
        let factor = |f: Factor| match f {
            Factor::One => 1.0,
            Factor::Cos(i) => trig[i].1,
            Factor::Sin(i) => trig[i].0,
            Factor::NegSin(i) => -trig[i].0,
            Factor::NegFy(i) => -world[base + 2 * i + 1],
            Factor::Fx(i) => world[base + 2 * i],
        };
        let mut values = self.values.borrow_mut();
        values.fill(0.0);
        let mut k = 0;
        self.inner.jacobian_entries(world, |_, _, j| {
            for &(s, fr, fc) in &self.contrib[self.start[k]..self.start[k + 1]] {
                values[s] += j * factor(fr) * factor(fc);
            }
            k += 1;
        });
        // d/dphi_i of the turned rows: (e . v_i, -e . u_i) = (turned y, -turned x).
        for (i, &(sx, sy)) in self.phi_slots.iter().enumerate() {
            values[sx] += residual[base + 2 * i + 1];
            values[sy] -= residual[base + 2 * i];
        }
        for (&(r, c), &v) in self.entries.iter().zip(values.iter()) {
            emit(r, c, v);
        }
    }
    fn blocks(&self) -> Option<Vec<usize>> {
        Some(self.inner.rod_blocks())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::{Chain, ChainParams};
    use crate::dynamics::Workspace;
    use crate::pivot::Pivot;

    /// Chains with every term: friction, bending, a tip mass, and a fixed,
    /// a driven and a released pivot (`free`).
    fn chains() -> Vec<(Chain, bool)> {
        let driven = Pivot {
            amplitude: [0.1, 0.05],
            frequency: 3.0,
            ..Pivot::default()
        };
        let released = Pivot {
            release: Some(0.0),
            ..Pivot::default()
        };
        [(Pivot::default(), false), (driven, false), (released, true)]
            .into_iter()
            .map(|(pivot, free)| {
                let chain = Chain::new(ChainParams {
                    links: 7,
                    damping: 0.3,
                    bending_stiffness: 0.1,
                    tip_mass: 0.4,
                    pivot,
                    ..ChainParams::default()
                })
                .unwrap();
                (chain, free)
            })
            .collect()
    }

    /// An arbitrary (inconsistent) state: every unknown different.
    fn state(dim: usize) -> Vec<f64> {
        (0..dim)
            .map(|k| ((k * 7 + 3) % 11) as f64 * 0.37 - 1.5)
            .collect()
    }

    fn dense_jacobian(dae: &RodFrameDae, t: f64, y: &[f64]) -> Vec<f64> {
        let dim = dae.dim();
        let mut jac = vec![0.0; dim * dim];
        dae.jacobian_entries(t, y, &mut |r, c, v| jac[r * dim + c] += v);
        jac
    }

    /// At `ChainDae`'s consistent start, turned, the algebraic rows vanish
    /// and the derivatives are `ChainDae`'s: the same solution.
    #[test]
    fn the_turned_start_is_consistent_and_moves_as_the_world_frame_dae() {
        for (chain, free) in chains() {
            let world_dae = ChainDae::new(&chain).released(free);
            let n = chain.links();
            let mut world = vec![0.0; world_dae.dim()];
            world[..2 * n].copy_from_slice(&state(2 * n));
            let t = 0.3;
            world_dae.make_consistent_at(t, &mut world, &mut Workspace::new(n));
            let dae = RodFrameDae::new(world_dae.clone());
            let y = dae.from_world(&world);
            let (mut a, mut b) = (vec![0.0; dae.dim()], vec![0.0; dae.dim()]);
            SemiExplicitDae::rhs(&dae, t, &y, &mut a);
            world_dae.rhs_at(t, &world, &mut b);
            let d = dae.differential_dim();
            for k in 0..d {
                assert!((a[k] - b[k]).abs() <= 1e-13 * b[k].abs().max(1.0), "{k}");
            }
            for (k, r) in a[d..].iter().enumerate() {
                assert!(r.abs() < 1e-10, "free {free}: algebraic row {k}: {r}");
            }
            // The turned forces are the world ones along and across the rods.
            for i in 0..n {
                let k = 3 * n + 1 + 2 * i;
                let (s, c) = sin_cos(world[i]);
                let (fx, fy) = (world[k], world[k + 1]);
                assert!((y[k] - (fx * c + fy * s)).abs() < 1e-14 * fx.hypot(fy).max(1.0));
                assert!((y[k + 1] - (fy * c - fx * s)).abs() < 1e-14 * fx.hypot(fy).max(1.0));
            }
        }
    }

    /// The emitted Jacobian is the central difference of the residual, at
    /// an arbitrary state, entry by entry.
    #[test]
    fn its_jacobian_is_the_central_difference_of_its_residual() {
        for (chain, free) in chains() {
            let dae = RodFrameDae::new(ChainDae::new(&chain).released(free));
            let dim = dae.dim();
            let (t, y) = (0.7, state(dim));
            let jac = dense_jacobian(&dae, t, &y);
            let step = 1e-6;
            let (mut up, mut down) = (vec![0.0; dim], vec![0.0; dim]);
            for c in 0..dim {
                let (mut yp, mut ym) = (y.clone(), y.clone());
                yp[c] += step;
                ym[c] -= step;
                SemiExplicitDae::rhs(&dae, t, &yp, &mut up);
                SemiExplicitDae::rhs(&dae, t, &ym, &mut down);
                // The row of W is left out, as in ChainDae.
                for r in (0..dim).filter(|&r| r != 2 * chain.links()) {
                    let fd = (up[r] - down[r]) / (2.0 * step);
                    let err = (jac[r * dim + c] - fd).abs();
                    assert!(
                        err < 1e-6 * fd.abs().max(1.0),
                        "free {free}: ({r}, {c}): {} vs {fd}",
                        jac[r * dim + c]
                    );
                }
            }
        }
    }

    /// Turning the whole chain (every angle by the same amount, the turned
    /// forces kept) leaves the Jacobian as it was, but for the two entries
    /// through which gravity pulls rod 0 (its turned translation rows'
    /// `d/dphi_0`): a Newton matrix kept while the chain swings stays right.
    #[test]
    fn its_jacobian_does_not_turn_with_the_chain() {
        let chain = Chain::new(ChainParams {
            links: 9,
            damping: 0.3,
            tip_mass: 0.2,
            ..ChainParams::default()
        })
        .unwrap();
        let n = chain.links();
        let dae = RodFrameDae::new(ChainDae::new(&chain));
        let dim = dae.dim();
        let y = state(dim);
        let mut turned = y.clone();
        for phi in &mut turned[..n] {
            *phi += 0.4;
        }
        let (a, b) = (
            dense_jacobian(&dae, 0.0, &y),
            dense_jacobian(&dae, 0.0, &turned),
        );
        let gravity = [(3 * n + 1, 0), (3 * n + 2, 0)];
        let mut moved = 0;
        for r in 0..dim {
            for c in 0..dim {
                let (x, z) = (a[r * dim + c], b[r * dim + c]);
                if gravity.contains(&(r, c)) {
                    moved += usize::from((x - z).abs() > 1e-3);
                } else {
                    assert!(
                        (x - z).abs() < 1e-12 * x.abs().max(1.0),
                        "({r}, {c}): {x} vs {z}"
                    );
                }
            }
        }
        // Gravity's own entries do turn (a check that the state was turned).
        assert!(moved > 0);
    }

    /// The DAE that `bdf` runs on the chain (`ChainSystem::banded_dae`) is
    /// this one: its Jacobian does not turn with the chain either.
    #[test]
    fn the_chains_bdf_runs_the_turned_form() {
        use fc_methods::Problem;
        let chain = Chain::new(ChainParams {
            links: 9,
            damping: 0.3,
            ..ChainParams::default()
        })
        .unwrap();
        let n = chain.links();
        let sys = crate::system::ChainSystem::new(&chain);
        let y0 = state(2 * n + 1);
        let banded = sys.banded_dae(0.0, &y0).unwrap();
        let dim = banded.dae.dim();
        let y = state(dim);
        let mut turned = y.clone();
        for phi in &mut turned[..n] {
            *phi += 0.4;
        }
        let jac = |y: &[f64]| {
            let mut m = vec![0.0; dim * dim];
            banded
                .dae
                .jacobian_entries(0.0, y, &mut |r, c, v| m[r * dim + c] += v);
            m
        };
        let (a, b) = (jac(&y), jac(&turned));
        let changed = (0..dim * dim)
            .filter(|&k| ![(3 * n + 1) * dim, (3 * n + 2) * dim].contains(&k))
            .filter(|&k| (a[k] - b[k]).abs() > 1e-12 * a[k].abs().max(1.0))
            .count();
        assert_eq!(changed, 0, "entries that turn with the chain");
    }
}
