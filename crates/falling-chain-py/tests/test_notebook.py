"""The notebook examples/falling-chain.ipynb runs: its code cells, in order,
with matplotlib's Agg backend (no Jupyter needed), from examples/."""

import json
import os

import pytest

from conftest import ROOT

NOTEBOOK = ROOT / "examples" / "falling-chain.ipynb"


def code_cells():
    nb = json.loads(NOTEBOOK.read_text())
    return nb, [c for c in nb["cells"] if c["cell_type"] == "code"]


def test_the_notebook_keeps_no_outputs():
    _, cells = code_cells()
    assert cells
    for c in cells:
        assert c["outputs"] == [] and c["execution_count"] is None


def test_the_notebook_runs(monkeypatch, capsys):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    monkeypatch.chdir(NOTEBOOK.parent)
    namespace = {"__name__": "__main__"}
    _, cells = code_cells()
    for i, cell in enumerate(cells):
        source = "".join(cell["source"])
        exec(compile(source, f"{NOTEBOOK.name}[{i}]", "exec"), namespace)
    out = capsys.readouterr().out
    assert "span-d3" in out and "at x = L/2" in out
    # Three figures were drawn: Fig. 7b, Fig. 9, the folded chain.
    assert len(namespace["dense"]["tip_speed_max"]) == 120
    assert namespace["ok"].sum() >= 110
    # The law and the chain agree within a few percent over most of the fall.
    half = namespace["half"]
    assert abs(namespace["speed"][half] / namespace["law"][half] - 1) < 0.05
    # The viewer: a page of two runs, and a Run that shows as one.
    assert "folded.html" in out
    assert namespace["watched"]._repr_html_().startswith("<iframe srcdoc=")
    # needs answered on its ladder; precision's table has the reference rows.
    assert namespace["need"]["links"] in (10, 20, 40)
    assert namespace["wp"]["method"][0] == "reference-dopri5"
    plt.close("all")


def test_the_notebook_names_the_method_its_fig7b_runs():
    """The Fig. 7b cell says how its scene runs: the method of
    scenes/span-d3.toml (once RK4, since DOPRI5: the text was stale)."""
    import falling_chain as fc

    nb, _ = code_cells()
    text = next("".join(c["source"]) for c in nb["cells"]
                if c["cell_type"] == "markdown" and "".join(c["source"]).startswith("## Fig. 7b"))
    run = fc.simulate(fc.Scene.load(str(ROOT / "scenes" / "span-d3.toml")), t_end=0.1)
    method = run.summary["method"]
    assert method.upper() in text, (method, text)
    for other in fc.methods():
        if other != method and other.upper() != method.upper():
            assert f"({other.upper()}" not in text, (other, text)
