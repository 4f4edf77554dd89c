//! The methods' public handle, [`Method`] (its name, kind and accuracy
//! parameter come from its integrator in the registry), and the
//! [`Segment`] of a run that one method covered.

use std::fmt;
use std::str::FromStr;

use super::integrator::{Accuracy, Integrator};
use super::registry;
use crate::error::InvalidParameter;

/// An integration method. The variant is the public handle; its name and
/// kind come from its integrator in the registry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Method {
    /// Classical fixed-step Runge–Kutta 4 (`dt`).
    Rk4,
    /// Adaptive Dormand–Prince 5(4) with dense output (`rtol`, `atol`).
    Dopri5,
    /// Adaptive Dormand–Prince 8(5,3) with 7th-order dense output, for tight
    /// tolerances (`rtol`, `atol`).
    Dop853,
    /// Implicit variable-order BDF from diffsol on the banded DAE, sparse LU:
    /// O(n) per step (`rtol`, `atol`).
    Bdf,
    /// diffsol's BDF on the explicit form with a dense Jacobian and dense LU:
    /// O(n^3) per factorisation, kept as the reference for `bdf` (`rtol`, `atol`).
    BdfDense,
    /// The problem's plan ([`crate::AutoPlan`]): BDF from the start, or an
    /// explicit method (DOPRI5, DOP853 at tight tolerances) handing over to
    /// BDF when its stiffness detector fires past the plan's threshold. A
    /// chain's plan (chain-ode's): BDF past the measured crossover damping
    /// rate, else the explicit method to the end (rigid links, lightly
    /// damped elastic ones) or to the first stiffness detection (elastic
    /// links whose joints are damped). A problem without a plan
    /// ([`crate::AutoPlan::generic`]: BEAM, a model from outside) runs DOP853
    /// to the end.
    Auto,
    /// The generalized-alpha method (Chung & Hulbert) in first-order form
    /// on the banded DAE, adaptive, O(n) per step: second order, and
    /// damping the modes its step does not resolve by `run.rho_inf` per
    /// step instead of following them (`rtol`, `atol`).
    GenAlpha,
    /// Moreau–Jean time stepping (`dt`): a mechanical problem with
    /// joints, contacts and friction as constraints, its impacts stepped
    /// over by impulses at a fixed step far longer than any contact time;
    /// it runs only a problem that states itself as
    /// [`Nonsmooth`](crate::Nonsmooth) (chain-ode's chain on a
    /// `floor.law = "constraint"` floor).
    MoreauJean,
}

impl Method {
    /// Every method, in the order figures list them (the registry's).
    pub const ALL: [Method; registry::REGISTRY.len()] = registry::methods();

    /// The name used on the command line, in scenes and in output.
    pub fn as_str(self) -> &'static str {
        registry::integrator(self).name
    }

    /// True if the method adapts its step to `rtol`/`atol`.
    pub fn adaptive(self) -> bool {
        registry::integrator(self).adaptive
    }

    /// True if the method runs only problems that state themselves as
    /// mechanical systems with constraints ([`crate::Problem::nonsmooth`]).
    pub fn is_nonsmooth(self) -> bool {
        registry::integrator(self).nonsmooth
    }

    /// The parameter that sets the method's accuracy.
    pub fn accuracy(self) -> Accuracy {
        registry::integrator(self).accuracy()
    }

    /// The name of that parameter: `"dt"` or `"rtol"`.
    pub fn accuracy_name(self) -> &'static str {
        self.accuracy().name()
    }

    /// What runs the method: its integrator in the registry.
    pub fn integrator(self) -> &'static Integrator {
        registry::integrator(self)
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for Method {
    type Err = InvalidParameter;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        registry::named(s).ok_or_else(|| InvalidParameter {
            field: "run.method",
            accepted: registry::accepted_names().into(),
            got: s.to_string(),
        })
    }
}

/// The time span over which one method ran (several for `auto`).
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    pub method: Method,
    pub t_start: f64,
    pub t_end: f64,
}
