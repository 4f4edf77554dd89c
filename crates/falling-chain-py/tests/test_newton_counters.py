"""The implicit methods' work counters in `run.summary`: rejections by cause
(`error_test_failures`, `newton_failures`) and `newton_iterations`, as
`simulate --json` prints them. Checked against what the counts mean, not
against numbers a run printed before."""

import pytest

import falling_chain as fc
from conftest import scene_path

COUNTERS = ("error_test_failures", "newton_failures", "newton_iterations")


def stiff_rope(t_end):
    return fc.Scene.load(scene_path("stiff-rope")).set("run.t_end", t_end)


@pytest.mark.parametrize("method", ["bdf", "bdf-dense"])
def test_the_implicit_methods_count_their_newton_work(method):
    s = fc.simulate(stiff_rope(0.5), method=method).summary
    assert s["status"] == "ok"
    assert all(isinstance(s[k], int) for k in COUNTERS)
    # Every attempt, accepted or failed, runs at least one Newton iteration.
    assert s["newton_iterations"] >= s["steps"] + s["newton_failures"] + s["error_test_failures"]
    assert s["steps"] > 0
    # A rejected attempt failed either its error test or its Newton iteration.
    assert s["rejected_steps"] == s["error_test_failures"] + s["newton_failures"]


@pytest.mark.parametrize("method", ["rk4", "dopri5", "dop853"])
def test_the_explicit_methods_count_no_newton_work(method):
    s = fc.simulate(stiff_rope(0.002), method=method, dt=1e-5).summary
    assert s["status"] == "ok"
    assert s["steps"] > 0
    assert [s[k] for k in COUNTERS] == [0, 0, 0]
