//! Axis ranges and ticks: linear axes with nice steps, logarithmic axes
//! drawn as linear axes over `log10` of the data with our own key points
//! (exactly the powers of ten), handed to plotters as fixed key points.

use plotters::coord::ranged1d::DefaultFormatting;
use plotters::prelude::{BindKeyPoints, IntoPartialAxis, Ranged};

use crate::format::{linear_labels, power_of_ten};
use crate::sizes::text_width;

/// One axis: its range and ticks in plot space (`log10` of the data on a
/// log axis) and the tick labels.
#[derive(Debug, Clone)]
pub(crate) struct Axis {
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
    pub ticks: Vec<f64>,
    pub labels: Vec<String>,
    /// Minor grid lines (log axes: 2..9 times each decade).
    pub minor: Vec<f64>,
}

impl Axis {
    /// A linear axis over `[lo, hi]` with about `target` ticks.
    pub fn linear(lo: f64, hi: f64, target: usize) -> Axis {
        let (lo, hi) = nondegenerate(lo, hi);
        let ticks_for = |n: usize| {
            let step = nice_step((hi - lo) / n as f64);
            (step, multiples(lo, hi, step))
        };
        // At least three labelled ticks, whatever the range.
        let mut n = target.max(2);
        let (mut step, mut ticks) = ticks_for(n);
        while ticks.len() < 3 && n < 12 {
            n += 1;
            (step, ticks) = ticks_for(n);
        }
        let labels = linear_labels(&ticks, step);
        Axis {
            lo,
            hi,
            log: false,
            ticks,
            labels,
            minor: Vec::new(),
        }
    }

    /// A linear axis over `[lo, hi]` with ticks every `step` (at least
    /// the ends' nice ticks when `step` would give fewer than two).
    pub fn linear_step(lo: f64, hi: f64, step: f64) -> Axis {
        let (lo, hi) = nondegenerate(lo, hi);
        if !(step.is_finite() && step > 0.0) || (hi - lo) / step < 2.0 || (hi - lo) / step > 60.0 {
            return Axis::linear(lo, hi, 6);
        }
        let ticks = multiples(lo, hi, step);
        let labels = linear_labels(&ticks, step);
        Axis {
            lo,
            hi,
            log: false,
            ticks,
            labels,
            minor: Vec::new(),
        }
    }

    /// A log axis over `[lo, hi]` given in `log10` units: ticks at the
    /// powers of ten when at least two lie inside, else at 1, 2, 5 (or
    /// every mantissa, or nice linear steps) times them, labelled as plain
    /// numbers, so that data within a decade get ticks of their own.
    pub fn log(lo: f64, hi: f64, target: usize) -> Axis {
        let (lo, hi) = nondegenerate(lo, hi);
        let first = (lo - 1e-9).ceil() as i64;
        let last = (hi + 1e-9).floor() as i64;
        let count = (last - first + 1).max(0) as usize;
        if count < 2 || (hi - lo < 2.5 && 3 * count <= target.max(3) + 3) {
            return Axis::log_within(lo, hi, target);
        }
        let every = count.div_ceil(target.max(2)).max(1) as i64;
        let ticks: Vec<f64> = (first..=last)
            .filter(|k| k.rem_euclid(every) == 0)
            .map(|k| k as f64)
            .collect();
        let labels = ticks.iter().map(|&k| power_of_ten(k as i64)).collect();
        let mut minor = Vec::new();
        if every == 1 && count <= 8 {
            for k in (first - 1)..=last {
                for j in 2..=9 {
                    let v = k as f64 + (j as f64).log10();
                    if v > lo && v < hi {
                        minor.push(v);
                    }
                }
            }
        }
        Axis {
            lo,
            hi,
            log: true,
            ticks,
            labels,
            minor,
        }
    }

    /// A log axis over less than two and a half decades (`lo`, `hi` in
    /// `log10` units): ticks at the first of the mantissa sets 1, 2, 5 and
    /// 1 .. 9 that puts at least three inside, else at nice linear steps
    /// of the data; the other mantissas 1 .. 9 as minor grid lines.
    fn log_within(lo: f64, hi: f64, target: usize) -> Axis {
        let decades = (lo.floor() as i64 - 1)..=(hi.ceil() as i64);
        let inside = |v: f64| v >= lo - 1e-9 && v <= hi + 1e-9;
        let at = |mantissas: &[f64]| -> Vec<f64> {
            decades
                .clone()
                .flat_map(|k| mantissas.iter().map(move |m| k as f64 + m.log10()))
                .filter(|&v| inside(v))
                .collect()
        };
        let all: Vec<f64> = (1..=9).map(f64::from).collect();
        let mut ticks = at(&[1.0, 2.0, 5.0]);
        if ticks.len() < 3 {
            ticks = at(&all);
        }
        if ticks.len() > target.max(3) + 3 {
            ticks = at(&[1.0, 2.0, 5.0]);
        }
        if ticks.len() < 3 {
            let (a, b) = (10f64.powf(lo), 10f64.powf(hi));
            let step = nice_step((b - a) / target.max(3) as f64);
            ticks = multiples(a, b, step)
                .into_iter()
                .filter(|&v| v > 0.0)
                .map(f64::log10)
                .collect();
        }
        let labels = ticks
            .iter()
            .map(|&t| crate::format::format_number(10f64.powf(t), 3))
            .collect();
        let minor = at(&all)
            .into_iter()
            .filter(|v| !ticks.iter().any(|t| (t - v).abs() < 1e-9))
            .collect();
        Axis {
            lo,
            hi,
            log: true,
            ticks,
            labels,
            minor,
        }
    }

    /// An axis like this one (linear or log) over `[lo, hi]` (plot space)
    /// with ticks at the data values `at` inside it, labelled as plain
    /// numbers (a ladder of `n`, the steps of a method).
    pub fn with_ticks_at(&self, at: &[f64]) -> Axis {
        let ticks: Vec<f64> = at
            .iter()
            .filter_map(|&v| self.to_plot(v))
            .filter(|&p| {
                p >= self.lo - 1e-9 * self.span().abs() && p <= self.hi + 1e-9 * self.span().abs()
            })
            .collect();
        if ticks.len() < 2 {
            return self.clone();
        }
        let labels = at
            .iter()
            .filter(|&&v| {
                self.to_plot(v).is_some_and(|p| {
                    p >= self.lo - 1e-9 * self.span().abs()
                        && p <= self.hi + 1e-9 * self.span().abs()
                })
            })
            .map(|&v| crate::format::format_number(v, 4))
            .collect();
        Axis {
            ticks,
            labels,
            ..self.clone()
        }
    }

    /// An axis like this one with ticks at `at` (data values), each with
    /// its own label (e.g. the time of the snapshot drawn there); ticks
    /// outside the axis are left out. Fewer than two inside: unchanged.
    pub fn with_labelled_ticks(&self, at: &[(f64, String)]) -> Axis {
        let tol = 1e-9 * self.span().abs();
        let inside: Vec<(f64, String)> = at
            .iter()
            .filter_map(|(v, l)| self.to_plot(*v).map(|p| (p, l.clone())))
            .filter(|(p, _)| *p >= self.lo - tol && *p <= self.hi + tol)
            .collect();
        if inside.len() < 2 {
            return self.clone();
        }
        Axis {
            ticks: inside.iter().map(|(p, _)| *p).collect(),
            labels: inside.into_iter().map(|(_, l)| l).collect(),
            ..self.clone()
        }
    }

    /// Choose a range for data values in `[min, max]` (data space), padded
    /// by `pad` of the span, or exactly `fixed` if given.
    pub fn auto(
        min: f64,
        max: f64,
        fixed: Option<(f64, f64)>,
        log: bool,
        pad: f64,
        target: usize,
    ) -> Axis {
        if log {
            let (lo, hi) = match fixed {
                Some((a, b)) if a > 0.0 && b > 0.0 => (a.log10(), b.log10()),
                _ => log_range(min, max, pad),
            };
            Axis::log(lo, hi, target)
        } else {
            let (lo, hi) = fixed.unwrap_or_else(|| {
                let (lo, hi) = nondegenerate(min, max);
                let p = (hi - lo) * pad;
                (lo - p, hi + p)
            });
            Axis::linear(lo, hi, target)
        }
    }

    /// Data value to plot space; `None` if it cannot be shown.
    pub fn to_plot(&self, v: f64) -> Option<f64> {
        let p = if self.log {
            if v > 0.0 {
                v.log10()
            } else {
                return None;
            }
        } else {
            v
        };
        p.is_finite().then_some(p)
    }

    pub fn span(&self) -> f64 {
        self.hi - self.lo
    }

    /// The step between its first two ticks (its span without two).
    pub fn step(&self) -> f64 {
        match self.ticks[..] {
            [a, b, ..] => b - a,
            _ => self.span(),
        }
    }

    /// The label of the tick nearest to `v` (for plotters' formatter).
    pub fn label_at(&self, v: f64) -> String {
        let tol = 1e-6 * self.span().abs();
        self.ticks
            .iter()
            .position(|t| (t - v).abs() <= tol)
            .map(|i| self.labels[i].clone())
            .unwrap_or_default()
    }

    /// The plotters coordinate of this axis: linear over plot space, with
    /// the ticks as fixed bold key points and the minor grid lines as light
    /// ones.
    ///
    /// The outer `partial_axis` over the whole range changes nothing drawn:
    /// in plotters 0.3.7 `WithKeyPoints` over an `f64` range lacks the value
    /// formatter `configure_mesh` asks for (fixed after 0.3.7 by plotters
    /// PR #653), and `PartialAxis` brings the default one, which our label
    /// formatters replace.
    pub fn coord(&self) -> impl Ranged<ValueType = f64, FormatOption = DefaultFormatting> {
        (self.lo..self.hi)
            .with_key_points(self.ticks.clone())
            .with_light_points(self.minor.iter().copied())
            .partial_axis(self.lo..self.hi)
    }

    /// Widest tick label in pixels.
    pub fn max_label_width(&self, size: f64) -> i32 {
        self.labels
            .iter()
            .map(|l| text_width(l, size))
            .max()
            .unwrap_or(0)
    }
}

/// The most ticks an axis gets; more means a range the step cannot divide
/// (a span that overflows, such as `[-1e308, 1e308]`).
const MAX_TICKS: f64 = 1000.0;

/// The multiples `k step` in `[lo, hi]`, or none when there would be more
/// than [`MAX_TICKS`] of them or the range or step is not finite.
fn multiples(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let first = (lo / step - 1e-9).ceil();
    let last = (hi / step + 1e-9).floor();
    if !(first.is_finite() && last.is_finite() && last - first <= MAX_TICKS) {
        return Vec::new();
    }
    (first as i64..=last as i64)
        .map(|i| i as f64 * step)
        .collect()
}

fn nondegenerate(lo: f64, hi: f64) -> (f64, f64) {
    let (lo, hi) = if lo.is_finite() && hi.is_finite() {
        (lo.min(hi), lo.max(hi))
    } else {
        (0.0, 1.0)
    };
    if hi - lo > 1e-12 * lo.abs().max(hi.abs()) && hi > lo {
        (lo, hi)
    } else {
        let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        (lo - d, hi + d)
    }
}

/// A log range (log10 units) of the data padded by `pad` of its span (at
/// least a fiftieth of a decade each side): data within a decade keep a
/// range of their own ([`Axis::log`] gives it ticks).
fn log_range(min: f64, max: f64, pad: f64) -> (f64, f64) {
    if !(min > 0.0 && max > 0.0 && min.is_finite() && max.is_finite()) {
        return (0.0, 1.0);
    }
    let (a, b) = (min.log10(), max.log10());
    let p = ((b - a) * pad).max(0.02);
    (a - p, b + p)
}

/// 1, 2, 2.5 or 5 times a power of ten, at least `raw`.
pub(crate) fn nice_step(raw: f64) -> f64 {
    let raw = if raw.is_finite() && raw > 0.0 {
        raw
    } else {
        1.0
    };
    let e = raw.log10().floor();
    let base = 10f64.powf(e);
    let m = raw / base;
    let nice = if m <= 1.0 + 1e-9 {
        1.0
    } else if m <= 2.0 + 1e-9 {
        2.0
    } else if m <= 2.5 + 1e-9 {
        2.5
    } else if m <= 5.0 + 1e-9 {
        5.0
    } else {
        10.0
    };
    nice * base
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Labelled ticks keep their own labels, in order, and drop those
    /// outside the axis (fig12's snapshots labelled by their times).
    #[test]
    fn labelled_ticks_replace_the_numbers() {
        let a = Axis::linear(-0.3, 2.1, 5);
        let at: Vec<(f64, String)> = [(0.0, "0.00"), (0.6, "0.48"), (1.2, "0.96"), (9.0, "9.9")]
            .iter()
            .map(|(x, l)| (*x, l.to_string()))
            .collect();
        let b = a.with_labelled_ticks(&at);
        assert_eq!(b.labels, vec!["0.00", "0.48", "0.96"]);
        assert_eq!(b.ticks, vec![0.0, 0.6, 1.2]);
        assert_eq!(b.label_at(0.6), "0.48");
        // One tick inside is not an axis: the numbers stay.
        assert_eq!(a.with_labelled_ticks(&at[3..]).labels, a.labels);
    }

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(0.13), 0.2);
        assert_eq!(nice_step(0.9), 1.0);
        assert_eq!(nice_step(2.2), 2.5);
        assert_eq!(nice_step(30.0), 50.0);
        assert_eq!(nice_step(70.0), 100.0);
    }

    #[test]
    fn a_range_that_overflows_gets_no_ticks_rather_than_too_many() {
        let a = Axis::linear(-1.7e308, 1.7e308, 6);
        assert!(a.ticks.len() <= 1000, "{}", a.ticks.len());
        let a = Axis::linear_step(-1.7e308, 1.7e308, 1.0);
        assert!(a.ticks.len() <= 1000, "{}", a.ticks.len());
    }

    #[test]
    fn linear_ticks_and_labels() {
        let a = Axis::linear(-1.05, 6.3, 8);
        assert_eq!(a.ticks.first(), Some(&-1.0));
        assert_eq!(a.labels.first().map(String::as_str), Some("−1"));
        assert!(a.labels.contains(&"6".to_string()));
        let b = Axis::linear(0.0, 0.3, 3);
        assert_eq!(b.labels, vec!["0.0", "0.1", "0.2", "0.3"]);
        let d = Axis::linear(0.0, 100.0, 4);
        assert_eq!(d.labels, vec!["0", "25", "50", "75", "100"]);
        let f = Axis::linear(-1.6, 1.6, 3);
        assert!(f.ticks.len() >= 3, "{:?}", f.labels);
        let e = Axis::linear(-0.5, 0.5, 4);
        assert_eq!(e.labels, vec!["−0.50", "−0.25", "0.00", "0.25", "0.50"]);
        let c = Axis::linear(0.0, 5e-6, 5);
        assert!(c.labels.iter().any(|l| l == "1×10⁻⁶"), "{:?}", c.labels);
    }

    #[test]
    fn log_ticks_are_powers_of_ten() {
        let a = Axis::auto(2e-7, 3e-2, None, true, 0.03, 8);
        assert!(a.log);
        assert!(a.labels.contains(&"10⁻⁶".to_string()), "{:?}", a.labels);
        assert!(a.labels.iter().all(|l| l.starts_with("10")));
        // Data within a decade keep their range and get ticks inside it.
        let b = Axis::auto(2.0, 8.0, None, true, 0.03, 8);
        assert_eq!(b.labels, vec!["2", "3", "4", "5", "6", "7", "8"]);
        assert!(b.lo > 2f64.log10() - 0.05 && b.hi < 8f64.log10() + 0.05);
        let t = Axis::auto(1.4, 3.5, None, true, 0.04, 6);
        assert_eq!(t.labels, vec!["1.5", "2", "2.5", "3", "3.5"]);
        let i = Axis::auto(0.35, 0.75, None, true, 0.04, 6);
        assert_eq!(i.labels, vec!["0.4", "0.5", "0.6", "0.7"]);
        let n = Axis::auto(25.0, 400.0, None, true, 0.04, 6);
        assert_eq!(n.labels, vec!["50", "100", "200"]);
        let ladder = n.with_ticks_at(&[25.0, 50.0, 100.0, 200.0, 400.0]);
        assert_eq!(ladder.labels, vec!["25", "50", "100", "200", "400"]);
        // Many decades: labels thinned.
        let c = Axis::auto(1e-14, 1e2, None, true, 0.0, 6);
        assert!(c.ticks.len() <= 6, "{:?}", c.labels);
    }
}
