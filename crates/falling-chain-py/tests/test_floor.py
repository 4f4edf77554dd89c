"""The floor from Python (issue 50): a chain laid on a constraint floor
carries each joint's share of its weight in `run.floor_forces`, the run's
summary carries moreau-jean's contact statistics, and bad floor input is
the CLI's one line."""

import numpy as np
import pytest

import falling_chain as fc
from conftest import cli_error, scene_path


def test_a_chain_at_rest_on_a_constraint_floor_carries_its_weight_per_joint():
    scene = fc.Scene.load(scene_path("horizontal-undamped"))
    for key, value in [("pivot.release", 0.0), ("floor.law", "constraint"), ("run.output_dt", 0.1)]:
        scene = scene.set(key, value)
    run = fc.simulate(scene, method="moreau-jean", dt=0.01, t_end=0.5)
    assert run.summary["status"] == "ok"
    assert run.summary["contacts_max"] == 26
    f = run.floor_forces
    assert f.shape == (len(run.t), 26, 2)
    # m g = 0.2 at a joint between two rods, half of it at either end.
    want = np.full(26, 0.2)
    want[0] = want[-1] = 0.1
    for k in range(1, len(run.t)):
        assert np.allclose(f[k, :, 1], want, rtol=1e-13, atol=0.0)
        assert np.allclose(f[k, :, 0], 0.0, atol=1e-14)


@pytest.mark.parametrize(
    "key,value",
    [("floor.law", "soft"), ("floor.restitution", 1.5)],
)
def test_bad_floor_input_is_the_clis_one_line(key, value):
    scene = fc.Scene.load(scene_path("span-d3-floor"))
    with pytest.raises(ValueError) as e:
        fc.simulate(scene.set(key, value))
    line = cli_error("simulate", scene_path("span-d3-floor"), "--set", f"{key}={value}")
    assert str(e.value) == line
