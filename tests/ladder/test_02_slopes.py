"""Ladder rung 2: a slope just inside floor_z stands, one just outside it slides (``ladder-02-slopes``).

The slopes are terrain planes z = s·x (s = 1.12 and 1.13) from the scenario's heights and height table.
"""

from __future__ import annotations

import math
from itertools import pairwise
from pathlib import Path
from typing import Any

import pytest

import acphys
from acphys.constants import FLOOR_Z, GRAVITY
from acphys.precision import f32
from support import UNIT_TOL, step_records, ulp32, walk_tolerance

GENTLE, STEEP = 1.12, 1.13


def slope_normal(s: float) -> list[float]:
    """The upward unit normal of the plane z = s·x."""
    k = math.sqrt(1.0 + s * s)
    return [-s / k, 0.0, 1.0 / k]


@pytest.fixture(scope="module")
def steps(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[dict[str, Any]]]:
    sim = acphys.load_scenario("ladder-02-slopes")
    trace = Path(tmp_path_factory.mktemp("ladder02")) / "slopes.jsonl"
    sim.run(trace=trace)
    by_body: dict[str, list[dict[str, Any]]] = {}
    for record in step_records(trace):
        by_body.setdefault(record["body"], []).append(record)
    return by_body


def test_the_slopes_straddle_floor_z() -> None:
    # CPhysicsObj::is_valid_walkable: N.z >= floor_z (acclient.c:316499).
    assert slope_normal(GENTLE)[2] >= FLOOR_Z > slope_normal(STEEP)[2]


def test_walkable_slope_stands(steps: dict[str, list[dict[str, Any]]]) -> None:
    stander = steps["stander"]
    assert stander[-1]["t"] >= 2.0 - 1e-9
    for record in stander:
        # SetPositionInternal sets ON_WALKABLE from N.z >= floor_z (acclient.c:322503); on walkable
        # ground in contact calc_acceleration gives no gravity (acclient.c:317786), so the origin never
        # changes and no sweep runs (acclient.c:322718).
        assert {"contact", "on_walkable"} <= set(record["transient"])
        assert record["contact_normal"] == pytest.approx(slope_normal(GENTLE), abs=UNIT_TOL)
        assert record["origin"] == stander[0]["origin"]
        assert record["velocity"] == [0.0, 0.0, 0.0]
    # Placed with the sphere's low point on the slope, as its origin says (to the float32 spacing
    # there: placement's own step-down, CTransition::find_placement_position, puts it there).
    assert stander[0]["origin"] == pytest.approx([132.0, 36.0, 147.845], abs=ulp32(147.845))


def test_steep_slope_is_not_walkable_and_slides(steps: dict[str, list[dict[str, Any]]]) -> None:
    slider = steps["slider"]
    n = slope_normal(STEEP)
    dt = slider[0]["quantum"]
    first = slider[0]
    # In contact (placed on the plane) but not on walkable ground (acclient.c:322503): gravity applies
    # (acclient.c:317786). Step 1 has no velocity yet, so it does not move (acclient.c:317740).
    assert "contact" in first["transient"] and "on_walkable" not in first["transient"]
    assert first["contact_normal"] == pytest.approx(n, abs=UNIT_TOL)
    assert first["origin"] == [132.0, 156.0, f32(149.165)]
    assert first["velocity"][2] == f32(dt * GRAVITY)  # the spilled dt·a.z plus 0 (acclient.c:317772)
    # Step 2: the candidate drops dz = g·dt + g·dt²/2. CTransition::adjust_offset (acclient.c:311863)
    # removes its part into the contact plane, leaving (-N.x·N.z·dz, 0, (1 - N.z²)·dz), and lifts the
    # sphere (r 0.48), whose centre is r·N.z from the plane (its low point is on it), by
    # (r - r·N.z)/N.z. Lifted clear of the plane the sweep ends out of contact.
    dz = GRAVITY * dt * dt * 1.5
    lift = 0.48 * (1.0 - n[2]) / n[2]
    second = slider[1]
    # (to the float32 spacing at 132 m, where these are stored)
    assert second["origin"] == pytest.approx(
        [132.0 - n[0] * n[2] * dz, 156.0, 149.165 + lift + (1.0 - n[2] ** 2) * dz], abs=ulp32(132.0)
    )
    assert second["transient"] == ["active"]
    for record in slider:
        assert "on_walkable" not in record["transient"]
        if record["contact_normal"] is not None:
            # Each landing puts the sphere's low point on the plane (acclient.c:314160).
            assert record["contact_normal"] == pytest.approx(n, abs=UNIT_TOL)
            assert record["origin"][2] == pytest.approx(
                STEEP * record["origin"][0] + 0.005, abs=walk_tolerance(150.0, 2)
            )
    xs = [record["origin"][0] for record in slider]
    assert all(b <= a for a, b in pairwise(xs))
    landings = [r for r in slider[2:] if r["contact_normal"] is not None]
    assert len(landings) >= 5
    assert xs[-1] < 124.0  # more than 8 m down the slope in 2 s
