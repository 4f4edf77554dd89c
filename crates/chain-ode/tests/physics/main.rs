//! Physics tests of the `chain-ode` crate, in one test binary: the O(n)
//! dynamics against the dense reference and the conservation laws, the
//! banded DAE, every method against the others and against closed forms,
//! and the validation claims. Shared scenes and option builders are here.

#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "test code, helpers included: a failed unwrap is a failed test"
)]

mod bdf;
mod bounds;
mod contact;
mod dae;
mod dopri5;
mod drag;
mod dynamics;
mod elastic;
mod elastic_scenes;
mod failures;
mod floor;
mod gen_alpha;
mod methods;
mod modes;
mod observed_rhs;
mod one_energy;
mod peak_forces;
mod pivot;
mod profile;
mod profile_compression;
mod profile_terms;
mod report;
mod rk4;
mod snap_tension;
mod tip_mass;
mod validation;

use chain_ode::{
    solve, Chain, ChainParams, Method, Profile, SolveOptions, Start, State, Status, Trajectory,
    Vec2,
};
use proptest::prelude::*;

/// Every method of smooth problems: all but `moreau-jean`, which runs a
/// chain on a constraint floor only (its checks: `contact.rs`).
pub fn smooth_methods() -> impl Iterator<Item = Method> {
    Method::ALL.into_iter().filter(|m| !m.is_nonsmooth())
}

/// The report's chain (`L = 6`, `m = 0.2` per rod, `g = 1`) of `n` rods
/// with joint friction `damping`, started from `start`.
pub fn scene(n: usize, damping: f64, start: Start) -> (Chain, State) {
    let chain = Chain::report(n, damping).unwrap();
    let s = start.state(&chain).unwrap();
    (chain, s)
}

/// The report's chain hanging from `(0, 0)` to `(d, 0)` at rest.
pub fn span(n: usize, damping: f64, d: f64) -> (Chain, State) {
    scene(
        n,
        damping,
        Start::Catenary {
            p0: [0.0, 0.0],
            p1: [d, 0.0],
        },
    )
}

/// The report's span d = 3 (Fig. 7b).
pub fn span3(n: usize, damping: f64) -> (Chain, State) {
    span(n, damping, 3.0)
}

/// The report's folded start: half the rods hanging from `(0, 0)`, one
/// horizontal, the rest up.
pub fn folded(n: usize, damping: f64) -> (Chain, State) {
    scene(
        n,
        damping,
        Start::Folded {
            p0: [0.0, 0.0],
            down: None,
        },
    )
}

/// Options of a fixed-step run.
pub fn fixed(t_end: f64, dt: f64) -> SolveOptions {
    SolveOptions {
        t_end,
        dt,
        ..Default::default()
    }
}

/// Options of an adaptive run.
pub fn tolerances(t_end: f64, rtol: f64, atol: f64) -> SolveOptions {
    SolveOptions {
        t_end,
        rtol,
        atol,
        ..Default::default()
    }
}

/// Runs `method` and checks that it completed.
pub fn run_ok(chain: &Chain, s: &State, method: Method, opts: &SolveOptions) -> Trajectory {
    let tr = solve(chain, s, method, opts).unwrap();
    assert_eq!(tr.status, Status::Ok, "{method}");
    tr
}

/// `|a - b|`.
pub fn dist(a: Vec2, b: Vec2) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The largest `|x_i|`.
pub fn max_abs(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// True if every entry is finite.
pub fn all_finite(y: &[f64]) -> bool {
    y.iter().all(|v| v.is_finite())
}

/// A random chain of 1 to `max_links` rods in a random state: any length,
/// mass, gravity, friction and bending stiffness (none in a third of the
/// cases), a tip mass (none in half of the cases), a rod profile (none in
/// two fifths), angles anywhere, rates up to 3 rad/time. Every term goes
/// with every other.
pub fn chain_and_state(max_links: usize) -> impl Strategy<Value = (Chain, Vec<f64>, Vec<f64>)> {
    (
        1usize..=max_links,
        0.1f64..20.0,
        0.01f64..5.0,
        0.0f64..10.0,
        0.0f64..0.5,
        prop_oneof![Just(0.0), 0.0f64..2.0, 0.0f64..2.0],
        // A rod profile: none, a taper, or random lists (0, 1, 2, 3).
        prop_oneof![Just(0u8), Just(0u8), 1u8..=3],
        0.01f64..100.0,
        // The tip mass in rod masses.
        prop_oneof![Just(0.0), 0.0f64..3.0],
    )
        .prop_flat_map(
            |(n, length, mass, gravity, damping, bending_stiffness, profile, taper, tip)| {
                (
                    Just((
                        n,
                        length,
                        mass,
                        gravity,
                        damping,
                        bending_stiffness,
                        profile,
                        taper,
                        tip,
                    )),
                    prop::collection::vec(0.05f64..5.0, n),
                    prop::collection::vec(0.2f64..5.0, n),
                    prop::collection::vec(-7.0f64..7.0, n),
                    prop::collection::vec(-3.0f64..3.0, n),
                )
            },
        )
        .prop_map(
            |(
                (n, length, mass, gravity, damping, bending_stiffness, profile, taper, tip),
                masses,
                lengths,
                phi,
                w,
            )| {
                let profile = match profile {
                    1 => Profile {
                        taper,
                        ..Profile::default()
                    },
                    2 => Profile {
                        masses: Some(masses),
                        lengths: Some(lengths),
                        ..Profile::default()
                    },
                    3 => Profile {
                        taper,
                        lengths: Some(lengths),
                        ..Profile::default()
                    },
                    _ => Profile::default(),
                };
                let chain = Chain::new(ChainParams {
                    length,
                    links: n,
                    mass,
                    gravity,
                    damping,
                    bending_stiffness,
                    tip_mass: tip * mass,
                    profile,
                    ..ChainParams::default()
                })
                .unwrap();
                (chain, phi, w)
            },
        )
}
