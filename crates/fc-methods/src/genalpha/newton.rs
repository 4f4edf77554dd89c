//! gen-alpha's Newton matrix `E - beta J` and its LU, kept across steps
//! and attempts: the Jacobian `J` is evaluated only when the Newton
//! iteration asks for it (its contraction rate, a failure with an older
//! `J`, or its age), and the LU is formed again only when `J` or `beta`
//! (the step) changed. docs/model.md, "The generalized-alpha method",
//! states the policy beside CVODE's and RADAU5's.

use std::rc::Rc;

use diffsol::{FaerContext, FaerVec};
use diffsol_la::LinearSolver;
use faer::sparse::SymbolicSparseColMat;

use crate::bdf::NewtonLu;
use crate::ode::{SemiExplicitDae, Stats};
use crate::sparse_lu::LuLog;

use super::policy::ReusePolicy;

/// The Newton matrix `E - beta J` on the DAE's pattern (the Jacobian's
/// entries and the differential rows' diagonal), its values in CSC order,
/// as the LU reads it, and the Jacobian's values it was made from.
struct NewtonOp {
    dim: usize,
    pattern: SymbolicSparseColMat<usize>,
    /// The CSC position of each Jacobian entry, in emission order, then
    /// of each differential row's diagonal (from `jacobian_len` on).
    slots: Vec<u32>,
    /// The Jacobian's entry count.
    jacobian_len: usize,
    /// The Jacobian's values, in emission order.
    jac: Vec<f64>,
    /// `E - beta J`, in CSC order.
    values: Vec<f64>,
    /// The differential rows with a Jacobian entry: Newton's convergence
    /// is measured on these. A row the Jacobian leaves empty (the chain's
    /// work `W`, read by no equation, its dense row left out) is corrected
    /// by its residual alone, one iteration behind the rest, and would
    /// only slow the measured rate.
    rows: Vec<usize>,
    ctx: FaerContext,
}

impl NewtonOp {
    /// The pattern of `dae` at its start; `None` if it is malformed.
    fn new(dae: &dyn SemiExplicitDae, t0: f64, y0: &[f64]) -> Option<Self> {
        let (dim, nd) = (dae.dim(), dae.differential_dim());
        // The Jacobian's entries and the differential diagonal, with their
        // CSC positions (bdf's pattern builder), as u32s at their count.
        let entries = crate::bdf::entries(dae, t0, y0, nd)?;
        let m = entries.len() - nd;
        let mut has_entry = vec![false; nd];
        for &(r, _) in &entries[..m] {
            if let Some(e) = has_entry.get_mut(r as usize) {
                *e = true;
            }
        }
        let rows = (0..nd).filter(|&i| has_entry[i]).collect();
        let (pattern, slots) = crate::bdf::pattern(dim, &entries)?;
        drop(entries);
        let nnz = pattern.row_idx().len();
        Some(Self {
            dim,
            slots,
            jacobian_len: m,
            pattern,
            jac: vec![0.0; m],
            values: vec![0.0; nnz],
            rows,
            ctx: FaerContext::default(),
        })
    }

    /// `E - beta J` from the kept `J`: O(nnz), allocation-free.
    fn assemble(&mut self, beta: f64) {
        self.values.fill(0.0);
        let (jac_slots, diag_slots) = self.slots.split_at(self.jacobian_len);
        for &s in diag_slots {
            self.values[s as usize] = 1.0;
        }
        for (&s, &j) in jac_slots.iter().zip(&self.jac) {
            self.values[s as usize] -= beta * j;
        }
    }
}

impl NewtonOp {
    /// The kept values, in the pattern's order.
    fn fill_values(&self, vals: &mut [f64]) {
        vals.copy_from_slice(&self.values);
    }
}

crate::newton_matrix::pattern_op!(NewtonOp);

/// The Newton matrix, its LU, and when they were made.
pub(crate) struct Newton {
    op: NewtonOp,
    lu: NewtonLu,
    log: Rc<LuLog>,
    /// `beta` of the factorised matrix (`NaN`: none yet).
    beta_lu: f64,
    /// A Jacobian has been evaluated and is kept.
    has_jac: bool,
    /// The next attempt evaluates the Jacobian first.
    stale: bool,
    /// The Jacobian was evaluated during the current attempt.
    fresh: bool,
    /// Accepted steps since the Jacobian was evaluated.
    age: u64,
    policy: ReusePolicy,
}

impl Newton {
    /// The Newton matrix on `dae`'s pattern at its start; `None` if the
    /// pattern is malformed.
    pub fn new(
        dae: &dyn SemiExplicitDae,
        t0: f64,
        y0: &[f64],
        policy: ReusePolicy,
    ) -> Option<Self> {
        let op = NewtonOp::new(dae, t0, y0)?;
        let log = Rc::new(LuLog::default());
        let mut lu = NewtonLu::choose(dae.blocks(), &op.pattern, log.clone());
        lu.set_sparsity(&op);
        Some(Self {
            op,
            lu,
            log,
            beta_lu: f64::NAN,
            has_jac: false,
            stale: true,
            fresh: false,
            age: 0,
            policy,
        })
    }

    pub fn policy(&self) -> &ReusePolicy {
        &self.policy
    }

    /// True if the Jacobian was evaluated during this attempt.
    pub fn fresh(&self) -> bool {
        self.fresh
    }

    /// Before an attempt with `beta` at the predictor `(t, u)`: the
    /// Jacobian evaluated if it is stale, the LU formed if the Jacobian or
    /// `beta` changed. `false` if the factorisation failed.
    pub fn prepare(
        &mut self,
        dae: &dyn SemiExplicitDae,
        t: f64,
        u: &[f64],
        beta: f64,
        stats: &mut Stats,
    ) -> bool {
        self.fresh = false;
        if self.stale || !self.has_jac {
            return self.refresh(dae, t, u, beta, stats);
        }
        if beta != self.beta_lu || self.log.last_failed.get() {
            return self.factorise(beta, stats);
        }
        true
    }

    /// The Jacobian evaluated at `(t, u)` and the LU of `E - beta J`.
    pub fn refresh(
        &mut self,
        dae: &dyn SemiExplicitDae,
        t: f64,
        u: &[f64],
        beta: f64,
        stats: &mut Stats,
    ) -> bool {
        dae.jacobian_values(t, u, &mut self.op.jac);
        stats.jacobian_evals += 1;
        self.has_jac = true;
        self.stale = false;
        self.fresh = true;
        self.age = 0;
        self.factorise(beta, stats)
    }

    fn factorise(&mut self, beta: f64, stats: &mut Stats) -> bool {
        self.op.assemble(beta);
        self.lu.set_linearisation(&self.op);
        stats.lu_factorizations += 1;
        self.beta_lu = beta;
        !self.log.last_failed.get()
    }

    /// The differential rows Newton's convergence is measured on.
    pub fn rows(&self) -> &[usize] {
        &self.op.rows
    }

    /// `x <- (E - beta_LU J)^-1 x`; `false` if the solve failed.
    pub fn solve(&self, x: &mut FaerVec<f64>) -> bool {
        self.lu.solve_in_place(x).is_ok()
    }

    /// The next attempt evaluates the Jacobian first.
    pub fn mark_stale(&mut self) {
        self.stale = true;
    }

    /// After an accepted step whose corrections contracted by `theta` per
    /// iteration at most: the Jacobian is kept unless that rate or its age
    /// asks for a new one.
    pub fn accepted(&mut self, theta: f64) {
        self.age += 1;
        if theta > self.policy.theta_refresh || self.age >= self.policy.max_age {
            self.stale = true;
        }
    }
}
