//! `bdf`: diffsol's BDF (variable order 1-5) on a problem's banded, index-1
//! DAE (the chain's is `ChainDae`), with sparse linear algebra: every step
//! of the chain costs O(n).
//!
//! What keeps it O(n), against diffsol's defaults:
//! * the Jacobian's pattern is given explicitly and its values are written
//!   analytically into the CSC storage (no NaN probing, no colouring, no
//!   column-by-column JVPs);
//! * the mass matrix `diag(1 (2n+1), 0 (3n))` is given with its pattern;
//! * the start is made consistent by the O(n) recursion, so diffsol's
//!   consistent-initialisation solve (O(N^2) colouring) is skipped;
//! * the Newton matrices are factorised block-tridiagonally, rod by rod
//!   ([`BlockLu`]), when the DAE groups its unknowns in a chain of blocks
//!   ([`SemiExplicitDae::blocks`]: the rigid chain's `ChainDae` and the
//!   elastic `ElasticDae` do) and its pattern bears that out; otherwise
//!   (the tests' small DAEs) by [`SparseLu`] (faer, COLAMD ordering). Both
//!   fail with an error instead of a panic.
//!
//! The algebraic unknowns (`alpha`, forces) get an absolute tolerance of
//! [`ALGEBRAIC_ATOL`], which takes them out of the error test and the
//! Newton convergence test: they are functions of `phi, w` fixed by linear
//! equations, and they jump at a whip by orders of magnitude. Step sizes
//! are set by `phi`, `w` and `W` only, as for the explicit methods.
//!
//! The step loop runs any [`SemiExplicitDae`] ([`integrate_dae`]): every
//! [`Problem`] that states itself as one ([`Problem::banded_dae`]: the
//! chain's `ChainDae`, autonomous, and the tests' problems with known
//! solutions, non-autonomous ones among them) through [`integrate`].

use std::cell::Cell;
use std::rc::Rc;

use diffsol::{
    Bdf, BdfState, ConstantOp, FaerContext, FaerSparseMat, FaerVec, LinearOp, Matrix, NonLinearOp,
    NonLinearOpJacobian, OdeBuilder, OdeEquations, OdeEquationsRef, OdeSolverMethod,
    OdeSolverState, Op, ParameterisedOp, UnitCallable,
};
use faer::sparse::SymbolicSparseColMat;

use super::block_lu::{BlockLayout, BlockLu};
use super::diffsol_driver::{drive, raise_first_step, slice, slice_mut, Hooks};
use super::integrator::{Integrator, Settings, Span};
use super::sparse_lu::{LuLog, SparseLu};
use crate::ode::{
    all_finite, BandedDae, Observer, Outcome, Problem, SemiExplicitDae, Stats, Status,
};

type Mat = FaerSparseMat<f64>;
type Vf = FaerVec<f64>;

/// Absolute tolerance of the algebraic unknowns: large enough that they
/// never weigh in the error norm (their values are below 1e8 in every scene).
pub(crate) const ALGEBRAIC_ATOL: f64 = 1e10;

/// diffsol's Newton tolerance (its `nonlinear_solver_tolerance`, default
/// 0.2) on a DAE with algebraic unknowns. The Newton iteration stops when
/// `eta |dy| < tol`, `|dy|` over the differential unknowns only (the
/// algebraic ones are out of the norm, [`ALGEBRAIC_ATOL`]); at 0.2 it left
/// unconverged steps on the chain, whose energy balance at rtol 1e-8 was 15
/// times the world-frame DAE's, and its stale iterates cost Newton
/// failures later (docs/model.md, "The Newton matrix in the rods' frames").
pub(crate) const ALGEBRAIC_NEWTON_TOLERANCE: f64 = 0.01;

thread_local! {
    /// Set by [`with_general_sparse_lu`]: every run on this thread uses the
    /// general sparse LU.
    static GENERAL_SPARSE_LU: Cell<bool> = const { Cell::new(false) };
}

/// Runs `f` with every `bdf` run on this thread factorising its Newton
/// matrices by the general sparse LU (faer, COLAMD), as before the
/// block-tridiagonal one: for benchmarks that time both in the same run.
#[doc(hidden)]
pub fn with_general_sparse_lu<R>(f: impl FnOnce() -> R) -> R {
    let before = GENERAL_SPARSE_LU.with(|g| g.replace(true));
    let out = f();
    GENERAL_SPARSE_LU.with(|g| g.set(before));
    out
}

/// The Newton matrices' LU: block-tridiagonal when the DAE's blocks allow
/// it, the general sparse LU otherwise.
pub(crate) enum NewtonLu {
    Block(Box<BlockLu>),
    Sparse(Box<SparseLu>),
}

impl Default for NewtonLu {
    fn default() -> Self {
        Self::Sparse(Box::default())
    }
}

impl NewtonLu {
    /// The block LU if `blocks` makes `pattern` block tridiagonal (and the
    /// general one is not forced), else the sparse LU; both log to `log`.
    pub(crate) fn choose(
        blocks: Option<Vec<usize>>,
        pattern: &SymbolicSparseColMat<usize>,
        log: Rc<LuLog>,
    ) -> Self {
        let general = GENERAL_SPARSE_LU.with(Cell::get);
        match blocks {
            Some(b) if !general && BlockLayout::new(&b, pattern.as_ref()).is_some() => {
                Self::Block(Box::new(BlockLu::new(b, log)))
            }
            _ => Self::Sparse(Box::new(SparseLu::logging(log))),
        }
    }
}

impl diffsol_la::LinearSolver<Mat> for NewtonLu {
    fn set_sparsity<C: diffsol_la::LinearOp<T = f64, V = Vf, M = Mat, C = FaerContext>>(
        &mut self,
        op: &C,
    ) {
        match self {
            Self::Block(lu) => diffsol_la::LinearSolver::set_sparsity(lu.as_mut(), op),
            Self::Sparse(lu) => diffsol_la::LinearSolver::set_sparsity(lu.as_mut(), op),
        }
    }

    fn set_linearisation<C: diffsol_la::LinearOp<T = f64, V = Vf, M = Mat, C = FaerContext>>(
        &mut self,
        op: &C,
    ) {
        match self {
            Self::Block(lu) => diffsol_la::LinearSolver::set_linearisation(lu.as_mut(), op),
            Self::Sparse(lu) => diffsol_la::LinearSolver::set_linearisation(lu.as_mut(), op),
        }
    }

    fn solve_in_place(&self, x: &mut Vf) -> Result<(), diffsol_la::error::LaError> {
        match self {
            Self::Block(lu) => lu.solve_in_place(x),
            Self::Sparse(lu) => lu.solve_in_place(x),
        }
    }

    fn solve_transpose_in_place(&self, x: &mut Vf) -> Result<(), diffsol_la::error::LaError> {
        match self {
            Self::Block(lu) => lu.solve_transpose_in_place(x),
            Self::Sparse(lu) => lu.solve_transpose_in_place(x),
        }
    }
}

/// The DAE as diffsol's `OdeEquations`, with exact call counters.
struct DaeEquations<D> {
    dae: D,
    ctx: FaerContext,
    /// The consistent start.
    y0: Vec<f64>,
    jacobian_pattern: SymbolicSparseColMat<usize>,
    /// CSC position of each entry of [`SemiExplicitDae::jacobian_entries`], in its order.
    jacobian_slots: Vec<u32>,
    mass_pattern: SymbolicSparseColMat<usize>,
    rhs_evals: Cell<u64>,
    jacobian_evals: Cell<u64>,
    /// A non-finite value came out of the right-hand side since the last reset.
    nonfinite: Cell<bool>,
}

/// The `(row, column)` pairs of `dae`'s Jacobian at `(t0, y0)`, in its
/// emission order, then the diagonal `(i, i)` of the first `diagonal`
/// unknowns: held as `u32` pairs at their exact count (one counting pass
/// first, no growth slack; issue 47 A2); `None` if an index does not fit
/// in a `u32` (a DAE of more than 4e9 unknowns: never within the bounds on
/// `chain.links`).
pub(crate) fn entries<D: SemiExplicitDae + ?Sized>(
    dae: &D,
    t0: f64,
    y0: &[f64],
    diagonal: usize,
) -> Option<Vec<(u32, u32)>> {
    let mut count = diagonal;
    dae.jacobian_entries(t0, y0, &mut |_, _, _| count += 1);
    let mut entries = Vec::with_capacity(count);
    let mut fits = true;
    dae.jacobian_entries(
        t0,
        y0,
        &mut |r, c, _| match (u32::try_from(r), u32::try_from(c)) {
            (Ok(r), Ok(c)) => entries.push((r, c)),
            _ => fits = false,
        },
    );
    for i in 0..diagonal {
        entries.push((u32::try_from(i).ok()?, u32::try_from(i).ok()?));
    }
    (fits && entries.len() == count).then_some(entries)
}

/// A pattern from `(row, column)` pairs (repeats allowed), and each pair's
/// CSC position; `None` if an entry is out of range (a programming error
/// of the DAE). The CSC arrays are built at their exact size from the
/// pairs' sorted, deduplicated keys (`column << 32 | row`), which are
/// also the positions' index: the pattern is the one faer's
/// `try_new_from_indices` builds, without its copy of the pairs as
/// `usize` (issue 47 A2).
pub(crate) fn pattern(
    dim: usize,
    entries: &[(u32, u32)],
) -> Option<(SymbolicSparseColMat<usize>, Vec<u32>)> {
    let key = |&(r, c): &(u32, u32)| (u64::from(c) << 32) | u64::from(r);
    let mut keys: Vec<u64> = entries.iter().map(key).collect();
    keys.sort_unstable();
    keys.dedup();
    let mut col_ptr = vec![0usize; dim + 1];
    let mut row_idx = Vec::with_capacity(keys.len());
    for &k in &keys {
        let (c, r) = (
            usize::try_from(k >> 32).ok()?,
            usize::try_from(k & 0xffff_ffff).ok()?,
        );
        if r >= dim || c >= dim {
            return None;
        }
        col_ptr[c + 1] += 1;
        row_idx.push(r);
    }
    for c in 0..dim {
        col_ptr[c + 1] += col_ptr[c];
    }
    let slots = entries
        .iter()
        .map(|e| u32::try_from(keys.binary_search(&key(e)).ok()?).ok())
        .collect::<Option<Vec<u32>>>()?;
    let sym = SymbolicSparseColMat::new_checked(dim, dim, col_ptr, None, row_idx);
    Some((sym, slots))
}

impl<D: SemiExplicitDae> DaeEquations<D> {
    /// The equations of `dae` from the consistent start `(t0, y0)`; `None`
    /// if its Jacobian's pattern is malformed.
    fn new(dae: D, t0: f64, y0: Vec<f64>) -> Option<Self> {
        let dim = dae.dim();
        let (jacobian_pattern, jacobian_slots) = pattern(dim, &entries(&dae, t0, &y0, 0)?)?;
        let diagonal = (0..dae.differential_dim())
            .map(|i| u32::try_from(i).ok().map(|i| (i, i)))
            .collect::<Option<Vec<_>>>()?;
        let (mass_pattern, _) = pattern(dim, &diagonal)?;
        let ctx = FaerContext::default();
        Some(Self {
            dae,
            ctx,
            y0,
            jacobian_pattern,
            jacobian_slots,
            mass_pattern,
            rhs_evals: Cell::new(0),
            jacobian_evals: Cell::new(0),
            nonfinite: Cell::new(false),
        })
    }

    /// Right-hand side on slices, counted and checked.
    fn rhs_slices(&self, t: f64, y: &[f64], out: &mut [f64]) {
        self.dae.rhs(t, y, out);
        self.rhs_evals.set(self.rhs_evals.get() + 1);
        if !all_finite(out) {
            self.nonfinite.set(true);
        }
    }
}

/// The right-hand side `f(t, y)` and its Jacobian.
struct DaeRhs<'a, D>(&'a DaeEquations<D>);
/// The constant mass matrix.
struct DaeMass<'a, D>(&'a DaeEquations<D>);
/// The consistent start.
struct DaeInit<'a, D>(&'a DaeEquations<D>);

macro_rules! dae_op {
    ($($name:ident),*) => {$(
        impl<D: SemiExplicitDae> Op for $name<'_, D> {
            type T = f64;
            type V = Vf;
            type M = Mat;
            type C = FaerContext;
            fn nstates(&self) -> usize {
                self.0.dae.dim()
            }
            fn nout(&self) -> usize {
                self.0.dae.dim()
            }
            fn nparams(&self) -> usize {
                0
            }
            fn context(&self) -> &FaerContext {
                &self.0.ctx
            }
        }
    )*};
}
dae_op!(DaeRhs, DaeMass, DaeInit);

impl<D: SemiExplicitDae> Op for DaeEquations<D> {
    type T = f64;
    type V = Vf;
    type M = Mat;
    type C = FaerContext;
    fn nstates(&self) -> usize {
        self.dae.dim()
    }
    fn nout(&self) -> usize {
        self.dae.dim()
    }
    fn nparams(&self) -> usize {
        0
    }
    fn context(&self) -> &FaerContext {
        &self.ctx
    }
}

impl<D: SemiExplicitDae> NonLinearOp for DaeRhs<'_, D> {
    fn call_inplace(&self, x: &Vf, t: f64, y: &mut Vf) {
        self.0.rhs_slices(t, slice(x), slice_mut(y));
    }
}

impl<D: SemiExplicitDae> NonLinearOpJacobian for DaeRhs<'_, D> {
    fn jac_mul_inplace(&self, x: &Vf, t: f64, v: &Vf, y: &mut Vf) {
        let (v, out) = (slice(v), slice_mut(y));
        out.fill(0.0);
        self.0
            .dae
            .jacobian_entries(t, slice(x), &mut |r, c, j| out[r] += j * v[c]);
    }

    fn jacobian_inplace(&self, x: &Vf, t: f64, y: &mut Mat) {
        let slots = &self.0.jacobian_slots;
        let values = y.inner_mut()[0].val_mut();
        let mut k = 0;
        self.0.dae.jacobian_entries(t, slice(x), &mut |_, _, j| {
            values[slots[k] as usize] = j;
            k += 1;
        });
        self.0.jacobian_evals.set(self.0.jacobian_evals.get() + 1);
    }

    fn jacobian_sparsity(&self) -> Option<SymbolicSparseColMat<usize>> {
        Some(self.0.jacobian_pattern.clone())
    }
}

impl<D: SemiExplicitDae> LinearOp for DaeMass<'_, D> {
    /// `y = M x + beta y`, the differential rows and the algebraic ones in
    /// two branch-free loops (once per Newton iteration).
    fn gemv_inplace(&self, x: &Vf, _t: f64, beta: f64, y: &mut Vf) {
        let nd = self.0.dae.differential_dim();
        let (x, y) = (slice(x), slice_mut(y));
        let (yd, ya) = y.split_at_mut(nd.min(y.len()));
        for (yi, xi) in yd.iter_mut().zip(x) {
            *yi = xi + beta * *yi;
        }
        for yi in ya {
            *yi *= beta;
        }
    }

    fn matrix_inplace(&self, _t: f64, y: &mut Mat) {
        y.inner_mut()[0].val_mut().fill(1.0);
    }

    fn sparsity(&self) -> Option<SymbolicSparseColMat<usize>> {
        Some(self.0.mass_pattern.clone())
    }
}

impl<D: SemiExplicitDae> ConstantOp for DaeInit<'_, D> {
    fn call_inplace(&self, _t: f64, y: &mut Vf) {
        slice_mut(y).copy_from_slice(&self.0.y0);
    }
}

impl<'a, D: SemiExplicitDae> OdeEquationsRef<'a> for DaeEquations<D> {
    type Mass = DaeMass<'a, D>;
    type Rhs = DaeRhs<'a, D>;
    type Root = ParameterisedOp<'a, UnitCallable<Mat>>;
    type Init = DaeInit<'a, D>;
    type Out = ParameterisedOp<'a, UnitCallable<Mat>>;
    type Reset = ParameterisedOp<'a, UnitCallable<Mat>>;
}

impl<D: SemiExplicitDae> OdeEquations for DaeEquations<D> {
    fn rhs(&self) -> DaeRhs<'_, D> {
        DaeRhs(self)
    }
    fn mass(&self) -> Option<DaeMass<'_, D>> {
        Some(DaeMass(self))
    }
    fn init(&self) -> DaeInit<'_, D> {
        DaeInit(self)
    }
    fn set_params(&mut self, _p: &Vf) {}
    fn get_params(&self, _p: &mut Vf) {}
}

/// Integrates `problem` from `t0` (its state `y0`) to `t_end` on its banded
/// DAE ([`Problem::banded_dae`]); a problem without one ends at the start,
/// `diverged`.
pub(crate) fn integrate(problem: &dyn Problem, s: &Span<'_>, obs: &mut dyn Observer) -> Outcome {
    let (t0, y0) = (s.t0, s.y0);
    let Some(BandedDae { dae, y0: full }) = problem.banded_dae(t0, y0) else {
        return Outcome::ended(
            Status::Diverged,
            t0,
            Some(t0),
            Stats::default(),
            y0.to_vec(),
        );
    };
    integrate_dae(dae, t0, full, s.t_end, s.settings, obs)
}

/// Integrates `dae` from `(t0, y0)` to `t_end`; `y0` holds every unknown,
/// consistent (the algebraic equations hold at `t0`). Observers and the
/// outcome see the differential unknowns only. Every evaluation of the DAE
/// (diffsol's, and the loop's own for the observer) is counted; the
/// observer's derivatives at an accepted step are read off the state
/// instead where the DAE can ([`SemiExplicitDae::derivatives`]: no
/// evaluation, none counted).
pub fn integrate_dae<D: SemiExplicitDae>(
    dae: D,
    t0: f64,
    y0: Vec<f64>,
    t_end: f64,
    opts: &Settings,
    obs: &mut dyn Observer,
) -> Outcome {
    let (d, dim) = (dae.differential_dim(), dae.dim());
    let y = y0[..d].to_vec();
    let blocks = dae.blocks();
    let Some(eqn) = DaeEquations::new(dae, t0, y0) else {
        // A malformed pattern is a programming error: a failure at the start.
        return Outcome::ended(Status::Diverged, t0, Some(t0), Stats::default(), y);
    };
    let mut f = vec![0.0; dim];
    eqn.rhs_slices(t0, &eqn.y0, &mut f);
    let stats = Stats {
        rhs_evals: eqn.rhs_evals.get(),
        ..Stats::default()
    };
    if !all_finite(&eqn.y0) || !all_finite(&f) {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y);
    }
    obs.start(t0, &y, &f[..d]);
    if t_end <= t0 {
        return Outcome::ended(Status::Ok, t0, None, stats, y);
    }

    let atol = (0..dim).map(|i| if i < d { opts.atol } else { ALGEBRAIC_ATOL });
    let mut builder = OdeBuilder::<Mat>::new().t0(t0).rtol(opts.rtol).atol(atol);
    if let Some(h0) = opts.h0 {
        // Only its sign is used: diffsol picks the first step itself.
        builder = builder.h0(h0);
    }
    // Building only fails on a programming error (a shape mismatch):
    // reported as a failure at the start.
    let Ok(mut problem) = builder.build_from_eqn(eqn) else {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y);
    };
    if dim > d {
        problem.ode_options.nonlinear_solver_tolerance = ALGEBRAIC_NEWTON_TOLERANCE;
    }
    let log = Rc::new(LuLog::default());
    let lu = NewtonLu::choose(blocks, &problem.eqn.jacobian_pattern, log.clone());
    let setup = <BdfState<Vf> as OdeSolverState<Vf>>::new(&problem, 1).and_then(|mut state| {
        let eqn = &problem.eqn;
        raise_first_step(&mut state, t_end, opts, &mut |t, y, f| {
            eqn.rhs_slices(t, y, f)
        });
        Bdf::<_, _>::new(&problem, state, lu)
    });
    let Ok(mut solver) = setup else {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y);
    };
    let eqn = &problem.eqn;
    // f1 for the observer: [w, alpha, W'], the DAE's own derivatives, read
    // off the state where the DAE can (no right-hand side evaluated).
    let hooks = Hooks {
        rhs: &mut |t: f64, y: &[f64], f: &mut [f64]| {
            if !eqn.dae.derivatives(t, y, f) {
                eqn.rhs_slices(t, y, f);
            }
        },
        nonfinite: &eqn.nonfinite,
        linear_failed: &|| log.last_failed.get(),
    };
    let driven = drive(&mut solver, t0, y, t_end, opts, obs, hooks);
    driven.outcome(
        solver.get_statistics(),
        eqn.rhs_evals.get(),
        eqn.jacobian_evals.get(),
    )
}

/// `bdf`: diffsol's BDF on the problem's banded DAE, O(n) per step.
pub(crate) const BDF: Integrator = Integrator {
    name: "bdf",
    adaptive: true,
    nonsmooth: false,
    run: |p, s, obs| integrate(p, s, obs).into(),
};

/// Whether [`integrate_dae`] would factorise `dae`'s Newton matrices by
/// the block LU (at the state `0.1` everywhere; test support,
/// [`crate::testing`]). Panics on a malformed Jacobian pattern.
#[cfg(any(test, feature = "test-support"))]
#[allow(
    clippy::expect_used,
    reason = "test support: a malformed pattern fails the test"
)]
pub fn picks_block_lu<D: SemiExplicitDae>(dae: D) -> bool {
    let y0 = vec![0.1; dae.dim()];
    let blocks = dae.blocks();
    let eqn = DaeEquations::new(dae, 0.0, y0).expect("a well-formed Jacobian pattern");
    let log = Rc::new(LuLog::default());
    matches!(
        NewtonLu::choose(blocks, &eqn.jacobian_pattern, log),
        NewtonLu::Block(_)
    )
}
