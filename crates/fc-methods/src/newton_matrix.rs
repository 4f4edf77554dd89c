//! The Newton matrix `M - c J` of a semi-explicit DAE at a state, held
//! dense on its sparsity pattern, as diffsol hands it to a linear solver:
//! what `unit_costs` times the linear solvers on, and what the block LU's
//! tests solve against. Not on any solver's path (it is `O(dim^2)`).

use diffsol::FaerContext;
use faer::sparse::{Pair, SymbolicSparseColMat};

use crate::ode::SemiExplicitDae;

/// `M - c J` at one state, dense, with its sparsity pattern.
pub struct NewtonMatrix {
    pub(crate) dim: usize,
    /// Row-major, dense (only the pattern's entries are handed over).
    pub(crate) a: Vec<f64>,
    pub(crate) pattern: SymbolicSparseColMat<usize>,
    pub ctx: FaerContext,
}

impl NewtonMatrix {
    /// `M - c J` of `dae` at `(t, y)` (`M` the identity on the
    /// differential unknowns, zero on the algebraic ones); `None` if the
    /// Jacobian's pattern is not a valid sparse pattern.
    pub fn of<D: SemiExplicitDae>(dae: &D, t: f64, y: &[f64], c: f64) -> Option<Self> {
        let dim = dae.dim();
        let mut a = vec![0.0; dim * dim];
        let mut pairs: Vec<Pair<usize, usize>> = Vec::new();
        for i in 0..dae.differential_dim() {
            a[i * dim + i] = 1.0;
            pairs.push(Pair::new(i, i));
        }
        dae.jacobian_entries(t, y, &mut |r, col, j| {
            a[r * dim + col] -= c * j;
            pairs.push(Pair::new(r, col));
        });
        let pattern = SymbolicSparseColMat::try_new_from_indices(dim, dim, &pairs)
            .ok()?
            .0;
        Some(Self {
            dim,
            a,
            pattern,
            ctx: FaerContext::default(),
        })
    }
}

/// `LinearOp` for a square operator of `dim` rows held on a sparsity
/// `pattern` with a faer `ctx`, whose `fill_values(&self, vals)` writes the
/// pattern's values in its column order: the Newton matrix here and
/// gen-alpha's Newton operator share it.
macro_rules! pattern_op {
    ($ty:ty) => {
        impl diffsol_la::LinearOp for $ty {
            type T = f64;
            type V = diffsol::FaerVec<f64>;
            type M = diffsol::FaerSparseMat<f64>;
            type C = diffsol::FaerContext;
            fn nrows(&self) -> usize {
                self.dim
            }
            fn ncols(&self) -> usize {
                self.dim
            }
            fn context(&self) -> &diffsol::FaerContext {
                &self.ctx
            }
            fn matrix_inplace(&self, y: &mut diffsol::FaerSparseMat<f64>) {
                use diffsol::Matrix;
                self.fill_values(y.inner_mut()[0].val_mut());
            }
            fn sparsity(&self) -> Option<faer::sparse::SymbolicSparseColMat<usize>> {
                Some(self.pattern.clone())
            }
        }
    };
}
pub(crate) use pattern_op;

impl NewtonMatrix {
    /// The pattern's values, column by column, from the dense matrix.
    fn fill_values(&self, vals: &mut [f64]) {
        let (col_ptr, row_idx) = (self.pattern.col_ptr(), self.pattern.row_idx());
        for c in 0..self.dim {
            for k in col_ptr[c]..col_ptr[c + 1] {
                vals[k] = self.a[row_idx[k] * self.dim + c];
            }
        }
    }
}

pattern_op!(NewtonMatrix);
