//! One energy per model: every sample's energy (`Trajectory::energy`, what
//! the CSV writes) is the one the run's balance used (`Summary::energy_end`,
//! from `StateView::observe`), for each model and each kind of pivot. A model
//! whose per-state energy and per-step energy drift apart (a frame term, a
//! tip mass or a bending term in one and not the other) fails. The runs
//! walk every model a scene can choose ([`ModelKind::MODELS`]): a model
//! added there without a run here fails.

use chain_ode::report::ReportModel;
use chain_ode::{
    solve, Chain, ChainParams, Method, Model, ModelKind, Pivot, SolveOptions, Start, Status,
};

fn chain(pivot: Pivot, elastic: bool) -> Chain {
    Chain::new(ChainParams {
        links: 6,
        length: 1.0,
        mass: 1.0,
        gravity: 1.0,
        damping: 0.01,
        tip_mass: if elastic { 0.0 } else { 0.5 },
        bending_stiffness: 0.01,
        axial_stiffness: elastic.then_some(1e3),
        axial_damping: if elastic { 0.1 } else { 0.0 },
        pivot,
        ..ChainParams::default()
    })
    .unwrap()
}

#[test]
fn every_samples_energy_is_the_balances_energy() {
    let pivots = [
        Pivot::default(),
        Pivot {
            amplitude: [0.05, 0.1],
            frequency: 3.0,
            ..Pivot::default()
        },
        Pivot {
            release: Some(0.4),
            ..Pivot::default()
        },
    ];
    let options = SolveOptions {
        t_end: 0.8,
        output_dt: Some(0.2),
        ..SolveOptions::default()
    }
    .at_accuracy(Method::Dopri5, 1e-9);
    let mut runs = Vec::new();
    for pivot in pivots {
        for elastic in [false, true] {
            let c = chain(pivot, elastic);
            let start = Start::Catenary {
                p0: [0.0, 0.0],
                p1: [0.6, 0.0],
            }
            .state(&c)
            .unwrap();
            runs.push((
                format!("{pivot:?} elastic {elastic}"),
                ModelKind::of(&c),
                start,
            ));
        }
    }
    let plain = Chain::report(6, 0.01).unwrap();
    let start = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [0.6, 0.0],
    }
    .state(&plain)
    .unwrap();
    runs.push((
        "report".into(),
        ModelKind::choose(&plain, Some(ReportModel::AS_CODED)),
        start,
    ));
    // The rigid chain on a constraint floor (no tip mass: refused there).
    let on_floor = Chain::new(ChainParams {
        links: 6,
        damping: 0.01,
        floor: Some(chain_ode::Floor {
            height: Some(-3.2),
            angle: 0.0,
            stiffness: 1e4,
            damping: 0.0,
            friction: 0.3,
            slip_speed: 1e-3,
            law: chain_ode::FloorLaw::Constraint,
            restitution: 0.0,
        }),
        ..ChainParams::default()
    })
    .unwrap();
    let start = Start::Catenary {
        p0: [0.0, 0.0],
        p1: [0.6, 0.0],
    }
    .state(&on_floor)
    .unwrap();
    runs.push(("contact".into(), ModelKind::of(&on_floor), start));
    for model in ModelKind::MODELS {
        assert!(
            runs.iter().any(|r| r.1.name() == model),
            "no run of the {model} model"
        );
    }
    for (name, model, start) in runs {
        let (method, options) = if name == "contact" {
            let o = options.clone().at_accuracy(Method::MoreauJean, 1e-3);
            (Method::MoreauJean, o)
        } else {
            (Method::Dopri5, options.clone())
        };
        let traj = solve(model, &start, method, &options).unwrap();
        assert_eq!(traj.status, Status::Ok, "{name}");
        let last = traj.len() - 1;
        assert_eq!(traj.times[last], traj.t_reached, "{name}");
        let (e, end) = (traj.energy(last), traj.summary.energy_end);
        assert!(
            (e - end).abs() <= 1e-12 * end.abs().max(1.0),
            "{name}: sample {e}, balance {end}"
        );
        let e0 = traj.energy(0);
        assert!(
            (e0 - traj.summary.energy_start).abs() <= 1e-12 * e0.abs().max(1.0),
            "{name}"
        );
    }
}
