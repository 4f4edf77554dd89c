"""Runs release the GIL: Python threads go on while a simulation runs, and two
threads run two simulations at once."""

import threading
import time

import falling_chain as fc
from conftest import best_time, in_two_threads, require_two_free_cores, scene_path


def long_run():
    """Fixed-step RK4 (the same work every time), about 0.3-0.5 s alone here."""
    scene = fc.Scene.load(scene_path("span-d3")).set("chain.links", 100)
    return lambda: fc.simulate(scene, method="rk4", dt=2e-4, t_end=5.5)


def test_python_runs_while_a_simulation_runs():
    # With the GIL held for the whole solve, this thread could not count.
    run = long_run()
    done = threading.Event()
    worker = threading.Thread(target=lambda: (run(), done.set()))
    count = 0
    worker.start()
    time.sleep(0.01)
    while not done.is_set():
        count += 1
    worker.join()
    assert count > 1000, count


def test_a_sweep_runs_while_python_runs():
    scene = fc.Scene.load(scene_path("span-d3")).set("run.dt", 0.002)
    result = {}
    worker = threading.Thread(
        target=lambda: result.update(fc.sweep(scene, {"start.p1.0": [2.0, 3.0, 4.0, 5.0]}))
    )
    count = 0
    worker.start()
    time.sleep(0.01)
    while worker.is_alive():
        count += 1
    assert count > 1000 and list(result["status"]) == ["ok"] * 4, count


def test_two_threads_take_clearly_less_than_twice_one():
    run = long_run()
    run()  # warm up
    # Interleaved, best of three: the machine may be busy with other work.
    t1 = best_time(run)
    t2 = best_time(lambda: in_two_threads(run))
    assert 0.05 < t1 < 5.0, t1
    require_two_free_cores(t2 / t1, 1.6)
    assert t2 < 1.6 * t1, (t1, t2)
