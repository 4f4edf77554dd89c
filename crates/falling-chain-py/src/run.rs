//! `falling_chain.simulate` and the `Run` it returns.

use ::fc_scene::{Error, RunSummary, Scene};
use chain_ode::kinematics::joints;
use chain_ode::Model as _;
use chain_ode::{Chain, Method, Status, Trajectory, Vec2};
use numpy::{PyArray1, PyArray2, PyArray3, PyArrayMethods};
use pyo3::exceptions::PyIndexError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{array1, array2, array3, bound, json_to_dict, points, value_error};
use crate::interrupt::run_interruptible;
use crate::scene::PyScene;

/// The scene with the keyword flags of `simulate` applied, in the CLI's
/// order (`--method`, `--dt`, `--rtol`, `--atol`, `--t-end`), then
/// `run.output_dt`.
pub fn with_flags(scene: &Scene, flags: &[(&str, Option<toml::Value>)]) -> Result<Scene, Error> {
    let mut scene = scene.clone();
    for (path, value) in flags {
        if let Some(value) = value {
            scene = scene.with_value(path, value.clone())?;
        }
    }
    Ok(scene)
}

/// A trajectory without its samples: what `Run` shows besides the arrays.
struct Head {
    chain: Chain,
    anchor: Vec2,
    method: Method,
    status: Status,
    t_reached: f64,
    samples: usize,
    /// The floor `[height at x = 0, angle]` of a run with a `[floor]`.
    floor: Option<[f64; 2]>,
}

impl Head {
    fn of(traj: &Trajectory) -> Self {
        Self {
            chain: traj.chain().clone(),
            anchor: traj.anchor,
            method: traj.method,
            status: traj.status,
            t_reached: traj.t_reached,
            samples: traj.len(),
            floor: traj.model.view().floor_line().map(|(h, a)| [h, a]),
        }
    }
}

/// The per-sample series of a trajectory, computed as `--out`'s CSV does.
struct Series {
    samples: usize,
    links: usize,
    t: Vec<f64>,
    phi: Vec<f64>,
    w: Vec<f64>,
    tip: Vec<f64>,
    tip_velocity: Vec<f64>,
    energy: Vec<f64>,
    dissipated: Vec<f64>,
    /// The work the support has done on the chain since t = 0 (zero for a
    /// fixed pivot): `F_0 · P0'` by the trapezoid rule over the samples.
    support_work: Vec<f64>,
    /// Joint forces `[tension, shear]`, `n + 1` per sample.
    forces: Vec<f64>,
    /// The joints of every sample, `n + 1` points each, kept for an elastic
    /// chain and a moving pivot only (a rigid chain's on a fixed pivot
    /// follow from its angles, as always).
    joints: Option<Vec<f64>>,
    /// The floor's force at each joint, `n + 1` points per sample, for a
    /// scene with a floor only.
    floor_forces: Option<Vec<f64>>,
    /// The support's force on rod 1, `[fx, fy]` per sample (scene axes).
    pivot_force: Vec<f64>,
    /// The floor's total force, the weight and the length landed on it, per
    /// sample, for a scene with a floor only.
    floor: Option<FloorSeries>,
}

/// A floor's time series.
struct FloorSeries {
    force: Vec<f64>,
    landed_weight: Vec<f64>,
    landed_length: Vec<f64>,
    /// What `Run.floor_reading` reads: the chain's momentum, the floor's
    /// total force and the landed length per sample, and the times.
    reading: ReadingSamples,
}

/// The samples Cayley's reading is computed from, kept as they are
/// (`chain_ode::analysis::floor_reading_of`).
#[derive(Default)]
struct ReadingSamples {
    times: Vec<f64>,
    momentum: Vec<Vec2>,
    floor_force: Vec<Vec2>,
    landed_length: Vec<f64>,
}

impl Series {
    fn of(traj: &Trajectory) -> Self {
        let (samples, n) = (traj.len(), traj.chain().links());
        let mut s = Self {
            samples,
            links: n,
            t: Vec::with_capacity(samples),
            phi: Vec::with_capacity(samples * n),
            w: Vec::with_capacity(samples * n),
            tip: Vec::with_capacity(samples * 2),
            tip_velocity: Vec::with_capacity(samples * 2),
            energy: Vec::with_capacity(samples),
            dissipated: Vec::with_capacity(samples),
            support_work: support_work(traj),
            forces: Vec::with_capacity(samples * 2 * (n + 1)),
            // The joints of a model with positions among its unknowns (the
            // elastic chain), and a moving or released pivot's, do not
            // follow from the angles and the anchor.
            joints: (traj.model.layout().positions.is_some() || !traj.chain().pivot().is_fixed())
                .then(|| Vec::with_capacity(samples * 2 * (n + 1))),
            floor_forces: traj
                .model
                .view()
                .floor_line()
                .map(|_| Vec::with_capacity(samples * 2 * (n + 1))),
            pivot_force: Vec::with_capacity(samples * 2),
            floor: traj.model.view().floor_line().map(|_| FloorSeries {
                force: Vec::with_capacity(samples * 2),
                landed_weight: Vec::with_capacity(samples),
                landed_length: Vec::with_capacity(samples),
                reading: ReadingSamples::default(),
            }),
        };
        for (k, sample) in traj.samples().enumerate() {
            s.t.push(sample.t);
            s.phi.extend_from_slice(sample.angles);
            s.w.extend_from_slice(sample.rates);
            s.tip.extend(traj.tip(k));
            s.tip_velocity.extend(traj.tip_velocity(k));
            s.energy.push(traj.energy(k));
            s.dissipated.push(sample.dissipated);
            s.forces.extend(traj.joint_forces(k).into_iter().flatten());
            if let Some(j) = s.joints.as_mut() {
                j.extend(traj.joints(k).into_iter().flatten());
            }
            if let (Some(f), Some(joints)) = (s.floor_forces.as_mut(), traj.floor_joint_forces(k)) {
                f.extend(joints.into_iter().flatten());
            }
            s.pivot_force.extend(traj.support_force(k));
            if let Some(f) = s.floor.as_mut() {
                let force = traj.floor_force(k).unwrap_or([0.0, 0.0]);
                f.reading.times.push(sample.t);
                f.reading.momentum.push(traj.momentum(k));
                f.reading.floor_force.push(force);
                f.reading
                    .landed_length
                    .push(traj.floor_landed_length(k).unwrap_or(0.0));
                f.force.extend(force);
                f.landed_weight
                    .push(traj.floor_landed_weight(k).unwrap_or(0.0));
                f.landed_length
                    .push(traj.floor_landed_length(k).unwrap_or(0.0));
            }
        }
        s
    }
}

/// The work the support has done on the chain by each sample,
/// `int F_0 · P0' dt` by the trapezoid rule over the samples (`F_0` the
/// force of the pivot on rod 1, `chain_ode::analysis::pivot_forces`; `P0'`
/// the pivot's velocity): zero for a fixed pivot, and no power once the
/// pivot is let go (`F_0 = 0`).
fn support_work(traj: &Trajectory) -> Vec<f64> {
    if traj.chain().pivot().is_fixed() {
        return vec![0.0; traj.len()];
    }
    let forces = chain_ode::analysis::pivot_forces(traj);
    let mut out = Vec::with_capacity(traj.len());
    let (mut work, mut last) = (0.0, None);
    for (k, (t, f)) in forces.iter().enumerate() {
        let v = traj.pivot_at(k)[1];
        let power = f[0] * v[0] + f[1] * v[1];
        if let Some((t0, p0)) = last {
            work += 0.5 * (power + p0) * (t - t0);
        }
        last = Some((*t, power));
        out.push(work);
    }
    out
}

/// A finished run: its summary and its samples as numpy arrays.
///
/// `summary` is the dict `falling-chain simulate --json` prints for the same
/// scene and flags. The arrays are float64 and read-only, one row per
/// recorded sample (every `run.output_dt`, and the last time reached):
/// `t` (samples,), `phi` and `w` (samples, n) (angles from the horizontal
/// and their rates), `tip` and `tip_velocity` (samples, 2), `energy` and
/// `dissipated` (samples,) (`W` of the energy balance `E + W = E(0)`: the
/// joint friction's work with a fixed pivot, the friction's work less the
/// support's with a moving one; `friction_work` and `support_work` apart). A run
/// that failed (`summary["status"]` is `diverged`, `step_size_too_small`,
/// `max_steps`, ...) holds what it computed up to `summary["t_reached"]`.
#[pyclass(module = "falling_chain", frozen)]
pub struct Run {
    /// What the arrays need besides themselves (the trajectory's own copy
    /// of the samples is dropped once the arrays hold them).
    head: Head,
    scene: Scene,
    /// The `simulate --json` line, parsed on each access (a fresh dict).
    summary: String,
    /// The same summary as a JSON value, for the viewer's page (serde_json's
    /// parser is not exact to the last bit, so it is kept, not re-parsed).
    summary_value: serde_json::Value,
    t: Py<PyArray1<f64>>,
    phi: Py<PyArray2<f64>>,
    w: Py<PyArray2<f64>>,
    tip: Py<PyArray2<f64>>,
    tip_velocity: Py<PyArray2<f64>>,
    energy: Py<PyArray1<f64>>,
    dissipated: Py<PyArray1<f64>>,
    support_work: Py<PyArray1<f64>>,
    friction_work: Py<PyArray1<f64>>,
    forces: Py<PyArray3<f64>>,
    /// An elastic chain's joints, `n + 1` points per sample (`None`: rigid).
    joints: Option<Vec<f64>>,
    /// The floor's force at each joint (`None`: no floor).
    floor_forces: Option<Py<PyArray3<f64>>>,
    pivot_force: Py<PyArray2<f64>>,
    /// The floor's total force, landed weight and landed length (`None`:
    /// no floor).
    floor_force: Option<Py<PyArray2<f64>>>,
    landed_weight: Option<Py<PyArray1<f64>>>,
    landed_length: Option<Py<PyArray1<f64>>>,
    /// Cayley's reading's samples (`None`: no floor).
    reading: Option<ReadingSamples>,
}

#[pymethods]
impl Run {
    /// Cayley's reading over windows of width `window` (time units, from
    /// one output spacing to the whole run), as a dict of arrays: `t` (the
    /// windows' centres, samples of the run), `force` (the floor's normal
    /// force averaged over the window), `landed_length` (the landed length
    /// averaged over it), `reading` (`force / (3 mu g landed_length)`, `mu
    /// = M / L`: 1 for Cayley's ideal chain) and `from_momentum` (True
    /// where `force` is the momentum balance's, exact whatever happens
    /// between the samples: the pivot let go and no air drag; otherwise the
    /// sampled force's trapezoid average). Windows whose mean landed length
    /// is zero are left out. `None` for a scene without a floor; a window
    /// out of range raises ValueError naming it (docs/model.md, "The
    /// floor's reading").
    #[pyo3(signature = (window))]
    fn floor_reading<'py>(
        &self,
        py: Python<'py>,
        window: f64,
    ) -> PyResult<Option<Bound<'py, PyDict>>> {
        let (Some(r), Some([_, angle])) = (self.reading.as_ref(), self.head.floor) else {
            return Ok(None);
        };
        let read = chain_ode::analysis::floor_reading_of(
            &self.head.chain,
            angle,
            chain_ode::analysis::FloorSamples {
                times: &r.times,
                momentum: &r.momentum,
                floor_force: &r.floor_force,
                landed_length: &r.landed_length,
            },
            window,
        )
        .map_err(pyo3::exceptions::PyValueError::new_err)?;
        let d = PyDict::new(py);
        d.set_item("t", array1(py, read.t)?)?;
        d.set_item("force", array1(py, read.force)?)?;
        d.set_item("landed_length", array1(py, read.landed_length)?)?;
        d.set_item("reading", array1(py, read.reading)?)?;
        d.set_item("from_momentum", read.from_momentum)?;
        Ok(Some(d))
    }

    /// The `simulate --json` object as a dict (a new dict on each access).
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        json_to_dict(py, &self.summary)
    }

    /// Sample times, shape (samples,).
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        bound(py, &self.t)
    }

    /// Angles phi_1..phi_n from the horizontal (rad), shape (samples, n).
    #[getter]
    fn phi<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        bound(py, &self.phi)
    }

    /// Angular rates w_1..w_n, shape (samples, n).
    #[getter]
    fn w<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        bound(py, &self.w)
    }

    /// Position of the free end, shape (samples, 2).
    #[getter]
    fn tip<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        bound(py, &self.tip)
    }

    /// Velocity of the free end (exact, from phi and w), shape (samples, 2).
    #[getter]
    fn tip_velocity<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        bound(py, &self.tip_velocity)
    }

    /// Energy T + V (+ the bending and the elastic links' energy), shape (samples,).
    #[getter]
    fn energy<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        bound(py, &self.energy)
    }

    /// Joint forces at every sample, shape (samples, n + 1, 2): joint 0 is
    /// the pivot, joint n the free tip (zero); each `[tension, shear]` in
    /// the frame of the rod after the joint (tension > 0 pulls that rod
    /// back toward the pivot; shear along the rod's normal, its direction
    /// turned +90 degrees). Force units.
    #[getter]
    fn forces<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        bound(py, &self.forces)
    }

    /// The floor's force at each joint at every sample, shape
    /// (samples, n + 1, 2), `[fx, fy]` in the scene's axes (force units,
    /// `fy > 0` pushing up): joint j gathers the contacts at rod j's start
    /// and rod j − 1's end; summed over the joints, what a scale under the
    /// chain reads (the columns `floor_x_k`, `floor_y_k` of
    /// `simulate --forces`). `None` for a scene without a floor.
    #[getter]
    fn floor_forces<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray3<f64>>> {
        self.floor_forces.as_ref().map(|f| bound(py, f))
    }

    /// The floor's total force on the chain at every sample, shape
    /// (samples, 2), `[fx, fy]` in the scene's axes (force units, `fy > 0`
    /// pushing up): what a scale under the chain reads, `floor_forces`
    /// summed over the joints (the columns `floor_x`, `floor_y` of
    /// `simulate --out`). `None` for a scene without a floor. Read at the
    /// samples: on a stiff floor the contacts are impulses far shorter than
    /// `run.output_dt`, so a sampled force is no peak and no mean.
    #[getter]
    fn floor_force<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray2<f64>>> {
        self.floor_force.as_ref().map(|f| bound(py, f))
    }

    /// The weight of what the floor pushes at every sample, shape
    /// (samples,): `g m_i / 2` for each contact point with a force (each
    /// end of rod i stands for half of it; the tip's also for the tip
    /// mass), the column `landed_weight` of `simulate --out`. `None` for a
    /// scene without a floor.
    #[getter]
    fn landed_weight<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.landed_weight.as_ref().map(|f| bound(py, f))
    }

    /// The length of chain that has landed at every sample, shape
    /// (samples,): `l_i / 2` for each end of rod i at most one rod length
    /// above the floor line (or in it), so what lies on the floor or has
    /// piled up on it, to about a rod; read off the rods' ends, not the
    /// contact forces (landed rods rest far below the tolerance and tumble
    /// above a plastic floor, pushed by nothing at most samples). On
    /// Cayley's chain it follows the free fall's `g t^2 / 2` to two rods
    /// up to half the chain landed; rods thrown higher than a rod are not
    /// counted. `None` for a scene without a floor.
    #[getter]
    fn landed_length<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.landed_length.as_ref().map(|f| bound(py, f))
    }

    /// The support's force on the chain's first rod at every sample, shape
    /// (samples, 2), `[fx, fy]` in the scene's axes (force units; a chain
    /// hanging at rest gives `[0, M g]`, the support holding it up): the
    /// rigid chain's from its dynamics, the elastic chain's from its pivot
    /// spring; zero once the pivot is let go. In the rod's frame it is
    /// `forces[:, 0, :]` (tension and shear at joint 0).
    #[getter]
    fn pivot_force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        bound(py, &self.pivot_force)
    }

    /// `W` of the energy balance `E + W = E(0)` since t = 0, shape
    /// (samples,) (the summary's `dissipated`, integrated with the run):
    /// with a fixed pivot, the work dissipated by joint friction (and, for
    /// elastic links, their dashpots); with a moving pivot, that work less
    /// the support's, `friction_work - support_work` (so it may be
    /// negative: the hand that moves the pivot feeds energy in).
    #[getter]
    fn dissipated<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        bound(py, &self.dissipated)
    }

    /// The work the support has done on the chain since t = 0, shape
    /// (samples,): `int F_0 · P0' dt`, `F_0` the pivot's force on rod 1 and
    /// `P0'` its velocity, by the trapezoid rule over the samples (as
    /// accurate as `run.output_dt` resolves the pivot's motion). Zero for a
    /// fixed pivot and once the pivot is let go.
    #[getter]
    fn support_work<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        bound(py, &self.support_work)
    }

    /// The work dissipated by joint friction alone since t = 0 (and, for
    /// elastic links, their dashpots; for elastic links let go, the pivot
    /// spring's energy that leaves at the release), shape (samples,):
    /// `dissipated + support_work`. With a fixed pivot it is `dissipated`,
    /// exactly.
    #[getter]
    fn friction_work<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        bound(py, &self.friction_work)
    }

    /// The number of rods n.
    #[getter]
    fn links(&self) -> usize {
        self.head.chain.links()
    }

    /// `ok`, or how the run failed (the same as `summary["status"]`).
    #[getter]
    fn status(&self) -> &'static str {
        self.head.status.as_str()
    }

    /// The scene that ran (with the keyword flags of `simulate` applied).
    #[getter]
    fn scene(&self) -> PyScene {
        PyScene::new(self.scene.clone())
    }

    /// The joints r_0 = P0, r_1, ..., r_n (the tip) at sample `k`, shape
    /// (n + 1, 2). A negative `k` counts from the end, as in Python.
    fn joints(&self, py: Python<'_>, k: isize) -> PyResult<Py<PyArray2<f64>>> {
        let len = self.head.samples;
        let index = if k < 0 {
            k.checked_add_unsigned(len)
        } else {
            Some(k)
        };
        let Some(row) = index
            .and_then(|i| usize::try_from(i).ok())
            .filter(|&i| i < len)
        else {
            return Err(PyIndexError::new_err(format!(
                "sample {k} out of range (the run has {len} samples)"
            )));
        };
        let n = self.head.chain.links();
        if let Some(all) = &self.joints {
            let rows = all.get(row * 2 * (n + 1)..(row + 1) * 2 * (n + 1));
            let rows =
                rows.ok_or_else(|| PyIndexError::new_err(format!("sample {k}: no joints stored")))?;
            return array2(py, rows.to_vec(), n + 1, 2);
        }
        let phi = self.phi.bind(py).readonly();
        let angles = phi
            .as_slice()
            .ok()
            .and_then(|all| all.get(row * n..(row + 1) * n))
            .ok_or_else(|| {
                PyIndexError::new_err(format!("sample {k}: the angles array is not {len} x {n}"))
            })?;
        points(py, &joints(&self.head.chain, self.head.anchor, angles))
    }

    fn __len__(&self) -> usize {
        self.head.samples
    }

    /// Each rod's length l_1..l_n (the scene's length unit), pivot to tip,
    /// shape (n,): `chain.length / n` each for equal rods, else as the
    /// profile (`chain.taper`, `chain.rod_masses`, `chain.rod_lengths`)
    /// shares the length; they sum to `chain.length`.
    #[getter]
    fn rod_lengths<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let chain = &self.head.chain;
        let (n, l) = (chain.links(), chain.rod_length());
        let v = match chain.rods() {
            Some(r) => r.length.iter().map(|lam| lam * l).collect(),
            None => vec![l; n],
        };
        array1(py, v).map(|a| a.into_bound(py))
    }

    /// Each rod's mass m_1..m_n (the scene's mass unit), pivot to tip,
    /// shape (n,): `chain.mass` each for equal rods, else as the profile
    /// shares the chain's mass `n chain.mass`.
    #[getter]
    fn rod_masses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let chain = &self.head.chain;
        let (n, m) = (chain.links(), chain.mass());
        let v = match chain.rods() {
            Some(r) => r.mass.iter().map(|mu| mu * m).collect(),
            None => vec![m; n],
        };
        array1(py, v).map(|a| a.into_bound(py))
    }

    /// The run as `falling-chain view`'s page, in an `<iframe srcdoc>`:
    /// what Jupyter shows for a `Run`, its data within the page's cap
    /// (`DATA_BUDGET_BYTES`, 1.8 MB). A chain the viewer does not draw
    /// (more rods than `view` takes: 10^4, 5000 of unequal rods) shows as a
    /// short text instead, saying why.
    fn _repr_html_(&self, py: Python<'_>) -> PyResult<String> {
        use ::fc_viewer as viewer;
        let degraded = |why: String| {
            format!(
                "<pre>{}</pre><p>Not shown as a page: {}.</p>",
                viewer::html_escape(&self.__repr__()),
                viewer::html_escape(&why)
            )
        };
        if let Err(e) = viewer::check_chain("links", self.chain()) {
            return Ok(degraded(e.to_string()));
        }
        let run = self.view_run(py, viewer::DATA_BUDGET_BYTES)?;
        let title = run.label.clone();
        match viewer::fitted_page("run", &title, &mut [run]) {
            Ok(page) => Ok(viewer::iframe(&page)),
            Err(e) => Ok(degraded(e.to_string())),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "Run(scene={:?}, method={:?}, links={}, status={:?}, t_reached={}, samples={})",
            self.scene.name(),
            self.head.method.as_str(),
            self.head.chain.links(),
            self.head.status.as_str(),
            self.head.t_reached,
            self.head.samples
        )
    }
}

impl Run {
    /// The chain that ran.
    pub(crate) fn chain(&self) -> &Chain {
        &self.head.chain
    }

    /// The run as the viewer's page holds it, thinned to `budget` bytes
    /// (`fc_viewer`), from the arrays this run holds.
    pub(crate) fn view_run(&self, py: Python<'_>, budget: usize) -> PyResult<::fc_viewer::ViewRun> {
        use ::fc_viewer::{fixed_bytes, keeps, stride_for, RodProfile, ViewRun};
        let (samples, n) = (self.head.samples, self.head.chain.links());
        let profile = RodProfile::of(&self.head.chain);
        let budget = budget.saturating_sub(fixed_bytes(n, profile.is_some()));
        let broken = |what: &str| {
            PyIndexError::new_err(format!("the run's {what} array is not C-contiguous"))
        };
        let t = self.t.bind(py).readonly();
        let phi = self.phi.bind(py).readonly();
        let v = self.tip_velocity.bind(py).readonly();
        let e = self.energy.bind(py).readonly();
        let d = self.dissipated.bind(py).readonly();
        let (t, phi, v, e, d) = (
            t.as_slice().map_err(|_| broken("t"))?,
            phi.as_slice().map_err(|_| broken("phi"))?,
            v.as_slice().map_err(|_| broken("tip_velocity"))?,
            e.as_slice().map_err(|_| broken("energy"))?,
            d.as_slice().map_err(|_| broken("dissipated"))?,
        );
        if [t.len(), e.len(), d.len(), phi.len() / n.max(1), v.len() / 2] != [samples; 5] {
            return Err(PyIndexError::new_err(
                "the run's arrays disagree on the sample count",
            ));
        }
        let summary = self.summary_value.clone();
        let stride = stride_for(samples, n, 0, budget);
        let mut run = ViewRun {
            label: self.scene.name().to_string(),
            status: self.head.status.as_str().to_string(),
            t_failed: summary["t_failed"].as_f64(),
            summary,
            links: n,
            rod: self.head.chain.length() / n as f64,
            anchor: self.head.anchor,
            samples,
            stride,
            t: Vec::new(),
            speed: Vec::new(),
            energy: Vec::new(),
            dissipated: Vec::new(),
            phi: Vec::new(),
            forces: None,
            // A moving or released pivot: its place in every kept sample,
            // the first of the joints kept for it.
            pivot: (!self.head.chain.pivot().is_fixed()).then(Vec::new),
            // Unequal rods: their lengths and densities.
            profile,
            source: None,
            floor: self.head.floor,
        };
        for k in (0..samples).filter(|&k| keeps(k, samples, stride)) {
            if let (Some(p), Some(all)) = (run.pivot.as_mut(), &self.joints) {
                let m = 2 * (n + 1);
                p.extend(all.get(k * m..k * m + 2).unwrap_or(&[0.0, 0.0]));
            }
            run.t.push(t[k]);
            run.speed.push(v[2 * k].hypot(v[2 * k + 1]));
            run.energy.push(e[k]);
            run.dissipated.push(d[k]);
            run.phi.extend_from_slice(&phi[k * n..(k + 1) * n]);
        }
        Ok(run)
    }
}

/// Runs `scene` and returns its `Run`; the same as
/// `falling-chain simulate SCENE [--method M] [--dt S] [--rtol R] [--atol A]
/// [--t-end T] --json --out FILE.csv`, without files.
///
/// The keywords override the scene's `run.method`, `run.dt`, `run.rtol`,
/// `run.atol`, `run.t_end` and `run.output_dt` (the spacing of the samples).
/// Bad input raises ValueError with the CLI's one-line message naming the
/// field. A run that fails does not raise: its `summary["status"]` says how
/// it failed. The run releases the GIL, so Python threads run in parallel,
/// and Ctrl-C stops it within a fraction of a second: `simulate` then raises
/// KeyboardInterrupt (and returns no run).
#[pyfunction]
#[pyo3(signature = (scene, *, method=None, dt=None, rtol=None, atol=None, t_end=None, output_dt=None))]
#[allow(clippy::too_many_arguments)]
pub fn simulate(
    py: Python<'_>,
    scene: &Bound<'_, PyScene>,
    method: Option<String>,
    dt: Option<f64>,
    rtol: Option<f64>,
    atol: Option<f64>,
    t_end: Option<f64>,
    output_dt: Option<f64>,
) -> PyResult<Run> {
    let float = |x: Option<f64>| x.map(toml::Value::Float);
    let scene = with_flags(
        &scene.get().inner,
        &[
            ("run.method", method.map(toml::Value::String)),
            ("run.dt", float(dt)),
            ("run.rtol", float(rtol)),
            ("run.atol", float(atol)),
            ("run.t_end", float(t_end)),
            ("run.output_dt", float(output_dt)),
        ],
    )
    .map_err(value_error)?;
    let mut prepared = scene.prepare().map_err(value_error)?;
    let (head, series, (json, summary_value)) =
        run_interruptible(py, |cancel| -> Result<_, Error> {
            prepared.options.cancel = Some(cancel.clone());
            let traj = prepared.solve()?;
            let series = Series::of(&traj);
            let summary = RunSummary::from_trajectory(scene.name(), &traj);
            let value = serde_json::to_value(&summary).unwrap_or(serde_json::Value::Null);
            Ok((Head::of(&traj), series, (summary.to_json(), value)))
        })?
        .map_err(value_error)?;
    let (s, n) = (series.samples, series.links);
    let mut floor = series.floor;
    Ok(Run {
        summary: json,
        summary_value,
        t: array1(py, series.t)?,
        phi: array2(py, series.phi, s, n)?,
        w: array2(py, series.w, s, n)?,
        tip: array2(py, series.tip, s, 2)?,
        tip_velocity: array2(py, series.tip_velocity, s, 2)?,
        energy: array1(py, series.energy)?,
        friction_work: array1(
            py,
            series
                .dissipated
                .iter()
                .zip(&series.support_work)
                .map(|(w, s)| w + s)
                .collect(),
        )?,
        dissipated: array1(py, series.dissipated)?,
        support_work: array1(py, series.support_work)?,
        forces: array3(py, series.forces, (s, n + 1, 2))?,
        joints: series.joints,
        floor_forces: series
            .floor_forces
            .map(|f| array3(py, f, (s, n + 1, 2)))
            .transpose()?,
        pivot_force: array2(py, series.pivot_force, s, 2)?,
        floor_force: floor
            .as_mut()
            .map(|f| array2(py, std::mem::take(&mut f.force), s, 2))
            .transpose()?,
        landed_weight: floor
            .as_mut()
            .map(|f| array1(py, std::mem::take(&mut f.landed_weight)))
            .transpose()?,
        reading: floor.as_mut().map(|f| std::mem::take(&mut f.reading)),
        landed_length: floor.map(|f| array1(py, f.landed_length)).transpose()?,
        head,
        scene,
    })
}
