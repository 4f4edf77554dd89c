//! Render every kind of figure into a temporary folder and check the files:
//! PNG decodes with the expected size and real content, SVG parses as XML
//! and carries its labels as text, GIF frames, determinism, atomic writes.
//!
//! Set FIGURES_KEEP=<dir> to keep the files there for a look.
// The helpers below are test code too: a failing check is a panic.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    reason = "test code: a failed check panics"
)]

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use figures::*;

/// A fresh folder for one test.
fn scratch(name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let dir = match std::env::var_os("FIGURES_KEEP") {
        Some(d) => PathBuf::from(d).join(format!("{name}-{n}")),
        None => {
            std::env::temp_dir().join(format!("figures-test-{}-{name}-{n}", std::process::id()))
        }
    };
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn done(dir: &Path) {
    if std::env::var_os("FIGURES_KEEP").is_none() {
        let _ = fs::remove_dir_all(dir);
    }
}

struct Png {
    w: u32,
    h: u32,
    rgb: Vec<u8>,
}

impl Png {
    fn read(path: &Path) -> Png {
        let bytes = fs::read(path).unwrap();
        assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "PNG signature");
        let dec = png::Decoder::new(bytes.as_slice());
        let mut reader = dec.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        buf.truncate(info.buffer_size());
        Png {
            w: info.width,
            h: info.height,
            rgb: buf,
        }
    }

    fn pixels(&self) -> impl Iterator<Item = (u8, u8, u8)> + '_ {
        self.rgb.chunks_exact(3).map(|p| (p[0], p[1], p[2]))
    }

    fn distinct(&self) -> usize {
        self.pixels().collect::<BTreeSet<_>>().len()
    }

    fn count(&self, f: impl Fn((u8, u8, u8)) -> bool) -> usize {
        self.pixels().filter(|&p| f(p)).count()
    }
}

fn cyanish(p: (u8, u8, u8)) -> bool {
    p.0 < 70 && p.1 > 190 && p.2 > 230
}
fn magentaish(p: (u8, u8, u8)) -> bool {
    p.0 > 190 && p.1 < 70 && p.2 > 230
}
fn near(c: RGBColor) -> impl Fn((u8, u8, u8)) -> bool {
    move |p| {
        (p.0 as i32 - c.0 as i32).abs() < 12
            && (p.1 as i32 - c.1 as i32).abs() < 12
            && (p.2 as i32 - c.2 as i32).abs() < 12
    }
}

/// All `<text>` contents of an SVG (it must parse as XML).
fn svg_texts(path: &Path) -> Vec<String> {
    let src = fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&src).expect("SVG is well-formed XML");
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap_or("").trim().to_string())
        .collect()
}

fn assert_has_text(texts: &[String], want: &str) {
    assert!(
        texts.iter().any(|t| t == want),
        "no <text>{want}</text> in {texts:?}"
    );
}

/// A chain of `n` rods swinging down from the horizontal, bending as it goes.
fn falling_frames(n: usize, count: usize) -> Vec<(f64, Vec<[f64; 2]>)> {
    let l = 6.0 / n as f64;
    (0..count)
        .map(|k| {
            let t = 5.0 * k as f64 / (count - 1) as f64;
            let s = t / 5.0;
            let mut p = [0.0, 0.0];
            let mut joints = vec![p];
            for i in 0..n {
                let u = i as f64 / n as f64;
                let phi =
                    -std::f64::consts::FRAC_PI_2 * s.powf(1.0 + 2.0 * u) * (1.0 + 0.6 * u * s);
                p = [p[0] + l * phi.cos(), p[1] + l * phi.sin()];
                joints.push(p);
            }
            (t, joints)
        })
        .collect()
}

fn snapshots_fig() -> ChainSnapshots<'static> {
    let mut fig = ChainSnapshots::new(
        "Horizontal chain, n = 25, r = 0",
        falling_frames(25, 40),
        [0.0, 0.0],
    );
    fig.p1 = Some([6.0, 0.0]);
    fig
}

#[test]
fn chain_snapshots_png_and_svg() {
    let dir = scratch("snapshots");
    let out = chain_snapshots(&snapshots_fig(), &dir.join("fig03")).unwrap();
    assert_eq!(out.png, dir.join("fig03.png"));
    let png = Png::read(&out.png);
    assert_eq!(png.h, 900);
    assert!((765..=1800).contains(&png.w), "width {}", png.w);
    assert!(png.distinct() > 100, "only {} colours", png.distinct());
    assert!(png.count(cyanish) > 200, "no cyan early frames");
    assert!(png.count(magentaish) > 200, "no magenta late frames");
    assert!(png.count(near(P0_RED)) > 100, "no red P0");
    assert!(png.count(near(P1_BLUE)) > 100, "no blue P1");
    // White background dominates; it is a plot, not a filled block.
    let white = png.count(|p| p == (255, 255, 255));
    assert!(white > (png.w * png.h / 2) as usize);

    let texts = svg_texts(&out.svg);
    for want in ["x", "y", "t", "P₀", "P₁", "Horizontal chain, n = 25, r = 0"] {
        assert_has_text(&texts, want);
    }
    done(&dir);
}

#[test]
fn snapshots_have_equal_axis_scales() {
    // A wide scene makes a wide canvas; a tall scene, a narrow one.
    let dir = scratch("aspect");
    let wide = chain_snapshots(&snapshots_fig(), &dir.join("wide")).unwrap();
    let frames: Vec<(f64, Vec<[f64; 2]>)> = (0..5)
        .map(|k| {
            let x = 0.02 * k as f64;
            (k as f64, (0..=50).map(|j| [x, -0.1 * j as f64]).collect())
        })
        .collect();
    let tall = chain_snapshots(
        &ChainSnapshots::new("", frames, [0.0, 0.0]),
        &dir.join("tall"),
    )
    .unwrap();
    let (w1, w2) = (Png::read(&wide.png).w, Png::read(&tall.png).w);
    assert!(w1 > w2, "wide {w1} vs tall {w2}");
    done(&dir);
}

#[test]
fn folded_scene_with_fixed_x_range() {
    // Report Fig. 12: a narrow scene, x range about +-0.25, scales not equal.
    let dir = scratch("folded");
    let frames: Vec<(f64, Vec<[f64; 2]>)> = (0..30)
        .map(|k| {
            let t = k as f64 * 0.15;
            let pts = (0..=50)
                .map(|j| {
                    let s = j as f64 / 50.0;
                    // Wiggles grow with time and overshoot the x range.
                    [
                        0.05 + 0.4 * t / 4.5 * (12.0 * s + t).sin(),
                        -6.0 * s * (1.0 - s) * 2.0,
                    ]
                })
                .collect();
            (t, pts)
        })
        .collect();
    let mut fig = ChainSnapshots::new("Folded chain, n = 50", frames, [0.0, 0.0]);
    fig.p1 = Some([0.1, 0.0]);
    fig.x_range = Some((-0.25, 0.25));
    fig.equal_aspect = false;
    let out = chain_snapshots(&fig, &dir.join("fig12")).unwrap();
    let png = Png::read(&out.png);
    assert_eq!((png.w, png.h), (1200, 900));
    // Clipped to the plot: the left margin (tick labels, no data) holds no
    // chain colours.
    let mut stray = 0;
    for y in 0..png.h as usize {
        for x in 0..60 {
            let i = (y * png.w as usize + x) * 3;
            let p = (png.rgb[i], png.rgb[i + 1], png.rgb[i + 2]);
            if p.2 > 200 && (p.0 < 150 || p.1 < 150) {
                stray += 1;
            }
        }
    }
    assert_eq!(stray, 0);
    assert_has_text(&svg_texts(&out.svg), "−0.2");
    done(&dir);
}

#[test]
fn colored_curves_with_markers() {
    let dir = scratch("curves");
    let curves: Vec<(f64, Vec<(f64, f64)>)> = (0..30)
        .map(|k| {
            let big_l = 6.0 + 6.0 * k as f64 / 29.0;
            let sag = 0.8 * (big_l - 5.0);
            let pts = (0..=60)
                .map(|i| {
                    let x = 5.0 * i as f64 / 60.0;
                    (x, 0.2 * x - sag * (1.0 - ((x - 2.5) / 2.5).powi(2)))
                })
                .collect();
            (big_l, pts)
        })
        .collect();
    let markers = curves
        .iter()
        .map(|c| *c.1.iter().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap())
        .collect();
    let mut fig = ColoredCurves::new("Catenaries from P₀ to P₁", curves, [0.0, 0.0]);
    fig.p1 = Some([5.0, 1.0]);
    fig.markers = markers;
    fig.markers_label = "lowest point";
    fig.colorbar_label = "L";
    let out = colored_curves(&fig, &dir.join("fig02")).unwrap();
    let png = Png::read(&out.png);
    assert_eq!(png.h, 900);
    assert!(png.count(magentaish) > 200 && png.count(cyanish) > 200);
    assert!(png.count(|p| p == (0, 0, 0)) > 300, "black markers");
    let texts = svg_texts(&out.svg);
    for want in ["L", "lowest point", "P₁", "12"] {
        assert_has_text(&texts, want);
    }
    done(&dir);
}

fn wp_plot() -> LinePlot<'static> {
    let mut p = LinePlot::new(
        "Work-precision, span d = 3",
        "wall time [s]",
        "error at t_end",
    );
    p.log_x = true;
    p.log_y = true;
    let mk = |a: f64, order: f64| -> Vec<(f64, f64)> {
        (0..8)
            .map(|i| {
                let cost = 10f64.powf(-3.0 + 0.4 * i as f64);
                (cost, a * cost.powf(-order))
            })
            .collect()
    };
    p.series = vec![
        Series::new("RK4", mk(1e-9, 4.0), Style::LinePoints),
        Series::new("DOPRI5", mk(1e-10, 5.0), Style::LinePoints),
        Series::new("BDF", mk(1e-5, 2.0), Style::Dashed),
        // Zeros and NaN cannot be shown on a log axis: they break the line.
        Series::points(
            "reference",
            vec![(1e-2, 0.0), (1e-1, 1e-6), (f64::NAN, 1.0)],
        ),
    ];
    p.annotations = vec!["fitted order: 4.02".into(), "slope ≈ −4".into()];
    p
}

#[test]
fn line_plot_log_axes() {
    let dir = scratch("lines");
    let out = line_plot(&wp_plot(), &dir.join("wp")).unwrap();
    let png = Png::read(&out.png);
    assert_eq!((png.w, png.h), LINE_PLOT_SIZE);
    assert!(png.count(near(palette(0))) > 300, "RK4 line");
    assert!(png.count(near(palette(2))) > 200, "BDF dashes");
    let texts = svg_texts(&out.svg);
    for want in [
        "RK4",
        "DOPRI5",
        "BDF",
        "fitted order: 4.02",
        "wall time [s]",
        "10⁻²",
        "10⁰",
    ] {
        assert_has_text(&texts, want);
    }
    // Every tick label on a log axis is a power of ten.
    let numeric: Vec<&String> = texts.iter().filter(|t| t.starts_with("10")).collect();
    assert!(numeric.len() >= 6, "{texts:?}");
    done(&dir);
}

#[test]
fn line_plot_linear_equal_aspect_and_pair() {
    let dir = scratch("pair");
    let mut left = LinePlot::new("tip velocity", "vₓ", "v_y");
    left.equal_aspect = true;
    left.series = (0..4)
        .map(|k| {
            let r = 1.0 + 0.5 * k as f64;
            let pts = (0..200)
                .map(|i| {
                    let a = i as f64 / 199.0 * 5.0;
                    (-r * a.sin() * 0.4, -r * (1.0 - a.cos()) * 0.6)
                })
                .collect();
            Series::line(format!("d = {}", 2 * k + 1), pts).with_color(cool(k as f64 / 3.0))
        })
        .collect();
    let out = line_plot(&left, &dir.join("phase")).unwrap();
    assert_eq!(Png::read(&out.png).w, LINE_PLOT_SIZE.0);
    assert_has_text(&svg_texts(&out.svg), "d = 7");

    let mut right = wp_plot();
    right.title = "error vs RHS evaluations";
    right.x_label = "RHS evaluations";
    let pair = line_plot_pair(&wp_plot(), &right, "Work-precision", &dir.join("pair")).unwrap();
    let png = Png::read(&pair.png);
    assert_eq!((png.w, png.h), PAIR_SIZE);
    let texts = svg_texts(&pair.svg);
    assert_has_text(&texts, "Work-precision");
    assert_has_text(&texts, "RHS evaluations");
    done(&dir);
}

/// A plot whose legend and note box are each wider than half the plot.
fn wide_boxes_plot(series: Vec<Series>) -> LinePlot<'static> {
    let mut p = LinePlot::new("Wide legend and note", "x", "y");
    p.series = series;
    p.annotations = vec![
        "fitted order 4.02 over the three finest tolerances".into(),
        "reference: DOPRI5 at rtol 1e-13".into(),
    ];
    p
}

fn assert_apart(b: &LinePlotBoxes) -> (PixelRect, PixelRect) {
    let (legend, note) = (b.legend.expect("a legend"), b.note.expect("a note"));
    assert!(
        !legend.overlaps(&note),
        "note {note:?} on legend {legend:?}"
    );
    assert!(legend.inside(b.plot) && note.inside(b.plot), "{b:?}");
    (legend, note)
}

#[test]
fn note_box_never_covers_the_legend() {
    // Data across the lower part: both upper corners are free, but the
    // legend and the note are too wide to sit side by side there.
    let bottom: Vec<(f64, f64)> = (0..=50).map(|i| (i as f64 / 50.0, 0.1)).collect();
    let mut p = wide_boxes_plot(vec![
        Series::line("DOPRI5 (rtol 1e-3 … 1e-12), adaptive steps", bottom.clone()),
        Series::points("RK4 (dt 3e-5 … 2e-2), fixed steps", bottom),
    ]);
    p.y_range = Some((0.0, 1.0));
    let b = line_plot_boxes(&p).unwrap();
    let (legend, note) = assert_apart(&b);
    let widths = (legend.x1 - legend.x0) + (note.x1 - note.x0);
    assert!(widths > b.plot.0, "the two would fit side by side: {b:?}");
    assert_eq!(b.hidden, 0, "{b:?}");

    let dir = scratch("note");
    let out = line_plot(&p, &dir.join("note")).unwrap();
    assert_has_text(&svg_texts(&out.svg), "reference: DOPRI5 at rtol 1e-13");
    done(&dir);
}

#[test]
fn legend_and_note_share_the_one_free_corner() {
    // The data runs down the left edge and along the bottom: only the upper
    // right corner is free, so the note goes under the legend there.
    let mut edge: Vec<(f64, f64)> = (0..=20).map(|i| (0.0, 1.0 - i as f64 / 20.0)).collect();
    edge.extend((1..=20).map(|i| (i as f64 / 20.0, 0.0)));
    let mut p = wide_boxes_plot(vec![Series::line("along the edges", edge)]);
    p.annotations.truncate(1);
    p.y_range = Some((-0.05, 1.05));
    p.x_range = Some((-0.05, 1.05));
    let b = line_plot_boxes(&p).unwrap();
    let (legend, note) = assert_apart(&b);
    assert_eq!(b.hidden, 0, "{b:?}");
    // Both in the upper right, the note under the legend.
    assert!(legend.x1 > b.plot.0 / 2 && note.x1 > b.plot.0 / 2, "{b:?}");
    assert!(note.y0 >= legend.y1 && note.y1 < b.plot.1 / 2, "{b:?}");
}

/// Lines filling the whole plot: a legend anywhere inside would cover them.
fn filled(n: usize) -> Vec<Series> {
    (0..n)
        .map(|k| {
            let y = k as f64 / (n - 1) as f64;
            // Dashed past the palette's ten colours: one swatch, one meaning.
            let style = if k < 10 { Style::Line } else { Style::Dashed };
            Series::new(
                format!("level {k}"),
                (0..=40).map(|i| (i as f64 / 40.0, y)).collect(),
                style,
            )
        })
        .collect()
}

#[test]
fn a_legend_that_would_hide_data_goes_beside_the_plot_and_the_axes_stay_fitted() {
    let dir = scratch("beside");
    let mut p = LinePlot::new("Beside", "x", "y");
    p.series = filled(12);
    p.annotations = vec!["a note beside the legend".into()];
    let b = line_plot_boxes(&p).unwrap();
    let (legend, note) = (b.legend.unwrap(), b.note.unwrap());
    assert_eq!(b.hidden, 0, "{b:?}");
    for r in [legend, note] {
        assert!(
            r.x0 >= b.plot.0 || r.y0 >= b.plot.1,
            "a box inside the plot over its data: {b:?}"
        );
    }
    assert!(!legend.overlaps(&note), "{b:?}");
    let out = line_plot(&p, &dir.join("single")).unwrap();
    assert_eq!(out.problems(), Vec::<String>::new());
    let (fx, fy) = out.panels[0].fill();
    assert!(
        fx > 0.85 && fy > 0.85,
        "the axes grew past the data: {fx} {fy}"
    );
    // The same in a narrow panel of a pair.
    let out = line_plot_pair(&p, &p, "pair", &dir.join("pair")).unwrap();
    assert_eq!(out.problems(), Vec::<String>::new());
    assert_has_text(&svg_texts(&out.svg), "level 11");
    done(&dir);
}

#[test]
fn a_range_wider_than_its_data_and_a_box_over_data_are_reported() {
    let dir = scratch("report");
    let mut p = LinePlot::new("Too wide", "x", "y");
    p.series = vec![Series::line("data", vec![(0.0, 1.0), (1.0, 2.0)])];
    p.x_range = Some((0.0, 10.0));
    let out = line_plot(&p, &dir.join("wide")).unwrap();
    let problems = out.problems();
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(problems[0].contains("x axis"), "{problems:?}");
    // Decades on a log axis: data over two of eight.
    p.log_y = true;
    p.x_range = None;
    p.y_range = Some((1e-4, 1e4));
    p.series = vec![Series::line("data", vec![(0.0, 1.0), (1.0, 100.0)])];
    let out = line_plot(&p, &dir.join("decades")).unwrap();
    assert!(
        out.problems()[0].contains("y axis (decades)"),
        "{:?}",
        out.problems()
    );
    // Data within a decade fill a log axis of their own.
    p.y_range = None;
    p.series = vec![Series::line("data", vec![(0.0, 1.4), (1.0, 3.5)])];
    let out = line_plot(&p, &dir.join("within")).unwrap();
    assert_eq!(out.problems(), Vec::<String>::new());
    // A box over data, as a layout would report it.
    let mut panel = out.panels[0].clone();
    panel.hidden = 3;
    assert_eq!(
        panel.problems(),
        vec!["the legend or note covers 3 data samples".to_string()]
    );
    done(&dir);
}

#[test]
fn marks_are_drawn_over_every_line_and_hollow_ones_show_what_is_under_them() {
    let dir = scratch("marks");
    let mut p = LinePlot::new("Marks", "x", "y");
    let pts: Vec<(f64, f64)> = (0..5).map(|i| (f64::from(i), f64::from(i))).collect();
    p.series = vec![
        Series::points("under", pts.clone()).with_color(RGBColor(200, 0, 0)),
        Series::new("hollow squares", pts.clone(), Style::DashedPoints)
            .with_color(RGBColor(0, 0, 200))
            .with_marker(Marker::Square)
            .hollow(),
        Series::line("a line over both", pts).with_color(RGBColor(0, 160, 0)),
    ];
    let out = line_plot(&p, &dir.join("marks")).unwrap();
    let png = Png::read(&out.png);
    // The red marks lie under the line and the hollow squares, yet show.
    assert!(
        png.count(near(RGBColor(200, 0, 0))) > 200,
        "red marks hidden"
    );
    assert!(
        png.count(near(RGBColor(0, 0, 200))) > 200,
        "blue outlines hidden"
    );
    done(&dir);
}

#[test]
fn category_map_cells_and_legend() {
    let dir = scratch("category");
    let cats = vec![
        ("completed".to_string(), RGBColor(90, 170, 90)),
        ("energy error > 1%".to_string(), RGBColor(240, 190, 60)),
        ("diverged".to_string(), RGBColor(200, 50, 50)),
    ];
    let panel = |title: &str, shift: usize| CategoryPanel {
        title: title.to_string(),
        row_labels: vec!["RK4".into(), "DOPRI5".into(), "BDF".into()],
        col_labels: (0..6).map(|i| format!("10⁻{}", i + 2)).collect(),
        cells: (0..3)
            .map(|r| {
                (0..6)
                    .map(|c| {
                        if r == 2 && c == 0 {
                            None
                        } else {
                            Some((r + c + shift) % 3)
                        }
                    })
                    .collect()
            })
            .collect(),
        cell_text: Vec::new(),
    };
    // Long column labels are written vertically.
    let mut wide = panel("n = 800", 2);
    wide.col_labels = (0..6)
        .map(|i| format!("dt = {:.4}", 0.04 / f64::from(1 << i)))
        .collect();
    wide.cell_text = wide
        .cells
        .iter()
        .map(|r| {
            r.iter()
                .map(|c| c.map_or(String::new(), |k| format!("{k}")))
                .collect()
        })
        .collect();
    let map = CategoryMap {
        title: "Where each method fails",
        x_label: "step size dt (RK4) / tolerance (DOPRI5, BDF)",
        y_label: "method",
        categories: cats.clone(),
        panels: vec![panel("span d = 3", 0), panel("folded", 1), wide],
    };
    let out = category_map(&map, &dir.join("stability")).unwrap();
    let png = Png::read(&out.png);
    for (label, c) in &cats {
        assert!(
            png.count(|p| p == (c.0, c.1, c.2)) > 2000,
            "cells of {label}"
        );
    }
    let texts = svg_texts(&out.svg);
    for want in [
        "completed",
        "diverged",
        "not run",
        "folded",
        "RK4",
        "10⁻4",
        "dt = 0.0050",
        "method",
    ] {
        assert_has_text(&texts, want);
    }

    // Cells naming an unknown category are refused, and nothing is written.
    let mut bad = map.clone();
    bad.panels[0].cells[0][0] = Some(7);
    let err = category_map(&bad, &dir.join("bad")).unwrap_err();
    assert!(matches!(err, FigureError::Data(_)), "{err}");
    assert!(!dir.join("bad.png").exists());
    done(&dir);
}

#[test]
fn sketch_draws_the_problem() {
    let dir = scratch("sketch");
    let out = sketch(&dir.join("fig01")).unwrap();
    let png = Png::read(&out.png);
    assert_eq!((png.w, png.h), SKETCH_SIZE);
    assert!(png.count(near(P0_RED)) > 200);
    assert!(png.count(near(P1_BLUE)) > 200);
    let texts = svg_texts(&out.svg);
    for want in ["d", "h", "g", "P₀, fixed"] {
        assert_has_text(&texts, want);
    }
    done(&dir);
}

#[test]
fn animation_is_a_gif_with_every_frame() {
    let dir = scratch("anim");
    let mut fig = snapshots_fig();
    fig.frames.truncate(3);
    let path = dir.join("fig03.gif");
    chain_animation(&fig, &path, 10).unwrap();
    let bytes = fs::read(&path).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut dec = opts.read_info(bytes.as_slice()).unwrap();
    assert_eq!(dec.height(), ANIMATION_HEIGHT as u16);
    let mut frames = 0;
    let mut magenta_last = false;
    while let Some(f) = dec.read_next_frame().unwrap() {
        frames += 1;
        assert_eq!(f.delay, 10);
        magenta_last = f
            .buffer
            .chunks_exact(4)
            .filter(|p| magentaish((p[0], p[1], p[2])))
            .count()
            > 100;
    }
    assert_eq!(frames, 3);
    assert!(magenta_last, "last frame shows the chain in magenta");
    done(&dir);
}

#[test]
fn rendering_is_deterministic() {
    let dir = scratch("determinism");
    let a = chain_snapshots(&snapshots_fig(), &dir.join("a")).unwrap();
    let b = chain_snapshots(&snapshots_fig(), &dir.join("b")).unwrap();
    assert_eq!(fs::read(&a.png).unwrap(), fs::read(&b.png).unwrap());
    assert_eq!(fs::read(&a.svg).unwrap(), fs::read(&b.svg).unwrap());
    let c = line_plot(&wp_plot(), &dir.join("c")).unwrap();
    let d = line_plot(&wp_plot(), &dir.join("d")).unwrap();
    assert_eq!(fs::read(&c.png).unwrap(), fs::read(&d.png).unwrap());
    assert_eq!(fs::read(&c.svg).unwrap(), fs::read(&d.svg).unwrap());
    let mut fig = snapshots_fig();
    fig.frames.truncate(2);
    chain_animation(&fig, &dir.join("e.gif"), 5).unwrap();
    chain_animation(&fig, &dir.join("f.gif"), 5).unwrap();
    assert_eq!(
        fs::read(dir.join("e.gif")).unwrap(),
        fs::read(dir.join("f.gif")).unwrap()
    );
    done(&dir);
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn failed_writes_leave_no_file() {
    let dir = scratch("atomic");
    // A folder that does not exist.
    let missing = dir.join("no-such-dir").join("fig");
    let err = chain_snapshots(&snapshots_fig(), &missing).unwrap_err();
    assert!(matches!(err, FigureError::Io { .. }), "{err}");
    assert!(!err.to_string().contains('\n'));
    let err = chain_animation(&snapshots_fig(), &dir.join("no-such-dir/a.gif"), 10).unwrap_err();
    assert!(matches!(err, FigureError::Io { .. }), "{err}");
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));

    // The PNG could be written but the SVG cannot (a folder is in its
    // place): neither file nor any temporary is left.
    fs::create_dir(dir.join("fig.svg")).unwrap();
    let err = line_plot(&wp_plot(), &dir.join("fig")).unwrap_err();
    assert!(matches!(err, FigureError::Io { .. }), "{err}");
    assert_eq!(files_in(&dir), vec!["fig.svg".to_string()]);
    done(&dir);
}

#[test]
fn empty_data_is_an_error() {
    let dir = scratch("empty");
    let fig = ChainSnapshots::new("nothing", Vec::new(), [0.0, 0.0]);
    assert!(matches!(
        chain_snapshots(&fig, &dir.join("x")),
        Err(FigureError::Data(_))
    ));
    assert!(files_in(&dir).is_empty());
    // A plot without series is an empty frame, not an error.
    let out = line_plot(&LinePlot::new("empty", "x", "y"), &dir.join("empty")).unwrap();
    assert_eq!(Png::read(&out.png).w, LINE_PLOT_SIZE.0);
    done(&dir);
}

/// One swatch for two meanings in a legend, and an axis name shrunk below
/// [`MIN_NAME_SHARE`] to fit its side, are reported (issue 51: cayley-top's
/// grey dashed "free fall" and "standard errors", its 45% y name); the
/// same swatch for one meaning, or a distinct swatch, is not.
#[test]
fn one_swatch_for_two_meanings_and_a_shrunk_axis_name_are_reported() {
    let dir = scratch("swatch");
    let grey = RGBColor(127, 127, 127);
    let mut p = LinePlot::new("Swatches", "x", "y");
    p.series = vec![
        Series::new("free fall: 1", vec![(0.0, 1.0), (1.0, 1.0)], Style::Dashed).with_color(grey),
        Series::new("data", vec![(0.0, 0.0), (1.0, 2.0)], Style::Line),
        Series::legend_only("dashed: +- 2 standard errors", Style::Dashed).with_color(grey),
    ];
    let out = line_plot(&p, &dir.join("two")).unwrap();
    let problems = out.problems();
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(problems[0].contains("two meanings"), "{problems:?}");
    // A distinct swatch (solid black) for the reference line: nothing.
    p.series[0] = p.series[0].clone().with_color(RGBColor(0, 0, 0));
    p.series[0].style = Style::Line;
    let out = line_plot(&p, &dir.join("one")).unwrap();
    assert_eq!(out.problems(), Vec::<String>::new());
    // A y name far longer than the plot is tall.
    let long = "a very long axis name that says everything about its axis, twice over, \
                and once more for good measure";
    p.y_label = long;
    let out = line_plot(&p, &dir.join("long")).unwrap();
    let problems = out.problems();
    assert!(
        problems.iter().any(|e| e.contains("axis name set at")),
        "{problems:?}"
    );
    assert!(out.panels[0].axis_names < MIN_NAME_SHARE);
    done(&dir);
}
