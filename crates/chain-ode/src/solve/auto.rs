//! `auto`: a policy over the registered methods. BDF from the start past
//! the measured crossover damping rate; otherwise DOPRI5 (DOP853 at tight
//! tolerances) until its stiffness detector keeps firing with `|lambda|`
//! past the crossover's `48 gamma`, then BDF from that state.

use super::integrator::{Integrator, Settings};
use super::{registry, Method};
use crate::chain::Chain;
use crate::ode::{Observer, Outcome};
use crate::system::ChainSystem;

/// The damping rate `gamma = r / (m l^2)` (1/time) past which the O(n) BDF
/// overtakes DOPRI5 on this chain, and from which `auto` runs BDF from the
/// start.
///
/// An explicit step is held below `~3.3 / |lambda|`, and the chain has two
/// fast rates: damping, `|lambda| ~ 48 gamma`, and its fastest undamped mode,
/// `omega_max ~ 3.4 sqrt(g L) / l` (the hanging chain's top frequency; it
/// grows like n). So the crossover grows with n once `omega_max` dominates.
/// The `stiffness` study (span d = 3, t = 1, rtol 1e-6, n = 25 to 3200)
/// measured it and fits it as `27 sqrt(g/L) + 0.12 sqrt(g L) / l`: 12 at
/// n = 25 and 168 at n = 3200 in the report's units.
pub fn bdf_crossover_gamma(chain: &Chain) -> f64 {
    let (g, big_l) = (chain.gravity(), chain.length());
    27.0 * (g / big_l).sqrt() + 0.12 * (g * big_l).sqrt() / chain.rod_length()
}

/// Relative tolerance at and below which `auto`'s explicit method is DOP853
/// rather than DOPRI5 (measured on the work-precision diagrams).
pub(crate) const AUTO_DOP853_RTOL: f64 = 1e-8;

impl Method {
    /// The methods `auto` runs for this chain and tolerance: the explicit one
    /// it starts with (none when the chain is past the crossover), and BDF.
    pub fn auto_plan(chain: &Chain, rtol: f64) -> Option<Method> {
        if chain.damping_rate() >= bdf_crossover_gamma(chain) {
            None
        } else if rtol <= AUTO_DOP853_RTOL {
            Some(Method::Dop853)
        } else {
            Some(Method::Dopri5)
        }
    }
}

/// `auto`: runs [`Method::auto_plan`]'s methods through the registry.
pub(crate) struct Auto;

impl Integrator for Auto {
    fn name(&self) -> &'static str {
        "auto"
    }

    fn adaptive(&self) -> bool {
        true
    }

    fn integrate(
        &self,
        sys: &mut ChainSystem,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        settings: &Settings,
        obs: &mut dyn Observer,
    ) -> Outcome {
        let chain = sys.chain().clone();
        let Some(explicit) = Method::auto_plan(&chain, settings.rtol) else {
            return registry::run(Method::Bdf, sys, t0, y0, t_end, settings, obs);
        };
        let watch = Settings {
            stop_when_stiff: true,
            switch_lambda: 48.0 * bdf_crossover_gamma(&chain),
            ..*settings
        };
        let first = registry::run(explicit, sys, t0, y0, t_end, &watch, obs);
        let Some(t_switch) = first.stiff_at.filter(|_| first.status.is_ok()) else {
            return first;
        };
        // What is left of the step budget.
        let budget = Settings {
            max_steps: settings
                .max_steps
                .saturating_sub(first.stats.steps + first.stats.rejected_steps)
                .max(1),
            ..*settings
        };
        let mut second = registry::run(
            Method::Bdf,
            sys,
            t_switch,
            &first.y_end,
            t_end,
            &budget,
            obs,
        );
        second.stats += first.stats;
        second.segments.splice(0..0, first.segments);
        second
    }
}
