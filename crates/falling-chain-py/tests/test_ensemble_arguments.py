"""`ensemble` and `ensemble_series` take `members` and `seed` as the CLI's
`--members` and `--seed` (issue 47, Y1): an int in range, a TypeError for
what is not an int, a ValueError naming the argument and its range for an
int outside it, never Python's OverflowError; their defaults are the CLI's.
And `needs(links=...)` with a huge list says how long it is (U7)."""

import itertools

import pytest

import falling_chain as fc
from conftest import cli_json, scene_path

MEMBERS = "members: must be an integer in 2..=4096"
SEED = "seed: must be an integer in 0..=4294967295"
ENSEMBLES = [fc.ensemble, fc.ensemble_series]


def small():
    return fc.Scene.load(scene_path("span-d3")).set("chain.links", 4).set("run.t_end", 0.05)


def one_line_starting(error, prefix):
    message = str(error.value)
    assert message.startswith(prefix) and "\n" not in message, message
    return message


@pytest.mark.parametrize("call", ENSEMBLES)
@pytest.mark.parametrize(
    "kwargs, prefix, got",
    [
        ({"members": -1}, MEMBERS, "-1"),
        ({"members": 10**30}, MEMBERS, str(10**30)),
        ({"members": 1}, MEMBERS, "1"),
        ({"members": 4097}, MEMBERS, "4097"),
        ({"seed": -1}, SEED, "-1"),
        ({"seed": 2**32}, SEED, "4294967296"),
        ({"seed": -(2**70)}, SEED, str(-(2**70))),
    ],
)
def test_an_int_out_of_range_is_a_value_error_naming_the_argument(call, kwargs, prefix, got):
    with pytest.raises(ValueError) as e:
        call(small(), **kwargs)
    assert not isinstance(e.value, OverflowError)
    assert one_line_starting(e, prefix).endswith(f"(got {got})")


@pytest.mark.parametrize("call", ENSEMBLES)
@pytest.mark.parametrize(
    "kwargs, prefix, type_name",
    [
        ({"members": True}, "members: must be an int in 2..=4096", "bool"),
        ({"members": 4.0}, "members: must be an int in 2..=4096", "float"),
        ({"members": "4"}, "members: must be an int in 2..=4096", "str"),
        ({"seed": False}, "seed: must be an int in 0..=4294967295", "bool"),
        ({"seed": 1.5}, "seed: must be an int in 0..=4294967295", "float"),
    ],
)
def test_what_is_not_an_int_is_a_type_error(call, kwargs, prefix, type_name):
    with pytest.raises(TypeError) as e:
        call(small(), **kwargs)
    assert one_line_starting(e, prefix).endswith(f"(got '{type_name}')")


def test_the_ranges_ends_are_accepted_and_the_seed_chooses_the_draws():
    low = fc.ensemble(small(), members=2, seed=0, spread=1e-2)
    high = fc.ensemble(small(), members=2, seed=2**32 - 1, spread=1e-2)
    assert low["members"] == high["members"] == 2
    assert (low["seed"], high["seed"]) == (0, 2**32 - 1)
    assert low["ok"] == high["ok"] == 2
    # Other draws, other starts: the statistics differ.
    assert low["stats"]["tip_end_x"]["mean"] != high["stats"]["tip_end_x"]["mean"]


def test_the_defaults_are_the_clis():
    want = cli_json(
        "ensemble", scene_path("span-d3"), "--set", "chain.links=4", "--set", "run.t_end=0.05",
        "--json", "--quiet", check=0,
    )
    got = fc.ensemble(small())
    assert (got["members"], got["seed"], got["spread"]) == (16, 0, 1e-3)
    assert got == want
    assert fc.ensemble(small(), members=16, seed=0) == got
    series = fc.ensemble_series(small())
    assert series["ensemble"] == got and series["members"] == 16


def test_a_huge_links_list_is_refused_with_its_length():
    with pytest.raises(ValueError) as e:
        fc.needs(small(), 0.1, links=list(range(2, 10**6)))
    one_line_starting(e, "links: at most 32 numbers of rods (got 999998 values)")
    # Without a length (an endless iterator), only the cap is known; it is
    # read no further than one value past it.
    with pytest.raises(ValueError) as e:
        fc.needs(small(), 0.1, links=itertools.count(2))
    one_line_starting(e, "links: at most 32 numbers of rods (got more than 32 values)")
    # One past the cap is counted exactly.
    with pytest.raises(ValueError) as e:
        fc.needs(small(), 0.1, links=list(range(2, 35)))
    one_line_starting(e, "links: at most 32 numbers of rods (got 33 values)")
