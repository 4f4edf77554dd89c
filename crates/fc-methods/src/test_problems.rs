//! What the integrators' tests share: a system made of closures with exact
//! call counters ([`Toy`]), problems with known solutions (as ODEs, and as
//! index-1 DAEs for the sparse BDF), observers that
//! record or probe a run, and the least-squares slope behind every order
//! measurement.

use super::integrator::{Settings, Span, TimeScales};
use super::{registry, Method};
use crate::nonsmooth::{Nonsmooth, Row, StepRecord};
use crate::ode::{
    BandedDae, Observer, OdeSystem, Outcome, Problem, SemiExplicitDae, Status, StepView,
};

type Rhs = Box<dyn Fn(f64, &[f64], &mut [f64])>;
type Jvp = Box<dyn Fn(f64, &[f64], &[f64], &mut [f64])>;

/// A small system given by closures, counting its own calls: a
/// [`Problem`] that every method runs through the registry, as the chain.
pub(crate) struct Toy {
    dim: usize,
    f: Rhs,
    j: Option<Jvp>,
    /// The same problem as an index-1 DAE, for the sparse BDF.
    dae: Option<KnownDae>,
    /// `y = [x, x']` of `x'' = a(t, x, x')`: a body of one coordinate and
    /// unit mass, for `moreau-jean` (no constraints).
    mechanical: bool,
    pub rhs_calls: u64,
    pub jvp_calls: u64,
}

/// A toy states itself as its [`KnownDae`], if it has one. The algebraic
/// unknowns of every test DAE are the last derivatives of the ODE (`z = y'`
/// or the acceleration `a = v'`), so the consistent start is `y0` followed
/// by the last entries of `f(t0, y0)`.
impl Problem for Toy {
    fn banded_dae(&self, t0: f64, y0: &[f64]) -> Option<BandedDae> {
        let dae = self.dae?;
        let mut f = vec![0.0; self.dim];
        (self.f)(t0, y0, &mut f);
        let algebraic = dae.dim - dae.differential_dim;
        let mut full = y0.to_vec();
        full.extend_from_slice(&f[self.dim - algebraic..]);
        Some(BandedDae {
            dae: Box::new(dae),
            y0: full,
        })
    }

    fn nonsmooth(&mut self) -> Option<&mut dyn Nonsmooth> {
        if self.mechanical {
            Some(self)
        } else {
            None
        }
    }
}

/// A mechanical toy (`Toy::with_mechanics`): one body of one coordinate
/// and unit mass, its force the toy's own acceleration (each a counted
/// right-hand side), no constraint rows.
impl Nonsmooth for Toy {
    fn bodies(&self) -> usize {
        1
    }
    fn body_dim(&self) -> usize {
        1
    }
    fn block_rows(&self) -> usize {
        1
    }
    fn inverse_mass(&self, out: &mut [f64]) {
        out.fill(1.0);
    }
    fn coordinates(&self, y: &[f64], q: &mut [f64], v: &mut [f64]) {
        q[0] = y[0];
        v[0] = y[1];
    }
    fn forces(&mut self, t: f64, q: &[f64], v: &[f64], f: &mut [f64]) {
        let mut dy = [0.0; 2];
        self.rhs(t, &[q[0], v[0]], &mut dy);
        f[0] = dy[1];
    }
    fn rows(&mut self, _t: f64, _q: &[f64], rows: &mut [Row]) {
        rows.fill(Row::OFF);
    }
    fn state(&mut self, step: &StepRecord<'_>, y: &mut [f64]) {
        y[0] = step.q[0];
        y[1] = step.v[0];
    }
}

impl OdeSystem for Toy {
    fn dim(&self) -> usize {
        self.dim
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.rhs_calls += 1;
        (self.f)(t, y, dy)
    }
    fn jvp(&mut self, t: f64, y: &[f64], v: &[f64], jv: &mut [f64]) {
        self.jvp_calls += 1;
        let j = self.j.as_ref().expect("this toy has no Jacobian");
        j(t, y, v, jv)
    }
}

/// `y' = f(t, y)` on `R^dim`, without a Jacobian (explicit methods only).
pub(crate) fn toy(dim: usize, f: impl Fn(f64, &[f64], &mut [f64]) + 'static) -> Toy {
    Toy {
        dim,
        f: Box::new(f),
        j: None,
        dae: None,
        mechanical: false,
        rhs_calls: 0,
        jvp_calls: 0,
    }
}

impl Toy {
    /// The same system with its Jacobian-vector product `jv = (df/dy) v`.
    pub fn with_jvp(mut self, j: impl Fn(f64, &[f64], &[f64], &mut [f64]) + 'static) -> Self {
        self.j = Some(Box::new(j));
        self
    }

    /// The same system, stating itself as `dae` for the sparse BDF.
    pub fn with_dae(mut self, dae: KnownDae) -> Self {
        self.dae = Some(dae);
        self
    }

    /// The same system (`y = [x, x']`), stating itself as a body of unit
    /// mass for `moreau-jean`.
    pub fn with_mechanics(mut self) -> Self {
        self.mechanical = true;
        self
    }
}

/// A problem with its exact solution `y(t)`.
pub(crate) struct Known {
    pub name: &'static str,
    pub system: fn() -> Toy,
    pub exact: fn(f64) -> Vec<f64>,
}

/// `x'' = -x`: `y = [x, v] = [cos t, -sin t]` (autonomous).
pub(crate) const OSCILLATOR: Known = Known {
    name: "x'' = -x",
    system: || {
        toy(2, |_t, y, dy| {
            dy[0] = y[1];
            dy[1] = -y[0];
        })
        .with_jvp(|_t, _y, v, jv| {
            jv[0] = v[1];
            jv[1] = -v[0];
        })
        .with_dae(OSCILLATOR_DAE)
        .with_mechanics()
    },
    exact: |t| vec![t.cos(), -t.sin()],
};

/// `y' = -2 t y`: `y = exp(-t^2)`. Non-autonomous, so the nodes `c_i` matter.
pub(crate) const GAUSSIAN: Known = Known {
    name: "y' = -2ty",
    system: || {
        toy(1, |t, y, dy| dy[0] = -2.0 * t * y[0])
            .with_jvp(|t, _y, v, jv| jv[0] = -2.0 * t * v[0])
            .with_dae(GAUSSIAN_DAE)
    },
    exact: |t| vec![(-t * t).exp()],
};

/// `x'' + x = cos 2t`, `x(0) = 1`, `x'(0) = 0`: `x = (4 cos t - cos 2t) / 3`.
/// `y = [x, x']`; non-autonomous, with an oscillation of its own.
pub(crate) const FORCED: Known = Known {
    name: "x'' + x = cos 2t",
    system: || {
        toy(2, |t, y, dy| {
            dy[0] = y[1];
            dy[1] = -y[0] + (2.0 * t).cos();
        })
        .with_jvp(|_t, _y, v, jv| {
            jv[0] = v[1];
            jv[1] = -v[0];
        })
        .with_dae(FORCED_DAE)
        .with_mechanics()
    },
    exact: |t| {
        vec![
            (4.0 * t.cos() - (2.0 * t).cos()) / 3.0,
            (-4.0 * t.sin() + 2.0 * (2.0 * t).sin()) / 3.0,
        ]
    },
};

/// Arenstorf's orbit (Hairer, Norsett & Wanner I, II.0): a satellite of the
/// Earth-Moon system in rotating coordinates, `y = [x1, x2, x1', x2']`.
pub(crate) mod arenstorf {
    use super::{toy, Toy};

    /// The Moon's share of the mass.
    pub const MU: f64 = 0.012277471;
    /// The period of the orbit from [`Y0`].
    pub const PERIOD: f64 = 17.065_216_560_157_96;
    /// The periodic orbit's start.
    pub const Y0: [f64; 4] = [0.994, 0.0, 0.0, -2.001_585_106_379_082_5];

    pub fn system() -> Toy {
        toy(4, |_t, y, dy| {
            let mu1 = 1.0 - MU;
            let d1 = ((y[0] + MU).powi(2) + y[1] * y[1]).powf(1.5);
            let d2 = ((y[0] - mu1).powi(2) + y[1] * y[1]).powf(1.5);
            dy[0] = y[2];
            dy[1] = y[3];
            dy[2] = y[0] + 2.0 * y[3] - mu1 * (y[0] + MU) / d1 - MU * (y[0] - mu1) / d2;
            dy[3] = y[1] - 2.0 * y[2] - mu1 * y[1] / d1 - MU * y[1] / d2;
        })
    }
}

/// Van der Pol's oscillator `x'' = mu (1 - x^2) x' - x`, `y = [x, x']`
/// (at `mu = 10`, with its DAE for the sparse BDF).
pub(crate) fn van_der_pol(mu: f64) -> Toy {
    let toy = toy(2, move |_t, y, dy| {
        dy[0] = y[1];
        dy[1] = mu * (1.0 - y[0] * y[0]) * y[1] - y[0];
    })
    .with_jvp(move |_t, y, v, jv| {
        jv[0] = v[1];
        jv[1] = (-2.0 * mu * y[0] * y[1] - 1.0) * v[0] + mu * (1.0 - y[0] * y[0]) * v[1];
    });
    if mu == 10.0 {
        toy.with_dae(VAN_DER_POL_DAE)
    } else {
        toy
    }
}

/// `y' = y^2`, `y(0) = 1`: `y = 1 / (1 - t)` leaves every bound at `t = 1`.
pub(crate) fn blow_up() -> Toy {
    toy(1, |_t, y, dy| dy[0] = y[0] * y[0])
        .with_jvp(|_t, y, v, jv| jv[0] = 2.0 * y[0] * v[0])
        .with_dae(BLOW_UP_DAE)
}

/// Eccentricity of the Kepler test orbit (`a = 1`, `mu = 1`, period `2 pi`).
pub(crate) const ECC: f64 = 0.5;

/// Kepler's problem: `y = [q, p]`, `q'' = -q / |q|^3`.
pub(crate) fn kepler() -> Toy {
    toy(4, |_t, y, dy| {
        let r3 = y[0].hypot(y[1]).powi(3);
        dy[0] = y[2];
        dy[1] = y[3];
        dy[2] = -y[0] / r3;
        dy[3] = -y[1] / r3;
    })
}

/// The orbit through periapsis `(1 - e, 0)` at `t = 0`, from Kepler's equation.
pub(crate) fn kepler_exact(t: f64) -> [f64; 4] {
    let mut ea = t + ECC * t.sin();
    for _ in 0..50 {
        ea -= (ea - ECC * ea.sin() - t) / (1.0 - ECC * ea.cos());
    }
    let (s, c) = ea.sin_cos();
    let b = (1.0 - ECC * ECC).sqrt();
    let den = 1.0 - ECC * c;
    [c - ECC, b * s, -s / den, b * c / den]
}

/// `y' = -1000 (y - cos t)`: stiff, `lambda = -1000`.
pub(crate) fn relaxation() -> Toy {
    toy(1, |t, y, dy| dy[0] = -1000.0 * (y[0] - t.cos()))
}

/// Runs `method` on `sys` from `(t0, y0)` to `t_end` through the registry,
/// as `solve` runs the chain: RK4 with the step `o.dt`, the others with
/// their tolerances, the sparse BDF on the toy's DAE. The work counters are
/// the toy's own count (the sparse BDF and gen-alpha count their DAE's calls too).
pub(crate) fn run(
    method: Method,
    sys: &mut Toy,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    o: &Settings,
    obs: &mut dyn Observer,
) -> Outcome {
    let span = Span {
        t0,
        y0,
        t_end,
        settings: o,
    };
    let run = registry::run(method, sys, &span, obs);
    let out = run.outcome;
    if run
        .segments
        .iter()
        .all(|s| !matches!(s.method, Method::Bdf | Method::GenAlpha))
    {
        assert_eq!(out.stats.rhs_evals, sys.rhs_calls, "{method}");
    }
    assert_eq!(
        run.segments.first().map(|s| s.t_start),
        Some(t0),
        "{method}"
    );
    assert_eq!(run.segments.last().map(|s| s.t_end), Some(out.t_reached));
    out
}

/// Runs the sparse BDF on `p`'s problem from its exact state at `t0`.
pub(crate) fn run_dae(
    p: &Known,
    t0: f64,
    t_end: f64,
    o: &Settings,
    obs: &mut dyn Observer,
) -> Outcome {
    run(
        Method::Bdf,
        &mut (p.system)(),
        t0,
        &(p.exact)(t0),
        t_end,
        o,
        obs,
    )
}

/// Every adaptive method (every registered one but RK4) from `(t0, y0)` to
/// `t_end`, quietly, each on a fresh `system()` through the registry.
pub(crate) fn every_adaptive(
    system: fn() -> Toy,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    o: &Settings,
) -> Vec<(Method, Outcome)> {
    Method::ALL
        .into_iter()
        .filter(|m| m.adaptive())
        .map(|m| (m, run(m, &mut system(), t0, y0, t_end, o, &mut Quiet)))
        .collect()
}

/// Settings of an adaptive run with these tolerances and a budget of 10^6.
pub(crate) fn options(rtol: f64, atol: f64) -> Settings {
    Settings {
        dt: 0.01,
        rtol,
        atol,
        h_min: 0.0,
        max_steps: 1_000_000,
        h0: None,
        scales: TimeScales::NONE,
        rho_inf: crate::DEFAULT_RHO_INF,
    }
}

/// Settings for one step of exactly `h` that is accepted whatever its error.
pub(crate) fn one_step(h: f64) -> Settings {
    Settings {
        h0: Some(h),
        ..options(0.5, 1e6)
    }
}

/// `max_i |a_i - b_i|`.
pub(crate) fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Least-squares slope of `log y` against `log x`.
pub(crate) fn slope(xy: &[(f64, f64)]) -> f64 {
    let n = xy.len() as f64;
    let (lx, ly): (Vec<f64>, Vec<f64>) = xy.iter().map(|(x, y)| (x.ln(), y.ln())).unzip();
    let (mx, my) = (lx.iter().sum::<f64>() / n, ly.iter().sum::<f64>() / n);
    let sxy: f64 = lx.iter().zip(&ly).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = lx.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

pub(crate) use super::testing::Quiet;

/// Evaluates every step's interpolant at the given times inside it.
#[derive(Default)]
pub(crate) struct Probe {
    pub times: Vec<f64>,
    pub values: Vec<(f64, Vec<f64>)>,
}

impl Observer for Probe {
    fn start(&mut self, _: f64, _: &[f64], _: &[f64]) {}
    fn step(&mut self, s: &StepView<'_>) {
        for &t in &self.times {
            if s.t0 <= t && t <= s.t1 {
                let mut out = vec![0.0; s.y0.len()];
                s.interpolant.eval(t, &mut out);
                self.values.push((t, out));
            }
        }
    }
}

/// Where a [`KnownDae`] writes its Jacobian's entries: `(row, column, value)`.
type Emit<'a> = &'a mut dyn FnMut(usize, usize, f64);

/// A semi-explicit index-1 DAE for the sparse BDF: a [`Toy`]'s problem with
/// its last derivatives as algebraic unknowns ([`Toy::with_dae`]).
#[derive(Clone, Copy)]
pub(crate) struct KnownDae {
    /// Number of unknowns.
    pub dim: usize,
    /// Number of differential unknowns (the first ones).
    pub differential_dim: usize,
    pub rhs: fn(f64, &[f64], &mut [f64]),
    /// The Jacobian's entries, always the same ones in the same order.
    pub jacobian: fn(f64, &[f64], Emit<'_>),
}

impl SemiExplicitDae for KnownDae {
    fn dim(&self) -> usize {
        self.dim
    }
    fn differential_dim(&self) -> usize {
        self.differential_dim
    }
    fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) {
        (self.rhs)(t, y, out)
    }
    fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
        (self.jacobian)(t, y, emit)
    }
}

/// `x' = v`, `v' = a`, `0 = a + x`: [`OSCILLATOR`] with the acceleration as
/// an algebraic unknown.
pub(crate) const OSCILLATOR_DAE: KnownDae = KnownDae {
    dim: 3,
    differential_dim: 2,
    rhs: |_t, y, out| {
        out[0] = y[1];
        out[1] = y[2];
        out[2] = y[2] + y[0];
    },
    jacobian: |_t, _y, emit| {
        emit(0, 1, 1.0);
        emit(1, 2, 1.0);
        emit(2, 0, 1.0);
        emit(2, 2, 1.0);
    },
};

/// `y' = z`, `0 = z + 2 t y`: [`GAUSSIAN`] with its derivative as an
/// algebraic unknown.
pub(crate) const GAUSSIAN_DAE: KnownDae = KnownDae {
    dim: 2,
    differential_dim: 1,
    rhs: |t, y, out| {
        out[0] = y[1];
        out[1] = y[1] + 2.0 * t * y[0];
    },
    jacobian: |t, _y, emit| {
        emit(0, 1, 1.0);
        emit(1, 0, 2.0 * t);
        emit(1, 1, 1.0);
    },
};

/// `x' = v`, `v' = a`, `0 = a + x - cos 2t`: [`FORCED`] with the
/// acceleration as an algebraic unknown.
pub(crate) const FORCED_DAE: KnownDae = KnownDae {
    dim: 3,
    differential_dim: 2,
    rhs: |t, y, out| {
        out[0] = y[1];
        out[1] = y[2];
        out[2] = y[2] + y[0] - (2.0 * t).cos();
    },
    jacobian: |_t, _y, emit| {
        emit(0, 1, 1.0);
        emit(1, 2, 1.0);
        emit(2, 0, 1.0);
        emit(2, 2, 1.0);
    },
};

/// Van der Pol as `x' = v`, `v' = a`, `0 = a - (mu (1 - x^2) v - x)` with
/// `mu = 10` (no closed form: `exact` only gives the start `(2, 0)`).
pub(crate) const VAN_DER_POL_DAE: KnownDae = KnownDae {
    dim: 3,
    differential_dim: 2,
    rhs: |_t, y, out| {
        out[0] = y[1];
        out[1] = y[2];
        out[2] = y[2] - (10.0 * (1.0 - y[0] * y[0]) * y[1] - y[0]);
    },
    jacobian: |_t, y, emit| {
        emit(0, 1, 1.0);
        emit(1, 2, 1.0);
        emit(2, 0, 20.0 * y[0] * y[1] + 1.0);
        emit(2, 1, -10.0 * (1.0 - y[0] * y[0]));
        emit(2, 2, 1.0);
    },
};

/// `y' = z`, `0 = z - y^2`, `y(0) = 1`: [`blow_up`] as a DAE, `y = 1 / (1 - t)`.
pub(crate) const BLOW_UP_DAE: KnownDae = KnownDae {
    dim: 2,
    differential_dim: 1,
    rhs: |_t, y, out| {
        out[0] = y[1];
        out[1] = y[1] - y[0] * y[0];
    },
    jacobian: |_t, y, emit| {
        emit(0, 1, 1.0);
        emit(1, 0, -2.0 * y[0]);
        emit(1, 1, 1.0);
    },
};

/// `y' = 1` while `y <= 1`, not finite past it (as `sqrt(1 - y)` is not):
/// the exact solution `y = t` leaves the domain of `f` at `t = 1`.
pub(crate) fn domain_exit() -> Toy {
    let f = |y: f64| 1.0 + 0.0 * (1.0 - y).sqrt();
    toy(1, move |_t, y, dy| dy[0] = f(y[0]))
        .with_jvp(|_t, y, v, jv| jv[0] = if y[0] <= 1.0 { 0.0 } else { f64::NAN } * v[0])
        .with_dae(DOMAIN_EXIT_DAE)
}

/// [`domain_exit`] as `y' = z`, `0 = z - 1 - 0 sqrt(1 - y)`.
pub(crate) const DOMAIN_EXIT_DAE: KnownDae = KnownDae {
    dim: 2,
    differential_dim: 1,
    rhs: |_t, y, out| {
        out[0] = y[1];
        out[1] = y[1] - 1.0 - 0.0 * (1.0 - y[0]).sqrt();
    },
    jacobian: |_t, y, emit| {
        emit(0, 1, 1.0);
        emit(1, 0, if y[0] <= 1.0 { 0.0 } else { f64::NAN });
        emit(1, 1, 1.0);
    },
};

/// Runs `run` on [`OSCILLATOR`] from its exact state at `t0 = 0` and at
/// `t0 = 1.5` to `t_end = 10`, watched by an [`ExactCheck`] of `f1`: each
/// run ends `ok` on `t_end` with its last step there and every step shown;
/// its end error and its interpolant's error (max norm) are below `tol`,
/// and the interpolant passes through each step's ends to 1e-12.
pub(crate) fn oscillator_dense_check(
    tol: f64,
    mut run: impl FnMut(&mut Toy, f64, &[f64], f64, &mut ExactCheck) -> Outcome,
) {
    for t0 in [0.0, 1.5] {
        let mut sys = (OSCILLATOR.system)();
        let mut obs = ExactCheck::new(OSCILLATOR.exact).with_rhs(|_t, y| vec![y[1], -y[0]]);
        let y0 = [f64::cos(t0), -f64::sin(t0)];
        let t_end = 10.0;
        let out = run(&mut sys, t0, &y0, t_end, &mut obs);
        assert_eq!(out.status, Status::Ok);
        assert_eq!(out.t_reached, t_end);
        assert_eq!(out.t_failed, None);
        assert_eq!(obs.starts, 1);
        assert_eq!(obs.t_last, t_end, "the last step lands on t_end");
        assert_eq!(obs.steps, out.stats.steps);
        let e = max_diff(&out.y_end, &[t_end.cos(), -t_end.sin()]);
        eprintln!(
            "oscillator t0 = {t0}: {} steps, end error {e:.1e}, dense {:.1e}, ends {:.1e}",
            out.stats.steps, obs.inside, obs.ends
        );
        assert!(e < tol, "end error {e:e}");
        assert!(obs.inside < tol, "dense error {:e}", obs.inside);
        assert!(obs.ends < 1e-12, "ends {:e}", obs.ends);
    }
}

/// `f(t, y)` as a value, for checking what a method reports as `f1`.
type RhsOf = fn(f64, &[f64]) -> Vec<f64>;

/// Checks a run step by step against the exact solution: the steps are
/// contiguous and forward, the interpolant passes through each step's ends
/// and follows the solution at 7 interior points, and (if given) `f1` is
/// `f(t1, y1)`.
pub(crate) struct ExactCheck {
    exact: fn(f64) -> Vec<f64>,
    rhs: Option<RhsOf>,
    pub starts: u32,
    pub steps: u64,
    pub t_last: f64,
    /// Largest error of the interpolant strictly inside a step.
    pub inside: f64,
    /// Largest error of the method's own values at step ends.
    pub nodes: f64,
    /// Largest gap between the interpolant at a step's ends and the step's values.
    pub ends: f64,
}

impl ExactCheck {
    pub fn new(exact: fn(f64) -> Vec<f64>) -> Self {
        Self {
            exact,
            rhs: None,
            starts: 0,
            steps: 0,
            t_last: f64::NAN,
            inside: 0.0,
            nodes: 0.0,
            ends: 0.0,
        }
    }

    /// Also checks every step's `f1` against `rhs(t1, y1)`, exactly.
    pub fn with_rhs(mut self, rhs: RhsOf) -> Self {
        self.rhs = Some(rhs);
        self
    }
}

impl Observer for ExactCheck {
    fn start(&mut self, t0: f64, _: &[f64], _: &[f64]) {
        self.starts += 1;
        self.t_last = t0;
    }
    fn step(&mut self, s: &StepView<'_>) {
        assert_eq!(s.t0, self.t_last, "steps are contiguous");
        assert!(s.t1 > s.t0);
        self.t_last = s.t1;
        self.steps += 1;
        let mut out = vec![0.0; s.y1.len()];
        for (t, y) in [(s.t0, s.y0), (s.t1, s.y1)] {
            s.interpolant.eval(t, &mut out);
            self.ends = self.ends.max(max_diff(&out, y));
        }
        self.nodes = self.nodes.max(max_diff(s.y1, &(self.exact)(s.t1)));
        for k in 1..8 {
            let t = s.t0 + (s.t1 - s.t0) * k as f64 / 8.0;
            s.interpolant.eval(t, &mut out);
            self.inside = self.inside.max(max_diff(&out, &(self.exact)(t)));
        }
        if let Some(rhs) = self.rhs {
            assert_eq!(s.f1, &rhs(s.t1, s.y1)[..], "f1 is f(t1, y1)");
        }
    }
}
