//! The banded DAE against the O(n) recursion, its analytic Jacobian against
//! central differences, and the sparse BDF built on it against the dense BDF
//! and DOPRI5.

use chain_ode::dae::ChainDae;
use chain_ode::dynamics::{accelerations, Workspace};
use chain_ode::{solve, Chain, Method, Profile, SolveOptions, Start, Status};
use faer::linalg::solvers::Solve;
use faer::Mat;
use proptest::prelude::*;

use crate::{chain_and_state, dist, max_abs, scene};

/// `[phi, w, W = 0]` followed by zeros for the algebraic unknowns.
fn packed(dae: &ChainDae, phi: &[f64], w: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; dae.dim()];
    y[..phi.len()].copy_from_slice(phi);
    y[phi.len()..2 * phi.len()].copy_from_slice(w);
    y
}

/// The recursion's `phi''` and pivot force (physical units).
fn recursion(chain: &Chain, phi: &[f64], w: &[f64]) -> (Vec<f64>, [f64; 2]) {
    let mut acc = vec![0.0; chain.links()];
    let r = accelerations(chain, phi, w, &mut acc, &mut Workspace::new(chain.links()));
    (acc, r.pivot_force)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The recursion's `alpha` and the forces summed from it satisfy every
    /// algebraic equation of the DAE.
    #[test]
    fn the_residual_vanishes_at_the_consistent_state((chain, phi, w) in chain_and_state(60)) {
        let dae = ChainDae::new(&chain);
        let mut y = packed(&dae, &phi, &w);
        dae.make_consistent(&mut y, &mut Workspace::new(chain.links()));
        let mut f = vec![0.0; dae.dim()];
        dae.rhs(&y, &mut f);
        let scale = 1.0 + max_abs(&y[2 * chain.links() + 1..]);
        let worst = max_abs(&f[2 * chain.links() + 1..]);
        prop_assert!(worst < 1e-12 * scale, "residual {worst:e} (scale {scale:e})");
    }

    /// Solving the algebraic equations alone, from zero, by the analytic
    /// Jacobian's algebraic block (one Newton step is exact: they are linear
    /// in `alpha` and `f`) reproduces the recursion's `alpha` and pivot force.
    #[test]
    fn the_algebraic_block_reproduces_the_recursion((chain, phi, w) in chain_and_state(60)) {
        let n = chain.links();
        let dae = ChainDae::new(&chain);
        let (d, dim) = (dae.differential_dim(), dae.dim());
        let y = packed(&dae, &phi, &w);
        let mut r0 = vec![0.0; dim];
        dae.rhs(&y, &mut r0);
        let mut jaa = Mat::<f64>::zeros(dim - d, dim - d);
        dae.jacobian_entries(&y, |r, c, v| {
            if r >= d && c >= d {
                jaa[(r - d, c - d)] = v;
            }
        });
        let rhs = Mat::from_fn(dim - d, 1, |i, _| -r0[d + i]);
        let x = jaa.partial_piv_lu().solve(&rhs);
        let (acc, pivot) = recursion(&chain, &phi, &w);
        let scale = 1.0 + max_abs(&acc);
        for i in 0..n {
            prop_assert!((x[(i, 0)] - acc[i]).abs() < 1e-9 * scale, "alpha_{i}: {} vs {}", x[(i, 0)], acc[i]);
        }
        let ml = chain.mass() * chain.rod_length();
        let fscale = 1.0 + pivot[0].abs().max(pivot[1].abs());
        for k in 0..2 {
            let f = x[(n + k, 0)] * ml;
            prop_assert!((f - pivot[k]).abs() < 1e-9 * fscale, "pivot {k}: {f} vs {}", pivot[k]);
        }
        // The consistent state's pivot force is the same.
        let mut yc = y.clone();
        dae.make_consistent(&mut yc, &mut Workspace::new(n));
        let p = dae.pivot_force(&yc);
        prop_assert!((p[0] * ml - pivot[0]).abs() < 1e-9 * fscale);
        prop_assert!((p[1] * ml - pivot[1]).abs() < 1e-9 * fscale);
    }
}

/// A random but reproducible value in [-1, 1).
fn noise(k: usize) -> f64 {
    let x = (k as f64 * 12.9898 + 78.233).sin() * 43758.5453;
    2.0 * (x - x.floor()) - 1.0
}

#[test]
fn the_analytic_jacobian_matches_central_differences() {
    // The last three: rods of unequal mass and length (a taper, lists).
    let lists = |n: usize, k: usize| Some((0..n).map(|i| 1.0 + ((i * k) % 5) as f64).collect());
    for (n, damping, ei, profile) in [
        (1, 0.3, 0.0, Profile::default()),
        (2, 0.0, 0.0, Profile::default()),
        (5, 0.02, 0.0, Profile::default()),
        (17, 1.0, 0.0, Profile::default()),
        (2, 0.0, 0.7, Profile::default()),
        (9, 0.05, 0.02, Profile::default()),
        (
            2,
            0.1,
            0.0,
            Profile {
                masses: lists(2, 3),
                lengths: lists(2, 2),
                ..Profile::default()
            },
        ),
        (
            7,
            0.02,
            0.0,
            Profile {
                taper: 10.0,
                ..Profile::default()
            },
        ),
        (
            11,
            0.0,
            0.0,
            Profile {
                masses: lists(11, 3),
                lengths: lists(11, 2),
                ..Profile::default()
            },
        ),
    ] {
        let chain = Chain::new(chain_ode::ChainParams {
            links: n,
            damping,
            bending_stiffness: ei,
            profile,
            ..chain_ode::ChainParams::default()
        })
        .unwrap();
        let dae = ChainDae::new(&chain);
        let dim = dae.dim();
        // An inconsistent state: every unknown random.
        let y: Vec<f64> = (0..dim).map(|k| 3.0 * noise(k + 31 * n)).collect();
        let mut jac = vec![0.0; dim * dim];
        let mut seen = vec![false; dim * dim];
        dae.jacobian_entries(&y, |r, c, v| {
            assert!(!seen[r * dim + c], "entry ({r}, {c}) emitted twice");
            seen[r * dim + c] = true;
            jac[r * dim + c] = v;
        });
        let (mut fp, mut fm) = (vec![0.0; dim], vec![0.0; dim]);
        let w_row = 2 * n;
        let mut worst: f64 = 0.0;
        let mut dissipation = vec![0.0; n];
        dae.dissipation_row(&y[n..2 * n], &mut dissipation);
        for c in 0..dim {
            let h = 1e-6 * (1.0 + y[c].abs());
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[c] += h;
            ym[c] -= h;
            dae.rhs(&yp, &mut fp);
            dae.rhs(&ym, &mut fm);
            for r in 0..dim {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                let exact = if r == w_row {
                    // Left out of the Newton matrix; checked through its own row.
                    if (n..2 * n).contains(&c) {
                        dissipation[c - n]
                    } else {
                        0.0
                    }
                } else {
                    jac[r * dim + c]
                };
                let e = (fd - exact).abs() / (1.0 + exact.abs());
                assert!(
                    e < 1e-6,
                    "n = {n}: d f_{r} / d y_{c}: analytic {exact}, central {fd}"
                );
                worst = worst.max(e);
                // Nothing outside the pattern may depend on y_c.
                if r != w_row && !seen[r * dim + c] {
                    assert!(
                        fd.abs() < 1e-7,
                        "n = {n}: ({r}, {c}) = {fd} is not in the pattern"
                    );
                }
            }
        }
        assert!(worst < 1e-6);
    }
}

#[test]
fn the_pattern_has_at_most_thirty_entries_per_rod() {
    for n in [1, 10, 1000] {
        let chain = Chain::report(n, 1e-3).unwrap();
        let dae = ChainDae::new(&chain);
        let mut count = 0;
        dae.jacobian_entries(&vec![0.0; dae.dim()], |_, _, _| count += 1);
        assert!(count <= 30 * n, "n = {n}: {count} entries");
        // Banded: every entry couples neighbouring rods only.
        let rod = |k: usize| -> Option<usize> {
            let d = 2 * n + 1;
            match k {
                k if k < n => Some(k),
                k if k < 2 * n => Some(k - n),
                k if k == 2 * n => None,
                k if k < d + n => Some(k - d),
                k => Some((k - d - n) / 2),
            }
        };
        dae.jacobian_entries(&vec![0.0; dae.dim()], |r, c, _| {
            let (a, b) = (rod(r).unwrap(), rod(c).unwrap());
            assert!(a.abs_diff(b) <= 1, "({r}, {c}) couples rods {a} and {b}");
        });
    }
}

/// At rtol 1e-9 the sparse BDF agrees with the dense BDF and with DOPRI5 at
/// 1e-12 to 1e-6 in tip position, on the report's span and folded starts.
#[test]
fn sparse_bdf_agrees_with_dense_bdf_and_dopri5_on_report_scenes() {
    let scenes = [
        (
            "span d = 3",
            scene(
                50,
                5e-4,
                Start::Catenary {
                    p0: [0.0, 0.0],
                    p1: [3.0, 0.0],
                },
            ),
            8.0,
        ),
        (
            "span d = 1",
            scene(
                50,
                5e-4,
                Start::Catenary {
                    p0: [0.0, 0.0],
                    p1: [1.0, 0.0],
                },
            ),
            4.0,
        ),
        (
            "folded",
            scene(
                50,
                1e-3,
                Start::Folded {
                    p0: [0.0, 0.0],
                    down: None,
                },
            ),
            3.0,
        ),
    ];
    for (name, (chain, s), t_end) in scenes {
        let opts = |rtol: f64| SolveOptions {
            t_end,
            rtol,
            atol: rtol * 1e-2,
            ..Default::default()
        };
        let sparse = solve(&chain, &s, Method::Bdf, &opts(1e-9)).unwrap();
        let dense = solve(&chain, &s, Method::BdfDense, &opts(1e-9)).unwrap();
        let reference = solve(&chain, &s, Method::Dopri5, &opts(1e-12)).unwrap();
        for tr in [&sparse, &dense, &reference] {
            assert_eq!(tr.status, Status::Ok, "{name}: {}", tr.method);
        }
        let d_ref = dist(sparse.summary.tip_end, reference.summary.tip_end);
        let d_dense = dist(sparse.summary.tip_end, dense.summary.tip_end);
        assert!(d_ref < 1e-6, "{name}: sparse vs DOPRI5 {d_ref:e}");
        assert!(d_dense < 1e-6, "{name}: sparse vs dense {d_dense:e}");
        // The energy balance holds to the tolerance's order (M g L = 60).
        let scale = chain.energy_scale();
        assert!(
            sparse.summary.energy_balance_error < 1e-6 * scale,
            "{name}: balance {:e}",
            sparse.summary.energy_balance_error
        );
    }
}
