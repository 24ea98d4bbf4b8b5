"""Examples that do what they say: every claim in the comments of the built-in example scenarios
(default, hills, house, yard, seam, remote, carry), checked on a real run of the scenario; and the
acceptance walks of issue 12: with no [data] and no step heights given, the built-in human walks
at least 80% of 3.12 m/s x time over rolling hills, along and across a 4.8-degree slope, and from
outside through a doorway into a room and on across its floor into the next room.

The ladder-* scenarios have their own tests (tests/ladder/). Expected values are derived from
retail: the built-in walk is 3.12 m/s of root motion, 0.104 m a frame at 30 frames a second, one
frame per 30-Hz step (CMotionInterp::get_state_velocity @ 0x00527D50, acclient.c:343538; the
humanoid table's WalkForward cycle); running 4 m/s. Positions are float32 stores, so sums of steps
are compared within the drift of their stores (support.walk_tolerance).
"""

from __future__ import annotations

import itertools
import math
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

import acphys
from acphys.constants import GRAVITY
from acphys.math.vector import Vector3
from acphys.precision import f32
from acphys.scenario import builtin_scenario_text
from acphys.world.terrain import WaterType
from support import fall, step_records, ulp32, walk_tolerance

STEP = 3.12 / 30.0  # one walk frame a 30-Hz step
RUN_STEP = 4.0 / 30.0  # one run frame (RunForward, 4 m/s) a step
RADIUS = 0.48  # the human's spheres (setup 0x02000001)
STEP_UP = 0.6  # the built-in human's step-up height
LAND = 0xA9B4

Records = dict[str, list[dict[str, Any]]]


def _read(path: Path) -> Records:
    records: Records = {}
    for record in step_records(path):
        records.setdefault(record["body"], []).append(record)
    return records


@pytest.fixture(scope="module")
def run(tmp_path_factory: pytest.TempPathFactory) -> Callable[[str], tuple[acphys.Simulation, Records]]:
    """Run a built-in scenario to its end once per module: the simulation and its trace by body."""
    cache: dict[str, tuple[acphys.Simulation, Records]] = {}

    def go(name: str) -> tuple[acphys.Simulation, Records]:
        if name not in cache:
            sim = acphys.load_scenario(name)
            path = tmp_path_factory.mktemp(name) / f"{name}.jsonl"
            sim.run(trace=path)
            cache[name] = (sim, _read(path))
        return cache[name]

    return go


def _run_text(text: str, path: Path) -> tuple[acphys.Simulation, Records]:
    sim = acphys.parse_scenario(text, source="inline.toml")
    sim.run(trace=path)
    return sim, _read(path)


def _event_index(records: list[dict[str, Any]], event: str) -> int:
    return next(i for i, r in enumerate(records) if event in r["events"])


def _global_xy(record: dict[str, Any]) -> tuple[float, float]:
    """The record's origin in the landblock-global frame (landblock 0xXXYY starts at 192·XX, 192·YY)."""
    cell = int(record["cell"], 16)
    return (cell >> 24) * 192.0 + record["origin"][0], ((cell >> 16) & 0xFF) * 192.0 + record["origin"][1]


def _ccw_degrees(record: dict[str, Any]) -> float:
    """The rotation about +z of the record's orientation (counter-clockwise seen from above)."""
    w, _x, _y, z = record["orientation"]
    return math.degrees(2.0 * math.atan2(z, w))


def _compass(record: dict[str, Any]) -> float:
    return (-_ccw_degrees(record)) % 360.0


def _grounded(record: dict[str, Any]) -> bool:
    return {"contact", "on_walkable"} <= set(record["transient"])


def _unwrap(degrees: float) -> float:
    return (degrees + 180.0) % 360.0 - 180.0


# == default =======================================================================================


def test_default_skydiver_does_not_move_on_its_first_step_then_falls_by_v_dt_plus_half_a_dt2(run) -> None:
    _sim, records = run("default")
    sky = records["skydiver"]
    q = sky[0]["quantum"]
    # CPhysicsObj::UpdatePhysicsInternal @ 0x00510700 (acclient.c:317700) moves the origin only when
    # v² > 0, so the first step from rest only gains velocity; then z += v·dt + a·dt²/2 and v += a·dt
    # with retail's float stores (support.fall).
    assert sky[0]["origin"] == [96.0, 96.0, 400.0]
    assert sky[0]["velocity"] == [0.0, 0.0, f32(q * GRAVITY)]
    for n, record in enumerate(sky[:150], start=1):
        z, v = fall(400.0, q, n)
        assert record["velocity"][2] == v, n
        # (the sweep re-stores the candidate position: within a float32 spacing a step)
        assert abs(record["origin"][2] - z) <= (n + 1) * ulp32(z), n
        assert record["origin"][:2] == [96.0, 96.0]


def test_default_skydiver_is_clamped_to_50_m_per_s(run) -> None:
    _sim, records = run("default")
    sky = records["skydiver"]
    q = sky[0]["quantum"]
    # Free fall passes 50 m/s in step 154 (v = 154·q·g); from the next step UpdatePhysicsInternal
    # (acclient.c:317700) normalises the velocity to 50 m/s before it moves, then adds a·dt.
    first = next(n for n in range(1, 400) if fall(400.0, q, n)[1] < -50.0)
    assert first == 154
    assert sky[first - 1]["velocity"][2] == fall(400.0, q, first)[1]
    clamped = f32(f32(q * GRAVITY) - 50.0)
    six = next(i for i, r in enumerate(sky) if r["t"] > 6.0 - 1e-6)
    assert 5.1 < sky[first]["t"] < 5.2
    for record in sky[first : six + 1]:  # through the step at 6 s (see the next test)
        assert record["velocity"] == [0.0, 0.0, clamped], record["t"]


def test_default_gravity_off_at_6_s_leaves_the_skydiver_falling_at_exactly_50_m_per_s(run) -> None:
    _sim, records = run("default")
    sky = records["skydiver"]
    q = sky[0]["quantum"]
    six = next(i for i, r in enumerate(sky) if r["t"] > 6.0 - 1e-6)
    # CPhysicsObj::set_state @ 0x00514DD0 (acclient.c:322171) only stores the state: the step at
    # 6 s still integrates gravity, and its commit (CPhysicsObj::SetPositionInternal @ 0x00515330,
    # acclient.c:322503, calling calc_acceleration @ 0x00510950, acclient.c:317786) sets a = 0.
    assert sky[six]["velocity"][2] == f32(f32(q * GRAVITY) - 50.0)
    for before, record in zip(sky[six:], sky[six + 1 :], strict=False):
        assert record["velocity"] == [0.0, 0.0, -50.0], record["t"]
        drop = before["origin"][2] - record["origin"][2]
        assert drop == pytest.approx(50.0 * q, abs=2 * ulp32(before["origin"][2]))


def test_default_ball_flies_a_parabola_lands_hops_once_and_slides_to_a_stop(run) -> None:
    _sim, records = run("default")
    ball = records["ball"]
    q = ball[0]["quantum"]
    land = _event_index(ball, "hit_ground")
    # The parabola: x = 40 + 6t, z and v_z by UpdatePhysicsInternal's stores from v_z = 9 at 60 m.
    # The sphere (r 0.1, centre 0.1 up) meets the ground in the first step whose free fall goes
    # below 50 m.
    assert land == next(n for n in range(1, 200) if fall(60.0, q, n, 9.0)[0] < 50.0) - 1
    assert ball[land]["t"] == pytest.approx(2.6333, abs=1e-3)
    for n, record in enumerate(ball[:land], start=1):
        z, v = fall(60.0, q, n, 9.0)
        assert record["velocity"] == [6.0, 0.0, v]
        assert abs(record["origin"][2] - z) <= (n + 1) * ulp32(z)
        assert abs(record["origin"][0] - (40.0 + 6.0 * q * n)) <= (n + 1) * ulp32(60.0)
    # The landing reflects v_z·(1 + e) along the terrain normal (CPhysicsObj::handle_all_collisions
    # @ 0x00514780, acclient.c:321807): 0.05 of the 16.8 m/s it arrives with (the previous
    # step's v_z plus this step's g·dt), upward. More than friction's 0.25 m/s (calc_friction @
    # 0x0050EE70, acclient.c:316090): it hops once.
    arriving = f32(ball[land - 1]["velocity"][2] + f32(q * GRAVITY))
    assert arriving == pytest.approx(-16.8, abs=0.01)
    assert ball[land]["velocity"][2] == pytest.approx(-0.05 * arriving, rel=1e-5)
    events = [e for r in ball for e in r["events"] if e in ("hit_ground", "leave_ground")]
    assert events == ["hit_ground", "leave_ground", "hit_ground"]
    # Then it slides to a stop: at rest, on walkable ground, with no movement manager it
    # deactivates (UpdatePhysicsInternal), and lies still.
    stop = next(i for i, r in enumerate(ball) if r["velocity"] == [0.0, 0.0, 0.0])
    assert ball[stop]["t"] < 4.0
    assert all(r["origin"] == ball[stop]["origin"] and _grounded(r) for r in ball[stop:])
    assert "active" not in ball[-1]["transient"]
    assert ball[stop]["origin"][0] > ball[land]["origin"][0] + 2.0  # it slid on east
    assert ball[stop]["origin"][2] == pytest.approx(50.0, abs=1e-4)


def test_default_spinner_turns_in_place_at_its_omega_and_reverses_at_4_s(run) -> None:
    _sim, records = run("default")
    spin = records["spinner"]
    # Frame::grotate @ 0x005357A0 (acclient.c:357421) turns it by omega·dt a step: 90°/s is 3° a
    # 30-Hz step counter-clockwise; set_omega at 4 s (fired before that tick's UseTime) makes the
    # step ending at 4 s the first at -45°/s, -1.5°.
    angles = [0.0] + [_ccw_degrees(r) for r in spin]
    for before, after, record in zip(angles, angles[1:], spin, strict=False):
        expected = 3.0 if record["t"] < 4.0 - 1e-6 else -1.5
        assert _unwrap(after - before) == pytest.approx(expected, abs=1e-3), record["t"]
    # A setup without spheres keeps its origin (its sweep has nothing to move) and takes the rotation.
    assert all(r["origin"] == [120.0, 96.0, 52.0] for r in spin)
    assert _compass(spin[-1]) == pytest.approx(360.0 - (119 * 3.0 - 121 * 1.5), abs=1e-3)


def test_default_drifter_crosses_into_landblock_0xAAB4_at_x_192(run) -> None:
    _sim, records = run("default")
    drift = records["drifter"]
    q = drift[0]["quantum"]
    crossed = False
    for n, record in enumerate(drift, start=1):
        x, _y = _global_xy(record)
        # No gravity: a constant 2 m/s east (UpdatePhysicsInternal), from x = 186 of 0xA9B4.
        assert x - 0xA9 * 192.0 == pytest.approx(186.0 + 2.0 * q * n, abs=1e-3)
        assert record["velocity"] == [2.0, 0.0, 0.0]
        assert record["origin"][1:] == [100.0, 55.0]
        block = int(record["cell"], 16) >> 16
        assert block == (0xAAB4 if x - 0xA9 * 192.0 >= 192.0 else 0xA9B4), record["t"]
        crossed = crossed or block == 0xAAB4
    assert crossed
    assert drift[-1]["origin"][0] == pytest.approx(186.0 + 16.0 - 192.0, abs=1e-3)


def test_default_sitter_is_at_rest_on_walkable_ground_and_deactivates(run) -> None:
    _sim, records = run("default")
    sitter = records["sitter"]
    # No velocity, no movement manager, on walkable ground: UpdatePhysicsInternal (acclient.c:317700)
    # clears ACTIVE on the first step.
    assert all("active" not in r["transient"] and _grounded(r) for r in sitter)
    assert all(r["origin"] == [60.0, 96.0, 50.0] for r in sitter)


def test_default_walker_walks_from_its_first_step_and_stops_at_6_s(run) -> None:
    _sim, records = run("default")
    walker = records["walker"]
    start = _event_index(walker, "motion:WalkForward")
    stop = _event_index(walker, "stop_motion:WalkForward")
    # add_motion @ 0x005224B0 (acclient.c:337430) replaces the sequence's velocity with each motion
    # it adds, the link first and the cycle last, so the 4-frame Ready->WalkForward link already
    # plays at the cycle's 3.12 m/s: the step the command arrives in moves a whole frame.
    assert walker[start]["t"] == pytest.approx(0.5, abs=1e-6)
    ys = [r["origin"][1] for r in walker]
    assert ys[start] - ys[start - 1] == pytest.approx(STEP, abs=2 * ulp32(60.0))
    steps = [ys[i] - ys[i - 1] for i in range(start, stop)]
    assert len(steps) == 165
    assert all(s == pytest.approx(STEP, abs=2 * ulp32(80.0)) for s in steps)
    assert abs(ys[stop - 1] - (60.0 + 165 * STEP)) < walk_tolerance(77.0, 165)
    # stop_motion at 6 s: the WalkForward->Ready link plays at Ready's zero velocity.
    assert all(y == ys[stop - 1] for y in ys[stop:])
    assert all(_grounded(r) for r in walker)


def test_default_runner_runs_jumps_lands_hops_and_runs_on(run) -> None:
    _sim, records = run("default")
    runner = records["runner"]
    q = runner[0]["quantum"]
    start = _event_index(runner, "motion:WalkForward")
    jump = _event_index(runner, "jump")
    ys = [r["origin"][1] for r in runner]
    # WalkForward with the run key is RunForward: 4 m/s, 4/30 m a step.
    for i in range(start, jump):
        assert ys[i] - ys[i - 1] == pytest.approx(RUN_STEP, abs=2 * ulp32(80.0))
    # The jump at 3 s: CMotionInterp::jump @ 0x00528780 (acclient.c:344223) leaves the ground with
    # 10 m/s up (get_jump_v_z without a weenie, acclient.c:343342) and the 4 m/s of the run
    # (LeaveGround @ 0x00528B00, acclient.c:344456); the step then adds g·dt.
    assert runner[jump]["t"] == pytest.approx(3.0, abs=1e-6)
    assert "leave_ground" in runner[jump]["events"]
    assert runner[jump]["velocity"] == [0.0, 4.0, f32(f32(q * GRAVITY) + 10.0)]
    # It lands in the step in which its free fall from 10 m/s first goes below where it left.
    z0 = runner[jump - 1]["origin"][2]
    flight = next(n for n in range(1, 200) if fall(z0, q, n, 10.0)[0] < z0)
    land = _event_index(runner[jump:], "hit_ground") + jump
    assert land - jump == flight - 1 == 61  # 2.03 s after the jump
    assert runner[land]["t"] == pytest.approx(3.0 + 61 / 30.0, abs=1e-4)
    # It hops once (its 0.05 bounce of ~10 m/s is above friction's 0.25 m/s) ...
    after = [e for r in runner[land:] for e in r["events"] if e in ("hit_ground", "leave_ground")]
    assert after == ["hit_ground", "leave_ground", "hit_ground"]
    # ... and runs on: on the ground at the end, at the run's 4/30 m a step.
    assert _grounded(runner[-1])
    assert ys[-1] - ys[-2] == pytest.approx(RUN_STEP, abs=2 * ulp32(90.0))
    assert ys[-1] > ys[land] + 4.0 * (runner[-1]["t"] - runner[land]["t"])


# == hills =========================================================================================


def _hills_terrain(sim: acphys.Simulation):
    return sim.world.landscape.get_landblock(LAND << 16 | 0xFFFF).terrain


def _slope(poly) -> float:
    return math.degrees(math.acos(poly.plane.N.z))


def test_hills_heights_go_through_retail_land_height_table() -> None:
    # No height_table: byte i is 2·i m, the part of retail's table acphys ships
    # (CLandBlockStruct::ConstructVertices @ 0x005328D0, acclient.c:354620, reads it).
    assert all(
        "height_table" not in block for block in tomllib.loads(builtin_scenario_text("hills"))["landblock"]
    )
    sim = acphys.load_scenario("hills")
    terrain = _hills_terrain(sim)
    assert min(terrain.height) >= 20 and max(terrain.height) <= 31
    for x in range(9):
        for y in range(9):
            assert terrain.vertex(x, y).z == 2.0 * terrain.height[9 * x + y]


def test_hills_slope_up_to_17_degrees_and_the_lake_banks_more() -> None:
    terrain = _hills_terrain(acphys.load_scenario("hills"))
    lake_side = [(cx, cy) for cx in range(3) for cy in range(5, 8)]  # cells touching a lake vertex
    dry = [
        _slope(p)
        for cx in range(8)
        for cy in range(8)
        if (cx, cy) not in lake_side
        for p in terrain.cell_polygons(cx, cy)
    ]
    banks = [_slope(p) for cx, cy in lake_side for p in terrain.cell_polygons(cx, cy)]
    lake = {(x, y) for x in range(3) for y in range(6, 9)}
    assert {terrain.height[9 * x + y] for x, y in lake} == {20}
    rises = [
        abs(terrain.height[9 * x + y] - terrain.height[9 * (x + dx) + y + dy])
        for x in range(9)
        for y in range(9)
        for dx, dy in ((1, 0), (0, 1))
        if x + dx < 9 and y + dy < 9 and not {(x, y), (x + dx, y + dy)} & lake
    ]
    assert max(rises) == 3  # 6 m over a 24-m cell
    assert 16.5 < max(dry) < 17.0
    assert 43.0 < max(banks) < 43.5
    row = [_slope(p) for cx in range(8) for p in terrain.cell_polygons(cx, 2)]  # the hiker's row
    assert 10.5 < max(row) < 10.6


def test_hills_lake_cells_are_water() -> None:
    # CLandBlockStruct::CalcCellWater @ 0x00531550 (acclient.c:353607): a cell is entirely water
    # when its four corners are water (the nine lake vertices, terrain type 17), partially when
    # some are.
    block = acphys.load_scenario("hills").world.landscape.get_landblock(LAND << 16 | 0xFFFF)
    for cx in range(8):
        for cy in range(8):
            corners = {(x, y) for x in (cx, cx + 1) for y in (cy, cy + 1)}
            wet = sum(1 for x, y in corners if x <= 2 and y >= 6)
            expected = (
                WaterType.ENTIRELY_WATER
                if wet == 4
                else WaterType.PARTIALLY_WATER
                if wet
                else WaterType.NOT_WATER
            )
            assert block.lcell[8 * cx + cy].water_type == expected, (cx, cy)
    assert (
        sum(
            block.lcell[8 * cx + cy].water_type == WaterType.ENTIRELY_WATER
            for cx in range(8)
            for cy in range(8)
        )
        == 4
    )


def test_hills_hiker_walks_east_over_the_hill_down_the_valley_and_up_at_nearly_the_full_walk(run) -> None:
    sim, records = run("hills")
    hiker = records["hiker"]
    terrain = _hills_terrain(sim)
    start = _event_index(hiker, "motion:WalkForward")
    assert hiker[start]["t"] == pytest.approx(0.5, abs=1e-6)
    # On the ground at the west edge, and on walkable ground every step after.
    assert hiker[0]["origin"][2] == pytest.approx(
        terrain.get_height(Vector3(6.0, 54.0, 0.0)) + 0.005, abs=1e-4
    )
    assert terrain.get_height(Vector3(6.0, 54.0, 0.0)) == pytest.approx(50.5, abs=1e-4)
    assert all(_grounded(r) for r in hiker)
    assert all(48.0 <= r["origin"][1] < 72.0 for r in hiker)  # in the row of cells y 48-72
    # Over the hill ...
    zs = [r["origin"][2] for r in hiker]
    top = max(range(len(zs)), key=zs.__getitem__)
    assert 47.0 < hiker[top]["origin"][0] < 49.0
    assert zs[top] == pytest.approx(55.5, abs=0.05)
    # ... down into the valley ...
    low = min(range(top, len(zs)), key=zs.__getitem__)
    assert 119.0 < hiker[low]["origin"][0] < 121.0
    assert zs[low] == pytest.approx(43.5, abs=0.05)
    # ... and up the far slope.
    assert zs[-1] > zs[low] + 7.0
    # Each 0.104-m step keeps its horizontal length downhill (CTransition::adjust_offset @ 0x0050A370,
    # acclient.c:311863, snaps a step leaving the plane onto it) and loses its part into the slope
    # uphill: at least 0.104 cos² 10.6° horizontally. 1666 steps in the 55.5 s.
    walk = hiker[start - 1 :]
    steps = len(walk) - 1
    assert steps == 1666
    horizontal = sum(math.dist(a["origin"][:2], b["origin"][:2]) for a, b in itertools.pairwise(walk))
    full = steps * STEP
    assert full == pytest.approx(173.26, abs=0.01)
    assert full * math.cos(math.radians(10.6)) ** 2 < horizontal < full
    assert 171.0 < horizontal < 172.0
    assert hiker[-1]["origin"][0] > 177.0


def test_hills_stone_lands_on_the_lake_bed_hops_and_rests_0_9_m_into_it(run) -> None:
    _sim, records = run("hills")
    stone = records["stone"]
    q = stone[0]["quantum"]
    # CLandCell::find_env_collisions @ 0x00532F20 (acclient.c:354991) rests sphere 0 on the terrain
    # plane lowered by the cell's water depth: 0.9 m for an entirely-water cell
    # (CObjCell::get_water_depth @ 0x0052B8A0, acclient.c:347232). The bed is at 40 m (byte 20).
    rest = 40.0 - 0.9
    land = _event_index(stone, "hit_ground")
    assert land == next(n for n in range(1, 200) if fall(50.0, q, n)[0] < rest) - 1
    assert stone[land]["t"] == pytest.approx(1.5, abs=1e-4)
    events = [e for r in stone for e in r["events"] if e in ("hit_ground", "leave_ground")]
    assert events == ["hit_ground", "leave_ground", "hit_ground"]
    assert stone[-1]["origin"] == [24.0, 168.0, pytest.approx(rest, abs=1e-5)]
    assert stone[-1]["velocity"] == [0.0, 0.0, 0.0]
    assert {"contact", "on_walkable", "water_contact"} <= set(stone[-1]["transient"])
    assert "active" not in stone[-1]["transient"]


# == seam ==========================================================================================


SEAM_SLOPE = math.atan(2.0 / 24.0)  # 2 m a 24-m cell: 4.76 degrees


def test_seam_terrain_is_continuous_and_rises_2_m_a_cell_on_both_sides() -> None:
    sim = acphys.load_scenario("seam")
    assert all(
        "height_table" not in block for block in tomllib.loads(builtin_scenario_text("seam"))["landblock"]
    )
    west = sim.world.landscape.get_landblock(0xA9B4FFFF).terrain
    east = sim.world.landscape.get_landblock(0xAAB4FFFF).terrain
    for y in range(9):
        assert west.vertex(8, y).z == east.vertex(0, y).z == 48.0
        assert west.vertex(8, y).z - west.vertex(7, y).z == 2.0
        assert east.vertex(1, y).z - east.vertex(0, y).z == 2.0
        assert east.vertex(2, y).z == east.vertex(8, y).z == 52.0


def test_seam_walker_crosses_the_seam_in_its_78th_step_on_the_ground(run) -> None:
    _sim, records = run("seam")
    walker = records["walker"]
    start = _event_index(walker, "motion:WalkForward")
    assert all(_grounded(r) for r in walker)
    # Uphill, CTransition::adjust_offset (acclient.c:311863) takes the step's part into the slope
    # off: 0.104 cos² of the slope eastward (0.1033 m), so the 8 m to the seam take 78 steps.
    east_step = STEP * math.cos(SEAM_SLOPE) ** 2
    steps = math.ceil(8.0 / east_step)
    assert steps == 78
    crossing = next(i for i, r in enumerate(walker) if r["cell"].startswith("0xAAB4"))
    assert crossing - start + 1 == steps
    assert walker[crossing]["t"] == pytest.approx(0.5 + 77 / 30.0, abs=1e-4)
    assert all(r["cell"].startswith("0xA9B4") for r in walker[:crossing])
    assert all(r["cell"].startswith("0xAAB4") for r in walker[crossing:])
    # At 48 m, on the one plane on either side: the low point 0.005 under the sphere's rest.
    for record in walker[crossing - 1 : crossing + 1]:
        x, _y = _global_xy(record)
        assert record["origin"][2] == pytest.approx(48.0 + (x - 0xAA * 192.0) / 12.0 + 0.005, abs=2e-3)
    xs = [_global_xy(r)[0] for r in walker[start - 1 : crossing + 1]]
    assert all(b - a == pytest.approx(east_step, abs=1e-4) for a, b in itertools.pairwise(xs))


def test_seam_walker_walks_up_to_the_crest_and_on_along_the_level_top(run) -> None:
    _sim, records = run("seam")
    walker = records["walker"]
    start = _event_index(walker, "motion:WalkForward")
    east_step = STEP * math.cos(SEAM_SLOPE) ** 2
    # The crest is x = 48 of 0xAAB4, 56 m from the start: 543 uphill steps.
    crest_steps = math.ceil(56.0 / east_step)
    crest = next(i for i, r in enumerate(walker) if r["origin"][0] >= 48.0 and r["cell"].startswith("0xAAB4"))
    assert crest - start + 1 == crest_steps == 543
    assert walker[crest]["t"] == pytest.approx(18.567, abs=1e-3)
    # On the level top: the whole 0.104-m step, at 52 m.
    xs = [r["origin"][0] for r in walker[crest:]]
    assert len(xs) > 30
    assert all(b - a == pytest.approx(STEP, abs=2 * ulp32(64.0)) for a, b in itertools.pairwise(xs))
    assert all(r["origin"][2] == pytest.approx(52.005, abs=1e-5) for r in walker[crest:])


# == house =========================================================================================


def test_house_rooms_are_env_cells_and_the_building_stands_in_the_land_cell_under_it() -> None:
    sim = acphys.load_scenario("house")
    hall, parlour = sim.world.get_cell(0xA9B40100), sim.world.get_cell(0xA9B40101)
    assert hall is not None and parlour is not None
    # CLandBlock::init_buildings @ 0x0052FD80 (acclient.c:352113) adds a building to the one land
    # cell under its origin (CBuildingObj::add_to_cell @ 0x006B5550, acclient.c:719256): (108, 108)
    # is cell 1 + 8·4 + 4 = 0x25.
    holding = [c for c in range(1, 65) if sim.world.get_cell(LAND << 16 | c).has_building()]
    assert holding == [0x25]


def test_house_visitor_walks_through_the_front_door_and_the_inner_doorway_to_the_far_wall(run) -> None:
    _sim, records = run("house")
    visitor = records["visitor"]
    start = _event_index(visitor, "motion:WalkForward")
    assert all(_grounded(r) for r in visitor)
    # Its cell follows sphere 0's centre (CObjCell::find_cell_list @ 0x0052B4E0, acclient.c:346960):
    # the land cell, the hall past x = 104, the parlour past x = 108.
    for record in visitor:
        x = record["origin"][0]
        expected = "0xA9B40025" if x < 104.0 else "0xA9B40100" if x < 108.0 else "0xA9B40101"
        assert record["cell"] == expected, (record["t"], x)
    assert {r["cell"] for r in visitor} == {"0xA9B40025", "0xA9B40100", "0xA9B40101"}
    # Full walk steps until the parlour's east wall (x = 112): the step that would bring sphere 0
    # within its radius of the wall is rolled back (CTransition::validate_transition @ 0x0050AA70,
    # acclient.c:312193), leaving it at its last clear step, 97.5 + 134 x 0.104.
    last = math.floor((112.0 - RADIUS - 97.5) / STEP)
    assert last == 134
    xs = [r["origin"][0] for r in visitor]
    assert abs(xs[-1] - (97.5 + last * STEP)) < walk_tolerance(111.0, last)
    stopped = next(i for i in range(start, len(xs)) if xs[i] == xs[-1])
    assert stopped - start + 1 == last
    assert visitor[stopped]["t"] < 5.0
    assert all(r["origin"][1] == 108.0 for r in visitor)


def test_house_resident_starts_and_stays_in_the_parlour(run) -> None:
    _sim, records = run("house")
    resident = records["resident"]
    assert all(r["cell"] == "0xA9B40101" and _grounded(r) for r in resident)
    assert all(r["origin"] == resident[0]["origin"] for r in resident)
    assert resident[0]["origin"][:2] == [110.5, 106.0]


def test_a_house_is_found_only_through_the_land_cell_under_its_origin(tmp_path: Path) -> None:
    # The header's reason for placing the house: retail lists a building in one land cell
    # (CBuildingObj::add_to_cell, acclient.c:719256) and a sweep finds its shell and rooms only
    # through that cell (CSortCell::find_transit_cells @ 0x00534060, acclient.c:356086;
    # CBuildingObj::find_building_transit_cells, acclient.c:719067). Moved so that its origin,
    # (96.5, 108), is in land cell 0x25 (x >= 96) but its hall reaches x = 92.5, a body walking
    # north through the hall at x = 93.5 (sphere 0 never reaching x = 96) never meets it: it walks
    # through both shell walls and stays in the land cell 0x1D.
    text = builtin_scenario_text("house").replace(
        "origin = [108.0, 108.0, 50.0]", "origin = [96.5, 108.0, 50.0]"
    )
    text = text.replace(
        "origin = [97.5, 108.0, 50.0]\nheading = 90.0", "origin = [93.5, 101.0, 50.0]\nheading = 0.0"
    ).replace("origin = [110.5, 106.0, 50.0]", "origin = [98.5, 106.0, 50.0]")
    _sim, records = _run_text(text, tmp_path / "moved.jsonl")
    visitor = records["visitor"]
    start = _event_index(visitor, "motion:WalkForward")
    assert visitor[-1]["origin"][1] > 111.25 + 1.0  # past the shell's north wall
    assert abs(visitor[-1]["origin"][1] - (101.0 + (len(visitor) - start) * STEP)) < walk_tolerance(
        115.0, 170
    )
    assert {r["cell"] for r in visitor} == {"0xA9B4001D"}


# == yard ==========================================================================================


def test_yard_walker_stops_at_its_last_clear_step_before_the_pillar(run) -> None:
    _sim, records = run("yard")
    walker = records["walker"]
    # The pillar's cylsphere (r 1, axis at y = 100) and sphere 0 (r 0.48) meet within 1.48 m
    # (CCylSphere::intersects_sphere @ 0x0053B440, acclient.c:362034); the 3-m pillar is no step
    # (CCylSphere::step_sphere_up, acclient.c:361975), the head-on slide leaves nothing and the
    # step is rolled back: 62 steps, 98.448, 0.552 m short of its face.
    last = math.floor((100.0 - 1.0 - RADIUS - 92.0) / STEP)
    assert last == 62
    assert 100.0 - (92.0 + (last + 1) * STEP) < 1.0 + RADIUS
    origin = walker[-1]["origin"]
    assert abs(origin[1] - (92.0 + last * STEP)) < walk_tolerance(98.0, last)
    assert origin[0] == 96.0 and origin[2] == f32(50.005)
    assert all(_grounded(r) for r in walker)
    assert "sliding" in walker[-1]["transient"]


def test_yard_climber_climbs_the_stairs_and_stays_on_the_top(run) -> None:
    _sim, records = run("yard")
    climber = records["climber"]
    assert all(_grounded(r) for r in climber)
    # Each 0.3-m riser is under the 0.6-m step-up: CTransition::step_up @ 0x0050B610
    # (acclient.c:312793) lifts sphere 0 onto each tread in turn, 0.005 over it as on the ground.
    heights = sorted({round(r["origin"][2], 4) for r in climber})
    assert heights == [50.005, 50.305, 50.605, 50.905, 51.205]
    # On the top (y 87.5-88) it walks on until its centre is 0.2 m past the back edge; the next
    # step would put it 0.304 m past, more than half a radius: CTransition::step_down @ 0x0050B2A0
    # (acclient.c:312628) refuses it for an EDGE_SLIDE body (check_walkable, acclient.c:312474;
    # SPHEREPATH::precipice_slide, acclient.c:313979), so it stays 1.2 m up.
    last = 50  # 83 + 50 x 0.104 = 88.2
    assert 83.0 + last * STEP - 88.0 < RADIUS / 2 < 83.0 + (last + 1) * STEP - 88.0
    origin = climber[-1]["origin"]
    assert abs(origin[1] - (83.0 + last * STEP)) < walk_tolerance(88.0, last)
    assert origin[2] == pytest.approx(51.205, abs=1e-5)
    top = next(i for i, r in enumerate(climber) if r["origin"][1] == origin[1])
    assert all(r["origin"] == origin for r in climber[top:])
    assert climber[top]["t"] < 2.5


def test_yard_climber_without_edge_slide_would_step_down_behind_the_stairs(tmp_path: Path) -> None:
    # The header's counterfactual: without EDGE_SLIDE the step past the edge is taken, and the
    # step-down (1.5 m) reaches the ground 1.2 m below once sphere 0 clears the edge.
    text = builtin_scenario_text("yard").replace(
        'origin = [104.0, 83.0, 50.0]\nstate = ["gravity", "report_collisions", "edge_slide"]',
        'origin = [104.0, 83.0, 50.0]\nstate = ["gravity", "report_collisions"]',
    )
    _sim, records = _run_text(text, tmp_path / "no-edge-slide.jsonl")
    climber = records["climber"]
    assert all(_grounded(r) for r in climber)
    assert climber[-1]["origin"][1] > 90.0
    assert climber[-1]["origin"][2] == pytest.approx(50.005, abs=1e-5)


def test_yard_ledger_is_stopped_by_the_1_m_ledge(run) -> None:
    _sim, records = run("yard")
    ledger = records["ledger"]
    # 1 m is beyond the human's step-up: the step-up (BSPTREE::step_sphere_up @ 0x00539F20,
    # acclient.c:361071, CTransition::step_up) finds no walkable top in reach, the head-on slide
    # (SPHEREPATH::step_up_slide, acclient.c:313455) leaves nothing: rolled back at the last
    # clear step before the face at y = 103.
    last = math.floor((103.0 - RADIUS - 99.0) / STEP)
    assert last == 33
    origin = ledger[-1]["origin"]
    assert abs(origin[1] - (99.0 + last * STEP)) < walk_tolerance(102.0, last)
    assert origin[0] == 88.0 and origin[2] == f32(50.005)
    assert all(_grounded(r) for r in ledger)


def test_yard_leaner_slides_north_along_the_east_wall(run) -> None:
    _sim, records = run("yard")
    leaner = records["leaner"]
    start = _event_index(leaner, "motion:WalkForward")
    across = along = STEP * math.sin(math.radians(45.0))
    # It closes on the wall's west face (x = 111.75) to its last clear step ...
    last = math.floor((111.75 - RADIUS - 106.0) / across)
    assert last == 71
    xs = [r["origin"][0] for r in leaner]
    assert abs(xs[-1] - (106.0 + last * across)) < walk_tolerance(111.0, last)
    hit = next(i for i in range(start, len(xs)) if xs[i] == xs[-1])
    # ... and keeps the step's part along the wall (CSphere::slide_sphere @ 0x00537440,
    # acclient.c:358898; adjust_offset with the sliding normal): 0.104 sin 45 north a step.
    ys = [r["origin"][1] for r in leaner[hit:]]
    assert len(ys) > 20
    assert all(b - a == pytest.approx(along, abs=2 * ulp32(110.0)) for a, b in itertools.pairwise(ys))
    assert "sliding" in leaner[-1]["transient"]
    assert all(_grounded(r) for r in leaner)


# == remote ========================================================================================

GLIDE = 8.0 / 30.0  # twice the adjusted max speed (4 m/s without a weenie) per 1/30-s step


def test_remote_glides_to_each_server_position_turning_at_once_and_snaps_past_the_blip(run) -> None:
    _sim, records = run("remote")
    remote = records["remote"]
    events = [i for i, r in enumerate(remote) if "interpolate_to" in r["events"]]
    assert len(events) == 4
    targets = [(99.0, 96.0), (99.0, 100.0), (96.0, 104.0)]
    headings = [0.0, 90.0, 0.0]
    for index, target, heading in zip(events, targets, headings, strict=False):
        # InterpolationManager::adjust_offset @ 0x00555D30 (acclient.c:389177): a glide of
        # 2 x get_adjusted_max_speed (acclient.c:343511) a second, the node's whole rotation at once.
        glide = remote[index : index + 3]
        for before, after in zip(remote[index - 1 : index + 2], glide, strict=True):
            assert math.dist(before["origin"][:2], after["origin"][:2]) == pytest.approx(GLIDE, abs=1e-4)
        assert _unwrap(_compass(remote[index]) - heading) == pytest.approx(0.0, abs=1e-3)
        # It completes the node within 0.05 m (DESIRED_DISTANCE) before the next arrives.
        nxt = events[events.index(index) + 1]
        assert math.dist(remote[nxt - 1]["origin"][:2], target) < 0.05
    # 111 m: beyond the 100-m outdoor blip distance (CPhysicsObj::GetAutonomyBlipDistance @
    # 0x0050EB70, acclient.c:315860): one step puts it there.
    snap = remote[events[3]]
    assert math.dist((96.0, 104.0), (20.0, 180.0)) > 100.0
    assert snap["origin"][:2] == [20.0, 180.0]
    assert snap["cell"] == "0xA9B40008"
    assert all(r["origin"][:2] == [20.0, 180.0] for r in remote[events[3] :])


def test_remote_pet_keeps_the_standoff_while_the_stick_is_renewed_and_stays_when_let_go(run) -> None:
    _sim, records = run("remote")
    owner = {round(r["t"], 4): r["origin"][0] for r in records["owner"]}
    pet = records["pet"]
    sticks = [r["t"] for r in pet if "stick_to:owner" in r["events"]]
    assert sticks == pytest.approx([0.2, 1.0, 1.8, 2.6], abs=1e-3)
    for record in pet:
        if 0.45 < record["t"] < 3.0:
            # StickyManager::adjust_offset @ 0x00555430 (acclient.c:388518): 0.3 m between the two
            # 0.48-m cylinders.
            gap = owner[round(record["t"], 4)] - record["origin"][0] - 2 * RADIUS
            assert gap == pytest.approx(0.3, abs=2 * ulp32(100.0)), record["t"]
    release = _event_index(pet, "unstick")
    assert pet[release]["t"] == pytest.approx(3.0, abs=1e-6)
    assert len({r["origin"][0] for r in pet[release + 1 :]}) == 1
    assert owner[round(pet[-1]["t"], 4)] - pet[-1]["origin"][0] > 5.0  # the owner walked on


def test_remote_leashed_body_walks_north_held_between_1_and_3_m(run) -> None:
    sim, records = run("remote")
    ys = [r["origin"][1] for r in records["leashed"]]
    steps = [b - a for a, b in itertools.pairwise(ys)]
    # ConstraintManager::adjust_offset @ 0x00556180 (acclient.c:389477): whole walk frames inside
    # 1 m, damped by (3 - d) / (3 - 1) beyond, never past 3 m.
    inside = [s for y, s in zip(ys, steps, strict=False) if y - 60.0 + STEP < 1.0]
    assert inside and all(s == pytest.approx(STEP, abs=2 * ulp32(64.0)) for s in inside)
    assert all(b <= a + 1e-9 for a, b in itertools.pairwise(steps))
    assert 2.9 < sim.body("leashed").position.frame.origin.y - 60.0 <= 3.0
    assert all(r["origin"][0] == 120.0 for r in records["leashed"])


def test_remote_grower_scales_up_and_back() -> None:
    sim = acphys.load_scenario("remote")
    grower = sim.body("grower")
    # ScaleHook::Execute @ 0x00526E40 (acclient.c:342473): to 2 over 1 s from 0.5 s, back to 1
    # over 0.5 s from 2 s.
    sim.run(until=1.0)
    assert 1.0 < grower.scale < 2.0
    sim.run(until=1.6)
    assert grower.scale == pytest.approx(2.0)
    sim.run(until=2.7)
    assert grower.scale == pytest.approx(1.0)


# == carry =========================================================================================

HAND = (0.7, 0.3, 1.1)


def test_carry_porter_walks_north_with_the_lantern_at_arms_length(run, tmp_path: Path) -> None:
    _sim, records = run("carry")
    porter, lantern = records["porter"], records["lantern"]
    assert "holds:lantern" in porter[0]["events"]
    # Held, the lantern is carried by the porter's set_frame (CPhysicsObj::UpdateChildrenInternal
    # @ 0x00513DA0, acclient.c:321121) and takes no steps: no trace record before the release.
    assert lantern[0]["t"] > 2.0
    sim = acphys.load_scenario("carry")
    sim.run(until=1.5)
    carried = sim.body("lantern").position.frame.origin
    hand = [f32(a + f32(b)) for a, b in zip(sim.body("porter").position.frame.origin, HAND, strict=True)]
    assert list(carried) == hand
    ys = [r["origin"][1] for r in porter]
    assert all(b - a == pytest.approx(STEP, abs=2 * ulp32(90.0)) for a, b in itertools.pairwise(ys))


def test_carry_lantern_let_go_is_inactive_where_the_hand_was_then_tossed_east_lands_and_rests(run) -> None:
    _sim, records = run("carry")
    porter, lantern = records["porter"], records["lantern"]
    # Let go at 2 s (CPhysicsObj::unset_parent @ 0x00513470, acclient.c:320479 clears its transient
    # states), where the hand was at the porter's last step before.
    first = lantern[0]
    assert "unset_parent" in first["events"]
    assert first["transient"] == []
    released = max((r for r in porter if r["t"] <= 2.0), key=lambda r: r["t"])
    assert first["origin"] == [f32(a + f32(b)) for a, b in zip(released["origin"], HAND, strict=True)]
    # The toss at 2.05 s wakes it (set_velocity @ 0x005113F0, acclient.c:318577): it flies east ...
    toss = lantern[1]
    assert "active" in toss["transient"]
    assert toss["velocity"][0] == 3.0
    # (its first record also carries the hit_ground of its placement on the ground at 0 s)
    land = next(i for i in range(1, len(lantern)) if "hit_ground" in lantern[i]["events"])
    assert all(not _grounded(r) for r in lantern[1:land])
    # ... lands, and comes to rest on the ground, inactive.
    last = lantern[-1]
    assert last["velocity"] == [0.0, 0.0, 0.0]
    assert _grounded(last) and "active" not in last["transient"]
    assert last["origin"][2] == pytest.approx(50.0, abs=1e-6)
    assert last["origin"][0] > first["origin"][0] + 3.0
    assert last["origin"][1] == first["origin"][1]


# == issue 12 acceptance: the built-in human walks =================================================

WALK_SPEED = 3.12


def _acceptance_walk(records: list[dict[str, Any]], direction: tuple[float, float]) -> tuple[float, float]:
    """(distance made good along ``direction`` since the walk started, the time walked)."""
    start = _event_index(records, "motion:WalkForward")
    first, last = records[start - 1], records[-1]
    time = sum(r["quantum"] for r in records[start:])
    (x0, y0), (x1, y1) = _global_xy(first), _global_xy(last)
    return (x1 - x0) * direction[0] + (y1 - y0) * direction[1], time


def _walker(name: str, origin: tuple[float, float, float], heading: float, landblock: str = "0xA9B4") -> str:
    # The built-in human (no setup named), no step heights given, on the ground.
    return (
        f'[[body]]\nname = "{name}"\nlandblock = "{landblock}"\n'
        f"origin = [{origin[0]}, {origin[1]}, {origin[2]}]\n"
        f'heading = {heading}\nstate = ["gravity", "report_collisions", "edge_slide"]\non_ground = true\n\n'
        f'[[event]]\nat = 0.5\nbody = "{name}"\naction = "motion"\nmotion = "WalkForward"\n\n'
    )


def _heights(f) -> str:
    return "heights = [" + ", ".join(str(f(x, y)) for x in range(9) for y in range(9)) + "]\n"


def _terrain_walk(
    heights: str, duration: float, walkers: list[tuple[str, tuple[float, float], float]]
) -> str:
    """A scenario of landblock 0xA9B4 with ``heights`` (through retail's table, no height_table)
    and built-in humans standing on it at the given (x, y), walking from 0.5 s."""
    land = f'[[landblock]]\nid = "0xA9B4"\n{heights}\n'
    probe = '[[body]]\nname = "probe"\nlandblock = "0xA9B4"\norigin = [1.0, 1.0, 500.0]\n'
    terrain = acphys.parse_scenario(land + probe).world.landscape.get_landblock(0xA9B4FFFF).terrain
    text = f"[scenario]\nduration = {duration}\ndriver_hz = 60.0\n\n{land}"
    for name, (x, y), heading in walkers:
        text += _walker(name, (x, y, round(terrain.get_height(Vector3(x, y, 0.0)), 4)), heading)
    return text


# Rolling hills: ridges and valleys along x (vertex bytes 2 apart: 4 m over 24 m) and a gentle
# swell along y (0 or 1 byte), so the triangles slope by up to ~10.6 degrees.
RIDGES = (30, 28, 26, 27, 29, 29, 27, 25, 26)
SWELL = (0, 1, 1, 0, 0, 1, 1, 0, 0)


def test_acceptance_the_human_walks_over_rolling_hills(tmp_path: Path) -> None:
    text = _terrain_walk(
        _heights(lambda x, y: RIDGES[x] + SWELL[y]),
        45.0,
        [("east", (4.0, 60.0), 90.0), ("north", (60.0, 4.0), 0.0), ("north-east", (20.0, 20.0), 45.0)],
    )
    sim, records = _run_text(text, tmp_path / "hills.jsonl")
    terrain = sim.world.landscape.get_landblock(0xA9B4FFFF).terrain
    slopes = [_slope(p) for cx in range(8) for cy in range(8) for p in terrain.cell_polygons(cx, cy)]
    assert 10.0 < max(slopes) < 11.0  # slopes up to ~10 degrees
    for name, heading in (("east", 90.0), ("north", 0.0), ("north-east", 45.0)):
        walk = records[name]
        direction = (math.sin(math.radians(heading)), math.cos(math.radians(heading)))
        made, time = _acceptance_walk(walk, direction)
        assert time > 44.0
        assert made >= 0.8 * WALK_SPEED * time, (name, made, time)
        assert all(_grounded(r) for r in walk), name
        # over the hills: up and down by metres (the swell along y alone is 2 m)
        zs = [r["origin"][2] for r in walk]
        assert max(zs) - min(zs) > (1.5 if name == "north" else 4.0), name


def test_acceptance_the_human_walks_along_up_and_down_a_4_8_degree_slope(tmp_path: Path) -> None:
    # A ramp rising east, one byte (2 m) a 24-m cell: 4.76 degrees, across the whole landblock.
    text = _terrain_walk(
        _heights(lambda x, y: 20 + x),
        55.0,
        [("along", (96.0, 4.0), 0.0), ("up", (4.0, 40.0), 90.0), ("down", (188.0, 150.0), 270.0)],
    )
    sim, records = _run_text(text, tmp_path / "ramp.jsonl")
    terrain = sim.world.landscape.get_landblock(0xA9B4FFFF).terrain
    assert {
        round(_slope(p), 2) for cx in range(8) for cy in range(8) for p in terrain.cell_polygons(cx, cy)
    } == {round(math.degrees(math.atan(2.0 / 24.0)), 2)}
    for name, direction in (("along", (0.0, 1.0)), ("up", (1.0, 0.0)), ("down", (-1.0, 0.0))):
        walk = records[name]
        made, time = _acceptance_walk(walk, direction)
        assert time > 54.0
        assert made >= 0.8 * WALK_SPEED * time, (name, made, time)
        assert all(_grounded(r) for r in walk), name
    # Across it the whole way: the climber rises and the other descends by 14 m or so.
    assert records["up"][-1]["origin"][2] - records["up"][0]["origin"][2] > 13.0
    assert records["down"][0]["origin"][2] - records["down"][-1]["origin"][2] > 13.0
    assert records["along"][-1]["origin"][2] == pytest.approx(records["along"][0]["origin"][2], abs=1e-4)


HOUSE = """
[scenario]
duration = 5.0
driver_hz = 60.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[[building]]
landblock = "0xA9B4"
origin = [108.0, 108.0, 50.0]
rooms = [
    { name = "hall", min = [-3.0, -6.0, 0.0], max = [3.0, 0.0, 3.0] },
    { name = "parlour", min = [-3.0, 0.0, 0.0], max = [3.0, 6.0, 3.0] },
]
doorways = [
    { between = ["outside", "hall"], min = [-0.6, -6.0, 0.0], max = [0.6, -6.0, 2.2] },
    { between = ["hall", "parlour"], min = [-0.6, 0.0, 0.0], max = [0.6, 0.0, 2.2] },
]

"""


def test_acceptance_the_human_walks_in_through_a_doorway_and_on_into_the_next_room(tmp_path: Path) -> None:
    # The hall is y 102-108 and the parlour y 108-114 (x 105-111); the front door in the hall's
    # south wall, the inner doorway between them. The walker starts outside, 4 m south of the front
    # door in the building's own land cell (0x25: a building is found only through it), walks north
    # through the hall and across the parlour's floor.
    text = HOUSE + _walker("visitor", (108.0, 98.0, 50.0), 0.0)
    _sim, records = _run_text(text, tmp_path / "house.jsonl")
    walk = records["visitor"]
    made, time = _acceptance_walk(walk, (0.0, 1.0))
    assert time > 4.4
    assert made >= 0.8 * WALK_SPEED * time
    assert all(_grounded(r) for r in walk)
    assert walk[-1]["origin"][1] > 112.0  # across the parlour's floor, short of its far wall
    order = [r["cell"] for i, r in enumerate(walk) if i == 0 or r["cell"] != walk[i - 1]["cell"]]
    assert order == ["0xA9B40025", "0xA9B40100", "0xA9B40101"]
    for record in walk:
        y = record["origin"][1]
        assert record["cell"] == ("0xA9B40025" if y < 102.0 else "0xA9B40100" if y < 108.0 else "0xA9B40101")
