"""`sweep` gives the rows of `falling-chain sweep --out`, as numpy columns."""

import csv

import numpy as np
import pytest

import falling_chain as fc
from conftest import best_time, cli, require_two_free_cores, scene_path

INT = {"run", "links", "steps", "rejected_steps", "rhs_evals", "jacobian_evals",
       "lu_factorizations", "stiffness_detections", "runs"}
TEXT = {"name", "status", "method", "segments", "scene_hash"}
WALL = {"wall_seconds"}


def cli_sweep(tmp_path, *args):
    out = tmp_path / "sweep.csv"
    done = cli("sweep", scene_path("span-d3"), "--quiet", "--out", out, *args)
    assert done.returncode in (0, 1), done.stderr
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def assert_columns_are_the_csv(got, header, rows, ints=(), texts=()):
    """`ints` and `texts` name the varied keys of those kinds (others are numbers)."""
    assert list(got) == header
    for i, name in enumerate(header):
        col, cells = got[name], [r[i] for r in rows]
        assert isinstance(col, np.ndarray) and col.shape == (len(rows),), name
        assert not col.flags.writeable, name
        if name in WALL:
            assert col.dtype == np.float64
        elif name in INT or name in ints:
            assert col.dtype == np.int64, name
            assert col.tolist() == [int(c) for c in cells], name
        elif name in TEXT or name in texts:
            assert col.dtype.kind == "U", name
            assert col.tolist() == cells, name
        else:
            assert col.dtype == np.float64, name
            want = np.array([float(c) if c else np.nan for c in cells])
            np.testing.assert_array_equal(col, want, err_msg=name)


def test_a_product_sweep_is_the_cli_csv(span, tmp_path):
    header, rows = cli_sweep(
        tmp_path,
        "--vary", "start.p1.0=1.5,3.0,4.5",
        "--vary", "chain.links=20,30",
        "--set", "run.method=dopri5", "--set", "run.rtol=1e-7", "--set", "run.t_end=3",
    )
    got = fc.sweep(
        span.set("run.t_end", 3),
        {"start.p1.0": np.array([1.5, 3.0, 4.5]), "chain.links": [20, 30]},
        method="dopri5",
        rtol=1e-7,
    )
    assert len(rows) == 6
    assert_columns_are_the_csv(got, header, rows, ints=["chain.links"])
    assert got["run"].tolist() == list(range(6))
    assert got["chain.links"].tolist() == [20, 30] * 3
    assert got["start.p1.0"].tolist() == [1.5, 1.5, 3.0, 3.0, 4.5, 4.5]


def test_ranges_in_cli_syntax_and_shards(span, tmp_path):
    header, rows = cli_sweep(
        tmp_path,
        "--vary", "start.p1.0=2:5:7", "--shard", "1/3",
        "--set", "run.method=rk4", "--set", "run.t_end=2",
    )
    got = fc.sweep(span.set("run.t_end", 2), {"start.p1.0": "2:5:7"}, method="rk4", shard=(1, 3))
    assert got["run"].tolist() == [1, 4]
    assert_columns_are_the_csv(got, header, rows)


def test_failed_runs_are_rows_with_their_status(span, tmp_path):
    # RK4 at dt = 0.01 (the scene runs DOPRI5) diverges at r = 0.1.
    header, rows = cli_sweep(
        tmp_path, "--vary", "chain.damping=0.0005,0.1", "--set", "run.method=rk4",
    )
    got = fc.sweep(span.set("run.method", "rk4"), {"chain.damping": [0.0005, 0.1]})
    assert_columns_are_the_csv(got, header, rows)
    assert got["status"].tolist() == ["ok", "diverged"]
    assert np.isnan(got["t_failed"][0]) and got["t_failed"][1] > 0


def test_text_values_vary_too(span, tmp_path):
    header, rows = cli_sweep(
        tmp_path, "--vary", "run.method=rk4,dopri5,dop853", "--set", "run.t_end=1",
    )
    got = fc.sweep(span.set("run.t_end", 1), {"run.method": ["rk4", "dopri5", "dop853"]})
    assert_columns_are_the_csv(got, header, rows, texts=["run.method"])
    assert got["run.method"].tolist() == got["method"].tolist() == ["rk4", "dopri5", "dop853"]


def test_the_sweep_runs_in_parallel(span):
    scene = span.set("run.method", "rk4").set("run.dt", 0.002)
    vary = {"start.p1.0": np.linspace(1.5, 5.5, 16)}
    fc.sweep(scene, vary, jobs=2)  # warm up
    # Up to three measurements, keeping the best ratio: on a shared
    # machine one measurement of 0.16 s can catch a core slowed for a
    # moment (seen once at 0.81 with the control below 1.6, against
    # 0.45-0.65 on ten others).
    best = None
    for _ in range(3):
        one = best_time(lambda: fc.sweep(scene, vary, jobs=1))
        two = best_time(lambda: fc.sweep(scene, vary, jobs=2))
        if best is None or two / one < best[1] / best[0]:
            best = (one, two)
        if two < 0.8 * one:
            break
    one, two = best
    require_two_free_cores(two / one, 0.8)
    assert two < 0.8 * one, (one, two)
