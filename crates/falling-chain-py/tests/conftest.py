"""Shared helpers: the repository's paths and the CLI binary the module is
compared with (``FALLING_CHAIN_CLI``, default ``target/release/falling-chain``,
built by ``cargo test --workspace --release``)."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
SCENES = ROOT / "scenes"
CLI = Path(os.environ.get("FALLING_CHAIN_CLI", ROOT / "target" / "release" / "falling-chain"))


def scene_path(name):
    return str(SCENES / f"{name}.toml")


def cli(*args, check=None):
    """Runs the CLI; `check` is the exit code it must return, if given."""
    if not CLI.is_file():
        pytest.fail(
            f"the CLI {CLI} is missing: build it (cargo build --release) "
            "or set FALLING_CHAIN_CLI"
        )
    done = subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True)
    if check is not None:
        assert done.returncode == check, (args, done.returncode, done.stderr)
    return done


def cli_json(*args, check=None):
    return json.loads(cli(*args, check=check).stdout)


def cli_error(*args):
    """The CLI's one-line error for bad input, without its `error: ` prefix."""
    done = cli(*args)
    assert done.returncode == 2, (args, done.returncode, done.stderr)
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1, lines
    assert lines[0].startswith("error: "), lines[0]
    return lines[0][len("error: "):]


def assert_same(a, b, where="", rel=1e-12):
    """Equal JSON-like values: numbers to `rel` relative (and NaN = NaN)."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and list(a) == list(b), (where, list(a), list(b))
        for k in a:
            assert_same(a[k], b[k], f"{where}.{k}", rel)
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), (where, a, b)
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same(x, y, f"{where}[{i}]", rel)
    elif isinstance(a, float) or isinstance(b, float):
        if a != a and b != b:
            return
        assert abs(a - b) <= rel * max(abs(a), abs(b)), (where, a, b)
    else:
        assert a == b and type(a) is type(b), (where, a, b)


@pytest.fixture
def span():
    import falling_chain

    return falling_chain.Scene.load(scene_path("span-d3"))


def best_time(work, repeats=3):
    import time

    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        work()
        times.append(time.perf_counter() - t)
    return min(times)


def in_two_threads(work):
    """Runs `work` in two threads at once; returns when both are done."""
    import threading

    errors = []

    def run():
        try:
            work()
        except BaseException as e:  # noqa: BLE001 - reported below
            errors.append(e)

    threads = [threading.Thread(target=run) for _ in range(2)]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    if errors:
        raise errors[0]


def control_ratio():
    """Two threads' time over one thread's for zlib.compress, which releases
    the GIL: about 1 when the machine has two free cores, about 2 when other
    work leaves this process one core or less."""
    import os
    import zlib

    data = os.urandom(1 << 16) * 96  # 6 MiB, compressible
    def work():
        return zlib.compress(data, 6)

    return best_time(lambda: in_two_threads(work)) / best_time(work)


def require_two_free_cores(ratio, limit):
    """Skips (with the numbers) when `ratio` missed its `limit` and the
    control shows that the machine did not have two free cores (zlib in two
    threads took 1.6x one thread or more), so the ratio says nothing."""
    if ratio < limit:
        return
    control = control_ratio()
    if control >= 1.6:
        pytest.skip(
            f"the machine is busy: even zlib in two threads took {control:.2f}x one thread "
            f"(ours {ratio:.2f}x); no free second core to measure with"
        )


# The address space of a child interpreter: the module and numpy take a few
# hundred MB of it (threads reserve stacks); runs that would take gigabytes
# fail within it.
CHILD_MEMORY = 3 << 30


def cap_memory(memory=CHILD_MEMORY):
    """A preexec_fn that caps a child's address space at `memory` bytes."""
    import resource

    def cap():
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))

    return cap


def in_child(code, timeout=60, memory=CHILD_MEMORY, **popen):
    """Runs `code` in a fresh interpreter (this one's) whose address space
    is capped at `memory` bytes, so that a runaway allocation fails there
    instead of taking the machine. Returns the CompletedProcess (text);
    fails the test if it runs past `timeout`."""
    import sys

    try:
        return subprocess.run(
            [sys.executable, "-c", code],
            capture_output=True,
            text=True,
            timeout=timeout,
            preexec_fn=cap_memory(memory),
            **popen,
        )
    except subprocess.TimeoutExpired as e:
        pytest.fail(f"still running after {timeout} s: {e.stderr!r}"[-2000:])
