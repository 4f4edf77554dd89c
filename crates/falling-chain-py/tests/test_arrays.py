"""The run's arrays: shapes, dtypes, and the very numbers of `--out`'s CSV."""

import csv

import numpy as np
import pytest

import falling_chain as fc
from conftest import cli, scene_path

ARRAYS = {
    "t": lambda s, n: (s,),
    "phi": lambda s, n: (s, n),
    "w": lambda s, n: (s, n),
    "tip": lambda s, n: (s, 2),
    "tip_velocity": lambda s, n: (s, 2),
    "energy": lambda s, n: (s,),
    "dissipated": lambda s, n: (s,),
    "forces": lambda s, n: (s, n + 1, 2),
}


def test_shapes_and_dtypes(span):
    run = fc.simulate(span, method="dopri5", output_dt=0.05)
    samples, n = len(run), run.links
    assert n == 50
    assert samples == len(run.t) == 85  # 4.157 / 0.05 -> 0, 0.05, ..., 4.15, then 4.157
    for name, shape in ARRAYS.items():
        a = getattr(run, name)
        assert isinstance(a, np.ndarray), name
        assert a.dtype == np.float64, name
        assert a.shape == shape(samples, n), name
        assert a.flags.c_contiguous and not a.flags.writeable, name
        assert np.isfinite(a).all(), name
        assert getattr(run, name) is a, "the same array each time, not a copy"
    for k in (0, 7, samples - 1, -1):
        j = run.joints(k)
        assert j.dtype == np.float64 and j.shape == (n + 1, 2)
        np.testing.assert_array_equal(j[0], [0.0, 0.0])
        np.testing.assert_allclose(j[-1], run.tip[k], rtol=0, atol=1e-12)
        np.testing.assert_allclose(np.hypot(*np.diff(j, axis=0).T), 6.0 / n, rtol=1e-12)
    for k in (samples, -samples - 1):
        with pytest.raises(IndexError):
            run.joints(k)
    assert np.all(np.diff(run.t) > 0) and run.t[0] == 0.0 and run.t[-1] == 4.157


def test_the_arrays_are_the_csv(span, tmp_path):
    out = tmp_path / "run.csv"
    cli("simulate", scene_path("span-d3"), "--method", "dop853", "--out", out, check=0)
    run = fc.simulate(span, method="dop853")
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    header, cells = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    col = {name: cells[:, i] for i, name in enumerate(header)}
    assert cells.shape == (len(run), 7 + run.links)
    # Bit for bit: the CSV's numbers round-trip.
    np.testing.assert_array_equal(run.t, col["t"])
    np.testing.assert_array_equal(run.tip, np.column_stack([col["tip_x"], col["tip_y"]]))
    np.testing.assert_array_equal(
        run.tip_velocity, np.column_stack([col["tip_vx"], col["tip_vy"]])
    )
    np.testing.assert_array_equal(run.energy, col["energy"])
    np.testing.assert_array_equal(run.dissipated, col["dissipated"])
    np.testing.assert_array_equal(run.phi, cells[:, 7:])


def test_rates_give_the_tip_velocity(span):
    # w is not in the CSV: check it against the tip velocity it implies,
    # v_tip = l sum_i w_i (-sin phi_i, cos phi_i).
    run = fc.simulate(span, method="dopri5")
    l = 6.0 / run.links
    v = l * np.stack(
        [-(run.w * np.sin(run.phi)).sum(axis=1), (run.w * np.cos(run.phi)).sum(axis=1)], axis=1
    )
    np.testing.assert_allclose(v, run.tip_velocity, rtol=0, atol=1e-12 * np.abs(v).max())
    # And the energy balance the summary reports holds on the samples.
    drift = np.abs(run.energy + run.dissipated - run.energy[0]).max()
    assert drift <= run.summary["energy_balance_error"] * (1 + 1e-9)


def test_a_failed_run_keeps_what_it_computed(span, tmp_path):
    out = tmp_path / "diverged.csv"
    cli(
        "simulate", scene_path("span-d3"), "--set", "chain.damping=0.1",
        "--method", "rk4", "--dt", "0.01", "--t-end", "20", "--out", out, check=1,
    )
    run = fc.simulate(span.set("chain.damping", 0.1), method="rk4", dt=0.01, t_end=20.0)
    assert run.status == "diverged"
    csv_t = np.loadtxt(out, delimiter=",", skiprows=1, usecols=0)
    np.testing.assert_array_equal(run.t, csv_t)
    assert all(np.isfinite(getattr(run, name)).all() for name in ARRAYS)


def forces_csv(tmp_path, *args):
    out = tmp_path / "forces.csv"
    cli("simulate", scene_path("span-d3"), *args, "--forces", out, check=0)
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


ELASTIC = {
    "chain.links": 12,
    "chain.axial_stiffness": 2e3,
    "chain.axial_damping": 0.01,
    "chain.bending_stiffness": 0.01,
}


@pytest.mark.parametrize("elastic", [False, True])
def test_forces_are_the_csv_of_forces(span, tmp_path, elastic):
    scene, args = span, ["--method", "dopri5", "--t-end", "0.5"]
    if elastic:
        for key, value in ELASTIC.items():
            scene = scene.set(key, value)
            args += ["--set", f"{key}={value}"]
    run = fc.simulate(scene, method="dopri5", t_end=0.5)
    n = run.links
    assert run.forces.shape == (len(run), n + 1, 2)
    assert run.forces.dtype == np.float64 and not run.forces.flags.writeable
    header, cells = forces_csv(tmp_path, *args)
    assert header[:3] == ["t", "tension_0", "shear_0"] and len(header) == 1 + 2 * (n + 1)
    np.testing.assert_array_equal(run.t, cells[:, 0])
    np.testing.assert_array_equal(run.forces.reshape(len(run), -1), cells[:, 1:])
    # The free tip carries nothing.
    assert (run.forces[:, -1, :] == 0.0).all()


def test_floor_forces_are_the_csv_of_forces(tmp_path):
    scene = fc.Scene.load(scene_path("cayley-scale")).set("chain.links", 8).set(
        "chain.mass", 0.125
    )
    angles = [-1.550796326795 if i % 2 == 0 else -1.590796326795 for i in range(8)]
    scene = scene.set("start.angles", angles)
    run = fc.simulate(scene, method="bdf", t_end=1.2, output_dt=0.1)
    n = run.links
    f = run.floor_forces
    assert f.shape == (len(run), n + 1, 2) and f.dtype == np.float64
    assert not f.flags.writeable and run.floor_forces is f
    out = tmp_path / "forces.csv"
    args = ["--set", "chain.links=8", "--set", "chain.mass=0.125", "--set"]
    args += ["start.angles=[" + ",".join(str(a) for a in angles) + "]"]
    cli("simulate", scene_path("cayley-scale"), *args, "--method", "bdf", "--t-end", "1.2",
        "--set", "run.output_dt=0.1", "--forces", out, check=0)
    with open(out, newline="") as fh:
        rows = list(csv.reader(fh))
    header, cells = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    assert len(header) == 1 + 4 * (n + 1) + 2
    assert header[-2:] == ["floor_x", "floor_y"] and header[1 + 2 * (n + 1)] == "floor_x_0"
    np.testing.assert_array_equal(run.t, cells[:, 0])
    joints = cells[:, 1 + 2 * (n + 1) : -2]
    np.testing.assert_array_equal(f.reshape(len(run), -1), joints)
    np.testing.assert_allclose(f.sum(axis=1), cells[:, -2:], rtol=1e-12, atol=1e-12)
    # The floor pushes, never pulls; the summary's peak is the run's, taken
    # at every step (issue 47 W1), so no sample's total is above it (here
    # the samples, 0.1 apart, miss the impacts' peaks altogether).
    assert (f[:, :, 1] >= 0.0).all()
    s = run.summary
    assert s["floor_force_max"] >= f[:, :, 1].sum(axis=1).max()
    assert 0.0 <= s["t_floor_force_max"] <= 1.2


def test_a_run_without_a_floor_has_no_floor_forces(span):
    assert fc.simulate(span, method="dopri5", t_end=0.2).floor_forces is None


def test_an_elastic_run_has_its_own_joints_tip_and_energy(span):
    scene = span
    for key, value in ELASTIC.items():
        scene = scene.set(key, value)
    run = fc.simulate(scene, method="dopri5", t_end=0.5, output_dt=0.05)
    for k in (0, 5, -1):
        j = run.joints(k)
        assert j.shape == (run.links + 1, 2)
        np.testing.assert_array_equal(j[0], [0.0, 0.0])
        np.testing.assert_array_equal(j[-1], run.tip[k])
    # The elastic energy (with the springs' stretch) balances the work.
    drift = np.abs(run.energy + run.dissipated - run.energy[0]).max()
    assert drift <= run.summary["energy_balance_error"] * (1 + 1e-9) + 1e-12
    assert drift < 1e-5 * abs(run.energy[0])
