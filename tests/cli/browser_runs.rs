//! The viewer's page with several runs, and its time in the URL, in
//! headless Chromium (as `browser.rs`): runs coloured by their joint forces
//! are still told apart (each outlined in its run's colour, as the legend
//! says); a floor is drawn under its own run only, in its colour; the page
//! opens at `view --at T` and at the `#t=T` of its URL, and keeps the time
//! shown in its URL.

use browser::Browser;

use crate::browser::{no_errors, of_colour, open, page, pixels};
use crate::common::{run, scene, scratch, stderr};
use crate::view::page_data;

/// The RGBA of the pixel that holds the canvas point `(x, y)`.
fn pixel(px: &[u8], x: f64, y: f64) -> &[u8] {
    let (x, y) = (x.floor() as usize, y.floor() as usize);
    &px[4 * (y * 640 + x)..4 * (y * 640 + x) + 4]
}

fn f(v: &serde_json::Value, k: usize) -> f64 {
    v[k].as_f64().unwrap()
}

/// Joint `j` of run `i` as drawn, in canvas pixels.
fn joint_px(b: &mut Browser, i: usize, j: usize) -> [f64; 2] {
    let at = b
        .eval(&format!(
            "(() => {{ const p = fallingChain.joint({i}, {j}); return fallingChain.toPixel(p[0], p[1]); }})()"
        ))
        .unwrap();
    [f(&at, 0), f(&at, 1)]
}

/// Two runs with `--forces`: every chain takes the tension's colours
/// along it, and each is outlined in its own run's colour: on both sides
/// of a rod, between the force line (3.5 px) and the outline's edge, the
/// pixels are the run's colour, while the rod's middle is not. Without the
/// outline (a break in `.ci/breaks`) the sides are white.
#[test]
fn runs_coloured_by_their_forces_are_outlined_in_their_own_colours() {
    let dir = scratch("browser-forces-runs");
    let page = page(
        &dir,
        "runs.html",
        &[&scene("span-d3"), &scene("span-d5"), "--forces"],
        0,
    );
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    b.eval("fallingChain.seek(0); 0").unwrap();
    let colors = b.eval("fallingChain.colors").unwrap();
    let outline = b.eval("fallingChain.outline").unwrap().as_f64().unwrap();
    let px = pixels(&mut b);
    for i in 0..2 {
        let colour = colors[i].as_str().unwrap();
        // Rods near the bottom of each U (apart from the other run's).
        let mut sides = 0;
        for j in [22, 25, 28] {
            let (p, q) = (joint_px(&mut b, i, j), joint_px(&mut b, i, j + 1));
            let (mx, my) = (0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]));
            let len = (q[0] - p[0]).hypot(q[1] - p[1]);
            let (nx, ny) = (-(q[1] - p[1]) / len, (q[0] - p[0]) / len);
            // The middle of the outline's band, 1.75 .. 1.75 + outline px.
            let d = 1.75 + 0.5 * outline;
            for s in [-1.0, 1.0] {
                let side = pixel(&px, mx + s * d * nx, my + s * d * ny);
                sides += of_colour(side, colour);
            }
            let middle = pixel(&px, mx, my);
            assert_eq!(of_colour(middle, colour), 0, "run {i} rod {j}: {middle:?}");
        }
        assert_eq!(sides, 6, "run {i}: {sides} of 6 side pixels in {colour}");
    }
    let notes = b
        .eval("document.getElementById('notes').textContent")
        .unwrap();
    assert!(
        notes
            .as_str()
            .unwrap()
            .contains("outlined in its run's colour"),
        "{notes}"
    );
    no_errors(&mut b);
}

/// A page of a run with a floor and one without: the floor is drawn for
/// its own run only (run 1 has none), in run 0's colour, across run 0's
/// own extent (a tenth of it and 2% of the chain's length each side), and
/// the legend marks run 0 alone as having a floor.
#[test]
fn a_floor_is_drawn_with_its_own_run_only() {
    let dir = scratch("browser-floor-runs");
    let page = page(
        &dir,
        "floor-runs.html",
        &[&scene("span-d3-floor"), &scene("span-d3")],
        0,
    );
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    b.eval("fallingChain.seek(0); 0").unwrap();
    assert!(b.eval("fallingChain.drawnFloor(1)").unwrap().is_null());
    let line = b.eval("fallingChain.drawnFloor(0)").unwrap();
    let bounds = b.eval("fallingChain.bounds(0)").unwrap();
    let (x0, x1, xmin, xmax) = (f(&line, 0), f(&line, 2), f(&bounds, 0), f(&bounds, 1));
    let pad = 0.1 * (xmax - xmin) + 0.02 * 6.0;
    assert!(
        (x0 - (xmin - pad)).abs() < 1e-9 && (x1 - (xmax + pad)).abs() < 1e-9,
        "floor [{x0}, {x1}] against run 0's [{xmin}, {xmax}]"
    );
    assert_eq!((f(&line, 1), f(&line, 3)), (-3.0, -3.0));
    let colour = b.eval("fallingChain.colors[0]").unwrap();
    let px = pixels(&mut b);
    let mut on = 0;
    for k in 1..10 {
        let x = x0 + 0.1 * k as f64 * (x1 - x0);
        let at = b.eval(&format!("fallingChain.toPixel({x}, -3)")).unwrap();
        on += of_colour(pixel(&px, f(&at, 0), f(&at, 1)), colour.as_str().unwrap());
    }
    assert!(on >= 8, "{on} of 9 points of the floor in run 0's colour");
    let marks = b
        .eval("Array.from(document.querySelectorAll('#legend > span')).map((s) => s.textContent)")
        .unwrap();
    assert_eq!(marks, serde_json::json!(["span-d3-floorfloor", "span-d3"]));
    no_errors(&mut b);
}

/// The sample time nearest `t` in the page's times.
fn nearest(times: &[f64], t: f64) -> f64 {
    times
        .iter()
        .copied()
        .min_by(|a, b| (a - t).abs().total_cmp(&(b - t).abs()))
        .unwrap()
}

/// `view --at 2.76` opens the page at the sample nearest 2.76; a `#t=1.5`
/// in its URL moves it there, and wins over `--at` when the page is
/// loaded with it; scrubbing writes the time shown into the URL. A time
/// out of the runs' range is refused by name, and no page is written.
#[test]
fn the_page_opens_at_the_time_of_view_at_and_of_its_url() {
    let dir = scratch("browser-at");
    let page = page(&dir, "at.html", &[&scene("span-d3"), "--at", "2.76"], 0);
    let data = page_data(&page);
    assert_eq!(data["at"], 2.76);
    let times: Vec<f64> = data["runs"][0]["t"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    for bad in ["5", "-1", "nan"] {
        let out = dir.join(format!("bad{bad}.html"));
        let o = run(&[
            "view",
            &scene("span-d3"),
            "--at",
            bad,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2), "--at {bad}");
        let e = stderr(&o);
        assert!(
            e.starts_with("error: --at: must be a time in [0, 4.157]") && e.lines().count() == 1,
            "{e}"
        );
        assert!(!out.exists());
    }
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    let time = |b: &mut Browser| b.eval("fallingChain.time()").unwrap().as_f64().unwrap();
    assert_eq!(time(&mut b), nearest(&times, 2.76));
    b.eval("location.hash = 't=1.5'; new Promise((r) => setTimeout(r, 100))")
        .unwrap();
    assert_eq!(time(&mut b), nearest(&times, 1.5));
    // Loaded with #t=1.5 in its URL: the URL's time, not --at's.
    b.eval("window.marker = 1; location.reload(); 0").unwrap();
    let mut reloaded = None;
    for _ in 0..100 {
        let v = b
            .eval(
                "new Promise((r) => setTimeout(r, 50)).then(() => \
                 window.marker === undefined && window.fallingChain ? fallingChain.time() : null)",
            )
            .unwrap_or(serde_json::Value::Null);
        if let Some(t) = v.as_f64() {
            reloaded = Some(t);
            break;
        }
    }
    assert_eq!(reloaded, Some(nearest(&times, 1.5)));
    // Scrubbing keeps the time shown in the URL.
    b.eval("fallingChain.seek(10); 0").unwrap();
    let hash = b.eval("location.hash").unwrap();
    assert_eq!(hash, format!("#t={}", times[10]));
    no_errors(&mut b);
}
