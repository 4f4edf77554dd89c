//! A block-tridiagonal LU for diffsol's Newton matrices: the chain's
//! unknowns grouped rod by rod, each rod coupled only to its two
//! neighbours, factorised in a fixed order with no fill outside the three
//! block diagonals. Fallible like [`super::sparse_lu::SparseLu`].
//!
//! The DAE names the block of every unknown
//! ([`SemiExplicitDae::blocks`](crate::ode::SemiExplicitDae::blocks)); an
//! unknown whose row and column hold only the diagonal (the chain's `W`,
//! whose row is left out of the Jacobian) is solved alone, and the others
//! must form blocks of one size `S <= MAX_BLOCK` (5 per rod for the rigid
//! chain, 6 for the elastic one). With `D_k`, `L_k`, `U_k` the diagonal,
//! left and right blocks of block row `k`, the factorisation is the block
//! Thomas algorithm
//!
//! ```text
//! D'_0 = D_0,   X_k = D'_k^-1 U_k,   D'_k = D_k - L_k X_{k-1}
//! ```
//!
//! with each `D'_k` factorised by dense LU with partial pivoting (within the
//! block) and kept as its inverse beside `G_k = D'_k^-1 L_k`. The solve is
//! then small dense products, forward `y_k = D'_k^-1 b_k - G_k y_{k-1}` and
//! back `x_k = y_k - X_k x_{k+1}`.
//!
//! Before that, the unknowns whose rows are *local* (every entry in their
//! own block's columns) are condensed out: the chain's `phi_i' = w_i` and
//! `w_i' = alpha_i`, whose Newton rows are `[1, -c]` on the rod's own
//! unknowns. With the `P` local unknowns of each block first and the other
//! `Q = S - P` after them, block row `k` reads `D_PP x_P + D_PQ x_Q = b_P`
//! on its local rows, so `x_P = y_P - Z_k x_Q` with `y_P = D_PP^-1 b_P` and
//! `Z_k = D_PP^-1 D_PQ`; put into the other rows, which reach the local
//! columns of blocks `k - 1`, `k` and `k + 1` only, it leaves the Schur
//! complement, block tridiagonal in `Q x Q` blocks,
//!
//! ```text
//! L'_k = L_QQ - L_QP Z_{k-1},   D'_k = D_QQ - D_QP Z_k,   U'_k = U_QQ - U_QP Z_{k+1},
//! b'_k = b_Q - L_QP y_{P,k-1} - D_QP y_{P,k} - U_QP y_{P,k+1},
//! ```
//!
//! which the block Thomas algorithm above factorises and solves. The rigid
//! chain's blocks shrink from 5 to 3 unknowns (`alpha_i`, `f_i`), the
//! elastic chain's from 6 to 3 and BEAM's from 4 to 3: per rod of the rigid
//! chain about 190 multiply-adds to factorise (540 without the
//! condensation) and 55 per solve (75). The factorisation and the solve are
//! compiled for each shape (the small loops unroll), with no ordering, no
//! symbolic phase and no allocation after the first pattern. Only the
//! shapes in [`CONDENSED`] are condensed; any other is factorised whole.
//!
//! Memory is laid out for the sweeps (issue 20: at n = 3200 the factors
//! outgrow the cache): the matrix is assembled into `[L_k | D_k | U_k]`
//! blocks whose entries outside the pattern are zeroed once and never
//! written again, so that nothing is cleared per factorisation; the factors
//! go to two streams, `[D'_k^-1 | G_k]` read in order by the forward sweep
//! and `X_k` read backwards by the back substitution; and the sweeps gather
//! the right-hand side from, and scatter the solution to, the unknowns'
//! own order themselves (the forward sweep computing each block's `y_P`
//! one block ahead, the back sweep recovering `x_P`), checking finiteness
//! as they write.
//!
//! Pivoting is confined to the diagonal blocks, so the factorisation relies
//! on every `D_PP` and `D'_k` being nonsingular (the chain's `D_PP` is
//! unit upper triangular); a zero or non-finite pivot, a
//! non-finite matrix entry or a non-finite solution is a failure (logged; the
//! solve returns an error, which diffsol treats as a failed Newton iteration
//! and answers with a smaller step). If a matrix with a usable structure
//! were ever badly conditioned block by block, the Newton iteration's own
//! convergence test is the next guard.

use std::cell::RefCell;
use std::rc::Rc;

use diffsol::{FaerContext, FaerSparseMat, FaerVec, Matrix, MatrixCommon};
use diffsol_la::error::{LaError, LinearSolverError};
use diffsol_la::{LinearOp, LinearSolver};
use faer::sparse::SymbolicSparseColMatRef;

use super::diffsol_driver::slice_mut;
use super::sparse_lu::LuLog;

/// Calls `$f::<S>($args)` for the block size `$s` (`1..=MAX_BLOCK`): every
/// size compiled on its own, so that the small loops unroll.
macro_rules! sized {
    ($s:expr, $f:ident($($arg:expr),*)) => {
        match $s {
            1 => $f::<1>($($arg),*),
            2 => $f::<2>($($arg),*),
            3 => $f::<3>($($arg),*),
            4 => $f::<4>($($arg),*),
            5 => $f::<5>($($arg),*),
            6 => $f::<6>($($arg),*),
            7 => $f::<7>($($arg),*),
            _ => $f::<MAX_BLOCK>($($arg),*),
        }
    };
}

/// Calls `$f::<P, Q>($args)` for `$s = P + Q` unknowns per block of which
/// `$p = P` are local: the shapes in [`CONDENSED`], and every block size
/// with none local, each compiled on its own so that the small loops
/// unroll. [`BlockLayout::new`] condenses no other shape.
macro_rules! shaped {
    ($s:expr, $p:expr, $f:ident($($arg:expr),*)) => {
        match ($s, $p) {
            (5, 2) => $f::<2, 3>($($arg),*),
            (6, 3) => $f::<3, 3>($($arg),*),
            (4, 1) => $f::<1, 3>($($arg),*),
            (1, _) => $f::<0, 1>($($arg),*),
            (2, _) => $f::<0, 2>($($arg),*),
            (3, _) => $f::<0, 3>($($arg),*),
            (4, _) => $f::<0, 4>($($arg),*),
            (5, _) => $f::<0, 5>($($arg),*),
            (6, _) => $f::<0, 6>($($arg),*),
            (7, _) => $f::<0, 7>($($arg),*),
            _ => $f::<0, MAX_BLOCK>($($arg),*),
        }
    };
}

/// The shapes `(S, P)` whose local unknowns are condensed: the rigid chain
/// (`phi_i`, `w_i` of 5), the elastic one (`theta_i`, `x_i`, `y_i` of 6)
/// and BEAM (`theta_i` of 4).
const CONDENSED: [(usize, usize); 3] = [(5, 2), (6, 3), (4, 1)];

/// Where each unknown sits: in a block of the chain, all blocks of one
/// size `S`, or alone (its row and column hold only the diagonal entry, as
/// the chain's `W` does, whose row is left out of the Jacobian).
#[derive(Clone, Debug)]
pub struct BlockLayout {
    /// The block size `S`.
    pub size: usize,
    /// `P`, the unknowns of every block whose rows hold entries in their own
    /// block's columns only (the chain's `phi_i` and `w_i`): placed first in
    /// each block and condensed out before the block Thomas algorithm (see
    /// the module doc). Zero when the blocks do not all have the same
    /// number of them, or when they would leave nothing to condense onto.
    pub local: usize,
    /// `order[p]`: the unknown at position `p` (block `p / S`).
    pub order: Vec<usize>,
    /// `place[u]`: `Ok(position)` in the blocks, or `Err(index)` in `lone`.
    place: Vec<Result<usize, usize>>,
    /// The unknowns alone.
    lone: Vec<usize>,
}

/// The largest block this solver takes (the solve is compiled for each size
/// up to it); a DAE with larger blocks gets the sparse LU.
pub(crate) const MAX_BLOCK: usize = 8;

impl BlockLayout {
    /// The layout of `block` (the block of every unknown, numbered `0..K` in
    /// the chain's order) for the matrix `pattern`; `None` unless every
    /// unknown not alone sits in a block of the same size `S <= MAX_BLOCK`,
    /// no block is empty, and every entry couples blocks at most one apart:
    /// then the matrix is not block tridiagonal in this grouping.
    pub fn new(block: &[usize], pattern: SymbolicSparseColMatRef<'_, usize>) -> Option<Self> {
        let dim = block.len();
        if dim == 0 || pattern.nrows() != dim || pattern.ncols() != dim {
            return None;
        }
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        let mut coupled = vec![false; dim];
        for c in 0..dim {
            for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
                if r != c {
                    coupled[r] = true;
                    coupled[c] = true;
                }
            }
        }
        let blocks = block.iter().max()? + 1;
        let mut count = vec![0usize; blocks];
        for (u, &k) in block.iter().enumerate() {
            if coupled[u] {
                count[k] += 1;
            }
        }
        let size = count[0];
        if size == 0 || size > MAX_BLOCK || count.iter().any(|&s| s != size) {
            return None;
        }
        // A row is local when every entry of it lies in its own block.
        let mut local_row: Vec<bool> = coupled.clone();
        for c in 0..dim {
            for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
                if !coupled[c] || block[c] != block[r] {
                    local_row[r] = false;
                }
            }
        }
        let mut locals = vec![0usize; blocks];
        for (u, &k) in block.iter().enumerate() {
            if local_row[u] {
                locals[k] += 1;
            }
        }
        let local =
            if locals.iter().all(|&p| p == locals[0]) && CONDENSED.contains(&(size, locals[0])) {
                locals[0]
            } else {
                0
            };
        // Each block: its local unknowns first (when condensing), then the rest.
        let mut next: Vec<[usize; 2]> = (0..blocks).map(|k| [k * size, k * size + local]).collect();
        let mut order = vec![0; blocks * size];
        let mut place = vec![Err(0); dim];
        let mut lone = Vec::new();
        for (u, &k) in block.iter().enumerate() {
            if coupled[u] {
                let side = usize::from(!(local > 0 && local_row[u]));
                let at = next[k][side];
                order[at] = u;
                place[u] = Ok(at);
                next[k][side] += 1;
            } else {
                place[u] = Err(lone.len());
                lone.push(u);
            }
        }
        let layout = Self {
            size,
            local,
            order,
            place,
            lone,
        };
        for c in 0..dim {
            for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
                layout.slot(r, c)?;
            }
        }
        Some(layout)
    }

    fn blocks(&self) -> usize {
        self.order.len() / self.size
    }

    /// Where entry `(r, c)` is stored: in block row `k`, `[L_k | D_k | U_k]`
    /// (each `S x S`, row-major) at `3 S^2 k`; the lone diagonals after all
    /// blocks. `None` outside the three block diagonals.
    fn slot(&self, r: usize, c: usize) -> Option<usize> {
        let s = self.size;
        match (*self.place.get(r)?, *self.place.get(c)?) {
            (Err(i), Err(j)) if i == j => Some(3 * s * s * self.blocks() + i),
            (Ok(pr), Ok(pc)) => {
                let (kr, kc) = (pr / s, pc / s);
                let (i, j) = (pr % s, pc % s);
                let part = if kc + 1 == kr {
                    0
                } else if kc == kr {
                    1
                } else if kc == kr + 1 {
                    2
                } else {
                    return None;
                };
                Some(3 * s * s * kr + part * s * s + i * s + j)
            }
            _ => None,
        }
    }
}

/// LU with partial pivoting of the `s x s` row-major `a` in place (unit
/// lower factor below the diagonal); `piv[j]` is the row swapped with row
/// `j` at step `j`. `false` on a zero or non-finite pivot. Inlined, as
/// [`lu_solve`] is, into [`factorise_blocks`], where `s` is a constant and
/// the small loops unroll.
#[inline(always)]
fn dense_lu(a: &mut [f64], s: usize, piv: &mut [usize]) -> bool {
    for j in 0..s {
        let mut p = j;
        let mut best = a[j * s + j].abs();
        for i in j + 1..s {
            let v = a[i * s + j].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        // `!(best > 0)` also catches a NaN column.
        if !(best > 0.0 && best.is_finite()) {
            return false;
        }
        piv[j] = p;
        if p != j {
            for c in 0..s {
                a.swap(j * s + c, p * s + c);
            }
        }
        let inv = 1.0 / a[j * s + j];
        for i in j + 1..s {
            let l = a[i * s + j] * inv;
            a[i * s + j] = l;
            if l != 0.0 {
                for c in j + 1..s {
                    a[i * s + c] -= l * a[j * s + c];
                }
            }
        }
    }
    true
}

/// `B = D^-1 B` for the factors of [`dense_lu`] and the `s x m` row-major `b`.
#[inline(always)]
fn lu_solve(lu: &[f64], s: usize, piv: &[usize], b: &mut [f64], m: usize) {
    for (j, &p) in piv.iter().enumerate().take(s) {
        if p != j {
            for c in 0..m {
                b.swap(j * m + c, p * m + c);
            }
        }
    }
    for i in 1..s {
        for j in 0..i {
            let l = lu[i * s + j];
            if l != 0.0 {
                for c in 0..m {
                    b[i * m + c] -= l * b[j * m + c];
                }
            }
        }
    }
    for i in (0..s).rev() {
        for j in i + 1..s {
            let u = lu[i * s + j];
            if u != 0.0 {
                for c in 0..m {
                    b[i * m + c] -= u * b[j * m + c];
                }
            }
        }
        let inv = 1.0 / lu[i * s + i];
        for c in 0..m {
            b[i * m + c] *= inv;
        }
    }
}

/// The local factors of one block for [`condense`]: with `D_PP`, `D_PQ`
/// the local rows of the diagonal block `d` (`S x S`, `S = P + Q`,
/// row-major; the first `P` unknowns local), `out` receives `[D_PP^-1 | Z
/// = D_PP^-1 D_PQ]` (`P x P`, then `P x Q`, row-major). `false` on a zero
/// or non-finite pivot.
fn local_factors<const P: usize, const Q: usize>(d: &[f64], out: &mut [f64]) -> bool {
    let s = P + Q;
    let mut a = [0.0; MAX_BLOCK * MAX_BLOCK];
    let mut piv = [0usize; MAX_BLOCK];
    for i in 0..P {
        for j in 0..P {
            a[i * P + j] = d[i * s + j];
        }
    }
    if !dense_lu(&mut a[..P * P], P, &mut piv[..P]) {
        return false;
    }
    let (inv, z) = out.split_at_mut(P * P);
    inv.fill(0.0);
    for i in 0..P {
        inv[i * P + i] = 1.0;
    }
    lu_solve(&a[..P * P], P, &piv[..P], inv, P);
    for i in 0..P {
        for j in 0..Q {
            z[i * Q + j] = d[i * s + P + j];
        }
    }
    lu_solve(&a[..P * P], P, &piv[..P], z, Q);
    true
}

/// `out = M_QQ - M_QP Z` for one `S x S` block `m` (row-major, the first
/// `P` unknowns local) and the `Z` of its column's block (`None`: `M` is
/// zero, the left block of the first row or the right one of the last);
/// `coupling` receives `M_QP` (`Q x P`) at stride `3 P`.
fn reduce_block<const P: usize, const Q: usize>(
    m: &[f64],
    z: Option<&[f64]>,
    out: &mut [f64],
    coupling: &mut [f64],
) {
    let s = P + Q;
    for i in 0..Q {
        for l in 0..P {
            coupling[i * 3 * P + l] = m[(P + i) * s + l];
        }
        for j in 0..Q {
            let mut acc = m[(P + i) * s + P + j];
            if let Some(z) = z {
                for l in 0..P {
                    acc -= m[(P + i) * s + l] * z[l * Q + j];
                }
            }
            out[i * Q + j] = acc;
        }
    }
}

/// Condenses the local unknowns out of `assembled` (`[L_k | D_k | U_k]`,
/// `S x S` each, the first `P` unknowns of each block local): `local`
/// receives each block's `[D_PP^-1 | Z_k]`, `coupling` its `[L_QP | D_QP |
/// U_QP]` (`Q x 3P`, row by row) and `reduced` the `Q x Q` blocks
/// `[L_QQ - L_QP Z_{k-1} | D_QQ - D_QP Z_k | U_QQ - U_QP Z_{k+1}]` of the
/// Schur complement, which is block tridiagonal again. `false` on a zero
/// or non-finite pivot of some `D_PP`.
fn condense<const P: usize, const Q: usize>(
    assembled: &[f64],
    local: &mut [f64],
    coupling: &mut [f64],
    reduced: &mut [f64],
) -> bool {
    let (s, qq, lsz) = (P + Q, Q * Q, P * P + P * Q);
    let ss = s * s;
    if P > 0 {
        for (blk, loc) in assembled
            .chunks_exact(3 * ss)
            .zip(local.chunks_exact_mut(lsz))
        {
            if !local_factors::<P, Q>(&blk[ss..2 * ss], loc) {
                return false;
            }
        }
    }
    let blocks = assembled.len() / (3 * ss);
    let z_of = |k: usize| (k < blocks).then(|| &local[k * lsz + P * P..(k + 1) * lsz]);
    for (k, ((blk, out), cpl)) in assembled
        .chunks_exact(3 * ss)
        .zip(reduced.chunks_exact_mut(3 * qq))
        .zip(coupling.chunks_exact_mut((3 * P * Q).max(1)))
        .enumerate()
    {
        let left = k.checked_sub(1).and_then(z_of);
        reduce_block::<P, Q>(&blk[..ss], left, &mut out[..qq], cpl);
        reduce_block::<P, Q>(
            &blk[ss..2 * ss],
            z_of(k),
            &mut out[qq..2 * qq],
            &mut cpl[P..],
        );
        reduce_block::<P, Q>(
            &blk[2 * ss..],
            z_of(k + 1),
            &mut out[2 * qq..],
            &mut cpl[2 * P..],
        );
    }
    true
}

/// `start - a . c` for the sweeps' loop-carried products, summed in two
/// halves that run side by side, `(start - a_0 c_0 - ..) - (a_h c_h + ..)`
/// with `h = Q / 2`: the chain from `c` to the result is then one product
/// and `Q / 2 + 1` additions long, against `Q + 1` one after the other.
#[inline(always)]
fn minus_dot<const Q: usize>(start: f64, a: &[f64], c: &[f64; Q]) -> f64 {
    let h = Q / 2;
    let mut left = start;
    for j in 0..h {
        left -= a[j] * c[j];
    }
    let mut right = a[h] * c[h];
    for j in h + 1..Q {
        right += a[j] * c[j];
    }
    left - right
}

/// `y = D_PP^-1 b_P` of the block whose unknowns are `uk`.
#[inline(always)]
fn local_rhs<const P: usize, const Q: usize>(inv: &[f64], uk: &[usize], x: &[f64]) -> [f64; P] {
    let mut b = [0.0; P];
    for (bj, &u) in b.iter_mut().zip(uk) {
        *bj = x[u];
    }
    let mut y = [0.0; P];
    for i in 0..P {
        for j in 0..P {
            y[i] += inv[i * P + j] * b[j];
        }
    }
    y
}

/// `x = A^-1 x` through the condensation, in two sweeps that gather from
/// and scatter to `x` through `order`. Forward, block by block: the local
/// unknowns' `y_P = D_PP^-1 b_P` (one block ahead), the reduced right-hand
/// side `b_Q - L_QP y_{P,k-1} - D_QP y_{P,k} - U_QP y_{P,k+1}`, and the
/// reduced forward substitution `y_k = D''_k^-1 r_k - G_k y_{k-1}`; back:
/// `x_Q = y_k - X_k x_{Q,k+1}` and `x_P = y_P - Z_k x_Q`. `work` is scratch
/// (`S` per block). Returns whether every entry written is finite.
#[allow(
    clippy::too_many_arguments,
    reason = "one sweep's inputs, all borrowed"
)]
fn solve_condensed<const P: usize, const Q: usize>(
    local: &[f64],
    coupling: &[f64],
    forward: &[f64],
    back: &[f64],
    order: &[usize],
    x: &mut [f64],
    work: &mut [f64],
) -> bool {
    let s = P + Q;
    let lsz = P * P + P * Q;
    let blocks = order.len() / s;
    let (yp, zq) = work.split_at_mut(P * blocks);
    let inv_of = |k: usize| &local[k * lsz..k * lsz + P * P];
    let mut y_prev = [0.0; P];
    let mut y_cur = if blocks > 0 {
        local_rhs::<P, Q>(inv_of(0), &order[..s], x)
    } else {
        [0.0; P]
    };
    let mut carry = [0.0; Q];
    for (k, (((uk, cpl), fwd), zk)) in order
        .chunks_exact(s)
        .zip(coupling.chunks_exact((3 * P * Q).max(1)))
        .zip(forward.chunks_exact(2 * Q * Q))
        .zip(zq.chunks_exact_mut(Q))
        .enumerate()
    {
        let y_next = if k + 1 < blocks {
            local_rhs::<P, Q>(inv_of(k + 1), &order[(k + 1) * s..(k + 2) * s], x)
        } else {
            [0.0; P]
        };
        let mut r = [0.0; Q];
        for i in 0..Q {
            let row = &cpl[i * 3 * P..(i + 1) * 3 * P];
            let mut acc = x[uk[P + i]];
            for l in 0..P {
                acc -= row[l] * y_prev[l] + row[P + l] * y_cur[l] + row[2 * P + l] * y_next[l];
            }
            r[i] = acc;
        }
        let (d_inv, g_k) = fwd.split_at(Q * Q);
        for i in 0..Q {
            let mut acc = 0.0;
            for j in 0..Q {
                acc += d_inv[i * Q + j] * r[j];
            }
            zk[i] = minus_dot::<Q>(acc, &g_k[i * Q..(i + 1) * Q], &carry);
        }
        carry.copy_from_slice(zk);
        yp[k * P..(k + 1) * P].copy_from_slice(&y_cur);
        y_prev = y_cur;
        y_cur = y_next;
    }
    let mut finite = true;
    let mut carry = [0.0; Q];
    for (k, ((x_k, zk), uk)) in back
        .chunks_exact(Q * Q)
        .zip(zq.chunks_exact(Q))
        .zip(order.chunks_exact(s))
        .enumerate()
        .rev()
    {
        let mut xq = [0.0; Q];
        for i in 0..Q {
            xq[i] = minus_dot::<Q>(zk[i], &x_k[i * Q..(i + 1) * Q], &carry);
        }
        for (&v, &u) in xq.iter().zip(&uk[P..]) {
            x[u] = v;
            finite &= v.is_finite();
        }
        let z = &local[k * lsz + P * P..(k + 1) * lsz];
        for i in 0..P {
            let mut acc = yp[k * P + i];
            for j in 0..Q {
                acc -= z[i * Q + j] * xq[j];
            }
            x[uk[i]] = acc;
            finite &= acc.is_finite();
        }
        carry = xq;
    }
    finite
}

/// `x = A^-T x` through the condensation (`A = [I 0; A_QP A_PP^-1 I]
/// [A_PP A_PQ; 0 S]`, `S` the reduced matrix): `u_P = D_PP^-T b_P`, the
/// reduced `S^T x_Q = b_Q - D_PQ^T u_P`, then `x_P = u_P - D_PP^-T (A_QP^T
/// x_Q)`, whose second term gathers the local columns' entries from the
/// block rows `k - 1`, `k` and `k + 1`. `work` as in [`solve_condensed`].
#[allow(
    clippy::too_many_arguments,
    reason = "one sweep's inputs, all borrowed"
)]
fn solve_condensed_transposed<const P: usize, const Q: usize>(
    assembled: &[f64],
    local: &[f64],
    reduced: &[f64],
    factors: (&[f64], &[f64]),
    order: &[usize],
    x: &mut [f64],
    work: &mut [f64],
) -> bool {
    let s = P + Q;
    let (ss, lsz) = (s * s, P * P + P * Q);
    let blocks = order.len() / s;
    let (up, zq) = work.split_at_mut(P * blocks);
    for (k, uk) in order.chunks_exact(s).enumerate() {
        let inv = &local[k * lsz..k * lsz + P * P];
        for i in 0..P {
            let mut acc = 0.0;
            for j in 0..P {
                acc += inv[j * P + i] * x[uk[j]];
            }
            up[k * P + i] = acc;
        }
        let d = &assembled[3 * ss * k + ss..3 * ss * k + 2 * ss];
        for i in 0..Q {
            let mut acc = x[uk[P + i]];
            for l in 0..P {
                acc -= d[l * s + P + i] * up[k * P + l];
            }
            zq[k * Q + i] = acc;
        }
    }
    solve_transposed::<Q>(reduced, factors.0, factors.1, zq);
    let mut finite = true;
    for (k, uk) in order.chunks_exact(s).enumerate() {
        for (i, &u) in uk[P..].iter().enumerate() {
            let v = zq[k * Q + i];
            x[u] = v;
            finite &= v.is_finite();
        }
        // t = A_QP^T x_Q on block k's local columns: D_k, L_{k+1}, U_{k-1}.
        let mut t = [0.0; P];
        for (row, part) in [(k.wrapping_sub(1), 2), (k, 1), (k + 1, 0)] {
            if row < blocks {
                let m = &assembled[3 * ss * row + part * ss..3 * ss * row + (part + 1) * ss];
                for i in 0..Q {
                    let xi = zq[row * Q + i];
                    for (l, tl) in t.iter_mut().enumerate() {
                        *tl += m[(P + i) * s + l] * xi;
                    }
                }
            }
        }
        let inv = &local[k * lsz..k * lsz + P * P];
        for i in 0..P {
            let mut acc = up[k * P + i];
            for j in 0..P {
                acc -= inv[j * P + i] * t[j];
            }
            x[uk[i]] = acc;
            finite &= acc.is_finite();
        }
    }
    finite
}

/// `z = A^-T z` on the blocks (`z` in block order), with `assembled`
/// holding `[L_k | D_k | U_k]` per block, `forward` the `D'_k^-1` (and
/// `G_k`), `back` the `X_k`.
fn solve_transposed<const S: usize>(
    assembled: &[f64],
    forward: &[f64],
    back: &[f64],
    z: &mut [f64],
) {
    let mut carry = [0.0; S];
    // A = Lb Ub (Lb: D'_k and L_k below; Ub: I and X_k above), so that
    // A^T x = b is Ub^T y = b forward, then Lb^T x = y backward.
    for (x_k, zk) in back.chunks_exact(S * S).zip(z.chunks_exact_mut(S)) {
        // z_k -= X_{k-1}^T z_{k-1}, then the same for the next block.
        for (zi, ci) in zk.iter_mut().zip(carry) {
            *zi -= ci;
        }
        carry = [0.0; S];
        for i in 0..S {
            for j in 0..S {
                carry[j] += x_k[i * S + j] * zk[i];
            }
        }
    }
    let mut below = [0.0; S];
    for ((blk, inv), zk) in assembled
        .chunks_exact(3 * S * S)
        .zip(forward.chunks_exact(2 * S * S))
        .zip(z.chunks_exact_mut(S))
        .rev()
    {
        let mut t = [0.0; S];
        for i in 0..S {
            t[i] = zk[i] - below[i];
        }
        let mut y = [0.0; S];
        for i in 0..S {
            for j in 0..S {
                y[j] += inv[i * S + j] * t[i];
            }
        }
        zk.copy_from_slice(&y);
        // Block k-1 subtracts L_k^T x_k.
        let l_k = &blk[..S * S];
        below = [0.0; S];
        for i in 0..S {
            for j in 0..S {
                below[j] += l_k[i * S + j] * y[i];
            }
        }
    }
}

/// The block Thomas factorisation of [`Factors::factorise`] for the block
/// size `S`: `assembled` holds `[L_k | D_k | U_k]` per block (read only);
/// `forward` receives `[D'_k^-1 | G_k = D'_k^-1 L_k]` and `back` the
/// `X_k = D'_k^-1 U_k`, block by block. The same operations in the same
/// order for every `S`, compiled for each so that the small loops unroll.
/// `false` on a zero or non-finite pivot.
fn factorise_blocks<const S: usize>(
    assembled: &[f64],
    forward: &mut [f64],
    back: &mut [f64],
    piv: &mut [usize],
) -> bool {
    let (s, ss) = (S, S * S);
    let mut product = [0.0; MAX_BLOCK * MAX_BLOCK];
    let mut dk = [0.0; MAX_BLOCK * MAX_BLOCK];
    let piv = &mut piv[..s];
    let mut x_prev: &[f64] = &[];
    for ((blk, fwd), x_k) in assembled
        .chunks_exact(3 * ss)
        .zip(forward.chunks_exact_mut(2 * ss))
        .zip(back.chunks_exact_mut(ss))
    {
        let (lk, rest) = blk.split_at(ss);
        let (dv, uk) = rest.split_at(ss);
        let d = &mut dk[..ss];
        d.copy_from_slice(dv);
        if !x_prev.is_empty() {
            // D_k -= L_k X_{k-1}.
            let p = &mut product[..ss];
            p.fill(0.0);
            for i in 0..s {
                for j in 0..s {
                    let lij = lk[i * s + j];
                    for c in 0..s {
                        p[i * s + c] += lij * x_prev[j * s + c];
                    }
                }
            }
            for (dv, pv) in d.iter_mut().zip(p.iter()) {
                *dv -= pv;
            }
        }
        if !dense_lu(d, s, piv) {
            return false;
        }
        let (inv, g) = fwd.split_at_mut(ss);
        inv.fill(0.0);
        for i in 0..s {
            inv[i * s + i] = 1.0;
        }
        lu_solve(d, s, piv, inv, s);
        // G_k = D'_k^-1 L_k, for the forward solve.
        g.copy_from_slice(lk);
        lu_solve(d, s, piv, g, s);
        // X_k = D'_k^-1 U_k, for the back substitution and the next block.
        x_k.copy_from_slice(uk);
        lu_solve(d, s, piv, x_k, s);
        x_prev = x_k;
    }
    true
}

/// The factors of one matrix on a [`BlockLayout`].
pub(crate) struct Factors {
    layout: BlockLayout,
    /// diffsol's Newton matrix in CSC, as it writes it.
    a: FaerSparseMat<f64>,
    /// The storage slot in `assembled` of each CSC value (32 bits: half the
    /// memory traffic of the scatter).
    slots: Vec<u32>,
    /// The matrix per block, `[L_k | D_k | U_k]` (each `S x S`, row-major,
    /// the local unknowns first), then the lone diagonals. Entries outside
    /// the pattern stay zero: only the slots are ever written.
    assembled: Vec<f64>,
    /// `[D_PP^-1 | Z_k = D_PP^-1 D_PQ]` per block (`P x P`, `P x Q`): the
    /// local unknowns' condensation.
    local: Vec<f64>,
    /// `[L_QP | D_QP | U_QP]` per block (`Q x 3P`, row by row): what the
    /// local unknowns' solution feeds into the condensed right-hand side.
    coupling: Vec<f64>,
    /// The condensed matrix per block, `[L'_k | D'_k | U'_k]` (`Q x Q`).
    reduced: Vec<f64>,
    /// `[D''_k^-1 | G_k = D''_k^-1 L'_k]` per block of the condensed
    /// matrix, row-major: the forward solve is then products of small dense
    /// blocks read in one stream.
    forward: Vec<f64>,
    /// `X_k = D''_k^-1 U'_k` per block: the back substitution's stream.
    back: Vec<f64>,
    /// Pivots of the current block's LU.
    piv: [usize; MAX_BLOCK],
    /// The last factorisation succeeded.
    ok: bool,
    /// Scratch of the solves (`S` per block).
    work: RefCell<Vec<f64>>,
}

impl Factors {
    fn factorise(&mut self) -> bool {
        let l = &self.layout;
        let (s, p) = (l.size, l.local);
        let csc = self.a.inner()[0].val();
        let assembled = self.assembled.as_mut_slice();
        let mut finite = true;
        for (&slot, &v) in self.slots.iter().zip(csc) {
            assembled[slot as usize] = v;
            finite &= v.is_finite();
        }
        if !finite {
            return false;
        }
        let blocks = l.blocks();
        let (assembled, lone) = self.assembled.split_at(3 * s * s * blocks);
        if lone.contains(&0.0) {
            return false;
        }
        let (local, coupling, reduced) = (&mut self.local, &mut self.coupling, &mut self.reduced);
        if !shaped!(s, p, condense(assembled, local, coupling, reduced)) {
            return false;
        }
        let (forward, back, piv) = (&mut self.forward, &mut self.back, &mut self.piv);
        sized!(s - p, factorise_blocks(&self.reduced, forward, back, piv))
    }

    /// `x = A^-1 x` (`transpose`: `x = A^-T x`); `false` if the result is
    /// not finite.
    fn solve(&self, x: &mut [f64], transpose: bool) -> bool {
        let l = &self.layout;
        let (s, p) = (l.size, l.local);
        let mut work = self.work.borrow_mut();
        let split = 3 * s * s * l.blocks();
        let (assembled, lone) = self.assembled.split_at(split);
        let (local, order) = (&self.local, &l.order);
        let mut finite = if transpose {
            let factors = (&self.forward[..], &self.back[..]);
            let reduced = &self.reduced;
            shaped!(
                s,
                p,
                solve_condensed_transposed(assembled, local, reduced, factors, order, x, &mut work)
            )
        } else {
            let (coupling, forward, back) = (&self.coupling, &self.forward, &self.back);
            shaped!(
                s,
                p,
                solve_condensed(local, coupling, forward, back, order, x, &mut work)
            )
        };
        for (&u, &d) in l.lone.iter().zip(lone) {
            x[u] /= d;
            finite &= x[u].is_finite();
        }
        finite
    }
}

/// A block-tridiagonal matrix of dense `S x S` blocks assembled by its
/// caller (the contact solve of `moreau-jean`, `complementarity.rs`), and
/// its factors: the same block Thomas algorithm and sweeps as diffsol's
/// Newton matrices get ([`factorise_blocks`], [`solve_condensed`] with no
/// local unknowns), without a sparse pattern in between.
pub(crate) struct DenseTridiagonal {
    size: usize,
    /// `[L_k | D_k | U_k]` per block row (`S x S` each, row-major); the
    /// caller writes it, and `L_0`, `U_{K-1}` must stay zero.
    pub assembled: Vec<f64>,
    forward: Vec<f64>,
    back: Vec<f64>,
    piv: [usize; MAX_BLOCK],
    /// The identity order and the empty coupling of the sweeps.
    order: Vec<usize>,
    coupling: Vec<f64>,
    work: Vec<f64>,
}

impl DenseTridiagonal {
    /// `blocks` block rows of `size x size` blocks (`size` in
    /// `1..=MAX_BLOCK`), all zero.
    pub fn new(size: usize, blocks: usize) -> Self {
        let ss = size * size;
        Self {
            size,
            assembled: vec![0.0; 3 * ss * blocks],
            forward: vec![0.0; 2 * ss * blocks],
            back: vec![0.0; ss * blocks],
            piv: [0; MAX_BLOCK],
            order: (0..size * blocks).collect(),
            coupling: vec![0.0; blocks],
            work: vec![0.0; size * blocks],
        }
    }

    /// Factorises [`DenseTridiagonal::assembled`]; `false` on a zero or
    /// non-finite pivot (or a non-finite entry).
    pub fn factorise(&mut self) -> bool {
        if !self.assembled.iter().all(|v| v.is_finite()) {
            return false;
        }
        let (forward, back, piv) = (&mut self.forward, &mut self.back, &mut self.piv);
        sized!(
            self.size,
            factorise_blocks(&self.assembled, forward, back, piv)
        )
    }

    /// `x = A^-1 x` with the last factors; `false` if the result is not
    /// finite.
    pub fn solve(&mut self, x: &mut [f64]) -> bool {
        let (coupling, forward, back) = (&self.coupling, &self.forward, &self.back);
        let (order, work) = (&self.order, &mut self.work);
        shaped!(
            self.size,
            0,
            solve_condensed(&[], coupling, forward, back, order, x, work)
        )
    }
}

/// Block-tridiagonal LU with fallible factorisation; see the module doc.
/// Built by [`BlockLu::new`] with the block of every unknown; its pattern
/// comes from diffsol (`set_sparsity`), and a pattern that is not block
/// tridiagonal in that grouping leaves it unusable: every factorisation
/// fails (the caller checks the Jacobian's pattern first; see `bdf.rs`).
#[derive(Default)]
pub struct BlockLu {
    block: Vec<usize>,
    /// The factors; `None` until a pattern that is block tridiagonal in
    /// `block` was set.
    pub(crate) factors: Option<Factors>,
    log: Rc<LuLog>,
}

impl BlockLu {
    /// A solver for unknowns grouped as `block` (see [`BlockLayout::new`])
    /// that records its factorisations in `log`.
    pub fn new(block: Vec<usize>, log: Rc<LuLog>) -> Self {
        Self {
            block,
            factors: None,
            log,
        }
    }

    fn fail(&self) -> LaError {
        LaError::LinearSolverError(LinearSolverError::LuSolveFailed)
    }

    fn solve_either(&self, x: &mut FaerVec<f64>, transpose: bool) -> Result<(), LaError> {
        let Some(f) = self.factors.as_ref().filter(|f| f.ok) else {
            return Err(self.fail());
        };
        if f.solve(slice_mut(x), transpose) {
            Ok(())
        } else {
            self.log.record(false);
            Err(self.fail())
        }
    }
}

impl LinearSolver<FaerSparseMat<f64>> for BlockLu {
    fn set_sparsity<
        C: LinearOp<T = f64, V = FaerVec<f64>, M = FaerSparseMat<f64>, C = FaerContext>,
    >(
        &mut self,
        op: &C,
    ) {
        let a =
            FaerSparseMat::new_from_sparsity(op.nrows(), op.ncols(), op.sparsity(), *op.context());
        let pattern = a.inner()[0].symbolic();
        let Some((layout, slots)) = BlockLayout::new(&self.block, pattern).and_then(|layout| {
            let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
            let mut slots = Vec::with_capacity(row_idx.len());
            for c in 0..pattern.ncols() {
                for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
                    slots.push(u32::try_from(layout.slot(r, c)?).ok()?);
                }
            }
            Some((layout, slots))
        }) else {
            self.factors = None;
            return;
        };
        let (blocks, s, p) = (layout.blocks(), layout.size, layout.local);
        let (ss, qq) = (s * s, (s - p) * (s - p));
        self.factors = Some(Factors {
            assembled: vec![0.0; 3 * ss * blocks + layout.lone.len()],
            local: vec![0.0; (p * p + p * (s - p)) * blocks],
            coupling: vec![0.0; (3 * p * (s - p)).max(1) * blocks],
            reduced: vec![0.0; 3 * qq * blocks],
            forward: vec![0.0; 2 * qq * blocks],
            back: vec![0.0; qq * blocks],
            piv: [0; MAX_BLOCK],
            work: RefCell::new(vec![0.0; layout.order.len()]),
            layout,
            a,
            slots,
            ok: false,
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
        f.ok = f.factorise();
        self.log.record(f.ok);
    }

    fn solve_in_place(&self, x: &mut FaerVec<f64>) -> Result<(), LaError> {
        self.solve_either(x, false)
    }

    fn solve_transpose_in_place(&self, x: &mut FaerVec<f64>) -> Result<(), LaError> {
        self.solve_either(x, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diffsol_driver::slice;
    use crate::newton_matrix::NewtonMatrix;
    use crate::ode::SemiExplicitDae;
    use crate::testing::DenseSolve;
    use diffsol::Vector;
    use faer::sparse::{Pair, SymbolicSparseColMat};

    /// Every row of the tridiagonal test matrix couples its neighbours:
    /// none is condensed. (The chains' and BEAM's local rows are checked
    /// where those DAEs live, in chain-ode.)
    #[test]
    fn the_rows_of_the_tridiagonal_test_matrix_are_not_condensed() {
        let m = three_blocks();
        let l = BlockLayout::new(&[0, 0, 1, 1, 2, 2], m.pattern.as_ref()).unwrap();
        assert_eq!((l.size, l.local), (2, 0));
    }

    /// A 6x6 tridiagonal matrix (4 on the diagonal, 1 beside it) as three
    /// blocks of two (unknown `u` in block `u / 2`).
    fn three_blocks() -> NewtonMatrix {
        let dim = 6;
        let mut a = vec![0.0; dim * dim];
        let mut pairs = Vec::new();
        for i in 0..dim {
            a[i * dim + i] = 4.0;
            pairs.push(Pair::new(i, i));
            if i + 1 < dim {
                a[i * dim + i + 1] = 1.0;
                a[(i + 1) * dim + i] = 1.0;
                pairs.push(Pair::new(i, i + 1));
                pairs.push(Pair::new(i + 1, i));
            }
        }
        NewtonMatrix {
            dim,
            a,
            pattern: SymbolicSparseColMat::try_new_from_indices(dim, dim, &pairs)
                .unwrap()
                .0,
            ctx: FaerContext::default(),
        }
    }

    #[test]
    fn a_singular_or_non_finite_matrix_fails_and_a_good_one_recovers() {
        let log = Rc::new(LuLog::default());
        let mut lu = BlockLu::new(vec![0, 0, 1, 1, 2, 2], log.clone());
        let good = three_blocks();
        lu.set_sparsity(&good);
        lu.set_linearisation(&good);
        assert!(!log.last_failed.get());
        let solve = |lu: &BlockLu| {
            let mut x = FaerVec::from_element(6, 1.0, FaerContext::default());
            lu.solve_in_place(&mut x).map(|()| slice(&x).to_vec())
        };
        let x = solve(&lu).unwrap();
        let want = good.solve(&[1.0; 6], false);
        for (a, b) in x.iter().zip(&want) {
            assert!((a - b).abs() < 1e-14);
        }
        // Rows 4 and 5 made equal (both [0, 0, 0, 0, 1, 1]): the last
        // block's pivot is exactly zero (and no later block would turn it
        // into a NaN that fails on its own).
        let mut singular = three_blocks();
        for (k, v) in [(4 * 6 + 3, 0.0), (4 * 6 + 4, 1.0), (5 * 6 + 5, 1.0)] {
            singular.a[k] = v;
        }
        lu.set_linearisation(&singular);
        assert!(log.last_failed.get());
        assert!(solve(&lu).is_err());
        let mut nan = three_blocks();
        nan.a[7] = f64::NAN;
        lu.set_linearisation(&nan);
        assert!(log.last_failed.get());
        assert!(solve(&lu).is_err());
        assert_eq!(log.failures.get(), 2);
        lu.set_linearisation(&good);
        assert!(!log.last_failed.get());
        assert!(solve(&lu).is_ok());
    }

    #[test]
    fn a_grouping_that_is_not_block_tridiagonal_is_refused() {
        let m = three_blocks();
        let p = m.pattern.as_ref();
        assert!(BlockLayout::new(&[0, 0, 1, 1, 2, 2], p).is_some());
        // Unknown 1 (block 2) couples to unknown 0 and 2 (block 0 and 1):
        // two blocks apart.
        assert!(BlockLayout::new(&[0, 2, 1, 1, 2, 0], p).is_none());
        // Blocks of different sizes.
        assert!(BlockLayout::new(&[0, 0, 0, 1, 1, 2], p).is_none());
        // An empty block.
        assert!(BlockLayout::new(&[0, 0, 0, 2, 2, 2], p).is_none());
    }

    /// `x' = v`, `v' = a` and `0 = 0 a`: no equation fixes `a`, so every
    /// Newton matrix is singular. `blocks` says whether it names a block.
    struct Undetermined {
        blocks: bool,
    }

    impl SemiExplicitDae for Undetermined {
        fn dim(&self) -> usize {
            3
        }
        fn differential_dim(&self) -> usize {
            2
        }
        fn rhs(&self, _t: f64, y: &[f64], out: &mut [f64]) {
            out.copy_from_slice(&[y[1], y[2], 0.0]);
        }
        fn jacobian_entries(&self, _t: f64, _y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
            emit(0, 1, 1.0);
            emit(1, 2, 1.0);
            emit(2, 2, 0.0);
        }
        fn blocks(&self) -> Option<Vec<usize>> {
            self.blocks.then(|| vec![0, 0, 0])
        }
    }

    #[test]
    fn a_singular_newton_matrix_ends_the_run_as_linear_solve_failed() {
        use crate::bdf::integrate_dae;
        use crate::ode::Status;
        use crate::test_problems::{options, Quiet};
        for blocks in [true, false] {
            let o = options(1e-6, 1e-8);
            let out = integrate_dae(
                Undetermined { blocks },
                0.0,
                vec![1.0, 0.0, 0.0],
                1.0,
                &o,
                &mut Quiet,
            );
            assert_eq!(out.status, Status::LinearSolveFailed, "blocks {blocks}");
            assert_eq!(out.t_reached, 0.0);
            assert!(out.y_end.iter().all(|v| v.is_finite()));
        }
    }
}
