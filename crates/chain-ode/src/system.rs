//! The chain as an ODE system: state `y = [phi_1..phi_n, w_1..w_n, W]`, where
//! `W` is the work dissipated so far (`W' = 2R`), carried so that the energy
//! balance `E + W = E(0)` can be checked along any run.

use crate::chain::Chain;
use crate::dae::ChainDae;
use crate::dynamics::{accelerations, Reactions, Workspace};
use crate::kinematics::dissipation_rate;
use crate::ode::{BandedDae, OdeSystem, Problem};
use crate::scalar::Dual;

/// The falling chain as `y' = f(y)`, with preallocated workspaces.
#[derive(Clone, Debug)]
pub struct ChainSystem {
    chain: Chain,
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
        Self {
            chain: chain.clone(),
            ws: Workspace::new(n),
            dual_ws: Workspace::new(n),
            dual_phi: vec![Dual::default(); n],
            dual_w: vec![Dual::default(); n],
            dual_acc: vec![Dual::default(); n],
        }
    }

    /// The chain.
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// Packs a state into `[phi, w, W]`.
    pub fn pack(angles: &[f64], rates: &[f64], dissipated: f64) -> Vec<f64> {
        let mut y = Vec::with_capacity(2 * angles.len() + 1);
        y.extend_from_slice(angles);
        y.extend_from_slice(rates);
        y.push(dissipated);
        y
    }

    /// `dy = f(y)`, also returning the pivot force and tip acceleration.
    pub fn rhs_with_reactions(&mut self, y: &[f64], dy: &mut [f64]) -> Reactions<f64> {
        let n = self.chain.links();
        let (phi, rest) = y.split_at(n);
        let w = &rest[..n];
        let (dphi, drest) = dy.split_at_mut(n);
        dphi.copy_from_slice(w);
        let r = accelerations(&self.chain, phi, w, &mut drest[..n], &mut self.ws);
        drest[n] = dissipation_rate(&self.chain, w);
        r
    }

    /// Length of the state `[phi, w, W]`: `2 n + 1`.
    pub fn dim(&self) -> usize {
        2 * self.chain.links() + 1
    }

    /// `dy = f(y)`, O(n) and allocation-free (the system is autonomous: `t`
    /// is unused).
    pub fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        self.rhs_with_reactions(y, dy);
    }

    /// The exact Jacobian-vector product `jv = (df/dy)(y) v`, by forward-mode
    /// dual numbers through the same recursion.
    pub fn jvp(&mut self, _t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        let n = self.chain.links();
        for i in 0..n {
            self.dual_phi[i] = Dual::new(y[i], v[i]);
            self.dual_w[i] = Dual::new(y[n + i], v[n + i]);
        }
        accelerations(
            &self.chain,
            &self.dual_phi,
            &self.dual_w,
            &mut self.dual_acc,
            &mut self.dual_ws,
        );
        jv[..n].copy_from_slice(&v[n..2 * n]);
        for i in 0..n {
            jv[n + i] = self.dual_acc[i].d;
        }
        // d(2R) = 2 r sum (w_i - w_{i-1}) (v_i - v_{i-1}).
        let (w, vw) = (&y[n..2 * n], &v[n..2 * n]);
        let mut d = 0.0;
        for i in 1..n {
            d += (w[i] - w[i - 1]) * (vw[i] - vw[i - 1]);
        }
        jv[2 * n] = 2.0 * self.chain.damping() * d;
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
    fn banded_dae(&self, _t0: f64, y0: &[f64]) -> Option<BandedDae> {
        let dae = ChainDae::new(&self.chain);
        let mut full = vec![0.0; dae.dim()];
        full[..dae.differential_dim()].copy_from_slice(y0);
        dae.make_consistent(&mut full, &mut Workspace::new(self.chain.links()));
        Some(BandedDae {
            dae: Box::new(dae),
            y0: full,
        })
    }

    fn chain(&self) -> Option<&Chain> {
        Some(&self.chain)
    }
}
