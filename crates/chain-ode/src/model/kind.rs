//! The crate's models as one type, and the one decision of which model a
//! chain is.

use super::{
    ContactModel, ElasticModel, ForceScratch, Layout, Model, Observed, PeakForce, PeakValue,
    ReportChain, RigidModel,
};
use crate::chain::Chain;
use crate::floor::FloorLaw;
use crate::kinematics::Vec2;
use crate::report::ReportModel;
use crate::solve::SolveOptions;
use crate::state::State;
use fc_methods::InvalidParameter;
use fc_methods::Problem;
use fc_methods::{AutoPlan, Integrator, Method, TimeScales};

/// The crate's models of a chain. [`ModelKind::of`] chooses a chain's
/// (rigid or elastic links), [`ReportChain`] is the report's; every
/// [`Model`] method dispatches to the variant's. Models that are not a
/// chain's (BEAM, a model of another crate) run as themselves.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelKind {
    /// Rigid rods.
    Rigid(RigidModel),
    /// Elastic links.
    Elastic(ElasticModel),
    /// Rigid rods on a constraint floor.
    Contact(ContactModel),
    /// The report's equations.
    Report(ReportChain),
}

impl ModelKind {
    /// The names of the models a scene can choose ([`Model::name`] of each
    /// variant, in [`ModelKind::choose`]'s order); tests walk it.
    pub const MODELS: [&'static str; 4] = ["rigid", "elastic", "contact", "report"];

    /// The model of `chain` with the report's equations `report`
    /// (`model.report = true` is `Some(ReportModel::AS_CODED)`): the
    /// report's when asked, else [`ModelKind::of`]. This is the one place
    /// that chooses a scene's model.
    pub fn choose(chain: &Chain, report: Option<ReportModel>) -> Self {
        match report {
            Some(model) => Self::Report(ReportChain::new(chain, model)),
            None => Self::of(chain),
        }
    }

    /// The model of `chain` without the report's equations: rigid rods on a
    /// constraint floor when its floor's law is `constraint`, elastic links
    /// when it has an axial stiffness, rigid rods otherwise.
    pub fn of(chain: &Chain) -> Self {
        if chain.floor().is_some_and(|f| f.law == FloorLaw::Constraint) {
            Self::Contact(ContactModel::new(chain))
        } else if chain.is_elastic() {
            Self::Elastic(ElasticModel::new(chain))
        } else {
            Self::Rigid(RigidModel::new(chain))
        }
    }

    /// The chain.
    pub fn chain(&self) -> &Chain {
        match self {
            Self::Rigid(m) => m.chain_ref(),
            Self::Elastic(m) => m.chain_ref(),
            Self::Contact(m) => m.chain_ref(),
            Self::Report(m) => m.chain_ref(),
        }
    }
}

/// What [`solve`](crate::solve) accepts as a model: any [`Model`], or a
/// [`Chain`] (whose model [`ModelKind::of`] chooses).
pub trait IntoModel {
    /// The model.
    type Model: Model;
    /// Makes it.
    fn into_model(self) -> Self::Model;
}

impl<M: Model> IntoModel for M {
    type Model = M;
    fn into_model(self) -> M {
        self
    }
}

impl IntoModel for &Chain {
    type Model = ModelKind;
    fn into_model(self) -> ModelKind {
        ModelKind::of(self)
    }
}

impl From<RigidModel> for ModelKind {
    fn from(m: RigidModel) -> Self {
        Self::Rigid(m)
    }
}

impl From<ElasticModel> for ModelKind {
    fn from(m: ElasticModel) -> Self {
        Self::Elastic(m)
    }
}

impl From<ContactModel> for ModelKind {
    fn from(m: ContactModel) -> Self {
        Self::Contact(m)
    }
}

impl From<ReportChain> for ModelKind {
    fn from(m: ReportChain) -> Self {
        Self::Report(m)
    }
}

/// `$m.$f(...)` on whichever model `self` holds.
macro_rules! each {
    ($self:ident, $m:ident => $e:expr) => {
        match $self {
            ModelKind::Rigid($m) => $e,
            ModelKind::Elastic($m) => $e,
            ModelKind::Contact($m) => $e,
            ModelKind::Report($m) => $e,
        }
    };
}

impl Model for ModelKind {
    fn name(&self) -> &'static str {
        each!(self, m => m.name())
    }
    fn chain(&self) -> Option<&Chain> {
        Some(ModelKind::chain(self))
    }
    fn layout(&self) -> Layout {
        each!(self, m => m.layout())
    }
    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter> {
        each!(self, m => m.validate(method, options))
    }
    fn initial_state(&mut self, start: &State) -> Result<Vec<f64>, InvalidParameter> {
        each!(self, m => m.initial_state(start))
    }
    fn problem(&self) -> Box<dyn Problem + '_> {
        each!(self, m => m.problem())
    }
    fn integrator(&self, method: Method) -> &'static Integrator {
        each!(self, m => m.integrator(method))
    }
    fn energy_scale(&self) -> f64 {
        each!(self, m => m.energy_scale())
    }
    fn is_driven(&self) -> bool {
        each!(self, m => m.is_driven())
    }
    fn time_scales(&self) -> TimeScales {
        each!(self, m => m.time_scales())
    }
    fn auto_plan(&self, rtol: f64) -> AutoPlan {
        each!(self, m => m.auto_plan(rtol))
    }
    fn event_time(&self) -> Option<f64> {
        each!(self, m => m.event_time())
    }
    fn at_event(&mut self, t: f64, y: &mut [f64]) {
        each!(self, m => m.at_event(t, y))
    }
    fn observe(&self, t: f64, y: &[f64], f: &[f64], trig: &mut Vec<(f64, f64)>) -> Observed {
        each!(self, m => m.observe(t, y, f, trig))
    }
    fn energy(&self, t: f64, y: &[f64]) -> f64 {
        each!(self, m => m.energy(t, y))
    }
    fn tip(&self, t: f64, y: &[f64]) -> Vec2 {
        each!(self, m => m.tip(t, y))
    }
    fn tip_velocity(&self, t: f64, y: &[f64]) -> Vec2 {
        each!(self, m => m.tip_velocity(t, y))
    }
    fn support(&self, t: f64, y: &[f64]) -> [Vec2; 2] {
        each!(self, m => m.support(t, y))
    }
    fn joints(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        each!(self, m => m.joints(t, y))
    }
    fn joint_forces(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        each!(self, m => m.joint_forces(t, y))
    }
    fn support_force(&self, t: f64, y: &[f64]) -> Vec2 {
        each!(self, m => m.support_force(t, y))
    }
    fn refines_tip_speed(&self) -> bool {
        each!(self, m => m.refines_tip_speed())
    }
    fn momentum(&self, t: f64, y: &[f64]) -> Vec2 {
        each!(self, m => m.momentum(t, y))
    }
    fn floor_forces(&self, t: f64, y: &[f64]) -> Option<Vec<Vec2>> {
        each!(self, m => m.floor_forces(t, y))
    }
    fn floor_line(&self) -> Option<(f64, f64)> {
        each!(self, m => m.floor_line())
    }
    fn peak_forces(&self) -> &'static [PeakForce] {
        each!(self, m => m.peak_forces())
    }
    fn peak_force(
        &self,
        force: PeakForce,
        t: f64,
        y: &[f64],
        scratch: &mut ForceScratch,
    ) -> PeakValue {
        each!(self, m => m.peak_force(force, t, y, scratch))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::ChainParams;

    /// [`ModelKind::choose`] chooses each of [`ModelKind::MODELS`], in its
    /// order: rigid links, elastic links, rigid links on a constraint floor,
    /// the report's equations.
    #[test]
    fn choose_makes_every_model_of_the_list() {
        let rigid = Chain::report(4, 0.0).unwrap();
        let elastic = Chain::new(ChainParams {
            links: 4,
            axial_stiffness: Some(1e4),
            ..ChainParams::default()
        })
        .unwrap();
        let on_floor = Chain::new(ChainParams {
            links: 4,
            floor: Some(crate::Floor {
                height: Some(-10.0),
                angle: 0.0,
                stiffness: 1e4,
                damping: 0.0,
                friction: 0.0,
                slip_speed: 1e-3,
                law: crate::floor::FloorLaw::Constraint,
                restitution: 0.0,
            }),
            ..ChainParams::default()
        })
        .unwrap();
        let chosen = [
            ModelKind::choose(&rigid, None),
            ModelKind::choose(&elastic, None),
            ModelKind::choose(&on_floor, None),
            ModelKind::choose(&rigid, Some(ReportModel::AS_CODED)),
        ];
        let names: Vec<&str> = chosen.iter().map(Model::name).collect();
        assert_eq!(names, ModelKind::MODELS);
        assert_eq!(ModelKind::of(&elastic), chosen[1]);
    }
}
