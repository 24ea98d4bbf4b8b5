"""Ladder rung 12: the unchanged-origin commit and the failed-sweep commit (RETAIL_NOTES §2).

CPhysicsObj::UpdateObjectInternal @ 0x005156B0 (acclient.c:322718): with spheres, an unchanged
candidate origin skips the transition (set_frame takes the rotation, cached_velocity = 0); a
transition that returns no position keeps the old origin, takes the new rotation and zeroes
cached_velocity.
"""

from __future__ import annotations

import acphys
from acphys.flags import TransientState as TS
from acphys.math.vector import Vector3
from support import walk_tolerance

STEP = 3.12 / 30.0  # one frame of the built-in walk (CMotionInterp::get_state_velocity, acclient.c:343538)
FACE_Y = 99.75  # the wall's south face
RADIUS = 0.48


def _run_with_sweep_log():
    sim = acphys.load_scenario("ladder-12-commits")
    log: dict[str, list[dict]] = {"turner": [], "pusher": []}
    for body in sim.bodies:
        sweep = body.transition
        calls: list[bool] = []

        def counted(old, new, admin_move=False, _sweep=sweep, _calls=calls):
            result = _sweep(old, new, admin_move)
            _calls.append(result is not None)
            return result

        body.transition = counted

        def record(obj, _quantum, _calls=calls, _name=body.name):
            log[_name].append(
                {
                    "t": obj.world.physics_time,
                    "origin": obj.position.frame.origin.copy(),
                    "heading": obj.position.frame.get_heading(),
                    "cached": obj.cached_velocity.copy(),
                    "transient": obj.transient_state,
                    "sweeps": list(_calls),
                }
            )

        body.observer = record
    sim.run()
    return sim, log


#: Headings read from float32 quaternions after up to 90 rotations (a few 1e-6° each).
HEADING_TOL = 5e-5


def test_turning_in_place_never_sweeps_and_keeps_its_contact():
    _sim, log = _run_with_sweep_log()
    start = log["turner"][0]["origin"]
    for k, step in enumerate(log["turner"], start=1):
        # Root motion is rotation only: the candidate origin equals the current one, so no
        # transition runs (acclient.c:322780-322790) ...
        assert step["sweeps"] == []
        assert step["origin"].exactly_equals(start)
        # ... set_frame takes the new rotation (3 degrees a frame boundary of the 90-deg/s turn;
        # each rotation stores a float32 quaternion, so the heading drifts by a few 1e-6°) ...
        assert (
            abs((step["heading"] - 3.0 * k) % 360.0) < HEADING_TOL
            or abs((step["heading"] - 3.0 * k) % 360.0 - 360.0) < HEADING_TOL
        )
        # ... cached_velocity is zeroed, and CONTACT / ON_WALKABLE are left as they were.
        assert step["cached"].exactly_equals(Vector3())
        assert step["transient"] & TS.CONTACT and step["transient"] & TS.ON_WALKABLE
    assert len(log["turner"]) == 90


def test_a_failed_sweep_keeps_the_origin_and_takes_the_rotation():
    sim, log = _run_with_sweep_log()
    steps = log["pusher"]
    # Walking north from 98: 12 clear steps; the 13th would put sphere 0 past the face
    # (98 + 13 x 0.104 + 0.48 > 99.75) and is rolled back (rung 3).
    clear = 12
    assert (98.0 + (clear + 1) * STEP + RADIUS) > FACE_Y > (98.0 + clear * STEP + RADIUS)
    stop = steps[clear - 1]["origin"]
    assert abs(stop.y - (98.0 + clear * STEP)) < walk_tolerance(99.0, clear)
    before_turn = [s for s in steps if s["t"] < 2.0 - 1e-6]
    # The rolled-back step left SLIDING along the wall normal (CTransition::validate_transition,
    # acclient.c:312193); from the next step on every sweep starts from it (get_object_info,
    # acclient.c:319073) and adjust_offset (acclient.c:311863) projects the walk into the wall's
    # plane: nothing is left and find_transitional_position fails on its first step (acclient.c:313271).
    failed = before_turn[clear + 1 :]
    assert len(failed) > 40
    for k, step in enumerate(failed, start=clear + 2):
        assert step["sweeps"][-1] is False, k
        assert len(step["sweeps"]) == k
        assert step["origin"].exactly_equals(stop)
        assert step["cached"].exactly_equals(Vector3())
        assert step["transient"] & TS.SLIDING
        assert step["heading"] == 0.0
    # At 2 s it turns left while still pushing: that step's sweep fails too, but the candidate's
    # rotation is committed (3 degrees of TurnLeft), the origin stays.
    turn = next(s for s in steps if s["t"] >= 2.0 - 1e-6)
    assert turn["sweeps"][-1] is False
    assert turn["origin"].exactly_equals(stop)
    assert abs(turn["heading"] - 357.0) < HEADING_TOL
    # Once turned, the walk has a component along the wall and the sweeps succeed again: west.
    assert sim.body("pusher").position.frame.origin.x < 83.0
