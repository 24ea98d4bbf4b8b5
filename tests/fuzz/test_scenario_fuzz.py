"""Malformed scenarios never crash: every built-in scenario, with one value at a time replaced by
something wrong (another type, NaN, infinities, huge or negative numbers, empty or odd strings and
lists) or one key dropped, either builds or fails with a one-line ScenarioError naming its
source; a scenario that builds runs a few steps without NaN."""

from __future__ import annotations

import copy
import math
import random
import tomllib
from importlib import resources
from typing import Any

import pytest

from acphys.scenario import ScenarioError, build_scenario, builtin_scenarios

WRONG_VALUES: list[Any] = [
    None,
    True,
    0,
    -1,
    7,
    10**12,
    -(10**12),
    0.0,
    -0.5,
    999.0,
    -999.0,
    1e5,
    1e300,
    math.nan,
    math.inf,
    -math.inf,
    "",
    "x",
    "0x",
    "0xFFFFFFFFFF",
    "nan",
    "RunForward",
    "0x02000001",
    [],
    [1.0],
    [1.0, 2.0],
    [math.nan, 0.0, 0.0],
    [1e300, 1e300, 1e300],
    ["a", "b", "c"],
    {},
    {"x": 1},
    [{}],
]


def _paths(value: Any, path: tuple[Any, ...] = ()) -> list[tuple[Any, ...]]:
    """Every place in a TOML document: keys of tables and indices of lists, depth first."""
    found = [path] if path else []
    if isinstance(value, dict):
        for key, item in value.items():
            found += _paths(item, (*path, key))
    elif isinstance(value, list):
        for index, item in enumerate(value):
            found += _paths(item, (*path, index))
    return found


def _mutated(document: dict[str, Any], path: tuple[Any, ...], value: Any, drop: bool) -> dict[str, Any]:
    result = copy.deepcopy(document)
    parent = result
    for step in path[:-1]:
        parent = parent[step]
    if drop and isinstance(parent, dict):
        del parent[path[-1]]
    else:
        parent[path[-1]] = copy.deepcopy(value)
    return result


@pytest.mark.parametrize("name", builtin_scenarios())
def test_one_wrong_value_is_a_clear_error_or_a_sound_run(name: str) -> None:
    text = resources.files("acphys.data.scenarios").joinpath(f"{name}.toml").read_text("utf-8")
    document = tomllib.loads(text)
    places = _paths(document)
    rng = random.Random(name)
    for trial in range(40):
        path = rng.choice(places)
        drop = rng.random() < 0.15
        value = rng.choice(WRONG_VALUES)
        mutated = _mutated(document, path, value, drop)
        where = f"{name}: {'dropped' if drop else repr(value)} at {path} (trial {trial})"
        try:
            sim = build_scenario(mutated, source=f"<fuzz {name}>")
        except ScenarioError as error:
            # Each problem is one line naming the source; one wrong value can be several problems
            # (a list of wrong entries), but what only depends on a broken part says nothing.
            assert str(error).splitlines() == error.problems, where
            for problem in error.problems:
                assert problem.startswith(f"<fuzz {name}>"), where
                assert "\n" not in problem, where
            continue
        sim.run(until=min(sim.duration, 0.2))
        for body in sim.bodies:
            origin = body.position.frame.origin
            assert not any(math.isnan(c) for c in (*origin, *body.velocity)), where
