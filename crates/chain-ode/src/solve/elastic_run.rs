//! A run of the elastic chain (`chain.axial_stiffness`): one span, or, for a
//! pivot let go at `0 < t_r < t_end` (`pivot.release`), two: held up to
//! `t_r`, then without the joint-0 spring. At the release the spring's
//! energy `K_0 |d_0|^2 / 2` leaves the chain: it is added to the work `W`
//! there, so that the balance `E + W = E(0)` holds across the cut.

use super::integrator::{Run, Span};
use super::observer::ChainObserver;
use super::{registry, Method, SolveOptions};
use crate::chain::Chain;
use crate::elastic::{self, ElasticSystem};
use crate::pivot::PivotPath;

/// Runs `method` on the elastic `chain` over `span`, the pivot on `path`.
pub(super) fn run(
    chain: &Chain,
    method: Method,
    options: &SolveOptions,
    span: &Span<'_>,
    path: &PivotPath,
) -> (Run, ChainObserver) {
    let mut obs = ChainObserver::for_run(chain, path.clone(), options);
    // `ElasticSystem::new` lets go at t = 0 already (`pivot.release = 0`).
    let mut sys = ElasticSystem::new(chain);
    let t_release = match chain.pivot().release {
        Some(tr) if tr > span.t0 && tr < span.t_end => tr,
        _ => {
            let run = registry::run(method, &mut sys, span, &mut obs);
            return (run, obs);
        }
    };
    let n = chain.links();
    let run = super::run_cut(method, &mut sys, span, &mut obs, t_release, |sys, y, _| {
        y[2 * n] += elastic::pivot_spring_energy(chain, y);
        sys.set_released(true);
    });
    (run, obs)
}
