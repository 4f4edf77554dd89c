"""Ctrl-C stops a long `simulate` or `sweep`: SIGINT raises KeyboardInterrupt
within a second or two (a liveness bound, not a benchmark), and the
interpreter goes on, and exits, cleanly."""

import signal
import subprocess
import sys
import time

import pytest

from conftest import cap_memory, scene_path

CHILD = """
import signal, sys, time
# Python's own handler, even if this process was started with SIGINT
# ignored (as a background job of a shell is).
signal.signal(signal.SIGINT, signal.default_int_handler)
import numpy as np
import falling_chain as fc
span = fc.Scene.load({span!r})
{setup}
print("started", flush=True)
start = time.monotonic()
try:
    {work}
except KeyboardInterrupt:
    caught = time.monotonic()
    print("interrupted", start, caught, flush=True)
else:
    print("finished", flush=True)
    sys.exit(3)
# The module still works after an interrupted call.
print("after", fc.simulate(span, t_end=0.05).status, flush=True)
"""

# The liveness bound: from SIGINT to KeyboardInterrupt.
BOUND = 2.0
# How long the work runs before SIGINT.
WAIT = 0.3


def interrupt(setup, work, wait=WAIT, bound=BOUND):
    """Runs `work` in a child, sends SIGINT after `wait` seconds, and checks
    that KeyboardInterrupt came within `bound` seconds and that the child
    then ran one more simulation and exited with 0."""
    code = CHILD.format(span=scene_path("span-d3"), setup=setup, work=work)
    child = subprocess.Popen(
        [sys.executable, "-c", code],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=cap_memory(),
    )
    try:
        assert child.stdout.readline() == "started\n", child.communicate(timeout=30)
        time.sleep(wait)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        try:
            out, err = child.communicate(timeout=bound + 20)
        except subprocess.TimeoutExpired:
            pytest.fail(f"no KeyboardInterrupt {bound + 20} s after SIGINT")
    finally:
        if child.poll() is None:
            child.kill()
            child.communicate()
    lines = out.splitlines()
    assert child.returncode == 0, (child.returncode, out, err[-2000:])
    assert len(lines) == 2 and lines[1] == "after ok", (out, err[-2000:])
    word, start, caught = lines[0].split()
    assert word == "interrupted"
    # time.monotonic is one clock for every process on Linux.
    start, caught = float(start), float(caught)
    assert sent - start > 0.5 * wait, "SIGINT came before the work had started"
    assert caught - sent < bound, f"KeyboardInterrupt {caught - sent:.2f} s after SIGINT"
    assert "panicked" not in err, err[-2000:]


# A run of many minutes: 100 rods, RK4 at dt = 1e-4 up to t = 10000.
LONG = (
    "long = span.set('chain.links', 100).set('run.method', 'rk4').set('run.dt', 1e-4)"
    ".set('run.t_end', 1e4).set('run.output_dt', 1.0)"
)


def test_ctrl_c_stops_a_long_simulate():
    # Needs the i24-core branch: the integrators stop when the run's Cancel
    # flag is set (status interrupted).
    interrupt(LONG, "fc.simulate(long)")


def test_ctrl_c_stops_a_sweep_of_long_runs():
    # Needs the i24-core branch (each run stops at its next step) and the
    # i24-cli branch (the sweep takes the Cancel flag).
    interrupt(LONG, "fc.sweep(long, {'start.p1.0': [2.0, 3.0, 4.0, 5.0]}, jobs=2)")


def test_ctrl_c_stops_a_sweep_of_many_short_runs():
    # Needs the i24-cli branch (no run starts once the flag is set).
    interrupt(
        "short = span.set('chain.links', 20).set('run.method', 'rk4').set('run.dt', 1e-3).set('run.t_end', 2)",
        "fc.sweep(short, {'start.p1.0': np.linspace(1.5, 5.5, 5000)}, jobs=2)",
    )


def test_ctrl_c_during_the_check_of_a_large_sweep():
    # Needs falling-chain's sweep to look at the Cancel flag while it checks
    # every run's scene (a grid of 10^6 runs takes ~15 s to check here):
    # asked of the i24-cli branch.
    # The values in `--vary` syntax: read in Rust at once, so that SIGINT
    # comes while the scenes are checked, not while values are converted.
    interrupt("", "fc.sweep(span, {'start.p1.0': '1.5:5.5:1000000'}, jobs=2)")
