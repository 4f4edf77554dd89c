//! Animated GIF of the chain: fixed axes (those of the snapshot figure),
//! the current chain in its time colour, the path of the free end so far,
//! the time in the title and on the colour bar.

use std::path::Path;

use crate::curve_layout::Geometry;
use crate::curves::{Current, Drawing};
use crate::font;
use crate::output;
use crate::sizes::Sizes;
use crate::snapshots::ChainSnapshots;
use crate::FigureError;

/// Height of the animation's frames in pixels (the width follows the data).
pub const ANIMATION_HEIGHT: u32 = 600;

/// Write an animated GIF of `fig`'s frames (in time order) to `path`,
/// `fps` frames per second, looping.
pub fn chain_animation(fig: &ChainSnapshots, path: &Path, fps: u32) -> Result<(), FigureError> {
    font::ensure_registered()?;
    if fig.frames.is_empty() {
        return Err(FigureError::Data("no frame to animate".into()));
    }
    let spec = fig.spec();
    let geom = Geometry::new(&spec, ANIMATION_HEIGHT, Sizes { scale: 0.7 })?;
    let (w, h) = geom.size;
    let (w16, h16) = match (u16::try_from(w), u16::try_from(h)) {
        (Ok(a), Ok(b)) => (a, b),
        _ => {
            return Err(FigureError::Data(format!(
                "frame {w}x{h} too large for GIF"
            )))
        }
    };
    // GIF delays are in hundredths of a second.
    let delay = (100.0 / f64::from(fps.max(1))).round().clamp(2.0, 65535.0) as u16;
    let enc_err = |e: gif::EncodingError| FigureError::Encode(e.to_string());
    let mut bytes = Vec::new();
    {
        let mut enc = gif::Encoder::new(&mut bytes, w16, h16, &[]).map_err(enc_err)?;
        enc.set_repeat(gif::Repeat::Infinite).map_err(enc_err)?;
        for index in 0..spec.curves.len() {
            let rgb = output::render_rgb(&Drawing {
                spec: &spec,
                geom: &geom,
                current: Some(Current { index }),
            })?;
            let mut frame = gif::Frame::from_rgb_speed(w16, h16, &rgb, 10);
            frame.delay = delay;
            enc.write_frame(&frame).map_err(enc_err)?;
        }
    }
    output::write_all_atomic(&[(path, &bytes)])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frames() -> Vec<(f64, Vec<[f64; 2]>)> {
        (0..4)
            .map(|k| {
                let a = -0.5 * k as f64;
                let r = (0..=10)
                    .map(|j| [0.6 * j as f64 * a.cos(), 0.6 * j as f64 * a.sin()])
                    .collect();
                (k as f64, r)
            })
            .collect()
    }

    #[test]
    fn frames_share_axes_and_differ() {
        let mut fig = ChainSnapshots::new("swing", frames(), [0.0, 0.0]);
        fig.p1 = Some([6.0, 0.0]);
        let spec = fig.spec();
        let geom = Geometry::new(&spec, ANIMATION_HEIGHT, Sizes { scale: 0.7 }).unwrap();
        let render = |index| {
            output::render_rgb(&Drawing {
                spec: &spec,
                geom: &geom,
                current: Some(Current { index }),
            })
            .unwrap()
        };
        let (a, b) = (render(0), render(3));
        assert_eq!(a.len(), b.len());
        assert_ne!(a, b);
        if let Some(dir) = std::env::var_os("FIGURES_KEEP") {
            let png = output::encode_png(&b, geom.size).unwrap();
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(std::path::Path::new(&dir).join("anim-frame.png"), png).unwrap();
        }
    }
}
