//! A sparse LU for diffsol's Newton matrices that fails with an error, not a
//! panic.
//!
//! faer's sparse LU (COLAMD ordering, symbolic factorisation once per
//! pattern, numeric factorisation per Newton matrix) behind diffsol-la's
//! `LinearSolver` trait. diffsol's own `FaerSparseLU` panics when a matrix is
//! singular; here a failed factorisation is logged, and every solve until
//! the next good factorisation returns an error, which diffsol treats as a
//! failed Newton iteration (it retries with a smaller step). A solve that
//! produces a non-finite value (an exactly zero pivot) is a failure too.

use std::cell::{Cell, RefCell};
use std::rc::Rc;

use diffsol::{FaerContext, FaerSparseMat, FaerVec, Matrix, MatrixCommon, Vector};
use diffsol_la::error::{LaError, LinearSolverError};
use diffsol_la::{LinearOp, LinearSolver};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::{Conj, Par};

/// The factorisation of one sparsity pattern.
struct Factors {
    a: FaerSparseMat<f64>,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    /// The last numeric factorisation succeeded.
    ok: bool,
    factor_scratch: MemBuffer,
    solve_scratch: RefCell<MemBuffer>,
}

/// What the factorisations did, shared with the driver that reports it.
#[derive(Debug, Default)]
pub struct LuLog {
    /// Failed factorisations (including those found singular only by the
    /// solve that followed).
    pub failures: Cell<u64>,
    /// The last factorisation failed.
    pub last_failed: Cell<bool>,
}

impl LuLog {
    pub(crate) fn record(&self, ok: bool) {
        self.last_failed.set(!ok);
        if !ok {
            self.failures.set(self.failures.get() + 1);
        }
    }
}

/// Sparse LU with fallible factorisation; see the module doc.
#[derive(Default)]
pub(crate) struct SparseLu {
    factors: Option<Factors>,
    log: Rc<LuLog>,
}

impl SparseLu {
    /// A solver that records its factorisations in `log`.
    pub fn logging(log: Rc<LuLog>) -> Self {
        Self { factors: None, log }
    }

    fn fail(&self) -> LaError {
        LaError::LinearSolverError(LinearSolverError::LuSolveFailed)
    }
}

impl LinearSolver<FaerSparseMat<f64>> for SparseLu {
    fn set_sparsity<
        C: LinearOp<T = f64, V = FaerVec<f64>, M = FaerSparseMat<f64>, C = FaerContext>,
    >(
        &mut self,
        op: &C,
    ) {
        let a =
            FaerSparseMat::new_from_sparsity(op.nrows(), op.ncols(), op.sparsity(), *op.context());
        self.factors = factorize_symbolic_lu(a.inner()[0].symbolic(), Default::default())
            .ok()
            .map(|symbolic| {
                let factor_scratch = MemBuffer::new(
                    symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
                );
                let solve_scratch = RefCell::new(MemBuffer::new(
                    symbolic
                        .solve_in_place_scratch::<f64>(1, Par::Seq)
                        .or(symbolic.solve_transpose_in_place_scratch::<f64>(1, Par::Seq)),
                ));
                Factors {
                    a,
                    symbolic,
                    numeric: NumericLu::new(),
                    ok: false,
                    factor_scratch,
                    solve_scratch,
                }
            });
    }

    fn set_linearisation<
        C: LinearOp<T = f64, V = FaerVec<f64>, M = FaerSparseMat<f64>, C = FaerContext>,
    >(
        &mut self,
        op: &C,
    ) {
        let Some(f) = self.factors.as_mut() else {
            self.log.record(false);
            return;
        };
        op.matrix_inplace(&mut f.a);
        let finite = f.a.inner()[0].val().iter().all(|v| v.is_finite());
        f.ok = finite
            && f.symbolic
                .factorize_numeric_lu(
                    &mut f.numeric,
                    f.a.inner()[0].as_ref(),
                    Par::Seq,
                    MemStack::new(&mut f.factor_scratch),
                    Default::default(),
                )
                .is_ok();
        self.log.record(f.ok);
    }

    fn solve_in_place(&self, x: &mut FaerVec<f64>) -> Result<(), LaError> {
        let Some(f) = self.factors.as_ref().filter(|f| f.ok) else {
            return Err(self.fail());
        };
        let lu = LuRef::new_unchecked(&f.symbolic, &f.numeric);
        let mut scratch = f.solve_scratch.borrow_mut();
        let col = x.inner_mut();
        lu.solve_in_place_with_conj(
            Conj::No,
            col.as_mut(),
            Par::Seq,
            MemStack::new(&mut scratch),
        );
        if col.col_as_slice(0).iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            // An exactly zero pivot passes faer's numeric factorisation and
            // shows up here, as infinities.
            self.log.record(false);
            Err(self.fail())
        }
    }

    fn solve_transpose_in_place(&self, x: &mut FaerVec<f64>) -> Result<(), LaError> {
        let Some(f) = self.factors.as_ref().filter(|f| f.ok) else {
            return Err(self.fail());
        };
        let lu = LuRef::new_unchecked(&f.symbolic, &f.numeric);
        let mut scratch = f.solve_scratch.borrow_mut();
        lu.solve_transpose_in_place_with_conj(
            Conj::No,
            x.inner_mut().as_mut(),
            Par::Seq,
            MemStack::new(&mut scratch),
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::{Pair, SymbolicSparseColMat};

    /// A 3x3 matrix on a tridiagonal pattern, given by its values in CSC order.
    struct Tri {
        values: Vec<f64>,
        ctx: FaerContext,
    }

    impl Tri {
        fn pattern() -> SymbolicSparseColMat<usize> {
            let pairs: Vec<_> = [(0, 0), (1, 0), (0, 1), (1, 1), (2, 1), (1, 2), (2, 2)]
                .iter()
                .map(|&(r, c)| Pair::new(r, c))
                .collect();
            SymbolicSparseColMat::try_new_from_indices(3, 3, &pairs)
                .unwrap()
                .0
        }
    }

    impl LinearOp for Tri {
        type T = f64;
        type V = FaerVec<f64>;
        type M = FaerSparseMat<f64>;
        type C = FaerContext;
        fn nrows(&self) -> usize {
            3
        }
        fn ncols(&self) -> usize {
            3
        }
        fn context(&self) -> &FaerContext {
            &self.ctx
        }
        fn matrix_inplace(&self, y: &mut FaerSparseMat<f64>) {
            y.inner_mut()[0].val_mut().copy_from_slice(&self.values);
        }
        fn sparsity(&self) -> Option<SymbolicSparseColMat<usize>> {
            Some(Self::pattern())
        }
    }

    fn solve(lu: &SparseLu, b: [f64; 3]) -> Result<Vec<f64>, LaError> {
        let mut x = FaerVec::from_vec(b.to_vec(), FaerContext::default());
        lu.solve_in_place(&mut x)?;
        Ok(crate::diffsol_driver::slice(&x).to_vec())
    }

    #[test]
    fn a_singular_matrix_is_an_error_and_a_good_one_recovers() {
        let log = Rc::new(LuLog::default());
        let mut lu = SparseLu::logging(log.clone());
        let ctx = FaerContext::default();
        // [[2, 1, 0], [1, 2, 1], [0, 1, 2]] x = (3, 4, 3): x = (1, 1, 1).
        let good = Tri {
            values: vec![2.0, 1.0, 1.0, 2.0, 1.0, 1.0, 2.0],
            ctx,
        };
        lu.set_sparsity(&good);
        lu.set_linearisation(&good);
        assert!(!log.last_failed.get());
        let x = solve(&lu, [3.0, 4.0, 3.0]).unwrap();
        for v in x {
            assert!((v - 1.0).abs() < 1e-14);
        }
        // Rank 2: the second row is the sum of the others.
        let singular = Tri {
            values: vec![1.0, 1.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            ctx,
        };
        lu.set_linearisation(&singular);
        assert!(solve(&lu, [1.0, 2.0, 1.0]).is_err());
        assert!(log.last_failed.get());
        assert_eq!(log.failures.get(), 1);
        // A non-finite matrix is a failure too, not a NaN solution.
        let nan = Tri {
            values: vec![2.0, f64::NAN, 1.0, 2.0, 1.0, 1.0, 2.0],
            ctx,
        };
        lu.set_linearisation(&nan);
        assert_eq!(log.failures.get(), 2);
        assert!(solve(&lu, [1.0, 2.0, 1.0]).is_err());
        // The next good matrix factorises again.
        lu.set_linearisation(&good);
        assert!(!log.last_failed.get());
        assert!(solve(&lu, [3.0, 4.0, 3.0]).is_ok());
    }
}
