//! Clipping polylines to the plot area (plotters draws outside it).

/// Split a polyline (plot space) into the pieces inside the rectangle
/// `[x0, x1] x [y0, y1]`; `None` points break the line.
pub(crate) fn clip_polyline(
    pts: &[Option<(f64, f64)>],
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let inside = |p: (f64, f64)| p.0 >= x0 && p.0 <= x1 && p.1 >= y0 && p.1 <= y1;
    if pts.len() == 1 {
        if let Some(p) = pts[0] {
            if inside(p) {
                out.push(vec![p]);
            }
        }
        return out;
    }
    for w in pts.windows(2) {
        let (Some(a), Some(b)) = (w[0], w[1]) else {
            if cur.len() > 1 {
                out.push(std::mem::take(&mut cur));
            }
            cur.clear();
            continue;
        };
        match clip_segment(a, b, (x0, x1), (y0, y1)) {
            Some((ca, cb)) => {
                if cur.last() != Some(&ca) {
                    if cur.len() > 1 {
                        out.push(std::mem::take(&mut cur));
                    }
                    cur.clear();
                    cur.push(ca);
                }
                cur.push(cb);
                if cb != b {
                    out.push(std::mem::take(&mut cur));
                }
            }
            None => {
                if cur.len() > 1 {
                    out.push(std::mem::take(&mut cur));
                }
                cur.clear();
            }
        }
    }
    if cur.len() > 1 {
        out.push(cur);
    }
    out
}

/// Liang-Barsky clipping of the segment `a`-`b`.
fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let mut t0 = 0.0f64;
    let mut t1 = 1.0f64;
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            a
        } else if t == 1.0 {
            b
        } else {
            (a.0 + t * dx, a.1 + t * dy)
        }
    };
    Some((at(t0), at(t1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_splits_lines() {
        let pts: Vec<Option<(f64, f64)>> = vec![
            Some((-1.0, 0.5)),
            Some((0.5, 0.5)),
            Some((2.0, 0.5)),
            Some((2.0, 0.7)),
            Some((0.5, 0.7)),
            None,
            Some((0.2, 0.2)),
            Some((0.3, 0.3)),
        ];
        let pieces = clip_polyline(&pts, (0.0, 1.0), (0.0, 1.0));
        assert_eq!(pieces.len(), 3, "{pieces:?}");
        assert_eq!(pieces[0], vec![(0.0, 0.5), (0.5, 0.5), (1.0, 0.5)]);
        assert_eq!(pieces[1], vec![(1.0, 0.7), (0.5, 0.7)]);
        assert_eq!(pieces[2], vec![(0.2, 0.2), (0.3, 0.3)]);
    }
}
