//! Colours: the 'cool' colormap (cyan -> magenta) used for time, and a
//! categorical palette for line plots.

use plotters::style::RGBColor;

/// matplotlib's 'cool': 0 -> cyan (0, 255, 255), 1 -> magenta (255, 0, 255).
/// `t` is clamped to [0, 1]; NaN maps to 0.
pub fn cool(t: f64) -> RGBColor {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let r = (255.0 * t).round() as u8;
    RGBColor(r, 255 - r, 255)
}

/// Red of P0 markers.
pub const P0_RED: RGBColor = RGBColor(214, 39, 40);
/// Blue of P1 markers.
pub const P1_BLUE: RGBColor = RGBColor(31, 80, 220);

/// A categorical palette (matplotlib's tab10 order), readable in print.
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Palette colour `i` (wraps around).
pub fn palette(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cool_ends_and_middle() {
        assert_eq!(cool(0.0), RGBColor(0, 255, 255));
        assert_eq!(cool(1.0), RGBColor(255, 0, 255));
        assert_eq!(cool(0.5), RGBColor(128, 127, 255));
        assert_eq!(cool(-3.0), cool(0.0));
        assert_eq!(cool(7.0), cool(1.0));
        assert_eq!(cool(f64::NAN), cool(0.0));
    }

    #[test]
    fn palette_wraps() {
        assert_eq!(palette(0), palette(10));
        assert_ne!(palette(0), palette(1));
    }
}
