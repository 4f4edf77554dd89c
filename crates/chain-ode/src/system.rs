//! The chain as an ODE system: state `y = [phi_1..phi_n, w_1..w_n, W]`, where
//! `W` is the work dissipated so far (`W' = 2R`), carried so that the energy
//! balance `E + W = E(0)` can be checked along any run.

use crate::chain::Chain;
use crate::dae::ChainDae;
use crate::dae_frame::RodFrameDae;
use crate::dynamics::{accelerations_under, Base, EqualRods, Reactions, RodView, Workspace};
use crate::load::{Loads, Units};
use crate::scalar::{Dual, Scalar};
use fc_methods::{BandedDae, OdeSystem, Problem};

/// The falling chain as `y' = f(y)`, with preallocated workspaces.
#[derive(Clone, Debug)]
pub struct ChainSystem {
    chain: Chain,
    /// The chain's loads in rod units.
    loads: Loads,
    /// The pivot has been let go (`pivot.release` reached): `solve` sets it
    /// between the run up to the release and the run after it.
    released: bool,
    ws: Workspace<f64>,
    dual_ws: Workspace<Dual>,
    dual_phi: Vec<Dual>,
    dual_w: Vec<Dual>,
    dual_acc: Vec<Dual>,
}

impl ChainSystem {
    /// The system for a validated chain.
    pub fn new(chain: &Chain) -> Self {
        let n = chain.links();
        let loads = Loads::of(chain, Units::Rod);
        let (mut ws, mut dual_ws) = (Workspace::new(n), Workspace::new(n));
        if loads.reads_centres() {
            (ws, dual_ws) = (ws.with_centres(), dual_ws.with_centres());
        }
        Self {
            chain: chain.clone(),
            loads,
            released: false,
            ws,
            dual_ws,
            dual_phi: vec![Dual::default(); n],
            dual_w: vec![Dual::default(); n],
            dual_acc: vec![Dual::default(); n],
        }
    }

    /// The chain.
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// Lets the pivot go (or holds it again): from now on the right-hand
    /// side, its JVP and its DAE take joint 0 as a free end.
    pub fn set_released(&mut self, released: bool) {
        self.released = released;
    }

    /// How joint 0 is held at `t`: fixed, driven (`P0''(t)`) or free.
    pub fn base_at(&self, t: f64) -> Base {
        let pivot = self.chain.pivot();
        if self.released {
            Base::Free
        } else if pivot.is_driven() {
            Base::Driven(pivot.acceleration_at(t))
        } else {
            Base::Fixed
        }
    }

    /// Packs a state into `[phi, w, W]`.
    pub fn pack(angles: &[f64], rates: &[f64], dissipated: f64) -> Vec<f64> {
        let mut y = Vec::with_capacity(2 * angles.len() + 1);
        y.extend_from_slice(angles);
        y.extend_from_slice(rates);
        y.push(dissipated);
        y
    }

    /// `dy = f(y)` with the pivot fixed, also returning the pivot force
    /// and tip acceleration.
    pub fn rhs_with_reactions(&mut self, y: &[f64], dy: &mut [f64]) -> Reactions<f64> {
        let n = self.chain.links();
        let (phi, rest) = y.split_at(n);
        let w = &rest[..n];
        let (dphi, drest) = dy.split_at_mut(n);
        dphi.copy_from_slice(w);
        let r = accelerations_under(
            &self.chain,
            &self.loads,
            Base::Fixed,
            [0.0, 0.0],
            phi,
            w,
            &mut drest[..n],
            &mut self.ws,
        );
        drest[n] = self.work_rate(phi, w, r.load_power);
        r
    }

    /// `W'`: the power the loads draw through the joints and at the rods
    /// (`rod_power`, the recursion's), physical units.
    #[inline(always)]
    fn work_rate<T: Scalar>(&self, phi: &[T], w: &[T], rod_power: T) -> T {
        let view = RodView {
            phi,
            w,
            sc: &[],
            rods: EqualRods,
            centre: &[],
            centre_velocity: &[],
        };
        let p = self.loads.joint_power(&view, T::cst(0.0));
        if self.loads.reads_centres() {
            p + rod_power
        } else {
            p
        }
    }

    /// The pivot's velocity at `t` (physical units; zero unless driven, and
    /// unknown once let go: the loads that read it are refused then).
    fn pivot_velocity(&self, base: Base, t: f64) -> [f64; 2] {
        match base {
            Base::Driven(_) => self.chain.pivot().drive(t)[1],
            _ => [0.0, 0.0],
        }
    }

    /// `dy = f(t, y)` with the pivot held as at `t` ([`ChainSystem::base_at`]),
    /// also returning the reactions. The work `W` counts the power the
    /// moving pivot puts in: `W' = 2R - F_0 . P0'(t)`.
    pub fn rhs_at(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Reactions<f64> {
        let base = self.base_at(t);
        let n = self.chain.links();
        let (phi, rest) = y.split_at(n);
        let w = &rest[..n];
        let (dphi, drest) = dy.split_at_mut(n);
        dphi.copy_from_slice(w);
        let v0 = self.pivot_velocity(base, t);
        let r = accelerations_under(
            &self.chain,
            &self.loads,
            base,
            v0,
            phi,
            w,
            &mut drest[..n],
            &mut self.ws,
        );
        drest[n] = self.work_rate(phi, w, r.load_power);
        if let Base::Driven(_) = base {
            let v0 = self.chain.pivot().drive(t)[1];
            drest[n] -= r.pivot_force[0] * v0[0] + r.pivot_force[1] * v0[1];
        }
        r
    }

    /// Length of the state `[phi, w, W]`: `2 n + 1`.
    pub fn dim(&self) -> usize {
        2 * self.chain.links() + 1
    }

    /// `dy = f(t, y)`, O(n) and allocation-free (with a fixed pivot the
    /// system is autonomous: `t` is unused).
    pub fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        if self.chain.pivot().is_fixed() {
            self.rhs_with_reactions(y, dy);
        } else {
            self.rhs_at(t, y, dy);
        }
    }

    /// The exact Jacobian-vector product `jv = (df/dy)(y) v`, by forward-mode
    /// dual numbers through the same recursion.
    pub fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        let n = self.chain.links();
        for i in 0..n {
            self.dual_phi[i] = Dual::new(y[i], v[i]);
            self.dual_w[i] = Dual::new(y[n + i], v[n + i]);
        }
        let base = self.base_at(t);
        let v0 = self.pivot_velocity(base, t);
        let r = accelerations_under(
            &self.chain,
            &self.loads,
            base,
            v0,
            &self.dual_phi,
            &self.dual_w,
            &mut self.dual_acc,
            &mut self.dual_ws,
        );
        jv[..n].copy_from_slice(&v[n..2 * n]);
        for i in 0..n {
            jv[n + i] = self.dual_acc[i].d;
        }
        // d(W') by the same dual numbers (friction's: 2 r sum dw dv).
        jv[2 * n] = self.work_rate(&self.dual_phi, &self.dual_w, r.load_power).d;
        if let Base::Driven(_) = base {
            let v0 = self.chain.pivot().drive(t)[1];
            jv[2 * n] -= r.pivot_force[0].d * v0[0] + r.pivot_force[1].d * v0[1];
        }
    }
}

/// The methods see the chain through the same three functions.
impl OdeSystem for ChainSystem {
    fn dim(&self) -> usize {
        ChainSystem::dim(self)
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        ChainSystem::rhs(self, t, y, dy)
    }

    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        ChainSystem::jvp(self, t, y, v, jv)
    }
}

/// Every method runs the chain: the explicit ones and `bdf-dense` through
/// [`OdeSystem`], `bdf` on its banded DAE ([`ChainDae`]), `auto` with its
/// crossover placed from the chain.
impl Problem for ChainSystem {
    /// [`ChainDae`] from `y0 = [phi, w, W]`, its accelerations and joint
    /// forces made consistent by the O(n) recursion.
    fn banded_dae(&self, t0: f64, y0: &[f64]) -> Option<BandedDae> {
        let dae = ChainDae::new(&self.chain).released(self.released);
        let mut full = vec![0.0; dae.dim()];
        full[..dae.differential_dim()].copy_from_slice(y0);
        dae.make_consistent_at(t0, &mut full, &mut Workspace::new(self.chain.links()));
        // In the rods' frames: a kept Newton matrix does not go stale as the
        // chain swings (`dae_frame`).
        let dae = RodFrameDae::new(dae)?;
        let y0 = dae.from_world(&full);
        Some(BandedDae {
            dae: Box::new(dae),
            y0,
        })
    }
}
