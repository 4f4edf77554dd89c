//! The chain of rigid rods as a [`Model`]: the state `[phi, w, W]`
//! (`2 n + 1`), the pivot's path along the run, and what such a state means,
//! [`RigidView`] (the chain's one energy, or the report's), which the report's
//! model shares.

use super::{ForceScratch, Layout, Model, Observed, PeakForce, PeakValue, StateView};
use crate::chain::Chain;
use crate::dae::ChainDae;
use crate::dynamics::Workspace;
use crate::elastic;
use crate::kinematics::{joints, lever_arm, tip, tip_velocity, RodSums, Vec2};
use crate::load::{Angles, Loads, Units};
use crate::pivot::{centre_of_mass, PivotPath};
use crate::profile::Rods;
use crate::report::ReportModel;
use crate::scalar::Scalar;
use crate::solve::{SolveOptions, BDF_DENSE_MAX_LINKS};
use crate::state::State;
use crate::system::ChainSystem;
use fc_methods::InvalidParameter;
use fc_methods::Problem;
use fc_methods::{AutoPlan, Method, TimeScales, AUTO_DOP853_RTOL};

/// The rigid chain and where its pivot is along a run (the prescribed
/// motion and, once let go, the free fall of the centre of mass).
#[derive(Clone, Debug, PartialEq)]
pub struct RigidModel {
    view: RigidView,
    released: bool,
}

/// What a state `[phi, w, W]` of a chain of rigid rods means: its pivot's
/// path, its tip, joints and joint forces, and its energy (the chain's, or
/// the report's equations' for the report's model).
#[derive(Clone, Debug, PartialEq)]
pub struct RigidView {
    chain: Chain,
    path: PivotPath,
    /// The chain's loads (rod units; their potentials are physical).
    loads: Loads,
    /// The report's equations, whose energy (in their units) the state's is;
    /// `None`: the chain's.
    report: Option<ReportModel>,
}

impl RigidModel {
    /// The model of a validated chain of rigid rods, its pivot at the
    /// origin until [`Model::initial_state`] places it.
    pub fn new(chain: &Chain) -> Self {
        Self {
            view: RigidView {
                chain: chain.clone(),
                path: PivotPath::new(chain, [0.0, 0.0]),
                loads: Loads::of(chain, Units::Rod),
                report: None,
            },
            released: false,
        }
    }

    /// The same model whose states are read by the report's equations
    /// (their energy): the report's model's view.
    pub(super) fn reading_as(mut self, report: ReportModel) -> Self {
        self.view.report = Some(report);
        self
    }

    /// The chain.
    pub fn chain_ref(&self) -> &Chain {
        &self.view.chain
    }

    /// The pivot's path.
    pub fn path(&self) -> &PivotPath {
        &self.view.path
    }
}

impl RigidView {
    /// The fused pass of [`rigid_pass`] plus the frame's terms of a moving
    /// pivot.
    fn chain_pass(&self, t: f64, y: &[f64], f: &[f64], trig: &mut Vec<(f64, f64)>) -> Observed {
        let mut m = rigid_pass(&self.chain, &self.loads, y, Some(f), trig);
        if self.path.is_fixed() {
            return m;
        }
        let n = self.chain.links();
        let (phi, w, acc) = (&y[..n], &y[n..2 * n], &f[n..2 * n]);
        let frame = self.path.frame(&self.chain, t, phi, w);
        let a0 = self.path.acceleration(&self.chain, t, phi, w, acc);
        m.energy += frame.energy;
        let [v, a] = [frame.velocity, a0];
        m.tip_velocity = [m.tip_velocity[0] + v[0], m.tip_velocity[1] + v[1]];
        m.tip_acceleration = [m.tip_acceleration[0] + a[0], m.tip_acceleration[1] + a[1]];
        m
    }

    fn split<'a>(&self, y: &'a [f64]) -> (&'a [f64], &'a [f64]) {
        let n = self.chain.links();
        (&y[..n], &y[n..2 * n])
    }

    /// The joints' forces `F_0..F_{n-1}` of `y` at `t` on the rod after
    /// each (physical units), in `scratch.joint`: the DAE's multipliers
    /// made consistent with `(phi, w)` by the O(n) recursion
    /// ([`ChainDae::make_consistent_at`], as [`StateView::joint_forces`] has
    /// them), kept for the next call on the same state, allocation free
    /// once `scratch` has grown.
    fn forces_into(&self, t: f64, y: &[f64], scratch: &mut ForceScratch) {
        if scratch.holds(t, y) {
            return;
        }
        let n = self.chain.links();
        let own = scratch.rigid.get_or_insert_with(|| {
            let held = ChainDae::new(&self.chain);
            Box::new(RigidForces {
                free: held.clone().released(true),
                full: vec![0.0; held.dim()],
                held,
                ws: Workspace::new(n),
            })
        });
        let dae = if self.path.is_free_at(t) {
            &own.free
        } else {
            &own.held
        };
        own.full[..2 * n].copy_from_slice(&y[..2 * n]);
        dae.make_consistent_at(t, &mut own.full, &mut own.ws);
        let ml = self.chain.mass() * self.chain.rod_length();
        let free = self.path.is_free_at(t);
        scratch.joint.resize(n, [0.0, 0.0]);
        let k0 = 3 * n + 1;
        for (k, f) in scratch.joint.iter_mut().enumerate() {
            *f = if k == 0 && free {
                [0.0, 0.0]
            } else {
                [ml * own.full[k0 + 2 * k], ml * own.full[k0 + 2 * k + 1]]
            };
        }
        scratch.keep(t, y);
    }
}

/// The rigid chain's scratch for its forces at every step
/// ([`ForceScratch`]): its DAE held and let go, a consistent state and the
/// recursion's workspace.
#[derive(Debug)]
pub(crate) struct RigidForces {
    held: ChainDae,
    free: ChainDae,
    full: Vec<f64>,
    ws: Workspace<f64>,
}

/// `[phi, w, W]`; a sample is the state, its time and the joints' positions.
fn rigid_layout(chain: &Chain) -> Layout {
    let n = chain.links();
    let numbers = (2 * n as u64 + 2) + 2 * (n as u64 + 1);
    Layout::angles_rates_work(n, 2 * n + 1, numbers)
}

/// The rigid chain's bounds of a run with `method`: the pivot's time
/// scales for a fixed step, the output's size, and `bdf-dense`'s size.
fn validate_rigid(
    chain: &Chain,
    method: Method,
    options: &SolveOptions,
) -> Result<(), InvalidParameter> {
    options.validate_common(Some(chain.pivot()), method, &rigid_layout(chain))?;
    check_dense_size(chain, method)?;
    // A released pivot moves with the free fall of the centre of mass
    // (`PivotPath`), which the rigid state does not carry: a load that reads
    // the rods' velocities (the drag) would see them relative to it.
    if chain.pivot().release.is_some() {
        if let Some(key) = Loads::of(chain, Units::Rod).first_reading_centres() {
            return Err(InvalidParameter {
                field: key,
                accepted: "0 with pivot.release on rigid links (the rigid chain's state does \
                           not carry the free pivot's velocity this load reads); set \
                           chain.axial_stiffness for elastic links, which do"
                    .into(),
                got: format!("{}", chain.params().coefficients.get(key)),
            });
        }
    }
    Ok(())
}

/// `bdf-dense`'s size bound, for any chain.
pub(super) fn check_dense_size(chain: &Chain, method: Method) -> Result<(), InvalidParameter> {
    crate::chain::check(
        method != Method::BdfDense || chain.links() <= BDF_DENSE_MAX_LINKS,
        "chain.links",
        format!(
            "at most {BDF_DENSE_MAX_LINKS} for bdf-dense (its dense Jacobian and LU \
             grow like n^2 in memory and n^3 in time); run.method = \"bdf\" is the \
             same method in O(n)"
        ),
        chain.links(),
    )
}

impl Model for RigidModel {
    fn name(&self) -> &'static str {
        "rigid"
    }

    fn chain(&self) -> Option<&Chain> {
        Some(&self.view.chain)
    }

    fn layout(&self) -> Layout {
        rigid_layout(&self.view.chain)
    }

    fn validate(&self, method: Method, options: &SolveOptions) -> Result<(), InvalidParameter> {
        validate_rigid(&self.view.chain, method, options)
    }

    fn initial_state(&mut self, start: &State) -> Result<Vec<f64>, InvalidParameter> {
        super::check_start(&self.view.chain, start)?;
        self.view.path = PivotPath::new(&self.view.chain, start.anchor);
        // A pivot let go at the start is free from the first step.
        if self.view.chain.pivot().release.is_some_and(|tr| tr <= 0.0) {
            self.view
                .path
                .release(&self.view.chain, 0.0, &start.angles, &start.rates);
            self.released = true;
        }
        Ok(ChainSystem::pack(&start.angles, &start.rates, 0.0))
    }

    fn problem(&self) -> Box<dyn Problem + '_> {
        let mut sys = ChainSystem::new(&self.view.chain);
        if self.released {
            sys.set_released(true);
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

    /// BDF from the start past the crossover damping rate, else DOPRI5
    /// (DOP853 at tight tolerances) to the end: the stiffness the detector
    /// sees in a rigid chain is the whip and the waves, not a reason to
    /// hand over mid-run.
    fn auto_plan(&self, rtol: f64) -> AutoPlan {
        AutoPlan {
            explicit: rigid_auto_start(&self.view.chain, rtol),
            hand_over_above: f64::INFINITY,
            implicit: Method::Bdf,
            implicit_tolerance: 1.0,
            implicit_rho_inf: None,
        }
    }

    fn event_time(&self) -> Option<f64> {
        self.view.chain.pivot().release
    }

    /// The release: the path notes where the centre of mass is and how fast
    /// it moves; from then on joint 0 is a free end.
    fn at_event(&mut self, t: f64, y: &mut [f64]) {
        let n = self.view.chain.links();
        self.view
            .path
            .release(&self.view.chain, t, &y[..n], &y[n..2 * n]);
        self.released = true;
    }

    fn view(&self) -> &dyn StateView {
        &self.view
    }
}

impl StateView for RigidView {
    /// The chain's pass (with the report's equations, their energy and the
    /// chain's tip).
    fn observe(&self, t: f64, y: &[f64], f: &[f64], trig: &mut Vec<(f64, f64)>) -> Observed {
        let m = self.chain_pass(t, y, f, trig);
        match self.report {
            Some(_) => Observed {
                energy: self.energy(t, y),
                ..m
            },
            None => m,
        }
    }

    /// The chain's energy, or the report's (its Lagrangian's `T + V`, in
    /// its units).
    fn energy(&self, t: f64, y: &[f64]) -> f64 {
        if let Some(report) = self.report {
            let n = self.chain.links();
            return report.energy(&self.chain, &y[..n], &y[n..2 * n]);
        }
        let e = rigid_pass(&self.chain, &self.loads, y, None, &mut Vec::new()).energy;
        if self.path.is_fixed() {
            return e;
        }
        let (phi, w) = self.split(y);
        e + self.path.frame(&self.chain, t, phi, w).energy
    }

    fn tip(&self, t: f64, y: &[f64]) -> Vec2 {
        let (phi, _) = self.split(y);
        tip(&self.chain, self.support(t, y)[0], phi)
    }

    fn tip_velocity(&self, t: f64, y: &[f64]) -> Vec2 {
        let (phi, w) = self.split(y);
        let v = tip_velocity(&self.chain, phi, w);
        if self.path.is_fixed() {
            return v;
        }
        let v0 = self.path.at(&self.chain, t, phi, w)[1];
        [v[0] + v0[0], v[1] + v0[1]]
    }

    fn support(&self, t: f64, y: &[f64]) -> [Vec2; 2] {
        let (phi, w) = self.split(y);
        self.path.at(&self.chain, t, phi, w)
    }

    fn joints(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        let (phi, _) = self.split(y);
        joints(&self.chain, self.support(t, y)[0], phi)
    }

    fn joint_forces(&self, t: f64, y: &[f64]) -> Vec<Vec2> {
        let free = self.path.is_free_at(t);
        let forces = elastic::rigid_joint_forces_at(&self.chain, t, free, y);
        elastic::tension_shear(&y[..self.chain.links()], &forces)
    }

    /// The recursion's force on rod 1 (with a moving pivot at its
    /// acceleration at `t`; zero once let go; zero for the report's
    /// equations, which state none).
    fn support_force(&self, t: f64, y: &[f64]) -> Vec2 {
        if self.report.is_some() {
            return [0.0, 0.0];
        }
        let mut sys = ChainSystem::new(&self.chain);
        let (phi, w) = self.split(y);
        let y = ChainSystem::pack(phi, w, 0.0);
        let mut dy = vec![0.0; y.len()];
        if self.path.is_fixed() {
            return sys.rhs_with_reactions(&y, &mut dy).pivot_force;
        }
        sys.set_released(self.path.is_free_at(t));
        sys.rhs_at(t, &y, &mut dy).pivot_force
    }

    fn peak_forces(&self) -> &'static [PeakForce] {
        &[PeakForce::Pivot, PeakForce::Tension]
    }

    /// From the multipliers (one recursion per state, shared by the pivot
    /// and the tensions: [`RigidModel::forces_into`]).
    fn peak_force(
        &self,
        force: PeakForce,
        t: f64,
        y: &[f64],
        scratch: &mut ForceScratch,
    ) -> PeakValue {
        self.forces_into(t, y, scratch);
        match force {
            PeakForce::Floor => [0.0, 0.0],
            PeakForce::Pivot => {
                let f = scratch.joint[0];
                [f[0].hypot(f[1]), 0.0]
            }
            PeakForce::Tension => {
                let (phi, _) = self.split(y);
                let (mut best, mut at) = (f64::NEG_INFINITY, 0);
                for (k, (f, &p)) in scratch.joint.iter().zip(phi).enumerate() {
                    let (s, c) = crate::scalar::sin_cos(p);
                    let tension = -(f[0] * c + f[1] * s);
                    if tension > best || tension.is_nan() {
                        (best, at) = (tension, k);
                    }
                }
                [best, at as f64]
            }
        }
    }

    /// `(sum m_i + M_t) c_rel'`, the centre of mass's velocity relative to
    /// the pivot (tip mass and unequal rods included).
    fn momentum(&self, _t: f64, y: &[f64]) -> Vec2 {
        let (phi, w) = self.split(y);
        let [_, v] = centre_of_mass(&self.chain, phi, w);
        let m = self.chain.total_mass() + self.chain.tip_mass();
        [m * v[0], m * v[1]]
    }
}

/// The rigid chain's energy `T + V (+ M_t terms) (+ U_b)` of `y = [phi, w, ..]`
/// relative to the pivot: the one energy of the model (the runs' balance,
/// every sample's `energy`, [`kinematics::energy`](crate::kinematics::energy)).
pub(crate) fn rigid_energy(chain: &Chain, y: &[f64]) -> f64 {
    let mut trig = Vec::new();
    rigid_pass(chain, &Loads::of(chain, Units::Rod), y, None, &mut trig).energy
}

/// The fused pass: energy, tip velocity and (with `f`) tip acceleration of
/// a rigid chain's state, relative to the pivot, in one loop over the rods.
fn rigid_pass(
    chain: &Chain,
    loads: &Loads,
    y: &[f64],
    f: Option<&[f64]>,
    trig: &mut Vec<(f64, f64)>,
) -> Observed {
    if let Some(rods) = chain.rods() {
        return rods_pass(chain, rods, loads, y, f);
    }
    let n = chain.links();
    let (phi, w) = (&y[..n], &y[n..2 * n]);
    let acc = |i: usize| f.map_or(0.0, |f| f[n + i]);
    if trig.len() < n {
        trig.resize(n, (0.0, 0.0));
    }
    let trig = &mut trig[..n];
    f64::sin_cos_all(phi, trig);
    // The kinematics' per-rod kernel, the potential's lever arms, and the
    // tip acceleration, in one pass.
    let mut sums = RodSums::default();
    let (mut ax, mut ay) = (0.0, 0.0);
    let mut v = 0.0;
    for i in 0..n {
        let (s, c) = trig[i];
        let (wi, ai) = (w[i], acc(i));
        sums.add(s, c, wi);
        v += lever_arm(n, i) * s;
        ax += -ai * s - wi * wi * c;
        ay += ai * c - wi * wi * s;
    }
    let l = chain.rod_length();
    // `T + V`; the products are kept in the order the committed data were
    // made with (`m l l`, then 1/2).
    let ml2 = chain.mass() * l * l;
    let mut e = 0.5 * ml2 * sums.twice_kinetic + chain.mass() * chain.gravity() * l * v;
    if chain.tip_mass() != 0.0 {
        // The tip mass: `(M_t / 2) |v_tip|^2 + M_t g y_tip`, `y_tip = l sum sin phi`
        // (a second pass, only for a chain that has one).
        let [vx, vy] = sums.tip_velocity(l);
        let y_tip: f64 = phi.iter().map(|p| l * p.sin()).sum();
        e += 0.5 * chain.tip_mass() * (vx * vx + vy * vy)
            + chain.tip_mass() * chain.gravity() * y_tip;
    }
    Observed {
        // The loads' potentials (bending's).
        energy: loads.potential(&Angles { phi, w }, e),
        tip_velocity: sums.tip_velocity(l),
        tip_acceleration: [l * ax, l * ay],
    }
}

/// [`rigid_pass`] for unequal rods (masses `mu_i m`, lengths `lambda_i l`).
fn rods_pass(chain: &Chain, rods: &Rods, loads: &Loads, y: &[f64], f: Option<&[f64]>) -> Observed {
    let n = chain.links();
    let (phi, w) = (&y[..n], &y[n..2 * n]);
    let acc = |i: usize| f.map_or(0.0, |f| f[n + i]);
    let mut sums = RodSums::default();
    let (mut ax, mut ay) = (0.0, 0.0);
    let (mut joint, mut v) = (0.0, 0.0);
    for i in 0..n {
        let (s, c) = crate::scalar::sin_cos(phi[i]);
        let (wi, ai) = (w[i], acc(i));
        let (mu, lam) = (rods.mass[i], rods.length[i]);
        sums.add_rod(s, c, wi, mu, lam);
        v += mu * (joint + 0.5 * lam * s);
        joint += lam * s;
        ax += lam * (-ai * s - wi * wi * c);
        ay += lam * (ai * c - wi * wi * s);
    }
    let l = chain.rod_length();
    let ml2 = chain.mass() * l * l;
    let mut e = 0.5 * ml2 * sums.twice_kinetic + chain.mass() * chain.gravity() * l * v;
    if chain.tip_mass() != 0.0 {
        // `(M_t / 2) |v_tip|^2 + M_t g y_tip`, the tip's height `l joint`.
        let [vx, vy] = sums.tip_velocity(l);
        e += 0.5 * chain.tip_mass() * (vx * vx + vy * vy)
            + chain.tip_mass() * chain.gravity() * (l * joint);
    }
    Observed {
        energy: loads.potential(&Angles { phi, w }, e),
        tip_velocity: sums.tip_velocity(l),
        tip_acceleration: [l * ax, l * ay],
    }
}

/// The damping rate `gamma = r / (m l^2)` (1/time) past which the O(n) BDF
/// overtakes DOPRI5 on this chain, and from which `auto` runs BDF from the
/// start.
///
/// An explicit step is held below `~3.3 / |lambda|`, and the chain has two
/// fast rates: damping, `|lambda| ~ 48 gamma`, and its fastest undamped mode,
/// `omega_max ~ 3.4 sqrt(g L) / l` (the hanging chain's top frequency; it
/// grows like n). So the crossover grows with n once `omega_max` dominates.
/// An earlier form of the `stiffness` study (span d = 3, t = 1, equal
/// rtol 1e-6, n = 25 to 3200) measured it and fits it as
/// `27 sqrt(g/L) + 0.12 sqrt(g L) / l`: 12 at n = 25 and 168 at n = 3200 in
/// the report's units, an empirical fit. At matched accuracy (error 1e-6)
/// over a fall past the whip (t = 3) the study now measures 11, 15, 28 and
/// 106 at n = 25, 100, 400 and 1600, 0.84 to 1.13 times this rule
/// (`cargo xtask figures --timings --only stiffness`, wall times on a
/// shared machine, known to a factor of about two).
pub fn bdf_crossover_gamma(chain: &Chain) -> f64 {
    let (g, big_l) = (chain.gravity(), chain.length());
    27.0 * (g / big_l).sqrt() + 0.12 * (g * big_l).sqrt() / chain.rod_length()
}

/// `auto`'s start on a rigid chain, as its doc says: BDF (`None`) at or past
/// the crossover damping rate, DOP853 at `rtol <= 1e-8`, DOPRI5 otherwise.
pub(crate) fn rigid_auto_start(chain: &Chain, rtol: f64) -> Option<Method> {
    if chain.stiffest_damping_rate() >= bdf_crossover_gamma(chain) {
        None
    } else if rtol <= AUTO_DOP853_RTOL {
        Some(Method::Dop853)
    } else {
        Some(Method::Dopri5)
    }
}
