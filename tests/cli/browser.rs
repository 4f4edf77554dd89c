//! `falling-chain view`'s page in a real browser: headless Chromium (the
//! distribution's package), driven over the DevTools pipe by the
//! `browser` crate. Each test opens a page that `view` wrote and checks
//! what was drawn against the run: no console error, a canvas that is not
//! blank, a slider and arrow keys that move the chain and the shown time, a
//! click on a curve that jumps there, space that plays and pauses,
//! the tip drawn at the last frame at `simulate --json`'s `tip_end`, the
//! summary equal to `simulate --json`'s, two runs in two colours, a failed
//! run in red, and joint forces as colour along the chain.
//!
//! Without Chromium a plain `cargo test` says once that it skipped these;
//! with `CI=true` (as in `.ci/run`) a missing browser fails them instead.

use std::io::Write as _;
use std::path::Path;
use std::sync::Once;

use browser::Browser;
use serde_json::Value;

use crate::common::{json, num, pair, run, scene, scratch, stderr};
use crate::view::view;

/// The page's size in CSS pixels (its canvases fit).
const WIDTH: u32 = 1200;
const HEIGHT: u32 = 900;

/// A browser, or `None` (said once on the terminal) when there is no
/// Chromium and this is not CI. Under `CI=true` a missing browser fails.
pub(crate) fn open(page: &Path, scratch_dir: &Path) -> Option<Browser> {
    static SKIPPED: Once = Once::new();
    let Some(chromium) = browser::find() else {
        assert!(
            std::env::var("CI").as_deref() != Ok("true"),
            "CI=true but no chromium on PATH (nor $CHROMIUM): .ci/run installs it"
        );
        SKIPPED.call_once(|| {
            // Straight to the terminal: the test harness captures eprintln!.
            let _ = writeln!(
                std::io::stderr().lock(),
                "skipped the browser tests of view: no chromium on PATH (apt-get install chromium)"
            );
        });
        return None;
    };
    let mut b = Browser::launch(&chromium, scratch_dir, WIDTH, HEIGHT).unwrap();
    b.open(page).unwrap();
    Some(b)
}

/// Runs `view` with `args` into `dir/name` and expects exit `code`.
pub(crate) fn page(dir: &Path, name: &str, args: &[&str], code: i32) -> std::path::PathBuf {
    let (page, o) = view(dir, name, args);
    assert_eq!(o.status.code(), Some(code), "{}", stderr(&o));
    page
}

/// JavaScript: the chain canvas's RGBA pixels as one array.
pub(crate) const PIXELS: &str = "Array.from(document.getElementById('chain').getContext('2d')\
    .getImageData(0, 0, 640, 540).data)";

pub(crate) fn pixels(b: &mut Browser) -> Vec<u8> {
    b.eval(PIXELS)
        .unwrap()
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap() as u8)
        .collect()
}

/// How many pixels are not white.
pub(crate) fn inked(px: &[u8]) -> usize {
    px.chunks(4)
        .filter(|p| p[0] < 250 || p[1] < 250 || p[2] < 250)
        .count()
}

/// How many pixels are within 12 of the colour `#rrggbb` in each channel.
pub(crate) fn of_colour(px: &[u8], hex: &str) -> usize {
    let c: Vec<i32> = (0..3)
        .map(|k| i32::from_str_radix(&hex[1 + 2 * k..3 + 2 * k], 16).unwrap())
        .collect();
    px.chunks(4)
        .filter(|p| (0..3).all(|k| (i32::from(p[k]) - c[k]).abs() <= 12))
        .count()
}

pub(crate) fn no_errors(b: &mut Browser) {
    let errors = b.errors();
    assert!(errors.is_empty(), "console errors: {errors:?}");
}

#[test]
fn the_page_draws_and_the_slider_and_keys_move_the_chain_and_the_time() {
    let dir = scratch("browser-scrub");
    let page = page(&dir, "scrub.html", &[&scene("span-d3")], 0);
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    no_errors(&mut b);
    let start = pixels(&mut b);
    assert!(inked(&start) > 500, "the chain canvas is blank");
    let times: Vec<f64> = crate::view::page_data(&page)["runs"][0]["t"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    // Move the slider as a user does: set it and fire its input event.
    let k = times.len() / 2;
    b.eval(&format!(
        "const s = document.getElementById('slider'); s.value = '{k}'; \
         s.dispatchEvent(new Event('input')); 0"
    ))
    .unwrap();
    let middle = pixels(&mut b);
    let changed = start
        .chunks(4)
        .zip(middle.chunks(4))
        .filter(|(a, c)| a != c)
        .count();
    assert!(changed > 200, "only {changed} pixels changed");
    // The shown time is the sample's.
    let shown = |b: &mut Browser| {
        let text = b
            .eval("document.getElementById('time').textContent")
            .unwrap();
        text.as_str()
            .unwrap()
            .trim_start_matches("t = ")
            .parse::<f64>()
            .unwrap()
    };
    assert!(
        (shown(&mut b) - times[k]).abs() < 5e-4,
        "{} vs {}",
        shown(&mut b),
        times[k]
    );
    // The right arrow key, as the browser delivers it, steps one sample.
    for (key, code, step) in [
        ("ArrowRight", 39, 1),
        ("ArrowLeft", 37, -1),
        ("ArrowLeft", 37, -1),
    ] {
        let before = b.eval("fallingChain.index()").unwrap().as_i64().unwrap();
        for kind in ["rawKeyDown", "keyUp"] {
            b.call(
                "Input.dispatchKeyEvent",
                serde_json::json!({ "type": kind, "key": key, "code": key,
                    "windowsVirtualKeyCode": code }),
            )
            .unwrap();
        }
        let after = b.eval("fallingChain.index()").unwrap().as_i64().unwrap();
        assert_eq!(after, before + step, "{key}");
        let i = usize::try_from(after).unwrap();
        assert!((shown(&mut b) - times[i]).abs() < 5e-4);
    }
    // A click on the tip-speed curve at the x of t = 2 jumps to the
    // sample nearest t = 2 (samples 0.08 apart).
    let at = b
        .eval(
            "(() => { const c = document.getElementById('speed').getBoundingClientRect(); \
             return [c.left, c.top, c.width]; })()",
        )
        .unwrap();
    // The plot box spans x = 62 .. width - 12 for t = 0 .. the last time.
    let (left, top, width) = (num_at_f(&at, 0), num_at_f(&at, 1), num_at_f(&at, 2));
    let last = times[times.len() - 1];
    let x = left + 62.0 + 2.0 / last * (width - 74.0);
    for kind in ["mousePressed", "mouseReleased"] {
        b.call(
            "Input.dispatchMouseEvent",
            serde_json::json!({ "type": kind, "x": x, "y": top + 100.0, "button": "left",
                "clickCount": 1 }),
        )
        .unwrap();
    }
    assert!(
        (shown(&mut b) - 2.0).abs() <= 0.04 + 1e-9,
        "{}",
        shown(&mut b)
    );
    // Space plays: the time moves on by itself, then stops on space again.
    let space = |b: &mut Browser| {
        for kind in ["keyDown", "keyUp"] {
            b.call(
                "Input.dispatchKeyEvent",
                serde_json::json!({ "type": kind, "key": " ", "code": "Space", "text": " ",
                    "windowsVirtualKeyCode": 32 }),
            )
            .unwrap();
        }
    };
    let before = shown(&mut b);
    space(&mut b);
    assert_eq!(b.eval("fallingChain.playing()").unwrap(), true);
    b.eval("new Promise((r) => setTimeout(r, 400))").unwrap();
    space(&mut b);
    assert_eq!(b.eval("fallingChain.playing()").unwrap(), false);
    assert!(shown(&mut b) > before, "playing did not move the time");
    no_errors(&mut b);
}

fn num_at_f(v: &Value, k: usize) -> f64 {
    v[k].as_f64().unwrap()
}

#[test]
fn the_tip_drawn_at_the_last_frame_is_the_runs_tip_end() {
    let dir = scratch("browser-tip");
    let page = page(&dir, "tip.html", &[&scene("span-d3")], 0);
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    let sim = json(&run(&["simulate", &scene("span-d3"), "--json"]));
    b.eval("fallingChain.seek(fallingChain.frames - 1); 0")
        .unwrap();
    let tip = b.eval("fallingChain.drawnTip(0)").unwrap();
    let tip = [tip[0].as_f64().unwrap(), tip[1].as_f64().unwrap()];
    let end = pair(&sim, "tip_end");
    // The page's angles carry 6 decimals: n l 5e-7 = 3e-6 at most.
    assert!(
        (tip[0] - end[0]).hypot(tip[1] - end[1]) < 3e-6,
        "{tip:?} vs {end:?}"
    );
    // And the pixel there is the run's colour (the tip's dot).
    let at = b
        .eval(&format!("fallingChain.toPixel({}, {})", end[0], end[1]))
        .unwrap();
    let (x, y) = (
        at[0].as_f64().unwrap().round() as usize,
        at[1].as_f64().unwrap().round() as usize,
    );
    let px = pixels(&mut b);
    let colour = b.eval("fallingChain.colors[0]").unwrap();
    let dot = &px[4 * (y * 640 + x)..4 * (y * 640 + x) + 4];
    assert_eq!(
        of_colour(dot, colour.as_str().unwrap()),
        1,
        "{dot:?} at ({x}, {y})"
    );
    no_errors(&mut b);
}

#[test]
fn the_summary_on_the_page_is_simulate_json() {
    let dir = scratch("browser-summary");
    let page = page(&dir, "summary.html", &[&scene("folded")], 0);
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    let sim = json(&run(&["simulate", &scene("folded"), "--json"]));
    let cells = b
        .eval(
            "Object.fromEntries(Array.from(document.querySelectorAll('#summary td[data-key]'))\
             .map((c) => [c.dataset.key, [c.dataset.value === undefined ? null : \
             JSON.parse(c.dataset.value), c.textContent]]))",
        )
        .unwrap();
    for key in [
        "status",
        "method",
        "links",
        "steps",
        "tip_speed_max",
        "t_tip_speed_max",
        "t_reached",
        "tip_end",
        "energy_balance_error",
    ] {
        assert_eq!(cells[key][0], sim[key], "{key}");
        // What is shown is the value to 4 digits.
        if let Some(v) = sim[key].as_f64().filter(|v| v.fract() != 0.0) {
            let text: f64 = cells[key][1].as_str().unwrap().parse().unwrap();
            assert!((text - v).abs() <= 1e-3 * v.abs(), "{key}: {text} vs {v}");
        }
    }
    assert_eq!(cells["t_failed"][1], "—");
    no_errors(&mut b);
}

#[test]
fn two_overlaid_runs_draw_in_two_colours() {
    let dir = scratch("browser-two");
    let page = page(&dir, "two.html", &[&scene("span-d3"), &scene("span-d5")], 0);
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    let colors = b.eval("fallingChain.colors").unwrap();
    let colors: Vec<&str> = colors
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    assert_eq!(colors.len(), 2);
    assert_ne!(colors[0], colors[1]);
    b.eval("fallingChain.seekTime(2); 0").unwrap();
    let px = pixels(&mut b);
    for c in &colors {
        assert!(of_colour(&px, c) > 100, "{c}: {} pixels", of_colour(&px, c));
    }
    let legend = b
        .eval("document.getElementById('legend').textContent")
        .unwrap();
    assert_eq!(legend, "span-d3span-d5");
    no_errors(&mut b);
}

#[test]
fn a_failed_run_shows_its_status_and_time_in_red() {
    let dir = scratch("browser-failed");
    let page = page(
        &dir,
        "failed.html",
        &[&scene("folded"), "--method", "rk4"],
        1,
    );
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    let red = "rgb(221, 0, 0)";
    let colour = |b: &mut Browser, selector: &str| {
        b.eval(&format!(
            "getComputedStyle(document.querySelector('{selector}')).color"
        ))
        .unwrap()
    };
    assert_eq!(colour(&mut b, "#summary td[data-key=status]"), red);
    assert_eq!(colour(&mut b, "#summary td[data-key=t_failed]"), red);
    assert_ne!(colour(&mut b, "#time"), red, "red before the failure");
    b.eval("fallingChain.seek(fallingChain.frames - 1); 0")
        .unwrap();
    assert_eq!(colour(&mut b, "#time"), red);
    let status = b
        .eval("document.querySelector('#summary td[data-key=status]').textContent")
        .unwrap();
    assert_ne!(status, "ok");
    assert_eq!(status, crate::view::page_data(&page)["runs"][0]["status"]);
    no_errors(&mut b);
}

#[test]
fn joint_forces_colour_the_chain_along_its_length() {
    // A run's CSV with a tension that grows along the chain, 0 at P0 to
    // n = 50 at the tip, in every row: the first rod is drawn in the
    // ramp's low end, the last in its high end.
    let dir = scratch("browser-forces");
    let csv = dir.join("run.csv");
    assert!(run(&[
        "simulate",
        &scene("span-d3"),
        "--out",
        csv.to_str().unwrap()
    ])
    .status
    .success());
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut out = String::new();
    for (k, line) in text.lines().enumerate() {
        out.push_str(line);
        for j in 0..=50 {
            out.push_str(&if k == 0 {
                format!(",tension_{j}")
            } else {
                format!(",{j}")
            });
        }
        out.push('\n');
    }
    std::fs::write(&csv, out).unwrap();
    let page = page(&dir, "forces.html", &["--from", csv.to_str().unwrap()], 0);
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    let px = pixels(&mut b);
    let rgb = |b: &mut Browser, j: usize| -> Vec<i32> {
        let at = b
            .eval(&format!(
                "(() => {{ const p = fallingChain.joint(0, {j}), q = fallingChain.joint(0, {}); \
                 return fallingChain.toPixel((p[0] + q[0]) / 2, (p[1] + q[1]) / 2); }})()",
                j + 1
            ))
            .unwrap();
        let (x, y) = (num_at(&at, 0), num_at(&at, 1));
        (0..3)
            .map(|c| i32::from(px[4 * (y * 640 + x) + c]))
            .collect()
    };
    // ramp(0.01) and ramp(0.99): the colour bar's ends.
    let (low, high) = (rgb(&mut b, 0), rgb(&mut b, 49));
    let near = |a: &[i32], b: [i32; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 16);
    assert!(near(&low, [48, 19, 61]), "first rod {low:?}");
    assert!(near(&high, [250, 229, 38]), "last rod {high:?}");
    let notes = b
        .eval("document.getElementById('notes').textContent")
        .unwrap();
    assert!(notes.as_str().unwrap().contains("tension"), "{notes}");
    no_errors(&mut b);
}

fn num_at(v: &Value, k: usize) -> usize {
    v[k].as_f64().unwrap().round() as usize
}

/// Not a test of behaviour: the frame times of the folded chain at n = 400
/// (8 s at the default output step) over 2 s of playback, from the
/// browser's own requestAnimationFrame timestamps, and the page's drawing
/// time per frame. Run by hand and quoted in the README:
/// `cargo test --release -p falling-chain --test cli frame_times -- --ignored --nocapture`
#[test]
#[ignore = "a measurement, run by hand"]
fn frame_times_of_the_folded_chain_at_400_rods() {
    let dir = scratch("browser-frames");
    let page = page(
        &dir,
        "folded-400.html",
        &[
            &scene("folded"),
            "--set",
            "chain.links=400",
            "--set",
            "start.down=200",
            "--set",
            "run.t_end=8",
            "--set",
            "run.output_dt=0.01",
        ],
        0,
    );
    let bytes = std::fs::metadata(&page).unwrap().len();
    let Some(mut b) = open(&page, &dir) else {
        return;
    };
    let stats = b
        .eval(
            "new Promise((done) => { const stamps = []; fallingChain.seek(0); \
             const drawn = fallingChain.drawTimes().length; fallingChain.play(); \
             const tick = (t) => { stamps.push(t); \
               if (t - stamps[0] < 2000) requestAnimationFrame(tick); \
               else { fallingChain.pause(); \
                 const d = stamps.slice(1).map((s, k) => s - stamps[k]).sort((a, b) => a - b); \
                 const draw = fallingChain.drawTimes().slice(drawn).sort((a, b) => a - b); \
                 const q = (a, p) => a[Math.min(a.length - 1, Math.floor(p * a.length))]; \
                 done({ frames: d.length, mean: d.reduce((a, b) => a + b, 0) / d.length, \
                   p50: q(d, 0.5), p95: q(d, 0.95), max: d[d.length - 1], \
                   draws: draw.length, draw_p50: q(draw, 0.5), draw_p95: q(draw, 0.95), \
                   draw_max: draw[draw.length - 1] }); } }; \
             requestAnimationFrame(tick); })",
        )
        .unwrap();
    let data = crate::view::page_data(&page);
    let r = &data["runs"][0];
    println!(
        "folded n = 400, {} bytes, stride {} of {} samples: {stats}",
        bytes, r["stride"], r["samples"]
    );
    assert!(num(&stats, "frames") > 0.0);
    no_errors(&mut b);
}

/// A run with a floor draws it: the line at the scene's `floor.height`
/// (level here), in the run's colour where no rod covers it at `t = 0`;
/// a run without a floor draws none.
#[test]
fn the_floor_is_drawn_at_its_height() {
    let dir = scratch("browser-floor");
    let floor_page = page(&dir, "floor.html", &[&scene("span-d3-floor")], 0);
    let Some(mut b) = open(&floor_page, &dir) else {
        return;
    };
    b.eval("fallingChain.seek(0); 0").unwrap();
    let line = b.eval("fallingChain.drawnFloor(0)").unwrap();
    let v: Vec<f64> = (0..4).map(|k| line[k].as_f64().unwrap()).collect();
    assert_eq!((v[1], v[3]), (-3.0, -3.0), "{v:?}");
    assert!(v[0] < 0.0 && v[2] > 3.0, "{v:?}");
    let colour = b.eval("fallingChain.colors[0]").unwrap();
    // Far left of the chain (which spans x in [0, 3] at t = 0).
    let at = b
        .eval(&format!(
            "fallingChain.toPixel({}, -3)",
            v[0] + 0.1 * (v[2] - v[0])
        ))
        .unwrap();
    let (x, y) = (
        at[0].as_f64().unwrap().round() as usize,
        at[1].as_f64().unwrap().round() as usize,
    );
    let px = pixels(&mut b);
    let dot = &px[4 * (y * 640 + x)..4 * (y * 640 + x) + 4];
    assert_eq!(
        of_colour(dot, colour.as_str().unwrap()),
        1,
        "{dot:?} at ({x}, {y})"
    );
    no_errors(&mut b);
    let plain = page(&dir, "plain.html", &[&scene("span-d3")], 0);
    let Some(mut b) = open(&plain, &dir) else {
        return;
    };
    assert!(b.eval("fallingChain.drawnFloor(0)").unwrap().is_null());
}
