//! Quantities derived from finished runs, and the closed forms the model is
//! validated against: the continuum refinement of a chain, the pivot force
//! along a trajectory, level crossings of the tip, the folded chain's
//! energy-conserving law and the Bessel-zero frequencies of the hanging
//! chain.

use crate::chain::Chain;
use crate::kinematics::Vec2;
use crate::model::Model;
use crate::solve::Trajectory;
use crate::system::ChainSystem;
use fc_methods::InvalidParameter;

/// The first zeros `j_{0,k}` of the Bessel function `J0`.
pub const J0_ZEROS: [f64; 5] = [
    2.404_825_557_695_773,
    5.520_078_110_286_311,
    8.653_727_912_911_013,
    11.791_534_439_014_281,
    14.930_917_708_487_787,
];

/// The continuum frequencies of the hanging chain, `omega_k = (j_{0,k}/2) sqrt(g/L)`.
pub fn bessel_frequencies(chain: &Chain) -> [f64; 5] {
    let s = (chain.gravity() / chain.length()).sqrt();
    J0_ZEROS.map(|j| 0.5 * j * s)
}

/// The same continuous chain cut into `links` rods, at fixed total mass
/// and bending viscosity: [`Chain::refined`], the one refinement (its
/// documentation derives it). Every other field is carried.
pub fn refined(chain: &Chain, links: usize) -> Result<Chain, InvalidParameter> {
    chain.refined(links)
}

/// The continuum bending viscosity `eta = r l` of a chain
/// ([`Chain::bending_viscosity`]).
pub fn bending_viscosity(chain: &Chain) -> f64 {
    chain.bending_viscosity()
}

/// The force of the pivot on rod 1 (physical units) in the state
/// `(angles, rates)`, from the O(n) recursion.
pub fn pivot_force(sys: &mut ChainSystem, angles: &[f64], rates: &[f64]) -> Vec2 {
    let y = ChainSystem::pack(angles, rates, 0.0);
    let mut dy = vec![0.0; y.len()];
    sys.rhs_with_reactions(&y, &mut dy).pivot_force
}

/// `(t, pivot force on rod 1)` at every sample of `traj`: the recursion's
/// for rigid links (with a moving pivot, at its acceleration at `t`; zero
/// once released), the pivot spring's for elastic ones.
pub fn pivot_forces<M: Model>(traj: &Trajectory<M>) -> Vec<(f64, Vec2)> {
    (0..traj.len())
        .map(|k| (traj.times[k], traj.support_force(k)))
        .collect()
}

/// The tip's position and velocity at every sample: `(t, tip, v_tip)`, for
/// either model (`Trajectory::tip`, `Trajectory::tip_velocity`).
pub fn tip_track<M: Model>(traj: &Trajectory<M>) -> Vec<(f64, Vec2, Vec2)> {
    traj.samples()
        .enumerate()
        .map(|(k, s)| (s.t, traj.tip(k), traj.tip_velocity(k)))
        .collect()
}

/// The first time the tip's height falls to `level`, or `None`.
///
/// Between two samples the height is the cubic Hermite interpolant of the
/// sampled heights and exact vertical velocities (error `O(dt^4)` for sample
/// spacing `dt`); the crossing is located in it by bisection.
pub fn first_time_below(track: &[(f64, Vec2, Vec2)], level: f64) -> Option<f64> {
    for w in track.windows(2) {
        let (t0, p0, v0) = w[0];
        let (t1, p1, v1) = w[1];
        if p0[1] < level {
            return Some(t0);
        }
        let h = t1 - t0;
        let y = |t: f64| {
            let s = (t - t0) / h;
            let (s2, s3) = (s * s, s * s * s);
            (2.0 * s3 - 3.0 * s2 + 1.0) * p0[1]
                + (s3 - 2.0 * s2 + s) * h * v0[1]
                + (-2.0 * s3 + 3.0 * s2) * p1[1]
                + (s3 - s2) * h * v1[1]
        };
        // The interpolant may dip below the level inside the step even if the
        // end point does not: check a few interior points.
        let mut lo = t0;
        let mut hit = None;
        for k in 1..=8 {
            let t = t0 + h * k as f64 / 8.0;
            if y(t) < level {
                hit = Some(t);
                break;
            }
            lo = t;
        }
        if let Some(mut hi) = hit {
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if y(mid) < level {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
    }
    None
}

/// The energy-conserving law of the folded chain (Calkin & March 1989) for
/// a chain of length `L` whose free end is released at the pivot's height:
/// the free end, fallen by `x`, moves at `v^2 = g x (2L - x) / (L - x)`.
pub mod folded_law {
    /// Tip speed after a fall `x` (`0 <= x < L`).
    pub fn speed(x: f64, length: f64, gravity: f64) -> f64 {
        (gravity * x * (2.0 * length - x) / (length - x)).sqrt()
    }

    /// Free fall: `sqrt(2 g x)`.
    pub fn free_fall_speed(x: f64, gravity: f64) -> f64 {
        (2.0 * gravity * x).sqrt()
    }

    /// The time to fall `x` (`0 <= x <= L`), `t = integral dx / v`.
    ///
    /// With `x = L sin^2(theta)` the integrand is smooth and analytic:
    /// `t = sqrt(L/g) * integral_0^asin(sqrt(x/L)) 2 cos^2(theta) / sqrt(2 - sin^2(theta)) dtheta`,
    /// evaluated by composite Gauss–Legendre (5 points, 200 panels): to rounding.
    pub fn time(x: f64, length: f64, gravity: f64) -> f64 {
        let top = (x / length).clamp(0.0, 1.0).sqrt().asin();
        let f = |th: f64| {
            let (s, c) = th.sin_cos();
            2.0 * c * c / (2.0 - s * s).sqrt()
        };
        const NODES: [f64; 5] = [
            0.0,
            -0.538_469_310_105_683_1,
            0.538_469_310_105_683_1,
            -0.906_179_845_938_664,
            0.906_179_845_938_664,
        ];
        const WEIGHTS: [f64; 5] = [
            0.568_888_888_888_888_9,
            0.478_628_670_499_366_5,
            0.478_628_670_499_366_5,
            0.236_926_885_056_189_1,
            0.236_926_885_056_189_1,
        ];
        let panels = 200;
        let h = top / panels as f64;
        let mut sum = 0.0;
        for p in 0..panels {
            let mid = (p as f64 + 0.5) * h;
            for (z, w) in NODES.iter().zip(WEIGHTS) {
                sum += w * f(mid + 0.5 * h * z);
            }
        }
        0.5 * h * sum * (length / gravity).sqrt()
    }

    /// The support force on the pivot in units of the weight `M g`, after a
    /// fall `x = xi L`: `(2 + 2 xi - 3 xi^2) / (4 (1 - xi))`.
    pub fn support_force(xi: f64) -> f64 {
        (2.0 + 2.0 * xi - 3.0 * xi * xi) / (4.0 * (1.0 - xi))
    }
}

/// Cayley's scale read over windows (issue 50): the floor's force on a
/// chain let go at the top with its lower end on the floor, averaged over
/// each window `[t_j − half, t_j + half]`, over the ideal's average there,
/// `3 mu g (g/2)(t_j² + half²/3)` (`mu = M / L`: the force `3 mu g x` of
/// the landed length `x = g t²/2`; `docs/model.md`, "The floor"). The
/// average comes from the momentum, `F = dP_y/dt + M g`, exact while the
/// floor and gravity are the only forces on the chain.
#[derive(Clone, Debug, PartialEq)]
pub struct ScaleReading {
    /// `(t_j, reading_j)`.
    pub windows: Vec<(f64, f64)>,
    /// The readings' mean.
    pub mean: f64,
    /// Their sample standard deviation: the window scatter.
    pub scatter: f64,
}

/// The window centres of issue 50's reading: `t = 0.3, 0.35, .., 1.2`
/// (19 windows of half width [`SCALE_HALF_WINDOW`], units of
/// `sqrt(L / g)`), before the ideal chain's last rod lands at `sqrt(2)`.
pub fn scale_windows() -> Vec<f64> {
    (0..19).map(|j| 0.3 + 0.05 * j as f64).collect()
}

/// Half a window of [`scale_windows`]: the windows tile `[0.275, 1.225]`.
pub const SCALE_HALF_WINDOW: f64 = 0.025;

/// The scale's reading of `traj` over the windows centred at `centres`
/// (units of `sqrt(L / g)`) of half width `half`, from its samples at the
/// windows' edges (which must be samples of the run); an error names the
/// first edge that is not.
pub fn scale_reading<M: Model>(
    traj: &Trajectory<M>,
    centres: &[f64],
    half: f64,
) -> Result<ScaleReading, String> {
    let chain = traj.model.chain().ok_or("a chain's run")?;
    let (l, g) = (chain.length(), chain.gravity());
    let mass = chain.total_mass() + chain.tip_mass();
    let mu = mass / l;
    let scale = (l / g).sqrt();
    let at = |t: f64| {
        traj.times
            .iter()
            .position(|&s| (s - t).abs() <= 1e-9 * t.abs().max(1.0))
            .ok_or_else(|| format!("no sample at t = {t}"))
    };
    let mut windows = Vec::with_capacity(centres.len());
    for &c in centres {
        let (tc, d) = (c * scale, half * scale);
        let (lo, hi) = (at(tc - d)?, at(tc + d)?);
        let force = (traj.momentum(hi)[1] - traj.momentum(lo)[1]) / (2.0 * d) + mass * g;
        let ideal = 3.0 * mu * g * 0.5 * g * (tc * tc + d * d / 3.0);
        windows.push((c, force / ideal));
    }
    let k = windows.len() as f64;
    let mean = windows.iter().map(|w| w.1).sum::<f64>() / k;
    let var = windows.iter().map(|w| (w.1 - mean).powi(2)).sum::<f64>() / (k - 1.0).max(1.0);
    Ok(ScaleReading {
        windows,
        mean,
        scatter: var.sqrt(),
    })
}

/// Cayley's reading of a run with a floor, over windows of the user's
/// width (`docs/model.md`, "The floor's reading"): at each sample `t_k`
/// whose window `[t_k - w/2, t_k + w/2]` lies in the run, the floor's
/// normal force averaged over the window, `F`, over `3 mu g x`, `x` the
/// landed length averaged over the same window (`mu = M / L`, `M` with the
/// tip mass). `F` comes from the momentum balance where that is exact
/// (the pivot let go before the window and no force but gravity and the
/// floor's on the chain: `F = n . (P(hi) - P(lo)) / (t_hi - t_lo) + M g
/// n_y`, whatever the contact's impulses between the samples), otherwise
/// from the sampled floor force by the trapezoid rule (then only as good as
/// the sampling: `from_momentum` says which). A window whose mean landed
/// length is zero has no reading and is left out.
#[derive(Clone, Debug, PartialEq)]
pub struct FloorReading {
    /// The windows' centres (samples of the run).
    pub t: Vec<f64>,
    /// The mean normal force over each window (force units).
    pub force: Vec<f64>,
    /// The mean landed length over each window (length units).
    pub landed_length: Vec<f64>,
    /// `force / (3 mu g landed_length)`: 1 for Cayley's ideal chain.
    pub reading: Vec<f64>,
    /// True where `force` is the momentum balance's (exact).
    pub from_momentum: Vec<bool>,
}

/// What [`floor_reading_of`] reads, per sample: the times, the chain's
/// momentum, the floor's total force and the landed length.
#[derive(Clone, Copy, Debug)]
pub struct FloorSamples<'a> {
    pub times: &'a [f64],
    pub momentum: &'a [Vec2],
    pub floor_force: &'a [Vec2],
    pub landed_length: &'a [f64],
}

/// [`FloorReading`] of `chain`'s run on a floor of slope `angle`, from its
/// samples, over windows of width `window` (time units, at least one
/// sample spacing, at most the run). An error names `window` and its range.
pub fn floor_reading_of(
    chain: &Chain,
    angle: f64,
    s: FloorSamples<'_>,
    window: f64,
) -> Result<FloorReading, String> {
    let k = s.times.len();
    let span = match (s.times.first(), s.times.last()) {
        (Some(a), Some(b)) if k >= 2 => b - a,
        _ => return Err("the run has fewer than two samples".to_string()),
    };
    let spacing = s.times.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max);
    if !(window.is_finite() && window >= (1.0 - 1e-9) * spacing && window <= span) {
        return Err(format!(
            "window must be in [{spacing}, {span}] (one output spacing to the run; got {window})"
        ));
    }
    let (g, l) = (chain.gravity(), chain.length());
    let mass = chain.total_mass() + chain.tip_mass();
    let normal = [-angle.sin(), angle.cos()];
    let dot = |f: Vec2| normal[0] * f[0] + normal[1] * f[1];
    let free_from = match chain.pivot().release {
        Some(tr)
            if crate::load::Loads::of(chain, crate::load::Units::Physical)
                .drag
                .is_none() =>
        {
            tr
        }
        _ => f64::INFINITY,
    };
    let eps = 1e-9 * span;
    // The sample nearest `t`.
    let near = |t: f64| match s.times.binary_search_by(|x| x.total_cmp(&t)) {
        Ok(i) => i,
        Err(0) => 0,
        Err(i) if i >= k => k - 1,
        Err(i) => {
            if t - s.times[i - 1] <= s.times[i] - t {
                i - 1
            } else {
                i
            }
        }
    };
    let trapezoid = |v: &dyn Fn(usize) -> f64, lo: usize, hi: usize| -> f64 {
        (lo..hi)
            .map(|j| 0.5 * (v(j) + v(j + 1)) * (s.times[j + 1] - s.times[j]))
            .sum::<f64>()
            / (s.times[hi] - s.times[lo])
    };
    let mut out = FloorReading {
        t: Vec::new(),
        force: Vec::new(),
        landed_length: Vec::new(),
        reading: Vec::new(),
        from_momentum: Vec::new(),
    };
    for (c, &t) in s.times.iter().enumerate() {
        let (a, b) = (t - 0.5 * window, t + 0.5 * window);
        if a < s.times[0] - eps || b > s.times[k - 1] + eps {
            continue;
        }
        let (lo, hi) = (near(a), near(b));
        if hi <= lo {
            continue;
        }
        let dt = s.times[hi] - s.times[lo];
        let exact = s.times[lo] >= free_from;
        let force = if exact {
            let (p, q) = (s.momentum[lo], s.momentum[hi]);
            dot([(q[0] - p[0]) / dt, (q[1] - p[1]) / dt + mass * g])
        } else {
            trapezoid(&|j| dot(s.floor_force[j]), lo, hi)
        };
        let x = trapezoid(&|j| s.landed_length[j], lo, hi);
        if x <= 0.0 {
            continue;
        }
        out.t.push(s.times[c]);
        out.force.push(force);
        out.landed_length.push(x);
        out.reading.push(force / (3.0 * (mass / l) * g * x));
        out.from_momentum.push(exact);
    }
    Ok(out)
}

/// [`floor_reading_of`] of `traj`'s samples; `None` without a floor.
pub fn floor_reading<M: Model>(
    traj: &Trajectory<M>,
    window: f64,
) -> Option<Result<FloorReading, String>> {
    let (_, angle) = traj.model.view().floor_line()?;
    let chain = traj.model.chain()?;
    let k = traj.len();
    let momentum: Vec<Vec2> = (0..k).map(|j| traj.momentum(j)).collect();
    let floor_force: Vec<Vec2> = (0..k)
        .map(|j| traj.floor_force(j).unwrap_or([0.0; 2]))
        .collect();
    let landed: Vec<f64> = (0..k)
        .map(|j| traj.floor_landed_length(j).unwrap_or(0.0))
        .collect();
    Some(floor_reading_of(
        chain,
        angle,
        FloorSamples {
            times: &traj.times,
            momentum: &momentum,
            floor_force: &floor_force,
            landed_length: &landed,
        },
        window,
    ))
}
