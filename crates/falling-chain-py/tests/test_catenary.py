"""`catenary` is `falling-chain catenary --json`."""

import numpy as np

import falling_chain as fc
from conftest import assert_same, cli_json


def test_catenary_is_the_cli_json():
    for p0, p1, length, links in [
        ((0, 0), (5, 1), 6, None),
        ((0, 0), (5, 1), 6, 50),
        ((-1.5, 2), (3, -1), 10, 7),
        ((0, 0), (3, 0), 6, 50),
    ]:
        args = ["catenary", "--p0", f"{p0[0]},{p0[1]}", "--p1", f"{p1[0]},{p1[1]}",
                "--length", length, "--json"]
        if links is not None:
            args += ["--links", links]
        want = cli_json(*args, check=0)
        got = fc.catenary(p0, p1, length, links)
        assert list(got) == list(want)
        if links is None:
            assert "angles" not in got and "end_error" not in got
        else:
            for key, shape in (("angles", (links,)), ("joints", (links + 1, 2))):
                a = got.pop(key)
                assert isinstance(a, np.ndarray) and a.dtype == np.float64 and a.shape == shape
                np.testing.assert_array_equal(a, np.array(want.pop(key), dtype=float))
            assert got["end_error"] < 1e-12 * length
        assert_same(got, want, rel=0)
