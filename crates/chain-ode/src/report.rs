//! The report's own model, as a control (`model.report` in a scene,
//! `docs/model.md`, "The report's model").
//!
//! The student report's equations (4.8)/(5.3) as printed and as its code
//! integrates them, each erratum a switch of [`ReportModel`], so that a
//! pair of runs that differ in one switch measures what that erratum
//! changes. With every switch off the equations are the corrected model's
//! (`docs/model.md`, "Equations of motion"), solved densely here instead of
//! by the O(n) recursion: a test checks the two agree.
//!
//! In rod units (`m l^2`), 1-based `i, j`:
//!
//! ```text
//! sum_j mt_ij c_ij phi_j'' + sum_j mt_ij s_ij w_j^2 + G q_i cos phi_i = sigma gamma D_i(w)
//! ```
//!
//! * `mt_ii = n - i + 1/3 + delta`, `mt_ij = n - max(i, j) + 1/2 + delta`
//!   (`i != j`), `q_i = n - i + 1/2 + delta`: `delta = 1` with the code's
//!   0-based indices (erratum 2: its `M(n)` and `qc` use the 1-based
//!   formulas with 0-based `i`, `j`, so every entry is one too large),
//!   `0` corrected. `+1` in every `mt_ij` and every `q_i` is exactly a
//!   point mass of one rod's mass `m` at the free end (`chain.tip_mass = m`,
//!   `docs/model.md`): the report's chain carries a tip mass it never
//!   mentions;
//! * `G = 1` (1/time^2) with the code's dropped `g/l` (erratum 3: its time
//!   unit is `sqrt(l/g)` of ours), `G = g/l` corrected;
//! * `gamma = r / (m l^2)`, `D_i` the joint stencil of the corrected model
//!   (`D_1 = w_2 - w_1`, `D_n = w_{n-1} - w_n`); `sigma = +1` is the
//!   dissipative sign, `sigma = -1` the sign of eq. (5.3) as printed
//!   (erratum 1), which feeds energy in.
//!
//! The model's own energy, conserved up to the work `W` its friction does
//! (`W' = sigma r sum_{i>=2} (w_i - w_{i-1})^2`, carried in the state so that
//! `E + W = E(0)` checks any run), is
//! `E = (m l^2 / 2) (w^T A w) + m l^2 G sum_i q_i sin phi_i`; with every
//! switch off it is the corrected chain's `T + V`.

use crate::chain::{check, Chain};
use crate::kinematics::Vec2;
use fc_methods::InvalidParameter;
use fc_methods::{OdeSystem, Problem};

/// The largest chain the report's model runs: its dense solve is O(n^3)
/// per right-hand side (the report used `n <= 100`).
pub const REPORT_MAX_LINKS: usize = 200;

/// The keys of the loads the report's model carries besides gravity (its
/// field): joint friction's. [`ReportModel::validate`] refuses every other
/// load of [`crate::load::KINDS`] by its key.
pub const REPORT_LOADS: [&str; 1] = ["chain.damping"];

/// Which of the report's errata a run keeps (`true`: as the report has it).
/// [`ReportModel::AS_CODED`] is `model.report = true`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReportModel {
    /// Erratum 2: `mt_ij` and `q_i` indexed from 0 (each one too large:
    /// a tip mass of one rod's mass).
    pub indices: bool,
    /// Erratum 3: the gravity term without `g/l` (`G = 1`): the report's
    /// clock, whose time unit is `sqrt(l/g)` of ours.
    pub clock: bool,
    /// Erratum 1 as printed: `+ gamma D_i` on the left of eq. (5.3), which
    /// feeds energy in. Off in [`ReportModel::AS_CODED`]: the report's code
    /// adds its friction term with the dissipative sign (and the boundary
    /// rows `D_1`, `D_n` above); only the printed equation has the other.
    pub printed_friction_sign: bool,
    /// Erratum 4: `rk4` runs the report's stepper (explicit Euler in
    /// `phi`, RK4 stages in `w` at frozen angles: [`crate::model::ReportChain`]) instead
    /// of RK4.
    pub stepper: bool,
}

impl ReportModel {
    /// The report's model as its code runs it: indices, clock and stepper
    /// as coded, friction dissipative.
    pub const AS_CODED: Self = Self {
        indices: true,
        clock: true,
        printed_friction_sign: false,
        stepper: true,
    };

    /// Every erratum corrected: the corrected model's equations.
    pub const CORRECTED: Self = Self {
        indices: false,
        clock: false,
        printed_friction_sign: false,
        stepper: false,
    };

    /// The index shift `delta` of `mt_ii` and `q_i`.
    fn delta(self) -> f64 {
        if self.indices {
            1.0
        } else {
            0.0
        }
    }

    /// The gravity rate `G` (1/time^2) of `chain` in this model.
    pub fn gravity_rate(self, chain: &Chain) -> f64 {
        if self.clock {
            1.0
        } else {
            chain.gravity() / chain.rod_length()
        }
    }

    /// The report's time unit in ours: a report time `tau` is
    /// `tau * time_unit` of the corrected model, a report speed `v` is
    /// `v / time_unit` (`sqrt(l / g)` with the clock erratum, else 1).
    pub fn time_unit(self, chain: &Chain) -> f64 {
        (self.gravity_rate(chain) / chain.gravity_rate()).sqrt()
    }

    /// The friction's sign `sigma`: `+1` dissipative, `-1` as printed.
    fn sigma(self) -> f64 {
        if self.printed_friction_sign {
            -1.0
        } else {
            1.0
        }
    }

    /// `mt_ij` (1-based `i`, `j` given 0-based here) of an `n`-rod chain.
    pub fn mt(self, n: usize, i: usize, j: usize) -> f64 {
        let k = i.max(j) + 1;
        if i == j {
            (n - k) as f64 + 1.0 / 3.0 + self.delta()
        } else {
            (n - k) as f64 + 0.5 + self.delta()
        }
    }

    /// `q_i` (0-based `i`) of an `n`-rod chain.
    pub fn q(self, n: usize, i: usize) -> f64 {
        (n - i - 1) as f64 + 0.5 + self.delta()
    }

    /// Checks that `chain` is one this model runs: rigid links without
    /// bending springs, a tip mass or a moving pivot (the report has none), at most
    /// [`REPORT_MAX_LINKS`] rods. The error names the scene key.
    pub fn validate(self, chain: &Chain) -> Result<(), InvalidParameter> {
        const WHY: &str = "absent with model.report = true (the report's model has rigid links)";
        // The loads it carries are gravity and joint friction (its `G` and
        // `sigma gamma D_i`); every other load is refused by its key.
        for kind in crate::load::KINDS {
            if kind.key != REPORT_LOADS[0] && (kind.is_on)(chain.params()) {
                return Err(InvalidParameter {
                    field: kind.key,
                    accepted: format!(
                        "absent (0) with model.report = true (the report's model carries \
                         gravity and joint friction only, no {})",
                        kind.name
                    )
                    .into(),
                    got: format!("the {}", kind.name),
                });
            }
        }
        if let Some(ea) = chain.axial_stiffness() {
            check(false, "chain.axial_stiffness", WHY, ea)?;
        }
        check(
            chain.tip_mass() == 0.0,
            "chain.tip_mass",
            "0 with model.report = true (the report's model has no tip mass)",
            chain.tip_mass(),
        )?;
        // The clock erratum's time unit is sqrt(l / g) of ours: infinite at
        // g = 0, where the report's model (G = 1) has no counterpart.
        check(
            !self.clock || chain.gravity() > 0.0,
            "chain.gravity",
            "a number > 0 with model.report = true (the report's clock unit is sqrt(l / g))",
            chain.gravity(),
        )?;
        if let Some(key) = chain.params().profile.first_given() {
            return Err(InvalidParameter {
                field: key,
                accepted: "absent with model.report = true (the report's rods are equal)".into(),
                got: "a rod profile".to_string(),
            });
        }
        if let Some(key) = chain.pivot().first_given() {
            return Err(InvalidParameter {
                field: key,
                accepted: "absent with model.report = true (the report's pivot is fixed)".into(),
                got: "a moving or released pivot".to_string(),
            });
        }
        check(
            chain.links() <= REPORT_MAX_LINKS,
            "chain.links",
            format!(
                "at most {REPORT_MAX_LINKS} with model.report = true (its dense solve is O(n^3) \
                 per step)"
            ),
            chain.links(),
        )
    }

    /// The model's energy `(m l^2 / 2) w^T A w + m l^2 G sum q_i sin phi_i`.
    pub fn energy(self, chain: &Chain, phi: &[f64], w: &[f64]) -> f64 {
        let n = phi.len();
        let mut twice_t = 0.0;
        let mut v = 0.0;
        for i in 0..n {
            for j in 0..n {
                twice_t += self.mt(n, i, j) * (phi[i] - phi[j]).cos() * w[i] * w[j];
            }
            v += self.q(n, i) * phi[i].sin();
        }
        let ml2 = chain.mass() * chain.rod_length().powi(2);
        0.5 * ml2 * twice_t + ml2 * self.gravity_rate(chain) * v
    }

    /// The energy scale past which a run's balance `|E + W - E(0)|` makes
    /// it `inaccurate`: the chain's [`Chain::energy_scale`] in this model's
    /// units of energy (`m l^2 G` for `m g l`).
    pub fn energy_scale(self, chain: &Chain) -> f64 {
        let ratio = self.gravity_rate(chain) / chain.gravity_rate();
        if ratio.is_finite() && ratio > 0.0 {
            chain.energy_scale() * ratio
        } else {
            chain.energy_scale()
        }
    }

    /// The rate of the work its friction does, `W' = sigma r sum (w_i - w_{i-1})^2`.
    pub fn work_rate(self, chain: &Chain, w: &[f64]) -> f64 {
        self.sigma() * chain.damping() * w.windows(2).map(|p| (p[1] - p[0]).powi(2)).sum::<f64>()
    }
}

/// The free end's point as the report's reconstruction `x_iz_phi`/`y_iz_phi`
/// gives it (erratum 5), relative to `P0`: `l sum_{j=2}^{n-1} u_j + (l/2)
/// u_n` (`u_j = (cos phi_j, sin phi_j)`: rod 1 left out of the sum, and the
/// last rod's midpoint, not its end).
fn report_tip(l: f64, phi: &[f64]) -> Vec2 {
    let n = phi.len();
    let mut r = [0.0, 0.0];
    for (j, p) in phi.iter().enumerate().skip(1) {
        let w = if j + 1 == n { 0.5 * l } else { l };
        r[0] += w * p.cos();
        r[1] += w * p.sin();
    }
    if n == 1 {
        r = [0.5 * l * phi[0].cos(), 0.5 * l * phi[0].sin()];
    }
    r
}

/// The tip speeds as the report's code computed them (erratum 5): its
/// point ([`report_tip`]) differenced between consecutive samples,
/// `|r(t_{k+1}) - r(t_k)| / (t_{k+1} - t_k)`; one `[t, speed]` per pair of
/// samples, at the later time.
pub fn finite_difference_tip_speeds(chain: &Chain, times: &[f64], angles: &[&[f64]]) -> Vec<Vec2> {
    let l = chain.rod_length();
    times
        .windows(2)
        .zip(angles.windows(2))
        .map(|(t, a)| {
            let (r0, r1) = (report_tip(l, a[0]), report_tip(l, a[1]));
            let v = (r1[0] - r0[0]).hypot(r1[1] - r0[1]) / (t[1] - t[0]);
            [t[1], v]
        })
        .collect()
}

/// The tip velocities behind [`finite_difference_tip_speeds`] (the report's
/// Figs. 8b and 11b): `[t, v_x, v_y]`, `(r(t_{k+1}) - r(t_k)) / (t_{k+1} -
/// t_k)` of the report's point, one per pair of samples, at the later time.
pub fn finite_difference_tip_velocities(
    chain: &Chain,
    times: &[f64],
    angles: &[&[f64]],
) -> Vec<[f64; 3]> {
    let l = chain.rod_length();
    times
        .windows(2)
        .zip(angles.windows(2))
        .map(|(t, a)| {
            let (r0, r1) = (report_tip(l, a[0]), report_tip(l, a[1]));
            let dt = t[1] - t[0];
            [t[1], (r1[0] - r0[0]) / dt, (r1[1] - r0[1]) / dt]
        })
        .collect()
}

/// The report's model as `y' = f(y)`, `y = [phi, w, W]`: `A phi'' = b`
/// assembled densely and solved by Cholesky in preallocated buffers (no
/// allocation per call; O(n^3), bounded by [`REPORT_MAX_LINKS`]).
#[derive(Clone, Debug)]
pub struct ReportSystem {
    chain: Chain,
    model: ReportModel,
    /// `mt_ij`, row-major.
    mt: Vec<f64>,
    q: Vec<f64>,
    a: Vec<f64>,
    b: Vec<f64>,
    y_shift: Vec<f64>,
    f_shift: Vec<f64>,
}

impl ReportSystem {
    /// The system of `chain` in `model` (call [`ReportModel::validate`] first).
    pub fn new(chain: &Chain, model: ReportModel) -> Self {
        let n = chain.links();
        let mut mt = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                mt[i * n + j] = model.mt(n, i, j);
            }
        }
        Self {
            chain: chain.clone(),
            model,
            mt,
            q: (0..n).map(|i| model.q(n, i)).collect(),
            a: vec![0.0; n * n],
            b: vec![0.0; n],
            y_shift: vec![0.0; 2 * n + 1],
            f_shift: vec![0.0; 2 * n + 1],
        }
    }

    /// The model it runs.
    pub fn model(&self) -> ReportModel {
        self.model
    }

    /// `acc = phi''` at `(phi, w)`; every entry NaN if the mass matrix is
    /// not positive definite (a non-finite angle).
    ///
    /// Each pair's `sin` and `cos` are taken once, for `j <= i`, and used for
    /// `(j, i)` too: `phi_j - phi_i` is exactly `-(phi_i - phi_j)`, and `cos`
    /// is even and `sin` odd bit for bit, so the entries are those of
    /// computing every pair (`the_pairs_taken_once_are_every_pair_bit_for_bit`);
    /// the trigonometry was 68% of a run (`perf`, `rm09-vmax-vs-span`). Row
    /// `j`'s centripetal sum still adds its terms in the order `k = 0 .. n`.
    pub fn accelerations(&mut self, phi: &[f64], w: &[f64], acc: &mut [f64]) {
        let n = phi.len();
        let g = self.model.gravity_rate(&self.chain);
        let gamma = self.model.sigma() * self.chain.damping_rate();
        // `b` holds each row's centripetal sum until the rows are done.
        self.b.fill(0.0);
        for i in 0..n {
            for j in 0..=i {
                let d = phi[i] - phi[j];
                let (sin, cos) = (d.sin(), d.cos());
                let m = self.mt[i * n + j];
                self.a[i * n + j] = m * cos;
                self.b[i] += m * sin * w[j] * w[j];
                if j < i {
                    let m = self.mt[j * n + i];
                    self.a[j * n + i] = m * cos;
                    self.b[j] += m * -sin * w[i] * w[i];
                }
            }
        }
        for i in 0..n {
            let centripetal = self.b[i];
            let mut stencil = 0.0;
            if i > 0 {
                stencil += w[i - 1] - w[i];
            }
            if i + 1 < n {
                stencil += w[i + 1] - w[i];
            }
            self.b[i] = -centripetal - g * self.q[i] * phi[i].cos() + gamma * stencil;
        }
        if cholesky_solve(&mut self.a, &mut self.b, n) {
            acc.copy_from_slice(&self.b);
        } else {
            acc.fill(f64::NAN);
        }
    }
}

/// Solves `A x = b` in place for a symmetric positive definite `A` (`n x n`,
/// row-major; overwritten by its Cholesky factor, `b` by `x`). False if a
/// pivot is not positive and finite.
fn cholesky_solve(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if !(d.is_finite() && d > 0.0) {
            return false;
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= a[i * n + k] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= a[k * n + i] * b[k];
        }
        b[i] = s / a[i * n + i];
    }
    true
}

impl OdeSystem for ReportSystem {
    fn dim(&self) -> usize {
        2 * self.chain.links() + 1
    }

    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.chain.links();
        let (phi, rest) = y.split_at(n);
        let w = &rest[..n];
        let (dphi, drest) = dy.split_at_mut(n);
        dphi.copy_from_slice(w);
        self.accelerations(phi, w, &mut drest[..n]);
        drest[n] = self.model.work_rate(&self.chain, w);
    }

    /// A forward difference of `rhs` (step `1e-7` relative): no method the
    /// report's model accepts calls it (`bdf` and `bdf-dense` are refused).
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        let norm = y.iter().fold(0.0f64, |m, x| m.max(x.abs())).max(1.0);
        let vnorm = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if vnorm == 0.0 {
            jv.fill(0.0);
            return;
        }
        let eps = 1e-7 * norm / vnorm;
        let mut y_shift = std::mem::take(&mut self.y_shift);
        let mut f_shift = std::mem::take(&mut self.f_shift);
        for i in 0..y.len() {
            y_shift[i] = y[i] + eps * v[i];
        }
        self.rhs(t, &y_shift, &mut f_shift);
        self.rhs(t, y, jv);
        for i in 0..y.len() {
            jv[i] = (f_shift[i] - jv[i]) / eps;
        }
        self.y_shift = y_shift;
        self.f_shift = f_shift;
    }
}

/// Runs with the explicit methods; it has no banded DAE (`bdf` is refused
/// before a run) and names no chain (`auto` is refused too).
impl Problem for ReportSystem {}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::ChainParams;

    /// The accelerations with every pair's `sin` and `cos` taken for
    /// `j < i` only are those of taking them for every pair (the loop as
    /// it was), bit for bit, in every model, on angles spread over many
    /// turns (so that `sin` and `cos` reduce their arguments) and all equal
    /// (the horizontal start: every difference a signed zero): the figures
    /// `rm*` read the same bytes. Using `sin` for `(j, i)` unnegated, or
    /// adding a row's terms out of order, fails.
    #[test]
    fn the_pairs_taken_once_are_every_pair_bit_for_bit() {
        let n = 23;
        let chain = Chain::new(ChainParams {
            links: n,
            damping: 2e-3,
            gravity: 1.3,
            ..ChainParams::default()
        })
        .unwrap();
        let models = [ReportModel::AS_CODED, ReportModel::CORRECTED];
        for (case, model) in models.into_iter().enumerate() {
            let mut sys = ReportSystem::new(&chain, model);
            for spread in [0.0, 0.3, 3.0, 40.0, 3e4] {
                let phi: Vec<f64> = (0..n)
                    .map(|i| (0.7 * i as f64 + case as f64).sin() * spread - 0.4)
                    .collect();
                let w: Vec<f64> = (0..n).map(|i| (1.3 * i as f64).cos() * 1.5).collect();
                let mut fast = vec![0.0; n];
                sys.accelerations(&phi, &w, &mut fast);
                // Every pair, row by row.
                let g = model.gravity_rate(&chain);
                let gamma = model.sigma() * chain.damping_rate();
                let (mut a, mut b) = (vec![0.0; n * n], vec![0.0; n]);
                for i in 0..n {
                    let mut centripetal = 0.0;
                    for j in 0..n {
                        let d = phi[i] - phi[j];
                        let m = sys.mt[i * n + j];
                        a[i * n + j] = m * d.cos();
                        centripetal += m * d.sin() * w[j] * w[j];
                    }
                    let mut stencil = 0.0;
                    if i > 0 {
                        stencil += w[i - 1] - w[i];
                    }
                    if i + 1 < n {
                        stencil += w[i + 1] - w[i];
                    }
                    b[i] = -centripetal - g * sys.q[i] * phi[i].cos() + gamma * stencil;
                }
                assert!(cholesky_solve(&mut a, &mut b, n));
                for i in 0..n {
                    assert_eq!(fast[i].to_bits(), b[i].to_bits(), "{model:?} {spread}: {i}");
                }
            }
        }
    }
}
