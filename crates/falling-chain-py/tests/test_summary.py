"""`run.summary` is `simulate --json` for the same scene and flags, field by
field (every field but the wall time), on several scenes and methods."""

import pytest

import falling_chain as fc
from conftest import assert_same, cli_json, scene_path

WALL = {"wall_seconds"}

# (scene, --set overrides, keyword flags): every method, failing runs too.
CASES = [
    ("span-d3", {}, {}),
    ("span-d3", {}, {"method": "dopri5", "rtol": 1e-10, "t_end": 8.0}),
    ("span-d3", {"chain.links": 30, "start.p1": [2.5, 0.0]}, {"method": "dop853"}),
    ("span-d1", {}, {"t_end": 3.0}),
    ("folded", {}, {"atol": 1e-12}),
    ("height-h2", {}, {"method": "rk4", "dt": 0.005, "t_end": 2.0}),
    ("horizontal-damped", {}, {"method": "auto", "rtol": 1e-6}),
    ("stiff-rope", {}, {"method": "bdf", "t_end": 0.5}),
    ("catenary-fall", {"chain.links": 12}, {"method": "bdf-dense", "t_end": 1.0}),
    # The constraint floor, stepped over by moreau-jean (its contact
    # statistics in the summary) and by auto, which runs it.
    ("span-d3-floor", {"floor.law": "constraint"}, {"method": "moreau-jean", "dt": 0.005}),
    ("span-d3-floor", {"floor.law": "constraint"}, {"method": "auto", "dt": 0.01, "t_end": 2.0}),
    # Diverges (RK4 far beyond its stability limit): exit 1, status diverged.
    ("span-d3", {"chain.damping": 0.1}, {"dt": 0.01, "t_end": 20.0}),
    # Runs out of its step budget: status max_steps.
    ("span-d3", {"run.max_steps": 50}, {"method": "dopri5"}),
]

FLAGS = {"method": "--method", "dt": "--dt", "rtol": "--rtol", "atol": "--atol", "t_end": "--t-end"}


def set_arg(key, value):
    text = "[" + ",".join(repr(float(x)) for x in value) + "]" if isinstance(value, list) else str(value)
    return ["--set", f"{key}={text}"]


@pytest.mark.parametrize("name,sets,flags", CASES, ids=lambda c: str(c))
def test_summary_is_the_cli_json(name, sets, flags):
    args = ["simulate", scene_path(name), "--json"]
    scene = fc.Scene.load(scene_path(name))
    for key, value in sets.items():
        args += set_arg(key, value)
        scene = scene.set(key, value)
    for key, value in flags.items():
        args.append(f"{FLAGS[key]}={value}")
    want = cli_json(*args)
    run = fc.simulate(scene, **flags)
    got = dict(run.summary)
    for key in WALL:
        assert isinstance(got.pop(key), float)
        want.pop(key)
    assert list(got) == list(want)
    assert_same(got, want)
    assert run.status == want["status"]


def test_a_failed_run_returns_its_run():
    scene = fc.Scene.load(scene_path("span-d3")).set("chain.damping", 0.1)
    run = fc.simulate(scene, method="rk4", dt=0.01, t_end=20.0)
    assert run.summary["status"] == "diverged"
    assert run.summary["t_reached"] < 20.0
    assert run.summary["t_failed"] > run.summary["t_reached"]
    assert run.t[-1] == run.summary["t_reached"]


def test_flags_come_after_sets_as_in_the_cli():
    scene = fc.Scene.load(scene_path("span-d3")).set("run.method", "rk4").set("run.t_end", 1)
    run = fc.simulate(scene, method="dopri5", t_end=0.5)
    assert run.summary["method"] == "dopri5"
    assert run.summary["t_end"] == 0.5
    assert run.scene.to_dict()["run"]["method"] == "dopri5"


@pytest.mark.parametrize(
    "sets,model",
    [({}, "rigid"), ({"chain.axial_stiffness": 1e5}, "elastic"), ({"model.report": True}, "report")],
)
def test_the_summary_says_which_model_ran(sets, model):
    scene = fc.Scene.load(scene_path("span-d3"))
    for key, value in sets.items():
        scene = scene.set(key, value)
    run = fc.simulate(scene, t_end=0.2)
    assert run.summary["model"] == model
