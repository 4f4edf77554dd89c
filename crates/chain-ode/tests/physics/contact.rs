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
/// to rounding, at steps from `1e-4` to `1e-2` of the fall's time.
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
                (far / want - 1.0).abs() < 1e-12,
                "theta {theta}, dt {dt}: far end {far}, closed form {want} at t = {t}"
            );
            assert!(
                near.abs() < 1e-12 * v && vc[0].abs() < 1e-12 * v,
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
