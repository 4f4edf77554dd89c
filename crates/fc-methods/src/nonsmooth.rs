//! The narrow interface of a nonsmooth mechanical problem, for a method
//! that steps over impacts (`moreau-jean`): bodies with a constant
//! diagonal mass, the smooth forces on them, and constraint rows (joints
//! that hold, contacts that may open, friction) with their gaps. It knows
//! no chain: a chain of rods, a bouncing ball and a pendulum are all
//! [`Nonsmooth`].
//!
//! **Coordinates.** `q` and `v` have `n B` entries, body `i`'s `B` at
//! `i B .. (i + 1) B` (`B` = [`Nonsmooth::body_dim`] <= [`MAX_BODY`]), and
//! `q' = v` (a rod's centre and angle, its velocity and angular rate). The
//! mass matrix `M` is constant and diagonal ([`Nonsmooth::inverse_mass`]).
//!
//! **Rows.** The constraints come in `n + 1` blocks of `S` rows
//! ([`Nonsmooth::block_rows`] <= [`MAX_ROWS`]); block `k` may act on bodies
//! `k − 1` and `k` only ([`Row::jac`]): a chain of bodies, each block the
//! joint between two of them and whatever touches there. Then the Delassus
//! matrix `J M⁻¹ Jᵀ` is block tridiagonal, and every linear solve of a step
//! is one block-tridiagonal factorisation, O(n) in the bodies and the
//! contacts. A row is [`RowKind::Off`] (an unused slot, its impulse zero),
//! [`RowKind::Bilateral`] (`g(q) = 0` holds: a joint), [`RowKind::Normal`]
//! (`g(q) >= 0`: a contact, with Newton's restitution), or
//! [`RowKind::Tangent`] (Coulomb friction on the contact of the row just
//! before it, which must be its `Normal`).

/// The most coordinates a body may have (a rigid body in the plane: 3).
pub const MAX_BODY: usize = 3;

/// The most rows a block may have.
pub const MAX_ROWS: usize = 8;

/// What a constraint row is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RowKind {
    /// An unused slot: no impulse.
    Off,
    /// `g(q) = 0`, held at the velocity level (`J v = 0` after the step)
    /// and projected to at the position level after it.
    Bilateral,
    /// `g(q) >= 0` (the gap; length): a unilateral contact, active in a
    /// step when the free motion would close its gap by the step's end.
    /// Newton's impact law on its normal velocity `u = J v`:
    /// `0 <= P ⊥ u⁺ + e min(û, 0) >= 0` with `e` in `[0, 1]` (`û` the
    /// free motion's velocity at the step's end, which the impulse acts on).
    Normal {
        /// The coefficient of restitution `e` (0: plastic).
        restitution: f64,
    },
    /// Coulomb friction on the contact of the previous row: the tangential
    /// impulse `|P_T| <= mu P_N`, sticking (`u_T⁺ = 0`) below the bound,
    /// sliding against `u_T⁺` at it. In the plane the cone is this
    /// interval: exact, not faceted.
    Tangent {
        /// `mu >= 0`.
        friction: f64,
    },
}

/// One constraint row of block `k`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Row {
    pub kind: RowKind,
    /// The row of the Jacobian `J = dg/dq` (and of `u = J v`): its entries
    /// on body `k − 1` (the first `B`) and on body `k` (the next `B`);
    /// entries on a body that does not exist (`−1` for block 0, `n` for
    /// block `n`) must be zero.
    pub jac: [f64; 2 * MAX_BODY],
    /// `g(q)`: a bilateral row's error (0 when it holds), a normal row's
    /// gap (> 0 apart); unused by a tangent row.
    pub gap: f64,
}

impl Row {
    /// An unused slot.
    pub const OFF: Row = Row {
        kind: RowKind::Off,
        jac: [0.0; 2 * MAX_BODY],
        gap: 0.0,
    };
}

/// What one step did, for the problem to update the rest of its state
/// (its work accumulator, its contact forces): [`Nonsmooth::state`].
pub struct StepRecord<'a> {
    /// The step's start and length.
    pub t0: f64,
    pub h: f64,
    /// The coordinates and velocities at the step's end.
    pub q: &'a [f64],
    pub v: &'a [f64],
    /// The velocities at the step's start.
    pub v0: &'a [f64],
    /// The rows at the step's midpoint, as the step used them (`Off` for a
    /// contact that was not active).
    pub rows: &'a [Row],
    /// Each row's impulse over the step (force × time): a contact's force
    /// averaged over the step is `impulse / h`.
    pub impulses: &'a [f64],
    /// The work the contact impulses (normal and tangential rows) took out
    /// of the motion, `−Σ P (u⁺ + û) / 2` (`u = J v`, `û` the free
    /// motion's at the step's end, which the impulses act on): exactly the
    /// kinetic energy they removed from it (Kelvin's theorem), `>= 0` for
    /// every impact and slip (0 for an elastic impact).
    pub contact_work: f64,
}

/// A mechanical system in maximal coordinates with constraints, as a
/// method that steps over impacts sees it (module doc). A problem states
/// itself so through [`Problem::nonsmooth`](crate::Problem::nonsmooth).
pub trait Nonsmooth {
    /// Bodies `n` (>= 1).
    fn bodies(&self) -> usize;
    /// Coordinates per body `B` (in `1..=MAX_BODY`).
    fn body_dim(&self) -> usize;
    /// Rows per block `S` (in `1..=MAX_ROWS`); there are `n + 1` blocks.
    fn block_rows(&self) -> usize;
    /// `M⁻¹`, one entry per coordinate (constant along the run, > 0).
    fn inverse_mass(&self, out: &mut [f64]);
    /// The coordinates `q` and velocities `v` of the problem's state `y`.
    fn coordinates(&self, y: &[f64], q: &mut [f64], v: &mut [f64]);
    /// The smooth generalised forces `f(t, q, v)` (gravity, friction in
    /// the joints, bending): no allocation.
    fn forces(&mut self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]);
    /// The rows at `(t, q)`, `(n + 1) S` of them, block by block.
    fn rows(&mut self, t: f64, q: &[f64], rows: &mut [Row]);
    /// The problem's state after the step `step`, written over `y` (which
    /// holds the state at the step's start): its coordinates and
    /// velocities, and whatever else it keeps (its work, its forces).
    fn state(&mut self, step: &StepRecord<'_>, y: &mut [f64]);
}
