//! The embedded font. plotters' `ab_glyph` backend loads no system font: a
//! family name must be registered before any text is drawn, or drawing
//! fails with `FontUnavailable`. DejaVu Sans is compiled in (the `dejavu`
//! crate), so figures render identically on a machine with no fonts.

use std::sync::OnceLock;

use plotters::style::{register_font, FontStyle};

use crate::FigureError;

/// The family every figure uses. SVG output names it as CSS, so a viewer
/// uses DejaVu Sans where it has it (same metrics as the PNG) and its own
/// sans-serif face otherwise.
pub(crate) const FAMILY: &str = "DejaVu Sans, sans-serif";

/// Register DejaVu Sans under [`FAMILY`] (once per process).
pub(crate) fn ensure_registered() -> Result<(), FigureError> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        let faces: [(FontStyle, &'static [u8]); 4] = [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
            (FontStyle::Italic, dejavu::sans::oblique()),
            (FontStyle::Oblique, dejavu::sans::oblique()),
        ];
        // Also as "sans-serif", plotters' default family.
        faces.into_iter().all(|(style, bytes)| {
            [FAMILY, "sans-serif"]
                .into_iter()
                .all(|name| register_font(name, style, bytes).is_ok())
        })
    });
    if ok {
        Ok(())
    } else {
        Err(FigureError::Font)
    }
}
