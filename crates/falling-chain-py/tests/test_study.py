"""`precision`, `stability`, `needs` and `merge` give the tables of the CLI's
commands of the same names (and `needs --json`), on a small scene."""

import csv
import math
import threading
import time

import numpy as np
import pytest

import falling_chain as fc
from conftest import cli, cli_error, cli_json, scene_path

SMALL = ("--set", "chain.links=10", "--set", "run.t_end=1")
WALL = {"wall_seconds"}


def small():
    return fc.Scene.load(scene_path("span-d3")).set("chain.links", 10).set("run.t_end", 1)


def cli_table(tmp_path, command, *args):
    out = tmp_path / f"{command}.csv"
    done = cli(command, scene_path("span-d3"), *SMALL, "--quiet", "--out", out, *args)
    assert done.returncode in (0, 1), done.stderr
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def assert_table(got, header, rows):
    """The columns are the CSV's, cell for cell (wall times aside)."""
    assert list(got) == header
    for i, name in enumerate(header):
        col = got[name]
        assert isinstance(col, np.ndarray) and col.shape == (len(rows),), name
        assert not col.flags.writeable, name
        if name in WALL:
            continue
        for cell, value in zip((r[i] for r in rows), col.tolist()):
            if isinstance(value, str):
                assert value == cell, (name, cell, value)
            elif cell == "" or cell == "NaN":
                assert math.isnan(value), (name, cell, value)
            else:
                assert value == float(cell), (name, cell, value)


def test_precision_is_the_cli_table(tmp_path):
    header, rows = cli_table(tmp_path, "precision", "--methods", "dopri5,dop853")
    got = fc.precision(small(), methods=["dopri5", "dop853"])
    assert_table(got, header, rows)
    assert got["method"][0] == "reference-dopri5"
    assert got["steps"].dtype == np.int64 and got["err_tip"].dtype == np.float64


def test_precision_measure_is_the_cli_table(tmp_path):
    header, rows = cli_table(
        tmp_path, "precision", "--methods", "dopri5", "--measure", "pivot_force_max,tip"
    )
    got = fc.precision(small(), methods="dopri5", measure=["pivot_force_max", "tip"])
    assert_table(got, header, rows)
    assert "err_pivot_force_max" in got and "pivot_force_max_ref" in got
    with pytest.raises(ValueError) as e:
        fc.precision(small(), measure="floor_force_max")
    assert "measure" in str(e.value) and "pivot_force_max" in str(e.value)


def test_stability_is_the_cli_table(tmp_path):
    header, rows = cli_table(
        tmp_path, "stability", "--methods", "rk4", "--vary", "chain.damping=1,16"
    )
    got = fc.stability(small(), methods="rk4", vary={"chain.damping": [1.0, 16.0]})
    assert_table(got, header, rows)
    assert set(got["outcome"]) == {"completed", "diverged"}


def test_needs_is_the_cli_json():
    args = ("--links", "5,10,20,40", "--tol", "1e-2", "--json", "--quiet")
    want = cli_json("needs", scene_path("span-d3"), *SMALL, *args, check=0)
    got = fc.needs(small(), 1e-2, links=[5, 10, 20, 40])
    assert got["links"] == want["links"] and got["links"] is not None
    assert got["least_work"]["method"] == want["least_work"]["method"]
    assert got["least_work"]["rhs_equiv"] == want["least_work"]["rhs_equiv"]
    assert got["ladder"]["adequate_links"] == want["ladder"]["adequate_links"]
    assert [t["needed"] for t in got["terms"]] == [t["needed"] for t in want["terms"]]


def test_ensemble_is_the_cli_json():
    args = ("--members", "4", "--spread", "1e-4", "--seed", "3", "--json", "--quiet")
    want = cli_json("ensemble", scene_path("span-d3"), *SMALL, *args, check=0)
    got = fc.ensemble(small(), members=4, spread=1e-4, seed=3)
    assert got == want and got["ok"] == 4 and got["failures"] == []
    # Members of one start (spread 0) are one run: no spread at all.
    still = fc.ensemble(small(), members=2, spread=0.0)
    assert all(s["sd"] == 0.0 for s in still["stats"].values())
    assert still["stats"]["tip_speed_max"]["mean"] == fc.simulate(small()).summary["tip_speed_max"]


def test_merge_joins_cli_shards_and_refuses_what_the_cli_refuses(tmp_path):
    for i in range(2):
        cli("stability", scene_path("span-d3"), *SMALL, "--methods", "rk4", "--quiet",
            "--shard", f"{i}/2", "--out", tmp_path / f"s{i}.csv", check=0)
    cli("merge", tmp_path / "s1.csv", tmp_path / "s0.csv", "--out", tmp_path / "all.csv", check=0)
    with open(tmp_path / "all.csv", newline="") as f:
        rows = list(csv.reader(f))
    got = fc.merge([tmp_path / "s0.csv", tmp_path / "s1.csv"])
    assert_table(got, rows[0], rows[1:])
    assert got["run"].tolist() == list(range(8))
    want = cli_error("merge", tmp_path / "s0.csv", "--out", tmp_path / "x.csv")
    with pytest.raises(ValueError) as e:
        fc.merge([tmp_path / "s0.csv"])
    assert str(e.value) == want and want.startswith("merge: runs 1, 3, 5, 7 are missing")


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda s: fc.precision(s, budget=-1.0), "budget"),
        (lambda s: fc.precision(s, methods="rk5"), "methods"),
        (lambda s: fc.precision(s, check_dt=0.0), "check_dt"),
        (lambda s: fc.precision(s, shard="2/2"), "shard"),
        (lambda s: fc.stability(s, vary={"chain.damping": [0.0], "chain.mass": [1.0]}), "vary"),
        (lambda s: fc.needs(s, 2.0), "tol"),
        (lambda s: fc.needs(s, 0.1, links=[7]), "links"),
        (lambda s: fc.ensemble(s, members=1), "members"),
        (lambda s: fc.ensemble(s, spread=0.5), "spread"),
    ],
)
def test_bad_input_is_a_value_error_naming_the_argument(call, field):
    with pytest.raises(ValueError) as e:
        call(small())
    assert str(e.value).startswith(f"{field}: ") and "\n" not in str(e.value), str(e.value)


def test_a_study_runs_while_python_runs():
    scene = fc.Scene.load(scene_path("span-d3")).set("chain.links", 40)
    result = {}
    worker = threading.Thread(target=lambda: result.update(fc.precision(scene, methods="rk4")))
    count = 0
    worker.start()
    time.sleep(0.01)
    while worker.is_alive():
        count += 1
    assert count > 1000 and "err_tip" in result, count
