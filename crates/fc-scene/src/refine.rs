//! Refinement: the same continuous chain cut into another number of rods,
//! the one rule `converge`, `needs`, the figures, `--refine N` and
//! Python's `Scene.refine(n)` all use ([`Scene::refined`]).
//!
//! `chain.links = N` alone is not a refinement: `chain.mass` and
//! `chain.damping` are per rod, so it multiplies the chain's mass by
//! `N / n` and changes its friction's continuum. Refining keeps what the
//! continuum sees ([`chain_ode::Chain::refined`]): the total mass
//! `M = n m`, the length `L`, the bending viscosity `eta = r l`, the axial
//! stiffness and viscosity `EA`, `eta_a` and the bending stiffness `EI`,
//! the tip mass, the pivot's motion and the rod profile's mass per length.

use chain_ode::Start;

use crate::error::Error;
use crate::scene::Scene;

/// The most rods a refinement may ask for: the scenes' cap on `chain.links`.
pub const MAX_LINKS: usize = 1_000_000;

/// The longest pattern of an `angles` start that a refinement continues
/// (rods): a zigzag's is 2.
pub const MAX_PERIOD: usize = 64;

/// One line stating the rule, for help texts, figures and data.
pub const RULE: &str = "total mass M = n m, length L and bending viscosity eta = r l kept \
                        (m = M/n, r = eta n/L), EA, EI and the tip mass carried";

/// Checks the number of rods a refinement asks for, naming `flag`
/// (`--refine`, `links`).
pub fn check_links(flag: &str, links: usize) -> Result<(), Error> {
    if (1..=MAX_LINKS).contains(&links) {
        Ok(())
    } else {
        Err(Error::field(
            flag,
            format!("must be an integer in 1..={MAX_LINKS} (got {links})"),
        ))
    }
}

impl Scene {
    /// This scene cut into `links` rods at fixed continuum: its chain
    /// refined by [`chain_ode::Chain::refined`] (which carries every field)
    /// and written back whole ([`Scene::with_chain`]). A folded start's
    /// `start.down` (if given) scales with `n` (rounded down). An `angles`
    /// start whose angles (and rates) repeat a pattern of at most
    /// [`MAX_PERIOD`] rods at least twice, such as a zigzag, continues that
    /// pattern rod by rod to `links` rods (each rod keeps its tilt, so the
    /// pattern's length shrinks with the rods); any other `angles` start has
    /// a fixed number of rods and is refused. The `[floor]` keys
    /// are the scene's own, kept as written (a contact stiffness given per
    /// contact point stays per point; its default, `1e4 m g / l`, follows
    /// the new rod).
    pub fn refined(&self, links: usize) -> Result<Scene, Error> {
        check_links("chain.links", links)?;
        let chain = self.chain()?;
        let mut s = self.with_chain(&chain.refined(links)?)?;
        if let Start::Angles { angles, rates, .. } = self.start() {
            // The start as written must hold first (its lists as long as
            // its rods): a refinement does not mend a wrong one.
            self.state()?;
            let Some(period) = pattern_period(&angles, rates.as_deref()) else {
                return Err(Error::field(
                    "start.kind",
                    format!(
                        "an \"angles\" start refines only when its angles (and rates) repeat \
                         a pattern of at most {MAX_PERIOD} rods at least twice; this one has a \
                         fixed number of rods"
                    ),
                ));
            };
            let continued = |list: &[f64]| {
                toml::Value::Array(
                    (0..links)
                        .map(|i| toml::Value::Float(list[i % period]))
                        .collect(),
                )
            };
            s = s.with_value("start.angles", continued(&angles))?;
            if let Some(rates) = rates {
                s = s.with_value("start.rates", continued(&rates))?;
            }
        }
        if let Start::Folded {
            down: Some(down), ..
        } = self.start()
        {
            let scaled = (down as u128 * links as u128 / chain.links() as u128) as i64;
            s = s.with_value("start.down", toml::Value::Integer(scaled))?;
        }
        Ok(s)
    }
}

/// The shortest period `p` with which `angles` (and `rates`, if given)
/// repeat exactly, `x[i] = x[i % p]`, if the pattern is there at least
/// twice (`2 p <= n`) and `p <= MAX_PERIOD`: a start such as a zigzag of
/// alternating tilts (`scenes/cayley-scale.toml`), which a refinement
/// continues rod by rod. At most `MAX_PERIOD` passes of O(n).
fn pattern_period(angles: &[f64], rates: Option<&[f64]>) -> Option<usize> {
    let n = angles.len();
    let repeats = |list: &[f64], p: usize| list.iter().enumerate().all(|(i, x)| *x == list[i % p]);
    (1..=(n / 2).min(MAX_PERIOD))
        .find(|&p| repeats(angles, p) && rates.is_none_or(|r| repeats(r, p)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(text: &str) -> Scene {
        Scene::from_toml_str(text).unwrap()
    }

    const ELASTIC: &str = "[chain]\nlinks = 10\nmass = 0.3\nlength = 4\ndamping = 0.002\n\
        axial_stiffness = 1e5\naxial_damping = 3\nbending_stiffness = 0.7\ntip_mass = 0.5\n\
        [start]\nkind = \"catenary\"\np1 = [2, 0]\n[run]\nt_end = 1\n";

    /// The continuum's properties, computed from the chain each time: M,
    /// L, eta = r l, EA, eta_a, EI, the tip mass.
    fn continuum(s: &Scene) -> [f64; 7] {
        let c = s.chain().unwrap();
        let p = c.params();
        [
            c.total_mass(),
            c.length(),
            c.damping() * c.rod_length(),
            p.axial_stiffness.unwrap_or(0.0),
            p.axial_damping,
            p.bending_stiffness,
            c.tip_mass(),
        ]
    }

    #[test]
    fn refining_keeps_the_continuum_and_moves_only_the_rods() {
        let base = scene(ELASTIC);
        let before = continuum(&base);
        for n in [1, 7, 10, 40, 333] {
            let s = base.refined(n).unwrap();
            assert_eq!(s.chain().unwrap().links(), n);
            for (a, b) in continuum(&s).iter().zip(before) {
                assert!(
                    (a - b).abs() <= 1e-13 * b.abs().max(1.0),
                    "n = {n}: {a} vs {b}"
                );
            }
            // Per rod: m = M / n and r = eta n / L.
            let c = s.chain().unwrap();
            assert!((c.mass() - 3.0 / n as f64).abs() < 1e-15 * 3.0);
            assert!((c.damping() - 0.0008 * n as f64 / 4.0).abs() < 1e-15 * c.damping().max(1.0));
        }
        // Setting chain.links is not refining: the mass grows with n.
        let set = base
            .with_value("chain.links", toml::Value::Integer(40))
            .unwrap();
        assert!((set.chain().unwrap().total_mass() - 12.0).abs() < 1e-12);
    }

    #[test]
    fn the_refinement_is_a_round_trip_and_bad_counts_name_the_field() {
        let base = scene(ELASTIC);
        let back = base.refined(80).unwrap().refined(10).unwrap();
        for (a, b) in continuum(&back).iter().zip(continuum(&base)) {
            assert!((a - b).abs() <= 1e-13 * b.abs().max(1.0));
        }
        assert_eq!(back.chain().unwrap().mass(), base.chain().unwrap().mass());
        for bad in [0, MAX_LINKS + 1] {
            let e = base.refined(bad).unwrap_err().to_string();
            assert!(
                e.starts_with("chain.links: must be an integer in 1..=1000000"),
                "{e}"
            );
            let e = check_links("--refine", bad).unwrap_err().to_string();
            assert!(e.starts_with("--refine: "), "{e}");
        }
    }

    #[test]
    fn a_repeating_angles_start_continues_its_pattern_and_any_other_is_refused() {
        let zigzag = "[chain]\nlinks = 4\nmass = 0.25\nlength = 1\n[start]\nkind = \"angles\"\n\
            angles = [-1.55, -1.59, -1.55, -1.59]\nrates = [0.5, 0.5, 0.5, 0.5]\n[run]\nt_end = 1\n";
        let s = scene(zigzag).refined(7).unwrap();
        let Start::Angles { angles, rates, .. } = s.start() else {
            panic!("the start stays an angles start");
        };
        assert_eq!(angles, [-1.55, -1.59, -1.55, -1.59, -1.55, -1.59, -1.55]);
        assert_eq!(rates.as_deref(), Some(&[0.5; 7][..]));
        let c = s.chain().unwrap();
        assert!((c.total_mass() - 1.0).abs() < 1e-15);
        s.state().unwrap();
        // A start whose angles do not match its rods stays refused.
        let short = zigzag.replace("-1.55, -1.59, -1.55, -1.59", "-1.55, -1.59");
        let e = scene(&short).refined(8).unwrap_err().to_string();
        assert!(e.starts_with("start.angles: "), "{e}");
        // No repeat (a pattern seen once), or rates that break the angles'
        // pattern: refused, naming the field.
        for bad in [
            zigzag.replace("-1.55, -1.59, -1.55, -1.59", "-1.55, -1.59, -1.55, -1.6"),
            zigzag.replace("0.5, 0.5, 0.5, 0.5", "0.5, 0.5, 0.5, 0.6"),
        ] {
            let e = scene(&bad).refined(8).unwrap_err().to_string();
            assert!(
                e.starts_with("start.kind: an \"angles\" start refines only"),
                "{e}"
            );
        }
    }
}
