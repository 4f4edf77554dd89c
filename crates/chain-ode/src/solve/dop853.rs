//! Dormand–Prince 8(5,3) (Hairer & Wanner's DOP853): 12 stages, the
//! combined fifth/third-order error estimate, a PI step-size controller,
//! Hairer's initial step, the seventh-order dense output (3 extra stages,
//! made only for steps that are interpolated) and Hairer's stiffness
//! detection.
//!
//! Stages are numbered as in the literature, `k1..k16`; slot `s` of the
//! stage buffer holds `k_{s+1}`. `k1 = f(t0, y0)` comes from the previous
//! step, `k2..k12` cost 11 evaluations per attempt, `k13 = f(t1, y1)` is
//! evaluated on acceptance and becomes the next `k1` (FSAL), and
//! `k14..k16` feed only the dense output and are evaluated on a step's first
//! interpolation: 12 evaluations per accepted step (15 if it is
//! interpolated), 11 per rejected one.

use std::cell::RefCell;

use super::integrator::{Integrator, Settings};
use super::step_size::initial_step;
use crate::ode::{
    all_finite, Counted, Interpolant, Observer, OdeSystem, Outcome, Stats, Status, StepView,
};
use crate::system::ChainSystem;

/// A stage row: the nonzero `a_ij` as `(slot j, a_ij)`.
type Row = &'static [(usize, f64)];

// Coefficients of Hairer's DOP853, rounded to f64 (the tests check the
// order conditions they must satisfy).
// Nodes c_i (c1 = 0, c12 = c13 = 1).
const C2: f64 = 0.05260015195876773;
const C3: f64 = 0.0789002279381516;
const C4: f64 = 0.1183503419072274;
const C5: f64 = 0.2816496580927726;
const C6: f64 = 0.3333333333333333;
const C7: f64 = 0.25;
const C8: f64 = 0.3076923076923077;
const C9: f64 = 0.6512820512820513;
const C10: f64 = 0.6;
const C11: f64 = 0.8571428571428571;
const C14: f64 = 0.1;
const C15: f64 = 0.2;
const C16: f64 = 0.7777777777777778;
// The step's stages: a_ij.
const A21: f64 = 0.05260015195876773;
const A31: f64 = 0.0197250569845379;
const A32: f64 = 0.0591751709536137;
const A41: f64 = 0.02958758547680685;
const A43: f64 = 0.08876275643042054;
const A51: f64 = 0.2413651341592667;
const A53: f64 = -0.8845494793282861;
const A54: f64 = 0.924834003261792;
const A61: f64 = 0.037037037037037035;
const A64: f64 = 0.17082860872947386;
const A65: f64 = 0.12546768756682242;
const A71: f64 = 0.037109375;
const A74: f64 = 0.17025221101954405;
const A75: f64 = 0.06021653898045596;
const A76: f64 = -0.017578125;
const A81: f64 = 0.03709200011850479;
const A84: f64 = 0.17038392571223998;
const A85: f64 = 0.10726203044637328;
const A86: f64 = -0.015319437748624402;
const A87: f64 = 0.008273789163814023;
const A91: f64 = 0.6241109587160757;
const A94: f64 = -3.3608926294469414;
const A95: f64 = -0.868219346841726;
const A96: f64 = 27.59209969944671;
const A97: f64 = 20.154067550477894;
const A98: f64 = -43.48988418106996;
const A101: f64 = 0.47766253643826434;
const A104: f64 = -2.4881146199716677;
const A105: f64 = -0.590290826836843;
const A106: f64 = 21.230051448181193;
const A107: f64 = 15.279233632882423;
const A108: f64 = -33.28821096898486;
const A109: f64 = -0.020331201708508627;
const A111: f64 = -0.9371424300859873;
const A114: f64 = 5.186372428844064;
const A115: f64 = 1.0914373489967295;
const A116: f64 = -8.149787010746927;
const A117: f64 = -18.52006565999696;
const A118: f64 = 22.739487099350505;
const A119: f64 = 2.4936055526796523;
const A1110: f64 = -3.0467644718982196;
const A121: f64 = 2.273310147516538;
const A124: f64 = -10.53449546673725;
const A125: f64 = -2.0008720582248625;
const A126: f64 = -17.9589318631188;
const A127: f64 = 27.94888452941996;
const A128: f64 = -2.8589982771350235;
const A129: f64 = -8.87285693353063;
const A1210: f64 = 12.360567175794303;
const A1211: f64 = 0.6433927460157636;
// Eighth-order weights b_i.
const B1: f64 = 0.054293734116568765;
const B6: f64 = 4.450312892752409;
const B7: f64 = 1.8915178993145003;
const B8: f64 = -5.801203960010585;
const B9: f64 = 0.3111643669578199;
const B10: f64 = -0.1521609496625161;
const B11: f64 = 0.20136540080403034;
const B12: f64 = 0.04471061572777259;
// The third-order comparison weights.
const BHH1: f64 = 0.2440944881889764;
const BHH2: f64 = 0.7338466882816118;
const BHH3: f64 = 0.022058823529411766;
// The fifth-order error estimate.
const ER1: f64 = 0.01312004499419488;
const ER6: f64 = -1.2251564463762044;
const ER7: f64 = -0.4957589496572502;
const ER8: f64 = 1.6643771824549864;
const ER9: f64 = -0.35032884874997366;
const ER10: f64 = 0.3341791187130175;
const ER11: f64 = 0.08192320648511571;
const ER12: f64 = -0.022355307863886294;
// The dense-output stages 14..16.
const A141: f64 = 0.056167502283047954;
const A147: f64 = 0.25350021021662483;
const A148: f64 = -0.2462390374708025;
const A149: f64 = -0.12419142326381637;
const A1410: f64 = 0.15329179827876568;
const A1411: f64 = 0.00820105229563469;
const A1412: f64 = 0.007567897660545699;
const A1413: f64 = -0.008298;
const A151: f64 = 0.03183464816350214;
const A156: f64 = 0.028300909672366776;
const A157: f64 = 0.053541988307438566;
const A158: f64 = -0.05492374857139099;
const A1511: f64 = -0.00010834732869724932;
const A1512: f64 = 0.0003825710908356584;
const A1513: f64 = -0.00034046500868740456;
const A1514: f64 = 0.1413124436746325;
const A161: f64 = -0.42889630158379194;
const A166: f64 = -4.697621415361164;
const A167: f64 = 7.683421196062599;
const A168: f64 = 4.06898981839711;
const A169: f64 = 0.3567271874552811;
const A1613: f64 = -0.0013990241651590145;
const A1614: f64 = 2.9475147891527724;
const A1615: f64 = -9.15095847217987;
// The dense-output coefficients.
const D41: f64 = -8.428938276109013;
const D46: f64 = 0.5667149535193777;
const D47: f64 = -3.0689499459498917;
const D48: f64 = 2.38466765651207;
const D49: f64 = 2.117034582445028;
const D410: f64 = -0.871391583777973;
const D411: f64 = 2.2404374302607883;
const D412: f64 = 0.6315787787694688;
const D413: f64 = -0.08899033645133331;
const D414: f64 = 18.148505520854727;
const D415: f64 = -9.194632392478356;
const D416: f64 = -4.436036387594894;
const D51: f64 = 10.427508642579134;
const D56: f64 = 242.28349177525817;
const D57: f64 = 165.20045171727028;
const D58: f64 = -374.5467547226902;
const D59: f64 = -22.113666853125306;
const D510: f64 = 7.733432668472264;
const D511: f64 = -30.674084731089398;
const D512: f64 = -9.332130526430229;
const D513: f64 = 15.697238121770845;
const D514: f64 = -31.139403219565178;
const D515: f64 = -9.35292435884448;
const D516: f64 = 35.81684148639408;
const D61: f64 = 19.985053242002433;
const D66: f64 = -387.0373087493518;
const D67: f64 = -189.17813819516758;
const D68: f64 = 527.8081592054236;
const D69: f64 = -11.57390253995963;
const D610: f64 = 6.8812326946963;
const D611: f64 = -1.0006050966910838;
const D612: f64 = 0.7777137798053443;
const D613: f64 = -2.778205752353508;
const D614: f64 = -60.19669523126412;
const D615: f64 = 84.32040550667716;
const D616: f64 = 11.99229113618279;
const D71: f64 = -25.69393346270375;
const D76: f64 = -154.18974869023643;
const D77: f64 = -231.5293791760455;
const D78: f64 = 357.6391179106141;
const D79: f64 = 93.40532418362432;
const D710: f64 = -37.45832313645163;
const D711: f64 = 104.0996495089623;
const D712: f64 = 29.8402934266605;
const D713: f64 = -43.53345659001114;
const D714: f64 = 96.32455395918828;
const D715: f64 = -39.17726167561544;
const D716: f64 = -149.72683625798564;

/// Nodes and rows of `k2..k12` (`k12` at `c = 1`).
const STAGES: [(f64, Row); 11] = [
    (C2, &[(0, A21)]),
    (C3, &[(0, A31), (1, A32)]),
    (C4, &[(0, A41), (2, A43)]),
    (C5, &[(0, A51), (2, A53), (3, A54)]),
    (C6, &[(0, A61), (3, A64), (4, A65)]),
    (C7, &[(0, A71), (3, A74), (4, A75), (5, A76)]),
    (C8, &[(0, A81), (3, A84), (4, A85), (5, A86), (6, A87)]),
    (
        C9,
        &[(0, A91), (3, A94), (4, A95), (5, A96), (6, A97), (7, A98)],
    ),
    (
        C10,
        &[
            (0, A101),
            (3, A104),
            (4, A105),
            (5, A106),
            (6, A107),
            (7, A108),
            (8, A109),
        ],
    ),
    (
        C11,
        &[
            (0, A111),
            (3, A114),
            (4, A115),
            (5, A116),
            (6, A117),
            (7, A118),
            (8, A119),
            (9, A1110),
        ],
    ),
    (
        1.0,
        &[
            (0, A121),
            (3, A124),
            (4, A125),
            (5, A126),
            (6, A127),
            (7, A128),
            (8, A129),
            (9, A1210),
            (10, A1211),
        ],
    ),
];
/// Eighth-order weights: `y1 = y0 + h sum b_i k_i`.
const B: [(usize, f64); 8] = [
    (0, B1),
    (5, B6),
    (6, B7),
    (7, B8),
    (8, B9),
    (9, B10),
    (10, B11),
    (11, B12),
];
/// `sum b_i k_i` minus these is the third-order error estimate.
const BHH: [(usize, f64); 3] = [(0, BHH1), (8, BHH2), (11, BHH3)];
/// The fifth-order error estimate.
const ER: [(usize, f64); 8] = [
    (0, ER1),
    (5, ER6),
    (6, ER7),
    (7, ER8),
    (8, ER9),
    (9, ER10),
    (10, ER11),
    (11, ER12),
];
/// Nodes and rows of the dense-output stages `k14..k16` (slot 12 is `k13 = f(t1, y1)`).
const DENSE_STAGES: [(f64, Row); 3] = [
    (
        C14,
        &[
            (0, A141),
            (6, A147),
            (7, A148),
            (8, A149),
            (9, A1410),
            (10, A1411),
            (11, A1412),
            (12, A1413),
        ],
    ),
    (
        C15,
        &[
            (0, A151),
            (5, A156),
            (6, A157),
            (7, A158),
            (10, A1511),
            (11, A1512),
            (12, A1513),
            (13, A1514),
        ],
    ),
    (
        C16,
        &[
            (0, A161),
            (5, A166),
            (6, A167),
            (7, A168),
            (8, A169),
            (12, A1613),
            (13, A1614),
            (14, A1615),
        ],
    ),
];
/// Rows of the dense coefficients `rcont5..rcont8`, over `k1, k6..k16`.
const D: [[(usize, f64); 12]; 4] = [
    [
        (0, D41),
        (5, D46),
        (6, D47),
        (7, D48),
        (8, D49),
        (9, D410),
        (10, D411),
        (11, D412),
        (12, D413),
        (13, D414),
        (14, D415),
        (15, D416),
    ],
    [
        (0, D51),
        (5, D56),
        (6, D57),
        (7, D58),
        (8, D59),
        (9, D510),
        (10, D511),
        (11, D512),
        (12, D513),
        (13, D514),
        (14, D515),
        (15, D516),
    ],
    [
        (0, D61),
        (5, D66),
        (6, D67),
        (7, D68),
        (8, D69),
        (9, D610),
        (10, D611),
        (11, D612),
        (12, D613),
        (13, D614),
        (14, D615),
        (15, D616),
    ],
    [
        (0, D71),
        (5, D76),
        (6, D77),
        (7, D78),
        (8, D79),
        (9, D710),
        (10, D711),
        (11, D712),
        (12, D713),
        (13, D714),
        (14, D715),
        (15, D716),
    ],
];
/// Stage slots: `k1..k13` and the dense stages `k14..k16`.
const SLOTS: usize = 16;

/// PI controller: exponents and limits (Hairer's DOP853 defaults).
const SAFETY: f64 = 0.9;
const BETA: f64 = 0.0;
const EXPO1: f64 = 1.0 / 8.0 - BETA * 0.2;
const FAC_MIN: f64 = 0.333; // h_new >= 0.333 h
const FAC_MAX: f64 = 6.0; // h_new <= 6 h
/// A non-finite trial is retried this much smaller (not in Hairer's code).
const NONFINITE_SHRINK: f64 = 0.2;
/// Stiffness test: `h |lambda| > 6.1` on 15 accepted steps (without 6 clean ones between).
const STIFF_HLAMBDA: f64 = 6.1;
const STIFF_COUNT: u32 = 15;
const NONSTIFF_RESET: u32 = 6;

/// `sum_j a_j k_j` at component `i` (`k` holds slots of length `d`).
#[inline]
fn weighted(k: &[f64], d: usize, i: usize, row: &[(usize, f64)]) -> f64 {
    row.iter().map(|&(j, a)| a * k[j * d + i]).sum()
}

/// `out = y + h sum_j a_j k_j`.
fn combine(out: &mut [f64], y: &[f64], h: f64, k: &[f64], row: &[(usize, f64)]) {
    let d = out.len();
    for (i, (o, yi)) in out.iter_mut().zip(y).enumerate() {
        *o = yi + h * weighted(k, d, i, row);
    }
}

/// The continuous extension of one step: `y(t0 + theta h)`, seventh order.
///
/// Its three extra stages `k14..k16` cost three right-hand sides, and only
/// some steps are ever interpolated (a sample falls in them, or a maximum of
/// the tip speed): they are computed on the first [`Interpolant::eval`] of
/// the step, not for every step.
struct Dense<'a, S> {
    t0: f64,
    h: f64,
    lazy: RefCell<Lazy<'a, S>>,
}

/// What the dense stages need, and the coefficients once they are made.
struct Lazy<'a, S> {
    ready: bool,
    sys: &'a mut S,
    y: &'a [f64],
    /// Stage slots `k1..k16`; `k14..k16` are written here.
    k: &'a mut [f64],
    ys: &'a mut [f64],
    /// `rcont1..rcont8`, `d` each: `[y0 | y1 - y0 | h k1 - (y1 - y0) |
    /// (y1 - y0) - h k13 - rcont3 | h sum d4_i k_i | ... | h sum d7_i k_i]`;
    /// the first four are set before the step is shown.
    r: &'a mut [f64],
}

impl<S: OdeSystem> Lazy<'_, S> {
    /// The dense stages and the coefficients `rcont5..rcont8`.
    fn prepare(&mut self, t0: f64, h: f64) {
        let d = self.y.len();
        for (slot, &(c, row)) in (13..).zip(&DENSE_STAGES) {
            let (done, rest) = self.k.split_at_mut(slot * d);
            combine(self.ys, self.y, h, done, row);
            self.sys.rhs(t0 + c * h, self.ys, &mut rest[..d]);
        }
        for i in 0..d {
            for (m, row) in D.iter().enumerate() {
                self.r[(4 + m) * d + i] = h * weighted(self.k, d, i, row);
            }
        }
        self.ready = true;
    }
}

impl<S: OdeSystem> Interpolant for Dense<'_, S> {
    fn eval(&self, t: f64, out: &mut [f64]) {
        let mut lazy = self.lazy.borrow_mut();
        if !lazy.ready {
            lazy.prepare(self.t0, self.h);
        }
        let d = out.len();
        let s = (t - self.t0) / self.h;
        let s1 = 1.0 - s;
        let r = |m: usize, i: usize| lazy.r[m * d + i];
        for (i, o) in out.iter_mut().enumerate() {
            let conf = r(4, i) + s * (r(5, i) + s1 * (r(6, i) + s * r(7, i)));
            *o = r(0, i) + s * (r(1, i) + s1 * (r(2, i) + s * (r(3, i) + s1 * conf)));
        }
    }
}

/// The two error estimates of one attempt, as sums over components of
/// `(estimate / (atol + rtol max(|y0|, |y1|)))^2`, without the factor `h`:
/// `sq5` of the fifth-order one (`sum er_i k_i`), `sq3` of the third-order
/// one (`sum (b_i - bhh_i) k_i`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Estimate {
    pub sq5: f64,
    pub sq3: f64,
}

impl Estimate {
    /// Hairer's combined error norm of a step of `h` in dimension `d`:
    /// `err5^2 / sqrt(err5^2 + 0.01 err3^2)`, with `errN` the RMS of `h` times
    /// estimate `N`. The step is accepted when it is at most 1.
    pub fn norm(self, h: f64, d: usize) -> f64 {
        let deno = self.sq5 + 0.01 * self.sq3;
        let deno = if deno > 0.0 { deno } else { 1.0 };
        h * self.sq5 / (d as f64 * deno).sqrt()
    }
}

/// One attempt of a step of `h` from `(t, y)`, with `k1 = f(t, y)` in slot 0:
/// the stages `k2..k12` (slots 1..12; the state of `k12` is left in `ys`),
/// the eighth-order `y1`, and its error estimates. The step loop's own
/// arithmetic; the tests call it to see the estimates.
#[allow(clippy::too_many_arguments)]
pub(crate) fn attempt<S: OdeSystem>(
    sys: &mut S,
    t: f64,
    h: f64,
    y: &[f64],
    k: &mut [f64],
    ys: &mut [f64],
    y1: &mut [f64],
    o: &Settings,
) -> Estimate {
    let d = y.len();
    for (slot, &(c, row)) in (1..).zip(&STAGES) {
        let (done, rest) = k.split_at_mut(slot * d);
        combine(ys, y, h, done, row);
        sys.rhs(t + c * h, ys, &mut rest[..d]);
    }
    let (mut sq5, mut sq3) = (0.0, 0.0);
    for i in 0..d {
        let b = weighted(k, d, i, &B);
        y1[i] = y[i] + h * b;
        let e3 = b - weighted(k, d, i, &BHH);
        let e5 = weighted(k, d, i, &ER);
        let sk = o.atol + o.rtol * y[i].abs().max(y1[i].abs());
        sq5 += (e5 / sk).powi(2);
        sq3 += (e3 / sk).powi(2);
    }
    Estimate { sq5, sq3 }
}

/// Integrates from `t0` to `t_end` (`> t0`), with `dopri5::integrate`'s
/// contract: observers see every accepted step with `f1 = f(t1, y1)` and the
/// seventh-order interpolant; the run ends on `t_end` or with a status, at
/// the last finite state.
pub(crate) fn integrate<S: OdeSystem>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    o: &Settings,
    obs: &mut dyn Observer,
) -> Outcome {
    Counted::run(sys, |sys| steps(sys, t0, y0, t_end, o, obs))
}

fn steps<S: OdeSystem>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    o: &Settings,
    obs: &mut dyn Observer,
) -> Outcome {
    let d = sys.dim();
    let mut stats = Stats::default();
    let mut y = y0.to_vec();
    let (mut y1, mut ys) = (vec![0.0; d], vec![0.0; d]);
    let mut k = vec![0.0; SLOTS * d];
    let mut rcont = vec![0.0; 8 * d];
    let mut f1 = vec![0.0; d];

    sys.rhs(t0, &y, &mut k[..d]);
    if !all_finite(&k[..d]) {
        return Outcome::ended(Status::Diverged, t0, Some(t0), stats, y);
    }
    obs.start(t0, &y, &k[..d]);

    let span = t_end - t0;
    let mut h = match o.h0 {
        Some(h) => h.min(span),
        None => {
            let (f0, rest) = k.split_at_mut(d);
            initial_step(sys, t0, &y, f0, span, o, 8, (&mut ys, &mut rest[..d]))
        }
    };
    let mut t = t0;
    let mut fac_old: f64 = 1e-4;
    let mut last_rejected = false;
    let mut last_nonfinite = false;
    let (mut stiff_steps, mut nonstiff_steps) = (0u32, 0u32);

    while t < t_end {
        if stats.steps + stats.rejected_steps >= o.max_steps {
            return Outcome::ended(Status::MaxSteps, t, Some(t), stats, y);
        }
        if obs.stop() {
            return Outcome::ended(Status::Interrupted, t, Some(t), stats, y);
        }
        let floor = o.floor(t);
        if h < floor {
            let status = if last_nonfinite {
                Status::Diverged
            } else {
                Status::StepSizeTooSmall
            };
            return Outcome::ended(status, t, Some(t + h), stats, y);
        }
        // Land on t_end exactly; stretch a step that would leave a sliver.
        let mut t1 = t + h;
        if t1 > t_end - 1e-10 * h {
            t1 = t_end;
            h = t_end - t;
        }

        let e = attempt(sys, t, h, &y, &mut k, &mut ys, &mut y1, o).norm(h, d);

        // A passing trial also needs a finite k13 before it is accepted.
        let mut finite = e.is_finite() && all_finite(&y1);
        let mut lambda = 0.0;
        if finite && e <= 1.0 {
            sys.rhs(t1, &y1, &mut k[12 * d..13 * d]);
            finite = all_finite(&k[12 * d..13 * d]);
            if finite {
                // |lambda| ~ |k13 - k12| / |y1 - Y12|: both stages at the step end (Y12 is in ys).
                let (mut num, mut den) = (0.0, 0.0);
                for i in 0..d {
                    num += (k[12 * d + i] - k[11 * d + i]).powi(2);
                    den += (y1[i] - ys[i]).powi(2);
                }
                lambda = if den > 0.0 { (num / den).sqrt() } else { 0.0 };
            }
        }
        if !finite {
            // A non-finite trial: retry much smaller; give up at the floor.
            stats.rejected_steps += 1;
            last_rejected = true;
            last_nonfinite = true;
            h *= NONFINITE_SHRINK;
            continue;
        }
        last_nonfinite = false;

        let fac11 = e.powf(EXPO1);
        if e <= 1.0 {
            // Accepted.
            let fac = (fac11 / fac_old.powf(BETA) / SAFETY).clamp(1.0 / FAC_MAX, 1.0 / FAC_MIN);
            let mut h_new = h / fac;
            fac_old = e.max(1e-4);
            stats.steps += 1;

            let mut stiff_now = false;
            if h * lambda > STIFF_HLAMBDA {
                nonstiff_steps = 0;
                stiff_steps += 1;
                if stiff_steps == STIFF_COUNT {
                    stats.stiffness_detections += 1;
                    stiff_steps = 0;
                    stiff_now = true;
                }
            } else {
                nonstiff_steps += 1;
                if nonstiff_steps == NONSTIFF_RESET {
                    stiff_steps = 0;
                }
            }

            // Dense output: the cheap coefficients now, the stages on demand.
            for i in 0..d {
                let dy = y1[i] - y[i];
                let bspl = h * k[i] - dy;
                rcont[i] = y[i];
                rcont[d + i] = dy;
                rcont[2 * d + i] = bspl;
                rcont[3 * d + i] = dy - h * k[12 * d + i] - bspl;
            }
            f1.copy_from_slice(&k[12 * d..13 * d]);
            {
                let dense = Dense {
                    t0: t,
                    h,
                    lazy: RefCell::new(Lazy {
                        ready: false,
                        sys: &mut *sys,
                        y: &y,
                        k: &mut k,
                        ys: &mut ys,
                        r: &mut rcont,
                    }),
                };
                obs.step(&StepView {
                    t0: t,
                    t1,
                    y0: &y,
                    y1: &y1,
                    f1: &f1,
                    interpolant: &dense,
                });
            }
            std::mem::swap(&mut y, &mut y1);
            k.copy_within(12 * d..13 * d, 0); // FSAL: k13 of this step is k1 of the next.
            t = t1;
            if last_rejected {
                h_new = h_new.min(h);
            }
            last_rejected = false;
            h = h_new;
            // As DOPRI5: hand over only where the implicit method should be cheaper.
            if stiff_now && o.stop_when_stiff && lambda > o.switch_lambda && t < t_end {
                let mut out = Outcome::ended(Status::Ok, t, None, stats, y);
                out.stiff_at = Some(t);
                return out;
            }
        } else {
            stats.rejected_steps += 1;
            last_rejected = true;
            h /= (fac11 / SAFETY).min(1.0 / FAC_MIN);
        }
    }
    Outcome::ended(Status::Ok, t, None, stats, y)
}

/// `dop853`: Dormand–Prince 8(5,3), adaptive, for tight tolerances.
pub(crate) struct Dop853;

impl Integrator for Dop853 {
    fn name(&self) -> &'static str {
        "dop853"
    }

    fn adaptive(&self) -> bool {
        true
    }

    fn integrate(
        &self,
        sys: &mut ChainSystem,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        settings: &Settings,
        obs: &mut dyn Observer,
    ) -> Outcome {
        integrate(sys, t0, y0, t_end, settings, obs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::test_problems::{
        blow_up, max_diff, options, slope, toy, van_der_pol, ExactCheck, Probe, Quiet, Toy,
        OSCILLATOR,
    };

    /// Eccentricity of the Kepler test orbit (`a = 1`, `mu = 1`, period `2 pi`).
    const ECC: f64 = 0.5;

    /// Kepler's problem: `y = [q, p]`, `q'' = -q / |q|^3`.
    fn kepler() -> Toy {
        toy(4, |_t, y, dy| {
            let r3 = y[0].hypot(y[1]).powi(3);
            dy[0] = y[2];
            dy[1] = y[3];
            dy[2] = -y[0] / r3;
            dy[3] = -y[1] / r3;
        })
    }

    /// The orbit through periapsis `(1 - e, 0)` at `t = 0`, from Kepler's equation.
    fn kepler_exact(t: f64) -> [f64; 4] {
        let mut ea = t + ECC * t.sin();
        for _ in 0..50 {
            ea -= (ea - ECC * ea.sin() - t) / (1.0 - ECC * ea.cos());
        }
        let (s, c) = ea.sin_cos();
        let b = (1.0 - ECC * ECC).sqrt();
        let den = 1.0 - ECC * c;
        [c - ECC, b * s, -s / den, b * c / den]
    }

    /// Runs and checks the cost model against the toy's own count:
    /// `1 + [probe] + 11 per attempt + 1 per accepted step + 3 per
    /// interpolated step` (no non-finite trials). `interpolates` says whether
    /// the observer evaluates every step's dense output, none, or (`None`)
    /// some.
    fn run_clean(
        sys: &mut Toy,
        t0: f64,
        y0: &[f64],
        t_end: f64,
        o: &Settings,
        obs: &mut dyn Observer,
        interpolates: Option<bool>,
    ) -> Outcome {
        let out = integrate(sys, t0, y0, t_end, o, obs);
        let s = out.stats;
        assert_eq!(s.rhs_evals, sys.rhs_calls);
        let probe = u64::from(o.h0.is_none());
        let base = 1 + probe + 11 * (s.steps + s.rejected_steps) + s.steps;
        match interpolates {
            Some(true) => assert_eq!(s.rhs_evals, base + 3 * s.steps, "{s:?}"),
            Some(false) => assert_eq!(s.rhs_evals, base, "{s:?}"),
            // Some steps: 3 more for each, at most every step.
            None => {
                let extra = s.rhs_evals - base;
                assert!(
                    extra.is_multiple_of(3) && extra > 0 && extra <= 3 * s.steps,
                    "{s:?}"
                );
            }
        }
        out
    }

    #[test]
    fn the_tableau_satisfies_its_simplest_order_conditions() {
        // Node of every slot: k1 at 0, k13 = f(t1, y1) at 1.
        let mut c = [0.0; SLOTS];
        for (s, &(cs, _)) in (1..).zip(&STAGES) {
            c[s] = cs;
        }
        c[12] = 1.0;
        for (s, &(cs, _)) in (13..).zip(&DENSE_STAGES) {
            c[s] = cs;
        }
        // Each stage's row sums to its node, and uses only earlier stages.
        for (s, &(cs, row)) in (1..).zip(&STAGES).chain((13..).zip(&DENSE_STAGES)) {
            assert!(row.iter().all(|&(j, _)| j < s), "stage {}", s + 1);
            let sum: f64 = row.iter().map(|(_, a)| a).sum();
            assert!((sum - cs).abs() < 1e-14, "stage {}: {sum} vs {cs}", s + 1);
        }
        let moment = |w: &[(usize, f64)], q: i32| -> f64 {
            w.iter().map(|&(j, a)| a * c[j].powi(q - 1)).sum()
        };
        // The fifth-order estimate kills polynomials up to degree 4, not 5;
        // the third-order one up to degree 2, not 3.
        for q in 1..=5 {
            assert!(moment(&ER, q).abs() < 1e-13, "er, q = {q}");
        }
        assert!(moment(&ER, 6).abs() > 1e-4);
        for q in 1..=3 {
            assert!(
                (moment(&BHH, q) - 1.0 / q as f64).abs() < 1e-14,
                "bhh, q = {q}"
            );
        }
        assert!((moment(&BHH, 4) - 0.25).abs() > 1e-2);
    }

    #[test]
    fn one_step_integrates_polynomials_up_to_the_order() {
        // y' = q t^(q-1): y = t^q. One step of h = 1, accepted whatever its error.
        let thetas = [0.25, 0.5, 0.9];
        for q in 1..=9 {
            let mut sys = toy(1, move |t, _y, dy| dy[0] = q as f64 * t.powi(q - 1));
            let mut obs = Probe {
                times: thetas.to_vec(),
                ..Probe::default()
            };
            let o = Settings {
                h0: Some(1.0),
                ..options(0.5, 1e3)
            };
            let out = run_clean(&mut sys, 0.0, &[0.0], 1.0, &o, &mut obs, Some(true));
            assert_eq!((out.stats.steps, out.stats.rejected_steps), (1, 0));
            let end = (out.y_end[0] - 1.0).abs();
            let dense = obs
                .values
                .iter()
                .map(|(t, y)| (y[0] - t.powi(q)).abs())
                .fold(0.0, f64::max);
            assert_eq!(obs.values.len(), thetas.len());
            // y1 is exact to degree 8, the interpolant to degree 7.
            if q <= 8 {
                assert!(end < 1e-14, "q = {q}: {end:e}");
            } else {
                assert!(end > 1e-6, "q = {q}: {end:e}");
            }
            if q <= 7 {
                assert!(dense < 1e-14, "q = {q}: {dense:e}");
            } else {
                assert!(dense > 1e-6, "q = {q}: {dense:e}");
            }
        }
    }

    #[test]
    fn oscillator_matches_the_exact_solution_with_dense_output() {
        for t0 in [0.0, 1.5] {
            let mut sys = (OSCILLATOR.system)();
            let mut obs = ExactCheck::new(OSCILLATOR.exact).with_rhs(|_t, y| vec![y[1], -y[0]]);
            let y0 = [f64::cos(t0), -f64::sin(t0)];
            let t_end = 10.0;
            let o = options(1e-12, 1e-14);
            let out = run_clean(&mut sys, t0, &y0, t_end, &o, &mut obs, Some(true));
            assert_eq!(out.status, Status::Ok);
            assert_eq!(out.t_reached, t_end);
            assert_eq!(out.t_failed, None);
            assert_eq!(out.stiff_at, None);
            assert_eq!(obs.starts, 1);
            assert_eq!(obs.t_last, t_end, "the last step lands on t_end");
            assert_eq!(obs.steps, out.stats.steps);
            let e = max_diff(&out.y_end, &[t_end.cos(), -t_end.sin()]);
            eprintln!(
                "oscillator t0 = {t0}: {} steps, end error {e:.1e}, dense {:.1e}, ends {:.1e}",
                out.stats.steps, obs.inside, obs.ends
            );
            assert!(e < 1e-10, "end error {e:e}");
            assert!(obs.inside < 1e-10, "dense error {:e}", obs.inside);
            assert!(obs.ends < 1e-12, "ends {:e}", obs.ends);
        }
    }

    #[test]
    fn kepler_orbit_closes_after_one_period() {
        let period = 2.0 * std::f64::consts::PI;
        let mut sys = kepler();
        let mut obs = Probe {
            times: (1..40).map(|k| period * k as f64 / 40.0).collect(),
            ..Probe::default()
        };
        let y0 = kepler_exact(0.0);
        let out = run_clean(
            &mut sys,
            0.0,
            &y0,
            period,
            &options(1e-12, 1e-12),
            &mut obs,
            None,
        );
        assert_eq!(out.status, Status::Ok);
        assert_eq!(out.t_reached, period);
        let e = max_diff(&out.y_end, &y0);
        let dense = obs
            .values
            .iter()
            .map(|(t, y)| max_diff(y, &kepler_exact(*t)))
            .fold(0.0, f64::max);
        eprintln!(
            "kepler e = {ECC}: {} steps, {} rejected, end error {e:.1e}, dense {dense:.1e}",
            out.stats.steps, out.stats.rejected_steps
        );
        assert!(obs.values.len() >= 39);
        assert!(e < 1e-9, "end error {e:e}");
        assert!(dense < 1e-9, "dense error {dense:e}");
    }

    #[test]
    fn global_error_falls_like_the_eighth_power_of_the_step_count() {
        let period = 2.0 * std::f64::consts::PI;
        let y0 = kepler_exact(0.0);
        let mut points = Vec::new();
        for k in 6..=13 {
            let tol = 10f64.powi(-k);
            let mut sys = kepler();
            let out = run_clean(
                &mut sys,
                0.0,
                &y0,
                period,
                &options(tol, tol),
                &mut Quiet,
                Some(false),
            );
            assert_eq!(out.status, Status::Ok);
            let e = max_diff(&out.y_end, &y0);
            eprintln!("tol 1e-{k}: {} steps, error {e:.2e}", out.stats.steps);
            points.push((out.stats.steps as f64, e));
        }
        let p = slope(&points);
        eprintln!("fitted slope of log(error) vs log(steps): {p:.2}");
        assert!(points.first().unwrap().0 * 2.0 < points.last().unwrap().0);
        assert!((-9.0..=-7.0).contains(&p), "slope {p}");
    }

    #[test]
    fn one_step_local_errors_show_orders_eight_and_seven() {
        // Single steps of size h from apoapsis (t = pi): the step's error is
        // O(h^9) (order 8), the interpolant's at mid-step O(h^8) (order 7).
        let t0 = std::f64::consts::PI;
        let (mut step, mut dense) = (Vec::new(), Vec::new());
        for m in 0..5 {
            let h = 1.6 / 2f64.powi(m);
            let mut sys = kepler();
            let mut obs = Probe {
                times: vec![t0 + 0.5 * h],
                ..Probe::default()
            };
            let o = Settings {
                h0: Some(h),
                ..options(0.5, 1.0)
            };
            let out = run_clean(
                &mut sys,
                t0,
                &kepler_exact(t0),
                t0 + h,
                &o,
                &mut obs,
                Some(true),
            );
            assert_eq!((out.stats.steps, out.stats.rejected_steps), (1, 0));
            let e = max_diff(&out.y_end, &kepler_exact(t0 + h));
            let (t, y) = &obs.values[0];
            let ed = max_diff(y, &kepler_exact(*t));
            eprintln!("h = {h}: step error {e:.2e}, mid-step dense error {ed:.2e}");
            step.push((h, e));
            dense.push((h, ed));
        }
        let (ps, pd) = (slope(&step), slope(&dense));
        eprintln!("local slopes: step {ps:.2}, dense {pd:.2}");
        assert!((8.5..=9.7).contains(&ps), "step slope {ps}");
        assert!((7.5..=8.7).contains(&pd), "dense slope {pd}");
    }

    #[test]
    fn counters_are_exact_with_rejections() {
        // A first step far too long forces rejections.
        let mut sys = kepler();
        let o = Settings {
            h0: Some(3.0),
            ..options(1e-9, 1e-9)
        };
        let out = run_clean(
            &mut sys,
            0.0,
            &kepler_exact(0.0),
            10.0,
            &o,
            &mut Quiet,
            Some(false),
        );
        assert_eq!(out.status, Status::Ok);
        assert!(out.stats.rejected_steps > 0, "{:?}", out.stats);
        assert_eq!(out.stats.jacobian_evals, 0);
        assert_eq!(out.stats.lu_factorizations, 0);
        assert!(max_diff(&out.y_end, &kepler_exact(10.0)) < 1e-6);
    }

    #[test]
    fn the_budget_counts_every_attempt() {
        let mut rejected_seen = false;
        for max_steps in 1..200 {
            let mut sys = van_der_pol(1000.0);
            let o = Settings {
                max_steps,
                ..options(1e-6, 1e-8)
            };
            let out = run_clean(
                &mut sys,
                0.0,
                &[2.0, 0.0],
                3000.0,
                &o,
                &mut Quiet,
                Some(false),
            );
            assert_eq!(out.status, Status::MaxSteps, "budget {max_steps}");
            assert_eq!(out.stats.steps + out.stats.rejected_steps, max_steps);
            assert!(out.t_reached < 3000.0 && all_finite(&out.y_end));
            rejected_seen |= out.stats.rejected_steps > 0;
        }
        assert!(rejected_seen);
    }

    #[test]
    fn a_blow_up_ends_with_a_status_and_a_finite_state() {
        // y' = y^2, y(0) = 1: y = 1 / (1 - t) leaves every bound at t = 1.
        let mut sys = blow_up();
        let out = integrate(
            &mut sys,
            0.0,
            &[1.0],
            2.0,
            &options(1e-8, 1e-10),
            &mut Quiet,
        );
        eprintln!("blow-up: {out:?}");
        // Never `diverged`: y stays finite (~1e12) while the step shrinks
        // to the floor; see known_solutions::a_blow_up_ends_step_size_too_small_just_before_the_pole.
        assert_eq!(out.status, Status::StepSizeTooSmall);
        assert_eq!(out.stats.rhs_evals, sys.rhs_calls);
        // The numerical pole lags the exact one by ~1e-9 here (DOP853's
        // error has that sign on this problem), so allow the tolerance.
        assert!(out.t_reached < 1.0 + 1e-8, "{out:?}");
        assert!(out.t_failed.is_some_and(|t| t >= out.t_reached));
        assert!(all_finite(&out.y_end));
        // It stopped on the numerical solution's pole: y = 1 / (t_pole - t)
        // with t_pole = 1 to the tolerance (y itself is ill-conditioned there).
        let t_pole = out.t_reached + 1.0 / out.y_end[0];
        assert!((t_pole - 1.0).abs() < 1e-5, "{out:?}");
    }

    #[test]
    fn a_non_finite_start_is_diverged() {
        let mut sys = (OSCILLATOR.system)();
        let out = integrate(
            &mut sys,
            0.0,
            &[f64::NAN, 0.0],
            1.0,
            &options(1e-8, 1e-10),
            &mut Quiet,
        );
        assert_eq!(out.status, Status::Diverged);
        assert_eq!(out.t_reached, 0.0);
        assert_eq!(out.stats.rhs_evals, 1);
    }

    #[test]
    fn a_non_finite_wall_ends_diverged_just_before_it() {
        // y' = 1 up to t = 0.5, NaN beyond: every trial across the wall is
        // non-finite and retried 5x smaller until the step hits the floor.
        let mut sys = toy(1, |t, _y, dy| dy[0] = if t > 0.5 { f64::NAN } else { 1.0 });
        let out = integrate(
            &mut sys,
            0.0,
            &[0.0],
            1.0,
            &options(1e-8, 1e-10),
            &mut Quiet,
        );
        eprintln!("wall: {out:?}");
        assert_eq!(out.status, Status::Diverged);
        assert_eq!(out.stats.rhs_evals, sys.rhs_calls);
        assert!(out.stats.rejected_steps > 0);
        assert!(
            out.t_reached <= 0.5 && out.t_reached > 0.5 - 1e-12,
            "{out:?}"
        );
        assert!(out.t_failed.is_some_and(|t| t > out.t_reached));
        assert!((out.y_end[0] - out.t_reached).abs() < 1e-14);
    }

    /// `y' = -1000 (y - cos t)`: stiff, `lambda = -1000`.
    fn relaxation() -> Toy {
        toy(1, |t, y, dy| dy[0] = -1000.0 * (y[0] - t.cos()))
    }

    #[test]
    fn stiffness_is_detected_and_can_stop_the_run() {
        let t_end = 10.0;
        // The slow solution that y(0) = 1 relaxes onto within ~1/1000.
        let slow = |t: f64| (1e6 * t.cos() + 1e3 * t.sin()) / (1e6 + 1.0);
        let mut sys = relaxation();
        // At this tolerance the step is limited by stability, h |lambda| ~ 6.4;
        // at tighter ones (rtol <~ 1e-6) it cycles around 6.1 and the detector stays quiet.
        let o = options(1e-5, 1e-7);
        let out = run_clean(&mut sys, 0.0, &[1.0], t_end, &o, &mut Quiet, Some(false));
        eprintln!("relaxation: {:?}", out.stats);
        assert_eq!(out.status, Status::Ok);
        assert_eq!(out.stiff_at, None);
        assert!(out.stats.stiffness_detections > 0, "{:?}", out.stats);
        let e = (out.y_end[0] - slow(t_end)).abs();
        eprintln!("relaxation end error {e:.1e}");
        assert!(e < 1e-5, "{:?}", out.y_end);

        // Stops at the first detection if |lambda| = 1000 exceeds switch_lambda ...
        for (switch_lambda, stops) in [(990.0, true), (1010.0, false)] {
            let mut sys = relaxation();
            let o = Settings {
                stop_when_stiff: true,
                switch_lambda,
                ..o
            };
            let stop = run_clean(&mut sys, 0.0, &[1.0], t_end, &o, &mut Quiet, Some(false));
            assert_eq!(stop.status, Status::Ok);
            if stops {
                let t = stop.stiff_at.expect("stopped when stiff");
                assert_eq!(stop.t_reached, t);
                assert!(t < t_end);
                assert_eq!(stop.stats.stiffness_detections, 1);
                let e = (stop.y_end[0] - slow(t)).abs();
                eprintln!("stopped when stiff at t = {t:.3}, error {e:.1e}");
                assert!(e < 1e-4, "{e:e}");
            } else {
                // ... and not otherwise.
                assert_eq!(stop.stiff_at, None);
                assert_eq!(stop.t_reached, t_end);
                assert_eq!(stop.stats, out.stats);
            }
        }
    }
}
