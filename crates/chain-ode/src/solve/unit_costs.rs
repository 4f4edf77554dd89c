//! What one unit of each kind of work that [`Stats`](crate::Stats) counts
//! costs, measured on this machine for one chain at one state, so that a
//! work-precision diagram can weigh BDF's Jacobians and LU factorisations
//! against the explicit methods' right-hand sides instead of leaving them
//! out.
//!
//! Each unit is the code the method runs for it:
//! * `rhs`: [`ChainSystem::rhs`], the explicit methods' one unit;
//! * `bdf`: a residual of the banded DAE ([`ChainDae`]'s right-hand side)
//!   and one solve with the factorised Newton matrix (diffsol's Newton
//!   iteration follows each residual with one solve: `Stats` counts the
//!   residuals only); a Jacobian (its analytic entries); an LU (the Newton
//!   matrix `M - c J` copied into its sparse storage and factorised
//!   block-tridiagonally, [`BlockLu`]);
//! * `bdf-dense`: a right-hand side and one dense solve; a Jacobian (`dim`
//!   Jacobian-vector products, as diffsol builds it column by column); an
//!   LU (faer's fully pivoted dense LU of the `dim x dim` Newton matrix,
//!   as diffsol's `FaerLU` runs it).
//!
//! Times are the fastest of a few batches (s per call): the least
//! disturbed by other work on a shared machine.

use std::hint::black_box;
use std::rc::Rc;
use std::time::Instant;

use diffsol::{FaerVec, Vector};
use diffsol_la::LinearSolver;
use faer::Mat;

use crate::dae::ChainDae;
use crate::dynamics::Workspace;
use crate::{Chain, ChainSystem, State};
use fc_methods::{BlockLu, LuLog, NewtonMatrix, SemiExplicitDae};

/// Seconds per call of each unit of work (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitCosts {
    /// One right-hand side `y' = f(y)` (the explicit methods).
    pub rhs: f64,
    /// `bdf`: one residual and one solve with the Newton matrix.
    pub bdf_residual: f64,
    /// `bdf`: one analytic banded Jacobian.
    pub bdf_jacobian: f64,
    /// `bdf`: one block-tridiagonal LU factorisation.
    pub bdf_lu: f64,
    /// `bdf-dense`: one right-hand side and one dense solve.
    pub dense_residual: f64,
    /// `bdf-dense`: one dense Jacobian (`dim` JVPs).
    pub dense_jacobian: f64,
    /// `bdf-dense`: one dense LU factorisation.
    pub dense_lu: f64,
}

/// Batches timed per unit; the fastest counts.
const BATCHES: usize = 5;
/// A batch lasts at least this long (s).
const BATCH_SECONDS: f64 = 2e-3;
/// The most calls in one batch.
const MAX_CALLS: usize = 1 << 20;

/// Seconds per call of `f`: the fastest of [`BATCHES`] batches, each of
/// as many calls as take [`BATCH_SECONDS`] (at most [`MAX_CALLS`]).
fn per_call(mut f: impl FnMut()) -> f64 {
    let mut calls = 1;
    loop {
        let t = Instant::now();
        for _ in 0..calls {
            f();
        }
        if t.elapsed().as_secs_f64() >= BATCH_SECONDS || calls >= MAX_CALLS {
            break;
        }
        calls *= 2;
    }
    (0..BATCHES)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..calls {
                f();
            }
            t.elapsed().as_secs_f64() / calls as f64
        })
        .fold(f64::INFINITY, f64::min)
}

/// The unit costs of `chain` at `state` (rigid links); `None` if the
/// state is not the chain's size or a Newton matrix could not be built or
/// factorised.
#[doc(hidden)]
pub fn unit_costs(chain: &Chain, state: &State) -> Option<UnitCosts> {
    let n = chain.links();
    if state.angles.len() != n || state.rates.len() != n {
        return None;
    }
    let mut sys = ChainSystem::new(chain);
    let y: Vec<f64> = state
        .angles
        .iter()
        .chain(&state.rates)
        .copied()
        .chain([0.0])
        .collect();
    let (y, dim) = (&y[..], y.len());
    let mut dy = vec![0.0; dim];
    let rhs = per_call(|| sys.rhs(0.0, black_box(y), &mut dy));

    // The banded DAE: its state made consistent, its Newton matrix.
    let dae = ChainDae::new(chain);
    let mut yd = vec![0.0; dae.dim()];
    yd[..dim].copy_from_slice(y);
    dae.make_consistent(&mut yd, &mut Workspace::new(chain.links()));
    let mut out = vec![0.0; dae.dim()];
    let residual = per_call(|| dae.rhs(black_box(&yd), &mut out));
    let mut sink = 0.0;
    let bdf_jacobian = per_call(|| dae.jacobian_entries(black_box(&yd), |_, _, v| sink += v));
    black_box(sink);
    let newton = NewtonMatrix::of(&dae, 0.0, &yd, 1e-3)?;
    let log = Rc::new(LuLog::default());
    let mut lu = BlockLu::new(SemiExplicitDae::blocks(&dae)?, log.clone());
    lu.set_sparsity(&newton);
    let bdf_lu = per_call(|| lu.set_linearisation(black_box(&newton)));
    if log.last_failed.get() {
        return None;
    }
    let mut x = FaerVec::from_vec(out.clone(), newton.ctx);
    let solve = per_call(|| {
        // A failed solve leaves `x` as it was: the time is what counts.
        let _ = lu.solve_in_place(black_box(&mut x));
    });

    // The dense form: `dim` JVPs per Jacobian, a full-pivoting LU.
    let mut v = vec![0.0; dim];
    v[0] = 1.0;
    let mut jv = vec![0.0; dim];
    let jvp = per_call(|| sys.jvp(0.0, black_box(y), &v, &mut jv));
    let m = Mat::<f64>::from_fn(dim, dim, |i, j| {
        f64::from(u8::from(i == j)) + 1e-3 * ((i * 7 + j * 13) % 17) as f64
    });
    let dense_lu = per_call(|| {
        black_box(m.full_piv_lu());
    });
    let factors = m.full_piv_lu();
    let mut b = Mat::<f64>::from_fn(dim, 1, |i, _| i as f64);
    let dense_solve = per_call(|| {
        faer::linalg::solvers::SolveCore::solve_in_place_with_conj(
            &factors,
            faer::Conj::No,
            black_box(b.as_mut()),
        );
    });
    Some(UnitCosts {
        rhs,
        bdf_residual: residual + solve,
        bdf_jacobian,
        bdf_lu,
        dense_residual: rhs + dense_solve,
        dense_jacobian: dim as f64 * jvp,
        dense_lu,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ChainParams, Start, Vec2};

    /// Every unit is measured (finite, positive: no timing is asserted),
    /// and a state of another chain's size is refused.
    #[test]
    fn every_unit_is_measured_and_a_foreign_state_refused() {
        let chain = |n: usize| {
            Chain::new(ChainParams {
                links: n,
                ..ChainParams::default()
            })
            .unwrap()
        };
        let start = Start::Folded {
            p0: Vec2::default(),
            down: None,
        };
        let (c40, c41) = (chain(40), chain(41));
        let c = unit_costs(&c40, &start.state(&c40).unwrap()).unwrap();
        for u in [
            c.rhs,
            c.bdf_residual,
            c.bdf_jacobian,
            c.bdf_lu,
            c.dense_residual,
            c.dense_jacobian,
            c.dense_lu,
        ] {
            assert!(u.is_finite() && u > 0.0, "{c:?}");
        }
        assert_eq!(unit_costs(&c40, &start.state(&c41).unwrap()), None);
    }
}
