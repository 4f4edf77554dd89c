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

use crate::dae::ChainDae;
use crate::scalar::sin_cos;
use fc_methods::SemiExplicitDae;

/// A factor of one contribution: 1, or `cos`, `sin`, `-sin` of rod `i`'s
/// angle, or rod `i`'s world force's `-f_iy` or `f_ix`, packed in a `u32`
/// (the kind in the top [`Factor::KIND_BITS`] bits, `i` below): the
/// pattern is stored once per rod and contribution, about 79 a rod.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Factor(u32);

impl Factor {
    const KIND_BITS: u32 = 3;
    const ROD_BITS: u32 = u32::BITS - Self::KIND_BITS;
    /// The largest rod index a factor holds (`2^29 - 1`, far above
    /// [`crate::chain::MAX_LINKS`]).
    const MAX_ROD: usize = (1 << Self::ROD_BITS) - 1;
    const ONE: Self = Self(0);
    const COS: u32 = 1;
    const SIN: u32 = 2;
    const NEG_SIN: u32 = 3;
    const NEG_FY: u32 = 4;
    const FX: u32 = 5;

    /// The factor of kind `kind` for rod `i` (`i <= MAX_ROD`, checked by
    /// [`RodFrameDae::new`] for the whole chain).
    fn of(kind: u32, i: usize) -> Self {
        Self((kind << Self::ROD_BITS) | (i as u32 & Self::MAX_ROD as u32))
    }

    /// Its value, from every rod's `(sin, cos)` and the world-frame state
    /// `world` whose forces start at `base`.
    #[inline]
    fn value(self, trig: &[(f64, f64)], world: &[f64], base: usize) -> f64 {
        let i = (self.0 & Self::MAX_ROD as u32) as usize;
        match self.0 >> Self::ROD_BITS {
            Self::COS => trig[i].1,
            Self::SIN => trig[i].0,
            Self::NEG_SIN => -trig[i].0,
            Self::NEG_FY => -world[base + 2 * i + 1],
            Self::FX => world[base + 2 * i],
            _ => 1.0,
        }
    }
}

/// One contribution of a [`ChainDae`] entry to an entry of this DAE:
/// `values[slot] += j * row * col`.
#[derive(Clone, Copy, Debug)]
struct Contribution {
    slot: u32,
    row: Factor,
    col: Factor,
}

/// A `(row, column)` pair as one sortable key.
fn key(row: usize, col: usize) -> u64 {
    ((row as u64) << 32) | col as u64
}

/// The pair of a [`key`].
fn pair(key: u64) -> (u32, u32) {
    ((key >> 32) as u32, key as u32)
}

/// [`ChainDae`] in the rods' frames; see the module doc.
#[derive(Clone, Debug)]
pub struct RodFrameDae {
    inner: ChainDae,
    n: usize,
    /// The entries this DAE emits, in order; the turned rows' `d/dphi_i`
    /// are `entries[phi_slots[i]]` (row x) and the next one noted there.
    entries: Vec<(u32, u32)>,
    /// For [`ChainDae`]'s `k`-th entry, `contrib[start[k]..start[k + 1]]`.
    contrib: Vec<Contribution>,
    start: Vec<u32>,
    /// Rod `i`'s two slots `(row x, phi_i)`, `(row y, phi_i)`.
    phi_slots: Vec<(u32, u32)>,
    /// Scratch: the world-frame state, `(sin, cos)` of every angle, the
    /// residual, the entries' values.
    world: RefCell<Vec<f64>>,
    trig: RefCell<Vec<(f64, f64)>>,
    residual: RefCell<Vec<f64>>,
    values: RefCell<Vec<f64>>,
}

impl RodFrameDae {
    /// `dae` in the rods' frames; `None` if its pattern does not fit the
    /// `u32` indices it is stored in (not for a chain of at most
    /// [`crate::chain::MAX_LINKS`] rods: about 79 contributions and 38
    /// entries a rod).
    ///
    /// The pattern costs about 1.4 kB a rod, in `u32`s: each contribution
    /// is noted as a `(row, column)` key, the keys sorted and deduplicated,
    /// and the slots numbered in the order the keys first appear (the
    /// order a `HashMap` gave before, so the entries, their sums and the
    /// runs are bit for bit the same), each contribution's slot found by a
    /// binary search.
    pub fn new(dae: ChainDae) -> Option<Self> {
        let n = dae.links();
        let dim = dae.dim();
        let base = 3 * n + 1;
        if n > Factor::MAX_ROD || u32::try_from(dim).is_err() {
            return None;
        }
        let probe = vec![0.0; dim];
        // Rod i's translation row pair mixes its two world rows (x = c ex +
        // s ey, y = -s ex + c ey); its force columns mix into its two
        // turned ones and its angle (fx = c gx - s gy, fy = s gx + c gy).
        let rows_of = |r: usize| -> [Option<(usize, Factor)>; 2] {
            if r >= base {
                let (i, comp) = ((r - base) / 2, (r - base) % 2);
                let (rx, ry) = (base + 2 * i, base + 2 * i + 1);
                if comp == 0 {
                    [
                        Some((rx, Factor::of(Factor::COS, i))),
                        Some((ry, Factor::of(Factor::NEG_SIN, i))),
                    ]
                } else {
                    [
                        Some((rx, Factor::of(Factor::SIN, i))),
                        Some((ry, Factor::of(Factor::COS, i))),
                    ]
                }
            } else {
                [Some((r, Factor::ONE)), None]
            }
        };
        let cols_of = |c: usize| -> [Option<(usize, Factor)>; 3] {
            if c >= base {
                let (i, comp) = ((c - base) / 2, (c - base) % 2);
                let (gx, gy) = (base + 2 * i, base + 2 * i + 1);
                if comp == 0 {
                    [
                        Some((gx, Factor::of(Factor::COS, i))),
                        Some((gy, Factor::of(Factor::NEG_SIN, i))),
                        Some((i, Factor::of(Factor::NEG_FY, i))),
                    ]
                } else {
                    [
                        Some((gx, Factor::of(Factor::SIN, i))),
                        Some((gy, Factor::of(Factor::COS, i))),
                        Some((i, Factor::of(Factor::FX, i))),
                    ]
                }
            } else {
                [Some((c, Factor::ONE)), None, None]
            }
        };
        // Count first, to hold every list at its exact length.
        let (mut inner, mut count) = (0usize, 0usize);
        dae.jacobian_entries(&probe, |r, c, _| {
            inner += 1;
            count += rows_of(r).iter().flatten().count() * cols_of(c).iter().flatten().count();
        });
        let total = count + 2 * n;
        if u32::try_from(total).is_err() {
            return None;
        }
        // Every contribution's key, in order, then the phi slots' keys.
        let mut keys: Vec<u64> = Vec::with_capacity(total);
        let mut contrib: Vec<Contribution> = Vec::with_capacity(count);
        let mut start: Vec<u32> = Vec::with_capacity(inner + 1);
        dae.jacobian_entries(&probe, |r, c, _| {
            start.push(contrib.len() as u32);
            for &(row, fr) in rows_of(r).iter().flatten() {
                for &(col, fc) in cols_of(c).iter().flatten() {
                    keys.push(key(row, col));
                    contrib.push(Contribution {
                        slot: 0,
                        row: fr,
                        col: fc,
                    });
                }
            }
        });
        start.push(contrib.len() as u32);
        keys.extend((0..n).flat_map(|i| [key(base + 2 * i, i), key(base + 2 * i + 1, i)]));
        if keys.len() != total || contrib.len() != count {
            return None;
        }
        // The distinct keys, sorted; each one's slot in the order of its
        // first appearance.
        let mut distinct = keys.clone();
        distinct.sort_unstable();
        distinct.dedup();
        distinct.shrink_to_fit();
        let mut slot_of = vec![u32::MAX; distinct.len()];
        let mut entries: Vec<(u32, u32)> = Vec::with_capacity(distinct.len());
        let mut slots = keys.iter().map(|k| {
            let p = distinct.binary_search(k).ok()?;
            if slot_of[p] == u32::MAX {
                slot_of[p] = entries.len() as u32;
                entries.push(pair(*k));
            }
            Some(slot_of[p])
        });
        for c in &mut contrib {
            c.slot = slots.next()??;
        }
        let mut phi_slots = Vec::with_capacity(n);
        for _ in 0..n {
            phi_slots.push((slots.next()??, slots.next()??));
        }
        drop(slots);
        let len = entries.len();
        Some(Self {
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
        })
    }

    /// The bytes its pattern holds (entries, contributions, their starts,
    /// the phi slots), by capacity.
    #[cfg(test)]
    fn pattern_bytes(&self) -> usize {
        use std::mem::size_of;
        self.entries.capacity() * size_of::<(u32, u32)>()
            + self.contrib.capacity() * size_of::<Contribution>()
            + self.start.capacity() * size_of::<u32>()
            + self.phi_slots.capacity() * size_of::<(u32, u32)>()
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
        let mut values = self.values.borrow_mut();
        values.fill(0.0);
        let mut k = 0;
        self.inner.jacobian_entries(world, |_, _, j| {
            let (a, b) = (self.start[k] as usize, self.start[k + 1] as usize);
            for c in &self.contrib[a..b] {
                values[c.slot as usize] +=
                    j * c.row.value(trig, world, base) * c.col.value(trig, world, base);
            }
            k += 1;
        });
        // d/dphi_i of the turned rows: (e . v_i, -e . u_i) = (turned y, -turned x).
        for (i, &(sx, sy)) in self.phi_slots.iter().enumerate() {
            values[sx as usize] += residual[base + 2 * i + 1];
            values[sy as usize] -= residual[base + 2 * i];
        }
        for (&(r, c), &v) in self.entries.iter().zip(values.iter()) {
            emit(r as usize, c as usize, v);
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
            let dae = RodFrameDae::new(world_dae.clone()).unwrap();
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
            let dae = RodFrameDae::new(ChainDae::new(&chain).released(free)).unwrap();
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
        let dae = RodFrameDae::new(ChainDae::new(&chain)).unwrap();
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

    /// Every entry is emitted once (bdf writes each into its own CSC
    /// position, so a repeated one would lose a contribution), and the
    /// pattern costs a small, fixed number of bytes a rod: 12 a
    /// contribution, 8 an entry (the `usize` and `HashMap` pattern it
    /// replaces held about 4 kB a rod, and 9.5 kB at its peak).
    #[test]
    fn its_entries_are_distinct_and_its_pattern_small() {
        for links in [1, 2, 7, 1000] {
            for (chain, free) in chains() {
                let chain = Chain::new(ChainParams {
                    links,
                    ..chain.params().clone()
                })
                .unwrap();
                let dae = RodFrameDae::new(ChainDae::new(&chain).released(free)).unwrap();
                let y = state(dae.dim());
                let mut seen = std::collections::HashSet::new();
                let mut count = 0;
                dae.jacobian_entries(0.2, &y, &mut |r, c, _| {
                    assert!(r < dae.dim() && c < dae.dim());
                    assert!(seen.insert((r, c)), "({r}, {c}) emitted twice");
                    count += 1;
                });
                assert_eq!(count, dae.entries.len());
                let per_rod = dae.pattern_bytes() as f64 / links as f64;
                assert!(per_rod < 1500.0, "n = {links}: {per_rod} bytes a rod");
            }
        }
    }
}
