"""The module documents itself: docstrings, signatures and the type stubs
shipped with it agree with what it holds."""

import ast
import inspect
from pathlib import Path

import falling_chain as fc

CONTRACT = [
    "Scene", "Run", "simulate", "sweep", "catenary", "precision", "stability", "needs", "ensemble",
    "merge", "view",
]


def stub():
    path = Path(fc.__file__).with_name("__init__.pyi")
    assert path.is_file(), "the stubs are installed with the module"
    assert path.with_name("py.typed").is_file()
    return ast.parse(path.read_text())


def test_the_names_and_their_docstrings():
    for name in CONTRACT + ["methods"]:
        obj = getattr(fc, name)
        assert name in fc.__all__
        assert obj.__doc__ and len(obj.__doc__) > 40, name
    for name in ("load", "from_toml", "set", "to_toml", "check"):
        assert getattr(fc.Scene, name).__doc__, name
    for name in ("summary", "t", "phi", "w", "tip", "tip_velocity", "energy", "dissipated", "joints"):
        assert getattr(fc.Run, name).__doc__, name
    assert fc.__doc__ and "simulate" in fc.__doc__


def test_signatures_are_visible():
    sig = inspect.signature(fc.simulate)
    assert list(sig.parameters) == ["scene", "method", "dt", "rtol", "atol", "t_end", "output_dt"]
    assert all(p.kind is p.KEYWORD_ONLY for p in list(sig.parameters.values())[1:])
    sig = inspect.signature(fc.sweep)
    assert list(sig.parameters)[:6] == ["scene", "vary", "method", "rtol", "atol", "shard"]
    assert list(inspect.signature(fc.catenary).parameters) == ["p0", "p1", "length", "links"]
    assert list(inspect.signature(fc.Scene.set).parameters) == ["self", "key", "value"]


def test_the_stubs_declare_what_the_module_has():
    tree = stub()
    top = {n.name: n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    assert set(CONTRACT + ["methods"]) <= set(top)
    for name, node in top.items():
        assert hasattr(fc, name), name
        if isinstance(node, ast.FunctionDef):
            params = [a.arg for a in node.args.args + node.args.kwonlyargs]
            assert params == list(inspect.signature(getattr(fc, name)).parameters), name
        else:
            for member in node.body:
                if isinstance(member, ast.FunctionDef) and not member.name.startswith("__"):
                    assert hasattr(getattr(fc, name), member.name), (name, member.name)


def test_methods_are_the_registry():
    assert {"rk4", "dopri5", "dop853", "bdf", "auto"} <= set(fc.methods())


def test_scene_round_trips(span):
    again = fc.Scene.from_toml(span.to_toml())
    assert again == span
    assert span.set("chain.links", 20) != span
    d = span.to_dict()
    assert d["chain"]["links"] == 50 and d["start"]["p1"] == [3.0, 0.0]
    assert span.set("start.p1.0", 2.5).to_dict()["start"]["p1"] == [2.5, 0.0]
    assert span.set("start.p1", "[2.5, 0.0]") == span.set("start.p1", (2.5, 0.0))
    assert span.name == "span-d3" and "Fig. 7b" in span.description
    assert repr(span) == 'Scene(name="span-d3")'
