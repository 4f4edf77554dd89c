//! The refinement of a list profile (`chain.rod_masses`, `chain.rod_lengths`)
//! to any number of rods: the continuum a list stands for, cut again.
//!
//! A list of `n` rods stands for a chain whose mass per length is piecewise
//! constant over arc length, `rho(s) = m_i / l_i` on rod `i`, with the
//! chain's length `L` and mass `M` fixed. Index the chain by the fractional
//! rod number `u` in `[0, n]`: rod `i` spans `u` in `[i, i + 1]`, and the arc
//! length `s(u)` is linear on it (slope `l_i`). The same chain cut into
//! `N` rods puts its joints at `u_j = j n / N`, `j = 0..=N`:
//!
//! * rod `j`'s length is `s(u_{j+1}) - s(u_j) = sum_i l_i |[u_j, u_{j+1}] ∩ [i, i + 1]|`
//!   (a length list refines to the lengths that keep its arc length as a
//!   function of the fractional joint index; without a length list the
//!   rods are equal, `s = u L / n`, and the cut is into equal rods);
//! * rod `j`'s mass is `rho` integrated over that span,
//!   `sum_i m_i |[u_j, u_{j+1}] ∩ [i, i + 1]|` (on rod `i`, `rho ds = m_i du`).
//!
//! Both are overlaps of index intervals, counted exactly in integers (units
//! of `1 / N` of an old rod: `[i N, (i + 1) N]` against `[j n, (j + 1) n]`),
//! so the totals `sum m_j = M` and `sum l_j = L` hold to rounding, and a new
//! rod that lies within one old rod has that rod's density. When `N` is a
//! multiple of `n` every new rod does: each old rod is cut into `N / n`
//! equal parts, the list's entries repeated, bit for bit as before this
//! refinement existed. A new rod that straddles a joint of the list gets the
//! mean density over its span; drawn as a uniform rod, its first moment of
//! mass about its midpoint `c` then differs from the continuum's by
//! `(rho_1 - rho_2) ((p - c)^2 - (l/2)^2) / 2` (`p` the straddled joint), at
//! most `|rho_1 - rho_2| l^2 / 8`: the refined chain's centre of mass along
//! the arc converges like `1 / N^2`, exact only for nested cuts.

/// The list `values` (one entry per rod, `n` of them), a piecewise
/// constant function of the fractional rod index, averaged over each of
/// `links` equal spans of the index: one entry per new rod, in the list's
/// own scale (the caller normalises). A nested cut (`links` a multiple of
/// `n`) repeats the entries. O(n + links).
pub(crate) fn refine_list(values: &[f64], links: usize) -> Vec<f64> {
    let n = values.len();
    if n == 0 || links == 0 {
        return Vec::new();
    }
    if links.is_multiple_of(n) {
        // Nested: each rod cut into equal parts, its entry repeated.
        let k = links / n;
        return values
            .iter()
            .flat_map(|&x| std::iter::repeat_n(x, k))
            .collect();
    }
    // Old rod i spans [i links, (i + 1) links], new rod j spans
    // [j n, (j + 1) n], in units of 1 / (n links) of the chain's index.
    let (n64, big) = (n as u64, links as u64);
    let mut out = Vec::with_capacity(links);
    let mut i = 0usize;
    for j in 0..big {
        let (lo, hi) = (j * n64, (j + 1) * n64);
        let mut sum = 0.0;
        // Old rods overlapping [lo, hi]: at most n / links + 2 of them.
        while i < n {
            let (a, b) = (i as u64 * big, (i as u64 + 1) * big);
            let overlap = hi.min(b).saturating_sub(lo.max(a));
            sum += values[i] * overlap as f64;
            if b <= hi {
                i += 1;
            } else {
                break;
            }
        }
        // In units of one new rod's span (n of the index units).
        out.push(sum / n as f64);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(sum x_j, sum x_j c_j)` with `c_j` the midpoints of equal cells on
    /// `[0, 1]`.
    fn moments(x: &[f64]) -> (f64, f64) {
        let h = 1.0 / x.len() as f64;
        x.iter().enumerate().fold((0.0, 0.0), |(m, f), (j, &v)| {
            (m + v * h, f + v * h * (j as f64 + 0.5) * h)
        })
    }

    #[test]
    fn nested_cuts_repeat_the_entries_and_keep_both_moments() {
        let rho = [3.0, 1.0, 2.5, 0.5];
        let fine = refine_list(&rho, 12);
        assert_eq!(fine[..3], [3.0; 3]);
        assert_eq!(fine[9..], [0.5; 3]);
        let (m0, f0) = moments(&rho);
        let (m1, f1) = moments(&fine);
        assert!((m1 - m0).abs() < 1e-15 && (f1 - f0).abs() < 1e-15);
        // Twice (4 -> 12 -> 36) is once (4 -> 36).
        assert_eq!(refine_list(&fine, 36), refine_list(&rho, 36));
    }

    #[test]
    fn any_cut_keeps_the_mass_and_moves_the_centre_by_the_straddled_joints() {
        // rho = 3 on [0, 1/2], 1 on [1/2, 1]; three rods: [0, 1/3] holds 1,
        // [1/3, 2/3] holds 2/3, [2/3, 1] holds 1/3 (per unit density x h).
        let x = refine_list(&[3.0, 1.0], 3);
        for (a, b) in x.iter().zip([3.0, 2.0, 1.0]) {
            assert!((a - b).abs() < 1e-15, "{x:?}");
        }
        for (rho, links) in [
            (vec![3.0, 1.0], 3),
            (vec![3.0, 1.0, 7.0, 0.2, 2.0], 7),
            (vec![1.0, 2.0, 3.0], 200),
            (vec![5.0, 1.0, 4.0, 2.0], 3),
        ] {
            let x = refine_list(&rho, links);
            assert_eq!(x.len(), links);
            let (m0, f0) = moments(&rho);
            let (m1, f1) = moments(&x);
            assert!((m1 - m0).abs() < 1e-14 * m0, "{rho:?} {links}");
            // The continuum's first moment less each straddling rod's
            // deficit (rho_1 - rho_2) ((p - c)^2 - (h/2)^2) / 2.
            let (n, h) = (rho.len(), 1.0 / links as f64);
            let mut want = f1;
            for k in 1..n {
                let p = k as f64 / n as f64;
                let j = (p / h).floor() as usize;
                let c = (j as f64 + 0.5) * h;
                if (p - j as f64 * h).abs() > 1e-12 && j < links {
                    want += (rho[k - 1] - rho[k]) * ((p - c).powi(2) - 0.25 * h * h) / 2.0;
                }
            }
            assert!(
                (want - f0).abs() < 1e-13 * f0,
                "{rho:?} {links}: {want} vs {f0}"
            );
        }
    }
}
