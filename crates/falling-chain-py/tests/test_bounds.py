"""No input kills the interpreter: values that go on for ever, nest without
end or ask for too much raise a one-line ValueError naming the key.

Each case runs in a fresh interpreter whose address space is capped
(`in_child`), so that a regression shows as a failed test (a signal, an
abort, a MemoryError) rather than a crash of pytest or a machine out of
memory."""

import pytest

from conftest import in_child, scene_path

SPAN = scene_path("span-d3")


def raises_value_error(code, field, timeout=30):
    """Runs `code` (with `fc`, `np`, `itertools` and `span`, the scene
    span-d3, defined) in a child; it must raise ValueError, whose message is
    one line starting with `field` (or `field.`; `field` may be a tuple of
    the fields accepted), within `timeout` seconds."""
    out = in_child(
        f"""
import itertools
import numpy as np
import falling_chain as fc
span = fc.Scene.load({SPAN!r})
try:
{indent(code)}
except ValueError as e:
    print("ValueError:", repr(str(e)))
else:
    print("no error")
""",
        timeout=timeout,
    )
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    lines = out.stdout.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("ValueError: "), out.stdout[-2000:]
    message = eval(lines[0][len("ValueError: "):])  # the repr printed above
    assert "\n" not in message and "\r" not in message, message
    fields = field if isinstance(field, tuple) else (field,)
    assert any(message.startswith((f + ":", f + ".")) for f in fields), message
    assert len(message) < 1000, message[:1000]
    return message


def indent(code):
    return "\n".join("    " + line for line in code.strip().splitlines())


# Scene values --------------------------------------------------------------


def test_a_list_that_contains_itself():
    m = raises_value_error("a = [1.0]\na.append(a)\nspan.set('start.p1', a)", "start.p1")
    assert "contain itself" in m


def test_a_dict_that_contains_itself():
    m = raises_value_error("d = {'links': 5}\nd['self'] = d\nspan.set('chain', d)", "chain")
    assert "contain itself" in m


def test_a_list_nested_200000_deep():
    raises_value_error(
        "x = 1.0\nfor _ in range(200000):\n    x = [x]\nspan.set('start.angles', x)",
        "start.angles",
    )


def test_text_nested_200000_deep():
    # The TOML parser's own limit, or ours: an error either way, not a crash.
    raises_value_error(
        "span.set('start.p1', '[' * 200000 + ']' * 200000)", "start.p1"
    )


def test_an_endless_iterator_as_a_value():
    m = raises_value_error("span.set('start.angles', itertools.count())", "start.angles")
    assert "1000000" in m


def test_an_endless_iterator_inside_a_value():
    raises_value_error(
        "span.set('start', {'kind': 'angles', 'angles': itertools.repeat(0.5)})",
        "start.angles",
    )


def test_too_long_a_sized_value_fails_before_it_is_read():
    # range(10**15) would take days to read item by item.
    raises_value_error("span.set('start.angles', range(10**15))", "start.angles", timeout=10)


def test_the_longest_list_a_key_takes_still_converts():
    # start.angles at chain.links' cap is a scene value (the scene check
    # then asks for the matching chain.links).
    out = in_child(
        f"""
import numpy as np
import falling_chain as fc
span = fc.Scene.load({SPAN!r})
s = span.set('start', {{'kind': 'angles', 'angles': np.zeros(1_000_000)}})
print(len(s.to_dict()['start']['angles']))
""",
        timeout=60,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["1000000"]


# Sweeps ---------------------------------------------------------------------


def test_an_endless_iterator_as_a_sweep_list():
    raises_value_error("fc.sweep(span, {'start.p1.0': itertools.count(1)})", "start.p1.0")


def test_a_sweep_list_longer_than_a_sweep_fails_before_it_is_read():
    raises_value_error(
        "fc.sweep(span, {'start.p1.0': range(10**14)})", "start.p1.0", timeout=10
    )


def test_a_sweep_grid_too_large_fails_before_it_is_built():
    # Two lists of 1e5: the product (1e10 runs) was built in memory first.
    m = raises_value_error(
        "v = np.linspace(1.0, 5.0, 100000)\n"
        "fc.sweep(span, {'start.p1.0': v, 'chain.damping': v * 1e-3})",
        "vary",
    )
    assert "100000 x 100000" in m


def test_a_sweep_range_of_1e14_values():
    # Needs the i24-cli branch: `--vary` ranges are bounded before they are
    # built (today: "capacity overflow", a panic). A str in `--vary` syntax
    # fails with the CLI's own message, naming the keyword `vary`.
    m = raises_value_error("fc.sweep(span, {'start.p1.0': '1:5:100000000000000'})", "vary")
    assert "1..=1000000" in m


def test_jobs_out_of_range():
    # 100000 threads hung while being spawned; 4000 failed after seconds.
    # All in one child (in this process a regression would hang the suite).
    out = in_child(
        f"""
import falling_chain as fc
span = fc.Scene.load({SPAN!r})
for jobs in (100000, 4000, 257, 0, -1, 10**30):
    try:
        fc.sweep(span, {{"start.p1.0": [2.0]}}, jobs=jobs, method="rk4")
    except ValueError as e:
        print(repr(str(e)), flush=True)
""",
        timeout=20,
    )
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])
    messages = [eval(line) for line in out.stdout.splitlines()]
    assert len(messages) == 6, messages
    for jobs, m in zip(("100000", "4000", "257", "0", "-1", str(10**30)), messages):
        assert m == f"jobs: must be an integer in 1..=256 (got {jobs})", m


def test_jobs_must_be_an_int(span):
    import falling_chain as fc

    for jobs in (2.0, "2", True):
        with pytest.raises(TypeError, match=r"^jobs: "):
            fc.sweep(span, {"start.p1.0": [2.0]}, jobs=jobs)


def test_jobs_above_the_runs_are_fine(span):
    import falling_chain as fc

    got = fc.sweep(span.set("run.t_end", 0.1), {"start.p1.0": [2.0, 3.0]}, jobs=256)
    assert got["status"].tolist() == ["ok", "ok"]


# The CLI's aborts, through the module -----------------------------------------


def test_huge_catenary_links():
    # Needs the i24-cli branch for 10**9 (catenary --links at the scene's
    # cap); 2**64 fits no integer and fails here already.
    raises_value_error("fc.catenary((0, 0), (5, 1), 6, links=2**64)", "links", timeout=10)
    raises_value_error("fc.catenary((0, 0), (5, 1), 6, links=10**9)", "links")


def test_a_sample_buffer_of_gigabytes():
    # Needs the i24-core branch (the output-sample cap).
    raises_value_error("fc.simulate(span, output_dt=1e-9)", "run.output_dt")


def test_bdf_dense_on_a_long_chain():
    # Needs the i24-core branch (bdf-dense's cap on n); it panicked at once
    # at 30000 links (PanicException), and took 6.3 GB at 10000.
    raises_value_error(
        "fc.simulate(span.set('chain.links', 30000), method='bdf-dense', t_end=0.01)",
        ("run.method", "chain.links"),
    )


def test_a_scene_path_of_dev_zero():
    # Needs the i24-cli branch (a scene file is regular and at most 1 MiB):
    # /dev/zero was read to 4.2 GB before "out of memory" (here, with the
    # child's address space capped, to the cap).
    m = raises_value_error("fc.Scene.load('/dev/zero')", "scene")
    assert "memory" not in m, m


# Messages ------------------------------------------------------------------


def test_a_key_with_a_newline_gives_one_line():
    # Needs the i24-cli branch for the ValueErrors (their messages escape
    # control characters); the TypeError is this module's own.
    raises_value_error("span.set('chain.li\\nnks', 5)", "chain.li\\nnks")
    raises_value_error("fc.sweep(span, {'chain.li\\nnks': [5]})", ("chain.li\\nnks", "--vary", "vary"))
    out = in_child(
        "import falling_chain as fc\n"
        f"span = fc.Scene.load({SPAN!r})\n"
        "try:\n    span.set('start.p1\\n', object())\n"
        "except TypeError as e:\n    print(repr(str(e)))\n",
        timeout=30,
    )
    assert out.returncode == 0, out.stderr[-2000:]
    message = eval(out.stdout)
    assert message.startswith("start.p1\\n: ") and "\n" not in message, message


def test_a_long_value_is_not_echoed_whole():
    # Needs the i24-cli branch: an echoed value is cut (a 5-million-element
    # p1 was a 25 MB error line). Past 1000000 items the value is refused
    # before it is read whole, without echoing it.
    raises_value_error("span.set('start.p1', [0.5] * 100000)", "start.p1")
    raises_value_error("span.set('start.p1', np.zeros(5_000_000))", "start.p1")
    raises_value_error("span.set('chain.links', 10**5000)", "chain.links")


def test_scene_text_is_bounded_as_a_scene_file_is(span):
    import falling_chain as fc

    text = span.to_toml()
    with pytest.raises(ValueError, match=r"^scene: .*1048576 bytes"):
        fc.Scene.from_toml(text + "#" * (1 << 20))
    fc.Scene.from_toml(text + "#" * 1000).check()


def test_a_key_and_its_element_in_one_sweep():
    # Needs the i24-cli branch: a key varied twice (here start.p1 and its
    # element start.p1.0) is refused instead of the later one winning.
    raises_value_error(
        "fc.sweep(span, {'start.p1': [[2.0, 0.0]], 'start.p1.0': [3.0, 4.0]})", ("--vary", "vary")
    )


# The run's memory (issue 47 A2) ---------------------------------------------


def test_a_chain_that_cannot_fit_in_memory_is_refused_before_it_runs():
    # bdf at n = 1e6 needs about 8.7 GB; the child's address space is 3 GiB,
    # which the estimate reads (RLIMIT_AS): refused before any allocation,
    # naming the key, the method and both numbers.
    m = raises_value_error(
        "big = span.set('chain.links', 1000000)\nfc.simulate(big, method='bdf', t_end=1e-3)",
        "chain.links",
    )
    assert "for bdf on the rigid chain" in m and "GB is available" in m, m


def test_the_memory_available_may_be_set():
    # FC_MEMORY_AVAILABLE replaces the machine's number: 50 rods refused
    # below the estimate's fixed part, run above it.
    m = raises_value_error(
        "import os\nos.environ['FC_MEMORY_AVAILABLE'] = '1e6'\nfc.simulate(span, method='bdf', t_end=0.01)",
        "chain.links",
    )
    assert "1.0 MB is available (FC_MEMORY_AVAILABLE" in m, m
