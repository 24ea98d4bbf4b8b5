"""Ladder rung 7: a ball with elasticity 0.1 bounces and comes to rest; an inelastic missile stops dead.

The expected values are worked out by hand from the retail steps (30 Hz, dt = f32(1/30)):
``UpdatePhysicsInternal`` moves by ``v·dt + a·dt²/2`` only when v² > 0 and always adds ``a·dt``;
``handle_all_collisions`` reflects the normal velocity with ``(1 + e)``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import acphys
from acphys.constants import GRAVITY
from acphys.flags import PhysicsState
from acphys.precision import f32
from support import fall, step_records, walk_tolerance

DT = f32(1.0 / 30.0)
G = GRAVITY


def _records(tmp_path: Path) -> dict[str, list[dict]]:
    sim = acphys.load_scenario("ladder-07-bounce")
    trace = tmp_path / "bounce.jsonl"
    sim.run(trace=trace)
    by_body: dict[str, list[dict]] = {}
    for record in step_records(trace):
        by_body.setdefault(record["body"], []).append(record)
    return by_body


@pytest.fixture(scope="module")
def records(tmp_path_factory: pytest.TempPathFactory) -> dict[str, list[dict]]:
    return _records(tmp_path_factory.mktemp("ladder07"))


def test_the_ball_loses_nine_tenths_of_its_speed_per_bounce(records: dict[str, list[dict]]) -> None:
    ball = records["ball"]
    landings = [i + 1 for i, r in enumerate(ball) if "hit_ground" in r["events"]]
    # Free fall from 55 m: step 1 does not move (v² = 0), so after step k the origin is at
    # 55 + G·dt²·(k² - 1)/2 (CPhysicsObj::UpdatePhysicsInternal, acclient.c:317700); the sphere's
    # bottom (the origin: centre 0.1, radius 0.1) first reaches 50 m on step 31.
    # Second fall: see test_between_the_bounces; it lands on step 39.
    assert landings == [31, 39]
    first, second = ball[30], ball[38]
    # v_in = 31·G·dt = -10.1267 m/s; v_out = -e·v_in with e = 0.1
    # (CPhysicsObj::handle_all_collisions, acclient.c:321807).
    # (float32 velocities: the fall's stores are replayed by support.fall, exact to the bit)
    assert fall(55.0, DT, 31)[1] == pytest.approx(31 * G * DT, rel=1e-6)
    assert first["velocity"][2] == pytest.approx(-0.1 * fall(55.0, DT, 31)[1], rel=1e-6)
    assert first["velocity"][2] == pytest.approx(1.0126667, abs=1e-6)
    # The second fall starts from rest at step 36 (apex deadband), so v_in = 4·G·dt = -1.3067.
    assert second["velocity"][2] == pytest.approx(-0.1 * fall(0.0, DT, 4)[1], rel=1e-6)
    # Both landings put the sphere's bottom on the ground (the sweep's contact plane z = 50).
    for landing in (first, second):
        assert landing["origin"][2] == 50.0
        assert set(landing["transient"]) >= {"contact", "on_walkable"}
        assert landing["events"].count("collision:environment") == 1


def test_between_the_bounces(records: dict[str, list[dict]]) -> None:
    ball = records["ball"]
    v_out = ball[30]["velocity"][2]
    # Step 32: landing zeroed the acceleration (contact and on walkable,
    # CPhysicsObj::calc_acceleration, acclient.c:317786), so the ball rises at v_out unchanged;
    # then it leaves the ground and gravity is back.
    assert ball[31]["origin"][2] == f32(f32(DT * v_out) + 50.0)
    assert ball[31]["velocity"][2] == v_out
    assert "leave_ground" in ball[31]["events"]
    # Steps 33-35 lose G·dt each: 0.686, 0.3593, 0.0327 m/s.
    for step in (33, 34, 35):
        assert ball[step - 1]["velocity"][2] == fall(0.0, DT, step - 32, v_out)[1]
    # Step 36: |v| = 0.0327 < 0.25, the deadband zeroes it before a·dt is added
    # (UpdatePhysicsInternal, acclient.c:317700): v = G·dt exactly, not 0.0327 + G·dt.
    assert ball[35]["velocity"][2] == f32(DT * G)


def test_the_ball_comes_to_rest(records: dict[str, list[dict]]) -> None:
    ball = records["ball"]
    # Step 40: 0.1307 m/s is inside the 0.25-m/s deadband: zeroed (acclient.c:317700).
    assert ball[39]["velocity"] == [0.0, 0.0, 0.0]
    # Step 41: no velocity, on walkable ground, no movement manager: ACTIVE dropped (same function).
    assert "active" in ball[39]["transient"]
    for record in ball[40:]:
        assert record["velocity"] == [0.0, 0.0, 0.0]
        assert record["origin"][2] == 50.0
        assert "active" not in record["transient"]
        assert {"contact", "on_walkable"} <= set(record["transient"])


def test_the_inelastic_missile_stops_dead_at_the_wall(tmp_path: Path) -> None:
    sim = acphys.load_scenario("ladder-07-bounce")
    trace = tmp_path / "missile.jsonl"
    sim.run(trace=trace)
    missile = [r for r in step_records(trace) if r["body"] == "missile"]
    hits = [i + 1 for i, r in enumerate(missile) if r["events"]]
    # 10 m/s moves 1/3 m a step from x = 100; the wall's west face is at 110 - 0.25 = 109.75.
    # Step 29 starts at 100 + 28/3 = 109.3333 and is swept in ceil((1/3) / 0.1) = 4 sub-steps
    # (CTransition::calc_num_steps, acclient.c:311763) of 1/12 m. The fourth (109.6667 + 0.1 >
    # 109.75) hits the wall; a PATH_CLIPPED body stops its sweep there at the last good sub-step,
    # 109.5833 (CTransition::find_transitional_position, acclient.c:313170).
    assert hits == [29]
    assert missile[28]["events"] == ["collision:environment"]
    expected_x = 100.0 + 28 * 10.0 * DT + 3 * (10.0 * DT / 4)
    # INELASTIC: the collision zeroes the velocity (CPhysicsObj::handle_all_collisions,
    # acclient.c:321807), and with no gravity it stays there.
    for record in missile[28:]:
        # Each of the 115 sub-steps so far stored its float32 check position near 105 m, where
        # the 1/12-m sub-step is 10922.67 spacings: each rounds up by a third of one.
        assert record["origin"][0] == pytest.approx(expected_x, abs=walk_tolerance(expected_x, 115))
        assert record["origin"][1:] == [120.0, 51.0]
        assert record["velocity"] == [0.0, 0.0, 0.0]
    # The environment report ends its life as a missile
    # (CPhysicsObj::report_environment_collision, acclient.c:320193).
    assert not sim.body("missile").state & PhysicsState.MISSILE
    assert sim.body("missile").state & PhysicsState.INELASTIC
