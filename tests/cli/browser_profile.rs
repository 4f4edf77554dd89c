//! `view`'s page for chains of unequal rods (issue 18's per-rod profiles:
//! `chain.rod_lengths`, `chain.rod_masses`, `chain.taper`) and for a
//! moving pivot, in headless Chromium (see `browser.rs`): the joints are
//! built from each rod's own length, so the drawn tip is the trajectory's
//! tip in every frame; a taper is drawn thicker where the chain is
//! heavier; the pivot is drawn where it is in the frame shown.

use std::path::Path;

use browser::Browser;

use crate::browser::{inked, no_errors, open, page, pixels};
use crate::common::{run, scene, scratch};

/// The rows `(t, tip_x, tip_y)` of a `simulate --out` CSV.
fn csv_tips(csv: &Path) -> Vec<[f64; 3]> {
    std::fs::read_to_string(csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|line| {
            let c: Vec<f64> = line
                .split(',')
                .take(3)
                .map(|x| x.parse().unwrap())
                .collect();
            [c[0], c[1], c[2]]
        })
        .collect()
}

fn pair(b: &mut Browser, js: &str) -> [f64; 2] {
    let v = b.eval(js).unwrap();
    [v[0].as_f64().unwrap(), v[1].as_f64().unwrap()]
}

#[test]
fn unequal_rods_are_drawn_to_their_lengths_in_every_frame() {
    let dir = scratch("browser-rod-lengths");
    // Ten rods from 4:1 long at the ends to short in the middle, released
    // from the catenary of span 3: drawn as equal rods, the tip would miss
    // P1 by a rod and more.
    let set = [
        "--set",
        "chain.links=10",
        "--set",
        "chain.rod_lengths=[4, 3, 2, 1, 1, 1, 1, 2, 3, 4]",
        "--set",
        "chain.rod_masses=[1, 1, 2, 2, 3, 3, 2, 2, 1, 1]",
        "--set",
        "run.t_end=2",
    ];
    let csv = dir.join("run.csv");
    let span = scene("span-d3");
    let mut args = vec!["simulate", span.as_str()];
    args.extend_from_slice(&set);
    args.extend_from_slice(&["--out", csv.to_str().unwrap()]);
    let o = run(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let tips = csv_tips(&csv);
    let mut args = vec![span.as_str()];
    args.extend_from_slice(&set);
    let page = page(&dir, "rods.html", &args, 0);
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    no_errors(&mut b);
    let frames = b.eval("fallingChain.frames").unwrap().as_u64().unwrap() as usize;
    assert_eq!(frames, tips.len());
    for (k, [t, x, y]) in tips.iter().copied().enumerate() {
        b.eval(&format!("fallingChain.seek({k}); 0")).unwrap();
        let shown = b.eval("fallingChain.time()").unwrap().as_f64().unwrap();
        assert!((shown - t).abs() <= 1e-12 * t.max(1.0), "{shown} vs {t}");
        let tip = pair(&mut b, "fallingChain.drawnTip(0)");
        // Angles to 6 decimals and lengths to 7 digits: L 1e-6 at most.
        assert!(
            (tip[0] - x).hypot(tip[1] - y) < 6e-6,
            "frame {k}: drawn tip {tip:?}, trajectory's ({x}, {y})"
        );
        let pivot = pair(&mut b, "fallingChain.drawnPivot(0)");
        assert_eq!(pivot, [0.0, 0.0], "frame {k}");
    }
    no_errors(&mut b);
}

/// Inked pixels on the normal through the midpoint of rod `j` of run 0,
/// within 9 px of it: the drawn line's width, give or take antialiasing.
fn width_across(b: &mut Browser, px: &[u8], j: usize) -> usize {
    let at = b
        .eval(&format!(
            "(() => {{ const p = fallingChain.joint(0, {j}), q = fallingChain.joint(0, {}); \
             const a = fallingChain.toPixel(p[0], p[1]), c = fallingChain.toPixel(q[0], q[1]); \
             return [(a[0] + c[0]) / 2, (a[1] + c[1]) / 2, c[0] - a[0], c[1] - a[1]]; }})()",
            j + 1
        ))
        .unwrap();
    let v: Vec<f64> = (0..4).map(|k| at[k].as_f64().unwrap()).collect();
    let len = v[2].hypot(v[3]);
    let normal = [-v[3] / len, v[2] / len];
    let mut seen = std::collections::BTreeSet::new();
    for step in -36..=36 {
        let s = f64::from(step) / 4.0;
        seen.insert((
            (v[0] + s * normal[0]).round() as usize,
            (v[1] + s * normal[1]).round() as usize,
        ));
    }
    seen.retain(|&(x, y)| inked(&px[4 * (y * 640 + x)..4 * (y * 640 + x) + 4]) == 1);
    seen.len()
}

#[test]
fn a_taper_is_drawn_thicker_where_the_chain_is_heavier() {
    let dir = scratch("browser-taper");
    let page = page(
        &dir,
        "taper.html",
        &[
            &scene("tapered-whip"),
            "--set",
            "chain.links=8",
            "--set",
            "run.t_end=0.5",
        ],
        0,
    );
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    no_errors(&mut b);
    let data = crate::view::page_data(&page);
    let density: Vec<f64> = data["runs"][0]["density"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // Taper 10 on 8 rods: the mass per length at the rods' midpoints,
    // 10 - 9 (i + 1/2) / 8, over its mean 5.5.
    for (i, d) in density.iter().enumerate() {
        let want = (10.0 - 9.0 * (i as f64 + 0.5) / 8.0) / 5.5;
        assert!((d - want).abs() <= 5e-3 * want, "rod {i}: {d} vs {want}");
    }
    let px = pixels(&mut b);
    let (first, last) = (width_across(&mut b, &px, 0), width_across(&mut b, &px, 7));
    // Widths 3 sqrt(rho): 3.9 and 1.6 px.
    assert!(
        first >= last + 2,
        "first rod {first} px, last rod {last} px"
    );
    no_errors(&mut b);
}

#[test]
fn a_moving_pivot_is_drawn_where_it_is() {
    let dir = scratch("browser-pivot");
    let page = page(
        &dir,
        "pivot.html",
        &[&scene("jerked-support"), "--set", "run.t_end=1"],
        0,
    );
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    let data = crate::view::page_data(&page);
    let pivot: Vec<f64> = data["runs"][0]["pivot"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // After the jerk (tau = 0.4) the pivot rests at P0 + D = (-1.5, 0.5).
    let last = pivot.len() / 2 - 1;
    assert!((pivot[2 * last] + 1.5).abs() < 1e-12 && (pivot[2 * last + 1] - 0.5).abs() < 1e-12);
    b.eval("fallingChain.seek(fallingChain.frames - 1); 0")
        .unwrap();
    assert_eq!(pair(&mut b, "fallingChain.drawnPivot(0)"), [-1.5, 0.5]);
    // The black square is there, and not at the start's P0.
    let px = pixels(&mut b);
    let black = |b: &mut Browser, p: [f64; 2]| {
        let at = pair(b, &format!("fallingChain.toPixel({}, {})", p[0], p[1]));
        let (x, y) = (at[0].round() as usize, at[1].round() as usize);
        px[4 * (y * 640 + x)..4 * (y * 640 + x) + 3]
            .iter()
            .all(|&c| c < 40)
    };
    assert!(black(&mut b, [-1.5, 0.5]), "no pivot drawn at P0(t)");
    assert!(
        !black(&mut b, [0.0, 0.0]),
        "the pivot drawn at the start's P0"
    );
    no_errors(&mut b);
}
