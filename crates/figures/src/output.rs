//! Errors, rendering a figure to both backends, and atomic file output.
//!
//! A figure is drawn twice from the same code: once into an RGB buffer
//! (encoded here as PNG) and once into an SVG string. Both are rendered in
//! memory first; only then are the files written, through [`crate::atomic`],
//! so a failure never leaves a half-written file behind.

use std::error::Error;
use std::ffi::OsString;
use std::fmt;
use std::io;
use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::drawing::DrawingAreaErrorKind;
use plotters::prelude::{BitMapBackend, DrawingArea, DrawingBackend, IntoDrawingArea, SVGBackend};

use crate::font;
use crate::line_layout::PanelLayout;

/// The files one figure was written to, and, for a line plot or a pair,
/// what each panel drew ([`PanelLayout`]: its axes, its data's extent,
/// its boxes), for checks of the figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Output {
    pub png: PathBuf,
    pub svg: PathBuf,
    /// Empty for the figures that report no layout (snapshots, maps, the
    /// sketch).
    pub panels: Vec<PanelLayout>,
}

impl Output {
    /// `<stem>.png` and `<stem>.svg` (the extensions are appended, so a stem
    /// such as `fig07-d1.5` keeps its dot).
    pub fn for_stem(stem: &Path) -> Self {
        Self {
            png: with_suffix(stem, ".png"),
            svg: with_suffix(stem, ".svg"),
            panels: Vec::new(),
        }
    }

    /// What is wrong with the panels drawn (see [`PanelLayout::problems`]),
    /// each line naming its panel; empty when nothing is.
    pub fn problems(&self) -> Vec<String> {
        self.panels
            .iter()
            .enumerate()
            .flat_map(|(k, p)| {
                let which = match (self.panels.len(), k) {
                    (1, _) => String::new(),
                    (_, 0) => "left panel: ".to_string(),
                    (_, 1) => "right panel: ".to_string(),
                    (_, k) => format!("panel {k}: "),
                };
                p.problems().into_iter().map(move |e| format!("{which}{e}"))
            })
            .collect()
    }
}

/// Why a figure could not be made.
#[derive(Debug)]
pub enum FigureError {
    /// Reading or writing a file failed.
    Io { path: PathBuf, source: io::Error },
    /// The embedded font could not be registered.
    Font,
    /// Drawing failed inside plotters.
    Plot(String),
    /// Encoding the PNG or GIF failed.
    Encode(String),
    /// The data cannot be drawn (nothing finite to show, mismatched sizes...).
    Data(String),
}

impl fmt::Display for FigureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, source } => write!(f, "cannot write {}: {source}", path.display()),
            Self::Font => write!(f, "cannot register the embedded DejaVu Sans font"),
            Self::Plot(msg) => write!(f, "plotting failed: {msg}"),
            Self::Encode(msg) => write!(f, "image encoding failed: {msg}"),
            Self::Data(msg) => write!(f, "cannot draw the data: {msg}"),
        }
    }
}

impl Error for FigureError {
    fn source(&self) -> Option<&(dyn Error + 'static)> {
        match self {
            Self::Io { source, .. } => Some(source),
            _ => None,
        }
    }
}

impl<E: Error + Send + Sync> From<DrawingAreaErrorKind<E>> for FigureError {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        // plotters' messages can span lines; keep ours to one.
        Self::Plot(e.to_string().replace('\n', " "))
    }
}

/// A figure that can draw itself on any plotters backend.
pub(crate) trait Draw {
    /// Canvas size in pixels (width, height) at scale 1.
    fn size(&self) -> (u32, u32);
    /// Draw on `root`, a canvas of `scale` times [`Draw::size`]: every
    /// length in pixels (text, lines, margins) is multiplied by `scale`.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: u32,
    ) -> Result<(), FigureError>;
}

/// Bitmaps are drawn at this many times their size and averaged down:
/// plotters draws lines without anti-aliasing, this smooths them.
pub(crate) const SUPERSAMPLE: u32 = 2;

/// Render `fig` into an RGB buffer (`width * height * 3` bytes).
pub(crate) fn render_rgb<D: Draw>(fig: &D) -> Result<Vec<u8>, FigureError> {
    font::ensure_registered()?;
    let (w, h) = fig.size();
    let s = SUPERSAMPLE;
    let (bw, bh) = (w * s, h * s);
    let mut big = vec![0u8; bw as usize * bh as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut big, (bw, bh)).into_drawing_area();
        fig.draw(&root, s)?;
        root.present()?;
    }
    Ok(downsample(&big, (w, h), s))
}

/// Average `s` x `s` blocks of an RGB image `s` times the size `(w, h)`.
fn downsample(big: &[u8], (w, h): (u32, u32), s: u32) -> Vec<u8> {
    let (w, h, s) = (w as usize, h as usize, s as usize);
    let bw = w * s;
    let n = (s * s) as u32;
    let mut out = vec![0u8; w * h * 3];
    for y in 0..h {
        for x in 0..w {
            let mut acc = [0u32; 3];
            for dy in 0..s {
                let row = (y * s + dy) * bw;
                for dx in 0..s {
                    let i = (row + x * s + dx) * 3;
                    for c in 0..3 {
                        acc[c] += u32::from(big[i + c]);
                    }
                }
            }
            let o = (y * w + x) * 3;
            for c in 0..3 {
                out[o + c] = ((acc[c] + n / 2) / n) as u8;
            }
        }
    }
    out
}

/// Render `fig` as an SVG document.
pub(crate) fn render_svg<D: Draw>(fig: &D) -> Result<String, FigureError> {
    font::ensure_registered()?;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, fig.size()).into_drawing_area();
        fig.draw(&root, 1)?;
        root.present()?;
    }
    Ok(svg)
}

/// Encode an RGB buffer as PNG (deterministic: no time or text chunks).
pub(crate) fn encode_png(rgb: &[u8], (w, h): (u32, u32)) -> Result<Vec<u8>, FigureError> {
    let enc_err = |e: png::EncodingError| FigureError::Encode(e.to_string());
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Best);
        let mut writer = enc.write_header().map_err(enc_err)?;
        writer.write_image_data(rgb).map_err(enc_err)?;
        writer.finish().map_err(enc_err)?;
    }
    Ok(out)
}

/// Render `fig` to `<stem>.png` and `<stem>.svg`.
pub(crate) fn save<D: Draw>(fig: &D, stem: &Path) -> Result<Output, FigureError> {
    let out = Output::for_stem(stem);
    let png = encode_png(&render_rgb(fig)?, fig.size())?;
    let svg = render_svg(fig)?;
    write_all_atomic(&[(&out.png, &png), (&out.svg, svg.as_bytes())])?;
    Ok(out)
}

/// Render `fig` to the one file `path`, PNG or SVG by its extension.
pub(crate) fn save_one<D: Draw>(fig: &D, path: &Path) -> Result<(), FigureError> {
    let bytes = match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("png") => encode_png(&render_rgb(fig)?, fig.size())?,
        Some(e) if e.eq_ignore_ascii_case("svg") => render_svg(fig)?.into_bytes(),
        _ => {
            return Err(FigureError::Data(format!(
                "{}: the file name must end in .png or .svg",
                path.display()
            )))
        }
    };
    write_all_atomic(&[(path, &bytes)])
}

fn with_suffix(stem: &Path, suffix: &str) -> PathBuf {
    let mut s: OsString = stem.as_os_str().to_owned();
    s.push(suffix);
    PathBuf::from(s)
}

/// Write every `(path, bytes)` pair, or none (see [`crate::atomic`]).
pub(crate) fn write_all_atomic(files: &[(&Path, &[u8])]) -> Result<(), FigureError> {
    crate::atomic::write_all_atomic(files)
        .map_err(|(path, source)| FigureError::Io { path, source })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stem_keeps_its_dots() {
        let o = Output::for_stem(Path::new("out/fig07-d1.5"));
        assert_eq!(o.png, PathBuf::from("out/fig07-d1.5.png"));
        assert_eq!(o.svg, PathBuf::from("out/fig07-d1.5.svg"));
    }

    #[test]
    fn downsample_averages_blocks() {
        // 4x2 image (RGB) to 2x1.
        let big: Vec<u8> = [
            [0, 0, 0],
            [255, 255, 255],
            [10, 20, 30],
            [10, 20, 30],
            [255, 255, 255],
            [0, 0, 0],
            [10, 20, 30],
            [14, 24, 34],
        ]
        .concat();
        assert_eq!(downsample(&big, (2, 1), 2), vec![128, 128, 128, 11, 21, 31]);
    }

    #[test]
    fn error_display_is_one_line() {
        let e = FigureError::Io {
            path: PathBuf::from("/nowhere/x.png"),
            source: io::Error::new(io::ErrorKind::NotFound, "not found"),
        };
        let s = e.to_string();
        assert!(s.contains("/nowhere/x.png") && !s.contains('\n'), "{s}");
    }
}
