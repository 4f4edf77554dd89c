//! What a chain run records as it goes: output samples, the energy balance,
//! and the continuous maximum of the tip speed. One O(n) pass per step.

use crate::chain::Chain;
use crate::kinematics::{energy, tip_velocity, Vec2};
use crate::ode::{Observer, StepView};

/// Energy, tip velocity and tip acceleration of `y = [phi, w, W]` with
/// `f = y'`, fused into one pass over the rods.
pub(crate) struct Metrics {
    pub energy: f64,
    pub tip_velocity: Vec2,
    pub tip_acceleration: Vec2,
}

pub(crate) fn metrics(chain: &Chain, y: &[f64], f: &[f64]) -> Metrics {
    let n = chain.links;
    let (phi, w, acc) = (&y[..n], &y[n..2 * n], &f[n..2 * n]);
    let (mut jx, mut jy) = (0.0, 0.0);
    let (mut ax, mut ay) = (0.0, 0.0);
    let (mut twice_t, mut v) = (0.0, 0.0);
    for i in 0..n {
        let (s, c) = crate::scalar::sin_cos(phi[i]);
        let (wi, ai) = (w[i], acc[i]);
        let (nx, ny) = (-s * wi, c * wi);
        let (cx, cy) = (jx + 0.5 * nx, jy + 0.5 * ny);
        twice_t += cx * cx + cy * cy + wi * wi / 12.0;
        v += ((n - i) as f64 - 0.5) * s;
        jx += nx;
        jy += ny;
        ax += -ai * s - wi * wi * c;
        ay += ai * c - wi * wi * s;
    }
    let l = chain.rod_length();
    let ml2 = chain.mass * l * l;
    Metrics {
        energy: 0.5 * ml2 * twice_t + chain.mass * chain.gravity * l * v,
        tip_velocity: [l * jx, l * jy],
        tip_acceleration: [l * ax, l * ay],
    }
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
    dim: usize,
    output_dt: Option<f64>,
    t_origin: f64,
    next_sample: u64,
    pub times: Vec<f64>,
    pub states: Vec<f64>,
    pub energy_start: f64,
    pub energy_end: f64,
    pub energy_balance_error: f64,
    pub max_energy_rise: f64,
    pub tip_speed_max: f64,
    pub t_tip_speed_max: f64,
    /// The first time a recorded quantity (energy, balance, tip speed) was
    /// not finite, if one was: the run then ends `diverged` (see `solve`).
    pub t_nonfinite: Option<f64>,
    /// `d|v|^2/dt` at the last step's end.
    slope: f64,
    started: bool,
    buf: Vec<f64>,
}

impl ChainObserver {
    pub fn new(chain: &Chain, output_dt: Option<f64>) -> Self {
        let dim = 2 * chain.links + 1;
        Self {
            chain: chain.clone(),
            dim,
            output_dt,
            t_origin: 0.0,
            next_sample: 0,
            times: Vec::new(),
            states: Vec::new(),
            energy_start: 0.0,
            energy_end: 0.0,
            energy_balance_error: 0.0,
            max_energy_rise: 0.0,
            tip_speed_max: 0.0,
            t_tip_speed_max: 0.0,
            t_nonfinite: None,
            slope: 0.0,
            started: false,
            buf: vec![0.0; dim],
        }
    }

    /// Notes `t` as the first time something recorded was not finite.
    fn check_finite(&mut self, t: f64, values: &[f64]) {
        if self.t_nonfinite.is_none() && !values.iter().all(|v| v.is_finite()) {
            self.t_nonfinite = Some(t);
        }
    }

    fn record(&mut self, t: f64, y: &[f64]) {
        self.times.push(t);
        self.states.extend_from_slice(y);
    }

    /// Records the final state if the last sample is not already it.
    pub fn finish(&mut self, t: f64, y: &[f64]) {
        if !self.started {
            // The method stopped before its first right-hand side was finite:
            // the energies and the speed are the start's, from the state
            // alone (not the zeros the observer was made with).
            let n = self.chain.links;
            let (phi, w) = (&y[..n], &y[n..2 * n]);
            self.energy_start = energy(&self.chain, phi, w);
            self.energy_end = self.energy_start;
            let v = tip_velocity(&self.chain, phi, w);
            self.tip_speed_max = v[0].hypot(v[1]);
            self.t_tip_speed_max = t;
            self.check_finite(t, &[self.energy_start, self.tip_speed_max]);
        }
        if self.output_dt.is_some() && self.times.last().is_none_or(|&tl| tl < t) {
            self.record(t, y);
        }
    }

    fn speed_at(&mut self, step: &StepView<'_>, t: f64) -> f64 {
        step.interpolant.eval(t, &mut self.buf);
        let n = self.chain.links;
        let v = tip_velocity(&self.chain, &self.buf[..n], &self.buf[n..2 * n]);
        v[0].hypot(v[1])
    }

    /// Golden-section search for the interpolated speed's maximum in the step.
    fn refine_max(&mut self, step: &StepView<'_>) {
        const R: f64 = 0.618_033_988_749_895;
        let (mut a, mut b) = (step.t0, step.t1);
        let mut c = b - R * (b - a);
        let mut d = a + R * (b - a);
        let (mut fc, mut fd) = (self.speed_at(step, c), self.speed_at(step, d));
        while b - a > 1e-10 * (step.t1 - step.t0) + 1e-15 {
            if fc > fd {
                b = d;
                d = c;
                fd = fc;
                c = b - R * (b - a);
                fc = self.speed_at(step, c);
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + R * (b - a);
                fd = self.speed_at(step, d);
            }
        }
        let (t, v) = if fc > fd { (c, fc) } else { (d, fd) };
        if v > self.tip_speed_max || v.is_nan() {
            self.tip_speed_max = v;
            self.t_tip_speed_max = t;
        }
    }
}

impl Observer for ChainObserver {
    fn start(&mut self, t0: f64, y0: &[f64], f0: &[f64]) {
        debug_assert_eq!(y0.len(), self.dim);
        if self.started {
            // A continuation (auto switching method): the record goes on.
            return;
        }
        self.started = true;
        let m = metrics(&self.chain, y0, f0);
        self.t_origin = t0;
        self.energy_start = m.energy;
        self.energy_end = m.energy;
        self.tip_speed_max = m.tip_velocity[0].hypot(m.tip_velocity[1]);
        self.t_tip_speed_max = t0;
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
        let n = self.chain.links;
        let m = metrics(&self.chain, step.y1, step.f1);
        let dissipated = step.y1[2 * n];
        // NaN-propagating maxima: `f64::max` would drop a NaN and hide it.
        self.energy_balance_error = max_nan(
            self.energy_balance_error,
            (m.energy + dissipated - self.energy_start).abs(),
        );
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
            loop {
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
            }
        }
    }
}
