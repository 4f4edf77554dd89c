//! Issue 47's defects, each run as the hostile run found it: a closed
//! standard output, outputs onto inputs, the ensemble's flags and
//! messages, the stability study on a row that cannot run, a merge of
//! shards without rows, numbers at the ends of their ranges.

use std::process::{Command, Stdio};

use crate::common::*;

/// Every command that prints to standard output, on a pipe whose reader
/// has already gone (`... | head -0`): an ordinary end, exit 0 (the run
/// is fine) with no panic and no "Broken pipe" on stderr. The pipe's
/// read end is closed before the binary starts, so every write fails
/// (the race of `| head -3` made certain).
#[test]
fn a_closed_standard_output_is_an_ordinary_end_for_every_command() {
    let span = scene("span-d3");
    let dir = scratch("closed-stdout");
    let out = dir.join("o.csv");
    let out = out.to_str().unwrap();
    let short = ["--set", "chain.links=6", "--set", "run.t_end=0.2"];
    let cases: Vec<Vec<&str>> = vec![
        vec!["catenary", "--p1", "1,0", "--length", "2", "--links", "50"],
        vec!["catenary", "--p1", "1,0", "--length", "2", "--json"],
        [&["simulate", &span][..], &short].concat(),
        [&["simulate", &span, "--json", "--out", out][..], &short].concat(),
        [
            &["sweep", &span, "--vary", "chain.damping=0,1e-3", "--quiet"][..],
            &short,
        ]
        .concat(),
        [
            &[
                "sweep",
                &span,
                "--vary",
                "chain.damping=0,1e-3",
                "--json",
                "--quiet",
            ][..],
            &short,
        ]
        .concat(),
        [
            &["converge", &span, "--links", "3,6", "--tol", "0.5"][..],
            &short[2..],
        ]
        .concat(),
        [
            &["precision", &span, "--methods", "rk4", "--quiet"][..],
            &short,
        ]
        .concat(),
        [
            &["stability", &span, "--methods", "rk4", "--quiet"][..],
            &short,
        ]
        .concat(),
        [
            &["needs", &span, "--links", "3,6", "--tol", "0.5", "--quiet"][..],
            &short[2..],
        ]
        .concat(),
        [
            &["ensemble", &span, "--members", "2", "--quiet"][..],
            &short,
        ]
        .concat(),
        [
            &["ensemble", &span, "--members", "2", "--json", "--quiet"][..],
            &short,
        ]
        .concat(),
    ];
    for args in cases {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = Command::new(BIN)
            .args(&args)
            .stdin(Stdio::null())
            .stdout(writer)
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        let err = stderr(&o);
        assert!(
            !err.contains("panicked") && !err.contains("Broken pipe") && !err.contains("error:"),
            "{args:?}: {err}"
        );
        assert!(
            matches!(o.status.code(), Some(0) | Some(141)),
            "{args:?}: {:?} {err}",
            o.status
        );
    }
}

/// F1: an output onto the command's own input is refused (exit 2, one
/// line naming the flag) and the input is left as it was: the scene file
/// under every command that reads one, also through `./`, a symbolic link
/// and a hard link; a shard under `merge`; a run under `view --from`.
#[test]
fn an_output_onto_an_input_is_refused_and_the_input_kept() {
    let dir = scratch("output-onto-input");
    let scene_text = std::fs::read_to_string(scene("span-d3")).unwrap();
    let input = dir.join("in.toml");
    std::fs::write(&input, &scene_text).unwrap();
    let link = dir.join("link.csv");
    std::os::unix::fs::symlink(&input, &link).unwrap();
    let hard = dir.join("hard.csv");
    std::fs::hard_link(&input, &hard).unwrap();
    let dotted = dir.join(".").join("in.toml");
    let (i, l, h, d) = (
        input.to_str().unwrap(),
        link.to_str().unwrap(),
        hard.to_str().unwrap(),
        dotted.to_str().unwrap(),
    );
    let short = ["--set", "chain.links=4", "--set", "run.t_end=0.1"];
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["simulate", i, "--out", i], "--out"),
        (vec!["simulate", i, "--out", d], "--out"),
        (vec!["simulate", i, "--forces", l], "--forces"),
        (vec!["simulate", i, "--out", h], "--out"),
        (
            vec!["sweep", i, "--vary", "chain.damping=0,1", "--out", i],
            "--out",
        ),
        (vec!["ensemble", i, "--members", "2", "--out", i], "--out"),
        (vec!["precision", i, "--out", l], "--out"),
        (vec!["stability", i, "--out", i], "--out"),
    ];
    for (args, flag) in cases {
        let all = [&args[..], &short].concat();
        let o = run_quick(&all);
        let err = refused(&o, flag);
        assert!(err.contains("own input"), "{all:?}: {err}");
        assert_eq!(
            std::fs::read_to_string(&input).unwrap(),
            scene_text,
            "{all:?}"
        );
    }
    // The drawing commands check their output's extension first: a scene
    // file named as their output.
    for (command, name) in [
        ("plot", "in.svg"),
        ("animate", "in.gif"),
        ("view", "in.html"),
    ] {
        let named = dir.join(name);
        std::fs::write(&named, &scene_text).unwrap();
        let n = named.to_str().unwrap();
        let o = run_quick(&[&[command, n, "--out", n][..], &short].concat());
        let err = refused(&o, "--out");
        assert!(err.contains("own input"), "{command}: {err}");
        assert_eq!(
            std::fs::read_to_string(&named).unwrap(),
            scene_text,
            "{command}"
        );
    }
    // A shard merged onto itself.
    let shard = dir.join("s.csv");
    let s = shard.to_str().unwrap();
    let o = run(&[
        &[
            "sweep",
            i,
            "--vary",
            "chain.damping=0,1",
            "--quiet",
            "--out",
            s,
        ][..],
        &short,
    ]
    .concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let before = std::fs::read_to_string(&shard).unwrap();
    refused(&run_quick(&["merge", s, "--out", s]), "--out");
    assert_eq!(std::fs::read_to_string(&shard).unwrap(), before);
}

/// U3: the ensemble's whole-number flags refuse what is not one of their
/// integers with their range (clap's own "invalid digit" named none, and
/// `--seed -1` was taken for a positional).
#[test]
fn the_ensembles_integer_flags_say_their_range() {
    let span = scene("span-d3");
    for (flag, value, range) in [
        ("--members", "-1", "2..=4096"),
        ("--members", "1e3", "2..=4096"),
        ("--members", "4097", "2..=4096"),
        ("--seed", "-1", "0..=4294967295"),
        ("--seed", "4294967296", "0..=4294967295"),
        ("--seed", "1.5", "0..=4294967295"),
    ] {
        let o = run_quick(&["ensemble", &span, flag, value]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains(flag) && err.contains(range),
            "{flag} {value}: {err}"
        );
    }
}

/// U1: a scene whose start `simulate` accepts (the floor 2e-4 below the
/// touching height's tolerance) with a spread that moves some member's
/// start into the floor: refused before any run, naming `--spread` and
/// the member, not `floor.height`.
#[test]
fn a_spread_that_moves_a_start_into_the_floor_is_named() {
    let floor = scene("span-d3-floor");
    let sets = ["--set", "floor.height=-2.3901", "--set", "run.t_end=0.02"];
    let o = run(&[&["simulate", &floor, "--json"][..], &sets].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let o = run_quick(
        &[
            &["ensemble", &floor, "--spread", "0.01", "--members", "16"][..],
            &sets,
        ]
        .concat(),
    );
    let err = refused(&o, "--spread");
    assert!(err.contains("member ") && err.contains("floor"), "{err}");
}

/// U4: 4096 members stopped or not run by a short budget: the failures
/// are a few grouped lines, each naming at most 8 members and counting
/// the rest, and the members the budget stopped are said to be so (not
/// `interrupted`).
#[test]
fn ensemble_failures_are_grouped_and_capped() {
    let floor = scene("span-d3-floor");
    let o = run_within(
        &[
            "ensemble",
            &floor,
            "--members",
            "4096",
            "--jobs",
            "8",
            "--spread",
            "0.1",
            "--budget",
            "1",
            "--json",
            "--quiet",
        ],
        std::time::Duration::from_secs(60),
    )
    .expect("the budget ends it");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.len() < 1200, "{} characters: {err}", err.len());
    assert!(!err.contains("interrupted"), "{err}");
    assert!(
        err.contains("not run within --budget") && err.contains("more"),
        "{err}"
    );
    let v = json(&o);
    let failures = v["failures"].as_array().unwrap();
    assert!(failures.len() <= 3, "{failures:?}");
    let counted: u64 = failures
        .iter()
        .map(|f| {
            f.as_str()
                .unwrap()
                .split(' ')
                .next()
                .unwrap()
                .parse::<u64>()
                .unwrap()
        })
        .sum();
    assert_eq!(counted + v["ok"].as_u64().unwrap(), 4096, "{failures:?}");
}

/// W5: members whose quantities are near 1e-300 and differ (a run of
/// t_end = 1e-300): the standard deviation is not 0 while min < max. Its
/// value is checked against the members' own CSV, computed here in a form
/// that cannot underflow (the deviations scaled by 1e300 first).
#[test]
fn the_spread_of_tiny_quantities_does_not_underflow() {
    let dir = scratch("tiny-spread");
    let out = dir.join("e.csv");
    let o = run(&[
        "ensemble",
        &scene("span-d3"),
        "--members",
        "64",
        "--set",
        "run.t_end=1e-300",
        "--set",
        "chain.links=8",
        "--json",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v = json(&o);
    let s = &v["stats"]["tip_speed_max"];
    assert!(num(s, "min") < num(s, "max"), "{s}");
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let c = header.iter().position(|h| *h == "tip_speed_max").unwrap();
    let xs: Vec<f64> = lines
        .map(|l| l.split(',').nth(c).unwrap().parse::<f64>().unwrap() * 1e300)
        .collect();
    let m = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / m;
    let sd = (xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (m - 1.0)).sqrt() * 1e-300;
    assert!(sd > 0.0);
    assert!(
        (num(s, "sd") / sd - 1.0).abs() < 1e-9,
        "{} against {sd}",
        num(s, "sd")
    );
    assert!((num(s, "sem") / (sd / m.sqrt()) - 1.0).abs() < 1e-9, "{s}");
}

/// W3: a stability row whose start lies inside the floor (floor.height =
/// 0, above the chain) is refused before any cell runs, with exit 2 and
/// one line naming the key, as sweep, precision, needs, converge and
/// ensemble refuse it.
#[test]
fn stability_refuses_a_row_whose_start_cannot_run() {
    let floor = scene("span-d3-floor");
    let o = run_quick(&[
        "stability",
        &floor,
        "--vary",
        "floor.height=-3,0",
        "--set",
        "run.t_end=0.1",
        "--methods",
        "bdf",
        "--quiet",
    ]);
    refused(&o, "floor.height");
    let o = run_quick(&[
        "sweep",
        &floor,
        "--vary",
        "floor.height=-3,0",
        "--set",
        "run.t_end=0.1",
    ]);
    refused(&o, "floor.height");
}

/// F3: a shard of more shards than runs holds no row; merging only such
/// shards is refused (exit 2), not "0 rows" with exit 0, and no file is
/// written.
#[test]
fn merging_shards_without_rows_is_refused() {
    let dir = scratch("empty-shards");
    let z5 = dir.join("z5.csv");
    let all = dir.join("all.csv");
    let o = run(&[
        "sweep",
        &scene("span-d3"),
        "--vary",
        "start.p1.0=1:5:3",
        "--set",
        "run.t_end=0.3",
        "--shard",
        "5/10",
        "--quiet",
        "--out",
        z5.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = run_quick(&[
        "merge",
        z5.to_str().unwrap(),
        "--out",
        all.to_str().unwrap(),
    ]);
    let err = refused(&o, "merge");
    assert!(err.contains("no shard holds a row"), "{err}");
    assert!(!all.exists());
}

/// The old U1: numbers at the ends of their range are echoed in their
/// shortest form, in a message (`needs --tol 1e-300`) and in a CSV cell
/// (stability varying `run.t_end` to 1e-300); each reads back exactly.
#[test]
fn extreme_numbers_are_written_in_their_shortest_form() {
    let o = run_quick(&[
        "needs",
        &scene("span-d3"),
        "--tol",
        "1e-300",
        "--links",
        "4,8",
    ]);
    let err = refused(&o, "--tol");
    assert!(err.contains("(got 1e-300)") && err.len() < 120, "{err}");
    let dir = scratch("short-numbers");
    let out = dir.join("x.csv");
    let o = run(&[
        "stability",
        &scene("span-d3"),
        "--vary",
        "run.t_end=1e-300,1",
        "--set",
        "chain.links=4",
        "--methods",
        "rk4",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        o.status.code() == Some(0) || o.status.code() == Some(1),
        "{}",
        stderr(&o)
    );
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    for line in text.lines().skip(1) {
        for (name, cell) in header.iter().zip(line.split(',')) {
            if ["scene", "label", "t_end", "t_reached", "t_failed"].contains(name) {
                assert!(cell.len() < 40, "a {}-character {name}: {cell}", cell.len());
            }
        }
    }
    let c = header.iter().position(|h| *h == "t_end").unwrap();
    let t_ends: Vec<f64> = lines
        .map(|l| l.split(',').nth(c).unwrap().parse().unwrap())
        .collect();
    assert!(
        t_ends.contains(&1e-300) && t_ends.contains(&1.0),
        "{t_ends:?}"
    );
}

/// A very stiff start at rest (g = 1e16: the time scale sqrt(l / g) is
/// 3e-9): every method used to stop at t = 0 with `step_size_too_small`,
/// its first step below the rounding floor. The run is the g = 1 run
/// rescaled (dynamical similarity, no friction: times by 1e-8, speeds by
/// 1e8, positions unchanged), which each method now reproduces to its
/// tolerance.
#[test]
fn a_very_stiff_start_at_rest_takes_its_first_step() {
    let span = scene("span-d3");
    let common = [
        "--set",
        "chain.links=10",
        "--set",
        "chain.damping=0",
        "--json",
    ];
    for method in ["dopri5", "dop853", "bdf", "bdf-dense", "gen-alpha", "auto"] {
        let mut slow = vec![
            "simulate",
            &span,
            "--method",
            method,
            "--set",
            "run.t_end=1",
        ];
        slow.extend(common);
        let mut fast = vec![
            "simulate",
            &span,
            "--method",
            method,
            "--set",
            "run.t_end=1e-8",
            "--set",
            "chain.gravity=1e16",
        ];
        fast.extend(common);
        let (a, b) = (run(&slow), run(&fast));
        assert!(
            a.status.success() && b.status.success(),
            "{method}: {}",
            stderr(&b)
        );
        let (a, b) = (json(&a), json(&b));
        let rel = |x: f64, y: f64| (x / y - 1.0).abs();
        assert!(
            rel(num(&b, "tip_speed_max") * 1e-8, num(&a, "tip_speed_max")) < 1e-5,
            "{method}: {} against {}",
            num(&b, "tip_speed_max") * 1e-8,
            num(&a, "tip_speed_max")
        );
        let (ta, tb) = (pair(&a, "tip_end"), pair(&b, "tip_end"));
        assert!(
            (ta[0] - tb[0]).abs().max((ta[1] - tb[1]).abs()) < 1e-5 * 6.0,
            "{method}: {ta:?} against {tb:?}"
        );
    }
}

/// W1: the floor's peak force is a property of the run. One level rod (m
/// = 1, g = 1) let go 0.5 above an undamped floor meets it at v = 1 on
/// both ends (stiffness k = 1e6 each): a spring of 2k under gravity, whose
/// largest force is `F = m g + sqrt((m g)^2 + 2 k m v^2)` = 1415.2139 and
/// lasts `pi sqrt(m / 2k)` = 2.2e-3, far shorter than the samples 0.1
/// apart (which saw nothing). Every method finds it to its tolerance, at
/// output_dt 0.1 and 0.001 alike; the ratio to the landed weight is `F /
/// m g` (both ends touch).
#[test]
fn a_contact_shorter_than_the_samples_has_its_peak_force() {
    let dir = scratch("short-contact");
    let path = dir.join("rod.toml");
    std::fs::write(
        &path,
        "name = \"rod\"\n[chain]\nlength = 1.0\nlinks = 1\nmass = 1.0\ngravity = 1.0\n\
         [pivot]\nrelease = 0.0\n[start]\nkind = \"angles\"\np0 = [0.0, 0.0]\nangles = [0.0]\n\
         [floor]\nheight = -0.5\nstiffness = 1e6\n[run]\nt_end = 1.5\nrtol = 1e-9\natol = 1e-11\n",
    )
    .unwrap();
    let p = path.to_str().unwrap();
    let (m, g, k, v) = (1.0_f64, 1.0_f64, 1e6_f64, 1.0_f64);
    let want = m * g + ((m * g).powi(2) + 2.0 * k * m * v * v).sqrt();
    let contact = std::f64::consts::PI * (m / (2.0 * k)).sqrt();
    for method in ["dopri5", "dop853", "bdf"] {
        let mut peaks = vec![];
        for dt in ["0.1", "0.001"] {
            let o = run(&[
                "simulate",
                p,
                "--method",
                method,
                "--set",
                &format!("run.output_dt={dt}"),
                "--json",
            ]);
            assert!(o.status.success(), "{method}: {}", stderr(&o));
            let j = json(&o);
            let (f, t, r) = (
                num(&j, "floor_force_max"),
                num(&j, "t_floor_force_max"),
                num(&j, "floor_force_over_landed_weight"),
            );
            assert!(
                (f / want - 1.0).abs() < 1e-5,
                "{method} at {dt}: {f} against {want}"
            );
            assert!(t > 1.0 && t < 1.0 + contact, "{method} at {dt}: t = {t}");
            assert!((r - f / (m * g)).abs() < 1e-9 * r, "{method}: {r}");
            peaks.push(f);
        }
        assert!(
            (peaks[0] / peaks[1] - 1.0).abs() < 1e-8,
            "{method}: {peaks:?}"
        );
    }
}

/// P1: a start inside the floor is bounded by its total overlap over
/// every contact point, at most `n m g / k` and `L / 100`: a very soft
/// floor 5e8 above the chain (where `n m g / k` is 1e9) is refused, and so
/// is a chain laid flat 0.001 inside a floor at 20 points (each point
/// within `n m g / k` = 0.01, their sum 0.02 not); 0.0004 at each (0.008
/// in all) is a start.
#[test]
fn a_start_inside_the_floor_is_bounded_over_every_contact_point() {
    let o = run_quick(&[
        "simulate",
        &scene("span-d3"),
        "--set",
        "floor.stiffness=1e-8",
        "--set",
        "floor.height=5e8",
        "--set",
        "pivot.release=0",
    ]);
    refused(&o, "floor.height");
    let dir = scratch("flat-inside");
    let path = dir.join("flat.toml");
    std::fs::write(
        &path,
        "name = \"flat\"\n[chain]\nlength = 1.0\nlinks = 10\nmass = 0.1\ngravity = 1.0\n\
         [pivot]\nrelease = 0.0\n[start]\nkind = \"angles\"\np0 = [0.0, 0.0]\n\
         angles = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]\n\
         [floor]\nstiffness = 100.0\ndamping = 1.0\n[run]\nt_end = 0.01\n",
    )
    .unwrap();
    let p = path.to_str().unwrap();
    let o = run_quick(&["simulate", p, "--set", "floor.height=0.001"]);
    let err = refused(&o, "floor.height");
    assert!(err.contains("20 points"), "{err}");
    let o = run(&["simulate", p, "--set", "floor.height=0.0004", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// H2: a friction switch far narrower than the scene's speeds
/// (`floor.slip_speed` 1e-12 against sqrt(g L) = 2.4, which bdf could not
/// cross) is refused before the run naming the key and its bound; the
/// bound itself is accepted. U2: a derived default out of range names
/// the key as not set and the keys it comes from.
#[test]
fn slip_speeds_below_the_scenes_scale_and_derived_defaults_are_named() {
    let floor = scene("span-d3-floor");
    let o = run_quick(&["simulate", &floor, "--set", "floor.slip_speed=1e-12"]);
    let err = refused(&o, "floor.slip_speed");
    assert!(err.contains("sqrt(g L)"), "{err}");
    let o = run(&[
        "simulate",
        &floor,
        "--set",
        "floor.slip_speed=2.45e-10",
        "--set",
        "run.t_end=0.01",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = run_quick(&[
        "simulate",
        &scene("span-d3"),
        "--set",
        "floor.height=-3",
        "--set",
        "chain.mass=1e12",
        "--set",
        "run.t_end=0.01",
    ]);
    let err = refused(&o, "floor.stiffness");
    assert!(
        err.contains("not set") && err.contains("chain.mass"),
        "{err}"
    );
}

/// A1: an ensemble keeps summaries only, so its members record no
/// samples: two members run at once, each of whose samples would take 1.06
/// GB (6.5e5 samples of 204 numbers), fit in an address space of 1.5 GB,
/// and their statistics are those of the default sampling (the samples
/// never entered a summary).
#[test]
fn ensemble_members_hold_no_samples() {
    let span = scene("span-d3");
    let sets = [
        "--set",
        "run.t_end=1.3",
        "--members",
        "2",
        "--jobs",
        "2",
        "--json",
        "--quiet",
    ];
    let fine = [
        &["prlimit", "--as=1500000000", BIN, "ensemble", &span][..],
        &sets,
        &["--set", "run.output_dt=2e-6"],
    ]
    .concat();
    let o = Command::new(fine[0]).args(&fine[1..]).output().unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    let coarse = run(&[&["ensemble", &span][..], &sets].concat());
    assert!(coarse.status.success(), "{}", stderr(&coarse));
    assert_eq!(json(&o)["stats"], json(&coarse)["stats"]);
}

/// W4: `inaccurate` is tied to the run's tolerance: an energy balance
/// error above 100 tolerances of the energy scale is not a solution at
/// that tolerance. The bungee at EA = 1e7 with no axial damping (10
/// rods) at rtol 1e-5: bdf steps over the undamped axial modes and loses
/// their energy (2.5e-3 of the scale, 246 tolerances: `ok` under the old
/// rule, the whole scale), dop853 resolves them (1.6e-4, 16 tolerances)
/// and stays `ok`; and every method's run of span-d3 at rtol 1e-3 and
/// 1e-6 stays `ok`.
#[test]
fn inaccurate_is_tied_to_the_runs_tolerance() {
    let bungee = scene("bungee");
    let sets = [
        "--set",
        "chain.axial_stiffness=1e7",
        "--set",
        "chain.axial_damping=0",
        "--set",
        "chain.links=10",
        "--rtol",
        "1e-5",
        "--json",
    ];
    let verdict = |scene: &str, method: &str, extra: &[&str]| {
        let o = run(&[&["simulate", scene, "--method", method][..], extra].concat());
        let j = json(&o);
        (
            j["status"].as_str().unwrap().to_string(),
            num(&j, "energy_balance_error") / num(&j, "energy_scale"),
        )
    };
    let (status, e) = verdict(&bungee, "bdf", &sets);
    assert!(e > 1e-3 && e < 1.0, "{e}");
    assert_eq!(status, "inaccurate", "{e}");
    let (status, e) = verdict(&bungee, "dop853", &sets);
    assert_eq!(status, "ok", "{e}");
    for method in ["dopri5", "dop853", "bdf", "gen-alpha"] {
        for rtol in ["1e-3", "1e-6"] {
            let (status, e) = verdict(&scene("span-d3"), method, &["--rtol", rtol, "--json"]);
            assert_eq!(status, "ok", "{method} {rtol}: {e}");
        }
    }
}

/// H1: `auto` on a stiff, heavily damped contact (a chain hanging onto a
/// floor of k = 1e8 and Hunt–Crossley c = 1e6: contact damping ratio 16)
/// hands over to bdf at its first stiffness detection, where it ran
/// DOPRI5 to the end before; H3: on a rope whose axial modes are far past
/// what gen-alpha progressed on (bungee at EA = 1e12, no axial damping,
/// rtol 1e-3) it starts explicit, not gen-alpha, and says so in the hint
/// when it stays explicit on a stiff run.
#[test]
fn auto_hands_over_on_damped_contact_and_starts_no_gen_alpha_it_cannot_run() {
    let o = run(&[
        "simulate",
        &scene("cayley-scale"),
        "--method",
        "auto",
        "--set",
        "floor.stiffness=1e8",
        "--set",
        "floor.damping=1e6",
        "--set",
        "run.t_end=0.05",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j = json(&o);
    let methods: Vec<&str> = j["segments"]
        .as_array()
        .unwrap()
        .iter()
        .map(|g| g["method"].as_str().unwrap())
        .collect();
    assert!(methods.contains(&"bdf"), "{methods:?}");
    let o = run(&[
        "simulate",
        &scene("bungee"),
        "--method",
        "auto",
        "--set",
        "chain.axial_stiffness=1e12",
        "--set",
        "chain.axial_damping=0",
        "--rtol",
        "1e-3",
        "--set",
        "run.t_end=2e-4",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let j = json(&o);
    let first = j["segments"][0]["method"].as_str().unwrap().to_string();
    assert_ne!(first, "gen-alpha");
    if num(&j, "stiffness_detections") >= 10.0 {
        assert!(
            stderr(&o).contains("auto stayed explicit"),
            "{}",
            stderr(&o)
        );
    }
}

/// H3, remeasured (docs/model.md, "auto and gen-alpha"): on the issue's
/// command (bungee, EA = 1e12, no axial damping, rtol 1e-3, atol 1e-10)
/// every method is held to steps of about 1e-8 (3.1 million DOPRI5 steps
/// to t = 0.05), but `auto` starts the method that goes furthest: under a
/// cap of 20,000 step attempts its DOPRI5 gets more than twice as far as
/// gen-alpha run as `auto` ran it before (rtol 1e-6, atol 1e-13, rho_inf
/// 0), whose Newton iteration fails at a fifth of its attempts. And inside
/// the gen-alpha band (EA = 1e7, stiffness ratio 2.8e5) at the scene's
/// atol, where gen-alpha's Newton iteration cannot reach its 1e-13, `auto`
/// runs DOPRI5, step for step.
#[test]
fn auto_on_the_h3_rope_starts_no_method_that_stalls() {
    let bungee = scene("bungee");
    let h3 = |ea: &str, method: &[&str]| {
        let stiffness = format!("chain.axial_stiffness={ea}");
        let o = run(&[
            &[
                "simulate",
                &bungee,
                "--set",
                &stiffness,
                "--set",
                "chain.axial_damping=0",
                "--set",
                "run.t_end=0.05",
                "--set",
                "run.max_steps=20000",
                "--json",
            ][..],
            method,
        ]
        .concat());
        json(&o)
    };
    let auto = h3("1e12", &["--rtol", "1e-3", "--method", "auto"]);
    assert_eq!(auto["segments"][0]["method"], "dopri5", "{auto}");
    let gen_alpha = [
        "--method",
        "gen-alpha",
        "--rtol",
        "1e-6",
        "--atol",
        "1e-13",
        "--set",
        "run.rho_inf=0",
    ];
    let stalled = h3("1e12", &gen_alpha);
    assert_eq!(stalled["status"], "max_steps", "{stalled}");
    let attempts = num(&stalled, "steps") + num(&stalled, "rejected_steps");
    assert!(
        num(&stalled, "newton_failures") * 5.0 > attempts,
        "{stalled}"
    );
    assert!(
        num(&auto, "t_reached") > 2.0 * num(&stalled, "t_reached"),
        "{auto} {stalled}"
    );
    let band = h3("1e7", &["--rtol", "1e-3", "--method", "auto"]);
    let dopri5 = h3("1e7", &["--rtol", "1e-3", "--method", "dopri5"]);
    assert_eq!(band["segments"][0]["method"], "dopri5", "{band}");
    assert_eq!(band["steps"], dopri5["steps"]);
    assert_eq!(band["tip_end"], dopri5["tip_end"]);
}
