"""Ladder rung 5: off a ledge a body falls without EDGE_SLIDE and stops at the edge with it."""

from __future__ import annotations

import math

import acphys
from acphys.flags import PhysicsState, TransientState
from acphys.math.vector import Vector3
from acphys.precision import f32
from support import step_records, walk_tolerance

STEP = 3.12 / 30.0  # walk root motion per 30-Hz step (CMotionInterp::get_state_velocity, acclient.c:343538)
EDGE_Y = 98.0
TOP = 51.0
LIFT = 0.005  # sphere 0 (z 0.475, r 0.48) touching its plane puts the origin 0.005 above it


def _records(tmp_path, body: str) -> tuple[acphys.Simulation, list[dict]]:
    sim = acphys.load_scenario("ladder-05-ledge")
    trace = tmp_path / "ledge.jsonl"
    sim.run(trace=trace)
    records = step_records(trace)
    return sim, [record for record in records if record["body"] == body]


def test_without_edge_slide_the_walker_walks_off_and_falls(tmp_path):
    sim, records = _records(tmp_path, "faller")
    assert not sim.body("faller").state & PhysicsState.EDGE_SLIDE
    airborne = next(index for index, record in enumerate(records) if "contact" not in record["transient"])
    before, left = records[airborne - 1], records[airborne]
    # The step-down (0.4, CTransition::transitional_insert, acclient.c:312833) lowers sphere 0 to
    # 0.08 above the top; BSPNODE::find_walkable needs it to reach the polygon
    # (CPolygon::walkable_hits_sphere, acclient.c:360518, polygon_hits_sphere_slow_but_sure,
    # acclient.c:360006): centre at most sqrt(0.48^2 - 0.08^2) = 0.473 past the edge.
    # 23 steps (0.392 past) stand; the 24th (0.496 past) finds nothing and CTransition::edge_slide
    # (acclient.c:312684) accepts it without contact.
    assert abs(before["origin"][1] - (96.0 + 23 * STEP)) < walk_tolerance(96.0, 23)
    assert before["origin"][2] == f32(TOP + LIFT)
    assert abs(left["origin"][1] - (96.0 + 24 * STEP)) < walk_tolerance(96.0, 24)
    assert left["origin"][2] == f32(TOP + LIFT)
    assert "leave_ground" in left["events"]
    # Leaving the ground turns the walk into velocity (CMotionInterp::LeaveGround, acclient.c:344456).
    assert left["velocity"][0] == 0.0
    assert abs(left["velocity"][1] - 3.12) < 1e-6  # the float32 3.12 of the walk
    # It lands on the ground below, clear of the platform.
    body = sim.body("faller")
    origin = body.position.frame.origin
    assert origin.z == f32(50.0 + LIFT)
    assert origin.y > EDGE_Y + 0.48
    assert body.transient_state & TransientState.CONTACT
    assert body.transient_state & TransientState.ON_WALKABLE


def test_with_edge_slide_the_walker_stops_at_the_edge(tmp_path):
    sim, records = _records(tmp_path, "edger")
    body = sim.body("edger")
    origin = body.position.frame.origin
    # CTransition::step_down (acclient.c:312628) also asks CTransition::check_walkable
    # (acclient.c:312474) of an EDGE_SLIDE body: SPHEREPATH::check_walkables (acclient.c:313467)
    # halves the radius to 0.24, and the probe's BSPLEAF::hits_walkable (acclient.c:364274) uses
    # CPolygon::check_small_walkable (acclient.c:360311), also r/2. 21 steps (0.184 past the edge)
    # pass; the 22nd (0.288) is refused, SPHEREPATH::precipice_slide (acclient.c:313979) slides
    # head-on to COLLIDED and CTransition::validate_transition (acclient.c:312193) rolls it back.
    assert abs(origin.y - (96.0 + 21 * STEP)) < walk_tolerance(96.0, 21)
    assert origin.z == f32(TOP + LIFT)
    assert body.transient_state & TransientState.CONTACT
    assert body.transient_state & TransientState.ON_WALKABLE
    assert all("contact" in record["transient"] for record in records)
    assert body.velocity.exactly_equals(Vector3())


CREASE_X = 144.0  # landblock 0xABB4: flat (50 m) up to vertex column 6, then 50 m down over 24 m


def _stuck_index(records: list[dict]) -> int:
    return next(i for i in range(1, len(records)) if records[i]["origin"] == records[i - 1]["origin"])


def test_cliff_slide_stops_a_walker_at_the_crease(tmp_path):
    sim, records = _records(tmp_path, "cliffer")
    body = sim.body("cliffer")
    # CLandCell::find_env_collisions (acclient.c:355028) tests only the triangle under sphere 0's
    # low point: 14 steps east (143.956) stand on the flat. The 15th (144.06) meets no plane; the
    # 0.4 step-down lands on the cliff face (normal z 0.433), which CTransition::step_down refuses
    # (acclient.c:312666), and CTransition::edge_slide (acclient.c:312710-312714) hands it to
    # CTransition::cliff_slide, which takes the whole eastward step back (acclient.c:312065).
    stuck = _stuck_index(records)
    assert stuck == 14
    assert abs(records[stuck]["origin"][0] - (142.5 + 14 * STEP)) < walk_tolerance(142.5, 14)
    assert all(record["origin"][0] < CREASE_X for record in records)
    origin = body.position.frame.origin
    assert abs(origin.x - (142.5 + 14 * STEP)) < walk_tolerance(142.5, 14)
    assert origin.y == 96.0
    assert origin.z == f32(50.0 + LIFT)
    # The slid step ends where it began: CTransition::validate_transition counts a stationary frame
    # (acclient.c:312312) and CPhysicsObj::handle_all_collisions sets STATIONARY_FALL; cliff_slide's
    # collision normal (-x, acclient.c:312065-312071) becomes the sliding normal (acclient.c:312271).
    assert "stationary_fall" in records[stuck]["transient"]
    assert "sliding" in records[stuck]["transient"]
    assert body.transient_state & TransientState.CONTACT
    assert body.transient_state & TransientState.ON_WALKABLE


def test_cliff_slide_turns_an_oblique_walker_along_the_crease(tmp_path):
    sim, records = _records(tmp_path, "slider")
    # Heading 60: each step is (STEP sin 60, STEP cos 60). 16 steps reach x 143.941; the 17th
    # would cross the crease, and cliff_slide removes only its +x part (acclient.c:312065): the
    # walker keeps going north along the crease, STEP cos 60 a step, x pinned. The next step runs
    # into the sliding normal and CTransition::adjust_offset (acclient.c:311863) turns it along
    # the crease itself; the one after has no sliding normal and cliff-slides again.
    dx, dy = STEP * math.sin(math.radians(60.0)), STEP * math.cos(math.radians(60.0))
    edge_x = 142.5 + 16 * dx
    assert edge_x < CREASE_X < edge_x + dx
    for index, record in enumerate(records[16:40], start=16):
        assert abs(record["origin"][0] - edge_x) < walk_tolerance(edge_x, 16)
        assert abs(record["origin"][1] - (90.0 + (index + 1) * dy)) < walk_tolerance(90.0, index + 1)
        assert record["origin"][2] == f32(50.0 + LIFT)
        assert "contact" in record["transient"]
    assert abs(records[15]["origin"][0] - edge_x) < walk_tolerance(edge_x, 16)
    body = sim.body("slider")
    assert body.transient_state & TransientState.ON_WALKABLE
    assert body.position.frame.origin.y > 90.0 + 40 * dy
