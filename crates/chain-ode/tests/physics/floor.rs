//! The floor (`docs/model.md`, "The floor"), against statics, the energy
//! balance and the rigid-body impact of a rod: each a closed form or a
//! conservation law that a wrong contact law fails.

use chain_ode::{solve, Chain, ChainParams, Floor, Method, Pivot, SolveOptions, Start, Status};

/// A floor of stiffness `k`, damping `c`, friction `mu`, slip speed `vs`
/// through `(0, height)` (or touching the start) at the angle `angle`.
fn floor(height: Option<f64>, angle: f64, k: f64, c: f64, mu: f64, vs: f64) -> Floor {
    Floor {
        height,
        angle,
        stiffness: k,
        damping: c,
        friction: mu,
        slip_speed: vs,
    }
}

/// An elastic chain of `n` rods of mass `m`, length `len`, `g = 1`, its
/// pivot let go at `t = 0` when `free`, on `floor`.
fn chain(n: usize, m: f64, len: f64, ea: f64, free: bool, floor: Floor) -> Chain {
    Chain::new(ChainParams {
        length: len,
        links: n,
        mass: m,
        gravity: 1.0,
        axial_stiffness: Some(ea),
        axial_damping: 1.0,
        pivot: Pivot {
            release: free.then_some(0.0),
            ..Pivot::default()
        },
        floor: Some(floor),
        ..ChainParams::default()
    })
    .unwrap()
}

fn opts(t_end: f64, rtol: f64, output_dt: f64) -> SolveOptions {
    SolveOptions {
        t_end,
        rtol,
        atol: rtol,
        output_dt: Some(output_dt),
        max_steps: 50_000_000,
        ..SolveOptions::default()
    }
}

/// A straight chain laid on a floor at the angle `a` (touching it), let go.
fn laid(n: usize, a: f64, k: f64, mu: f64, vs: f64) -> (Chain, chain_ode::State) {
    let len = 6.0;
    let ch = chain(n, 0.2, len, 1e3, true, floor(Some(0.0), a, k, 1e3, mu, vs));
    let p1 = [len * a.cos(), len * a.sin()];
    let s = Start::Stretched { p0: [0.0, 0.0], p1 }.state(&ch).unwrap();
    (ch, s)
}

/// At rest on a level floor, each of the `2 n` contact points (a rod's two
/// ends) carries half its rod's weight, `m g / 2`, and the floor the whole
/// weight `n m g`, at the static deflection `m g / (2 k)`; nothing moves.
/// It starts touching the floor and settles (the bound: a position error
/// of `atol = 1e-10` against the deflection `1e-5` is `1e-5`; measured
/// `7e-8` with dopri5).
#[test]
fn a_chain_lying_on_the_floor_rests_on_it_with_its_weight() {
    let (n, m, k) = (10, 0.2, 1e4);
    let (ch, s) = laid(n, 0.0, k, 0.5, 1e-3);
    for method in [Method::Dopri5, Method::Bdf] {
        let tr = solve(&ch, &s, method, &opts(5.0, 1e-10, 0.5)).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method}");
        let last = tr.len() - 1;
        let points = tr.floor_forces(last).unwrap();
        assert_eq!(points.len(), 2 * n);
        for (j, f) in points.iter().enumerate() {
            assert!(
                (f[1] / (0.5 * m) - 1.0).abs() < 1e-6 && f[0].abs() < 1e-10,
                "{method}: point {j} carries {f:?}, not m g / 2 = {}",
                0.5 * m
            );
        }
        let total = tr.floor_force(last).unwrap();
        assert!((total[1] / (n as f64 * m) - 1.0).abs() < 1e-6, "{total:?}");
        // All of it has landed: its whole length and weight.
        assert!((tr.floor_landed_length(last).unwrap() - 6.0).abs() < 1e-12);
        assert!((tr.floor_landed_weight(last).unwrap() - n as f64 * m).abs() < 1e-12);
        let y = tr.state(last);
        for i in 0..n {
            let depth = -y[3 * n + 1 + i];
            assert!(
                (depth / (0.5 * m / k) - 1.0).abs() < 1e-6,
                "rod {i} at {depth}"
            );
            assert!(y[4 * n + 1 + i].abs() < 1e-9 && y[5 * n + 1 + i].abs() < 1e-9);
        }
    }
}

/// The along-slope velocity of the chain's centre of mass at sample `j`.
fn slope_speed(tr: &chain_ode::Trajectory, n: usize, a: f64, j: usize) -> f64 {
    let y = tr.state(j);
    let (vx, vy): (f64, f64) = (0..n).fold((0.0, 0.0), |(sx, sy), i| {
        (sx + y[4 * n + 1 + i], sy + y[5 * n + 1 + i])
    });
    (vx * a.cos() + vy * a.sin()) / n as f64
}

/// Below the friction angle the regularised friction holds the chain: each
/// end slides down at the creep speed where `mu N tanh(v / v_s)` balances
/// the pull `N tan a`, `v = v_s atanh(tan a / mu)` (-> 0 with `v_s`). Above
/// it the chain slides with `g (sin a - mu cos a)` once `v >> v_s`.
#[test]
fn friction_holds_the_chain_below_the_friction_angle_and_lets_it_slide_above() {
    let (n, mu, vs) = (6, 0.5, 1e-3);
    // Below: tan 0.3 = 0.309 < 0.5.
    let a = 0.3;
    let (ch, s) = laid(n, a, 1e4, mu, vs);
    let tr = solve(&ch, &s, Method::Bdf, &opts(4.0, 1e-9, 0.5)).unwrap();
    assert_eq!(tr.status, Status::Ok);
    let creep = -vs * (a.tan() / mu).atanh();
    let got = slope_speed(&tr, n, a, tr.len() - 1);
    assert!(
        (got / creep - 1.0).abs() < 1e-4,
        "creep {got}, closed form {creep}"
    );
    // Above: tan 0.6 = 0.684 > 0.5.
    let a = 0.6;
    let (ch, s) = laid(n, a, 1e4, mu, vs);
    let tr = solve(&ch, &s, Method::Bdf, &opts(2.0, 1e-9, 0.5)).unwrap();
    assert_eq!(tr.status, Status::Ok);
    let (j1, j2) = (2, tr.len() - 1);
    let accel =
        (slope_speed(&tr, n, a, j2) - slope_speed(&tr, n, a, j1)) / (tr.times[j2] - tr.times[j1]);
    let want = -(a.sin() - mu * a.cos());
    assert!(
        (accel / want - 1.0).abs() < 1e-4,
        "slides at {accel}, closed form {want}"
    );
}

/// `E + W = E(0)` with the floor's stored energy in `E` and its damping and
/// friction in `W`: a pinned chain swung from the horizontal onto a floor
/// with damping and friction, every method.
#[test]
fn the_energy_balance_holds_with_the_floor_damping_and_friction() {
    let n = 8;
    let ch = chain(
        n,
        0.2,
        6.0,
        1e3,
        false,
        floor(Some(-3.0), 0.1, 1e3, 2.0, 0.4, 0.05),
    );
    let s = Start::Stretched {
        p0: [0.0, 0.0],
        p1: [6.0, 0.0],
    }
    .state(&ch)
    .unwrap();
    for method in [
        Method::Dopri5,
        Method::Dop853,
        Method::Bdf,
        Method::GenAlpha,
    ] {
        let tr = solve(&ch, &s, method, &opts(8.0, 1e-9, 0.05)).unwrap();
        assert_eq!(tr.status, Status::Ok, "{method}");
        let peak = (0..tr.len())
            .map(|j| tr.floor_force(j).unwrap()[1])
            .fold(0.0, f64::max);
        assert!(
            peak > 0.5,
            "{method}: the chain never hit the floor ({peak})"
        );
        let w = tr.summary.dissipated;
        assert!(w > 0.1 * tr.summary.energy_start.abs(), "{method}: W = {w}");
        let scale = ch.energy_scale();
        let err = tr.summary.energy_balance_error / scale;
        assert!(err < 1e-5, "{method}: |E + W - E(0)| = {err} of M g L");
    }
}

/// The far end's vertical speed just after a plastic, frictionless impact
/// of a uniform rod of half length `h` at the angle `theta` (near end
/// lower), falling at `v`: the impulse `P = m v / (1 + 3 cos^2 theta)`
/// stops the near end, and the far end moves at
/// `v 6 cos^2 theta / (1 + 3 cos^2 theta)` down (`3 v / 2` for a level rod).
fn far_end_speed(v: f64, theta: f64) -> f64 {
    let c2 = theta.cos().powi(2);
    v * 6.0 * c2 / (1.0 + 3.0 * c2)
}

/// A rod dropped from rest at the angle `theta` with its near end `drop`
/// above a floor of stiffness `k` and damping `c`: the far end's vertical
/// speed when the near end's compression ends (its velocity turns upward),
/// and the impact speed.
fn one_rod_impact(k: f64, c: f64, theta: f64, drop: f64) -> (f64, f64) {
    let ch = chain(
        1,
        1.0,
        1.0,
        1.0,
        true,
        floor(Some(-drop), 0.0, k, c, 0.0, 1.0),
    );
    let s = Start::Angles {
        p0: [0.0, 0.0],
        angles: vec![theta],
        rates: None,
    }
    .state(&ch)
    .unwrap();
    let v = (2.0 * drop).sqrt();
    let t_hit = v;
    let tau = (0.25 / k).sqrt();
    let o = SolveOptions {
        t_end: t_hit + 40.0 * tau,
        output_dt: Some(tau / 50.0),
        ..opts(t_hit + 40.0 * tau, 1e-10, tau / 50.0)
    };
    let tr = solve(&ch, &s, Method::Bdf, &o).unwrap();
    assert_eq!(tr.status, Status::Ok);
    let h = 0.5;
    let mut touched = false;
    for j in 0..tr.len() {
        let y = tr.state(j);
        let (s, co) = y[0].sin_cos();
        let (cy, vy, w) = (y[4], y[6], y[1]);
        let near_y = cy - h * s;
        let near_vy = vy - h * co * w;
        if near_y < -drop {
            touched = true;
        }
        if touched && near_vy >= 0.0 {
            return (-(vy + h * co * w), v);
        }
    }
    panic!("the compression never ended (k = {k})");
}

/// The one-rod impact: as the contact stiffens (plastic damping, `c v =
/// 1000`: a rebound of at most `1 / c`), the simulated far-end speed tends
/// to the rigid-body closed form; its error falls with the contact time.
#[test]
fn a_rod_hitting_the_floor_at_one_end_sends_its_far_end_down_at_the_closed_form() {
    let (theta, drop): (f64, f64) = (0.05, 0.5);
    let v = (2.0 * drop).sqrt();
    let want = far_end_speed(v, theta);
    let errors: Vec<f64> = [1e4, 1e5, 1e6]
        .iter()
        .map(|&k| {
            let (got, _) = one_rod_impact(k, 1e3 / v, theta, drop);
            (got / want - 1.0).abs()
        })
        .collect();
    eprintln!("one rod: far-end speed error {errors:?} (closed form {want})");
    assert!(errors.windows(2).all(|e| e[1] < 0.7 * e[0]), "{errors:?}");
    // Measured: 1.1e-3, 5.0e-4, 2.5e-4 (bdf, rtol 1e-10).
    assert!(errors[2] < 1e-3, "{errors:?}");
}

/// No floor key, no floor: the elastic chain's right-hand side is the one
/// it always was (a chain with its floor far below has the same numbers
/// until it gets there, bit for bit).
#[test]
fn a_floor_far_below_changes_nothing_until_it_is_reached() {
    let base = ChainParams {
        links: 6,
        axial_stiffness: Some(1e3),
        ..ChainParams::default()
    };
    let plain = Chain::new(base.clone()).unwrap();
    let far = Chain::new(ChainParams {
        floor: Some(floor(Some(-100.0), 0.0, 1e4, 1.0, 0.5, 0.01)),
        ..base
    })
    .unwrap();
    let start = Start::Stretched {
        p0: [0.0, 0.0],
        p1: [6.0, 0.0],
    };
    let o = opts(2.0, 1e-8, 0.1);
    let a = solve(&plain, &start.state(&plain).unwrap(), Method::Dopri5, &o).unwrap();
    let b = solve(&far, &start.state(&far).unwrap(), Method::Dopri5, &o).unwrap();
    assert_eq!(a.final_state, b.final_state);
    assert_eq!(b.floor_force(b.len() - 1), Some([0.0, 0.0]));
}

/// Bad input is one line naming its key: a start inside the floor, a floor
/// under a pivot moving on a path; a rigid chain on a floor runs the
/// elastic chain at `EA = 1e4 n m g`.
#[test]
fn a_start_inside_the_floor_and_a_moving_pivot_are_refused_by_name() {
    let ch = chain(
        4,
        0.2,
        6.0,
        1e3,
        false,
        floor(Some(1.0), 0.0, 1e4, 0.0, 0.0, 0.01),
    );
    let s = Start::Stretched {
        p0: [0.0, 0.0],
        p1: [6.0, 0.0],
    }
    .state(&ch)
    .unwrap();
    let e = solve(&ch, &s, Method::Dopri5, &opts(1.0, 1e-6, 0.1)).unwrap_err();
    assert_eq!(e.field, "floor.height");
    assert!(!e.to_string().contains('\n'), "{e}");
    assert!(e.to_string().contains(" inside at "), "{e}");
    let moving = Chain::new(ChainParams {
        links: 4,
        pivot: Pivot {
            jerk: [0.5, 0.0],
            ..Pivot::default()
        },
        floor: Some(floor(Some(-10.0), 0.0, 1e4, 0.0, 0.0, 0.01)),
        ..ChainParams::default()
    })
    .unwrap_err();
    assert_eq!(moving.field, "floor.height");
    let rigid = Chain::new(ChainParams {
        links: 4,
        floor: Some(floor(Some(-10.0), 0.0, 1e4, 0.0, 0.0, 0.01)),
        ..ChainParams::default()
    })
    .unwrap();
    assert_eq!(rigid.axial_stiffness(), Some(1e4 * 4.0 * 0.2 * 1.0));
}

/// Cayley's scale: a chain of `n` rods (`L = 1`, mass per length `mu = 1`,
/// `g = 1`) hangs straight down, its rods zigzagging by `±0.02` rad, its
/// lower end touching a floor of stiffness `k` and Hunt–Crossley damping
/// `c`, and is let go at the top at `t = 0`. Returns, at each of `times`,
/// the chain's momentum `P_y` over the ideal's and the work dissipated `W`
/// over the ideal's, and the landed length (`Trajectory::floor_landed_length`).
fn cayley(n: usize, k: f64, c: f64, times: &[f64]) -> Vec<(f64, f64, f64)> {
    let ch = Chain::new(ChainParams {
        length: 1.0,
        links: n,
        mass: 1.0 / n as f64,
        gravity: 1.0,
        pivot: Pivot {
            release: Some(0.0),
            ..Pivot::default()
        },
        floor: Some(floor(None, 0.0, k, c, 0.0, 1.0)),
        ..ChainParams::default()
    })
    .unwrap();
    let angles = (0..n)
        .map(|i| -std::f64::consts::FRAC_PI_2 + if i % 2 == 0 { 0.02 } else { -0.02 })
        .collect();
    let s = Start::Angles {
        p0: [0.0, 0.0],
        angles,
        rates: None,
    }
    .state(&ch)
    .unwrap();
    let tr = solve(&ch, &s, Method::Bdf, &opts(1.0, 1e-6, 0.1)).unwrap();
    assert_eq!(tr.status, Status::Ok);
    times
        .iter()
        .map(|&t| {
            let j = tr.times.iter().position(|&s| (s - t).abs() < 1e-9).unwrap();
            // The ideal: the part still falling, of mass mu (L - x) with
            // x = g t^2 / 2, moves at -g t; what has landed is at rest, and
            // landing at the speed v costs mu v^2 / 2 per length, so
            // dW/dt = mu (g t)^3 / 2 and W = mu g^3 t^4 / 8.
            let p_ideal = -(1.0 - t * t / 2.0) * t;
            let w_ideal = t.powi(4) / 8.0;
            let w = tr.samples().nth(j).unwrap().dissipated;
            let x = tr.floor_landed_length(j).unwrap();
            (tr.momentum(j)[1] / p_ideal, w / w_ideal, x)
        })
        .collect()
}

/// Cayley's scale, through the momentum its reading integrates: with the
/// floor and gravity the only forces on the released chain,
/// `F(t) = dP_y/dt + M g`, so the ideal's `F = 3 mu g x` (free fall of what
/// has not landed, plastic landing of the rest) is `P_y = -mu (L - x) g t`,
/// and its plastic landings dissipate `W = mu g^3 t^4 / 8`. The scale's
/// reading itself is a train of kicks, one per rod, `l / v` apart
/// (docs/model.md, "The floor"), but the momentum integrates them: at
/// `n = 40`, up to `x = 0.4 L`, it is the ideal's within 5% (two rods'
/// share of what is still falling there). Less than the ideal's work is
/// dissipated, but most of it (the landed rods keep some of their motion
/// and tumble): a band of 0.6 to 1.05. A floor that is missed fails the
/// momentum (the free fall's ratio is `1 / (1 - t^2 / 2)`, 1.14 to 1.68
/// here); an elastic floor (`c = 0`) dissipates nothing and fails the work.
#[test]
fn cayleys_scale_absorbs_the_momentum_and_energy_of_the_landing_chain() {
    let times = [0.5, 0.7, 0.9];
    for (&t, &(p, w, x)) in times.iter().zip(&cayley(40, 1e5, 100.0, &times)) {
        assert!((p - 1.0).abs() < 0.05, "t = {t}: P_y / ideal = {p}");
        assert!((0.6..1.05).contains(&w), "t = {t}: W / ideal = {w}");
        // What has landed is what the free fall has brought down,
        // x = g t^2 / 2, to a rod l = 0.025 (measured: 0.0125, 0.0175
        // and 0.0075 above it at t = 0.5, 0.7, 0.9); one read off the
        // contact forces is 0 at every one of these samples.
        assert!(
            (x - t * t / 2.0).abs() <= 1.0 / 40.0,
            "t = {t}: landed length {x} against g t^2 / 2 = {}",
            t * t / 2.0
        );
    }
    for (&t, &(_, w, _)) in times.iter().zip(&cayley(40, 1e5, 0.0, &times)) {
        assert!(
            w < 0.1,
            "t = {t}: an elastic floor dissipates W / ideal = {w}"
        );
    }
}
