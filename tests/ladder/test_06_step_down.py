"""Ladder rung 6: walking down stairs and down gentle terrain stays in contact (``ladder-06-step-down``).

Step-down (CTransition::step_down, called from transitional_insert when a body that was on walkable
ground finds no contact plane) puts the body back on the ground below within its step_down_height.
"""

from __future__ import annotations

import math
from itertools import pairwise
from pathlib import Path
from typing import Any

import pytest

import acphys
from acphys.precision import f32
from support import UNIT_TOL, step_records, ulp32

STAIR_TOPS = [1.2, 0.9, 0.6, 0.3, 0.0]  # box tops above the 50-m ground
OFFSET = 0.005  # sphere 0 (r 0.48 at z 0.475): its low point is 0.005 below the origin
SLOPE = 0.4  # terrain z = 50 - 0.4·(x - 120) for x >= 120


@pytest.fixture(scope="module")
def steps(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[dict[str, Any]]]:
    sim = acphys.load_scenario("ladder-06-step-down")
    trace = Path(tmp_path_factory.mktemp("ladder06")) / "step_down.jsonl"
    sim.run(trace=trace)
    by_body: dict[str, list[dict[str, Any]]] = {}
    for record in step_records(trace):
        by_body.setdefault(record["body"], []).append(record)
    return by_body


def test_stepper_walks_down_the_stairs_in_contact(steps: dict[str, list[dict[str, Any]]]) -> None:
    stepper = steps["stair-stepper"]
    heights = [f32(50.0 + top + OFFSET) for top in STAIR_TOPS]  # as float32 positions hold them
    zs = [record["origin"][2] for record in stepper]
    for record in stepper:
        # Never airborne: step-down (CTransition::step_down, acclient.c:312628, from transitional_insert,
        # acclient.c:312833) finds each lower tread, the new contact plane (acclient.c:322503).
        assert {"contact", "on_walkable"} <= set(record["transient"])
        assert record["contact_normal"] == [0.0, 0.0, 1.0]
        assert "leave_ground" not in record["events"]
        # Standing on a tread: the sphere's low point exactly on its top face (to float32).
        assert min(abs(record["origin"][2] - h) for h in heights) <= ulp32(51.0)
    drops = [a - b for a, b in pairwise(zs) if a != b]
    # one riser at a time, all four (each drop a difference of float32 heights near 51 m)
    assert drops == pytest.approx([0.3, 0.3, 0.3, 0.3], abs=2 * ulp32(51.0))
    assert stepper[-1]["origin"][1] > 94.5 + 0.48  # past the foot of the stairs


def test_shuffler_falls_off_the_stairs(steps: dict[str, list[dict[str, Any]]]) -> None:
    faller = steps["stair-faller"]
    airborne = [record for record in faller if "contact" not in record["transient"]]
    assert airborne, "a 0.02-m step-down cannot follow a 0.3-m riser"
    first = faller.index(airborne[0])
    # It walked off the platform (y 90..93) and left walkable ground there.
    assert "leave_ground" in airborne[0]["events"]
    assert faller[first - 1]["origin"][2] == pytest.approx(51.205, abs=ulp32(51.205))
    assert 93.0 < airborne[0]["origin"][1] < 93.0 + 0.48


def test_stepper_walks_down_the_slope_in_contact(steps: dict[str, list[dict[str, Any]]]) -> None:
    stepper = steps["hill-stepper"]
    k = math.sqrt(1.0 + SLOPE * SLOPE)
    on_slope = [record for record in stepper if record["origin"][0] > 120.0]
    assert len(on_slope) >= 25
    for record in stepper:
        assert {"contact", "on_walkable"} <= set(record["transient"])
        assert "leave_ground" not in record["events"]
    for record in on_slope:
        x, _, z = record["origin"]
        # Low point on the terrain plane (OBJECTINFO::validate_walkable, acclient.c:314160), the slope's
        # triangle as the contact plane.
        # To the float32 spacing of the plane's d and the origin, at ~50 m.
        assert z == pytest.approx(50.0 - SLOPE * (x - 120.0) + OFFSET, abs=2 * ulp32(50.0))
        assert record["contact_normal"] == pytest.approx([SLOPE / k, 0.0, 1.0 / k], abs=UNIT_TOL)


def test_shuffler_hops_down_the_slope(steps: dict[str, list[dict[str, Any]]]) -> None:
    faller = steps["hill-faller"]
    before = [record for record in faller if record["origin"][0] <= 120.0]
    assert all("contact" in record["transient"] for record in before)
    # Past the convex edge the ground falls 0.4 × 0.104 = 0.0416 m per step, more than 0.02.
    on_slope = [record for record in faller if record["origin"][0] > 120.0]
    assert "contact" not in on_slope[0]["transient"]
    assert "leave_ground" in on_slope[0]["events"]
    assert sum("contact" not in record["transient"] for record in on_slope) > len(on_slope) / 2
