//! `rhs-cost`: the cost of one right-hand side against n, the O(n)
//! recursion (a whole `ChainSystem::rhs`) against the dense reference
//! (assemble `A` and `b`, faer's Cholesky), timed with
//! `std::time::Instant` over many calls, median of repeats. All of it is
//! wall times: computed only by `--timings`, into `rhs-cost-timing.csv` and
//! `rhs-cost-fit-timing.csv`.

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

use chain_ode::{dense, Chain, ChainSystem};

use fc_csv::format::{exp, fixed};
use fc_study::{log_slope, median};

/// Rods for the O(n) recursion.
pub const FAST_N: [usize; 10] = [25, 50, 100, 200, 400, 1000, 2000, 4000, 7000, 10000];
/// Rods for the dense solve.
pub const DENSE_N: [usize; 7] = [25, 50, 100, 200, 400, 700, 1000];
/// Slopes are fitted from this many rods on (below, fixed costs show).
pub const FIT_FROM: usize = 200;
/// Repeats per n (each a batch of calls); the median batch counts.
const REPEATS: usize = 7;
/// A batch lasts about this long (s).
const BATCH: f64 = 0.02;

/// A state of `n` rods away from any symmetry: a "U" of angles and rates
/// that vary along the chain.
fn state(n: usize) -> Vec<f64> {
    let mut y = Vec::with_capacity(2 * n + 1);
    let s = |i: usize| i as f64 / (n - 1).max(1) as f64;
    y.extend((0..n).map(|i| -1.3 + 2.6 * s(i)));
    y.extend((0..n).map(|i| 0.4 * (3.0 * s(i)).cos()));
    y.push(0.0);
    y
}

/// Median seconds per call of `f`, in batches of about [`BATCH`] s.
fn per_call(mut f: impl FnMut()) -> (f64, usize) {
    let t0 = Instant::now();
    f();
    let once = t0.elapsed().as_secs_f64().max(1e-8);
    let calls = ((BATCH / once).ceil() as usize).max(1);
    let times: Vec<f64> = (0..REPEATS)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..calls {
                f();
            }
            t.elapsed().as_secs_f64() / calls as f64
        })
        .collect();
    (median(&times), calls)
}

/// `(solver, n, calls per batch, seconds per call)`.
type Row = (String, usize, usize, f64);

/// The slope of `log t` against `log n` of `kind` from [`FIT_FROM`] rods on.
fn fit(rows: &[Row], kind: &str) -> f64 {
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.0 == kind && r.1 >= FIT_FROM)
        .map(|r| (r.1 as f64, r.3))
        .collect();
    log_slope(&pts)
}

/// The cost tables, wall times all: seconds per call of each solver at each
/// n (`solver,n,calls_per_batch,batches,seconds_per_call`), and the fitted
/// slopes (`solver,n_from,n_to,slope`).
pub fn tables() -> Result<(String, String), String> {
    let mut rows: Vec<Row> = vec![];
    for &n in &FAST_N {
        let chain = Chain::report(n, 5e-4).map_err(|e| e.to_string())?;
        let mut sys = ChainSystem::new(&chain);
        let y = state(n);
        let mut dy = vec![0.0; y.len()];
        let (s, calls) = per_call(|| {
            sys.rhs(0.0, black_box(&y), &mut dy);
            black_box(&dy);
        });
        rows.push(("recursion".into(), n, calls, s));
    }
    for &n in &DENSE_N {
        let chain = Chain::report(n, 5e-4).map_err(|e| e.to_string())?;
        let y = state(n);
        let (phi, w) = (&y[..n], &y[n..2 * n]);
        // The two agree (the tests check it to 1e-12); confirm the state is fair.
        let mut sys = ChainSystem::new(&chain);
        let mut dy = vec![0.0; y.len()];
        sys.rhs(0.0, &y, &mut dy);
        let acc = dense::accelerations(&chain, phi, w);
        let scale = acc.iter().fold(0.0f64, |m, a| m.max(a.abs()));
        let diff = acc
            .iter()
            .zip(&dy[n..2 * n])
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        if diff > 1e-8 * scale.max(1.0) {
            return Err(format!(
                "n = {n}: the O(n) and dense accelerations differ by {diff:e}"
            ));
        }
        let (s, calls) = per_call(|| {
            black_box(dense::accelerations(&chain, black_box(phi), black_box(w)));
        });
        rows.push(("dense".into(), n, calls, s));
        let (s, calls) = per_call(|| {
            black_box(dense::mass_matrix(black_box(phi)));
            black_box(dense::forcing(&chain, black_box(phi), black_box(w)));
        });
        rows.push(("dense-assembly".into(), n, calls, s));
    }

    let slope_fast = fit(&rows, "recursion");
    let slope_dense = fit(&rows, "dense");
    let slope_assembly = fit(&rows, "dense-assembly");
    // The factorisation and solve alone: the dense time less the assembly.
    let factor: Vec<(f64, f64)> = DENSE_N
        .iter()
        .filter(|&&n| n >= FIT_FROM)
        .filter_map(|&n| {
            let t = |k: &str| rows.iter().find(|r| r.0 == k && r.1 == n).map(|r| r.3);
            Some((n as f64, t("dense")? - t("dense-assembly")?))
        })
        .filter(|p| p.1 > 0.0)
        .collect();
    let slope_factor = if factor.len() >= 2 {
        log_slope(&factor)
    } else {
        f64::NAN
    };

    let mut csv = String::from("solver,n,calls_per_batch,batches,seconds_per_call\n");
    for r in &rows {
        let _ = writeln!(csv, "{},{},{},{REPEATS},{}", r.0, r.1, r.2, exp(r.3));
    }
    let mut fits = String::from("solver,n_from,n_to,slope\n");
    for (kind, ns, slope) in [
        ("recursion", &FAST_N[..], slope_fast),
        ("dense", &DENSE_N[..], slope_dense),
        ("dense-assembly", &DENSE_N[..], slope_assembly),
        ("dense-minus-assembly", &DENSE_N[..], slope_factor),
    ] {
        let from = ns.iter().find(|&&n| n >= FIT_FROM).copied().unwrap_or(0);
        let _ = writeln!(
            fits,
            "{kind},{from},{},{}",
            ns[ns.len() - 1],
            fixed(slope, 3)
        );
    }
    Ok((csv, fits))
}
