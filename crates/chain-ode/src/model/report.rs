//! The report's model ([`crate::report`]) as a [`Model`]: the rigid chain's
//! state and geometry, the report's equations and energy (its errata as
//! switches), and, for `rk4` with the stepper erratum, the report's own
//! first-order stepper. Its states are the rigid model's, read by the same
//! [`RigidView`](super::RigidView) with the report's energy.

use super::{Layout, Model, RigidModel, StateView};
use crate::chain::{check, Chain};
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
            rigid: RigidModel::new(chain).reading_as(model),
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

    fn view(&self) -> &dyn StateView {
        self.rigid.view()
    }
}
