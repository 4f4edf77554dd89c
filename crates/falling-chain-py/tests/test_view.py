"""`fc.view` and `Run._repr_html_`: the page holds the run's own arrays (the
same data as the CLI's `view` of the same scene), several runs overlay with
distinct labels, and bad input raises ValueError naming the argument, with
nothing written."""

import html
import json

import numpy as np
import pytest

import falling_chain as fc
from conftest import assert_same, cli, scene_path


def page_data(text):
    open_tag = '<script id="fc-data" type="application/json">'
    start = text.index(open_tag) + len(open_tag)
    end = text.index("</script>", start)
    return json.loads(text[start:end])


def span_d3():
    return fc.Scene.load(scene_path("span-d3"))


def test_the_page_holds_the_runs_arrays(tmp_path):
    run = fc.simulate(span_d3())
    path = fc.view(run, tmp_path / "run.html")
    assert path == tmp_path / "run.html"
    data = page_data(path.read_text())
    (r,) = data["runs"]
    assert r["label"] == "span-d3" and r["stride"] == 1 and r["samples"] == len(run)
    # Angles to 6 decimals; the geometry is the scene's (L = 6, n = 50, P0 = 0).
    phi = np.array(r["phi"]).reshape(len(run), run.links)
    assert np.abs(phi - run.phi).max() <= 5e-7
    assert r["rod"] == pytest.approx(6.0 / 50, abs=1e-15) and r["anchor"] == [0.0, 0.0]
    assert np.array_equal(r["speed"], np.hypot(run.tip_velocity[:, 0], run.tip_velocity[:, 1]))
    assert np.array_equal(r["energy"], run.energy)
    assert r["summary"] == run.summary


def test_the_page_of_a_run_is_the_clis_page_of_its_scene(tmp_path):
    run = fc.simulate(span_d3())
    cli("view", scene_path("span-d3"), "-o", tmp_path / "cli.html", check=0)
    ours = page_data(fc.view(run, tmp_path / "py.html").read_text())
    theirs = page_data((tmp_path / "cli.html").read_text())
    # The module's runs agree with the CLI's to 1e-12 (test_summary.py); the
    # angles are on the page to 6 decimals, so a rounding may differ by 1e-6.
    ours, theirs = ours["runs"][0], theirs["runs"][0]
    for d in (ours, theirs):
        d["summary"].pop("wall_seconds")
    phi = [np.array(d.pop("phi")) for d in (ours, theirs)]
    assert np.abs(phi[0] - phi[1]).max() <= 1.0000001e-6
    assert_same(ours, theirs)


def test_a_run_shows_as_the_viewer_in_jupyter(tmp_path):
    run = fc.simulate(span_d3())
    shown = run._repr_html_()
    assert shown.startswith("<iframe srcdoc=") and 'sandbox="allow-scripts"' in shown
    srcdoc = html.unescape(shown.split('srcdoc="', 1)[1].split('"', 1)[0])
    assert srcdoc.startswith("<!DOCTYPE html>")
    page = fc.view(run, tmp_path / "run.html").read_text()
    assert page_data(srcdoc) == page_data(page)


def test_several_runs_overlay_with_distinct_labels(tmp_path):
    rigid = fc.simulate(span_d3(), method="rk4")
    other = fc.simulate(span_d3(), method="dopri5")
    data = page_data(fc.view([rigid, other, rigid], tmp_path / "three.html").read_text())
    assert [r["label"] for r in data["runs"]] == ["span-d3", "span-d3 #2", "span-d3 #3"]
    assert [r["summary"]["method"] for r in data["runs"]] == ["rk4", "dopri5", "rk4"]


def test_bad_input_raises_naming_the_argument_and_writes_nothing(tmp_path):
    run = fc.simulate(span_d3(), t_end=0.1)
    cases = [
        ([run] * 9, "x.html", "runs", "1 to 8"),
        ([], "x.html", "runs", "1 to 8"),
        ([1, 2], "x.html", "runs", "Run"),
        ("span-d3", "x.html", "runs", "Run"),
        (run, "x.png", "path", ".html"),
        (run, "absent/x.html", "path", "directory"),
    ]
    for runs, name, field, says in cases:
        with pytest.raises(ValueError) as e:
            fc.view(runs, tmp_path / name)
        message = str(e.value)
        assert message.startswith(field) and says in message and "\n" not in message, message
    assert list(tmp_path.iterdir()) == []


def test_a_floor_runs_page_draws_its_floor_as_the_clis_does(tmp_path):
    # scenes/span-d3-floor.toml: the floor at y = -3, level; the CLI's page of
    # the same scene holds the same floor line, and a run without a floor
    # has none on its page.
    scene = fc.Scene.load(scene_path("span-d3-floor")).set("run.t_end", 0.2)
    ours = page_data(fc.view(fc.simulate(scene), tmp_path / "py.html").read_text())
    cli("view", scene_path("span-d3-floor"), "--set", "run.t_end=0.2",
        "-o", tmp_path / "cli.html", check=0)
    theirs = page_data((tmp_path / "cli.html").read_text())
    assert ours["runs"][0]["floor"] == theirs["runs"][0]["floor"]
    height, angle = ours["runs"][0]["floor"]
    assert height == pytest.approx(-3.0, abs=1e-12) and angle == 0.0
    plain = page_data(fc.view(fc.simulate(span_d3().set("run.t_end", 0.2)),
                              tmp_path / "plain.html").read_text())
    assert "floor" not in plain["runs"][0]
