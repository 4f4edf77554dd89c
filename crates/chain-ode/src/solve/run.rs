//! The pieces of one run: its observers (the recorder, the tally, the
//! caller's watches) as one [`Observer`], the model's problem with its
//! plan for `auto`, a segment, a run cut at the model's event, and the
//! finished [`Trajectory`] with its status.

use std::time::Instant;

use fc_methods::registry;
use fc_methods::{
    AutoPlan, BandedDae, Method, Observer, OdeSystem, Problem, Run, Span, Status, StepView,
};

use super::recorder::Recorder;
use super::tally::Tally;
use super::{SolveOptions, Summary, Trajectory, Watch};
use crate::kinematics::Vec2;
use crate::model::Model;

/// A run's observers: the recorder, the summary's tally, the caller's.
pub(super) struct Parts<'w, 'a, M> {
    pub(super) rec: Recorder,
    pub(super) tally: Tally,
    pub(super) watches: &'w mut Vec<&'a mut dyn Watch<M>>,
}

/// [`Parts`] with the model they ask, as one [`Observer`] for one segment.
struct Observers<'p, 'w, 'a, M> {
    model: &'p M,
    parts: &'p mut Parts<'w, 'a, M>,
}

impl<M: Model> Observer for Observers<'_, '_, '_, M> {
    fn start(&mut self, t0: f64, y0: &[f64], f0: &[f64]) {
        let p = &mut *self.parts;
        p.tally.start(self.model, &mut p.rec, t0, y0, f0);
        p.rec.start(t0, y0);
        for w in p.watches.iter_mut() {
            w.start(self.model, t0, y0);
        }
    }

    fn step(&mut self, step: &StepView<'_>) {
        let p = &mut *self.parts;
        p.tally.step(self.model, &mut p.rec, step);
        p.rec.step(step);
        for w in p.watches.iter_mut() {
            w.step(self.model, step);
        }
    }

    fn stop(&self) -> bool {
        self.parts.rec.cancelled() || self.parts.watches.iter().any(|w| w.stop())
    }
}

/// The model's problem with the model's plan for `auto`: what the
/// integrators see.
struct Planned<'m> {
    inner: Box<dyn Problem + 'm>,
    plan: AutoPlan,
    /// The layout's angles and positions ([`Problem::configuration`]).
    configuration: Vec<std::ops::Range<usize>>,
}

impl OdeSystem for Planned<'_> {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.inner.rhs(t, y, dy)
    }
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        self.inner.jvp(t, y, v, jv)
    }
}

impl Problem for Planned<'_> {
    fn banded_dae(&self, t0: f64, y0: &[f64]) -> Option<BandedDae> {
        self.inner.banded_dae(t0, y0)
    }
    fn auto_plan(&self) -> Option<AutoPlan> {
        Some(self.plan)
    }
    fn configuration(&self) -> Vec<std::ops::Range<usize>> {
        self.configuration.clone()
    }
    fn measured(&self) -> Option<Box<dyn fc_methods::Measured>> {
        self.inner.measured()
    }
    fn nonsmooth(&mut self) -> Option<&mut dyn fc_methods::Nonsmooth> {
        self.inner.nonsmooth()
    }
}

/// The unknowns `gen-alpha` measures its local error on
/// ([`Problem::configuration`]): the configuration alone (the angles, and
/// the elastic chain's positions) where the model oscillates stiffly and
/// the step damps those modes unresolved (elastic links, bending springs,
/// BEAM), so that their rates do not hold the step; every unknown (empty)
/// on a rigid chain without bending springs, whose modes the step
/// resolves: measured on the angles alone, the rates' errors went
/// unchecked and its energy drifted (docs/model.md, "The
/// generalized-alpha method").
fn error_configuration<M: Model>(
    model: &M,
    layout: crate::model::Layout,
) -> Vec<std::ops::Range<usize>> {
    if model
        .chain()
        .is_some_and(|c| !c.is_elastic() && c.bending_stiffness() == 0.0)
    {
        return Vec::new();
    }
    std::iter::once(layout.angles)
        .chain(layout.positions)
        .filter(|r| !r.is_empty())
        .collect()
}

/// One segment of a run: `method` on the model's problem over `span`.
pub(super) fn segment<M: Model>(
    model: &M,
    method: Method,
    span: &Span<'_>,
    parts: &mut Parts<'_, '_, M>,
) -> Run {
    let layout = model.layout();
    let mut problem = Planned {
        inner: model.problem(),
        plan: super::auto_elastic::within_reach(
            model.auto_plan(span.settings.rtol),
            span.settings.rtol,
            span.settings.atol,
        ),
        configuration: error_configuration(model, layout),
    };
    let mut obs = Observers { model, parts };
    registry::run_with(
        model.integrator(method),
        method,
        &mut problem,
        span,
        &mut obs,
    )
}

/// Runs `method` over `span` in two pieces cut at the model's event
/// `t_cut` (inside the span), from one set of observers (as `auto`'s
/// handover): the first piece up to `t_cut`, then [`Model::at_event`] with
/// the state reached there, then the rest, with the steps left of the
/// budget. The two pieces' work adds up. A first piece that fails or is
/// stopped ends the whole run there.
pub(super) fn run_cut<M: Model>(
    model: &mut M,
    method: Method,
    span: &Span<'_>,
    t_cut: f64,
    parts: &mut Parts<'_, '_, M>,
) -> Run {
    let held = Span {
        t_end: t_cut,
        ..*span
    };
    let first = segment(model, method, &held, parts);
    if !first.outcome.status.is_ok() || first.outcome.t_reached < t_cut {
        return first;
    }
    let mut y = first.outcome.y_end.clone();
    model.at_event(t_cut, &mut y);
    let done = first.outcome.stats;
    let settings = span.settings.after(&done);
    let rest = Span {
        t0: t_cut,
        y0: &y,
        t_end: span.t_end,
        settings: &settings,
    };
    let mut second = segment(model, method, &rest, parts);
    second.outcome.stats += done;
    second.segments.splice(0..0, first.segments);
    second
}

/// The trajectory of a finished run of `method` on `model`: its summary
/// from the tally (finished here) and the final state, and its status: a
/// run that ended `ok` becomes `diverged` if its summary is not finite and
/// `inaccurate` if its energy balance error exceeds the model's energy
/// scale (or, driven, the tally's limit). `clock` started before the run.
pub(super) fn trajectory<M: Model>(
    model: M,
    anchor: Vec2,
    method: Method,
    options: &SolveOptions,
    run: Run,
    (mut rec, mut tally): (Recorder, Tally),
    clock: Instant,
) -> Trajectory<M> {
    let Run { outcome, segments } = run;
    let wall_seconds = clock.elapsed().as_secs_f64();
    tally.finish(&model, &mut rec, outcome.t_reached, &outcome.y_end);
    rec.finish(outcome.t_reached, &outcome.y_end);
    let y = &outcome.y_end;
    let summary = Summary {
        energy_start: tally.energy_start,
        energy_end: tally.energy_end,
        dissipated: tally.work_of(y),
        energy_balance_error: tally.energy_balance_error,
        max_energy_rise: tally.max_energy_rise,
        tip_end: model.view().tip(outcome.t_reached, y),
        tip_velocity_end: model.view().tip_velocity(outcome.t_reached, y),
        tip_speed_max: tally.tip_speed.value,
        t_tip_speed_max: tally.tip_speed.t,
        pivot_force_max: tally
            .peaks()
            .iter()
            .find(|p| p.force == crate::model::PeakForce::Pivot)
            .map(|p| (p.value, p.t)),
        peaks: tally.peaks(),
        forces_resolved: super::forces::resolved(
            model.chain(),
            method,
            &segments.iter().map(|g| g.method).collect::<Vec<_>>(),
            options,
            tally.h_max,
        ) && super::forces::floor_resolved(&tally.peaks()),
        wall_seconds,
    };
    // A non-finite value in the summary (an energy that overflowed, a NaN
    // from the observer) is a run that went wrong, even when every state
    // stayed finite: it must not pass as `ok`.
    // A finite run whose energy balance error exceeds the model's energy
    // scale is not a solution of the model (a step far too large, a
    // tolerance far too loose): it must not pass as `ok` either; with a
    // driven pivot, nor one whose error is a percent of the work done
    // (`Tally::balance_limit`).
    let (status, t_failed) = if outcome.status.is_ok() && !summary.all_finite() {
        let t = rec.t_nonfinite.unwrap_or(outcome.t_reached);
        (Status::Diverged, Some(t))
    } else if outcome.status.is_ok()
        && summary.energy_balance_error > model.energy_scale().min(tally.balance_limit())
    {
        let t = tally.t_inaccurate.unwrap_or(outcome.t_reached);
        (Status::Inaccurate, Some(t))
    } else {
        (outcome.status, outcome.t_failed)
    };
    Trajectory {
        model,
        anchor,
        method,
        status,
        t_end: options.t_end,
        t_reached: outcome.t_reached,
        t_failed,
        stats: outcome.stats,
        segments,
        summary,
        times: std::mem::take(&mut rec.times),
        states: std::mem::take(&mut rec.states),
        final_state: outcome.y_end,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::Chain;
    use crate::model::ModelKind;
    use crate::state::Start;
    use crate::state::State;
    use crate::system::ChainSystem;
    use fc_methods::all_finite;

    /// Asks every method to stop once it has seen `k` accepted steps.
    struct StopAfter {
        k: u64,
        steps: u64,
        t_last: f64,
    }

    impl Observer for StopAfter {
        fn start(&mut self, t0: f64, _: &[f64], _: &[f64]) {
            self.t_last = t0;
        }
        fn step(&mut self, s: &StepView<'_>) {
            self.steps += 1;
            self.t_last = s.t1;
        }
        fn stop(&self) -> bool {
            self.steps >= self.k
        }
    }

    /// Eight rods of the report's chain hanging on span d = 3: the chain,
    /// the start and its packed state.
    fn eight_rods_on_span_3() -> (Chain, State, Vec<f64>) {
        let chain = Chain::report(8, 5e-4).unwrap();
        let start = Start::Catenary {
            p0: [0.0, 0.0],
            p1: [3.0, 0.0],
        }
        .state(&chain)
        .unwrap();
        let y0 = ChainSystem::pack(&start.angles, &start.rates, 0.0);
        (chain, start, y0)
    }

    /// A run cut in two (a pivot let go mid-run) is the two pieces run
    /// one after the other: the first held, the second let go from the
    /// state the first reached, with the same end state and the work of
    /// both counted, for an explicit and an implicit method.
    #[test]
    fn a_run_cut_in_two_is_its_two_pieces_with_both_pieces_work() {
        let (chain, start, y0) = eight_rods_on_span_3();
        let mut params = chain.params().clone();
        params.pivot.release = Some(1.0);
        let chain = Chain::new(params).unwrap();
        let options = SolveOptions {
            t_end: 2.0,
            ..Default::default()
        };
        let settings = options.settings();
        let span = Span {
            t0: 0.0,
            y0: &y0,
            t_end: 2.0,
            settings: &settings,
        };
        let mut watches = Vec::new();
        for method in [Method::Dopri5, Method::Bdf] {
            let mut model = ModelKind::of(&chain);
            model.initial_state(&start).unwrap();
            let mut parts = Parts {
                rec: Recorder::new(y0.len(), 2.0, None, None),
                tally: Tally::new(&model, None),
                watches: &mut watches,
            };
            let held = Span { t_end: 1.0, ..span };
            let first = segment(&model, method, &held, &mut parts).outcome;
            let mut y1 = first.y_end.clone();
            model.at_event(1.0, &mut y1);
            let after = settings.after(&first.stats);
            let rest = Span {
                t0: 1.0,
                y0: &y1,
                t_end: 2.0,
                settings: &after,
            };
            let second = segment(&model, method, &rest, &mut parts).outcome;

            let mut model = ModelKind::of(&chain);
            model.initial_state(&start).unwrap();
            let mut parts = Parts {
                rec: Recorder::new(y0.len(), 2.0, None, None),
                tally: Tally::new(&model, None),
                watches: &mut watches,
            };
            let cut = run_cut(&mut model, method, &span, 1.0, &mut parts).outcome;
            assert_eq!(cut.status, Status::Ok, "{method}");
            assert_eq!(cut.y_end, second.y_end, "{method}");
            let (a, b, c) = (first.stats, second.stats, cut.stats);
            assert!(a.steps > 0 && b.steps > 0, "{method}");
            assert_eq!(c.steps, a.steps + b.steps, "{method}");
            assert_eq!(
                c.rejected_steps,
                a.rejected_steps + b.rejected_steps,
                "{method}"
            );
            assert_eq!(c.rhs_evals, a.rhs_evals + b.rhs_evals, "{method}");
            assert_eq!(
                c.lu_factorizations,
                a.lu_factorizations + b.lu_factorizations,
                "{method}"
            );
        }
    }

    #[test]
    fn every_method_stops_at_the_step_its_observer_asks() {
        let (chain, _, y0) = eight_rods_on_span_3();
        let settings = SolveOptions {
            t_end: 4.0,
            ..Default::default()
        }
        .settings();
        // moreau-jean runs a chain on a constraint floor (its own test:
        // tests/physics/contact.rs); the plain chain is not one.
        for method in Method::ALL.into_iter().filter(|m| !m.is_nonsmooth()) {
            for k in [0, 1, 7] {
                let mut sys = ChainSystem::new(&chain);
                let mut obs = StopAfter {
                    k,
                    steps: 0,
                    t_last: f64::NAN,
                };
                let span = Span {
                    t0: 0.0,
                    y0: &y0,
                    t_end: 4.0,
                    settings: &settings,
                };
                let out = registry::run(method, &mut sys, &span, &mut obs).outcome;
                assert_eq!(out.status, Status::Interrupted, "{method}, k = {k}");
                assert_eq!(out.stats.steps, k, "{method}, k = {k}");
                assert_eq!(obs.steps, k, "{method}, k = {k}");
                assert_eq!(
                    out.t_reached, obs.t_last,
                    "{method}: the last accepted step"
                );
                assert!(out.t_reached < 4.0 && all_finite(&out.y_end), "{method}");
                assert_eq!(out.t_failed, Some(out.t_reached));
            }
        }
    }
}
