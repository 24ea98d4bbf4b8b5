"""Ladder rung 11: a ball stuck in a pit while falling ends on the fabricated floor (``ladder-11-pit``)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

import acphys
from acphys.constants import GRAVITY
from acphys.precision import f32
from support import step_records, ulp32

STATIONARY = {"stationary_fall", "stationary_stop", "stationary_stuck"}


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> tuple[acphys.Simulation, list[dict[str, Any]]]:
    sim = acphys.load_scenario("ladder-11-pit")
    trace = Path(tmp_path_factory.mktemp("ladder11")) / "pit.jsonl"
    sim.run(trace=trace)
    return sim, step_records(trace)


def test_stationary_fall_sequence(run: tuple[acphys.Simulation, list[dict[str, Any]]]) -> None:
    _, ball = run
    dt = ball[0]["quantum"]
    stop = next(i for i, r in enumerate(ball) if "stationary_stop" in r["transient"])
    # STATIONARY_STOP: the sweep seeded with 1 from STATIONARY_FALL (CPhysicsObj::transition,
    # acclient.c:320060) did not move, validate_transition counted 2 (acclient.c:312193), and
    # handle_all_collisions zeroed the velocity and added the bit (acclient.c:321807).
    assert "stationary_fall" in ball[stop - 1]["transient"]
    assert {"stationary_fall", "stationary_stop"} <= set(ball[stop]["transient"])
    assert ball[stop]["velocity"] == [0.0, 0.0, 0.0]
    assert ball[stop]["origin"] == ball[stop - 1]["origin"]
    assert "contact" not in ball[stop]["transient"]
    # Next step: zero velocity means no translation (acclient.c:317740), an unchanged origin and no
    # sweep (acclient.c:322718): the bits survive and gravity gives v = g·dt.
    idle = ball[stop + 1]
    assert idle["origin"] == ball[stop]["origin"]
    assert idle["velocity"][2] == f32(dt * GRAVITY)  # the spilled dt·a.z plus 0 (acclient.c:317772)
    assert {"stationary_fall", "stationary_stop"} <= set(idle["transient"])
    # Then the sweep seeded with 2 does not move: count 3, a floor is fabricated through sphere 0's
    # bottom (acclient.c:312193) and, the ball being out of contact, it is also the collision normal.
    # handle_all_collisions zeroes velocity and clears the three bits (acclient.c:321807);
    # SetPositionInternal puts it on walkable ground (acclient.c:322503).
    floor = ball[stop + 2]
    assert floor["origin"] == ball[stop]["origin"]
    assert {"contact", "on_walkable"} <= set(floor["transient"])
    assert not STATIONARY & set(floor["transient"])
    assert floor["contact_normal"] == [0.0, 0.0, 1.0]
    assert floor["velocity"] == [0.0, 0.0, 0.0]
    assert "hit_ground" in floor["events"]


def test_rests_on_the_fabricated_floor(run: tuple[acphys.Simulation, list[dict[str, Any]]]) -> None:
    sim, ball = run
    stop = next(i for i, r in enumerate(ball) if "stationary_stop" in r["transient"])
    origin = ball[stop]["origin"]
    # Wedged between the two top edges (x = ±0.45, z = 53): sphere 0's centre (origin + 0.5) is at its
    # radius from each edge, i.e. sqrt(0.5² - 0.45²) above them; the unmoved sweep left it within a
    # millimetre of that.
    touching = 53.0 + math.sqrt(0.5**2 - 0.45**2) - 0.5
    assert origin[0] == 96.0 and origin[1] == 96.0
    assert origin[2] == pytest.approx(touching, abs=1e-3)
    # The fabricated plane passes through the sphere's bottom: N = +z, d = r - centre z
    # (acclient.c:312193), and the body keeps it.
    body = sim.body("ball")
    assert body.contact_plane.d == pytest.approx(0.5 - (origin[2] + 0.5), abs=ulp32(origin[2]))
    # At rest on it: no movement manager and zero velocity on walkable ground deactivate the ball
    # (UpdatePhysicsInternal, acclient.c:317700); it never moves again.
    assert all(r["origin"] == origin for r in ball[stop:])
    assert "active" not in ball[-1]["transient"]
    assert ball[-1]["t"] - ball[stop + 2]["t"] > 0.4
