//! Placing boxes (a legend, a note box) in the plot area where they hide the
//! least data and never each other; plotters only knows fixed positions.

use crate::ticks::Axis;

/// A rectangle in pixels of a plot area (y down): `x0..x1` by `y0..y1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelRect {
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
}

impl PixelRect {
    /// The rectangle of `(w, h)` pixels with its top-left corner at `(x, y)`.
    pub fn new((x, y): (i32, i32), (w, h): (i32, i32)) -> PixelRect {
        PixelRect {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + h,
        }
    }

    /// The top-left corner.
    pub fn origin(&self) -> (i32, i32) {
        (self.x0, self.y0)
    }

    /// Whether the two share any pixel (touching edges do not count).
    pub fn overlaps(&self, other: &PixelRect) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    /// Whether it lies inside an area of `(w, h)` pixels.
    pub fn inside(&self, (w, h): (i32, i32)) -> bool {
        self.x0 >= 0 && self.y0 >= 0 && self.x1 <= w && self.y1 <= h
    }

    /// This rectangle grown by `d` pixels on every side.
    fn grown(&self, d: i32) -> PixelRect {
        PixelRect {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }
}

/// A corner of the plot area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Corner {
    UpperRight,
    UpperLeft,
    LowerLeft,
    LowerRight,
}

impl Corner {
    pub const ALL: [Corner; 4] = [
        Corner::UpperRight,
        Corner::UpperLeft,
        Corner::LowerLeft,
        Corner::LowerRight,
    ];

    fn is_upper(self) -> bool {
        matches!(self, Corner::UpperRight | Corner::UpperLeft)
    }

    fn is_left(self) -> bool {
        matches!(self, Corner::UpperLeft | Corner::LowerLeft)
    }

    /// A box of `(bw, bh)` in this corner of a `(pw, ph)` plot area, `inset`
    /// px from its edges.
    pub fn rect(self, (bw, bh): (i32, i32), (pw, ph): (i32, i32), inset: i32) -> PixelRect {
        let x = if self.is_left() {
            inset
        } else {
            pw - inset - bw
        };
        let y = if self.is_upper() {
            inset
        } else {
            ph - inset - bh
        };
        PixelRect::new((x, y), (bw, bh))
    }
}

/// Where the data is, in pixels of the plot area: samples along every
/// polyline at most 6 px apart.
pub(crate) struct Occupancy {
    samples: Vec<(f64, f64)>,
}

impl Occupancy {
    pub fn new(lines: &[Vec<(f64, f64)>], x: &Axis, y: &Axis, (pw, ph): (i32, i32)) -> Occupancy {
        let to_px = |p: (f64, f64)| {
            (
                (p.0 - x.lo) / x.span() * pw as f64,
                (y.hi - p.1) / y.span() * ph as f64,
            )
        };
        let mut samples = Vec::new();
        for line in lines {
            let px: Vec<(f64, f64)> = line.iter().map(|&p| to_px(p)).collect();
            if let Some(&first) = px.first() {
                samples.push(first);
            }
            for w in px.windows(2) {
                let (a, b) = (w[0], w[1]);
                let n = ((b.0 - a.0).hypot(b.1 - a.1) / 6.0)
                    .ceil()
                    .clamp(1.0, 400.0) as usize;
                for i in 1..=n {
                    let t = i as f64 / n as f64;
                    samples.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
                }
            }
        }
        Occupancy { samples }
    }

    /// How many samples lie under `r` or within 6 px of it.
    pub fn covered(&self, r: &PixelRect) -> usize {
        let r = r.grown(6);
        let (x0, y0, x1, y1) = (r.x0 as f64, r.y0 as f64, r.x1 as f64, r.y1 as f64);
        self.samples
            .iter()
            .filter(|p| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1)
            .count()
    }

    /// The corner where a box of `size` covers the fewest samples, and how
    /// many it covers there; ties go to the order of [`Corner::ALL`].
    pub fn best_corner(&self, size: (i32, i32), plot: (i32, i32), inset: i32) -> (Corner, usize) {
        self.best_corner_except(size, plot, inset, None)
    }

    fn best_corner_except(
        &self,
        size: (i32, i32),
        plot: (i32, i32),
        inset: i32,
        taken: Option<Corner>,
    ) -> (Corner, usize) {
        let mut best = (Corner::UpperRight, usize::MAX);
        for c in Corner::ALL {
            if Some(c) == taken {
                continue;
            }
            let n = self.covered(&c.rect(size, plot, inset));
            if n < best.1 {
                best = (c, n);
            }
        }
        best
    }
}

/// Where the legend and the note box of a plot go, in pixels of its plot
/// area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Boxes {
    pub legend: Option<PixelRect>,
    pub note: Option<PixelRect>,
    /// Data samples the two cover together (see [`Occupancy::covered`]).
    pub hidden: usize,
}

/// Place a legend and a note box of the given sizes (either may be absent)
/// in a `plot` area. Each goes in a corner, `inset` px from the edges, or
/// the note right under an upper legend (above a lower one) on its side.
/// The two never overlap and keep `inset` px apart; of all such places, the
/// pair that hides the fewest data samples wins, then the one whose legend
/// hides fewer, then the first in the order of [`Corner::ALL`] (the note's
/// corners before the place beside the legend). Only in a plot too small
/// for both apart does the note go to the best corner the legend left.
pub(crate) fn place_boxes(
    occ: &Occupancy,
    plot: (i32, i32),
    inset: i32,
    legend: Option<(i32, i32)>,
    note: Option<(i32, i32)>,
) -> Boxes {
    let alone = |size: (i32, i32)| {
        let (c, hidden) = occ.best_corner(size, plot, inset);
        (c.rect(size, plot, inset), hidden)
    };
    let (legend_size, note_size) = match (legend, note) {
        (Some(l), Some(n)) => (l, n),
        (Some(l), None) => {
            let (r, hidden) = alone(l);
            return Boxes {
                legend: Some(r),
                note: None,
                hidden,
            };
        }
        (None, Some(n)) => {
            let (r, hidden) = alone(n);
            return Boxes {
                legend: None,
                note: Some(r),
                hidden,
            };
        }
        (None, None) => {
            return Boxes {
                legend: None,
                note: None,
                hidden: 0,
            }
        }
    };
    // (hidden by both, hidden by the legend, legend, note)
    let mut best: Option<(usize, usize, PixelRect, PixelRect)> = None;
    for lc in Corner::ALL {
        let l = lc.rect(legend_size, plot, inset);
        let l_hidden = occ.covered(&l);
        let beside = {
            let x = if lc.is_left() {
                inset
            } else {
                plot.0 - inset - note_size.0
            };
            let y = if lc.is_upper() {
                l.y1 + inset
            } else {
                l.y0 - inset - note_size.1
            };
            PixelRect::new((x, y), note_size)
        };
        let notes = Corner::ALL
            .into_iter()
            .filter(|&c| c != lc)
            .map(|c| c.rect(note_size, plot, inset))
            .chain(std::iter::once(beside));
        for n in notes {
            if !n.inside(plot) || n.overlaps(&l.grown(inset)) {
                continue;
            }
            let key = (l_hidden + occ.covered(&n), l_hidden);
            if best.is_none_or(|b| key < (b.0, b.1)) {
                best = Some((key.0, key.1, l, n));
            }
        }
    }
    match best {
        Some((hidden, _, l, n)) => Boxes {
            legend: Some(l),
            note: Some(n),
            hidden,
        },
        None => {
            let (lc, l_hidden) = occ.best_corner(legend_size, plot, inset);
            let (nc, n_hidden) = occ.best_corner_except(note_size, plot, inset, Some(lc));
            Boxes {
                legend: Some(lc.rect(legend_size, plot, inset)),
                note: Some(nc.rect(note_size, plot, inset)),
                hidden: l_hidden + n_hidden,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_occupancy(lines: &[Vec<(f64, f64)>], plot: (i32, i32)) -> Occupancy {
        let x = Axis::linear(0.0, 1.0, 5);
        let y = Axis::linear(0.0, 1.0, 5);
        Occupancy::new(lines, &x, &y, plot)
    }

    #[test]
    fn legend_avoids_data() {
        // Data along the top edge only.
        let occ = unit_occupancy(&[vec![(0.0, 0.95), (1.0, 0.95)]], (1000, 800));
        let (c, hidden) = occ.best_corner((200, 100), (1000, 800), 10);
        assert_eq!((c, hidden), (Corner::LowerLeft, 0));
        let (c2, _) = occ.best_corner_except((200, 100), (1000, 800), 10, Some(c));
        assert_eq!(c2, Corner::LowerRight);
    }

    #[test]
    fn wide_boxes_over_free_bottom_are_stacked() {
        // Data along the top: the lower band is free but too narrow for two
        // 600 px boxes side by side, so the note goes above the legend.
        let plot = (1000, 800);
        let occ = unit_occupancy(&[vec![(0.0, 0.95), (1.0, 0.95)]], plot);
        let b = place_boxes(&occ, plot, 10, Some((600, 100)), Some((600, 80)));
        let (l, n) = (b.legend.unwrap(), b.note.unwrap());
        assert_eq!(b.hidden, 0);
        assert!(!l.overlaps(&n) && l.inside(plot) && n.inside(plot));
        assert_eq!(l, Corner::LowerLeft.rect((600, 100), plot, 10));
        assert_eq!(n.y1 + 10, l.y0);
    }

    #[test]
    fn a_plot_too_small_for_both_still_gets_both() {
        let plot = (300, 200);
        let occ = unit_occupancy(&[], plot);
        let b = place_boxes(&occ, plot, 10, Some((250, 150)), Some((250, 150)));
        assert!(b.legend.is_some() && b.note.is_some());
        assert_ne!(b.legend, b.note);
    }
}
