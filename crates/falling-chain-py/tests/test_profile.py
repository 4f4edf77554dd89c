"""Per-rod profiles from Python (issue 18: ``chain.taper``,
``chain.rod_masses``, ``chain.rod_lengths``): lists set as Python lists
(or numpy arrays), each rod's length and mass on the ``Run``
(``rod_lengths``, ``rod_masses``), ``Run.joints`` built from each rod's
own length, and the viewer's page drawing the run's own rods."""

import json

import numpy as np
import pytest

import falling_chain as fc
from conftest import cli, scene_path

LENGTHS = [4.0, 3.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 3.0, 4.0]
MASSES = [1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 2.0, 2.0, 1.0, 1.0]


def listed(t_end=1.0):
    """span-d3 cut into 10 rods of the lengths and masses above."""
    return (
        fc.Scene.load(scene_path("span-d3"))
        .set("chain.links", 10)
        .set("chain.rod_lengths", LENGTHS)
        .set("chain.rod_masses", np.array(MASSES))
        .set("run.t_end", t_end)
    )


def page_data(text):
    open_tag = '<script id="fc-data" type="application/json">'
    start = text.index(open_tag) + len(open_tag)
    return json.loads(text[start : text.index("</script>", start)])


def test_lists_set_from_python_give_each_rods_length_and_mass():
    scene = listed()
    assert scene.to_dict()["chain"]["rod_lengths"] == LENGTHS
    run = fc.simulate(scene)
    assert run.status == "ok"
    # L = 6 and n m = 10 x 0.2 shared in proportion to the lists.
    lengths = np.array(LENGTHS) * 6.0 / sum(LENGTHS)
    masses = np.array(MASSES) * 2.0 / sum(MASSES)
    assert np.allclose(run.rod_lengths, lengths, rtol=1e-14, atol=0)
    assert np.allclose(run.rod_masses, masses, rtol=1e-14, atol=0)
    assert run.rod_lengths.shape == run.rod_masses.shape == (10,)
    # Equal rods: L / n and the scene's rod mass each.
    plain = fc.simulate(fc.Scene.load(scene_path("span-d3")), t_end=0.1)
    assert np.all(plain.rod_lengths == 6.0 / 50) and np.all(plain.rod_masses == 0.2)


def test_a_taper_shares_the_mass_linearly():
    run = fc.simulate(fc.Scene.load(scene_path("tapered-whip")).set("chain.links", 8), t_end=0.1)
    # rho at the midpoints, 10 - 9 (i + 1/2) / 8, of mean 5.5; total mass 8 x 0.2.
    want = np.array([10 - 9 * (i + 0.5) / 8 for i in range(8)]) / 5.5 * 0.2
    assert np.allclose(run.rod_masses, want, rtol=1e-13, atol=0)
    assert np.all(run.rod_lengths == 6.0 / 8)


def test_joints_of_unequal_rods_follow_each_rods_length():
    run = fc.simulate(listed())
    for k in (0, len(run) // 2, -1):
        r = run.joints(k)
        assert r.shape == (11, 2)
        steps = np.hypot(*np.diff(r, axis=0).T)
        assert np.allclose(steps, run.rod_lengths, rtol=1e-12, atol=0), k
        assert np.allclose(r[-1], run.tip[k], rtol=0, atol=1e-12), k
    # The start is the catenary of these rods to P1 = (3, 0).
    assert np.allclose(run.joints(0)[-1], [3.0, 0.0], rtol=0, atol=1e-11)


def test_a_bad_list_raises_naming_its_key():
    with pytest.raises(ValueError, match=r"^chain\.rod_lengths: .*chain\.links = 50"):
        fc.Scene.load(scene_path("span-d3")).set("chain.rod_lengths", [1.0, 2.0]).check()
    with pytest.raises(ValueError, match=r"^chain\.rod_masses: .*> 0"):
        listed().set("chain.rod_masses", [1.0] * 9 + [-1.0]).check()


def test_the_page_of_unequal_rods_holds_their_lengths_and_is_the_clis(tmp_path):
    run = fc.simulate(listed())
    data = page_data(fc.view(run, tmp_path / "rods.html").read_text())
    (r,) = data["runs"]
    # The page's rods: 7 digits of each length, 3 of each density.
    assert np.allclose(r["rod_lengths"], run.rod_lengths, rtol=1e-6, atol=0)
    density = (run.rod_masses / run.rod_lengths) / (2.0 / 6.0)
    assert np.allclose(r["density"], density, rtol=5e-3, atol=0)
    # The tip the page builds, P0 + sum l_i (cos, sin), is the run's tip.
    phi = np.array(r["phi"]).reshape(-1, 10)
    tips = np.stack([np.cos(phi) @ r["rod_lengths"], np.sin(phi) @ r["rod_lengths"]], axis=1)
    assert np.abs(tips - run.tip).max() < 6e-6
    # And the CLI's page of the scene holds the same rods.
    scene_file = tmp_path / "rods.toml"
    scene_file.write_text(listed().to_toml())
    cli("view", scene_file, "-o", tmp_path / "cli.html", check=0)
    theirs = page_data((tmp_path / "cli.html").read_text())["runs"][0]
    assert theirs["rod_lengths"] == r["rod_lengths"] and theirs["density"] == r["density"]
    # Equal rods hold neither.
    plain = page_data(fc.view(fc.simulate(fc.Scene.load(scene_path("span-d3")), t_end=0.1),
                              tmp_path / "plain.html").read_text())["runs"][0]
    assert plain["rod_lengths"] is None and plain["density"] is None


def test_view_refuses_more_unequal_rods_than_a_page_holds(tmp_path):
    scene = fc.Scene.load(scene_path("tapered-whip")).set("chain.links", 5001)
    run = fc.simulate(scene, t_end=1e-3, output_dt=1e-3)
    with pytest.raises(ValueError, match=r"^runs: .*5000 rods of unequal"):
        fc.view(run, tmp_path / "big.html")
    assert not (tmp_path / "big.html").exists()
