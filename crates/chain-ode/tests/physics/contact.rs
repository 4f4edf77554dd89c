//! The floor as a constraint (`docs/model.md`, "The floor as a
//! constraint"), `moreau-jean` on the rigid chain: each check a closed
//! form a wrong contact law fails, at any step.

use chain_ode::{
    solve, Chain, ChainParams, Floor, FloorLaw, Method, Pivot, Profile, SolveOptions, Start,
    Status, Trajectory,
};

/// A constraint floor through `(0, height)` (or touching the start) at
/// the angle `angle`, with friction `mu` and restitution `e`.
pub fn floor(height: Option<f64>, angle: f64, mu: f64, e: f64) -> Floor {
    Floor {
        height,
        angle,
        stiffness: 1.0,
        damping: 0.0,
        friction: mu,
        slip_speed: 1.0,
        law: FloorLaw::Constraint,
        restitution: e,
    }
}

/// `n` rods of mass `m` each, length `len`, `g`, the pivot let go at the
/// start when `free`, on `floor`.
pub fn chain(n: usize, m: f64, len: f64, g: f64, free: bool, floor: Floor) -> Chain {
    Chain::new(ChainParams {
        length: len,
        links: n,
        mass: m,
        gravity: g,
        pivot: Pivot {
            release: free.then_some(0.0),
            ..Pivot::default()
        },
        floor: Some(floor),
        ..ChainParams::default()
    })
    .unwrap()
}

/// `moreau-jean` at the step `dt` to `t_end`, sampled at every step.
pub fn run(chain: &Chain, angles: Vec<f64>, dt: f64, t_end: f64) -> Trajectory {
    let start = Start::Angles {
        p0: [0.0, 0.0],
        angles,
        rates: None,
    }
    .state(chain)
    .unwrap();
    let options = SolveOptions {
        t_end,
        dt,
        output_dt: Some(dt),
        ..SolveOptions::default()
    };
    let traj = solve(chain, &start, Method::MoreauJean, &options).unwrap();
    assert_eq!(traj.status, Status::Ok, "{:?}", traj.stats);
    traj
}

/// One rod (`L = 1`, `m = 1`, `g = 1`) at the angle `theta` from the
/// horizontal, its lower end `0.5` above a level floor, let go: it falls
/// without turning, and in the step where its lower end is first pushed
/// the impulse is the plastic impact's, `P = m v / (1 + 3 cos² theta)`,
/// with `v` the speed the free fall reached at that step's end, `g t`
/// (exact: the midpoint step of a constant force is). The far end then
/// moves down at `6 v cos² theta / (1 + 3 cos² theta)`, the centre at
/// `3 v cos² theta / (1 + 3 cos² theta)`, and the end that landed not at
/// all (the ends' velocities in the configuration the impulse acted in):
/// to rounding (measured: 2.2e-16 of the far end's velocity), at steps
/// from `1e-4` to `1e-2` of the fall's time.
#[test]
fn one_rods_plastic_impact_is_its_closed_form_at_any_step() {
    for theta in [0.05f64, 0.5, 1.0] {
        for dt in [1e-4, 1e-3, 3e-3, 1e-2] {
            let c = chain(1, 1.0, 1.0, 1.0, true, floor(Some(-0.5), 0.0, 0.0, 0.0));
            let traj = run(&c, vec![theta], dt, 1.2);
            let k = (0..traj.len())
                .find(|&k| traj.floor_force(k).unwrap()[1] > 0.0)
                .unwrap();
            let t = traj.times[k];
            let v = t; // g t
            let c2 = theta.cos().powi(2);
            // The motion after the impulse: the centre's velocity (m = 1)
            // and the rate, and the ends' velocities in the configuration
            // of the impact (the angle the rod fell at).
            let vc = traj.momentum(k);
            let w = traj.sample(k).rates[0];
            let hc = 0.5 * theta.cos();
            let (far, near) = (vc[1] + w * hc, vc[1] - w * hc);
            let want = -6.0 * v * c2 / (1.0 + 3.0 * c2);
            assert!(
                (far / want - 1.0).abs() < 1e-14,
                "theta {theta}, dt {dt}: far end {far}, closed form {want} at t = {t}"
            );
            assert!(
                near.abs() < 1e-14 * v && vc[0].abs() < 1e-14 * v,
                "theta {theta}, dt {dt}: the landed end moves at {near}, the centre across at {}",
                vc[0]
            );
            let want_p = -3.0 * v * c2 / (1.0 + 3.0 * c2);
            assert!(
                (vc[1] / want_p - 1.0).abs() < 1e-12,
                "theta {theta}, dt {dt}: centre {vc:?}, closed form {want_p}"
            );
            // The impulse of the step, as its averaged force over the step.
            let f = traj.floor_force(k).unwrap()[1];
            let want_f = v / (1.0 + 3.0 * c2) / dt;
            assert!(
                (f / want_f - 1.0).abs() < 1e-12,
                "theta {theta}, dt {dt}: force {f}, closed form {want_f}"
            );
        }
    }
}

/// A straight chain laid on a level floor, its pivot let go: it stays at
/// rest exactly, and the floor carries each joint's share of the weight
/// exactly: `(m_{k−1} + m_k) g / 2` at a joint between two rods, `m g / 2`
/// at either end, with or without friction, equal or unequal rods.
#[test]
fn a_chain_at_rest_on_a_level_floor_carries_its_weight_per_joint() {
    for (mu, masses) in [
        (0.0, None),
        (0.5, None),
        (0.3, Some(vec![1.0, 3.0, 0.5, 2.0, 1.0, 1.5, 0.7, 0.3])),
    ] {
        let n = 8;
        let mut params = chain(n, 0.2, 6.0, 1.0, true, floor(None, 0.0, mu, 0.0))
            .params()
            .clone();
        if let Some(m) = &masses {
            params.profile = Profile {
                masses: Some(m.clone()),
                ..Profile::default()
            };
        }
        let c = Chain::new(params).unwrap();
        let traj = run(&c, vec![0.0; n], 1e-2, 0.5);
        let m: Vec<f64> = (0..n)
            .map(|i| {
                0.2 * masses
                    .as_ref()
                    .map_or(1.0, |ms| ms[i] / ms.iter().sum::<f64>() * n as f64)
            })
            .collect();
        for k in 1..traj.len() {
            let joints = traj.floor_joint_forces(k).unwrap();
            for (j, f) in joints.iter().enumerate() {
                let left = if j > 0 { m[j - 1] } else { 0.0 };
                let right = if j < n { m[j] } else { 0.0 };
                let want = 0.5 * (left + right);
                assert!(
                    (f[1] / want - 1.0).abs() < 1e-12 && f[0].abs() < 1e-12 * want,
                    "mu {mu}, masses {masses:?}: joint {j} carries {f:?}, its share {want}"
                );
            }
            for s in traj.sample(k).rates {
                assert!(s.abs() < 1e-14, "mu {mu}: a rate {s}");
            }
            assert!(traj.momentum(k)[0].abs() < 1e-14 && traj.momentum(k)[1].abs() < 1e-14);
        }
    }
}

/// A chain of 6 rods laid along a floor that rises at the angle `a`
/// (touching it), its pivot let go, with friction `mu`: `moreau-jean` at
/// `dt` for `steps` steps.
fn on_slope(a: f64, mu: f64, dt: f64, steps: usize) -> Trajectory {
    let n = 6;
    let c = chain(n, 0.2, 6.0, 1.0, true, floor(None, a, mu, 0.0));
    run(&c, vec![a; n], dt, dt * steps as f64)
}

/// The friction angle, sharp: on a slope just below it (`tan a = mu (1 −
/// 1e-6)`) and well below, the chain stays at rest exactly (no rate, no
/// momentum beyond rounding), the floor carrying its weight; just above
/// (`tan a = mu (1 + 1e-6)`) and well above, the whole chain slides down
/// with the acceleration `g (sin a − mu cos a)` exactly from the first
/// step, its momentum `M g (sin a − mu cos a) t` along the slope and none
/// across it.
#[test]
fn the_friction_angle_is_sharp_rest_below_and_the_slide_above() {
    let mu = 0.4f64;
    let at = mu.atan();
    let m_total = 6.0 * 0.2;
    for (a, sliding) in [
        ((mu * (1.0 - 1e-6)).atan(), false),
        (0.5 * at, false),
        ((mu * (1.0 + 1e-6)).atan(), true),
        (1.5 * at, true),
    ] {
        let dt = 1e-2;
        let traj = on_slope(a, mu, dt, 50);
        let acc = (a.sin() - mu * a.cos()).max(0.0);
        let (s, c) = a.sin_cos();
        for k in 1..traj.len() {
            let t = traj.times[k];
            let p = traj.momentum(k);
            // Along the slope (up positive) and across it.
            let (along, across) = (p[0] * c + p[1] * s, -p[0] * s + p[1] * c);
            let want = -m_total * acc * t;
            // Measured: 7e-16 of itself well above the angle, 1e-16 of
            // M g t (3.6e-10 of itself) just above it.
            if sliding {
                assert!(
                    (along - want).abs() < 1e-14 * m_total * t,
                    "a = {a}: momentum along {along}, want {want} at t = {t}"
                );
            } else {
                assert!(
                    along.abs() < 1e-14,
                    "a = {a}: at rest, yet {along} at t = {t}"
                );
            }
            assert!(across.abs() < 1e-13, "a = {a}: across the slope {across}");
            for w in traj.sample(k).rates {
                assert!(w.abs() < 1e-13, "a = {a}: a rod turns at {w}");
            }
            // The floor holds the weight across the slope; along it,
            // friction holds it (rest) or gives mu N (sliding).
            let f = traj.floor_force(k).unwrap();
            let (f_along, f_across) = (f[0] * c + f[1] * s, -f[0] * s + f[1] * c);
            let w = m_total * 1.0;
            assert!(
                (f_across / (w * c) - 1.0).abs() < 1e-12,
                "a = {a}: normal {f_across}"
            );
            let want_t = if sliding { mu * w * c } else { w * s };
            assert!(
                (f_along / want_t - 1.0).abs() < 1e-9,
                "a = {a}: friction {f_along}, want {want_t}"
            );
        }
    }
}

/// A level chain of 5 rods dropped from `0.5` onto a level floor, with
/// restitution `e`: in the step of the impact every joint leaves at `e`
/// times the speed it came in with, `v = g t` (the free fall's at that
/// step's end, which the impulse acts on), the chain not turning; the work
/// `W` the impulses took is Kelvin's `M v² (1 − e²) / 2`, computed from
/// the impulses and the velocities either side (none for an elastic
/// impact), and the energy balance `E + W = E(0)` holds to rounding before
/// the impact and after it within `2 M g h v`: the step does not know
/// when in it the impact came (`M g h v / 2` either way), and the
/// projection lifts the chain out of the floor by at most `h v / 2`.
#[test]
fn an_impact_restitutes_e_and_its_loss_is_in_the_work() {
    for e in [0.0, 0.5, 1.0] {
        let n = 5;
        let c = chain(n, 0.2, 6.0, 1.0, true, floor(Some(-0.5), 0.0, 0.3, e));
        let dt = 3e-3;
        let traj = run(&c, vec![0.0; n], dt, 1.3);
        let k = (0..traj.len())
            .find(|&k| traj.floor_force(k).unwrap()[1] > 0.0)
            .unwrap();
        let (t, m) = (traj.times[k], 1.0);
        let p = traj.momentum(k);
        assert!(
            (p[1] - e * m * t).abs() < 1e-13 && p[0].abs() < 1e-15,
            "e = {e}: momentum {p:?} after the impact at t = {t}, want {}",
            e * m * t
        );
        for w in traj.sample(k).rates {
            assert!(w.abs() < 1e-13, "e = {e}: a rod turns at {w}");
        }
        let (e0, w0) = (traj.energy(0), traj.sample(0).dissipated);
        for j in 0..k {
            let balance = traj.energy(j) + traj.sample(j).dissipated - e0 - w0;
            assert!(
                balance.abs() < 1e-14,
                "e = {e}: balance {balance} before the impact"
            );
        }
        let w = traj.sample(k).dissipated;
        let kelvin = 0.5 * m * t * t * (1.0 - e * e);
        assert!(
            (w - kelvin).abs() < 1e-14,
            "e = {e}: W = {w}, Kelvin's {kelvin}"
        );
        let balance = traj.energy(k) + w - e0;
        assert!(
            balance.abs() <= 2.0 * m * 1.0 * dt * t,
            "e = {e}: balance {balance} after the impact, bound {}",
            2.0 * m * dt * t
        );
    }
}

/// Cayley's chain (`scenes/cayley-scale.toml` at `n` rods: `L = 1`,
/// `M = 1`, `g = 1`, its rods at `∓0.02` from the vertical, its lower end
/// touching a level constraint floor, the pivot let go at the start) and
/// its start.
fn cayley(n: usize) -> (Chain, chain_ode::State) {
    let c = chain(
        n,
        1.0 / n as f64,
        1.0,
        1.0,
        true,
        floor(None, 0.0, 0.0, 0.0),
    );
    let angles: Vec<f64> = (0..n)
        .map(|i| -std::f64::consts::FRAC_PI_2 + if i % 2 == 0 { 0.02 } else { -0.02 })
        .collect();
    let start = Start::Angles {
        p0: [0.0, 0.0],
        angles,
        rates: None,
    }
    .state(&c)
    .unwrap();
    (c, start)
}

/// Cayley's scale (`scenes/cayley-scale.toml`: `L = 1`, `M = 1`, `g = 1`,
/// hanging with its rods at `∓0.02` from the vertical and its lower end on
/// the floor, let go at the top), single runs at `dt = 2.5e-3`: the
/// reading over `t = 0.3 .. 1.2` converges to Cayley's `3 mu g x` as the
/// rods shorten. Its error `sqrt(mean (r_j − 1)²)` over the 19 windows
/// falls (measured 0.174, 0.089, 0.030 at `n = 40, 160, 640`; equal
/// pieces landing one by one at their free fall's times, each stopped at
/// once, scatter by 0.24, 0.045, 0.025 on these windows), and the mean
/// reading is within 1% at `n = 640` (measured 0.9996; 1.0197 and 1.0023
/// at `n = 40, 160`).
#[test]
fn cayleys_reading_converges_to_three_times_the_landed_weight() {
    let mut errors = vec![];
    for n in [40, 160, 640] {
        let (c, start) = cayley(n);
        let options = SolveOptions {
            t_end: 1.25,
            dt: 2.5e-3,
            output_dt: Some(chain_ode::analysis::SCALE_HALF_WINDOW),
            ..SolveOptions::default()
        };
        let traj = solve(&c, &start, Method::MoreauJean, &options).unwrap();
        assert_eq!(traj.status, Status::Ok, "n = {n}");
        let r = chain_ode::analysis::scale_reading(
            &traj,
            &chain_ode::analysis::scale_windows(),
            chain_ode::analysis::SCALE_HALF_WINDOW,
        )
        .unwrap();
        let error = (r.windows.iter().map(|w| (w.1 - 1.0).powi(2)).sum::<f64>()
            / r.windows.len() as f64)
            .sqrt();
        eprintln!(
            "cayley n = {n}: reading {:.4} scatter {:.4} error {error:.4}",
            r.mean, r.scatter
        );
        errors.push(error);
        if n == 640 {
            assert!((r.mean - 1.0).abs() < 0.01, "n = {n}: reading {}", r.mean);
        }
    }
    assert!(
        errors[1] < 0.7 * errors[0] && errors[2] < 0.7 * errors[1] && errors[2] < 0.05,
        "{errors:?}"
    );
}

/// `auto` on a constraint floor is `moreau-jean` at `run.dt`: the same
/// steps and states, and its energy balance judged as that fixed step's
/// (the balance of an impact step is `O(M g h v)`, whatever `rtol`), so a
/// tight `rtol` does not turn the run `inaccurate`. Cayley's chain of 40
/// rods at `dt = 2.5e-3` (its balance error is 3% of the energy scale,
/// which `rtol = 1e-9`'s limit, `1e4 rtol` of it, would flag).
#[test]
fn auto_on_a_constraint_floor_is_moreau_jean_at_its_step() {
    let n = 40;
    let (c, start) = cayley(n);
    let options = SolveOptions {
        t_end: 1.25,
        dt: 2.5e-3,
        rtol: 1e-9,
        atol: 1e-12,
        output_dt: Some(0.05),
        ..SolveOptions::default()
    };
    let mj = solve(&c, &start, Method::MoreauJean, &options).unwrap();
    let auto = solve(&c, &start, Method::Auto, &options).unwrap();
    assert_eq!(mj.status, Status::Ok);
    assert_eq!(
        auto.status,
        Status::Ok,
        "{:?}",
        auto.summary.energy_balance_error
    );
    assert!(auto.segments.iter().all(|g| g.method == Method::MoreauJean));
    assert_eq!(auto.stats.steps, mj.stats.steps);
    assert_eq!(auto.len(), mj.len());
    for k in 0..mj.len() {
        assert_eq!(auto.state(k), mj.state(k), "sample {k}");
    }
    assert!(auto.summary.energy_balance_error > 1e-3 * c.energy_scale());
}
