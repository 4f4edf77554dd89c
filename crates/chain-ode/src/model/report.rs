//! The report's model ([`crate::report`]) as a [`Model`]: the rigid chain's
//! state and geometry, the report's equations and energy (its errata as
//! switches), and, for `rk4` with the stepper erratum, the report's own
//! first-order stepper.

use super::{ForceScratch, Layout, Model, Observed, PeakForce, PeakValue, RigidModel};
use crate::chain::{check, Chain};
use crate::kinematics::Vec2;
use crate::report::{ReportModel, ReportSystem};
use crate::solve::{SolveOptions, REPORT_METHODS, REPORT_RK4};
use crate::state::State;
use fc_methods::InvalidParameter;
use fc_methods::Problem;
use fc_methods::{Integrator, Method};

/// A chain run by the report's equations.
#[derive(Clone, Debug, PartialEq)]
pub struct ReportChain {
    rigid: RigidModel,
    model: ReportModel,
}

impl ReportChain {
    /// `chain` under the report's `model` (checked by [`Model::validate`]).
    pub fn new(chain: &Chain, model: ReportModel) -> Self {
        Self {
            rigid: RigidModel::new(chain),
            model,
        }
    }

    /// The report's switches.
    pub fn report(&self) -> ReportModel {
        self.model
    }

    /// The chain.
    pub fn chain_ref(&self) -> &Chain {
        self.rigid.chain_ref()
    }

    fn rigid_chain(&self) -> &Chain {
        self.rigid.chain_ref()
    }
}

impl Model for ReportChain {
    fn name(&self) -> &'static str {
        "report"
    }

    fn chain(&self) -> Option<&Chain> {
        Some(self.rigid_chain())
    }

    fn layout(&self) -> Layout {
        self.rigid.layout()
    }

    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter> {
        check(
            REPORT_METHODS.contains(&method),
            "run.method",
            "one of rk4, dopri5, dop853 with model.report = true",
            method,
        )?;
        self.model.validate(self.rigid_chain())?;
        self.rigid.validate(method, options)
    }

    fn initial_state(&mut self, start: &State) -> Result<Vec<f64>, InvalidParameter> {
        self.rigid.initial_state(start)
    }

    fn problem(&self) -> Box<dyn Problem + '_> {
        Box::new(ReportSystem::new(self.rigid_chain(), self.model))
    }

    fn integrator(&self, method: Method) -> &'static Integrator {
        if method == Method::Rk4 && self.model.stepper {
            &REPORT_RK4
        } else {
            method.integrator()
        }
    }

    fn energy_scale(&self) -> f64 {
        self.model.energy_scale(self.rigid_chain())
    }

    fn observe(&self, t: f64, y: &[f64], f: &[f64], trig: &mut Vec<(f64, f64)>) -> Observed {
        Observed {
            energy: self.energy(t, y),
            ..self.rigid.observe(t, y, f, trig)
        }
    }

    /// The report's energy (its Lagrangian's `T + V`, in its units).
    fn energy(&self, _t: f64, y: &[f64]) -> f64 {
        let chain = self.rigid_chain();
        let n = chain.links();
        self.model.energy(chain, &y[..n], &y[n..2 * n])
    }

    fn tip(&self, t: f64, y: &[f64]) -> Vec2 {
        self.rigid.tip(t, y)
    }

    fn tip_velocity(&self, t: f64, y: &[f64]) -> Vec2 {
        self.rigid.tip_velocity(t, y)
    }

    fn support(&self, t: f64, y: &[f64]) -> [Vec2; 2] {
        self.rigid.support(t, y)
    }

    fn joints(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        self.rigid.joints(t, y)
    }

    fn joint_forces(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        self.rigid.joint_forces(t, y)
    }

    fn momentum(&self, t: f64, y: &[f64]) -> Vec2 {
        self.rigid.momentum(t, y)
    }

    /// The corrected chain's forces at the report's state, as
    /// [`Model::joint_forces`] has them (the report's equations have no
    /// multipliers of their own).
    fn peak_forces(&self) -> &'static [PeakForce] {
        self.rigid.peak_forces()
    }

    fn peak_force(
        &self,
        force: PeakForce,
        t: f64,
        y: &[f64],
        scratch: &mut ForceScratch,
    ) -> PeakValue {
        self.rigid.peak_force(force, t, y, scratch)
    }
}
