"""Cells: ``CObjCell`` lists and ``find_cell_list``, ``CLandCell`` terrain collisions, ``CLandBlock``.

Expected values are derived by hand from the decompiled code (acclient.c lines cited). The
landblocks are 0xA9B4 (lcoord x 1352..1359, y 1440..1447) and its east neighbour 0xAAB4.
Cell ``(cx, cy)`` of a block has id low word ``8*cx + cy + 1`` and covers
``[24cx, 24cx+24) x [24cy, 24cy+24)`` block-local.
"""

from __future__ import annotations

import random

import pytest

from acphys.flags import ObjectInfoState, PhysicsState, TransitionState
from acphys.geometry.cylsphere import CylSphere
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.physics_obj import PhysicsObj
from acphys.transition.transition import InsertType, Transition
from acphys.world.land_cell import LandCell
from acphys.world.landblock import LandBlock, Landscape
from acphys.world.obj_cell import CellArray, ObjCell, ShadowObj
from acphys.world.terrain import LandBlockStruct, WaterType
from acphys.world.world import World

WEST = 0xA9B4FFFF
EAST = 0xAAB4FFFF
TABLE = [float(i) for i in range(256)]
GRASS_WORD = 1 << 2
WATER_WORD = 16 << 2


def _block(block_id: int, height: list[int] | None = None, terrain: list[int] | None = None) -> LandBlock:
    return LandBlock(LandBlockStruct(block_id, height or [10] * 81, terrain or [GRASS_WORD] * 81, TABLE))


def _landscape(*blocks: LandBlock) -> Landscape:
    landscape = Landscape()
    for block in blocks:
        landscape.add_landblock(block)
    return landscape


def _cell_list(
    landscape: Landscape, cell_id: int, center: Vector3, radius: float
) -> tuple[list[int], ObjCell | None, CellArray]:
    cell_array = CellArray(landscape)
    p = Position(cell_id, Frame(center))
    curr = ObjCell.find_cell_list(p, [Sphere(center, radius)], cell_array, None, want_curr_cell=True)
    return cell_array.cell_ids(), curr, cell_array


def _id(block: int, cx: int, cy: int) -> int:
    return (block & 0xFFFF0000) | (8 * cx + cy + 1)


# --- find_cell_list: spheres ----------------------------------------------------------------


def test_sphere_inside_one_cell_lists_only_that_cell() -> None:
    landscape = _landscape(_block(WEST))
    # pt1 = (12, 12) lies within [r, 24 - r] = [1, 23] on both axes: no neighbour (acclient.c:355167-355188).
    ids, curr, cell_array = _cell_list(landscape, _id(WEST, 1, 1), Vector3(36.0, 36.0, 10.0), 1.0)
    assert ids == [0xA9B4000A]
    assert curr is landscape.get_cell(0xA9B4000A)
    # add_all_outside_cells marks the array (acclient.c:355371); ACE never sets AddedOutside.
    assert cell_array.added_outside is True


def test_sphere_near_north_east_corner_adds_east_then_corner_then_north() -> None:
    landscape = _landscape(_block(WEST))
    # pt1 = (23.5, 23.5) > 24 - 1: east (acclient.c:355170), north-east (355172), north (355186).
    ids, curr, _ = _cell_list(landscape, _id(WEST, 1, 1), Vector3(47.5, 47.5, 10.0), 1.0)
    assert ids == [0xA9B4000A, 0xA9B40012, 0xA9B40013, 0xA9B4000B]
    assert curr is landscape.get_cell(0xA9B4000A)


def test_sphere_near_south_west_corner_adds_west_then_corner_then_south() -> None:
    landscape = _landscape(_block(WEST))
    # pt1 = (0.5, 0.5) < r = 1: west (acclient.c:355179), south-west (355183), south (355188).
    ids, _, _ = _cell_list(landscape, _id(WEST, 1, 1), Vector3(24.5, 24.5, 10.0), 1.0)
    assert ids == [0xA9B4000A, 0xA9B40002, 0xA9B40001, 0xA9B40009]


def test_sphere_touching_no_side_exactly_at_the_limit() -> None:
    landscape = _landscape(_block(WEST))
    # pt1.x = 23 is not > 24 - 1 (strict compare, acclient.c:355167).
    ids, _, _ = _cell_list(landscape, _id(WEST, 1, 1), Vector3(47.0, 36.0, 10.0), 1.0)
    assert ids == [0xA9B4000A]


def test_seam_lists_the_cell_of_the_east_landblock() -> None:
    west, east = _block(WEST), _block(EAST)
    landscape = _landscape(west, east)
    # Cell (7,1) of 0xA9B4, pt1.x = 23.5: its east neighbour is lcoord x 1360, cell (0,1) of 0xAAB4.
    ids, curr, cell_array = _cell_list(landscape, _id(WEST, 7, 1), Vector3(191.5, 36.0, 10.0), 1.0)
    assert ids == [0xA9B4003A, 0xAAB40002]
    assert cell_array.cells[1].cell is east.lcell[1]
    # The east cell sees the centre at 191.5 - 192 = -0.5: outside it (acclient.c:347047).
    assert curr is west.lcell[8 * 7 + 1]


def test_centre_past_the_seam_is_rehomed_into_the_east_landblock() -> None:
    west, east = _block(WEST), _block(EAST)
    landscape = _landscape(west, east)
    # adjust_to_outside moves (192.5, 36) of 0xA9B4 to (0.5, 36) of 0xAAB4; pt1.x = 0.5 < 1 adds the west.
    ids, curr, _ = _cell_list(landscape, _id(WEST, 7, 1), Vector3(192.5, 36.0, 10.0), 1.0)
    assert ids == [0xAAB40002, 0xA9B4003A]
    assert curr is east.lcell[1]


def test_seam_to_a_missing_landblock_keeps_the_id_without_a_cell() -> None:
    landscape = _landscape(_block(WEST))
    # add_outside_cell adds the id with LScape's null cell (acclient.c:354981-354984); ACE skips it.
    ids, _, cell_array = _cell_list(landscape, _id(WEST, 7, 1), Vector3(191.5, 36.0, 10.0), 1.0)
    assert ids == [0xA9B4003A, 0xAAB40002]
    assert cell_array.cells[1].cell is None


def test_world_edge_drops_cells_outside_the_world() -> None:
    landscape = _landscape(_block(0x0000FFFF))
    # x - 1 = -1 fails add_outside_cell's bounds (acclient.c:354979).
    ids, _, _ = _cell_list(landscape, 0x00000002, Vector3(0.5, 36.0, 10.0), 1.0)
    assert ids == [0x00000002]


def test_second_sphere_adds_its_cells_after_the_first() -> None:
    landscape = _landscape(_block(WEST))
    cell_array = CellArray(landscape)
    p = Position(_id(WEST, 1, 1), Frame(Vector3(36.0, 36.0, 10.0)))
    spheres = [Sphere(Vector3(36.0, 36.0, 10.0), 1.0), Sphere(Vector3(36.0, 60.0, 10.0), 1.0)]
    ObjCell.find_cell_list(p, spheres, cell_array)
    # Sphere by sphere (acclient.c:355397); (36, 60) is cell (1, 2), pt1 = (12, 12).
    assert cell_array.cell_ids() == [0xA9B4000A, 0xA9B4000B]


def test_find_cell_list_for_path_uses_check_pos_and_global_spheres() -> None:
    landscape = _landscape(_block(WEST))
    world = World()
    transition = Transition(world, PhysicsObj(world))
    path = transition.sphere_path
    path.local_sphere = [Sphere(Vector3(0.0, 0.0, 0.5), 0.5)]
    path.set_check_pos(Position(_id(WEST, 1, 1), Frame(Vector3(47.8, 36.0, 10.0))), None)
    cell_array = CellArray(landscape)
    check_cell = ObjCell.find_cell_list_for_path(cell_array, path)
    # pt1.x = 23.8 > 24 - 0.5 (acclient.c:355170).
    assert cell_array.cell_ids() == [0xA9B4000A, 0xA9B40012]
    assert check_cell is landscape.get_cell(0xA9B4000A)


def test_find_cell_list_for_sphere_places_the_local_sphere() -> None:
    landscape = _landscape(_block(WEST))
    cell_array = CellArray(landscape)
    frame = Frame(Vector3(36.0, 36.0, 10.0))
    frame.set_heading(90.0)
    # Local +y faces global +x at heading 90: the centre lands at (47.5, 36) (acclient.c:347329).
    ObjCell.find_cell_list_for_sphere(
        Position(_id(WEST, 1, 1), frame), Sphere(Vector3(0, 11.5, 0), 1.0), cell_array
    )
    assert cell_array.cell_ids() == [0xA9B4000A, 0xA9B40012]


# --- find_cell_list: cylspheres -------------------------------------------------------------


def _cyl_ids(cyls: list[CylSphere], heading: float = 0.0) -> list[int]:
    landscape = _landscape(_block(WEST))
    frame = Frame(Vector3(36.0, 36.0, 10.0))
    frame.set_heading(heading)
    cell_array = CellArray(landscape)
    ObjCell.find_cell_list_for_cylspheres(Position(_id(WEST, 1, 1), frame), cyls, cell_array)
    return cell_array.cell_ids()


def test_cylsphere_uses_its_low_point_placed_by_the_frame() -> None:
    cyl = CylSphere(Vector3(0.0, 11.5, 0.0), 1.0, 2.0)
    # Sphere centre = localtoglobal(low_pt), radius = cylsphere radius (acclient.c:347366-347371).
    assert _cyl_ids([cyl]) == [0xA9B4000A, 0xA9B4000B]
    assert _cyl_ids([cyl], heading=90.0) == [0xA9B4000A, 0xA9B40012]


def test_cylsphere_list_is_clamped_to_ten() -> None:
    near = [CylSphere(Vector3(0.0, 0.0, 0.0), 0.5, 1.0) for _ in range(9)]
    far = CylSphere(Vector3(48.0, 0.0, 0.0), 0.5, 1.0)  # (84, 36): cell (3, 1), low word 0x1A
    assert _cyl_ids([*near, far]) == [0xA9B4000A, 0xA9B4001A]
    # An eleventh cylsphere is never read (num_cylsphere clamped to 10, acclient.c:347351-347357).
    assert _cyl_ids([*near, near[0], far]) == [0xA9B4000A]


# --- point_in_cell ----------------------------------------------------------------------------


def _hilly_block(block_id: int = WEST) -> LandBlock:
    rng = random.Random(5)
    return _block(block_id, height=[rng.randrange(256) for _ in range(81)])


def test_a_point_is_in_exactly_one_cell() -> None:
    block = _hilly_block()
    rng = random.Random(11)
    for _ in range(3000):
        point = Vector3(rng.uniform(0.0, 192.0), rng.uniform(0.0, 192.0), rng.uniform(-50.0, 300.0))
        if point.x % 24.0 == 0.0 or point.y % 24.0 == 0.0:
            continue
        holders = [cell for cell in block.lcell if cell.point_in_cell(point)]
        assert len(holders) == 1, point
        cx, cy = int(point.x // 24.0), int(point.y // 24.0)
        assert holders[0] is block.lcell[8 * cx + cy]


def test_a_point_on_a_cell_edge_is_in_both_cells() -> None:
    block = _hilly_block()
    # point_in_poly2D rejects only a strictly positive edge value (acclient.c:354869): edges are inside.
    holders = [cell.id for cell in block.lcell if cell.point_in_cell(Vector3(24.0, 30.0, 0.0))]
    assert holders == [0xA9B40002, 0xA9B4000A]


def test_curr_cell_is_the_cell_under_the_centre_for_random_spheres() -> None:
    west, east = _hilly_block(WEST), _hilly_block(EAST)
    landscape = _landscape(west, east)
    rng = random.Random(3)
    for _ in range(300):
        center = Vector3(rng.uniform(0.5, 383.5), rng.uniform(0.5, 191.5), 20.0)
        ids, curr, _ = _cell_list(landscape, _id(WEST, 0, 0), center, rng.uniform(0.1, 3.0))
        block, x = (west, center.x) if center.x < 192.0 else (east, center.x - 192.0)
        expected = block.lcell[8 * int(x // 24.0) + int(center.y // 24.0)]
        assert curr is expected
        assert ids[0] == expected.id


# --- shadow objects and find_obj_collisions ---------------------------------------------------


class _Body:
    """Stand-in for the body side of a shadow (``CPhysicsObj::FindObjCollisions`` comes later)."""

    def __init__(self, name: str, result: TransitionState = TransitionState.OK) -> None:
        self.name = name
        self.parent: object | None = None
        self.result = result
        self.calls: list[Transition] = []

    def find_obj_collisions(self, transition: Transition) -> TransitionState:
        self.calls.append(transition)
        return self.result


def _transition() -> Transition:
    world = World()
    return Transition(world, PhysicsObj(world))


def test_shadow_object_is_found_in_every_cell_it_overlaps_and_only_there() -> None:
    west, east = _block(WEST), _block(EAST)
    landscape = _landscape(west, east)
    body = _Body("pillar")
    # The body's shadow goes into every cell its sphere overlaps: a corner at the seam.
    cells, _, cell_array = _cell_list(landscape, _id(WEST, 7, 1), Vector3(191.5, 47.5, 10.0), 1.0)
    assert cells == [0xA9B4003A, 0xAAB40002, 0xAAB40003, 0xA9B4003B]
    for info in cell_array.cells:
        info.cell.add_shadow_object(ShadowObj(body, info.cell_id), len(cells))
    transition = _transition()
    for block in (west, east):
        for cell in block.lcell:
            before = len(body.calls)
            assert cell.find_obj_collisions(transition) == TransitionState.OK
            assert len(body.calls) - before == (1 if cell.id in cells else 0), hex(cell.id)


def test_find_obj_collisions_skips_mover_and_parented_and_stops_at_first_hit() -> None:
    cell = _block(WEST).lcell[0]
    transition = _transition()
    mover = transition.object_info.object
    child, blocker, after = _Body("child"), _Body("wall", TransitionState.COLLIDED), _Body("after")
    child.parent = object()
    for body in (mover, child, blocker, after):
        cell.add_shadow_object(ShadowObj(body, cell.id))
    # Parented bodies and the mover are skipped; a non-OK result ends the walk (acclient.c:347161-347162).
    assert cell.find_obj_collisions(transition) == TransitionState.COLLIDED
    assert child.calls == [] and len(blocker.calls) == 1 and after.calls == []


def test_initial_placement_collides_with_no_object() -> None:
    cell = _block(WEST).lcell[0]
    blocker = _Body("wall", TransitionState.COLLIDED)
    cell.add_shadow_object(ShadowObj(blocker, cell.id))
    transition = _transition()
    transition.sphere_path.insert_type = InsertType.INITIAL_PLACEMENT
    # insert_type 2 skips the walk (acclient.c:347151).
    assert cell.find_obj_collisions(transition) == TransitionState.OK
    assert blocker.calls == []


def test_lists_remove_by_moving_the_last_entry_into_the_gap() -> None:
    cell = _block(WEST).lcell[0]
    shadows = [ShadowObj(_Body(n), cell.id) for n in "abc"]
    for shadow in shadows:
        cell.add_shadow_object(shadow)
    assert all(s.cell is cell for s in shadows)
    cell.remove_shadow_object(shadows[0])
    # The last shadow fills slot 0 (acclient.c:346851); the removed one loses its cell.
    assert cell.shadow_objects == [shadows[2], shadows[1]]
    assert shadows[0].cell is None
    world = World()
    objs = [PhysicsObj(world, n) for n in "xyz"]
    for obj in objs:
        cell.add_object(obj)
    cell.remove_object(objs[0])
    assert cell.objects == [objs[2], objs[1]]  # acclient.c:347789
    assert cell.get_object(objs[1].id) is objs[1]


# --- find_env_collisions -----------------------------------------------------------------------


def _env_transition(cell: LandCell, center: Vector3, radius: float, state: ObjectInfoState) -> Transition:
    transition = _transition()
    transition.object_info.state = state
    path = transition.sphere_path
    path.local_sphere = [Sphere(Vector3(0.0, 0.0, radius), radius)]
    path.local_low_point = Vector3()
    origin = center - Vector3(0.0, 0.0, radius)
    path.curr_pos = Position(cell.id, Frame(origin))
    path.cache_global_curr_center()
    path.set_check_pos(Position(cell.id, Frame(origin)), cell)
    return transition


RESTING = ObjectInfoState.CONTACT | ObjectInfoState.ON_WALKABLE


def test_sphere_resting_on_flat_terrain_touches_it() -> None:
    cell = _block(WEST).lcell[9]  # flat at TABLE[10] = 10 m
    transition = _env_transition(cell, Vector3(36.0, 36.0, 10.5), 0.5, RESTING)
    # dist = 0 is within EPSILON: the triangle's plane becomes the contact plane (acclient.c:314237-314238).
    assert cell.find_env_collisions(transition) == TransitionState.OK
    info = transition.collision_info
    assert info.contact_plane_valid and info.contact_plane_cell_id == cell.id
    assert info.contact_plane.N.exactly_equals(Vector3(0.0, 0.0, 1.0)) and info.contact_plane.d == -10.0
    # In contact already: no collision normal (acclient.c:314240).
    assert not info.collision_normal_valid
    assert transition.sphere_path.check_pos.frame.origin.z == 10.0


def test_sphere_falling_into_sloped_terrain_is_lifted_onto_it() -> None:
    # Height byte 10 + 2·ix: the plane z = 10 + x/12 over the whole block.
    block = _block(WEST, height=[10 + 2 * (i // 9) for i in range(81)])
    cell = block.lcell[9]
    transition = _env_transition(cell, Vector3(36.0, 36.0, 13.2), 0.5, ObjectInfoState.DEFAULT)
    # The sphere bottom is 0.3 m below the plane (z 13 at x 36): lifted by -dist/N.z = 0.3
    # (acclient.c:314253, 314269), ADJUSTED, and without contact the plane normal is the
    # collision normal (acclient.c:314272).
    assert cell.find_env_collisions(transition) == TransitionState.ADJUSTED
    path = transition.sphere_path
    assert path.check_pos.frame.origin.z == pytest.approx(12.7 + 0.3, abs=1e-9)
    assert path.global_sphere[0].center.z == pytest.approx(13.5, abs=1e-9)
    info = transition.collision_info
    assert info.contact_plane_valid and info.contact_plane_cell_id == cell.id
    assert info.collided_with_environment and info.collision_normal_valid
    assert info.collision_normal.x == pytest.approx(-1.0 / 12.0 / (1.0 + 1.0 / 144.0) ** 0.5)


def test_sphere_above_terrain_is_untouched() -> None:
    cell = _block(WEST).lcell[9]
    transition = _env_transition(cell, Vector3(36.0, 36.0, 11.0), 0.5, RESTING)
    # dist = 0.5 > EPSILON (acclient.c:314231).
    assert cell.find_env_collisions(transition) == TransitionState.OK
    assert not transition.collision_info.contact_plane_valid


def test_water_depth_lets_the_sphere_sink_into_a_partly_wet_cell() -> None:
    terrain = [GRASS_WORD] * 81
    terrain[1 * 9 + 1] = WATER_WORD  # the south-west corner of cell (1, 1) is water
    cell = _block(WEST, terrain=terrain).lcell[9]
    assert cell.water_type == WaterType.PARTIALLY_WATER
    transition = _env_transition(cell, Vector3(26.0, 26.0, 10.2), 0.5, RESTING)
    # Nearest corner is water: depth 0.45 (acclient.c:353701); dist = -0.3 + 0.45 > EPSILON.
    assert cell.find_env_collisions(transition) == TransitionState.OK
    assert not transition.collision_info.contact_plane_valid


def test_all_water_landblock_stops_all_but_missiles() -> None:
    cell = _block(WEST, terrain=[WATER_WORD] * 81).lcell[9]
    transition = _env_transition(cell, Vector3(36.0, 36.0, 20.0), 0.5, RESTING)
    # Block water type ENTIRELY: COLLIDED (acclient.c:355030-355033).
    assert cell.find_env_collisions(transition) == TransitionState.COLLIDED
    transition.object_info.object.state |= PhysicsState.MISSILE
    assert cell.find_env_collisions(transition) == TransitionState.OK


def test_low_point_outside_the_cell_finds_no_terrain() -> None:
    block = _block(WEST)
    transition = _env_transition(block.lcell[9], Vector3(36.0, 36.0, 9.0), 0.5, ObjectInfoState.DEFAULT)
    # find_terrain_poly fails in a neighbouring cell: OK, nothing touched (acclient.c:355028).
    assert block.lcell[10].find_env_collisions(transition) == TransitionState.OK
    assert not transition.collision_info.contact_plane_valid


def test_find_collisions_checks_terrain_before_objects() -> None:
    cell = _block(WEST, terrain=[WATER_WORD] * 81).lcell[9]
    body = _Body("post")
    cell.add_shadow_object(ShadowObj(body, cell.id))
    transition = _env_transition(cell, Vector3(36.0, 36.0, 20.0), 0.5, RESTING)
    # Terrain COLLIDED ends find_collisions before the objects (acclient.c:354896-354898).
    assert cell.find_collisions(transition) == TransitionState.COLLIDED
    assert body.calls == []


def test_entry_restrictions_need_a_moving_object() -> None:
    cell = _block(WEST).lcell[9]
    transition = _env_transition(cell, Vector3(36.0, 36.0, 20.0), 0.5, RESTING)
    transition.object_info.object = None
    assert cell.check_entry_restrictions(transition) == TransitionState.COLLIDED  # acclient.c:347114


# --- landblock ----------------------------------------------------------------------------------


def test_landblock_cells_ids_centres_and_lookup() -> None:
    block = _block(WEST)
    cell = block.lcell[8 * 3 + 5]
    assert cell.id == 0xA9B4001E
    # Centre ((2cx+1)·12, (2cy+1)·12) (acclient.c:354095-354098).
    assert cell.pos.frame.origin.exactly_equals(Vector3(84.0, 132.0, 0.0))
    assert cell.landblock is block
    assert block.get_landcell(0xA9B4001E) is cell
    assert block.get_landcell(0xAAB4001E) is None  # same slot, other block: id mismatch (acclient.c:352110)
    landscape = _landscape(block)
    assert landscape.get_cell(0xA9B4001E) is cell
    assert landscape.get_cell(0xA9B40100) is None
    with pytest.raises(ValueError, match="already"):
        landscape.add_landblock(_block(WEST))
