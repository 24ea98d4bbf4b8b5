"""Ladder rung 4: steps up to 1.5 x the step-up height are climbed; a higher one blocks."""

from __future__ import annotations

import acphys
from acphys.flags import TransientState
from acphys.precision import f32
from support import walk_tolerance

STEP = 3.12 / 30.0  # walk root motion per 30-Hz step (CMotionInterp::get_state_velocity, acclient.c:343538)
GROUND = 50.0
LIFT = 0.005  # sphere 0 (z 0.475, r 0.48) rests 0.48 above its plane: origin 0.005 over it
TICKS = 45  # 1.5 s of 30-Hz steps, one walk frame each
TOUCH = 96.0 + 15 * STEP  # 97.56: the first step whose sphere (r 0.48) reaches the faces at y = 98


def _run():
    sim = acphys.load_scenario("ladder-04-steps")
    sim.run()
    return sim


def _on_ground(body) -> bool:
    return bool(
        body.transient_state & TransientState.CONTACT and body.transient_state & TransientState.ON_WALKABLE
    )


def test_low_step_is_climbed_and_walked_across():
    body = _run().body("low-climber")
    origin = body.position.frame.origin
    # The step-up (CTransition::step_up, acclient.c:312793) moves sphere 0 onto the top:
    # CPolygon::adjust_sphere_to_plane (acclient.c:359533) leaves it touching the plane, so
    # the origin is 0.3 + 0.005 above the ground; it then walks every step.
    assert origin.z == f32(GROUND + 0.3 + LIFT)
    assert abs(origin.y - (96.0 + TICKS * STEP)) < walk_tolerance(100.0, TICKS)
    assert _on_ground(body)


def test_step_between_the_height_and_one_and_a_half_times_it_is_climbed():
    body = _run().body("mid-climber")
    origin = body.position.frame.origin
    # rise 0.5 over a 0.4 step-up: walk_interp 1 - 0.5/0.4 = -0.25 >= -0.5, so
    # CPolygon::adjust_sphere_to_plane (acclient.c:359533) accepts it.
    assert origin.z == f32(GROUND + 0.5 + LIFT)
    assert abs(origin.y - (96.0 + TICKS * STEP)) < walk_tolerance(100.0, TICKS)
    assert _on_ground(body)


def test_edge_slider_is_held_on_the_lip_of_the_mid_step():
    body = _run().body("mid-edger")
    origin = body.position.frame.origin
    # Raised onto the top at the touching step (no check_walkable during a step-up:
    # CTransition::step_down, acclient.c:312628) ...
    assert origin.z == f32(GROUND + 0.5 + LIFT)
    # ... but the next step leaves its centre 0.336 m short of the top, over the half radius
    # (0.24) that SPHEREPATH::check_walkables (acclient.c:313467) and BSPLEAF::hits_walkable
    # (acclient.c:364274, CPolygon::check_small_walkable) allow; CTransition::edge_slide
    # (acclient.c:312684) precipice-slides head-on to COLLIDED and the step is rolled back.
    assert abs(origin.y - TOUCH) < walk_tolerance(TOUCH, 15)
    assert _on_ground(body)


def test_high_step_blocks():
    body = _run().body("blocked")
    origin = body.position.frame.origin
    # rise 0.7: walk_interp 1 - 0.7/0.4 = -0.75 < -0.5 (acclient.c:359533), and the top is out
    # of the sphere's reach anyway; the step-up fails, SPHEREPATH::step_up_slide
    # (acclient.c:313455) leaves nothing head-on and CTransition::validate_transition
    # (acclient.c:312193) rolls the step back: the body keeps the step before TOUCH.
    assert abs(origin.y - (TOUCH - STEP)) < walk_tolerance(TOUCH, 14)
    assert origin.z == f32(GROUND + LIFT)
    assert body.transient_state & TransientState.SLIDING
    assert _on_ground(body)
