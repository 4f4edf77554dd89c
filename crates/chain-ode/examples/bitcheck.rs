#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
//! Fingerprints of the chain's arithmetic: runs and raw evaluations, one line each.
use chain_ode::dae::ChainDae;
use chain_ode::{
    dense, elastic, solve, Chain, ChainParams, ChainSystem, ElasticSystem, Floor, Method, Pivot,
    Problem, Profile, SolveOptions, Start, State,
};
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

struct H(DefaultHasher);
impl H {
    fn new() -> Self {
        H(DefaultHasher::new())
    }
    fn f(&mut self, x: f64) {
        x.to_bits().hash(&mut self.0)
    }
    fn v(&mut self, xs: &[f64]) {
        for &x in xs {
            self.f(x)
        }
    }
    fn u(&mut self, x: u64) {
        x.hash(&mut self.0)
    }
    fn done(&self) -> u64 {
        self.0.finish()
    }
}

fn chains() -> Vec<(&'static str, ChainParams, Start)> {
    let span = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [3.0, 0.0],
    };
    let base = ChainParams {
        links: 12,
        damping: 5e-4,
        ..ChainParams::default()
    };
    let taper = Profile {
        taper: 4.0,
        ..Profile::default()
    };
    let lists = Profile {
        masses: Some((0..12).map(|i| 1.0 + 0.1 * i as f64).collect()),
        lengths: Some((0..12).map(|i| 1.5 - 0.07 * i as f64).collect()),
        ..Profile::default()
    };
    let driven = Pivot {
        jerk: [-1.5, 0.5],
        jerk_time: 0.4,
        ..Pivot::default()
    };
    let harmonic = Pivot {
        amplitude: [0.1, 0.05],
        frequency: 3.0,
        ..Pivot::default()
    };
    let released = Pivot {
        release: Some(0.0),
        ..Pivot::default()
    };
    let late = Pivot {
        release: Some(0.7),
        ..Pivot::default()
    };
    let floor = Floor {
        height: Some(-3.0),
        angle: 0.1,
        stiffness: 1e4,
        damping: 10.0,
        friction: 0.3,
        slip_speed: 0.01,
        law: chain_ode::FloorLaw::Penalty,
        restitution: 0.0,
    };
    let mut out = vec![];
    for (ename, ea) in [("rigid", None), ("elastic", Some(1e5))] {
        let b = ChainParams {
            axial_stiffness: ea,
            axial_damping: if ea.is_some() { 3.0 } else { 0.0 },
            ..base.clone()
        };
        out.push((ename, b.clone(), span.clone()));
        out.push((
            ename,
            ChainParams {
                damping: 0.2,
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                bending_stiffness: 0.02,
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                tip_mass: 0.3,
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                profile: taper.clone(),
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                profile: lists.clone(),
                bending_stiffness: 0.02,
                tip_mass: 0.3,
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                pivot: driven,
                bending_stiffness: 0.02,
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                pivot: harmonic,
                tip_mass: 0.3,
                profile: taper.clone(),
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                pivot: released,
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                pivot: late,
                profile: lists.clone(),
                tip_mass: 0.2,
                bending_stiffness: 0.01,
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                floor: Some(floor),
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                floor: Some(floor),
                pivot: late,
                bending_stiffness: 0.01,
                tip_mass: 0.1,
                ..b.clone()
            },
            span.clone(),
        ));
        out.push((
            ename,
            ChainParams {
                gravity: 0.0,
                ..b.clone()
            },
            Start::Folded {
                p0: [0.0, 0.0],
                down: None,
            },
        ));
    }
    out
}

fn state_with_rates(chain: &Chain, start: &Start) -> State {
    let mut s = start.state(chain).unwrap();
    let n = chain.links();
    s.rates = (0..n).map(|i| 0.3 * (i as f64 * 0.37).sin()).collect();
    s
}

fn main() {
    let methods = [
        Method::Rk4,
        Method::Dopri5,
        Method::Dop853,
        Method::Bdf,
        Method::BdfDense,
        Method::GenAlpha,
        Method::Auto,
    ];
    for (k, (name, params, start)) in chains().into_iter().enumerate() {
        let chain = match Chain::new(params) {
            Ok(c) => c,
            Err(e) => {
                println!("{k} {name}: {e}");
                continue;
            }
        };
        let n = chain.links();
        let st = state_with_rates(&chain, &start);
        // Raw evaluations.
        let mut h = H::new();
        if chain.is_elastic() {
            let y = elastic::start_state(&chain, &st);
            let mut sys = ElasticSystem::new(&chain);
            let mut dy = vec![0.0; y.len()];
            sys.rhs(0.3, &y, &mut dy);
            h.v(&dy);
            let v: Vec<f64> = (0..y.len()).map(|i| ((i * 7 % 5) as f64) - 2.0).collect();
            sys.jvp(0.3, &y, &v, &mut dy);
            h.v(&dy);
            let b = sys.banded_dae(0.3, &y).unwrap();
            let mut out = vec![0.0; b.dae.dim()];
            b.dae.rhs(0.3, &b.y0, &mut out);
            h.v(&out);
            b.dae.jacobian_entries(0.3, &b.y0, &mut |r, c, x| {
                h.u(r as u64);
                h.u(c as u64);
                h.f(x)
            });
            h.f(elastic::energy(&chain, &y));
            h.f(elastic::energy_at(&chain, 1.0, &y));
            for f in elastic::joint_forces(&chain, &y) {
                h.v(&f)
            }
        } else {
            let y = ChainSystem::pack(&st.angles, &st.rates, 0.0);
            let mut sys = ChainSystem::new(&chain);
            let mut dy = vec![0.0; y.len()];
            sys.rhs(0.3, &y, &mut dy);
            h.v(&dy);
            let v: Vec<f64> = (0..y.len()).map(|i| ((i * 7 % 5) as f64) - 2.0).collect();
            sys.jvp(0.3, &y, &v, &mut dy);
            h.v(&dy);
            let b = sys.banded_dae(0.3, &y).unwrap();
            let mut out = vec![0.0; b.dae.dim()];
            b.dae.rhs(0.3, &b.y0, &mut out);
            h.v(&out);
            b.dae.jacobian_entries(0.3, &b.y0, &mut |r, c, x| {
                h.u(r as u64);
                h.u(c as u64);
                h.f(x)
            });
            println!("{k} {name} frame {:016x}", h.done());
            let dae = ChainDae::new(&chain);
            let mut full = b.y0.clone();
            full[..2 * n + 1].copy_from_slice(&y);
            let mut map = std::collections::BTreeMap::new();
            dae.jacobian_entries(&full, |r, c, x| {
                *map.entry((r, c)).or_insert(0.0) += x;
            });
            for ((r, c), x) in map {
                h.u(r as u64);
                h.u(c as u64);
                h.f(x)
            }
            println!("{k} {name} chaindae {:016x}", h.done());
            h.f(chain_ode::kinematics::energy(&chain, &st.angles, &st.rates));
            h.f(chain_ode::kinematics::bending_energy(&chain, &st.angles));
            println!("{k} {name} energy {:016x}", h.done());
            h.v(&dense::accelerations(&chain, &st.angles, &st.rates));
            h.f(chain_ode::kinematics::energy(&chain, &st.angles, &st.rates));
        }
        println!("{k} {name} raw {:016x}", h.done());
        for m in methods {
            let opts = SolveOptions {
                t_end: 1.5,
                dt: 0.005,
                rtol: 1e-6,
                atol: 1e-8,
                output_dt: Some(0.1),
                ..SolveOptions::default()
            };
            let t = match solve(&chain, &st, m, &opts) {
                Ok(t) => t,
                Err(e) => {
                    println!("{k} {name} {m}: {e}");
                    continue;
                }
            };
            let mut h = H::new();
            h.v(&t.final_state);
            let s = &t.summary;
            h.v(&[
                s.energy_start,
                s.energy_end,
                s.dissipated,
                s.energy_balance_error,
                s.max_energy_rise,
                s.tip_speed_max,
                s.t_tip_speed_max,
            ]);
            h.v(&s.tip_end);
            h.v(&s.tip_velocity_end);
            if let Some((a, b)) = s.pivot_force_max {
                h.v(&[a, b]);
            }
            h.u(t.stats.steps);
            h.u(t.stats.rhs_evals);
            for i in 0..t.len() {
                h.v(t.state(i));
                h.f(t.energy(i));
                h.v(&t.tip(i));
                h.v(&t.tip_velocity(i));
                for f in t.joint_forces(i) {
                    h.v(&f)
                }
                for j in t.joints(i) {
                    h.v(&j)
                }
                h.v(&t.support_force(i));
                h.v(&t.momentum(i));
                if let Some(ff) = t.floor_forces(i) {
                    for f in ff {
                        h.v(&f)
                    }
                }
            }
            println!(
                "{k} {name} {m} {} {} {:016x}",
                t.status.as_str(),
                t.stats.steps,
                h.done()
            );
        }
    }
}
