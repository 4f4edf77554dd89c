//! Number formats: tick labels of linear axes, powers of ten with
//! superscript exponents, numbers for legends and notes, the typographic
//! minus.

const SUPERSCRIPT: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];

fn superscript(k: i64) -> String {
    let mut s = String::new();
    if k < 0 {
        s.push('⁻');
    }
    for d in k.unsigned_abs().to_string().bytes() {
        s.push(SUPERSCRIPT[(d - b'0') as usize]);
    }
    s
}

/// "10³", "10⁻⁴".
pub(crate) fn power_of_ten(k: i64) -> String {
    format!("10{}", superscript(k))
}

/// Typographic minus for negative numbers.
fn minus(s: String) -> String {
    if let Some(rest) = s.strip_prefix('-') {
        format!("−{rest}")
    } else {
        s
    }
}

/// Labels for ticks `step` apart: plain decimals, or "m×10ᵏ" for very
/// small or large values.
pub(crate) fn linear_labels(ticks: &[f64], step: f64) -> Vec<String> {
    let max_abs = ticks.iter().fold(0.0f64, |m, t| m.max(t.abs()));
    let step_exp = step.log10().floor() as i64;
    // 0.25, 2.5 need one digit more than their power of ten; 25 does not.
    let extra = usize::from(is_two_and_half(step) && step_exp <= 0);
    let sci = max_abs >= 1e5 || step < 1e-3;
    ticks
        .iter()
        .map(|&t| {
            let zero = t.abs() < step * 1e-6;
            if sci {
                if zero {
                    return "0".to_string();
                }
                let e = t.abs().log10().floor() as i64;
                let m = t / 10f64.powi(e as i32);
                let decimals =
                    (e - step_exp).clamp(0, 6) as usize + usize::from(is_two_and_half(step));
                let m = trim_zeros(format!("{m:.decimals$}"));
                minus(format!("{m}×{}", power_of_ten(e)))
            } else {
                let decimals = (-step_exp).max(0) as usize + extra;
                // No "−0.0".
                let t = if zero { 0.0 } else { t };
                minus(format!("{t:.decimals$}"))
            }
        })
        .collect()
}

fn is_two_and_half(step: f64) -> bool {
    let m = step / 10f64.powf(step.log10().floor());
    (m - 2.5).abs() < 1e-6
}

fn trim_zeros(s: String) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Format a number for text (legends, notes): up to `sig` significant
/// digits, typographic minus.
pub fn format_number(v: f64, sig: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let e = v.abs().log10().floor() as i64;
    if !(-3..5).contains(&e) {
        let m = v / 10f64.powi(e as i32);
        let m = trim_zeros(format!("{m:.*}", sig.saturating_sub(1)));
        return minus(format!("{m}×{}", power_of_ten(e)));
    }
    let decimals = (sig as i64 - 1 - e).max(0) as usize;
    minus(trim_zeros(format!("{v:.decimals$}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_format() {
        assert_eq!(format_number(2.5, 3), "2.5");
        assert_eq!(format_number(-0.126, 2), "−0.13");
        assert_eq!(format_number(1.5e-6, 2), "1.5×10⁻⁶");
        assert_eq!(power_of_ten(-12), "10⁻¹²");
    }
}
