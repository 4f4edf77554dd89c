"""Every class of bad input the CLI rejects raises ValueError, and its
message is the CLI's one line (after `error: `), naming the field."""

import math
import re

import pytest

import falling_chain as fc
from conftest import cli_error, scene_path

SPAN = scene_path("span-d3")

# (scene, --set KEY=TEXT overrides, CLI flags, keyword flags, field): the
# cases of tests/cli.rs's bad-input test, and a few more.
SIMULATE = [
    ("span-d3", {"chain.length": "2"}, {}, "chain.length"),
    ("span-d3", {"chain.links": "0"}, {}, "chain.links"),
    ("span-d3", {"chain.links": "10.5"}, {}, "chain.links"),
    ("span-d3", {"chain.mass": "-0.2"}, {}, "chain.mass"),
    ("span-d3", {"chain.mass": "nan"}, {}, "chain.mass"),
    ("span-d3", {"chain.damping": "-1e-3"}, {}, "chain.damping"),
    ("span-d3", {"chain.damping": "nan"}, {}, "chain.damping"),
    ("span-d3", {"chain.length": "-6"}, {}, "chain.length"),
    ("span-d3", {"chain.length": "nan"}, {}, "chain.length"),
    ("span-d3", {"chain.gravity": "inf"}, {}, "chain.gravity"),
    ("horizontal-undamped", {"start.p1": "[5.0,0.0]"}, {}, "start.p1"),
    ("span-d3", {"start.kind": "stretched"}, {}, "start.p1"),
    ("span-d3", {"start.kind": "zigzag"}, {}, "start.kind"),
    ("span-d3", {"start.down": "3"}, {}, "start.down"),
    ("span-d3", {"start.p1": "[0.0,3.0]"}, {}, "start.p1"),
    ("span-d3", {"start.p1": "[1.0,"}, {}, "start.p1"),
    ("span-d3", {"start.p1": "[1.0,2.0,3.0]"}, {}, "start.p1"),
    ("span-d3", {"chain.lenght": "6"}, {}, "chain.lenght"),
    ("span-d3", {"start.p1.2": "1"}, {}, "start.p1.2"),
    ("span-d3", {"colour": "1"}, {}, "colour"),
    ("span-d3", {"run.method": "nonesuch"}, {}, "run.method"),
    ("span-d3", {}, {"method": "nonesuch"}, "run.method"),
    ("span-d3", {}, {"dt": 0.0}, "run.dt"),
    ("span-d3", {}, {"t_end": -1.0}, "run.t_end"),
    ("span-d3", {}, {"rtol": -1e-8, "method": "dopri5"}, "run.rtol"),
    ("span-d3", {}, {"atol": math.nan, "method": "dopri5"}, "run.atol"),
    ("span-d3", {"run.output_dt": "0"}, {}, "run.output_dt"),
    ("span-d3", {"run.max_steps": "-1"}, {}, "run.max_steps"),
    ("folded", {"start.down": "60"}, {}, "start.down"),
]
FLAGS = {"method": "--method", "dt": "--dt", "rtol": "--rtol", "atol": "--atol", "t_end": "--t-end"}


@pytest.mark.parametrize("name,sets,flags,field", SIMULATE, ids=lambda c: str(c))
def test_simulate_raises_the_cli_error(name, sets, flags, field):
    args = ["simulate", scene_path(name), "--json"]
    for key, text in sets.items():
        args += ["--set", f"{key}={text}"]
    for key, value in flags.items():
        args.append(f"{FLAGS[key]}={value}")
    want = cli_error(*args)
    # The CLI names a numeric flag the user gave (`--dt: ...`, issue 38),
    # Python the scene key its keyword sets; the rest is the same line.
    flag = next((FLAGS[k] for k in flags if k != "method" and field == "run." + k), None)
    if flag is not None:
        assert want.startswith(flag + ": "), want
        want = field + want[len(flag):]
    assert want.startswith(field + ": ") or field in want, want
    with pytest.raises(ValueError) as e:
        scene = fc.Scene.load(scene_path(name))
        for key, text in sets.items():
            scene = scene.set(key, text)
        fc.simulate(scene, **flags)
    assert str(e.value) == want


@pytest.mark.parametrize(
    "key,value,text",
    [
        ("chain.mass", -0.2, "-0.2"),
        ("chain.mass", math.nan, "nan"),
        ("chain.links", 0, "0"),
        ("chain.links", 10.5, "10.5"),
        ("start.p1", [5.0, 0.0, 1.0], "[5.0,0.0,1.0]"),
        ("start.p1", (0.0, 7.0), "[0.0,7.0]"),
        ("run.t_end", "soon", "soon"),
        ("start.kind", True, "true"),
    ],
)
def test_python_values_fail_as_their_cli_text(span, key, value, text):
    want = cli_error("simulate", SPAN, "--set", f"{key}={text}")
    with pytest.raises(ValueError) as e:
        fc.simulate(span.set(key, value))
    assert str(e.value) == want


def test_check_reports_what_simulate_would(span):
    with pytest.raises(ValueError, match=r"^chain\.length: "):
        span.set("chain.length", 2).check()
    span.check()


def test_scene_files_and_text(tmp_path):
    missing = tmp_path / "no-such-scene.toml"
    want = cli_error("simulate", missing)
    with pytest.raises(ValueError) as e:
        fc.Scene.load(missing)
    assert str(e.value) == want

    text = open(SPAN).read()
    for bad in (
        text.replace("damping = ", 'colour = "red"\ndamping = '),
        text.replace("[run]", "[run\n"),
        text.replace("links = 50", ""),
        text.replace("t_end = 4.157", ""),
        "title = 1\n" + text,
    ):
        path = tmp_path / "bad.toml"
        path.write_text(bad)
        want = cli_error("simulate", path)
        with pytest.raises(ValueError) as e:
            fc.Scene.load(path)
        assert str(e.value) == want
        with pytest.raises(ValueError) as e:
            fc.Scene.from_toml(bad)
        # From text the place is "the scene text" instead of the file's path.
        assert str(e.value) == want.replace(f"'{path}'", "the scene text")


@pytest.mark.parametrize(
    "vary,kwargs,cli_args",
    [
        ({"chain.lenght": [1, 2]}, {}, ["--vary", "chain.lenght=1,2"]),
        ({"start.p1.0": [1.0, 7.0]}, {}, ["--vary", "start.p1.0=1.0,7.0"]),
        ({"chain.links": [10, 10.5]}, {}, ["--vary", "chain.links=10,10.5"]),
        ({"start.p1.0": "1:2"}, {}, ["--vary", "start.p1.0=1:2"]),
        ({"start.p1.0": "1:2:0"}, {}, ["--vary", "start.p1.0=1:2:0"]),
        ({"start.p1.0": [1.0]}, {"shard": "2/2"}, ["--vary", "start.p1.0=1.0", "--shard", "2/2"]),
        ({"start.p1.0": [1.0]}, {"shard": (0, 0)}, ["--vary", "start.p1.0=1.0", "--shard", "0/0"]),
        ({"start.p1.0": [1.0]}, {"method": "nonesuch"}, ["--vary", "start.p1.0=1.0", "--set", "run.method=nonesuch"]),
        ({"start.p1.0": [1.0]}, {"rtol": 0.0}, ["--vary", "start.p1.0=1.0", "--set", "run.rtol=0.0"]),
    ],
)
def test_sweep_raises_the_cli_error(span, vary, kwargs, cli_args):
    # In the keyword's name: the CLI's `--vary: ...` is `vary: ...` here.
    want = re.sub(r"^--([a-z-]+)", lambda m: m[1].replace("-", "_"), cli_error("sweep", SPAN, "--quiet", *cli_args))
    with pytest.raises(ValueError) as e:
        fc.sweep(span, vary, **kwargs)
    assert str(e.value) == want


def test_sweep_needs_keys_and_values(span):
    with pytest.raises(ValueError, match=r"^vary: "):
        fc.sweep(span, {})
    with pytest.raises(ValueError, match=r"^vary: "):
        fc.sweep(span, {"start.p1.0": []})
    with pytest.raises(ValueError, match=r"^jobs: "):
        fc.sweep(span, {"start.p1.0": [1.0]}, jobs=0)


@pytest.mark.parametrize(
    "args,kwargs",
    [
        (["--p1", "5,1", "--length", "4"], dict(p1=(5, 1), length=4)),
        (["--p1", "5,1", "--length", "-6"], dict(p1=(5, 1), length=-6)),
        (["--p1", "5,1", "--length", "nan"], dict(p1=(5, 1), length=math.nan)),
        (["--p1", "5,1", "--length", "6", "--links", "0"], dict(p1=(5, 1), length=6, links=0)),
        (["--p1", "5,1", "--length", "6", "--links", "1"], dict(p1=(5, 1), length=6, links=1)),
        (["--p1", "0,1", "--length", "6"], dict(p1=(0, 1), length=6)),
        (["--p0", "nan,0", "--p1", "5,1", "--length", "6"], dict(p0=(math.nan, 0), p1=(5, 1), length=6)),
    ],
)
def test_catenary_raises_the_cli_error_with_python_names(args, kwargs):
    # The CLI names its flags (--length); Python its parameters (length).
    want = cli_error("catenary", *args)
    assert want.startswith("--")
    kwargs.setdefault("p0", (0, 0))
    with pytest.raises(ValueError) as e:
        fc.catenary(**kwargs)
    assert str(e.value) == want[2:]


def test_catenary_points_are_pairs():
    with pytest.raises(ValueError, match=r"^p1: "):
        fc.catenary((0, 0), (5, "x"), 6)
    with pytest.raises(ValueError, match=r"^p0: "):
        fc.catenary((0, 0, 0), (5, 1), 6)
    with pytest.raises(ValueError, match=r"^links: "):
        fc.catenary((0, 0), (5, 1), 6, links=-2)


def test_wrong_python_types_are_type_errors(span):
    with pytest.raises(TypeError):
        span.set("chain.links", object())
    with pytest.raises(TypeError):
        fc.simulate("scenes/span-d3.toml")
    with pytest.raises(TypeError):
        fc.sweep(span, {"start.p1.0": 3.0})
