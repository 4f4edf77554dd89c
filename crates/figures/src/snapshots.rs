//! Chain snapshots coloured by time (report Figs. 3-7, 10, 12).

use std::path::Path;

use crate::curves::{self, Spec};
use crate::{FigureError, Output};

/// Snapshots of the chain: one polyline of joint positions per time.
#[derive(Debug, Clone)]
pub struct ChainSnapshots<'a> {
    pub title: &'a str,
    /// `(t, joint positions r_0..r_n)`, in any order (drawn by increasing t).
    pub frames: Vec<(f64, Vec<[f64; 2]>)>,
    pub p0: [f64; 2],
    pub p1: Option<[f64; 2]>,
    /// Fixed ranges; `None` fits the data (with equal scales, the shorter
    /// range is widened).
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    /// Same units per pixel on x and y (default). Turn off for a narrow
    /// scene such as the folded chain, with `x_range` set.
    pub equal_aspect: bool,
    /// Label of the colour bar (default "t").
    pub colorbar_label: &'a str,
    /// Legend name of `p1` (default "P₁").
    pub p1_label: &'a str,
    /// Label of the x axis (default "x").
    pub x_label: &'a str,
    /// Labelled x ticks `(x, label)` in place of the numbers (without
    /// equal scales): snapshots drawn side by side, each tick under one
    /// and labelled by its time.
    pub x_ticks: Option<Vec<(f64, String)>>,
}

impl<'a> ChainSnapshots<'a> {
    /// Equal scales, colour bar labelled "t", ranges fitted, no P1.
    pub fn new(title: &'a str, frames: Vec<(f64, Vec<[f64; 2]>)>, p0: [f64; 2]) -> Self {
        ChainSnapshots {
            title,
            frames,
            p0,
            p1: None,
            x_range: None,
            y_range: None,
            equal_aspect: true,
            colorbar_label: "t",
            p1_label: "P₁",
            x_label: "x",
            x_ticks: None,
        }
    }

    pub(crate) fn spec(&self) -> Spec<'a> {
        let mut spec = Spec {
            title: self.title,
            curves: self
                .frames
                .iter()
                .map(|(t, r)| (*t, r.iter().map(|p| (p[0], p[1])).collect()))
                .collect(),
            markers: Vec::new(),
            markers_label: "",
            p0: (self.p0[0], self.p0[1]),
            p1: self.p1.map(|p| (p[0], p[1])),
            p1_label: self.p1_label,
            cbar_label: self.colorbar_label,
            x_label: self.x_label,
            y_label: "y",
            equal_aspect: self.equal_aspect,
            x_range: self.x_range,
            y_range: self.y_range,
            x_ticks: self.x_ticks.clone(),
        };
        spec.sort();
        spec
    }
}

/// Draw every snapshot, coloured cyan (first) to magenta (last), with a
/// colour bar, P0 red and P1 blue, to `<stem>.png` and `<stem>.svg`.
pub fn chain_snapshots(fig: &ChainSnapshots, stem: &Path) -> Result<Output, FigureError> {
    if fig.frames.is_empty() {
        return Err(FigureError::Data("no frame to draw".into()));
    }
    curves::render_static(fig.spec(), stem)
}

/// As [`chain_snapshots`], to the one file `path` (`.png` or `.svg`).
pub fn chain_snapshots_to(fig: &ChainSnapshots, path: &Path) -> Result<(), FigureError> {
    if fig.frames.is_empty() {
        return Err(FigureError::Data("no frame to draw".into()));
    }
    curves::render_static_to(fig.spec(), path)
}
