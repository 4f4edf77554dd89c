//! Issue 47 A2: a run whose estimated memory exceeds what the machine can
//! give is refused before anything is allocated (one line naming
//! `chain.links`, the method, the estimate and the memory available, exit
//! 2), in every command that builds runs; and a size the estimate admits
//! runs within it.

use std::process::{Command, Output};

use chain_ode::memory::{estimate, MEMORY_ENV};
use chain_ode::Method;

use crate::common::*;

/// `args` with [`MEMORY_ENV`] set to `bytes`, under an address-space limit
/// of `limit` bytes (`prlimit --as`) when given.
fn run_with_memory(bytes: Option<&str>, limit: Option<u64>, args: &[&str]) -> Output {
    let mut c = match limit {
        Some(l) => {
            let mut c = Command::new("prlimit");
            c.arg(format!("--as={l}")).arg(BIN);
            c
        }
        None => Command::new(BIN),
    };
    if let Some(b) = bytes {
        c.env(MEMORY_ENV, b);
    }
    c.args(args).output().unwrap()
}

/// A refusal: exit 2, one stderr line naming `chain.links`, `method`, the
/// estimate and the memory available, nothing on stdout.
fn assert_refused(o: &Output, method: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: chain.links: must be at most "),
        "{err}"
    );
    for word in [method, "needs about ", "bytes a rod", " is available ("] {
        assert!(err.contains(word), "{word:?} not in {err}");
    }
    assert!(o.stdout.is_empty());
}

/// n = 1e6 with bdf and gen-alpha (about 7 GB) against 2 GB is refused
/// at once: under an address space of 400 MB, where the run's first large
/// allocation would abort, the refusal still comes back as exit 2.
#[test]
fn a_run_that_cannot_fit_is_refused_before_it_allocates() {
    let span = scene("span-d3");
    for method in ["bdf", "gen-alpha", "auto", "dopri5"] {
        let o = run_with_memory(
            Some("2e9"),
            Some(400_000_000),
            &[
                "simulate",
                &span,
                "--method",
                method,
                "--set",
                "chain.links=1000000",
                "--t-end",
                "1e-3",
                "--json",
            ],
        );
        if method == "dopri5" {
            // DOPRI5's state of 2n + 1 numbers and its stages fit in 2 GB.
            let est = estimate("rigid", Method::Dopri5, 1_000_000, 0);
            assert!(est < 2_000_000_000, "{est}");
            continue;
        }
        assert_refused(&o, method);
        assert!(
            stderr(&o).contains("2.00 GB is available (FC_MEMORY_AVAILABLE)"),
            "{}",
            stderr(&o)
        );
    }
}

/// The machine's own limit is read: under `prlimit --as` of 600 MB (no
/// [`MEMORY_ENV`]) bdf at the largest `n` whose estimate fits in it, less
/// the 120 MB the process's address space holds before it allocates,
/// runs to its end `ok`, and n = 1e6 is refused naming the limit.
#[test]
fn a_size_that_fits_runs_under_an_address_space_limit() {
    let limit: u64 = 600_000_000;
    let room = limit - 120_000_000;
    let mut n = 1000;
    while estimate("rigid", Method::Bdf, n + 1000, 0) <= room {
        n += 1000;
    }
    assert!(n >= 10_000, "{n}");
    let span = scene("span-d3");
    let links = format!("chain.links={n}");
    let args = [
        "simulate",
        &span,
        "--method",
        "bdf",
        "--set",
        &links,
        "--t-end",
        "1e-4",
        "--set",
        "run.output_dt=1e-4",
        "--json",
    ];
    let o = run_with_memory(None, Some(limit), &args);
    assert!(o.status.success(), "n = {n}: {}", stderr(&o));
    assert_eq!(json(&o)["status"], "ok");
    let big = [
        "simulate",
        &span,
        "--method",
        "bdf",
        "--set",
        "chain.links=1000000",
        "--t-end",
        "1e-4",
    ];
    let o = run_with_memory(None, Some(limit), &big);
    assert_refused(&o, "bdf");
    assert!(stderr(&o).contains("RLIMIT_AS"), "{}", stderr(&o));
}

/// The members or runs that run at once are checked together: 4 jobs of
/// a 50-rod chain need 4 times one run's estimate, refused where only 2
/// fit, naming the 4 runs; with one job the same command runs.
#[test]
fn runs_at_once_are_checked_together() {
    let span = scene("span-d3");
    let one = estimate("rigid", Method::Bdf, 50, 0);
    let avail = (2 * one + one / 2).to_string();
    let ensemble = |jobs: &str| {
        run_with_memory(
            Some(&avail),
            None,
            &[
                "ensemble",
                &span,
                "--set",
                "run.t_end=0.01",
                "--set",
                "run.method=bdf",
                "--members",
                "4",
                "--jobs",
                jobs,
                "--json",
                "--quiet",
            ],
        )
    };
    let o = ensemble("4");
    assert_refused(&o, "bdf");
    assert!(stderr(&o).contains("x 4 runs at once"), "{}", stderr(&o));
    let o = ensemble("1");
    assert!(o.status.success(), "{}", stderr(&o));
    let sweep = |jobs: &str| {
        run_with_memory(
            Some(&avail),
            None,
            &[
                "sweep",
                &span,
                "--vary",
                "chain.damping=0,0.1,0.2",
                "--set",
                "run.t_end=0.01",
                "--set",
                "run.method=bdf",
                "--jobs",
                jobs,
            ],
        )
    };
    let o = sweep("3");
    assert_refused(&o, "bdf");
    assert!(stderr(&o).contains("x 3 runs at once"), "{}", stderr(&o));
    let o = sweep("1");
    assert!(o.status.success(), "{}", stderr(&o));
    // A study command refuses a run that cannot fit as simulate does.
    let o = run_with_memory(
        Some("1e8"),
        None,
        &[
            "converge", &span, "--links", "4,200000", "--method", "bdf", "--tol", "1e-3",
        ],
    );
    assert_refused(&o, "bdf");
}
