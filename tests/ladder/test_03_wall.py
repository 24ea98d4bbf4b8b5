"""Ladder rung 3: walking into a wall stops at the last clear sub-step; at an angle, slides along it."""

from __future__ import annotations

import math

import acphys
from acphys.flags import TransientState
from acphys.precision import f32
from support import step_records, walk_tolerance

# The built-in walk: 3.12 m/s of root motion at 30 frames a second, one frame per 30-Hz step
# (CMotionInterp::get_state_velocity, acclient.c:343538).
STEP = 3.12 / 30.0
RADIUS = 0.48  # the human's sphere 0
FACE_Y = 99.75  # the wall's south face (box centre y 100, half thickness 0.25)


def _last_clear(start: float, per_step: float) -> float:
    """The last position on the step lattice whose sphere stays off the face."""
    steps = math.floor((FACE_Y - RADIUS - start) / per_step)
    return start + steps * per_step


def test_head_on_walker_stops_at_its_last_clear_step(tmp_path):
    sim = acphys.load_scenario("ladder-03-wall")
    trace = tmp_path / "wall.jsonl"
    sim.run(trace=trace)
    walker = sim.body("walker")
    origin = walker.position.frame.origin
    # One sub-step per step (0.104 < 0.48: CTransition::calc_num_steps, acclient.c:311763); the
    # step that reaches the face fails its step-up (BSPTREE::step_sphere_up, acclient.c:361071),
    # slides head-on to nothing (SPHEREPATH::step_up_slide, acclient.c:313455; CSphere::slide_sphere,
    # acclient.c:358898: COLLIDED) and is rolled back (CTransition::validate_transition,
    # acclient.c:312193). 31 steps: 99.224, 0.526 m from the face, not one radius (0.48).
    expected = _last_clear(96.0, STEP)
    assert math.isclose(expected, 96.0 + 31 * STEP)
    # The 31 steps are float32 stores near 99 m: each rounds (the 0.104-m step is 13631.49
    # float32 spacings there), so the body ends within their drift of the double sum.
    assert abs(origin.y - expected) < walk_tolerance(expected, 31)
    assert abs(FACE_Y - origin.y - 0.526) < walk_tolerance(expected, 31)
    assert origin.x == 84.0
    # Sphere 0 (z 0.475, r 0.48) sank 0.005 into the ground: the first step lifts it onto the
    # contact plane (CTransition::adjust_offset, acclient.c:311863).
    assert origin.z == f32(50.005)
    assert walker.transient_state & TransientState.CONTACT
    assert walker.transient_state & TransientState.ON_WALKABLE
    # The wall is static: FindObjCollisions (acclient.c:316158) records no object collision
    # for it, so no report is made.
    records = step_records(trace)
    events = [event for record in records if record["body"] == "walker" for event in record["events"]]
    assert not any(event.startswith("collision:wall") for event in events)


def test_angled_walker_slides_along_the_wall():
    sim = acphys.load_scenario("ladder-03-wall")
    angler = sim.body("angler")
    along = STEP * math.sin(math.radians(45.0))
    across = STEP * math.cos(math.radians(45.0))
    sim.run(until=2.0)
    first = angler.position.frame.origin.copy()
    sim.run(until=2.5)
    second = angler.position.frame.origin.copy()
    # It stops closing on the wall at its last clear lattice point (44 steps), as head-on ...
    expected_y = _last_clear(96.0, across)
    assert math.isclose(expected_y, 96.0 + 44 * across)
    assert abs(first.y - expected_y) < walk_tolerance(expected_y, 44)
    assert second.y == first.y
    # ... but the slide keeps the step's part along the wall (CSphere::slide_sphere,
    # acclient.c:358898, projects onto N_wall x N_ground; CTransition::adjust_offset,
    # acclient.c:311863, does the same with the sliding normal): 15 steps in 0.5 s, each
    # 0.104 sin 45 east.
    assert abs((second.x - first.x) - 15 * along) < 2 * walk_tolerance(second.x, 15)
    assert second.z == first.z
    # Every step so far has been a whole walk step east: 75 of them by t = 2.5.
    assert abs(second.x - (96.0 + 75 * along)) < walk_tolerance(second.x, 75)
