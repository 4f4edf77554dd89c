//! Per-rod profiles of mass and of length: the tapered whip.
//!
//! A [`Profile`] says how the chain's total mass `n m` and its length `L`
//! are shared among its `n` rods: by a rule (a linear taper of the mass per
//! length from the pivot to the tip, `chain.taper`), or by explicit lists of
//! relative rod masses (`chain.rod_masses`) and rod lengths
//! (`chain.rod_lengths`). The default, equal rods, is no profile at all:
//! [`Profile::rods`] is `None` and every computation keeps the arithmetic of
//! equal rods bit for bit.
//!
//! A profiled chain is described to the dynamics by [`Rods`]: rod `i`'s mass
//! `m_i = mu_i m` and length `l_i = lambda_i l` in units of the mean rod,
//! `m = M / n`, `l = L / n` (so `sum mu_i = sum lambda_i = n`).

use crate::chain::{check, number_text};
use fc_methods::InvalidParameter;

/// The taper's accepted range, in words (`chain.taper`).
pub const TAPER_RANGE: &str = "a finite number in 0.001..=1000";
/// The smallest and largest `chain.taper`.
pub const TAPER_BOUNDS: (f64, f64) = (1e-3, 1e3);
/// The largest ratio of two entries of a list (`chain.rod_masses`,
/// `chain.rod_lengths`): the rods' scales stay within floating point's
/// comfortable range.
pub const MAX_LIST_RATIO: f64 = 1e6;

/// How mass and length are shared among the rods (plain data; checked by
/// [`crate::Chain::new`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// The ratio `k` of the mass per length at the pivot to that at the tip
    /// (`chain.taper`; dimensionless, default 1: uniform). The mass per length
    /// falls linearly in arc length, `rho(s) ∝ k - (k - 1) s / L`; rod `i`
    /// carries `rho` integrated over its span. "Tapered 10:1" is `taper = 10`.
    pub taper: f64,
    /// Relative masses of the rods from the pivot to the tip
    /// (`chain.rod_masses`; `n` finite numbers > 0), scaled so that they sum
    /// to `n m`. Excludes a taper other than 1.
    pub masses: Option<Vec<f64>>,
    /// Relative lengths of the rods from the pivot to the tip
    /// (`chain.rod_lengths`; `n` finite numbers > 0), scaled so that they
    /// sum to `L`. With a taper, each rod's mass is the taper's mass per
    /// length integrated over its span.
    pub lengths: Option<Vec<f64>>,
}

impl Default for Profile {
    /// Equal rods.
    fn default() -> Self {
        Self {
            taper: 1.0,
            masses: None,
            lengths: None,
        }
    }
}

/// Rod masses and lengths in units of the mean rod (`mu_i = m_i / m`,
/// `lambda_i = l_i / l`, each summing to `n`), with the derived values the
/// recursion reads per rod.
#[derive(Clone, Debug, PartialEq)]
pub struct Rods {
    /// `mu_i = m_i / m`.
    pub mass: Vec<f64>,
    /// `lambda_i = l_i / l`.
    pub length: Vec<f64>,
    /// `1 / mu_i`.
    pub inv_mass: Vec<f64>,
    /// `1 / lambda_i`.
    pub inv_length: Vec<f64>,
    /// The bending spring of joint `i` (between rods `i - 1` and `i`) in
    /// units of the mean rod's `EI / l`: `2 / (lambda_{i-1} + lambda_i)`,
    /// one over the joint's share of length, the distance between the two
    /// rods' centres (`docs/model.md`, "Bending of unequal rods"). Entry 0,
    /// the pivot, is 0: it has no spring.
    pub joint: Vec<f64>,
}

impl Profile {
    /// True for equal rods (no key given, or `taper = 1` alone).
    pub fn is_uniform(&self) -> bool {
        self.taper == 1.0 && self.masses.is_none() && self.lengths.is_none()
    }

    /// The key of the first profile field given (for refusals of unknown
    /// combinations), `None` for equal rods.
    pub fn first_given(&self) -> Option<&'static str> {
        if self.taper != 1.0 {
            Some("chain.taper")
        } else if self.masses.is_some() {
            Some("chain.rod_masses")
        } else if self.lengths.is_some() {
            Some("chain.rod_lengths")
        } else {
            None
        }
    }

    /// Checks the profile for a chain of `links` rods (lengths first, so
    /// that nothing is read past them).
    pub(crate) fn validate(&self, links: usize) -> Result<(), InvalidParameter> {
        let (lo, hi) = TAPER_BOUNDS;
        check(
            self.taper.is_finite() && (lo..=hi).contains(&self.taper),
            "chain.taper",
            TAPER_RANGE,
            self.taper,
        )?;
        for (field, list) in [
            ("chain.rod_masses", &self.masses),
            ("chain.rod_lengths", &self.lengths),
        ] {
            let Some(list) = list else { continue };
            check(
                list.len() == links,
                field,
                format!("a list of chain.links = {links} numbers"),
                format!("{} values", list.len()),
            )?;
            let bad = list.iter().find(|x| !(x.is_finite() && **x > 0.0));
            check(
                bad.is_none(),
                field,
                "finite numbers > 0",
                bad.copied().unwrap_or(f64::NAN),
            )?;
            let (min, max) = list
                .iter()
                .fold((f64::INFINITY, 0.0_f64), |(a, b), &x| (a.min(x), b.max(x)));
            check(
                max <= MAX_LIST_RATIO * min,
                field,
                "numbers within a factor 1e6 of each other",
                format!("max / min = {}", number_text(max / min)),
            )?;
        }
        check(
            self.masses.is_none() || self.taper == 1.0,
            "chain.taper",
            "1 with chain.rod_masses (the list gives the masses)",
            self.taper,
        )
    }

    /// The rods of a checked profile of `links` rods; `None` for equal rods.
    pub(crate) fn rods(&self, links: usize) -> Option<Rods> {
        if self.is_uniform() {
            return None;
        }
        let n = links as f64;
        let scaled = |list: &[f64]| -> Vec<f64> {
            let sum: f64 = list.iter().sum();
            list.iter().map(|x| x * n / sum).collect()
        };
        let length = match &self.lengths {
            Some(list) => scaled(list),
            None => vec![1.0; links],
        };
        let mass = match &self.masses {
            Some(list) => scaled(list),
            None => {
                // rho(s) = k - (k - 1) s / L at each rod's midpoint, times its
                // length (exact for a linear rho), in units s / L.
                let k = self.taper;
                let mut s = 0.0;
                let raw: Vec<f64> = length
                    .iter()
                    .map(|&lam| {
                        let mid = (s + 0.5 * lam) / n;
                        s += lam;
                        lam * (k - (k - 1.0) * mid)
                    })
                    .collect();
                scaled(&raw)
            }
        };
        let inv = |v: &[f64]| v.iter().map(|x| 1.0 / x).collect();
        let joint = (0..links)
            .map(|i| match i {
                0 => 0.0,
                _ => 2.0 / (length[i - 1] + length[i]),
            })
            .collect();
        Some(Rods {
            joint,
            inv_mass: inv(&mass),
            inv_length: inv(&length),
            mass,
            length,
        })
    }

    /// The same continuum cut into `links` rods (any number, finer or
    /// coarser): a taper is a continuum property and is carried; lists (a
    /// piecewise constant mass per length over arc length) are cut again by
    /// [`crate::profile_refine`]: the masses integrated over each new rod,
    /// the lengths keeping the arc length as a function of the fractional
    /// joint index (equal rods stay equal), each rod of the list cut into
    /// `links / n` equal parts when `links` is a multiple of the `n` it was
    /// given for.
    pub(crate) fn refined(&self, n: usize, links: usize) -> Result<Self, InvalidParameter> {
        if self.masses.is_none() && self.lengths.is_none() {
            return Ok(self.clone());
        }
        let field = self.first_given().unwrap_or("chain.rod_masses");
        check(
            n > 0 && links > 0,
            field,
            "refined to at least one rod",
            format!("chain.links = {links}"),
        )?;
        let cut = |list: &Option<Vec<f64>>| {
            list.as_ref()
                .map(|l| crate::profile_refine::refine_list(l, links))
        };
        Ok(Self {
            taper: self.taper,
            masses: cut(&self.masses),
            lengths: cut(&self.lengths),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_taper_shares_the_mass_linearly_and_keeps_the_totals() {
        let p = Profile {
            taper: 10.0,
            ..Profile::default()
        };
        let rods = p.rods(4).unwrap();
        let sum: f64 = rods.mass.iter().sum();
        assert!((sum - 4.0).abs() < 1e-14);
        // Midpoints 1/8, 3/8, 5/8, 7/8 of rho = 10 - 9 s: equal steps.
        let d: Vec<f64> = rods.mass.windows(2).map(|w| w[0] - w[1]).collect();
        assert!(d.iter().all(|x| (x - d[0]).abs() < 1e-14 && *x > 0.0));
        // rho(1/8) / rho(7/8) = 8.875 / 2.125.
        assert!((rods.mass[0] / rods.mass[3] - 8.875 / 2.125).abs() < 1e-13);
        assert!(Profile::default().rods(4).is_none());
    }

    #[test]
    fn each_bad_profile_is_refused_by_its_key() {
        let bad = [
            (
                Profile {
                    taper: 0.0,
                    ..Profile::default()
                },
                "chain.taper",
            ),
            (
                Profile {
                    taper: f64::NAN,
                    ..Profile::default()
                },
                "chain.taper",
            ),
            (
                Profile {
                    masses: Some(vec![1.0; 3]),
                    ..Profile::default()
                },
                "chain.rod_masses",
            ),
            (
                Profile {
                    lengths: Some(vec![1.0, 0.0, 1.0, 1.0]),
                    ..Profile::default()
                },
                "chain.rod_lengths",
            ),
            (
                Profile {
                    lengths: Some(vec![1.0, 1e7, 1.0, 1.0]),
                    ..Profile::default()
                },
                "chain.rod_lengths",
            ),
            (
                Profile {
                    taper: 2.0,
                    masses: Some(vec![1.0; 4]),
                    ..Profile::default()
                },
                "chain.taper",
            ),
        ];
        for (p, field) in bad {
            let e = p.validate(4).unwrap_err();
            assert_eq!(e.field, field);
            assert!(!e.to_string().contains('\n'));
        }
    }

    #[test]
    fn lists_refine_by_whole_cuts_and_by_any_cut() {
        let p = Profile {
            masses: Some(vec![3.0, 1.0]),
            ..Profile::default()
        };
        let q = p.refined(2, 6).unwrap();
        assert_eq!(q.masses.unwrap(), vec![3.0, 3.0, 3.0, 1.0, 1.0, 1.0]);
        // Any number: the mean over each new rod's span.
        let q = p.refined(2, 5).unwrap().masses.unwrap();
        for (a, b) in q.iter().zip([3.0, 3.0, 2.0, 1.0, 1.0]) {
            assert!((a - b).abs() < 1e-15, "{q:?}");
        }
        assert_eq!(p.refined(2, 0).unwrap_err().field, "chain.rod_masses");
    }
}
