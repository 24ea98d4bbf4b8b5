"""Ladder rung 9: two bodies walking into each other stop; an ethereal one passes."""

from __future__ import annotations

import acphys
from acphys.flags import PhysicsState, TransientState
from support import walk_tolerance

STEP = 3.12 / 30.0  # walk root motion per 30-Hz step (CMotionInterp::get_state_velocity, acclient.c:343538)
REACH = 0.48 + 0.48 - 0.00019999999  # radsum in CSphere::intersects_sphere (acclient.c:359156)
TICKS = 75  # 2.5 s of 30-Hz steps, one walk frame each


def _run() -> acphys.Simulation:
    sim = acphys.load_scenario("ladder-09-bodies")
    sim.run()
    return sim


def test_solid_walkers_stop_at_their_last_clear_steps():
    sim = _run()
    north, south = sim.body("north-walker"), sim.body("south-walker")
    # The bodies step in turn (north first), closing the 4-m gap by 0.104 a move. A move whose
    # sphere 0 comes within REACH of the other's steps up (CSphere::step_sphere_up,
    # acclient.c:359071: 0.96 > step_up_height 0.6) and slides off it (CSphere::slide_sphere,
    # acclient.c:358708): head-on nothing is left, COLLIDED, and CTransition::validate_transition
    # (acclient.c:312193) rolls it back. Move m leaves 4 - 0.104 m; m = 30 (south's 15th) would
    # leave 0.88 < REACH, so north keeps 15 moves and south 14, and neither moves again.
    moves = next(m for m in range(1, 60) if 4.0 - m * STEP <= REACH)
    assert moves == 30
    # (float32 positions: within the drift of their stores, support.walk_tolerance)
    assert abs(north.position.frame.origin.y - (96.0 + 15 * STEP)) < walk_tolerance(96.0, 15)
    assert abs(south.position.frame.origin.y - (100.0 - 14 * STEP)) < walk_tolerance(100.0, 14)
    gap = south.position.frame.origin.y - north.position.frame.origin.y
    assert abs(gap - (4.0 - 29 * STEP)) < walk_tolerance(100.0, 29)
    for body in (north, south):
        assert body.position.frame.origin.x == 80.0
        assert body.transient_state & TransientState.CONTACT


def test_ethereal_walker_passes_through():
    sim = _run()
    solid, ghost = sim.body("solid-walker"), sim.body("ghost")
    assert ghost.state & PhysicsState.ETHEREAL
    # Against an ethereal body the sweep only tests overlap and FindObjCollisions
    # (acclient.c:316158) turns the answer into OK: both walk every step, straight through.
    assert abs(solid.position.frame.origin.y - (96.0 + TICKS * STEP)) < walk_tolerance(100.0, TICKS)
    assert abs(ghost.position.frame.origin.y - (100.0 - TICKS * STEP)) < walk_tolerance(100.0, TICKS)
    assert solid.position.frame.origin.y - ghost.position.frame.origin.y > REACH
