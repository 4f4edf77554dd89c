//! The one list of methods: each [`Method`] and the [`Integrator`] that runs
//! it. `Method::ALL`, every method's name and the "one of ..." of a bad
//! `run.method` come from here.

use std::sync::OnceLock;

use super::integrator::{Integrator, Run, Span};
use super::{auto, bdf, bdf_dense, dop853, dopri5, genalpha, moreau_jean, rk4, Method, Segment};
use crate::ode::{Observer, Problem};

/// Every method, in the order figures list them. Adding a method: its file,
/// its `Method` variant, its arm in [`integrator`] (the compiler asks for
/// it) and one line here.
pub(crate) const REGISTRY: &[Method] = &[
    Method::Rk4,
    Method::Dopri5,
    Method::Dop853,
    Method::Bdf,
    Method::BdfDense,
    Method::Auto,
    Method::GenAlpha,
    Method::MoreauJean,
];

/// The registered methods, in registry order (`Method::ALL`).
pub(crate) const fn methods<const N: usize>() -> [Method; N] {
    assert!(N == REGISTRY.len());
    let mut all = [Method::Auto; N];
    let mut i = 0;
    while i < N {
        all[i] = REGISTRY[i];
        i += 1;
    }
    all
}

/// The integrator of `method`: one for every variant, by construction.
pub(crate) fn integrator(method: Method) -> &'static Integrator {
    match method {
        Method::Rk4 => &rk4::RK4,
        Method::Dopri5 => &dopri5::DOPRI5,
        Method::Dop853 => &dop853::DOP853,
        Method::Bdf => &bdf::BDF,
        Method::BdfDense => &bdf_dense::BDF_DENSE,
        Method::Auto => &auto::AUTO,
        Method::GenAlpha => &genalpha::GEN_ALPHA,
        Method::MoreauJean => &moreau_jean::MOREAU_JEAN,
    }
}

/// The method named `name`, if any.
pub(crate) fn named(name: &str) -> Option<Method> {
    REGISTRY
        .iter()
        .copied()
        .find(|&m| integrator(m).name == name)
}

/// `"one of rk4, dopri5, ..."`: the accepted names, for error messages.
pub(crate) fn accepted_names() -> &'static str {
    static TEXT: OnceLock<String> = OnceLock::new();
    TEXT.get_or_init(|| {
        let names: Vec<&str> = REGISTRY.iter().map(|&m| integrator(m).name).collect();
        format!("one of {}", names.join(", "))
    })
}

/// Runs `method` on `problem` over `span` and records the span it covered
/// (a method that runs others, `auto`, records theirs instead).
pub fn run(
    method: Method,
    problem: &mut dyn Problem,
    span: &Span<'_>,
    obs: &mut dyn Observer,
) -> Run {
    run_with(integrator(method), method, problem, span, obs)
}

/// [`run`] with the integrator `it` standing for `method` (the report's
/// stepper is its model's `rk4`).
pub fn run_with(
    it: &Integrator,
    method: Method,
    problem: &mut dyn Problem,
    span: &Span<'_>,
    obs: &mut dyn Observer,
) -> Run {
    let mut run = (it.run)(problem, span, obs);
    if run.segments.is_empty() {
        run.segments.push(Segment {
            method,
            t_start: span.t0,
            t_end: run.outcome.t_reached,
        });
    }
    run
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_round_trip() {
        for (k, &m) in REGISTRY.iter().enumerate() {
            let i = integrator(m);
            assert_eq!(Method::ALL[k], m);
            assert_eq!(REGISTRY.iter().filter(|&&x| x == m).count(), 1);
            assert_eq!(m.as_str(), i.name);
            assert_eq!(named(i.name), Some(m));
            assert_eq!(i.name.parse::<Method>(), Ok(m));
        }
        assert_eq!(
            accepted_names(),
            "one of rk4, dopri5, dop853, bdf, bdf-dense, auto, gen-alpha, moreau-jean"
        );
    }

    #[test]
    fn only_rk4_and_moreau_jean_are_set_by_their_step() {
        for m in Method::ALL {
            let fixed = matches!(m, Method::Rk4 | Method::MoreauJean);
            assert_eq!(m.adaptive(), !fixed, "{m}");
            let name = if fixed { "dt" } else { "rtol" };
            assert_eq!(m.accuracy_name(), name, "{m}");
        }
    }
}
