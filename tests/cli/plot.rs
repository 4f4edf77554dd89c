//! `falling-chain plot` and `animate`: the figure and the GIF of a scene.

use std::fs;
use std::path::Path;

use crate::common::*;

#[test]
fn plot_and_animate_write_the_format_asked_for_or_nothing() {
    let dir = scratch("plot");
    let png = dir.join("span.png");
    let out = run(&[
        "plot",
        &scene("span-d3"),
        "-o",
        png.to_str().unwrap(),
        "--set",
        "run.t_end=1",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let bytes = fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR: width and height, big-endian, at bytes 16..24.
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert_eq!(h, 900);
    assert!(!dir.join("span.svg").exists(), "only the format asked for");

    let gif = dir.join("fall.gif");
    let out = run(&[
        "animate",
        &scene("span-d3"),
        "-o",
        gif.to_str().unwrap(),
        "--seconds",
        "0.5",
        "--fps",
        "10",
        "--set",
        "run.t_end=0.5",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(&fs::read(&gif).unwrap()[..6], b"GIF89a");

    for (args, field) in [
        (vec!["plot", &scene("span-d3"), "-o", "x.jpg"], "--out"),
        (
            vec!["animate", &scene("span-d3"), "-o", "x.gif", "--fps", "0"],
            "--fps",
        ),
        (vec!["animate", &scene("span-d3"), "-o", "x.png"], "--out"),
    ] {
        let out = run(&args);
        assert_eq!(out.status.code(), Some(2));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains(field) && err.trim().lines().count() == 1,
            "{err}"
        );
    }
    assert!(!Path::new("x.gif").exists() && !Path::new("x.jpg").exists());
}

#[test]
fn plot_and_animate_of_a_failed_run_exit_1_and_still_draw_it() {
    // gamma = 34.7 (chain.damping = 0.1): RK4 at dt = 0.01 diverges within
    // the first steps (see the sweep and simulate tests); what it computed
    // up to there is drawn.
    let dir = scratch("plot-failed");
    let png = dir.join("failed.png");
    let gif = dir.join("failed.gif");
    let span = scene("span-d3");
    for (args, file) in [
        (vec!["plot", "-o", png.to_str().unwrap()], &png),
        (
            vec!["animate", "-o", gif.to_str().unwrap(), "--seconds", "0.5"],
            &gif,
        ),
    ] {
        let mut all = args.clone();
        all.extend([
            span.as_str(),
            "--set",
            "chain.damping=0.1",
            "--set",
            "run.t_end=1",
            "--set",
            "run.method=rk4",
        ]);
        let out = run(&all);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains("status diverged"),
            "{args:?}: {}",
            stderr(&out)
        );
        let bytes = fs::read(file).unwrap();
        assert!(bytes.starts_with(b"\x89PNG") || bytes.starts_with(b"GIF89a"));
    }
    assert_eq!(names_in(&dir), ["failed.gif", "failed.png"]);
    fs::remove_dir_all(&dir).unwrap();
}
