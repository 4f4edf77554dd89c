//! What a chain run records as it goes: output samples, the energy balance,
//! and the continuous maximum of the tip speed. One O(n) pass per step.

use super::{state_energy, state_len, state_tip_velocity};
use crate::chain::Chain;
use crate::elastic;
use crate::kinematics::{bending_energy, lever_arm, RodSums, Vec2};
use crate::ode::{Cancel, Observer, StepView};
use crate::pivot::PivotPath;
use crate::profile::Rods;
use crate::report::ReportModel;
use crate::scalar::Scalar;

/// Energy, tip velocity and tip acceleration of `y = [phi, w, W]` with
/// `f = y'`, fused into one pass over the rods.
/// The fraction of the energy scale plus the work done (its total
/// variation) that the energy balance error of a run with a prescribed
/// pivot motion may reach and still be `ok` (see
/// [`ChainObserver::balance_limit`]). Measured on `scenes/jerked-support.toml`
/// (energy scale 60) at its rtol 1e-8: a balance error of 2.2e-5 with
/// DOPRI5 and 1.2e-6 with DOP853, under 4e-7 of the scale; BDF stepping
/// over a jerk of `tau = 1e-6` leaves 5, 0.08 of it
/// (`simulate scenes/jerked-support.toml --json --method bdf --set
/// pivot.jerk_time=1e-6`).
pub const DRIVE_BALANCE_FRACTION: f64 = 0.01;

pub(crate) struct Metrics {
    pub energy: f64,
    pub tip_velocity: Vec2,
    pub tip_acceleration: Vec2,
}

///
/// `trig` is scratch for `(sin phi_i, cos phi_i)` (grown to `n` if shorter:
/// the observer sizes it once), computed in one pass that vectorises, as the
/// recursion's are ([`Scalar::sin_cos_all`], bit for bit the per-rod
/// [`crate::scalar::sin_cos`]).
pub(crate) fn metrics(chain: &Chain, y: &[f64], f: &[f64], trig: &mut Vec<(f64, f64)>) -> Metrics {
    if chain.is_elastic() {
        return Metrics {
            energy: elastic::energy(chain, y),
            tip_velocity: elastic::tip_velocity(chain, y),
            tip_acceleration: elastic::tip_acceleration(chain, y, f),
        };
    }
    if let Some(rods) = chain.rods() {
        return metrics_rods(chain, rods, y, f);
    }
    let n = chain.links();
    let (phi, w, acc) = (&y[..n], &y[n..2 * n], &f[n..2 * n]);
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
        let (wi, ai) = (w[i], acc[i]);
        sums.add(s, c, wi);
        v += lever_arm(n, i) * s;
        ax += -ai * s - wi * wi * c;
        ay += ai * c - wi * wi * s;
    }
    let l = chain.rod_length();
    // `T + V` as `kinematics::energy` states it; the products are kept in
    // the order the committed data were made with (`m l l`, then 1/2).
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
    Metrics {
        energy: if chain.bending_spring() != 0.0 {
            e + bending_energy(chain, phi)
        } else {
            e
        },
        tip_velocity: sums.tip_velocity(l),
        tip_acceleration: [l * ax, l * ay],
    }
}

/// [`metrics`] of a profiled chain (rod masses `mu_i m`, lengths
/// `lambda_i l`), in one pass; a tip mass and the bending springs add
/// their terms only when the chain has them.
fn metrics_rods(chain: &Chain, rods: &Rods, y: &[f64], f: &[f64]) -> Metrics {
    let n = chain.links();
    let (phi, w, acc) = (&y[..n], &y[n..2 * n], &f[n..2 * n]);
    let mut sums = RodSums::default();
    let (mut ax, mut ay) = (0.0, 0.0);
    let (mut joint, mut v) = (0.0, 0.0);
    for i in 0..n {
        let (s, c) = crate::scalar::sin_cos(phi[i]);
        let (wi, ai) = (w[i], acc[i]);
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
    if chain.bending_spring() != 0.0 {
        e += bending_energy(chain, phi);
    }
    Metrics {
        energy: e,
        tip_velocity: sums.tip_velocity(l),
        tip_acceleration: [l * ax, l * ay],
    }
}

/// [`metrics`] at `t` in the inertial frame of a moving pivot: its
/// velocity and acceleration added to the tip's, its energy terms to `E`.
/// A fixed pivot's are [`metrics`] exactly.
pub(crate) fn metrics_at(
    chain: &Chain,
    path: &PivotPath,
    t: f64,
    y: &[f64],
    f: &[f64],
    trig: &mut Vec<(f64, f64)>,
) -> Metrics {
    if chain.is_elastic() && !path.is_fixed() {
        return elastic_metrics_at(chain, t, y, f);
    }
    let mut m = metrics(chain, y, f, trig);
    if path.is_fixed() || chain.is_elastic() {
        return m;
    }
    let n = chain.links();
    let (phi, w, acc) = (&y[..n], &y[n..2 * n], &f[n..2 * n]);
    let frame = path.frame(chain, t, phi, w);
    let a0 = path.acceleration(chain, t, phi, w, acc);
    m.energy += frame.energy;
    let [v, a] = [frame.velocity, a0];
    m.tip_velocity = [m.tip_velocity[0] + v[0], m.tip_velocity[1] + v[1]];
    m.tip_acceleration = [m.tip_acceleration[0] + a[0], m.tip_acceleration[1] + a[1]];
    m
}

/// [`metrics`] of an elastic chain whose pivot moves or is let go, at `t`
/// in the inertial frame: the energy without joint 0's spring once let go,
/// and a driven pivot's frame terms, velocity and acceleration added.
fn elastic_metrics_at(chain: &Chain, t: f64, y: &[f64], f: &[f64]) -> Metrics {
    let mut m = Metrics {
        energy: super::elastic_energy_at(chain, t, y),
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

/// The larger of `a` and `b`, or NaN if either is NaN.
fn max_nan(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// Records a chain run.
pub(crate) struct ChainObserver {
    chain: Chain,
    /// Where the pivot is (`solve` notes the release in it).
    pub path: PivotPath,
    dim: usize,
    output_dt: Option<f64>,
    t_origin: f64,
    next_sample: u64,
    /// The index of the last sample the run can record (`t_end / output_dt`,
    /// plus one for rounding): the sampling loop never goes past it.
    last_sample: u64,
    pub times: Vec<f64>,
    pub states: Vec<f64>,
    pub energy_start: f64,
    pub energy_end: f64,
    pub energy_balance_error: f64,
    pub max_energy_rise: f64,
    pub tip_speed_max: f64,
    pub t_tip_speed_max: f64,
    /// Elastic links only: the largest `|F_1|` of the pivot at the start
    /// and at any step end (force units), and when; `(0, 0)` for rigid links.
    pub pivot_force_max: f64,
    pub t_pivot_force_max: f64,
    /// The first time a recorded quantity (energy, balance, tip speed) was
    /// not finite, if one was: the run then ends `diverged` (see `solve`).
    pub t_nonfinite: Option<f64>,
    /// The energy balance error above which a run is not a solution of the
    /// model: the chain's energy scale [`Chain::energy_scale`].
    balance_limit: f64,
    /// A driven pivot only: the total variation `sum |W_{k+1} - W_k|` of
    /// the work over the steps so far, the size of the work the drive and
    /// the friction did, against which the balance is judged
    /// ([`DRIVE_BALANCE_FRACTION`]).
    work_variation: f64,
    /// `W` at the last step's end.
    work_last: f64,
    /// Whether the pivot's motion is prescribed (the balance limit then
    /// follows the work done, see [`ChainObserver::balance_limit`]).
    driven: bool,
    /// The first time the energy balance error exceeded `balance_limit`, if
    /// it did: a run that would be `ok` then ends `inaccurate` (see `solve`).
    pub t_inaccurate: Option<f64>,
    /// Stops the run from outside.
    cancel: Option<Cancel>,
    /// `d|v|^2/dt` at the last step's end.
    slope: f64,
    started: bool,
    buf: Vec<f64>,
    /// Scratch of [`metrics`]: `(sin phi_i, cos phi_i)` of every rod.
    trig: Vec<(f64, f64)>,
    /// The report's model, whose own energy the balance checks (`None`:
    /// the chain's model).
    report: Option<ReportModel>,
}

impl ChainObserver {
    /// An observer of a run of `chain` over `[0, t_end]`, recording a sample
    /// every `output_dt` (time units) if given; `cancel` stops the run.
    pub fn new(chain: &Chain, t_end: f64, output_dt: Option<f64>, cancel: Option<Cancel>) -> Self {
        Self::with_path(
            chain,
            PivotPath::new(chain, [0.0, 0.0]),
            t_end,
            output_dt,
            cancel,
        )
    }

    /// [`ChainObserver::with_path`] with the end time, the sampling and
    /// the cancel flag of a run's `options`.
    pub(crate) fn for_run(chain: &Chain, path: PivotPath, options: &super::SolveOptions) -> Self {
        Self::with_path(
            chain,
            path,
            options.t_end,
            options.output_dt,
            options.cancel.clone(),
        )
    }

    /// [`ChainObserver::new`] with the pivot's `path`.
    pub fn with_path(
        chain: &Chain,
        path: PivotPath,
        t_end: f64,
        output_dt: Option<f64>,
        cancel: Option<Cancel>,
    ) -> Self {
        let dim = state_len(chain);
        // Saturating: `solve` has bounded t_end / output_dt already.
        let last_sample = output_dt.map_or(0, |dt| ((t_end / dt).floor() as u64).saturating_add(1));
        Self {
            chain: chain.clone(),
            path,
            dim,
            output_dt,
            t_origin: 0.0,
            next_sample: 0,
            last_sample,
            times: Vec::new(),
            states: Vec::new(),
            energy_start: 0.0,
            energy_end: 0.0,
            energy_balance_error: 0.0,
            max_energy_rise: 0.0,
            tip_speed_max: 0.0,
            t_tip_speed_max: 0.0,
            pivot_force_max: 0.0,
            t_pivot_force_max: 0.0,
            t_nonfinite: None,
            balance_limit: chain.energy_scale(),
            work_variation: 0.0,
            work_last: 0.0,
            driven: chain.pivot().is_driven(),
            t_inaccurate: None,
            cancel,
            slope: 0.0,
            started: false,
            buf: vec![0.0; dim],
            trig: vec![(0.0, 0.0); chain.links()],
            report: None,
        }
    }

    /// An observer of a run of the report's `model` of `chain`: the same
    /// record, with that model's energy and energy scale in the balance.
    pub fn for_report(
        chain: &Chain,
        model: ReportModel,
        t_end: f64,
        output_dt: Option<f64>,
        cancel: Option<Cancel>,
    ) -> Self {
        let mut obs = Self::new(chain, t_end, output_dt, cancel);
        obs.balance_limit = model.energy_scale(chain);
        obs.report = Some(model);
        obs
    }

    /// The energy of `y` in the observed model (`fused`: the chain's, from
    /// the one-pass [`metrics`]).
    fn energy_of(&self, y: &[f64], fused: f64) -> f64 {
        match self.report {
            None => fused,
            Some(model) => {
                let n = self.chain.links();
                model.energy(&self.chain, &y[..n], &y[n..2 * n])
            }
        }
    }

    /// Notes `t` as the first time something recorded was not finite.
    /// The energy balance error above which the run so far is not a
    /// solution of the model: the energy scale, and for a driven pivot at
    /// most [`DRIVE_BALANCE_FRACTION`] of the energy scale plus the work's
    /// total variation. A drive that is stepped over (a jerk shorter than
    /// the first step) leaves a balance error well under the energy scale
    /// but a large fraction of the little work the run saw; a resolved
    /// drive's error is many orders of magnitude smaller.
    pub(crate) fn balance_limit(&self) -> f64 {
        if self.driven {
            let drive = DRIVE_BALANCE_FRACTION * (self.balance_limit + self.work_variation);
            drive.min(self.balance_limit)
        } else {
            self.balance_limit
        }
    }

    fn check_finite(&mut self, t: f64, values: &[f64]) {
        if self.t_nonfinite.is_none() && !values.iter().all(|v| v.is_finite()) {
            self.t_nonfinite = Some(t);
        }
    }

    fn record(&mut self, t: f64, y: &[f64]) {
        self.times.push(t);
        self.states.extend_from_slice(y);
        // Progress for a caller watching from another thread (per sample).
        if let Some(c) = &self.cancel {
            c.report(t);
        }
    }

    /// Records the final state if the last sample is not already it.
    pub fn finish(&mut self, t: f64, y: &[f64]) {
        if !self.started {
            // The method stopped before its first right-hand side was finite:
            // the energies and the speed are the start's, from the state
            // alone (not the zeros the observer was made with).
            self.energy_start =
                self.energy_of(y, state_energy(&self.chain, y)) + self.frame_energy(t, y);
            self.energy_end = self.energy_start;
            let v = self.tip_velocity(t, y);
            self.tip_speed_max = v[0].hypot(v[1]);
            self.t_tip_speed_max = t;
            self.check_finite(t, &[self.energy_start, self.tip_speed_max]);
        }
        if self.output_dt.is_some() && self.times.last().is_none_or(|&tl| tl < t) {
            self.record(t, y);
        }
    }

    /// The moving pivot's energy terms at `t` (0 for a fixed one).
    fn frame_energy(&self, t: f64, y: &[f64]) -> f64 {
        if self.path.is_fixed() {
            return 0.0;
        }
        if self.chain.is_elastic() {
            return super::elastic_energy_at(&self.chain, t, y) - state_energy(&self.chain, y);
        }
        let n = self.chain.links();
        self.path
            .frame(&self.chain, t, &y[..n], &y[n..2 * n])
            .energy
    }

    /// The tip velocity at `t` in the inertial frame.
    fn tip_velocity(&self, t: f64, y: &[f64]) -> Vec2 {
        let v = state_tip_velocity(&self.chain, y);
        if self.path.is_fixed() {
            return v;
        }
        if self.chain.is_elastic() {
            let v0 = self.chain.pivot().drive(t)[1];
            return [v[0] + v0[0], v[1] + v0[1]];
        }
        let n = self.chain.links();
        let v0 = self.path.at(&self.chain, t, &y[..n], &y[n..2 * n])[1];
        [v[0] + v0[0], v[1] + v0[1]]
    }

    fn speed_at(&mut self, step: &StepView<'_>, t: f64) -> f64 {
        step.interpolant.eval(t, &mut self.buf);
        let buf = std::mem::take(&mut self.buf);
        let v = self.tip_velocity(t, &buf);
        self.buf = buf;
        v[0].hypot(v[1])
    }

    /// Elastic links: keeps the largest pivot force `|F_1|` of `y` at `t`
    /// (a NaN is kept, as the tip speed's is). Rigid links: nothing.
    fn note_pivot_force(&mut self, t: f64, y: &[f64]) {
        if self.chain.is_elastic() {
            let f = elastic::pivot_force_at(&self.chain, t, y);
            let f = f[0].hypot(f[1]);
            if f > self.pivot_force_max || f.is_nan() {
                self.pivot_force_max = f;
                self.t_pivot_force_max = t;
            }
        }
    }

    /// Golden-section search for the interpolated speed's maximum in the step.
    fn refine_max(&mut self, step: &StepView<'_>) {
        let tol = golden_width(step.t0, step.t1);
        let (t, v, _) = golden_max(step.t0, step.t1, tol, |t| self.speed_at(step, t));
        if v > self.tip_speed_max || v.is_nan() {
            self.tip_speed_max = v;
            self.t_tip_speed_max = t;
        }
    }
}

/// Iteration cap of [`golden_max`]: the width `1e-10 h + 1e-15` of
/// [`golden_width`] is reached within 48 iterations (`R^48 < 1e-10`) wherever
/// floats are dense enough to reach it, so the cap binds only where a
/// bracket stalls at one or two ulps of `t`.
pub(crate) const GOLDEN_MAX_ITERS: u32 = 100;

/// The spacing of floats at `|x|` (one ulp; `inf` for `inf` or the largest float).
fn ulp(x: f64) -> f64 {
    let x = x.abs();
    if x.is_finite() {
        f64::from_bits(x.to_bits() + 1) - x
    } else {
        x
    }
}

/// The width at which the maximum search in a step `[t0, t1]` (time units)
/// stops: `1e-10 h + 1e-15`, but never below the spacing of floats in the
/// step (one ulp of the smaller `|t|`), the narrowest bracket of distinct
/// times. Below `|t| = 8` that spacing is under `1e-15` and the width is
/// `1e-10 h + 1e-15` exactly; where it is not, the narrower width could
/// only be met by a bracket of zero width, and the search could stall.
pub(crate) fn golden_width(t0: f64, t1: f64) -> f64 {
    let width = 1e-10 * (t1 - t0) + 1e-15;
    width.max(ulp(t0.abs().min(t1.abs())))
}

/// Golden-section search for the maximum of `f` on `[t0, t1]`: narrows the
/// bracket until it is at most `tol` wide, or for [`GOLDEN_MAX_ITERS`]
/// iterations, whichever comes first. Returns the better inner point, its
/// value and the iterations taken. The point always lies in `[t0, t1]`.
pub(crate) fn golden_max(
    t0: f64,
    t1: f64,
    tol: f64,
    mut f: impl FnMut(f64) -> f64,
) -> (f64, f64, u32) {
    const R: f64 = 0.618_033_988_749_895;
    let (mut a, mut b) = (t0, t1);
    let mut c = b - R * (b - a);
    let mut d = a + R * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    let mut iterations = 0;
    while b - a > tol && iterations < GOLDEN_MAX_ITERS {
        if fc > fd {
            b = d;
            d = c;
            fd = fc;
            c = b - R * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + R * (b - a);
            fd = f(d);
        }
        iterations += 1;
    }
    let (t, v) = if fc > fd { (c, fc) } else { (d, fd) };
    (t.max(t0).min(t1), v, iterations)
}

impl Observer for ChainObserver {
    fn stop(&self) -> bool {
        self.cancel.as_ref().is_some_and(Cancel::is_cancelled)
    }

    fn start(&mut self, t0: f64, y0: &[f64], f0: &[f64]) {
        debug_assert_eq!(y0.len(), self.dim);
        if self.started {
            // A continuation (auto switching method): the record goes on.
            return;
        }
        self.started = true;
        let mut m = metrics_at(&self.chain, &self.path, t0, y0, f0, &mut self.trig);
        m.energy = self.energy_of(y0, m.energy);
        self.t_origin = t0;
        self.energy_start = m.energy;
        self.work_last = y0[2 * self.chain.links()];
        self.energy_end = m.energy;
        self.tip_speed_max = m.tip_velocity[0].hypot(m.tip_velocity[1]);
        self.t_tip_speed_max = t0;
        self.note_pivot_force(t0, y0);
        self.check_finite(t0, &[m.energy, self.tip_speed_max]);
        self.slope = 2.0
            * (m.tip_velocity[0] * m.tip_acceleration[0]
                + m.tip_velocity[1] * m.tip_acceleration[1]);
        if self.output_dt.is_some() {
            self.record(t0, y0);
            self.next_sample = 1;
        }
    }

    fn step(&mut self, step: &StepView<'_>) {
        let n = self.chain.links();
        let mut m = metrics_at(
            &self.chain,
            &self.path,
            step.t1,
            step.y1,
            step.f1,
            &mut self.trig,
        );
        m.energy = self.energy_of(step.y1, m.energy);
        let dissipated = step.y1[2 * n];
        // NaN-propagating maxima: `f64::max` would drop a NaN and hide it.
        self.energy_balance_error = max_nan(
            self.energy_balance_error,
            (m.energy + dissipated - self.energy_start).abs(),
        );
        if self.driven {
            self.work_variation += (dissipated - self.work_last).abs();
            self.work_last = dissipated;
        }
        if self.t_inaccurate.is_none() && self.energy_balance_error > self.balance_limit() {
            self.t_inaccurate = Some(step.t1);
        }
        self.max_energy_rise = max_nan(self.max_energy_rise, m.energy - self.energy_end);
        self.energy_end = m.energy;

        let speed = m.tip_velocity[0].hypot(m.tip_velocity[1]);
        let slope = 2.0
            * (m.tip_velocity[0] * m.tip_acceleration[0]
                + m.tip_velocity[1] * m.tip_acceleration[1]);
        if self.slope > 0.0 && slope < 0.0 {
            self.refine_max(step);
        }
        if speed > self.tip_speed_max || speed.is_nan() {
            self.tip_speed_max = speed;
            self.t_tip_speed_max = step.t1;
        }
        self.slope = slope;
        self.note_pivot_force(step.t1, step.y1);
        self.check_finite(
            step.t1,
            &[
                m.energy,
                self.energy_balance_error,
                self.max_energy_rise,
                self.tip_speed_max,
            ],
        );

        if let Some(dt) = self.output_dt {
            while self.next_sample <= self.last_sample {
                let ts = self.t_origin + self.next_sample as f64 * dt;
                if ts > step.t1 + 1e-9 * dt {
                    break;
                }
                if (ts - step.t1).abs() <= 1e-9 * dt {
                    self.times.push(step.t1);
                    self.states.extend_from_slice(step.y1);
                } else {
                    step.interpolant.eval(ts, &mut self.buf);
                    self.times.push(ts);
                    self.states.extend_from_slice(&self.buf);
                }
                self.next_sample += 1;
                // Progress for a caller watching from another thread.
                if let Some(c) = &self.cancel {
                    c.report(ts);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::sync::mpsc;
    use std::time::Duration;

    /// Runs `f` on its own thread and fails if it has not returned within
    /// `secs`: a liveness bound (a hang fails the test instead of the suite).
    fn within<T: Send + 'static>(secs: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
        let (tx, rx) = mpsc::channel();
        std::thread::spawn(move || {
            let _ = tx.send(f());
        });
        rx.recv_timeout(Duration::from_secs(secs))
            .expect("did not finish: a loop without a bound")
    }

    proptest! {
        /// Steps at any time up to 1e9 and of any length down to 1e-12 (far
        /// below one ulp of t there): the search ends by its width, not its
        /// cap, and the time it returns lies in the step and within the
        /// final width of the true maximum of a known interpolant (a
        /// parabola peaking at a known point of the step, or at an end).
        #[test]
        fn the_maximum_search_ends_and_brackets_the_maximum(
            t_exp in -3.0f64..9.0,
            h_exp in -12.0f64..0.0,
            frac in -0.2f64..1.2,
            curvature in 1e-3f64..1e3,
        ) {
            let t0 = 10f64.powf(t_exp);
            let t1 = t0 + 10f64.powf(h_exp);
            // The true maximum of f on [t0, t1]: the vertex, or the nearer end.
            let vertex = t0 + frac * (t1 - t0);
            let t_max = vertex.max(t0).min(t1);
            let tol = golden_width(t0, t1);
            let (t, v, iterations) = within(20, move || {
                golden_max(t0, t1, tol, |t| -curvature * (t - vertex) * (t - vertex))
            });
            prop_assert!(iterations < GOLDEN_MAX_ITERS, "{iterations} iterations");
            prop_assert!(t0 <= t && t <= t1, "{t} outside [{t0}, {t1}]");
            // The final bracket (at most tol wide, plus the rounding of its
            // inner points) holds the maximum.
            let ulp = f64::EPSILON * t1.abs();
            prop_assert!((t - t_max).abs() <= tol + 4.0 * ulp,
                "t = {t}, true maximum at {t_max}, tol {tol:e}");
            prop_assert!(v <= 0.0 && v.is_finite());
        }
    }

    #[test]
    fn the_width_never_falls_below_one_ulp_of_t() {
        for t in [1.0, 8.0, 1e3, 1e6, 1e9, 1e15] {
            let w = golden_width(t, t + 1e-12);
            // A bracket [t, t + w] holds two distinct floats.
            assert!(t + w > t, "t = {t}: {w:e}");
            assert!(w >= 1e-15, "t = {t}: {w:e}");
        }
        assert_eq!(golden_width(1e9, 1e9 + 1e-12), 1.1920928955078125e-7);
        // Below |t| = 8 the width is the step's 1e-10 plus 1e-15, exactly.
        for (t0, h) in [(0.0, 1e-9), (1.0, 0.01), (7.99, 1e-12), (-3.0, 1e-6)] {
            assert_eq!(golden_width(t0, t0 + h), 1e-10 * (t0 + h - t0) + 1e-15);
        }
    }

    #[test]
    fn the_search_stops_at_its_cap_when_the_width_cannot_be_reached() {
        // A negative width can never be reached (a bracket of floats at
        // t = 1e9 stalls at an ulp anyway): only the iteration cap ends it.
        let (t, _, iterations) = within(20, || {
            golden_max(1e9, 1e9 + 1e-3, -1.0, |t| -(t - 1e9 - 5e-4).powi(2))
        });
        assert_eq!(iterations, GOLDEN_MAX_ITERS);
        assert!((1e9..=1e9 + 1e-3).contains(&t));
        assert!((t - (1e9 + 5e-4)).abs() < 1e-6, "{t}");
    }

    #[test]
    fn the_sampling_loop_stops_at_the_last_sample_of_the_run() {
        let chain = Chain::report(2, 0.0).unwrap();
        let obs = ChainObserver::new(&chain, 1.0, Some(0.3), None);
        // Samples at 0, 0.3, 0.6, 0.9 (index 3), and one more for rounding.
        assert_eq!(obs.last_sample, 4);
        // Counts near the limits of u64 saturate instead of overflowing.
        let obs = ChainObserver::new(&chain, 1e300, Some(1e-300), None);
        assert_eq!(obs.last_sample, u64::MAX);
    }
}
