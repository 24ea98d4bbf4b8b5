"""Ladder rung 1: free fall onto flat terrain, landing, and rest (scenario ``ladder-01-fall``).

Every expected value is derived from the decompiled client: free fall from UpdatePhysicsInternal's Euler
step, the landing height from OBJECTINFO::validate_walkable's low-point test, the landing velocity from
handle_all_collisions' bounce, and what the next steps do to it from calc_friction and the deadband.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

import acphys
from acphys.constants import DEFAULT_ELASTICITY, EPSILON, GRAVITY, SMALL_VELOCITY
from acphys.precision import f32
from support import fall, step_records, ulp32

REST = 10.0  # seconds of rest the rung asks for


@pytest.fixture(scope="module")
def steps(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[dict[str, Any]]]:
    sim = acphys.load_scenario("ladder-01-fall")
    trace = Path(tmp_path_factory.mktemp("ladder01")) / "fall.jsonl"
    sim.run(trace=trace)
    by_body: dict[str, list[dict[str, Any]]] = {}
    for record in step_records(trace):
        by_body.setdefault(record["body"], []).append(record)
    return by_body


def test_ball_falls_lands_and_stops(steps: dict[str, list[dict[str, Any]]]) -> None:
    ball = steps["ball"]
    dt = ball[0]["quantum"]
    # Falling: the sphere's low point (origin + 0.6 - 0.4) must reach 50 m. Step 14 is still above it,
    # step 15 would be below (z0 + g dt² 224/2 = 49.78): validate_walkable (acclient.c:314160) lifts the
    # low point back onto the plane, so the ball lands on step 15.
    for k in range(1, 15):
        assert (ball[k - 1]["origin"][2], ball[k - 1]["velocity"][2]) == fall(51.0, dt, k)
        assert "contact" not in ball[k - 1]["transient"]
    assert fall(51.0, dt, 14)[0] - 49.8 > 0.0 > fall(51.0, dt, 15)[0] - 49.8
    landing = ball[14]
    # Resting height from the sphere geometry: low point on the plane (acclient.c:314160), to
    # the float32 spacing there (the lift is computed through float stores).
    assert landing["origin"] == pytest.approx([90.0, 96.0, 49.8], abs=ulp32(49.8))
    assert {"contact", "on_walkable"} <= set(landing["transient"])
    assert landing["contact_normal"] == [0.0, 0.0, 1.0]
    assert "hit_ground" in landing["events"]
    # Out of contact the landing sets the collision normal +z (acclient.c:314160), and
    # handle_all_collisions bounces: v -= (1 + e)(v·n)n, i.e. v_z = -e·v_in (acclient.c:321807).
    v_in = fall(51.0, dt, 15)[1]
    assert landing["velocity"][2] == pytest.approx(-DEFAULT_ELASTICITY * v_in, rel=1e-6)
    # Step 16: on walkable ground the 0.245 m/s normal speed is under calc_friction's 0.25 cut-off, so
    # it is removed (acclient.c:316090); the pre-friction speed is inside the deadband as well
    # (acclient.c:317750). Zero velocity, unchanged origin: no sweep, still in contact.
    assert (DEFAULT_ELASTICITY * v_in) ** 2 - SMALL_VELOCITY**2 < EPSILON
    after = ball[15]
    assert after["velocity"] == [0.0, 0.0, 0.0]
    assert after["origin"] == landing["origin"]
    assert "active" in after["transient"]
    # Step 17: v = 0, no movement manager, on walkable ground: ACTIVE goes (acclient.c:317700).
    assert "active" not in ball[16]["transient"]
    assert all(r["origin"] == landing["origin"] and r["velocity"] == [0.0, 0.0, 0.0] for r in ball[15:])
    assert ball[-1]["t"] - landing["t"] >= REST


def test_human_hops_once_then_rests_without_drift(steps: dict[str, list[dict[str, Any]]]) -> None:
    human = steps["human"]
    dt = human[0]["quantum"]
    # The low point (origin - 0.005) starts 2.995 m up: step 23 is above, step 24 lands (576 - 1 > 550.1).
    assert fall(53.0, dt, 23)[0] - 50.005 > 0.0 > fall(53.0, dt, 24)[0] - 50.005
    landing = human[23]
    assert "contact" not in human[22]["transient"]
    assert landing["origin"][2] == f32(50.005)
    # handle_all_collisions bounce (acclient.c:321807) of the float32 landing speed
    v_out = landing["velocity"][2]
    assert v_out == pytest.approx(-DEFAULT_ELASTICITY * fall(53.0, dt, 24)[1], rel=1e-6)
    # Step 25: 0.392 m/s along the normal is >= 0.25, so calc_friction leaves it (acclient.c:316090) and
    # the deadband does not apply (acclient.c:317750). Still on walkable ground the acceleration is 0
    # (calc_acceleration, acclient.c:317786): it rises v·dt and, moving off its plane (check_contact,
    # acclient.c:316535), the sweep finds no ground: it leaves it.
    hop = human[24]
    assert hop["origin"][2] == f32(f32(f32(dt * v_out) + 0.0) + f32(50.005))
    assert "contact" not in hop["transient"] and "leave_ground" in hop["events"]
    # Step 26: under gravity again. Step 27: v = v_out + g·dt is inside the deadband even in the air
    # (acclient.c:317750), so it is zeroed before moving: only g·dt²/2, and v = g·dt.
    z26, v26 = fall(hop["origin"][2], dt, 1, v_out)
    assert (human[25]["origin"][2], human[25]["velocity"][2]) == (z26, v26)
    assert v26**2 - SMALL_VELOCITY**2 < EPSILON
    # zeroed before moving: the origin moves by the float w.z = 0 + (g·0.5)·dt·dt alone
    assert human[26]["origin"][2] == f32(f32(0.0 + f32(GRAVITY * 0.5) * dt * dt) + z26)
    assert human[26]["velocity"][2] == f32(dt * GRAVITY)
    # Step 28: lands again with v_in = 2·g·dt; the bounce is -e·v_in, which step 29's friction removes.
    second = human[27]
    assert second["origin"][2] == f32(50.005)
    assert "hit_ground" in second["events"]
    assert second["velocity"][2] == pytest.approx(-DEFAULT_ELASTICITY * 2 * GRAVITY * dt, rel=1e-6)
    rest = human[28:]
    assert rest[-1]["t"] - rest[0]["t"] >= REST
    # At rest: a movement manager keeps it active, every step has an unchanged origin (no sweep,
    # acclient.c:322718) and keeps CONTACT and ON_WALKABLE; no drift at all.
    for record in rest:
        assert record["origin"] == second["origin"]
        assert record["velocity"] == [0.0, 0.0, 0.0]
        assert {"active", "contact", "on_walkable"} <= set(record["transient"])
        assert record["cached_velocity"] == [0.0, 0.0, 0.0]
