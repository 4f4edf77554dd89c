//! What a work-precision study runs: a [`Subject`] is a model with its
//! start and its run's options, so that [`precision`](crate::precision)
//! runs any [`Model`] — a scene's chain ([`Prepared`]), BEAM, or a model of
//! another crate ([`ModelSubject`]) — through one [`solve`], with one
//! reference, one ladder and one table.
//!
//! A subject says how a point's options follow from its method and
//! accuracy ([`Subject::options_for`]) and, where it has one, against what
//! its errors are measured ([`Subject::errors`]): by default the tip's
//! position at the end and the largest tip speed, against the reference run
//! ([`Reference`]); BEAM's against the test set's published solution.

use std::sync::{Mutex, PoisonError};

use chain_ode::{InvalidParameter, Method, Model, ModelKind, SolveOptions, State, Trajectory};

use fc_scene::scene::Prepared;

use crate::measure::Measures;
use crate::precision::Reference;

/// A model, its start and its options, as the precision study sees them.
pub trait Subject: Clone + Sync {
    /// The model every run integrates.
    type Model: Model;

    /// A fresh copy of the model for one run (a run's event may change it).
    fn model(&self) -> Self::Model;

    /// The state every run starts from.
    fn state(&self) -> &State;

    /// The run's options (end time, bounds, the cancel flag); the study
    /// sets the accuracy per point ([`Subject::options_for`]).
    fn options(&self) -> &SolveOptions;

    /// The same, to set the cancel flag and drop the samples.
    fn options_mut(&mut self) -> &mut SolveOptions;

    /// The length that scales the tip's error (`L`, length units).
    fn length(&self) -> f64;

    /// The options of a point: these options with the method's accuracy
    /// `param` ([`SolveOptions::at_accuracy`]: `atol = rtol / 100`) and no
    /// samples.
    fn options_for(&self, method: Method, param: f64) -> SolveOptions {
        let mut o = self.options().clone().at_accuracy(method, param);
        o.output_dt = self.measures().output_dt(o.t_end);
        o
    }

    /// What the study measures ([`Measures`]; `tip` by default).
    fn measures(&self) -> Measures {
        Measures::TIP
    }

    /// `omega_max t_end`: the largest axial frequency of its elastic links
    /// (`2 sqrt(K / m)`, `K` a joint's axial stiffness, `m` a rod's mass)
    /// times the run's end time, the number of radians an explicit method
    /// must follow (`0`: no axial modes). The reference is chosen from it
    /// ([`crate::precision::ReferencePlan`]).
    fn axial_radians(&self) -> f64 {
        0.0
    }

    /// The relative errors `(first, second)` of a finished run: by default
    /// the tip's and the largest tip speed's against `reference`
    /// ([`Reference::errors`]).
    fn errors(&self, reference: &Reference, t: &Trajectory<Self::Model>) -> (f64, f64) {
        reference.errors(t)
    }

    /// Checks `options` for `method` on this model ([`Model::validate`],
    /// which adds the model's bounds to the common ones).
    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter> {
        self.model().validate(method, options)
    }

    /// One run of `method` with `options`, tracking the peaks of the
    /// pivot's force and the tensions exactly when the study measures one
    /// of them ([`Measures::tracks_forces`]; otherwise
    /// `Solve::without_force_peaks`, so that the work counters are the
    /// integrator's: a force's search inside a step would pay DOP853's lazy
    /// dense output).
    fn solve(
        &self,
        method: Method,
        options: &SolveOptions,
    ) -> Result<Trajectory<Self::Model>, InvalidParameter> {
        let solve = chain_ode::Solve::new(self.model(), self.state(), method, options);
        if self.measures().tracks_forces() {
            solve.run()
        } else {
            solve.without_force_peaks().run()
        }
    }
}

impl Subject for Prepared {
    type Model = ModelKind;

    fn model(&self) -> ModelKind {
        ModelKind::of(&self.chain)
    }

    fn state(&self) -> &State {
        &self.state
    }

    fn options(&self) -> &SolveOptions {
        &self.options
    }

    fn options_mut(&mut self) -> &mut SolveOptions {
        &mut self.options
    }

    fn length(&self) -> f64 {
        self.chain.length()
    }

    fn axial_radians(&self) -> f64 {
        axial_radians(&self.chain, self.options.t_end)
    }
}

/// [`Subject::axial_radians`] of `chain` up to `t_end`.
pub fn axial_radians(chain: &chain_ode::Chain, t_end: f64) -> f64 {
    chain
        .joint_stiffness()
        .map_or(0.0, |k| 2.0 * (k / chain.mass()).sqrt() * t_end)
}

/// A subject with what its study measures (`--measure`): the same runs,
/// the pivot's force and the tensions tracked when it measures them, and
/// the samples the floor's reading needs.
#[derive(Clone, Debug)]
pub struct Measured<S> {
    pub subject: S,
    pub measures: Measures,
}

impl<S: Subject> Subject for Measured<S> {
    type Model = S::Model;

    fn model(&self) -> S::Model {
        self.subject.model()
    }

    fn state(&self) -> &State {
        self.subject.state()
    }

    fn options(&self) -> &SolveOptions {
        self.subject.options()
    }

    fn options_mut(&mut self) -> &mut SolveOptions {
        self.subject.options_mut()
    }

    fn length(&self) -> f64 {
        self.subject.length()
    }

    fn options_for(&self, method: Method, param: f64) -> SolveOptions {
        let mut o = self.subject.options_for(method, param);
        o.output_dt = self.measures.output_dt(o.t_end);
        o
    }

    fn measures(&self) -> Measures {
        self.measures
    }

    fn axial_radians(&self) -> f64 {
        self.subject.axial_radians()
    }

    fn errors(&self, reference: &Reference, t: &Trajectory<Self::Model>) -> (f64, f64) {
        self.subject.errors(reference, t)
    }

    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter> {
        self.subject.validate(method, options)
    }
}

/// Any model with its start and options, measured at the tip (the default
/// [`Subject::errors`]): the subject of a model that no scene names. The
/// study runs its points on several threads, each on its own copy of the
/// model, so the model need only be `Send` (one with scratch in a
/// `RefCell` qualifies): it is kept behind a lock and cloned per run.
#[derive(Debug)]
pub struct ModelSubject<M> {
    model: Mutex<M>,
    state: State,
    options: SolveOptions,
    length: f64,
}

impl<M: Model + Send> ModelSubject<M> {
    /// `model` from `state` with `options` (the study sets the accuracy),
    /// the tip's error scaled by `length`.
    pub fn new(model: M, state: State, options: SolveOptions, length: f64) -> Self {
        Self {
            model: Mutex::new(model),
            state,
            options,
            length,
        }
    }
}

impl<M: Model + Send> Clone for ModelSubject<M> {
    fn clone(&self) -> Self {
        Self::new(
            self.model(),
            self.state.clone(),
            self.options.clone(),
            self.length,
        )
    }
}

impl<M: Model + Send> Subject for ModelSubject<M> {
    type Model = M;

    fn model(&self) -> M {
        // A copy is all that is read: a poisoned lock still holds a model.
        self.model
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
    }

    fn state(&self) -> &State {
        &self.state
    }

    fn options(&self) -> &SolveOptions {
        &self.options
    }

    fn options_mut(&mut self) -> &mut SolveOptions {
        &mut self.options
    }

    fn length(&self) -> f64 {
        self.length
    }
}
