//! The chain with elastic links as a [`Model`]: the state
//! `[phi, w, W, x, y, vx, vy]` (`6 n + 1`, rod centres relative to the
//! pivot's prescribed position), and what such a state means, [`LinkView`];
//! the physics is [`crate::elastic`]'s.
//!
//! Its event is the release of the pivot at `0 < t_r < t_end`: the run is
//! cut there and goes on without the joint-0 spring, whose energy
//! `K_0 |d_0|^2 / 2` leaves the chain then: it is added to the work `W`, so
//! that the balance `E + W = E(0)` holds across the cut.

use super::{ForceScratch, Layout, Model, Observed, PeakForce, PeakValue, StateView};
use crate::chain::{check, Chain};
use crate::elastic::{self, ElasticSystem};
use crate::floor::{self, FloorTerm};
use crate::kinematics::Vec2;
use crate::load::{FloorContact, Loads, Units};
use crate::pivot::PivotPath;
use crate::solve::auto_elastic;
use crate::solve::{SolveOptions, BDF_DENSE_MAX_ELASTIC_LINKS};
use crate::state::State;
use fc_methods::InvalidParameter;
use fc_methods::Problem;
use fc_methods::{AutoPlan, Method, TimeScales};

/// The elastic chain, its pivot's path, and whether joint 0 has let go.
#[derive(Clone, Debug, PartialEq)]
pub struct ElasticModel {
    view: LinkView,
    released: bool,
}

/// What a state `[phi, w, W, x, y, vx, vy]` of elastic links means: its
/// pivot's path, the floor as placed, the loads whose potentials its energy
/// holds.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkView {
    chain: Chain,
    path: PivotPath,
    /// The floor in the frame of the start's anchor (`None`: no floor).
    floor: Option<FloorTerm>,
    /// The loads (physical units), the placed floor among them.
    loads: Loads,
}

impl ElasticModel {
    /// The model of a validated chain with elastic links (a pivot let go
    /// at `t = 0` is free from the start).
    pub fn new(chain: &Chain) -> Self {
        Self {
            view: LinkView {
                chain: chain.clone(),
                path: PivotPath::new(chain, [0.0, 0.0]),
                floor: None,
                loads: Loads::of(chain, Units::Physical),
            },
            released: chain.pivot().release == Some(0.0),
        }
    }
}

impl ElasticModel {
    /// The chain.
    pub fn chain_ref(&self) -> &Chain {
        &self.view.chain
    }

    /// The floor as placed for the start (in the anchor's frame), once
    /// [`Model::initial_state`] has run; `None` without a floor.
    pub fn floor(&self) -> Option<&FloorTerm> {
        self.view.floor.as_ref()
    }

    /// The start's anchor `P0`.
    pub fn anchor(&self) -> Vec2 {
        self.view.path.anchor
    }
}

impl Model for ElasticModel {
    fn name(&self) -> &'static str {
        "elastic"
    }

    fn chain(&self) -> Option<&Chain> {
        Some(&self.view.chain)
    }

    fn layout(&self) -> Layout {
        elastic_layout(&self.view.chain)
    }

    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter> {
        options.validate_common(
            Some(self.view.chain.pivot()),
            method,
            &elastic_layout(&self.view.chain),
        )?;
        if method == Method::BdfDense {
            check(
                self.view.chain.links() <= BDF_DENSE_MAX_ELASTIC_LINKS,
                "chain.links",
                format!(
                    "at most {BDF_DENSE_MAX_ELASTIC_LINKS} for bdf-dense with chain.axial_stiffness \
                     (its dense Jacobian of 6 n + 1 unknowns grows like n^2 in memory and n^3 in \
                     time); run.method = \"bdf\" is the same method in O(n)"
                ),
                self.view.chain.links(),
            )?;
        }
        super::rigid::check_dense_size(&self.view.chain, method)
    }

    fn initial_state(&mut self, start: &State) -> Result<Vec<f64>, InvalidParameter> {
        super::check_start(&self.view.chain, start)?;
        self.view.path = PivotPath::new(&self.view.chain, start.anchor);
        let y = elastic::start_state(&self.view.chain, start);
        if let Some(f) = self.view.chain.floor() {
            let term = match f.height {
                Some(h) => f.term(h, start.anchor),
                None => f.term(0.0, start.anchor).touching(
                    floor::points(&self.view.chain, &y)
                        .into_iter()
                        .map(|[p, _]| p),
                ),
            };
            let tolerance =
                floor::start_tolerance(f, self.view.chain.weight(), self.view.chain.length());
            if let Some(o) = floor::overlap(&self.view.chain, &term, &y) {
                if o.total > tolerance {
                    return Err(floor::inside_error(o, tolerance));
                }
            }
            self.view.floor = Some(term);
            self.view.loads.floor = Some(FloorContact::placed(term));
        }
        Ok(y)
    }

    fn problem(&self) -> Box<dyn Problem + '_> {
        let mut sys = ElasticSystem::new(&self.view.chain);
        if self.released {
            sys.set_released(true);
        }
        if self.view.floor.is_some() {
            sys.set_floor(self.view.floor);
        }
        Box::new(sys)
    }

    fn energy_scale(&self) -> f64 {
        self.view.chain.energy_scale()
    }

    fn is_driven(&self) -> bool {
        self.view.chain.pivot().is_driven()
    }

    fn time_scales(&self) -> TimeScales {
        self.view.chain.pivot().time_scales()
    }

    fn auto_plan(&self, rtol: f64) -> AutoPlan {
        auto_elastic::plan(&self.view.chain, rtol)
    }

    fn event_time(&self) -> Option<f64> {
        self.view.chain.pivot().release
    }

    fn at_event(&mut self, _t: f64, y: &mut [f64]) {
        let n = self.view.chain.links();
        y[2 * n] += elastic::pivot_spring_energy(&self.view.chain, y);
        self.released = true;
    }

    fn view(&self) -> &dyn StateView {
        &self.view
    }
}

impl StateView for LinkView {
    fn observe(&self, t: f64, y: &[f64], f: &[f64], _trig: &mut Vec<(f64, f64)>) -> Observed {
        let chain = &self.chain;
        if self.floor.is_some() {
            // A floor's pivot is fixed until a release: no frame terms.
            return Observed {
                energy: elastic::energy_at_under(chain, &self.loads, t, y),
                tip_velocity: elastic::tip_velocity(chain, y),
                tip_acceleration: elastic::tip_acceleration(chain, y, f),
            };
        }
        if self.path.is_fixed() {
            return Observed {
                energy: elastic::energy_under(chain, &self.loads, y),
                tip_velocity: elastic::tip_velocity(chain, y),
                tip_acceleration: elastic::tip_acceleration(chain, y, f),
            };
        }
        let mut m = Observed {
            energy: self.energy(t, y),
            tip_velocity: elastic::tip_velocity(chain, y),
            tip_acceleration: elastic::tip_acceleration(chain, y, f),
        };
        if chain.pivot().is_driven() {
            let [_, v, a] = chain.pivot().drive(t);
            m.tip_velocity = [m.tip_velocity[0] + v[0], m.tip_velocity[1] + v[1]];
            m.tip_acceleration = [m.tip_acceleration[0] + a[0], m.tip_acceleration[1] + a[1]];
        }
        m
    }

    /// [`elastic::energy_at`] (no joint-0 spring once let go), plus the
    /// frame's terms of a driven pivot ([`elastic::frame_energy`]).
    fn energy(&self, t: f64, y: &[f64]) -> f64 {
        let e = elastic::energy_at_under(&self.chain, &self.loads, t, y);
        if self.floor.is_some() {
            return e;
        }
        if !self.chain.pivot().is_driven() {
            return e;
        }
        let [d, v0, _] = self.chain.pivot().drive(t);
        e + elastic::frame_energy(&self.chain, d, v0, y)
    }

    fn tip(&self, t: f64, y: &[f64]) -> Vec2 {
        elastic::tip(&self.chain, self.support(t, y)[0], y)
    }

    fn tip_velocity(&self, t: f64, y: &[f64]) -> Vec2 {
        let v = elastic::tip_velocity(&self.chain, y);
        if self.path.is_fixed() {
            return v;
        }
        let v0 = self.chain.pivot().drive(t)[1];
        [v[0] + v0[0], v[1] + v0[1]]
    }

    fn support(&self, t: f64, y: &[f64]) -> [Vec2; 2] {
        let n = self.chain.links();
        self.path.at(&self.chain, t, &y[..n], &y[n..2 * n])
    }

    fn joints(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        elastic::joints_at(&self.chain, t, self.support(t, y)[0], y)
    }

    fn joint_forces(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        let forces = elastic::joint_forces_at(&self.chain, t, y);
        elastic::tension_shear(&y[..self.chain.links()], &forces)
    }

    /// The pivot spring's force on rod 1 (zero once let go).
    fn support_force(&self, t: f64, y: &[f64]) -> Vec2 {
        elastic::pivot_force_at(&self.chain, t, y)
    }

    fn momentum(&self, _t: f64, y: &[f64]) -> Vec2 {
        elastic::momentum(&self.chain, y)
    }

    fn floor_forces(&self, _t: f64, y: &[f64]) -> Option<Vec<Vec2>> {
        let term = self.floor.as_ref()?;
        Some(floor::point_forces(&self.chain, term, y))
    }

    fn floor_line(&self) -> Option<(f64, f64)> {
        let (term, f) = (self.floor.as_ref()?, self.chain.floor()?);
        Some((term.height(self.path.anchor), f.angle))
    }

    fn peak_forces(&self) -> &'static [PeakForce] {
        if self.chain.floor().is_some() {
            &[PeakForce::Pivot, PeakForce::Tension, PeakForce::Floor]
        } else {
            &[PeakForce::Pivot, PeakForce::Tension]
        }
    }

    /// The links' springs: O(1) for the pivot's, one pass for the
    /// tensions and the floor (no scratch).
    fn peak_force(&self, force: PeakForce, t: f64, y: &[f64], _: &mut ForceScratch) -> PeakValue {
        match (force, &self.floor) {
            (PeakForce::Floor, Some(term)) => floor::normal_and_landed(&self.chain, term, y),
            (PeakForce::Floor, None) => [0.0, 0.0],
            (PeakForce::Pivot, _) => {
                let f = self.support_force(t, y);
                [f[0].hypot(f[1]), 0.0]
            }
            (PeakForce::Tension, _) => {
                let (tension, k) = elastic::largest_tension(&self.chain, t, y);
                [tension, k as f64]
            }
        }
    }
}

/// `[phi, w, W, x, y, vx, vy]`; a sample is the state, its time, and the
/// joints' positions and forces.
fn elastic_layout(chain: &Chain) -> Layout {
    let n = chain.links();
    let numbers = (6 * n as u64 + 2) + 4 * (n as u64 + 1);
    Layout {
        positions: Some(2 * n + 1..4 * n + 1),
        velocities: Some(4 * n + 1..6 * n + 1),
        ..Layout::angles_rates_work(n, 6 * n + 1, numbers)
    }
}
