//! Placing boxes (legend, notes) in the corner of the plot area where they
//! hide the least data.

use crate::ticks::Axis;

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
}

/// Where the data is, in pixels of the plot area: samples along every
/// polyline at most `step` px apart.
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

    /// Top-left pixel of a `(bw, bh)` box in `corner`, `inset` px from the edges.
    pub fn origin(
        corner: Corner,
        (bw, bh): (i32, i32),
        (pw, ph): (i32, i32),
        inset: i32,
    ) -> (i32, i32) {
        match corner {
            Corner::UpperRight => (pw - inset - bw, inset),
            Corner::UpperLeft => (inset, inset),
            Corner::LowerLeft => (inset, ph - inset - bh),
            Corner::LowerRight => (pw - inset - bw, ph - inset - bh),
        }
    }

    /// The corner (not in `taken`) where a box of `size` covers the fewest
    /// samples; ties go to the order of [`Corner::ALL`].
    pub fn best(&self, size: (i32, i32), plot: (i32, i32), inset: i32, taken: &[Corner]) -> Corner {
        self.best_with_count(size, plot, inset, taken).0
    }

    /// [`Occupancy::best`] and how many samples that box still covers.
    pub fn best_with_count(
        &self,
        size: (i32, i32),
        plot: (i32, i32),
        inset: i32,
        taken: &[Corner],
    ) -> (Corner, usize) {
        let pad = 6.0;
        let mut best = (usize::MAX, Corner::UpperRight);
        for c in Corner::ALL {
            if taken.contains(&c) {
                continue;
            }
            let (ox, oy) = Self::origin(c, size, plot, inset);
            let (x0, y0) = (ox as f64 - pad, oy as f64 - pad);
            let (x1, y1) = (
                x0 + size.0 as f64 + 2.0 * pad,
                y0 + size.1 as f64 + 2.0 * pad,
            );
            let n = self
                .samples
                .iter()
                .filter(|p| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1)
                .count();
            if n < best.0 {
                best = (n, c);
            }
        }
        (best.1, best.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn legend_avoids_data() {
        let x = Axis::linear(0.0, 1.0, 5);
        let y = Axis::linear(0.0, 1.0, 5);
        // Data along the top edge only.
        let lines = vec![vec![(0.0, 0.95), (1.0, 0.95)]];
        let occ = Occupancy::new(&lines, &x, &y, (1000, 800));
        let c = occ.best((200, 100), (1000, 800), 10, &[]);
        assert_eq!(c, Corner::LowerLeft);
        let c2 = occ.best((200, 100), (1000, 800), 10, &[Corner::LowerLeft]);
        assert_eq!(c2, Corner::LowerRight);
    }
}
