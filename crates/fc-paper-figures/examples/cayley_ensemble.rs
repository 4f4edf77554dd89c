//! Cayley's scale as one ensemble, for measurements beyond the figure's:
//! `cargo run --release -p fc-paper-figures --example cayley_ensemble --
//! SCENE N K C TILT SPREAD MEMBERS METHOD RTOL [MU_F [R]]`, where `SCENE` is
//! `scenes/cayley-scale.toml` (its total mass and length are kept), `MU_F`
//! the floor's friction and `R` the joints' (both 0 by default). Prints
//! the ensemble's mid-fall readings (mean, standard deviation and error
//! over the members; `fc_paper_figures::cayley`) and its cost: steps,
//! right-hand sides and the members' wall time summed, and the wall time
//! of the whole ensemble on this machine's threads.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "a developer's tool: a bad argument or a failed run stops it with the message"
)]

use chain_ode::Method;
use fc_paper_figures::cayley::{self, Case, Stat};
use fc_scene::scene::Scene;

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    assert!(
        (9..=11).contains(&a.len()),
        "usage: SCENE N K C TILT SPREAD MEMBERS METHOD RTOL [MU_F [R]]"
    );
    let base = Scene::load(&a[0]).unwrap();
    let case = Case {
        links: a[1].parse().unwrap(),
        stiffness: a[2].parse().unwrap(),
        damping: a[3].parse().unwrap(),
        friction: a.get(9).map_or(0.0, |s| s.parse().unwrap()),
        joint_friction: a.get(10).map_or(0.0, |s| s.parse().unwrap()),
        tilt: a[4].parse().unwrap(),
        spread: a[5].parse().unwrap(),
        members: a[6].parse().unwrap(),
        method: a[7].parse::<Method>().unwrap(),
        rtol: a[8].parse().unwrap(),
    };
    let clock = std::time::Instant::now();
    let e = cayley::run(&base, &case).unwrap();
    let wall = clock.elapsed().as_secs_f64();
    let p = e.midfall();
    let show = |s: &Stat| format!("{:.4} sd {:.4} sem {:.4}", s.mean, s.sd, s.sem);
    println!(
        "n={} k={:e} c={} tilt={} spread={:e} members={} {} rtol={:e}: steps {} rhs {} \
         member-wall {:.2} s ensemble-wall {:.2} s",
        case.links,
        case.stiffness,
        case.damping,
        case.tilt,
        case.spread,
        case.members,
        case.method,
        case.rtol,
        e.steps,
        e.rhs_evals,
        e.wall_seconds,
        wall
    );
    if !e.failed.is_empty() {
        println!(
            "  {} of {} members failed (left out): {:?}",
            e.failed.len(),
            case.members,
            e.failed
        );
    }
    println!("  mid-fall reading t+-0.05: {}", show(&p.reading));
    if let Some(w) = &p.reading_wide {
        println!("  mid-fall reading t+-0.2:  {}", show(w));
    }
    println!("  momentum / ideal:         {}", show(&p.momentum));
    println!("  dissipated / ideal:       {}", show(&p.dissipated));
    println!("  top / free fall:          {}", show(&p.top));
}
