"""A body sweeping off the west edge of the map (landblock 0x0000): what retail commits.

The human (no gravity, so no stationary-fall counting) flies west at 3 m/s; each 30-Hz step
moves it 0.1 m, less than a sphere radius, so every sweep is one step. A candidate whose
sphere 0 centre has left the map finds no cell holding it (CObjCell::find_cell_list,
acclient.c:346960; CPolygon::point_in_poly2D has no tolerance, acclient.c:359419), and
CTransition::check_other_cells (acclient.c:312445-312468) asks LandDefs::adjust_to_outside:

- a candidate x within EPSILON of 0 is snapped to 0 (acclient.c:467450), lies in land cell
  (0, 4) and is accepted with that cell id but *no cell* (acclient.c:312459-312466). The sweep
  succeeds, UpdateObjectInternal sets ``cached_velocity`` from the committed offset
  (acclient.c:322816-322828) and SetPositionInternal, given no cell, parks the body in the lost
  cell and clears ACTIVE (acclient.c:322644-322647). update_object then skips a cell-less body
  (acclient.c:323099): it stays at x = 0 with that last ``cached_velocity``.
- a candidate further west has lcoord x -1 (acclient.c:467428): cell id 0, COLLIDED. The step
  is rolled back (CTransition::validate_transition, acclient.c:312223-312253) and the sweep
  still returns OK, so the body keeps its origin with ``cached_velocity`` 0 (offset 0 / dt)
  and its velocity (no contact plane, and the +z collision normal is perpendicular to it).
"""

from __future__ import annotations

from acphys.constants import EPSILON
from acphys.flags import PhysicsState, TransientState
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.part_array import PartArray
from acphys.physics_obj import PhysicsObj
from acphys.setup import human_setup
from acphys.world.world import World

EDGE_BLOCK = 0x0000
DT = 1.0 / 30.0


def flyer(x: float) -> tuple[World, PhysicsObj]:
    world = World()
    world.set_flat_ground(EDGE_BLOCK, 0.0)
    body = PhysicsObj(world, "flyer", PartArray(human_setup()))
    body.state = PhysicsState(0)
    point = Vector3(x, 96.0, 50.0)
    assert body.enter_world(Position(outdoor_cell_id(EDGE_BLOCK, point), Frame(point)))
    body.velocity = Vector3(-3.0, 0.0, 0.0)
    return world, body


def tick(world: World, body: PhysicsObj) -> None:
    world.cur_time += DT
    body.update_object()


def test_a_candidate_snapped_onto_the_edge_is_committed_cell_less_and_lost():
    world, body = flyer(0.3)
    tick(world, body)
    tick(world, body)
    before = body.position.frame.origin.x
    assert 0.09 < before < 0.1 + EPSILON
    start_time = body.update_time
    tick(world, body)
    # before - 0.1 is within EPSILON of 0: adjust_to_outside snaps it to 0 (acclient.c:467450).
    assert body.position.frame.origin.x == 0.0
    assert body.position.objcell_id == 0x00000005  # land cell (0, 4) of landblock 0x0000
    # No cell: the lost cell, not ACTIVE (SetPositionInternal, acclient.c:322644-322647).
    assert body.cell is None
    assert body in world.lost_cell
    assert not body.transient_state & TransientState.ACTIVE
    # cached_velocity is the committed offset over the quantum (acclient.c:322816-322828).
    quantum = body.update_time - start_time
    assert abs(body.cached_velocity.x - (0.0 - before) / quantum) < 1e-4
    assert body.cached_velocity.x < -2.99
    cached = body.cached_velocity.copy()
    # update_object skips a cell-less body (acclient.c:323099): nothing changes any more.
    for _ in range(5):
        tick(world, body)
    assert body.position.frame.origin.x == 0.0
    assert body.cached_velocity.exactly_equals(cached)
    assert body.velocity.exactly_equals(Vector3(-3.0, 0.0, 0.0))


def test_a_candidate_off_the_map_collides_and_keeps_the_old_origin():
    world, body = flyer(0.35)
    tick(world, body)
    tick(world, body)
    before = body.position.frame.origin.copy()
    assert abs(before.x - 0.15) < 1e-6
    tick(world, body)
    stop = body.position.frame.origin.x
    assert abs(stop - 0.05) < 1e-6
    # x -0.05: lcoord -1, no cell id (acclient.c:467428, 467465): COLLIDED, rolled back.
    for _ in range(5):
        tick(world, body)
        assert body.position.frame.origin.x == stop
        assert body.cell is not None
        assert body.cached_velocity.exactly_equals(Vector3())
        assert body.transient_state & TransientState.ACTIVE
    assert body.cell is not None
    assert body not in world.lost_cell
    assert body.velocity.exactly_equals(Vector3(-3.0, 0.0, 0.0))
