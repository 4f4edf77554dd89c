"""Issue 38 from Python: `merge` reads shards of a scene named with commas,
quotes and line breaks and refuses rows not run for a shard's budget (F2,
F3); errors name the keyword arguments, never the CLI's flags (U7); a
`Run`'s notebook page keeps the viewer's bounds (Y2); `Run.dissipated`,
`friction_work` and `support_work` under a moving pivot, against the energy
balance (Y3)."""

import pathlib

import numpy as np
import pytest

import falling_chain as fc
from conftest import cli, scene_path

NASTY = 'a,b "q"\nc'
NASTY_SET = r'name="a,b \"q\"\nc"'


def small():
    return fc.Scene.from_toml(
        '[chain]\nlinks = 4\n[start]\nkind = "folded"\n[run]\nt_end = 0.2\n'
    )


def test_merge_reads_shards_of_a_name_with_commas_quotes_and_newlines(tmp_path):
    for i in range(2):
        cli("sweep", scene_path("span-d3"), "--set", NASTY_SET, "--set", "run.t_end=0.2",
            "--vary", "chain.damping=0,0.001,0.002", "--shard", f"{i}/2", "--quiet",
            "--out", tmp_path / f"s{i}.csv", check=0)
    table = fc.merge([tmp_path / "s1.csv", str(tmp_path / "s0.csv")])
    assert list(table["run"]) == [0, 1, 2]
    assert list(table["name"]) == [NASTY] * 3
    assert list(table["chain.damping"]) == [0.0, 0.001, 0.002]
    # The same scene from Python's own sweep (`set` takes TOML text, as --set).
    scene = fc.Scene.load(scene_path("span-d3")).set("name", NASTY_SET.split("=", 1)[1])
    swept = fc.sweep(scene.set("run.t_end", 0.2), {"chain.damping": [0.0, 0.001, 0.002]})
    assert list(swept["name"]) == [NASTY] * 3
    assert list(swept["scene_hash"]) == list(table["scene_hash"])


def test_merge_refuses_rows_not_run_for_the_budget(tmp_path):
    for i in range(2):
        done = cli("stability", scene_path("span-d3"), "--set", "chain.links=400",
                   "--methods", "rk4,dopri5", "--budget", "0.001", "--shard", f"{i}/2",
                   "--quiet", "--out", tmp_path / f"b{i}.csv")
        assert done.returncode in (0, 1), done.stderr
    with pytest.raises(ValueError) as e:
        fc.merge([tmp_path / "b0.csv", tmp_path / "b1.csv"])
    message = str(e.value)
    assert message.startswith("merge: ") and "b0.csv" in message and "--budget" in message, message


@pytest.mark.parametrize("paths", ["s0.csv", pathlib.Path("s0.csv"), b"s0.csv"])
def test_merge_of_one_path_is_a_type_error_naming_paths(paths):
    with pytest.raises(TypeError) as e:
        fc.merge(paths)
    assert str(e.value).startswith("paths: ") and "merge([path])" in str(e.value), str(e.value)


def test_merge_of_no_paths_names_paths(tmp_path):
    with pytest.raises(TypeError, match=r"^paths: "):
        fc.merge(7)
    with pytest.raises(TypeError, match=r"^paths: every element"):
        fc.merge([3.5])
    with pytest.raises(ValueError, match=r"^paths: cannot read"):
        fc.merge([tmp_path / "missing.csv"])


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda s: fc.precision(s, shard="2/2"), "shard"),
        (lambda s: fc.stability(s, shard=(3, 1)), "shard"),
        (lambda s: fc.stability(s, vary={"chain.damping": "0:1:1000001"}), "vary"),
        (lambda s: fc.sweep(s, {"chain.damping": [0.0]}, shard="1/1"), "shard"),
        (lambda s: fc.needs(s, 2.0), "tol"),
        (lambda s: fc.needs(s, 0.1, links=[7]), "links"),
        (lambda s: fc.needs(s, 0.1, links="2,3," + ",".join(str(k) for k in range(4, 40))), "links"),
        (lambda s: fc.precision(s, check_dt=-1.0), "check_dt"),
    ],
)
def test_errors_name_the_keyword_argument(call, field):
    with pytest.raises(ValueError) as e:
        call(small())
    message = str(e.value)
    assert message.startswith(f"{field}: "), message
    assert "\n" not in message and not message.startswith("--"), message


def test_a_notebook_page_keeps_the_viewers_bounds():
    # Above view's rod bound: a short text saying why, not a page.
    huge = fc.Scene.load(scene_path("span-d3")).set("chain.links", 20000)
    run = fc.simulate(huge, method="bdf", t_end=1e-3)
    html = run._repr_html_()
    assert len(html) < 2000 and "at most 10000 rods" in html and "<iframe" not in html, html
    # A long run is thinned to the page's cap.
    long = fc.Scene.load(scene_path("folded")).set("chain.links", 400).set("start.down", 200)
    run = fc.simulate(long, t_end=8.0, output_dt=0.002)
    html = run._repr_html_()
    assert html.startswith("<iframe") and len(html) < 4_000_000, len(html)
    # A page must end in .html exactly.
    with pytest.raises(ValueError, match=r"^path: must end in \.html"):
        fc.view(run, "run.htm")


def test_dissipated_friction_and_support_work_under_a_moving_pivot():
    jerked = fc.Scene.load(scene_path("jerked-support"))
    run = fc.simulate(jerked, output_dt=1e-3)
    e, w = run.energy, run.dissipated
    scale = 60.0  # M g L of the scene
    # `dissipated` is the W of the balance E + W = E(0) ...
    assert np.max(np.abs(e + w - e[0])) < 1e-5 * scale
    # ... which the hand that jerks the pivot drives negative: it is the
    # friction's work less the support's.
    assert w[-1] < -60 and np.allclose(run.friction_work - run.support_work, w, rtol=0, atol=1e-12)
    # The friction's work alone: r sum (w_i - w_{i-1})^2 integrated by hand.
    r = 0.0005
    power = r * np.sum(np.diff(run.w, axis=1) ** 2, axis=1)
    by_hand = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(run.t))])
    friction = run.friction_work
    assert np.max(np.abs(friction - by_hand)) < 1e-4 * friction[-1], np.max(np.abs(friction - by_hand))
    assert np.min(np.diff(friction)) > -1e-6 * friction[-1]
    # Without friction, the support's work is the chain's energy gained.
    free = fc.simulate(jerked.set("chain.damping", 0.0), output_dt=1e-3)
    gained = free.energy - free.energy[0]
    assert np.max(np.abs(free.support_work - gained)) < 1e-4 * np.max(np.abs(gained))
    assert np.max(np.abs(free.friction_work)) < 1e-4 * np.max(np.abs(gained))
    # A fixed pivot: the support does no work and `dissipated` is the
    # friction's, exactly.
    fixed = fc.simulate(fc.Scene.load(scene_path("span-d3")), t_end=1.0)
    assert np.all(fixed.support_work == 0.0)
    assert np.array_equal(fixed.friction_work, fixed.dissipated)
