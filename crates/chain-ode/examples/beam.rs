//! One run of the BEAM benchmark (`chain_ode::beam`: the IVP test set's
//! stiff beam of 40 segments, `t` in `[0, 5]`) as one JSON line: the
//! method, its accuracy parameter (`rtol`, with `atol = rtol`, or RK4's
//! `dt`), the status, the work counters, the wall time of the integration
//! and `y1, y40, y41, y80` at the end, beside the test set's reference.
//!
//! `cargo run --release -p chain-ode --example beam -- METHOD RTOL`
//!
//! A bad argument prints one line naming it and exits with status 2.

use std::process::ExitCode;

use chain_ode::beam::REFERENCE;
use chain_ode::{solve, BeamModel, Method};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [method, accuracy] = args.as_slice() else {
        eprintln!("usage: beam METHOD RTOL (RK4: beam rk4 DT)");
        return ExitCode::from(2);
    };
    let method: Method = match method.parse() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    let name = method.accuracy_name();
    let Ok(x) = accuracy.parse::<f64>() else {
        eprintln!("{name}: expected a number, got {accuracy:?}");
        return ExitCode::from(2);
    };
    let model = BeamModel::new();
    let start = model.start();
    let run = match BeamModel::options(method, x).and_then(|o| solve(model, &start, method, &o)) {
        Ok(run) => run,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    let num = |v: f64| {
        if v.is_finite() {
            format!("{v:e}")
        } else {
            "null".into()
        }
    };
    let s = &run.stats;
    let mut line = format!(
        "{{\"method\":\"{method}\",\"{name}\":{},\"status\":\"{}\",\"t_reached\":{},\
         \"steps\":{},\"rejected_steps\":{},\"rhs_evals\":{},\"jacobian_evals\":{},\
         \"lu_factorizations\":{},\"error_test_failures\":{},\"newton_failures\":{},\
         \"newton_iterations\":{},\"wall_seconds\":{}",
        num(x),
        run.status,
        num(run.t_reached),
        s.steps,
        s.rejected_steps,
        s.rhs_evals,
        s.jacobian_evals,
        s.lu_factorizations,
        s.error_test_failures,
        s.newton_failures,
        s.newton_iterations,
        num(run.summary.wall_seconds),
    );
    for (i, r) in REFERENCE {
        line += &format!(
            ",\"y{i}\":{},\"y{i}_reference\":{}",
            num(BeamModel::component(&run.final_state, i)),
            num(r)
        );
    }
    line += "}";
    println!("{line}");
    ExitCode::SUCCESS
}
