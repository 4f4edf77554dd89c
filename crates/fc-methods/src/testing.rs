//! Test support: what the integrators' own tests share with the tests of
//! problems defined elsewhere (the chains, whose banded DAEs the sparse BDF
//! and its block LU are checked on): an observer that records nothing,
//! the run of a DAE and which LU it gets, the block LU against a dense
//! solve, and the block layout of a DAE's Newton matrix.
#![allow(
    clippy::unwrap_used,
    reason = "test support: a failed step of a check fails the test"
)]

use std::rc::Rc;

use diffsol::{FaerVec, Vector};
use diffsol_la::LinearSolver;

pub use super::bdf::{integrate_dae, picks_block_lu};
pub use super::block_lu::BlockLayout;
use super::block_lu::BlockLu;
use super::diffsol_driver::slice;
use super::newton_matrix::NewtonMatrix;
use super::sparse_lu::LuLog;
use crate::ode::{Observer, SemiExplicitDae, StepView};

/// Records nothing.
pub struct Quiet;

impl Observer for Quiet {
    fn start(&mut self, _: f64, _: &[f64], _: &[f64]) {}
    fn step(&mut self, _: &StepView<'_>) {}
}

/// The dense reference solve, on the Newton matrix's dense copy.
pub trait DenseSolve {
    /// `A^-1 b`, or `A^-T b` if `transpose`.
    fn solve(&self, b: &[f64], transpose: bool) -> Vec<f64>;
}

impl DenseSolve for NewtonMatrix {
    /// `A^-1 b` (`A^-T b`) by Gaussian elimination with partial pivoting
    /// on the whole matrix.
    fn solve(&self, b: &[f64], transpose: bool) -> Vec<f64> {
        let n = self.dim;
        let mut m: Vec<f64> = (0..n * n)
            .map(|k| {
                let (i, j) = (k / n, k % n);
                if transpose {
                    self.a[j * n + i]
                } else {
                    self.a[k]
                }
            })
            .collect();
        let mut x = b.to_vec();
        for j in 0..n {
            let p = (j..n)
                .max_by(|&r, &s| m[r * n + j].abs().total_cmp(&m[s * n + j].abs()))
                .unwrap();
            for c in 0..n {
                m.swap(j * n + c, p * n + c);
            }
            x.swap(j, p);
            for i in j + 1..n {
                let l = m[i * n + j] / m[j * n + j];
                for c in j..n {
                    m[i * n + c] -= l * m[j * n + c];
                }
                x[i] -= l * x[j];
            }
        }
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|c| m[i * n + c] * x[c]).sum();
            x[i] = (x[i] - s) / m[i * n + i];
        }
        x
    }
}

/// A reproducible sequence in `[-1, 1)`.
pub struct Lcg(pub u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// Solves `M - c J` of `dae` at a random state both ways (and
/// transposed) against the dense solve; returns the largest error
/// relative to the solution's size.
pub fn worst_error<D: SemiExplicitDae>(dae: &D, y: &[f64], c: f64, rng: &mut Lcg) -> f64 {
    let m = NewtonMatrix::of(dae, 0.0, y, c).unwrap();
    let log = Rc::new(LuLog::default());
    let mut lu = BlockLu::new(dae.blocks().unwrap(), log.clone());
    lu.set_sparsity(&m);
    assert!(lu.factors.is_some(), "the layout was refused");
    lu.set_linearisation(&m);
    assert!(!log.last_failed.get());
    let mut worst: f64 = 0.0;
    for transpose in [false, true] {
        let b: Vec<f64> = (0..m.dim).map(|_| rng.next()).collect();
        let want = m.solve(&b, transpose);
        let mut x = FaerVec::from_vec(b, m.ctx);
        if transpose {
            lu.solve_transpose_in_place(&mut x).unwrap();
        } else {
            lu.solve_in_place(&mut x).unwrap();
        }
        let size = want.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
        let diff = slice(&x)
            .iter()
            .zip(&want)
            .fold(0.0_f64, |s, (a, b)| s.max((a - b).abs()));
        worst = worst.max(diff / size);
    }
    worst
}

/// A random consistent-looking state of `dim` unknowns: angles in
/// `[-pi, pi)`, everything else in `[-scale, scale)`.
pub fn random_state(dim: usize, n: usize, scale: f64, rng: &mut Lcg) -> Vec<f64> {
    (0..dim)
        .map(|u| {
            if u < n {
                std::f64::consts::PI * rng.next()
            } else {
                scale * rng.next()
            }
        })
        .collect()
}

/// The layout of `dae`'s Newton matrix.
pub fn layout_of<D: SemiExplicitDae>(dae: &D) -> BlockLayout {
    let y = vec![0.1; dae.dim()];
    let m = NewtonMatrix::of(dae, 0.0, &y, 0.01).unwrap();
    BlockLayout::new(&dae.blocks().unwrap(), m.pattern.as_ref()).unwrap()
}
