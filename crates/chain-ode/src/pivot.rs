//! How the pivot `P0` moves: held fixed (the default), moved along a
//! prescribed path `P0(t)`, and let go at a time `t_r` (`pivot.*` keys).
//!
//! A prescribed path is the sum of three motions, each zero by default,
//! with `P0(0)` the start's anchor:
//!
//! ```text
//! d(t) = a t^2 / 2                         constant acceleration a
//!      + A sin(Omega t)                    harmonic, amplitude A, angular frequency Omega
//!      + D s(t / tau),  s(u) = 10 u^3 - 15 u^4 + 6 u^5  (0 <= u <= 1)
//!                                          a smooth jerk: a move by D in time tau
//! ```
//!
//! The smooth jerk is the minimum-jerk move: its velocity and acceleration
//! are zero at both ends (`s'(0) = s'(1) = s''(0) = s''(1) = 0`), so the
//! pivot's acceleration is continuous. A run with a moving pivot is
//! non-autonomous: the right-hand side reads `t`. The pivot's acceleration
//! enters the recursion as the acceleration of joint 0
//! ([`crate::dynamics::Base::Driven`]); the power it puts in, `F_0 . P0'`,
//! is counted in the balance's work `W` (`W' = 2R - F_0 . P0'`), so that
//! `E + W = E(0)` still holds with the energy `E` of the inertial frame.
//!
//! Released at `t_r` (`pivot.release`), the pivot is a free end from then
//! on (`F_0 = 0`, [`crate::dynamics::Base::Free`]): no external force but
//! gravity acts, the centre of mass falls freely, and the pivot's position
//! is recovered from it, `P0 = c(t) - c_rel(phi)`, with
//! `c(t) = c_r + v_r (t - t_r) - g (t - t_r)^2 / 2 e_y` and
//! `c_rel = l sum_i (q_i + mu) u_i / (n + mu)` ([`PivotPath`]). The state stays
//! `[phi, w, W]`.

use crate::chain::{check, number_text, Chain};
use crate::kinematics::{lever_arm, Vec2};
use crate::scalar::sin_cos;
use fc_methods::InvalidParameter;
/// The step caps of a prescribed motion, as the integrators read them.
pub use fc_methods::TimeScales;

/// The pivot's motion, as given (every field in the chain's units).
/// The default is a fixed pivot: [`Pivot::is_fixed`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pivot {
    /// A constant acceleration `a` of `P0` (length / time^2).
    pub acceleration: Vec2,
    /// The amplitude `A` of a harmonic motion `A sin(Omega t)` (length).
    pub amplitude: Vec2,
    /// Its angular frequency `Omega` (rad / time, finite and >= 0; default 1).
    pub frequency: f64,
    /// The displacement `D` of a smooth jerk (length): `P0` moves by `D`
    /// over `jerk_time` along the minimum-jerk profile, from `t = 0`.
    pub jerk: Vec2,
    /// The duration `tau` of the smooth jerk (time, finite and > 0; default 1).
    pub jerk_time: f64,
    /// The time `t_r` (>= 0) at which the pivot is let go; `None`: never.
    /// `Some(0.0)` lets both ends go at `t = 0`.
    pub release: Option<f64>,
}

impl Default for Pivot {
    /// A fixed pivot.
    fn default() -> Self {
        Self {
            acceleration: [0.0, 0.0],
            amplitude: [0.0, 0.0],
            frequency: 1.0,
            jerk: [0.0, 0.0],
            jerk_time: 1.0,
            release: None,
        }
    }
}

/// `s(u), s'(u), s''(u)` of the minimum-jerk profile, `u` clamped to `[0, 1]`.
fn min_jerk(u: f64) -> [f64; 3] {
    if u <= 0.0 {
        [0.0, 0.0, 0.0]
    } else if u >= 1.0 {
        [1.0, 0.0, 0.0]
    } else {
        let v = 1.0 - u;
        [
            u * u * u * (10.0 - 15.0 * u + 6.0 * u * u),
            30.0 * u * u * v * v,
            60.0 * u * v * (1.0 - 2.0 * u),
        ]
    }
}

/// Steps per time scale of a prescribed motion that a step-size
/// controller must take at least: at most `tau / 16` during a smooth jerk of
/// duration `tau`, at most `T / 16` on a harmonic motion of period
/// `T = 2 pi / Omega` (see [`Pivot::time_scales`]).
pub const STEPS_PER_TIME_SCALE: f64 = 16.0;

impl Pivot {
    /// The time scales of the prescribed motion, as step caps: the smooth
    /// jerk's `tau / 16` up to `tau` (landed on), and a harmonic motion's
    /// `2 pi / (16 Omega)` throughout; [`TimeScales::NONE`] for a fixed pivot,
    /// a release alone or a constant acceleration (which has no time scale).
    pub fn time_scales(&self) -> TimeScales {
        let nz = |p: Vec2| p[0] != 0.0 || p[1] != 0.0;
        let harmonic = if nz(self.amplitude) && self.frequency > 0.0 {
            std::f64::consts::TAU / self.frequency / STEPS_PER_TIME_SCALE
        } else {
            f64::INFINITY
        };
        if nz(self.jerk) {
            TimeScales {
                max_step: (self.jerk_time / STEPS_PER_TIME_SCALE).min(harmonic),
                until: self.jerk_time,
                max_step_after: harmonic,
            }
        } else {
            TimeScales {
                max_step: harmonic,
                until: 0.0,
                max_step_after: harmonic,
            }
        }
    }

    /// True for a pivot that never moves: no prescribed motion, no release.
    /// A chain with a fixed pivot runs exactly the arithmetic it always ran.
    pub fn is_fixed(&self) -> bool {
        !self.is_driven() && self.release.is_none()
    }

    /// True when a prescribed motion is given (any of `a`, `A`, `D` nonzero).
    pub fn is_driven(&self) -> bool {
        let nz = |p: Vec2| p[0] != 0.0 || p[1] != 0.0;
        nz(self.acceleration) || nz(self.amplitude) || nz(self.jerk)
    }

    /// The scene key of the first motion given (`pivot.acceleration`,
    /// `pivot.amplitude`, `pivot.jerk`, `pivot.release`), `None` for a fixed pivot.
    pub fn first_given(&self) -> Option<&'static str> {
        let nz = |p: Vec2| p[0] != 0.0 || p[1] != 0.0;
        [
            (nz(self.acceleration), "pivot.acceleration"),
            (nz(self.amplitude), "pivot.amplitude"),
            (nz(self.jerk), "pivot.jerk"),
            (self.release.is_some(), "pivot.release"),
        ]
        .into_iter()
        .find_map(|(given, key)| given.then_some(key))
    }

    /// Whether the pivot is free at `t` (`t >= t_r`).
    pub fn released_at(&self, t: f64) -> bool {
        self.release.is_some_and(|tr| t >= tr)
    }

    /// The prescribed displacement, velocity and acceleration `d, d', d''`
    /// of `P0` at `t` (as if never released).
    pub fn drive(&self, t: f64) -> [Vec2; 3] {
        let [a, amp, dj] = [self.acceleration, self.amplitude, self.jerk];
        let (s, c) = sin_cos(self.frequency * t);
        let om = self.frequency;
        let [js, jv, ja] = min_jerk(t / self.jerk_time);
        let tau = self.jerk_time;
        let mut out = [[0.0; 2]; 3];
        for k in 0..2 {
            out[0][k] = 0.5 * a[k] * t * t + amp[k] * s + dj[k] * js;
            out[1][k] = a[k] * t + amp[k] * om * c + dj[k] * jv / tau;
            out[2][k] = a[k] - amp[k] * om * om * s + dj[k] * ja / (tau * tau);
        }
        out
    }

    /// The prescribed acceleration `P0''(t)`.
    pub fn acceleration_at(&self, t: f64) -> Vec2 {
        self.drive(t)[2]
    }

    /// Checks every field; the error names the first one out of range by
    /// its scene key (`pivot.*`). Called by [`Chain::new`].
    pub(crate) fn validate(&self) -> Result<(), InvalidParameter> {
        let finite = |p: Vec2| p.iter().all(|x| x.is_finite());
        let point = |p: Vec2| format!("[{}, {}]", number_text(p[0]), number_text(p[1]));
        check(
            finite(self.acceleration),
            "pivot.acceleration",
            "a pair of finite numbers",
            point(self.acceleration),
        )?;
        check(
            finite(self.amplitude),
            "pivot.amplitude",
            "a pair of finite numbers",
            point(self.amplitude),
        )?;
        check(
            self.frequency.is_finite() && self.frequency >= 0.0,
            "pivot.frequency",
            "a finite number >= 0",
            self.frequency,
        )?;
        check(
            finite(self.jerk),
            "pivot.jerk",
            "a pair of finite numbers",
            point(self.jerk),
        )?;
        check(
            self.jerk_time.is_finite() && self.jerk_time > 0.0,
            "pivot.jerk_time",
            "a finite number > 0",
            self.jerk_time,
        )?;
        if let Some(tr) = self.release {
            check(
                tr.is_finite() && tr >= 0.0,
                "pivot.release",
                "a finite time >= 0",
                tr,
            )?;
        }
        Ok(())
    }
}

/// The weight of rod `i`'s direction in the centre of mass, `q_i + mu`
/// (the mass beyond rod `i`'s centre, tip mass included, in rod masses and
/// lengths), for rods taken from the pivot down: `above` is the mass of
/// the rods before rod `i` (updated) and `total` their sum over all rods.
/// Unequal rods: `lambda_i (S_{i+1} + mu_i / 2 + mu_t)`,
/// `S_{i+1} = total - above - mu_i`.
#[inline(always)]
fn rod_weight(chain: &Chain, n: usize, i: usize, total: f64, above: &mut f64) -> f64 {
    let mu_t = chain.tip_mass_ratio();
    match chain.rods() {
        Some(r) => {
            let q = r.length[i] * ((total - *above - 0.5 * r.mass[i]) + mu_t);
            *above += r.mass[i];
            q
        }
        None => lever_arm(n, i) + mu_t,
    }
}

/// The rods' total mass in mean-rod masses (`n` to rounding; 0 for equal
/// rods, whose weights do not read it).
fn rods_total(chain: &Chain) -> f64 {
    chain.rods().map_or(0.0, |r| r.mass.iter().sum())
}

/// The centre of mass relative to `P0` and its velocity, `c_rel` and
/// `c_rel'` (tip mass included): `l sum_i (q_i + mu) u_i / (n + mu)` and
/// `l sum_i (q_i + mu) w_i v_i / (n + mu)`. O(n). Unequal rods weigh rod
/// `i`'s direction by `lambda_i (S_{i+1} + mu_i / 2 + mu)` (the mass beyond
/// its centre, `S_{i+1}` the rods' beyond it; `sum mu_i = n`).
pub fn centre_of_mass(chain: &Chain, phi: &[f64], w: &[f64]) -> [Vec2; 2] {
    let n = phi.len();
    let mu = chain.tip_mass_ratio();
    let k = chain.rod_length() / (n as f64 + mu);
    let (mut c, mut v) = ([0.0, 0.0], [0.0, 0.0]);
    let (total, mut above) = (rods_total(chain), 0.0);
    for i in 0..n {
        let (s, co) = sin_cos(phi[i]);
        let q = rod_weight(chain, n, i, total, &mut above);
        c[0] += q * co;
        c[1] += q * s;
        v[0] -= q * w[i] * s;
        v[1] += q * w[i] * co;
    }
    [[k * c[0], k * c[1]], [k * v[0], k * v[1]]]
}

/// Where the pivot is along a run: the start's anchor, the prescribed
/// motion, and, once released, the free fall of the centre of mass.
#[derive(Clone, Debug, PartialEq)]
pub struct PivotPath {
    /// `P0(0)`.
    pub anchor: Vec2,
    /// The motion as given.
    pub pivot: Pivot,
    /// Gravity `g` (along -y).
    gravity: f64,
    /// The centre of mass's position and velocity at the release, once the
    /// run has reached it.
    released: Option<(f64, Vec2, Vec2)>,
}

impl PivotPath {
    /// The path of `chain`'s pivot from `anchor`, not yet released.
    pub fn new(chain: &Chain, anchor: Vec2) -> Self {
        Self {
            anchor,
            pivot: *chain.pivot(),
            gravity: chain.gravity(),
            released: None,
        }
    }

    /// True when the pivot never moves.
    pub fn is_fixed(&self) -> bool {
        self.pivot.is_fixed()
    }

    /// Notes the release at `t` from the state `(phi, w)` there (the
    /// prescribed motion up to `t` places the pivot).
    pub fn release(&mut self, chain: &Chain, t: f64, phi: &[f64], w: &[f64]) {
        let [d, dv, _] = self.pivot.drive(t);
        let [c, v] = centre_of_mass(chain, phi, w);
        let p = [self.anchor[0] + d[0] + c[0], self.anchor[1] + d[1] + c[1]];
        self.released = Some((t, p, [dv[0] + v[0], dv[1] + v[1]]));
    }

    /// The pivot's position and velocity at `t` for the state `(phi, w)`:
    /// the anchor for a fixed pivot (no loop), `P0(t)` for a prescribed
    /// motion, and the free fall's for a released one (O(n)).
    pub fn at(&self, chain: &Chain, t: f64, phi: &[f64], w: &[f64]) -> [Vec2; 2] {
        if self.pivot.is_fixed() {
            return [self.anchor, [0.0, 0.0]];
        }
        match self.released {
            Some((tr, c, v)) if self.pivot.released_at(t) => {
                let s = t - tr;
                let cc = [
                    c[0] + v[0] * s,
                    c[1] + v[1] * s - 0.5 * self.gravity * s * s,
                ];
                let vc = [v[0], v[1] - self.gravity * s];
                let [cr, vr] = centre_of_mass(chain, phi, w);
                [
                    [cc[0] - cr[0], cc[1] - cr[1]],
                    [vc[0] - vr[0], vc[1] - vr[1]],
                ]
            }
            _ => {
                let [d, dv, _] = self.pivot.drive(t);
                [[self.anchor[0] + d[0], self.anchor[1] + d[1]], dv]
            }
        }
    }
}

/// The centre of mass's acceleration relative to `P0`,
/// `c_rel'' = l sum_i (q_i + mu) (alpha_i v_i - w_i^2 u_i) / (n + mu)`
/// (unequal rods' weights as in [`centre_of_mass`]). O(n).
pub fn centre_of_mass_acceleration(chain: &Chain, phi: &[f64], w: &[f64], alpha: &[f64]) -> Vec2 {
    let n = phi.len();
    let mu = chain.tip_mass_ratio();
    let k = chain.rod_length() / (n as f64 + mu);
    let mut a = [0.0, 0.0];
    let (total, mut above) = (rods_total(chain), 0.0);
    for i in 0..n {
        let (s, c) = sin_cos(phi[i]);
        let q = rod_weight(chain, n, i, total, &mut above);
        let w2 = w[i] * w[i];
        a[0] += q * (-alpha[i] * s - w2 * c);
        a[1] += q * (alpha[i] * c - w2 * s);
    }
    [k * a[0], k * a[1]]
}

/// What a moving pivot adds to a state's kinematics and energy at `t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// `P0(t)`.
    pub position: Vec2,
    /// `P0'(t)`.
    pub velocity: Vec2,
    /// The energy the pivot's motion adds to `T + V` measured from a fixed
    /// pivot at the anchor: `M_tot (V0 . c_rel' + |V0|^2 / 2 + g (P0_y - anchor_y))`,
    /// `M_tot = n m + M_t`.
    pub energy: f64,
}

impl PivotPath {
    /// The pivot's position, velocity and energy terms at `t` for `(phi, w)`.
    pub fn frame(&self, chain: &Chain, t: f64, phi: &[f64], w: &[f64]) -> Frame {
        let [p, v] = self.at(chain, t, phi, w);
        if self.is_fixed() {
            return Frame {
                position: p,
                velocity: v,
                energy: 0.0,
            };
        }
        let [_, vc] = centre_of_mass(chain, phi, w);
        let m_tot = chain.total_mass() + chain.tip_mass();
        let energy = m_tot
            * ((v[0] * vc[0] + v[1] * vc[1])
                + 0.5 * (v[0] * v[0] + v[1] * v[1])
                + chain.gravity() * (p[1] - self.anchor[1]));
        Frame {
            position: p,
            velocity: v,
            energy,
        }
    }

    /// The pivot's acceleration `P0''` at `t` for the state `(phi, w)` and
    /// its angular accelerations `alpha`: zero, the prescribed one, or, once
    /// released, `(0, -g) - c_rel''` (the centre of mass falls freely).
    pub fn acceleration(
        &self,
        chain: &Chain,
        t: f64,
        phi: &[f64],
        w: &[f64],
        alpha: &[f64],
    ) -> Vec2 {
        if self.is_fixed() {
            return [0.0, 0.0];
        }
        if self.released.is_some() && self.pivot.released_at(t) {
            let a = centre_of_mass_acceleration(chain, phi, w, alpha);
            [-a[0], -self.gravity - a[1]]
        } else {
            self.pivot.acceleration_at(t)
        }
    }

    /// True once `t` is past the release (the release noted).
    pub fn is_free_at(&self, t: f64) -> bool {
        self.released.is_some() && self.pivot.released_at(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth jerk caps the step at `tau / 16` up to `tau` and not past
    /// it; a harmonic drive at a sixteenth of its period throughout, and
    /// the jerk's cap never exceeds it; a constant acceleration, a release
    /// or a fixed pivot caps nothing.
    #[test]
    fn the_caps_follow_the_time_scales_the_user_set() {
        let jerk = Pivot {
            jerk: [1.0, 0.0],
            jerk_time: 0.32,
            ..Pivot::default()
        };
        let s = jerk.time_scales();
        assert_eq!((s.max_step_at(0.0), s.max_step_at(0.31)), (0.02, 0.02));
        assert_eq!(s.max_step_at(0.32), f64::INFINITY);
        assert_eq!((s.until, s.smallest()), (0.32, 0.02));

        let omega = 2.0;
        let period = std::f64::consts::TAU / omega;
        let both = Pivot {
            amplitude: [0.0, 0.1],
            frequency: omega,
            jerk_time: 100.0,
            ..jerk
        };
        let s = both.time_scales();
        assert_eq!(s.max_step_at(0.0), period / 16.0);
        assert_eq!(s.max_step_at(1e3), period / 16.0);

        for quiet in [
            Pivot::default(),
            Pivot {
                acceleration: [0.0, -3.0],
                release: Some(0.5),
                ..Pivot::default()
            },
            Pivot {
                amplitude: [0.0, 0.1],
                frequency: 0.0,
                ..Pivot::default()
            },
        ] {
            assert_eq!(quiet.time_scales(), TimeScales::NONE);
            assert_eq!(quiet.time_scales().smallest(), f64::INFINITY);
        }
    }
}
