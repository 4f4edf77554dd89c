"""A released pivot (issue 18): the run's joints start from where the pivot
is at each sample, not from the start's anchor; both ends let go at rest
fall together at g (the tip and the pivot drop g t^2 / 2)."""

import numpy as np

import falling_chain as fc
from conftest import scene_path


def test_both_ends_let_go_joints_follow_the_falling_pivot():
    run = fc.simulate(fc.Scene.load(scene_path("both-ends-let-go")))
    assert run.status == "ok"
    t = run.t[-1]
    joints = run.joints(-1)
    first = run.joints(0)
    # Every joint has fallen g t^2 / 2 (g = 1) and kept its x.
    np.testing.assert_allclose(joints[:, 0], first[:, 0], atol=1e-9)
    np.testing.assert_allclose(joints[:, 1], first[:, 1] - 0.5 * t * t, atol=1e-9)
    # The tip array agrees with the last joint.
    np.testing.assert_allclose(run.tip[-1], joints[-1], atol=1e-12)
