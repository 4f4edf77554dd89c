//! The integrators' checks that need a chain: the sparse BDF and its block
//! LU on the banded DAEs of the rigid and the elastic chain and of BEAM.
//! They are the methods' own tests (the methods know no model: the same
//! checks on toy problems stay beside them), run here, where the chains
//! are, through the methods' test support (`testing`).

/// From the sparse BDF's tests (`bdf.rs`): the chain's derivatives read
/// off its state, the observer's view of a run with and without them, and
/// the LU each DAE gets.
mod bdf {
    use crate::dae::ChainDae;
    use crate::elastic::ElasticDae;
    use crate::{Chain, ChainParams};
    use fc_methods::testing::{integrate_dae, picks_block_lu};
    use fc_methods::with_general_sparse_lu;
    use fc_methods::{Observer, Outcome, SemiExplicitDae, Stats, StepView};
    use fc_methods::{Settings, TimeScales};

    /// `dae` without its [`SemiExplicitDae::derivatives`]: the loop then
    /// evaluates the right-hand side for the observer.
    struct Evaluated<D>(D);

    impl<D: SemiExplicitDae> SemiExplicitDae for Evaluated<D> {
        fn dim(&self) -> usize {
            self.0.dim()
        }
        fn differential_dim(&self) -> usize {
            self.0.differential_dim()
        }
        fn rhs(&self, t: f64, y: &[f64], out: &mut [f64]) {
            self.0.rhs(t, y, out)
        }
        fn jacobian_entries(&self, t: f64, y: &[f64], emit: &mut dyn FnMut(usize, usize, f64)) {
            self.0.jacobian_entries(t, y, emit)
        }
        fn blocks(&self) -> Option<Vec<usize>> {
            self.0.blocks()
        }
    }

    /// Every `(t1, y1, f1)` the loop shows.
    #[derive(Default)]
    struct Record(Vec<(f64, Vec<f64>, Vec<f64>)>);

    impl Observer for Record {
        fn start(&mut self, t0: f64, y0: &[f64], f0: &[f64]) {
            self.0.push((t0, y0.to_vec(), f0.to_vec()));
        }
        fn step(&mut self, s: &StepView<'_>) {
            self.0.push((s.t1, s.y1.to_vec(), s.f1.to_vec()));
        }
    }

    /// A run of `dae` from its consistent start `y` to `t_end`.
    fn run<D: SemiExplicitDae>(dae: D, y: Vec<f64>, t_end: f64) -> (Outcome, Record) {
        let opts = Settings {
            dt: 0.01,
            rtol: 1e-6,
            atol: 1e-8,
            h_min: 0.0,
            max_steps: 100_000,
            h0: None,
            scales: TimeScales::NONE,
            rho_inf: fc_methods::DEFAULT_RHO_INF,
        };
        let mut rec = Record::default();
        let out = integrate_dae(dae, 0.0, y, t_end, &opts, &mut rec);
        (out, rec)
    }

    #[test]
    fn the_chains_derivatives_read_off_the_state_are_the_rhs_and_its_physics() {
        use crate::pivot::Pivot;
        let driven = Pivot {
            amplitude: [0.1, 0.05],
            frequency: 3.0,
            ..Pivot::default()
        };
        let released = Pivot {
            release: Some(0.0),
            ..Pivot::default()
        };
        for (pivot, free) in [(Pivot::default(), false), (driven, false), (released, true)] {
            let chain = Chain::new(ChainParams {
                links: 7,
                damping: 0.3,
                bending_stiffness: 0.1,
                tip_mass: 0.4,
                pivot,
                ..ChainParams::default()
            })
            .unwrap();
            let dae = ChainDae::new(&chain).released(free);
            let (n, d) = (chain.links(), dae.differential_dim());
            let y: Vec<f64> = (0..dae.dim())
                .map(|k| ((k * 7 + 3) % 11) as f64 * 0.37 - 1.5)
                .collect();
            let t = 0.7;
            let mut full = vec![0.0; dae.dim()];
            SemiExplicitDae::rhs(&dae, t, &y, &mut full);
            let mut read = vec![f64::NAN; dae.dim()];
            assert!(SemiExplicitDae::derivatives(&dae, t, &y, &mut read));
            for k in 0..d {
                assert_eq!(read[k].to_bits(), full[k].to_bits(), "{pivot:?} entry {k}");
            }
            // phi' = w, w' = alpha, and W' the friction's power
            // r sum (w_i - w_{i-1})^2 over the joints between rods, less the
            // power of a driven pivot's force on rod 0, -m l f_0 . P0'(t).
            assert_eq!(&read[..n], &y[n..2 * n]);
            assert_eq!(&read[n..2 * n], &y[2 * n + 1..3 * n + 1]);
            let mut power: f64 = (1..n)
                .map(|i| 0.3 * (y[n + i] - y[n + i - 1]).powi(2))
                .sum();
            if pivot.amplitude != [0.0, 0.0] {
                // P0 = A sin(Omega t): P0' = A Omega cos(Omega t).
                let v0 = [0.1 * 3.0 * (3.0 * t).cos(), 0.05 * 3.0 * (3.0 * t).cos()];
                let (f0x, f0y) = (y[3 * n + 1], y[3 * n + 2]);
                power -= chain.mass() * chain.rod_length() * (f0x * v0[0] + f0y * v0[1]);
            }
            assert!(
                (read[2 * n] - power).abs() <= 1e-12 * power.abs().max(1.0),
                "{pivot:?}"
            );
        }
    }

    #[test]
    fn the_observer_sees_the_same_run_with_the_derivatives_read_off_as_evaluated() {
        let chain = Chain::new(ChainParams {
            links: 12,
            damping: 0.05,
            tip_mass: 0.2,
            ..ChainParams::default()
        })
        .unwrap();
        let dae = ChainDae::new(&chain);
        let mut y = vec![0.0; dae.dim()];
        for (i, p) in y[..12].iter_mut().enumerate() {
            *p = -0.3 + 0.05 * i as f64;
        }
        dae.make_consistent(&mut y, &mut crate::dynamics::Workspace::new(12));
        let (read, read_rec) = run(dae.clone(), y.clone(), 1.0);
        let (evaluated, evaluated_rec) = run(Evaluated(dae), y, 1.0);
        assert!(
            read.status.is_ok() && read.stats.steps > 10,
            "{:?}",
            read.stats
        );
        // The same steps, states and derivatives, bit for bit ...
        assert_eq!(read.y_end, evaluated.y_end);
        assert_eq!(read_rec.0, evaluated_rec.0);
        // ... with one right-hand side fewer per accepted step.
        let (a, b) = (read.stats, evaluated.stats);
        assert_eq!(b.rhs_evals - a.rhs_evals, a.steps, "{a:?} {b:?}");
        assert_eq!(Stats { rhs_evals: 0, ..a }, Stats { rhs_evals: 0, ..b });
    }

    #[test]
    fn the_chains_get_the_block_lu_and_the_general_one_can_be_forced() {
        for n in [1, 2, 9] {
            let rigid = Chain::new(ChainParams {
                links: n,
                bending_stiffness: 0.1,
                tip_mass: 0.3,
                ..ChainParams::default()
            })
            .unwrap();
            assert!(picks_block_lu(ChainDae::new(&rigid)), "rigid n = {n}");
            let elastic = Chain::new(ChainParams {
                links: n,
                axial_stiffness: Some(1e3),
                ..ChainParams::default()
            })
            .unwrap();
            assert!(picks_block_lu(ElasticDae::new(&elastic)), "elastic n = {n}");
            assert!(!with_general_sparse_lu(|| picks_block_lu(ChainDae::new(
                &rigid
            ))));
        }
        // BEAM's DAE groups its unknowns four to a segment.
        for n in [2, 40] {
            assert!(picks_block_lu(crate::beam::BeamDae::new(n)), "beam n = {n}");
        }
        // After the closure, the default again.
        let chain = Chain::report(4, 0.0).unwrap();
        assert!(picks_block_lu(ChainDae::new(&chain)));
    }
}

/// From the block LU's tests (`block_lu.rs`): its solve against a dense
/// solve on the chains' and BEAM's Newton matrices, and the rows it
/// condenses in each.
mod block_lu {
    use crate::dae::ChainDae;
    use crate::elastic::ElasticDae;
    use crate::{Chain, ChainParams};
    use fc_methods::testing::{layout_of, random_state, worst_error, Lcg};
    use fc_methods::SemiExplicitDae;

    /// An elastic chain of `n` rods with damped joints and links.
    fn elastic_chain(n: usize) -> Chain {
        Chain::new(ChainParams {
            links: n,
            damping: 0.01,
            axial_stiffness: Some(1e4),
            axial_damping: 0.1,
            ..ChainParams::default()
        })
        .unwrap()
    }

    #[test]
    fn the_block_solve_matches_a_dense_solve_on_random_chains() {
        let mut rng = Lcg(20);
        let mut worst: f64 = 0.0;
        for n in [1usize, 2, 3, 7, 20, 41] {
            for (r, ei, tip) in [
                (5e-4, 0.0, 0.0),
                (1.0, 0.0, 0.0),
                (0.1, 0.3, 0.0),
                (0.2, 0.0, 0.5),
            ] {
                let chain = Chain::new(ChainParams {
                    links: n,
                    damping: r,
                    bending_stiffness: ei,
                    tip_mass: tip,
                    ..ChainParams::default()
                })
                .unwrap();
                let dae = ChainDae::new(&chain);
                let y = random_state(dae.dim(), n, 10.0, &mut rng);
                for c in [1e-4, 1e-2, 0.3] {
                    worst = worst.max(worst_error(&dae, &y, c, &mut rng));
                }
            }
            let dae = ElasticDae::new(&elastic_chain(n));
            let y = random_state(dae.dim(), n, 1.0, &mut rng);
            for c in [1e-4, 1e-2] {
                worst = worst.max(worst_error(&dae, &y, c, &mut rng));
            }
        }
        println!("worst relative difference {worst:e}");
        assert!(worst < 1e-9, "{worst:e}");
    }

    #[test]
    fn the_block_solve_matches_a_dense_solve_on_beam() {
        let mut rng = Lcg(40);
        let mut worst: f64 = 0.0;
        for n in [2usize, 5, 40] {
            let dae = crate::beam::BeamDae::new(n);
            let y = random_state(dae.dim(), n, 3.0, &mut rng);
            for c in [1e-4, 1e-2, 0.3] {
                worst = worst.max(worst_error(&dae, &y, c, &mut rng));
            }
        }
        println!("worst relative difference {worst:e}");
        assert!(worst < 1e-9, "{worst:e}");
    }

    /// The rows `phi_i' = w_i` and `w_i' = alpha_i` (the elastic chain's
    /// `theta_i' = w_i`, `x_i' = vx_i`, `y_i' = vy_i`; BEAM's `theta_i' =
    /// omega_i`) hold entries of their own rod only, and are condensed out,
    /// first in their block; no other row is. (A single rod is one block,
    /// all of whose rows are local: nothing is condensed. The tridiagonal
    /// test matrix's rows, none local, are checked beside the block LU.)
    #[test]
    fn the_rows_local_to_a_rod_are_condensed() {
        let one = Chain::report(1, 0.1).unwrap();
        assert_eq!(layout_of(&ChainDae::new(&one)).local, 0);
        for n in [2usize, 3, 9] {
            let rigid = Chain::new(ChainParams {
                links: n,
                damping: 0.3,
                bending_stiffness: 0.1,
                tip_mass: 0.3,
                ..ChainParams::default()
            })
            .unwrap();
            let dae = ChainDae::new(&rigid);
            let l = layout_of(&dae);
            assert_eq!((l.size, l.local), (5, 2), "rigid n = {n}");
            for k in 0..n {
                assert_eq!(&l.order[5 * k..5 * k + 2], &[k, n + k], "rigid n = {n}");
            }
            let l = layout_of(&ElasticDae::new(&elastic_chain(n)));
            assert_eq!((l.size, l.local), (6, 3), "elastic n = {n}");
        }
        let l = layout_of(&crate::beam::BeamDae::new(7));
        assert_eq!((l.size, l.local), (4, 1), "beam");
    }
}
