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

/// Place a legend in its best corner, then a note box in the best corner
/// the legend left.
pub(crate) fn place_boxes(
    occ: &Occupancy,
    plot: (i32, i32),
    inset: i32,
    legend: Option<(i32, i32)>,
    note: Option<(i32, i32)>,
) -> Boxes {
    let mut boxes = Boxes {
        legend: None,
        note: None,
        hidden: 0,
    };
    let mut taken = None;
    if let Some(size) = legend {
        let (c, hidden) = occ.best_corner(size, plot, inset);
        boxes.legend = Some(c.rect(size, plot, inset));
        boxes.hidden += hidden;
        taken = Some(c);
    }
    if let Some(size) = note {
        let (c, hidden) = occ.best_corner_except(size, plot, inset, taken);
        boxes.note = Some(c.rect(size, plot, inset));
        boxes.hidden += hidden;
    }
    boxes
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
}
