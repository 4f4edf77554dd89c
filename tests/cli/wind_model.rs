//! A model from outside the crates, as ARCHITECTURE.md's "How to add a
//! model" has it: the rigid chain in a uniform horizontal wind, a constant
//! force `m a` along +x on every rod (per unit mass `a`, like gravity).
//!
//! The wind and gravity add to one uniform field `(a, -g)` of strength
//! `G = hypot(g, a)`, tilted from the vertical by `theta = atan2(a, g)`. In
//! angles turned by `-theta` (`phi' = phi - theta`) it is the windless chain
//! under gravity `G`: the problem is the crate's `ChainSystem` (and its
//! banded DAE, for `bdf`) of that chain, read at the turned angles; the
//! state keeps the physical angles. Its potential energy is
//! `sum m (g y - a x)` (`= G` times the height along the field), so `E + W`
//! is conserved as for the chain.
//!
//! The tests: a single rod swings about the tilted vertical with the small-
//! oscillation period `2 pi sqrt(2 L / (3 G))` (a model that drops or
//! misdirects the wind misses it by 12% here); a chain hung along the field
//! stays at rest; every method runs it and agrees with a tight reference.

use std::cell::RefCell;

use chain_ode::{
    solve, BandedDae, Chain, ChainParams, ChainSystem, InvalidParameter, Layout, Method, Model,
    Observed, OdeSystem, Problem, RigidModel, SemiExplicitDae, SolveOptions, State, StateView,
    Status, Vec2,
};

/// The chain in wind: the windless chain under `G`, turned by `theta`.
#[derive(Clone, Debug, PartialEq)]
pub struct WindModel {
    /// The chain as given (gravity `g`).
    chain: Chain,
    /// The same chain under `G`, in the turned frame.
    turned: RigidModel,
    theta: f64,
    /// Scratch for the turned state (the model is read through `&self`).
    buf: RefCell<Vec<f64>>,
}

impl WindModel {
    /// `chain` (with a fixed pivot) in a wind of `a` per unit mass along +x.
    pub fn new(chain: &Chain, a: f64) -> Result<Self, InvalidParameter> {
        let g = chain.gravity();
        let turned = Chain::new(ChainParams {
            gravity: g.hypot(a),
            ..chain.params().clone()
        })?;
        Ok(Self {
            chain: chain.clone(),
            turned: RigidModel::new(&turned),
            theta: a.atan2(g),
            buf: RefCell::new(vec![0.0; 2 * chain.links() + 1]),
        })
    }

    /// The angle of the field from the downward vertical (rad).
    pub fn tilt(&self) -> f64 {
        self.theta
    }

    /// `f` of the turned state `y - theta` (angles only).
    fn turned<T>(&self, y: &[f64], f: impl FnOnce(&[f64]) -> T) -> T {
        let mut buf = self.buf.borrow_mut();
        buf.clear();
        buf.extend_from_slice(y);
        for phi in &mut buf[..self.chain.links()] {
            *phi -= self.theta;
        }
        f(&buf)
    }

    /// A vector of the turned frame in the plane's.
    fn back(&self, v: Vec2) -> Vec2 {
        let (s, c) = self.theta.sin_cos();
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    }

    /// A point of the turned frame (pivot at `anchor`) in the plane's.
    fn back_point(&self, anchor: Vec2, p: Vec2) -> Vec2 {
        let d = self.back([p[0] - anchor[0], p[1] - anchor[1]]);
        [anchor[0] + d[0], anchor[1] + d[1]]
    }

    fn anchor(&self, t: f64, y: &[f64]) -> Vec2 {
        self.turned.view().support(t, y)[0]
    }
}

/// The turned chain's system, read at `y - theta`.
struct WindSystem {
    inner: ChainSystem,
    n: usize,
    theta: f64,
    buf: Vec<f64>,
}

impl WindSystem {
    fn shift(&mut self, y: &[f64]) {
        self.buf.clear();
        self.buf.extend_from_slice(y);
        for phi in &mut self.buf[..self.n] {
            *phi -= self.theta;
        }
    }
}

impl OdeSystem for WindSystem {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.shift(y);
        self.inner.rhs(t, &self.buf, dy);
    }
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        self.shift(y);
        self.inner.jvp(t, &self.buf, v, jv);
    }
}

/// The turned chain's banded DAE, read at `y - theta`: the shift is a
/// constant, so the Jacobian is the inner one's.
struct WindDae {
    inner: Box<dyn SemiExplicitDae>,
    n: usize,
    theta: f64,
    buf: RefCell<Vec<f64>>,
}

impl WindDae {
    fn at<T>(&self, y: &[f64], f: impl FnOnce(&[f64]) -> T) -> T {
        let mut buf = self.buf.borrow_mut();
        buf.clear();
        buf.extend_from_slice(y);
        for phi in &mut buf[..self.n] {
            *phi -= self.theta;
        }
        f(&buf)
    }
}

impl SemiExplicitDae for WindDae {
    fn dim(&self) -> usize {
        self.inner.dim()
    }
    fn differential_dim(&self) -> usize {
        self.inner.differential_dim()
    }
    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) {
        self.at(y, |y| self.inner.rhs(t, y, out))
    }
    fn derivatives(&self, t: f64, y: &[f64], out: &mut [f64]) -> bool {
        self.at(y, |y| self.inner.derivatives(t, y, out))
    }
    fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        self.at(y, |y| self.inner.jacobian_entries(t, y, emit))
    }
    fn blocks(&self) -> Option<Vec<usize>> {
        self.inner.blocks()
    }
}

impl Problem for WindSystem {
    fn banded_dae(&self, t0: f64, y0: &[f64]) -> Option<BandedDae> {
        let mut turned = y0.to_vec();
        for phi in &mut turned[..self.n] {
            *phi -= self.theta;
        }
        let BandedDae { dae, mut y0 } = self.inner.banded_dae(t0, &turned)?;
        for phi in &mut y0[..self.n] {
            *phi += self.theta;
        }
        let dim = dae.dim();
        Some(BandedDae {
            dae: Box::new(WindDae {
                inner: dae,
                n: self.n,
                theta: self.theta,
                buf: RefCell::new(Vec::with_capacity(dim)),
            }),
            y0,
        })
    }
}

impl Model for WindModel {
    fn name(&self) -> &'static str {
        "wind"
    }
    fn chain(&self) -> Option<&Chain> {
        Some(&self.chain)
    }
    fn layout(&self) -> Layout {
        self.turned.layout()
    }
    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter> {
        if !self.chain.pivot().is_fixed() {
            return Err(InvalidParameter {
                field: "pivot",
                accepted: "a fixed pivot in the wind model".into(),
                got: "a moving one".into(),
            });
        }
        self.turned.validate(method, options)
    }
    fn initial_state(&mut self, start: &State) -> Result<Vec<f64>, InvalidParameter> {
        let turned = State {
            angles: start.angles.iter().map(|p| p - self.theta).collect(),
            ..start.clone()
        };
        let mut y = self.turned.initial_state(&turned)?;
        y[..start.angles.len()].copy_from_slice(&start.angles);
        Ok(y)
    }
    fn problem(&self) -> Box<dyn Problem + '_> {
        let n = self.chain.links();
        Box::new(WindSystem {
            inner: ChainSystem::new(self.turned.chain_ref()),
            n,
            theta: self.theta,
            buf: Vec::with_capacity(2 * n + 1),
        })
    }
    fn energy_scale(&self) -> f64 {
        self.turned.energy_scale()
    }
    fn view(&self) -> &dyn StateView {
        self
    }
}

/// The wind model's states are the turned rigid chain's, read back in the
/// scene's axes.
impl StateView for WindModel {
    fn observe(&self, t: f64, y: &[f64], f: &[f64], trig: &mut Vec<(f64, f64)>) -> Observed {
        let m = self.turned(y, |y| self.turned.view().observe(t, y, f, trig));
        Observed {
            energy: m.energy,
            tip_velocity: self.back(m.tip_velocity),
            tip_acceleration: self.back(m.tip_acceleration),
        }
    }
    fn energy(&self, t: f64, y: &[f64]) -> f64 {
        self.turned(y, |y| self.turned.view().energy(t, y))
    }
    fn tip(&self, t: f64, y: &[f64]) -> Vec2 {
        let p = self.turned(y, |y| self.turned.view().tip(t, y));
        self.back_point(self.anchor(t, y), p)
    }
    fn tip_velocity(&self, t: f64, y: &[f64]) -> Vec2 {
        self.back(self.turned(y, |y| self.turned.view().tip_velocity(t, y)))
    }
    fn support(&self, t: f64, y: &[f64]) -> [Vec2; 2] {
        self.turned.view().support(t, y)
    }
    fn joints(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        let a = self.anchor(t, y);
        let joints = self.turned(y, |y| self.turned.view().joints(t, y));
        joints.into_iter().map(|p| self.back_point(a, p)).collect()
    }
    /// Tension and shear are read in each rod's own frame: the turn leaves
    /// them as they are.
    fn joint_forces(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        self.turned(y, |y| self.turned.view().joint_forces(t, y))
    }
    fn support_force(&self, t: f64, y: &[f64]) -> Vec2 {
        self.back(self.turned(y, |y| self.turned.view().support_force(t, y)))
    }
    fn momentum(&self, t: f64, y: &[f64]) -> Vec2 {
        self.back(self.turned(y, |y| self.turned.view().momentum(t, y)))
    }
}

/// A chain of `links` rods of total length 1, mass 1 per rod, `g = 1`.
fn chain(links: usize, damping: f64) -> Chain {
    Chain::new(ChainParams {
        links,
        length: 1.0,
        mass: 1.0,
        gravity: 1.0,
        damping,
        ..ChainParams::default()
    })
    .unwrap()
}

/// Every method at an accuracy where the runs below are resolved.
fn options(method: Method, t_end: f64, output_dt: Option<f64>) -> SolveOptions {
    SolveOptions {
        t_end,
        output_dt,
        ..SolveOptions::default()
    }
    .at_accuracy(method, if method.adaptive() { 1e-9 } else { 1e-3 })
}

/// The angle's deviation from the tilted vertical `-pi/2 + theta` crosses
/// zero upwards every period: the mean spacing of those crossings.
fn period(times: &[f64], dev: &[f64]) -> f64 {
    let ups: Vec<f64> = (1..dev.len())
        .filter(|&k| dev[k - 1] < 0.0 && dev[k] >= 0.0)
        .map(|k| {
            let s = dev[k - 1] / (dev[k - 1] - dev[k]);
            times[k - 1] + s * (times[k] - times[k - 1])
        })
        .collect();
    assert!(ups.len() >= 3, "{} crossings", ups.len());
    (ups[ups.len() - 1] - ups[0]) / (ups.len() - 1) as f64
}

#[test]
fn a_rod_in_the_wind_swings_about_the_tilted_vertical_with_the_fields_period() {
    let a = 0.75; // G = 1.25 g, theta = 36.87 degrees
    let c = chain(1, 0.0);
    let model = WindModel::new(&c, a).unwrap();
    let eq = -std::f64::consts::FRAC_PI_2 + model.tilt();
    let start = State {
        anchor: [0.0, 0.0],
        angles: vec![eq + 1e-3],
        rates: vec![0.0],
    };
    let expected = 2.0 * std::f64::consts::PI * (2.0 / (3.0 * 1.0f64.hypot(a))).sqrt();
    for method in Method::ALL.into_iter().filter(|m| !m.is_nonsmooth()) {
        let traj = solve(
            model.clone(),
            &start,
            method,
            &options(method, 30.0, Some(1e-3)),
        )
        .unwrap();
        assert_eq!(traj.status, Status::Ok, "{method}");
        let dev: Vec<f64> = traj.samples().map(|s| s.angles[0] - eq).collect();
        let t = period(&traj.times, &dev);
        assert!(
            (t / expected - 1.0).abs() < 1e-4,
            "{method}: period {t}, closed form {expected}"
        );
        // The energy balance holds for the model's own energy.
        assert!(traj.summary.energy_balance_error < 1e-8, "{method}");
    }
}

#[test]
fn a_chain_hung_along_the_field_stays_at_rest_and_one_hung_plumb_does_not() {
    let c = chain(8, 0.01);
    let model = WindModel::new(&c, 0.5).unwrap();
    let along = State {
        anchor: [0.2, -0.1],
        angles: vec![-std::f64::consts::FRAC_PI_2 + model.tilt(); 8],
        rates: vec![0.0; 8],
    };
    let plumb = State {
        angles: vec![-std::f64::consts::FRAC_PI_2; 8],
        ..along.clone()
    };
    let o = options(Method::Dopri5, 2.0, Some(0.5));
    let rest = solve(model.clone(), &along, Method::Dopri5, &o).unwrap();
    let moved = solve(model.clone(), &plumb, Method::Dopri5, &o).unwrap();
    // The tip of the chain along the field: `anchor + L (sin theta, -cos theta)`.
    let (s, co) = model.tilt().sin_cos();
    let tip = [0.2 + s, -0.1 - co];
    let last = rest.len() - 1;
    for k in [0, last] {
        let p = rest.tip(k);
        assert!(
            (p[0] - tip[0]).abs() < 1e-9 && (p[1] - tip[1]).abs() < 1e-9,
            "{p:?}"
        );
    }
    let joints = rest.joints(last);
    assert_eq!(joints.len(), 9);
    assert!((joints[0][0] - 0.2).abs() < 1e-15 && (joints[8][0] - tip[0]).abs() < 1e-9);
    // Hung plumb, the wind blows it toward +x.
    assert!(
        moved.tip(moved.len() - 1)[0] > 0.2 + 0.05,
        "{:?}",
        moved.summary.tip_end
    );
}

#[test]
fn every_method_runs_the_wind_model_and_meets_a_tight_reference() {
    let c = chain(6, 0.05);
    let model = WindModel::new(&c, 0.4).unwrap();
    let start = State {
        anchor: [0.0, 0.0],
        angles: vec![0.0; 6],
        rates: vec![0.0; 6],
    };
    let reference = solve(
        model.clone(),
        &start,
        Method::Dop853,
        &SolveOptions {
            t_end: 1.5,
            ..SolveOptions::default()
        }
        .at_accuracy(Method::Dop853, 1e-12),
    )
    .unwrap();
    let tip = reference.summary.tip_end;
    for method in Method::ALL.into_iter().filter(|m| !m.is_nonsmooth()) {
        let traj = solve(model.clone(), &start, method, &options(method, 1.5, None)).unwrap();
        assert_eq!(traj.status, Status::Ok, "{method}");
        let p = traj.summary.tip_end;
        let err = (p[0] - tip[0]).hypot(p[1] - tip[1]);
        assert!(err < 1e-4, "{method}: tip error {err:e}");
    }
}

/// The outputs serve the model as they serve the chain: the trajectory CSV
/// (`fc_scene::csv`) writes the model's own tip and energy for every sample,
/// and the forces CSV a row of `n + 1` joints; the summary's balance holds.
#[test]
fn the_wind_models_trajectory_reaches_the_csv_writers() {
    let c = chain(4, 0.02);
    let model = WindModel::new(&c, 0.6).unwrap();
    let start = State {
        anchor: [0.0, 0.0],
        angles: vec![0.3; 4],
        rates: vec![0.0; 4],
    };
    let traj = solve(
        model,
        &start,
        Method::Dopri5,
        &options(Method::Dopri5, 1.0, Some(0.1)),
    )
    .unwrap();
    assert_eq!(traj.status, Status::Ok);
    let mut out = Vec::new();
    fc_scene::csv::write_trajectory(&mut out, &traj).unwrap();
    let text = String::from_utf8(out).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,tip_x,tip_y,tip_vx,tip_vy,energy,dissipated,phi_1,phi_2,phi_3,phi_4"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), traj.len());
    for (k, row) in rows.iter().enumerate() {
        let tip = traj.tip(k);
        assert_eq!((row[1], row[2]), (tip[0], tip[1]));
        assert_eq!(row[5], traj.energy(k));
        // `E + W` is the start's energy at every sample.
        assert!((row[5] + row[6] - rows[0][5]).abs() < 1e-7, "row {k}");
    }
    let mut out = Vec::new();
    fc_scene::csv::write_forces(&mut out, &traj).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert_eq!(text.lines().nth(1).unwrap().split(',').count(), 1 + 2 * 5);
}

/// The model's work-precision table is the study's ([`fc_study::precision`]
/// on a [`ModelSubject`](fc_study::subject::ModelSubject)), as a scene's is:
/// the reference (DOPRI5 at 1e-13) is confirmed by its RK4 and BDF checks,
/// each method's error falls as its tolerance tightens (at least 1e4 over
/// the line), and the table's CSV reads back with one row per point. The
/// reference's tip is the wind's: the windless chain's lies far from it.
#[test]
fn the_wind_model_gets_a_precision_table() {
    use fc_batch::shard::Provenance;
    use fc_study::precision::{self, Checks, Options};
    use fc_study::subject::ModelSubject;

    let c = chain(6, 0.05);
    let start = State {
        anchor: [0.0, 0.0],
        angles: vec![0.0; 6],
        rates: vec![0.0; 6],
    };
    let base = SolveOptions {
        t_end: 1.5,
        ..SolveOptions::default()
    };
    let subject = ModelSubject::new(
        WindModel::new(&c, 0.4).unwrap(),
        start.clone(),
        base.clone(),
        c.length(),
    );
    let options = Options {
        methods: vec![Method::Dopri5, Method::Bdf],
        checks: Checks::default(),
        budget: None,
        shard: None,
        jobs: 2,
        measures: fc_study::measure::Measures::TIP,
    };
    let provenance = Provenance {
        runs: precision::ladder(&options.methods).len(),
        hash: "0".repeat(16),
    };
    let s = precision::study_of(subject, "wind", provenance, &options, None, &|| {}).unwrap();
    assert!(s.failures.is_empty(), "{:?}", s.failures);
    let (a_rk4, a_bdf) = precision::agreement(&s.rows);
    assert!(a_rk4 < 1e-6 && a_bdf < 1e-6, "{a_rk4:e} {a_bdf:e}");
    for m in &options.methods {
        let line: Vec<f64> = s
            .rows
            .iter()
            .filter(|r| r.method == m.as_str())
            .map(|r| r.err())
            .collect();
        assert_eq!(line.len(), precision::RTOLS.len(), "{m}");
        assert!(line.iter().all(|e| e.is_finite()), "{m}: {line:?}");
        assert!(line[line.len() - 1] < 1e-4 * line[0], "{m}: {line:?}");
    }
    let table = fc_csv::table::Table::parse("wind", &s.csv()).unwrap();
    assert_eq!(table.len(), s.rows.len());
    let windless = solve(
        &c,
        &start,
        Method::Dop853,
        &base.at_accuracy(Method::Dop853, 1e-12),
    )
    .unwrap();
    let (r, w) = (s.reference.tip, windless.summary.tip_end);
    assert!((r[0] - w[0]).hypot(r[1] - w[1]) > 0.05, "{r:?} {w:?}");
}
