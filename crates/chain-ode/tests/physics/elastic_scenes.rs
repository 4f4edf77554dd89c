//! The elastic chain with a rod profile, a tip mass and a moving or
//! released pivot: statics, the Jacobian, free fall, the accelerating
//! support, the energy balance and the rigid limit, against closed forms
//! and independent formulations.

use chain_ode::elastic::{self, ElasticDae, ElasticSystem};
use chain_ode::{
    solve, Chain, ChainParams, Method, Pivot, Profile, SolveOptions, Start, State, Status,
    Trajectory,
};

use crate::{dist, max_abs, tolerances};

/// A deterministic pseudo-random number in [-1, 1].
fn noise(k: usize) -> f64 {
    let x = (k as f64 * 12.9898 + 78.233).sin() * 43758.5453;
    2.0 * (x - x.floor()) - 1.0
}

/// Random relative rod masses and lengths (within a factor 3), seeded by `k`.
fn random_profile(n: usize, k: usize) -> Profile {
    Profile {
        masses: Some((0..n).map(|i| 2.0 + noise(i + 31 * k)).collect()),
        lengths: Some((0..n).map(|i| 2.0 + noise(i + 31 * k + 7)).collect()),
        ..Profile::default()
    }
}

/// A chain of `n` rods (`L = 6`, `m = 0.2`, `g = 1`), elastic with `ea`.
fn params(n: usize, ea: f64) -> ChainParams {
    ChainParams {
        links: n,
        axial_stiffness: Some(ea),
        ..ChainParams::default()
    }
}

/// The chain hanging straight down from the origin, at rest.
fn hanging(chain: &Chain) -> State {
    Start::Angles {
        p0: [0.0, 0.0],
        angles: vec![-std::f64::consts::FRAC_PI_2; chain.links()],
        rates: None,
    }
    .state(chain)
    .unwrap()
}

/// The folded start (both ends at the origin), at rest.
fn folded_at_origin(chain: &Chain) -> State {
    Start::Folded {
        p0: [0.0, 0.0],
        down: None,
    }
    .state(chain)
    .unwrap()
}

/// A straight chain at `angle` from the horizontal, at rest.
fn slanted(chain: &Chain, angle: f64) -> State {
    Start::Angles {
        p0: [0.0, 0.0],
        angles: vec![angle; chain.links()],
        rates: None,
    }
    .state(chain)
    .unwrap()
}

/// Rod `i`'s length and mass from the test's own numbers: the profile's
/// lists scaled to `L` and `n m`.
fn rods_of(p: &ChainParams) -> (Vec<f64>, Vec<f64>) {
    let scaled = |list: &Option<Vec<f64>>, total: f64| match list {
        Some(l) => {
            let s: f64 = l.iter().sum();
            l.iter().map(|x| x * total / s).collect()
        }
        None => vec![total / p.links as f64; p.links],
    };
    (
        scaled(&p.profile.lengths, p.length),
        scaled(&p.profile.masses, p.mass * p.links as f64),
    )
}

/// The exact Jacobian-vector product and the banded Jacobian the sparse
/// BDF factorises are the right-hand side's derivatives (central
/// differences), at a time where a driven pivot moves, for random rod
/// profiles with a tip mass, held and let go; nothing outside the band
/// depends on anything (the dense row of `W` apart).
#[test]
fn the_jvp_and_the_band_hold_with_profiles_a_tip_mass_and_a_moving_pivot() {
    for (case, n) in [1, 2, 5, 7].into_iter().enumerate() {
        let p = ChainParams {
            damping: 0.05,
            axial_damping: 0.3,
            bending_stiffness: 0.2,
            tip_mass: 0.4 + 0.3 * noise(case),
            profile: random_profile(n, case),
            pivot: Pivot {
                amplitude: [0.2, 0.1],
                frequency: 3.0,
                acceleration: [0.1, -0.3],
                release: (case % 2 == 1).then_some(0.0),
                ..Pivot::default()
            },
            ..params(n, 200.0)
        };
        let chain = Chain::new(p).unwrap();
        let dim = 6 * n + 1;
        let t = 0.7;
        let y: Vec<f64> = (0..dim).map(|k| 2.0 * noise(k + 17 * n)).collect();
        let mut sys = ElasticSystem::new(&chain);
        let dae = ElasticDae::new(&chain);
        let mut jac = vec![f64::NAN; dim * dim];
        dae.jacobian_entries_at(t, &y, &mut |r, c, v| {
            assert!(jac[r * dim + c].is_nan(), "({r}, {c}) emitted twice");
            jac[r * dim + c] = v;
        });
        let (mut fp, mut fm, mut jv) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
        sys.rhs(t, &y, &mut fp);
        let mut fd_dae = vec![0.0; dim];
        dae.rhs_at(t, &y, &mut fd_dae);
        assert_eq!(fp, fd_dae, "the DAE's right-hand side is the system's");
        let rounding = 1e-9 * max_abs(&fp);
        for c in 0..dim {
            let h = 1e-6 * (1.0 + y[c].abs());
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[c] += h;
            ym[c] -= h;
            sys.rhs(t, &yp, &mut fp);
            sys.rhs(t, &ym, &mut fm);
            let mut e = vec![0.0; dim];
            e[c] = 1.0;
            sys.jvp(t, &y, &e, &mut jv);
            for r in 0..dim {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                let scale = 1.0 + fd.abs() + rounding * 1e6;
                assert!(
                    (jv[r] - fd).abs() < 1e-6 * scale,
                    "n = {n}: jvp ({r}, {c}) {} vs {fd}",
                    jv[r]
                );
                if r == 2 * n {
                    continue;
                }
                let b = jac[r * dim + c];
                if b.is_nan() {
                    assert!(
                        fd.abs() < 1e-8 + rounding,
                        "n = {n}: ({r}, {c}) = {fd} outside the band"
                    );
                } else {
                    assert!(
                        (b - fd).abs() < 1e-6 * scale,
                        "n = {n}: band ({r}, {c}) {b} vs {fd}"
                    );
                }
            }
        }
    }
}

/// A hanging rope of unequal rods with a tip mass, its support
/// accelerating upward: joint `k` carries the rope from the centre of rod
/// `k - 1` to that of rod `k`, `s_k = (l_{k-1} + l_k) / 2` (the pivot the
/// half rod `s_0 = l_0 / 2`), and stretches as that segment does,
/// `T_k s_k / EA` under the tension it carries,
/// `T_k = (g + a) (M_t + sum_{j >= k} m_j)` (the test's own sums), so the
/// tip hangs `L + sum T_k s_k / EA` below the pivot; and that start is the
/// chain's equilibrium in the accelerating frame (every acceleration zero
/// to rounding). A joint spring on the wrong rod's length, or a tip mass
/// left out of the statics, moves the tip or leaves a force.
#[test]
fn a_hanging_profiled_rope_with_a_tip_mass_stretches_as_a_rope() {
    for (case, n) in [1, 3, 8].into_iter().enumerate() {
        let (ea, mt, a) = (300.0, 0.7, 0.4);
        let p = ChainParams {
            tip_mass: mt,
            damping: 0.01,
            axial_damping: 0.1,
            bending_stiffness: 0.05,
            profile: random_profile(n, case + 40),
            pivot: Pivot {
                acceleration: [0.0, a],
                ..Pivot::default()
            },
            ..params(n, ea)
        };
        let (lengths, masses) = rods_of(&p);
        let chain = Chain::new(p.clone()).unwrap();
        let y = elastic::start_state(&chain, &hanging(&chain));
        let g = p.gravity + a;
        let mut drop = 0.0;
        for k in 0..n {
            let t_k = g * (mt + masses[k..].iter().sum::<f64>());
            let share = match k {
                0 => 0.5 * lengths[0],
                _ => 0.5 * (lengths[k - 1] + lengths[k]),
            };
            drop += lengths[k] + t_k * share / ea;
        }
        let tip = elastic::tip(&chain, [0.0, 0.0], &y);
        assert!(tip[0].abs() < 1e-13, "n = {n}: {tip:?}");
        assert!(
            (tip[1] + drop).abs() < 1e-12 * drop,
            "n = {n}: tip {} vs {}",
            tip[1],
            -drop
        );
        let mut f = vec![0.0; y.len()];
        ElasticSystem::new(&chain).rhs(0.0, &y, &mut f);
        let acc = f[n..2 * n].iter().chain(&f[4 * n + 1..]);
        let worst = acc.fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(worst < 1e-11, "n = {n}: an acceleration {worst:e} at rest");
    }
}

/// Linearised about the hanging equilibrium, the rods' vertical motion is a
/// chain of masses `m_i` and springs `K_k = EA / s_k` (`s_k` joint `k`'s
/// share of the rope, centre to centre, half a rod at the pivot), fixed at the top and
/// free at the bottom, the tip mass riding on the last rod: the block of the
/// exact Jacobian is `-M^-1 K` with the tridiagonal `K` and the diagonal `M`
/// assembled here from the test's own numbers.
#[test]
fn the_axial_block_of_a_profiled_rope_is_its_spring_chain() {
    let n = 6;
    let (ea, mt) = (500.0, 0.3);
    let p = ChainParams {
        tip_mass: mt,
        profile: random_profile(n, 3),
        ..params(n, ea)
    };
    let (lengths, masses) = rods_of(&p);
    let chain = Chain::new(p).unwrap();
    let y = elastic::start_state(&chain, &hanging(&chain));
    let mut sys = ElasticSystem::new(&chain);
    let (oy, ovy) = (3 * n + 1, 5 * n + 1);
    let mut jv = vec![0.0; y.len()];
    for j in 0..n {
        let mut e = vec![0.0; y.len()];
        e[oy + j] = 1.0;
        sys.jvp(0.0, &y, &e, &mut jv);
        for i in 0..n {
            let k = |q: usize| match q {
                0 => 2.0 * ea / lengths[0],
                _ => 2.0 * ea / (lengths[q - 1] + lengths[q]),
            };
            let stiff = match i {
                _ if i == j => k(i) + if i + 1 < n { k(i + 1) } else { 0.0 },
                _ if i + 1 == j => -k(j),
                _ if j + 1 == i => -k(i),
                _ => 0.0,
            };
            let m = masses[i] + if i + 1 == n { mt } else { 0.0 };
            let want = -stiff / m;
            assert!(
                (jv[ovy + i] - want).abs() < 1e-9 * (1.0 + want.abs()),
                "({i}, {j}): {} vs {want}",
                jv[ovy + i]
            );
        }
    }
}

/// Both ends let go at `t = 0`: nothing but gravity acts, so every rod
/// falls at `g` and keeps its angle, and every gap keeps its start value
/// (zero: a chain in free fall is unstretched), to rounding, with unequal
/// rods, a tip mass and a folded start; the tip's acceleration is `-g`.
#[test]
fn both_ends_let_go_an_elastic_chain_falls_as_one_body() {
    let n = 8;
    let p = ChainParams {
        tip_mass: 0.5,
        axial_damping: 0.2,
        damping: 0.01,
        profile: random_profile(n, 9),
        pivot: Pivot {
            release: Some(0.0),
            ..Pivot::default()
        },
        ..params(n, 1e4)
    };
    let chain = Chain::new(p).unwrap();
    let s = folded_at_origin(&chain);
    let opts = SolveOptions {
        output_dt: Some(0.25),
        ..tolerances(1.0, 1e-10, 1e-12)
    };
    let tr = solve(&chain, &s, Method::Dop853, &opts).unwrap();
    assert_eq!(tr.status, Status::Ok);
    let y0 = tr.state(0).to_vec();
    let g = chain.gravity();
    for k in 0..tr.len() {
        let (t, y) = (tr.times[k], tr.state(k));
        for i in 0..n {
            assert!((y[i] - y0[i]).abs() < 1e-13, "angle {i} at t = {t}");
            let (x, yy) = (y[2 * n + 1 + i], y[3 * n + 1 + i]);
            assert!((x - y0[2 * n + 1 + i]).abs() < 1e-13, "x {i} at {t}");
            let want = y0[3 * n + 1 + i] - 0.5 * g * t * t;
            assert!((yy - want).abs() < 1e-12, "y {i} at {t}: {yy} vs {want}");
        }
        let forces = tr.joint_forces(k);
        assert!(
            forces.iter().flatten().all(|f| f.abs() < 1e-9),
            "{forces:?}"
        );
    }
    let mut f = vec![0.0; y0.len()];
    ElasticSystem::new(&chain).rhs(0.0, &y0, &mut f);
    let a = elastic::tip_acceleration(&chain, &y0, &f);
    assert!(
        a[0].abs() < 1e-12 * g && (a[1] + g).abs() < 1e-12 * g,
        "{a:?}"
    );
}

/// A support accelerating uniformly at `a` (downward) gives the same motion
/// relative to it as gravity `g - a` with a fixed support: the elastic
/// states (relative to the pivot) of the two runs agree to the
/// integration's accuracy, with a profile, a tip mass and dashpots.
#[test]
fn an_accelerating_support_is_gravity_changed() {
    let n = 6;
    let a = 0.35;
    let base = ChainParams {
        tip_mass: 0.4,
        axial_damping: 0.05,
        damping: 0.002,
        profile: random_profile(n, 5),
        ..params(n, 2e3)
    };
    let moving = Chain::new(ChainParams {
        pivot: Pivot {
            acceleration: [0.0, -a],
            ..Pivot::default()
        },
        ..base.clone()
    })
    .unwrap();
    let fixed = Chain::new(ChainParams {
        gravity: base.gravity - a,
        ..base
    })
    .unwrap();
    let s = slanted(&fixed, -0.4);
    let opts = SolveOptions {
        output_dt: Some(0.1),
        ..tolerances(1.5, 1e-11, 1e-13)
    };
    let tm = solve(&moving, &s, Method::Dop853, &opts).unwrap();
    let tf = solve(&fixed, &s, Method::Dop853, &opts).unwrap();
    assert_eq!((tm.status, tf.status), (Status::Ok, Status::Ok));
    let mut worst: f64 = 0.0;
    for k in 0..tm.len() {
        let (ym, yf) = (tm.state(k), tf.state(k));
        for (i, (u, v)) in ym.iter().zip(yf).enumerate() {
            if i != 2 * n {
                worst = worst.max((u - v).abs());
            }
        }
    }
    eprintln!("accelerating support against g - a: {worst:e}");
    assert!(worst < 1e-7, "{worst:e}");
    // The tip the samples report is in the inertial frame: P0(t) added.
    let k = tm.len() - 1;
    let t = tm.times[k];
    let (pm, pf) = (tm.tip(k), tf.tip(k));
    assert!(
        (pm[1] - (pf[1] - 0.5 * a * t * t)).abs() < 1e-7,
        "{pm:?} {pf:?}"
    );
}

/// `E + W = E(0)` along runs with every term at once (unequal rods, a tip
/// mass, friction, dashpots, bending, a pivot that oscillates, jerks and
/// accelerates, held and let go mid-run): the energy is the inertial
/// frame's and `W` counts the support's work; the samples' and the
/// observer's balances both hold. A term left out of the energy, the
/// support's work or the release's bookkeeping fails it.
#[test]
fn the_energy_balance_holds_with_every_new_term() {
    for (case, release) in [None, Some(0.6), Some(0.0)].into_iter().enumerate() {
        let n = 7;
        let p = ChainParams {
            tip_mass: 0.3,
            axial_damping: 0.02,
            damping: 0.003,
            bending_stiffness: 0.05,
            profile: random_profile(n, 11 + case),
            pivot: Pivot {
                amplitude: [0.1, 0.15],
                frequency: 4.0,
                acceleration: [0.2, 0.1],
                jerk: [0.3, -0.2],
                jerk_time: 0.5,
                release,
            },
            ..params(n, 1e3)
        };
        let chain = Chain::new(p).unwrap();
        let s = folded_at_origin(&chain);
        for method in [Method::Dop853, Method::Bdf] {
            let opts = SolveOptions {
                output_dt: Some(0.05),
                ..tolerances(1.2, 1e-10, 1e-12).at_accuracy(method, 1e-9)
            };
            let tr = solve(&chain, &s, method, &opts).unwrap();
            assert_eq!(tr.status, Status::Ok, "{method} case {case}");
            let e0 = tr.energy(0);
            let worst = (0..tr.len())
                .map(|k| (tr.energy(k) + tr.sample(k).dissipated - e0).abs())
                .fold(0.0, f64::max);
            let scale = chain.energy_scale();
            let bound = if method == Method::Bdf { 1e-8 } else { 1e-9 } * scale;
            eprintln!(
                "balance {method} case {case}: {:.2e} / {:.2e} (E spans {:.2e})",
                worst / scale,
                tr.summary.energy_balance_error / scale,
                (tr.energy(tr.len() - 1) - e0).abs() / scale
            );
            assert!(worst < bound, "{method} case {case}: {worst:e}");
            assert!(
                tr.summary.energy_balance_error < bound,
                "{method} case {case}"
            );
            if release != Some(0.0) {
                let moved = (tr.energy(tr.len() - 1) - e0).abs();
                assert!(moved > 100.0 * bound, "the support did no work");
            }
        }
    }
}

/// The largest distance between the tips of two runs sampled alike.
fn tip_path_error(a: &Trajectory, b: &Trajectory) -> f64 {
    (0..a.len().min(b.len()))
        .map(|k| dist(a.tip(k), b.tip(k)))
        .fold(0.0, f64::max)
}

/// As `EA` grows at fixed `n`, the elastic chain's tip path tends to the
/// rigid chain's at first order in `1/EA`, for each new term on its own: a
/// rod profile, a tip mass, a driven pivot (the rigid chain's recursion
/// shares no equation with the elastic one). The ratio per decade of `EA`
/// must lie in [6, 16] (order 0.78 to 1.2): a term that differs between the
/// models leaves an offset that does not fall (ratio ~1).
#[test]
fn the_rigid_limit_is_first_order_with_a_profile_a_tip_mass_and_a_driven_pivot() {
    let n = 6;
    let cases: [(&str, ChainParams); 3] = [
        (
            "profile",
            ChainParams {
                profile: random_profile(n, 21),
                ..params(n, 1.0)
            },
        ),
        (
            "tip mass",
            ChainParams {
                tip_mass: 0.8,
                ..params(n, 1.0)
            },
        ),
        (
            "driven pivot",
            ChainParams {
                pivot: Pivot {
                    amplitude: [0.15, 0.1],
                    frequency: 3.0,
                    acceleration: [0.0, 0.3],
                    ..Pivot::default()
                },
                ..params(n, 1.0)
            },
        ),
    ];
    for (label, p) in cases {
        let rigid = Chain::new(ChainParams {
            axial_stiffness: None,
            ..p.clone()
        })
        .unwrap();
        let s = slanted(&rigid, -0.3);
        let opts = SolveOptions {
            output_dt: Some(0.05),
            ..tolerances(1.0, 1e-11, 1e-13)
        };
        let r = solve(&rigid, &s, Method::Dop853, &opts).unwrap();
        assert_eq!(r.status, Status::Ok, "{label}");
        let errors: Vec<f64> = [1e3, 1e4, 1e5]
            .iter()
            .map(|&ea| {
                let chain = Chain::new(ChainParams {
                    axial_stiffness: Some(ea),
                    ..p.clone()
                })
                .unwrap();
                let e = solve(&chain, &s, Method::Dop853, &opts).unwrap();
                assert_eq!(e.status, Status::Ok, "{label} EA {ea}");
                tip_path_error(&r, &e)
            })
            .collect();
        eprintln!("rigid limit, {label}: tip path errors {errors:?}");
        for pair in errors.windows(2) {
            let ratio = pair[0] / pair[1];
            assert!((6.0..=16.0).contains(&ratio), "{label}: {errors:?}");
        }
    }
}
