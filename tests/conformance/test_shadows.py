"""Shadows: a body's entry in every cell it overlaps, for static objects and for moving bodies.

CPhysicsObj::add_obj_to_cell @ 0x005159E0 (acclient.c:322896) → calc_cross_cells_static (322404);
SetPositionInternal (acclient.c:322503) re-shadows a moved body from the transition's cell array.
"""

from __future__ import annotations

from acphys.flags import PhysicsState as PS
from acphys.geometry.cylsphere import CylSphere
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.setup import Setup
from acphys.world.static_objects import add_static_object
from support import LANDBLOCK, place


def _cells_holding(world, body) -> set[int]:
    cells = set()
    for low in range(1, 65):
        cell = world.get_cell((LANDBLOCK << 16) | low)
        if any(shadow.physobj is body for shadow in cell.shadow_objects):
            cells.add(low)
    return cells


def _pillar() -> Setup:
    return Setup("pillar", cylspheres=[CylSphere(Vector3(), 1.0, 3.0)])


def test_a_pillar_on_a_cell_corner_shadows_into_the_four_cells_around_it(world):
    world.set_flat_ground(LANDBLOCK, 50.0)
    corner = Vector3(48.0, 48.0, 50.0)  # the corner of cells (1,1), (1,2), (2,1), (2,2)
    pillar = add_static_object(
        world, "pillar", _pillar(), Position(outdoor_cell_id(LANDBLOCK, corner), Frame(corner))
    )
    assert pillar.state & PS.STATIC
    # Outdoor cell low word = 1 + 8·cx + cy: (1,1) 0x0A, (1,2) 0x0B, (2,1) 0x12, (2,2) 0x13.
    assert _cells_holding(world, pillar) == {0x0A, 0x0B, 0x12, 0x13}
    assert len(pillar.shadow_objects) == 4
    assert pillar in world.get_cell(pillar.position.objcell_id).objects


def test_a_pillar_in_the_middle_of_a_cell_shadows_only_there(world):
    world.set_flat_ground(LANDBLOCK, 50.0)
    middle = Vector3(36.0, 36.0, 50.0)  # cell (1,1), 12 m from every edge
    pillar = add_static_object(
        world, "pillar", _pillar(), Position(outdoor_cell_id(LANDBLOCK, middle), Frame(middle))
    )
    assert _cells_holding(world, pillar) == {0x0A}


def test_a_moving_body_carries_its_shadows_across_a_cell_edge(world):
    world.set_flat_ground(LANDBLOCK, 50.0)
    # Human spheres r 0.48: at x = 47.7 the spheres reach past x = 48 into the next column.
    body = place(world, state=PS(0), origin=(47.4, 36.0, 50.0), on_ground=True)
    body.friction = 0.0
    body.set_velocity(Vector3(3.0, 0.0, 0.0))
    world.cur_time = 0.1
    body.update_object()
    straddling = _cells_holding(world, body)
    assert straddling == {0x0A, 0x12}
    world.cur_time = 1.0
    body.update_object()
    world.cur_time = 1.1
    body.update_object()
    # Well inside (2,1) now: the old cell lost the shadow, the new one has it, once.
    assert body.position.frame.origin.x > 49.0 + 0.48
    assert _cells_holding(world, body) == {0x12}
    assert sum(1 for s in world.get_cell((LANDBLOCK << 16) | 0x12).shadow_objects if s.physobj is body) == 1


def test_a_commit_into_no_cell_parks_the_body_in_the_lost_cell(world):
    # SetPositionInternal with no curr_cell (acclient.c:322503, the else branch): leave visibility
    # (shadows, own cell), store the position, GotoLostCell, clear ACTIVE.
    from acphys.flags import TransientState as TS
    from acphys.transition.transition import Transition

    world.set_flat_ground(LANDBLOCK, 50.0)
    body = place(world, state=PS(0), origin=(47.7, 36.0, 50.0), on_ground=True)
    body.calc_cross_cells()
    old_cell = body.cell
    assert _cells_holding(world, body) == {0x0A, 0x12}
    transit = Transition(world, body)
    transit.sphere_path.curr_pos = Position(0xA9B40012, Frame(Vector3(50.0, 36.0, 50.0)))
    transit.sphere_path.curr_cell = None
    body.set_position_internal(transit)
    assert body.cell is None and body not in old_cell.objects
    assert _cells_holding(world, body) == set() and body.shadow_objects == []
    assert world.lost_cell == [body]
    assert body.position.objcell_id == 0xA9B40012 and body.position.frame.origin.x == 50.0
    assert not body.transient_state & TS.ACTIVE
    # Leaving visibility again takes it out of the lost cell.
    body.prepare_to_leave_visibility()
    assert world.lost_cell == []


def test_leaving_the_world_clears_cells_shadows_and_ground_state(world):
    # CPhysicsObj::leave_world (acclient.c:322653): lost cell, shadows, cell, cell id 0, contact and
    # walkable off (LeaveGround to the movement manager), then mask 0xFFFFFE0B keeps only bits 0x1|0x2|0x8.
    from acphys.flags import TransientState as TS
    from acphys.scenario.motion_tables import builtin_motion_table

    world.set_flat_ground(LANDBLOCK, 50.0)
    body = place(
        world,
        state=PS.GRAVITY,
        origin=(47.7, 36.0, 50.0),
        on_ground=True,
        motion_table=builtin_motion_table("humanoid"),
    )
    body.calc_cross_cells()
    body.transient_state |= TS.SLIDING | TS.STATIONARY_FALL
    cell = body.cell
    world.remove_object(body)
    assert body.cell is None and body not in cell.objects and _cells_holding(world, body) == set()
    assert body.position.objcell_id == 0
    assert body.transient_state == TS(0)
    # Off the ground with gravity: calc_acceleration now falls (acclient.c:317814).
    assert body.acceleration.z < 0.0
    assert world.get_object(body.id) is None
