//! Sizes of text, lines and margins in pixels, the embedded font as a text
//! style, and text widths.

use plotters::prelude::*;
use plotters::style::FontDesc;

use crate::font::FAMILY;

/// Sizes of text, lines and margins in pixels: those of a canvas about
/// 900 px tall ([`Sizes::STANDARD`]) times `scale`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sizes {
    /// Every size is this many times its standard value (e.g. 2 on a
    /// canvas drawn at twice the size, 0.7 for the smaller animation).
    pub scale: f64,
}

impl Sizes {
    pub const STANDARD: Sizes = Sizes { scale: 1.0 };

    /// These sizes on a canvas `s` times larger.
    pub fn scaled(self, s: u32) -> Sizes {
        Sizes {
            scale: self.scale * f64::from(s),
        }
    }

    /// plotters' font size is the line height (ascent + descent); the em is
    /// about 0.86 of it, so a tick label of 28 has an em of about 24 px.
    pub fn title(&self) -> f64 {
        40.0 * self.scale
    }
    pub fn label(&self) -> f64 {
        34.0 * self.scale
    }
    pub fn tick(&self) -> f64 {
        28.0 * self.scale
    }
    pub fn legend(&self) -> f64 {
        28.0 * self.scale
    }
    /// Width of a data line.
    pub fn line(&self) -> u32 {
        self.px(3.0) as u32
    }
    /// Width of axes and frames.
    pub fn axis(&self) -> u32 {
        self.px(2.0) as u32
    }
    pub fn px(&self, v: f64) -> i32 {
        (v * self.scale).round().max(1.0) as i32
    }
    pub fn font(&self, size: f64) -> TextStyle<'static> {
        TextStyle::from(FontDesc::new(
            FontFamily::Name(FAMILY),
            size,
            FontStyle::Normal,
        ))
    }
}

/// Width and height in pixels of `text` in the embedded font at `size`,
/// as plotters measures it (the height is the font's, whatever the text).
pub(crate) fn text_size(text: &str, size: f64) -> (i32, i32) {
    FontDesc::new(FontFamily::Name(FAMILY), size, FontStyle::Normal)
        .box_size(text)
        .map(|(w, h)| (w as i32, h as i32))
        .unwrap_or_else(|_| {
            (
                (text.chars().count() as f64 * 0.6 * size) as i32,
                (size / 1.24) as i32,
            )
        })
}

/// Width in pixels of `text` in the embedded font at `size`.
pub(crate) fn text_width(text: &str, size: f64) -> i32 {
    text_size(text, size).0
}
