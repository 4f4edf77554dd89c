"""The study functions under hostile input (issue 38): an empty `methods`
is refused, and Ctrl-C stops `precision(..., jobs=2)` in every phase (its
reference, the reference's RK4 check, the methods' points) as it stops the
other study functions."""

import pytest

import falling_chain as fc
from conftest import scene_path
from test_interrupt import interrupt

# From SIGINT to KeyboardInterrupt: the study polls for signals every 20 ms
# and its runs look at their cancel flag every step; a liveness bound with
# room for a loaded machine (the reference phase used to take 23-31 s).
BOUND = 1.0


def interrupt_after(setup, work, wait):
    """`test_interrupt.interrupt` with SIGINT `wait` seconds after the work
    started and this module's BOUND."""
    interrupt(setup, work, wait=wait, bound=BOUND)


def test_ctrl_c_stops_precision_in_its_reference():
    # The reference (DOPRI5 at rtol 1e-13) of 50 rods up to t = 10^4: minutes.
    interrupt_after(
        "s = span.set('run.t_end', 1e4)",
        "fc.precision(s, methods='rk4', check_dt=1.0, jobs=2)",
        0.3,
    )


def test_ctrl_c_stops_precision_in_the_reference_check():
    # A reference of milliseconds, then RK4 at 1e-7: 10^7 steps of 20 rods.
    interrupt_after(
        "s = span.set('chain.links', 20).set('run.t_end', 1.0)",
        "fc.precision(s, methods='rk4', check_dt=1e-7, jobs=2)",
        0.3,
    )


def test_ctrl_c_stops_precision_in_the_methods_points():
    # The reference and its checks in under a second, then bdf-dense at 400
    # rods: seconds a point, ten points.
    interrupt_after(
        "s = span.set('chain.links', 400).set('run.t_end', 0.3)",
        "fc.precision(s, methods='bdf-dense', jobs=2)",
        2.0,
    )


@pytest.mark.parametrize("methods", [[], "", ()])
def test_an_empty_methods_list_is_refused(methods):
    scene = fc.Scene.load(scene_path("span-d3")).set("chain.links", 5).set("run.t_end", 0.1)
    calls = [
        lambda: fc.precision(scene, methods=methods),
        lambda: fc.stability(scene, methods=methods),
        lambda: fc.needs(scene, 0.1, methods=methods),
    ]
    for call in calls:
        with pytest.raises(ValueError) as e:
            call()
        message = str(e.value)
        assert message.startswith("methods: names no method"), message
        assert "rk4, dopri5, dop853, bdf, bdf-dense, auto" in message
        assert "\n" not in message


def test_a_check_dt_past_the_step_bound_is_refused():
    scene = fc.Scene.load(scene_path("span-d3"))
    for dt in [1e-300, 4.157e-8]:
        with pytest.raises(ValueError) as e:
            fc.precision(scene, methods="rk4", check_dt=dt, richardson=True)
        assert str(e.value).startswith("check_dt: must be a step in ["), str(e.value)
