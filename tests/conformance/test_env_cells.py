"""Indoor cells, portals and buildings (CEnvCell, CCellStruct, CCellPortal, CBldPortal,
CBuildingObj), on a house built by ``acphys.world.rooms``; expected values worked by hand from the
decompiled CEnvCell.c, CCellStruct.c, CCellPortal.c, CBldPortal.c, CBuildingObj.c and CBSPNode.c.

The house, landblock 0xA9B4 (all coordinates landblock-local):
- room A 0xA9B40100: box (100,100,10)-(104,104,13), cell frame at (100,100,10);
- room B 0xA9B40101: box (104,100,10)-(108,104,13), cell frame at (104,100,10);
- doorway A-B on x = 104, y 101..102, z 10..12; front door of A on y = 100, x 101..102, z 10..12;
- shell 0.25 m outside the rooms (front face y = 99.75), origin (104,102,10): in land cell
  0xA9B40025 (cx = cy = 4, 1 + 8*4 + 4 = 37).
Each room's cell BSP is its six inward face planes; its walls face into the room.
"""

from __future__ import annotations

import pytest

from acphys.constants import EPSILON
from acphys.flags import TransitionState as TS
from acphys.geometry.bsp import CELL_OUTSIDE, CELL_PARTIALLY_INSIDE
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.physics_obj import PhysicsObj
from acphys.transition.transition import InsertType, Transition
from acphys.world.building import BldPortal, BuildingObj
from acphys.world.env_cell import OUTSIDE_CELL_ID, CellPortal, EnvCell, Environment
from acphys.world.land_cell import LandCell
from acphys.world.obj_cell import CellArray, ObjCell
from acphys.world.rooms import DoorwaySpec, RoomSpec, build_house, build_rooms
from acphys.world.world import World

A, B, C = 0xA9B40100, 0xA9B40101, 0xA9B40102
LAND = 0xA9B40025
ROOMS = [RoomSpec(A, V(100, 100, 10), V(104, 104, 13)), RoomSpec(B, V(104, 100, 10), V(108, 104, 13))]
DOORS = [DoorwaySpec(V(104, 101, 10), V(104, 102, 12)), DoorwaySpec(V(101, 100, 10), V(102, 100, 12))]


class Cells:
    """A cell source over a dict (retail's global ``CEnvCell::GetVisible`` / ``CLandCell::Get``)."""

    def __init__(self, *cells: ObjCell) -> None:
        self.cells = {cell.id: cell for cell in cells}

    def get_cell(self, cell_id: int) -> ObjCell | None:
        return self.cells.get(cell_id)


@pytest.fixture
def house() -> tuple[BuildingObj, EnvCell, EnvCell, LandCell, Cells]:
    building, (room_a, room_b) = build_house(ROOMS, DOORS)
    land = LandCell(LAND)
    building.add_to_cell(land)
    source = Cells(room_a, room_b, land)
    building.source = source
    return building, room_a, room_b, land, source


def transit(cell: EnvCell, source: Cells, center: V, radius: float) -> list[int]:
    array = CellArray(source)
    cell.find_transit_cells(Position(cell.id), [Sphere(center, radius)], array, None)
    return array.cell_ids()


def make_transition(cell_id: int, curr: V, check: V, radius: float) -> Transition:
    """One sphere of ``radius`` centred 0.5 above the origin, from ``curr`` to ``check``."""
    t = Transition(World(), PhysicsObj(World(), "mover"))
    path = t.sphere_path
    path.local_sphere = [Sphere(V(0, 0, 0.5), radius)]
    path.curr_pos = Position(cell_id, Frame(curr))
    path.cache_global_curr_center()
    path.set_check_pos(Position(cell_id, Frame(check)), None)
    path.walk_interp = 1.0
    return t


# --- point_in_cell ------------------------------------------------------------------------------


def test_point_is_in_exactly_one_of_two_adjoining_rooms(house) -> None:
    _b, room_a, room_b, _land, _src = house
    # CEnvCell::point_in_cell takes the point into the cell frame (acclient.c:347947) and walks the
    # cell BSP: outside once a plane has it more than EPSILON behind (acclient.c:362943).
    # (102,102,11) is (2,2,1) in A (all six distances >= 1) and (-2,2,1) in B (x = 0 plane: -2).
    assert room_a.point_in_cell(V(102, 102, 11)) and not room_b.point_in_cell(V(102, 102, 11))
    assert room_b.point_in_cell(V(106, 102, 11)) and not room_a.point_in_cell(V(106, 102, 11))
    # Retail's tolerance: 0.0001 past the shared wall is still in A (-0.0001 > -EPSILON) and in B.
    assert room_a.point_in_cell(V(104.0001, 102, 11)) and room_b.point_in_cell(V(104.0001, 102, 11))
    assert not room_a.point_in_cell(V(104.0003, 102, 11))


def test_cell_without_portals_holds_no_point(house) -> None:
    _b, room_a, _rb, _land, _src = house
    # acclient.c:347941: a null portal array answers 0 before the BSP is asked. ACE's EnvCell.cs
    # always asks the BSP (divergence, decompile wins).
    bare = EnvCell(0xA9B40105, room_a.structure, room_a.pos.frame)
    assert room_a.structure.point_in_cell(V(2, 2, 1))
    assert not bare.point_in_cell(V(102, 102, 11))


# --- find_transit_cells -------------------------------------------------------------------------


def test_sphere_at_the_doorway_reaches_the_neighbour(house) -> None:
    _b, room_a, room_b, _land, source = house
    # Loaded other cell: the sphere in B's frame against B's cell BSP (acclient.c:348339-348355).
    # (103.7,101.5,10.6) r 0.5 is (-0.3,1.5,0.6) in B: the x = 0 plane is within r + 0.0099999998
    # (acclient.c:362993) and the rest of the chain is ahead -> partially inside -> B is added.
    local = Sphere(room_b.pos.frame.globaltolocal(V(103.7, 101.5, 10.6)), 0.5)
    assert room_b.structure.sphere_intersects_cell(local) == CELL_PARTIALLY_INSIDE
    assert transit(room_a, source, V(103.7, 101.5, 10.6), 0.5) == [B]
    # In the middle of A, B's x = 0 plane has it 2 m behind -> outside, nothing added.
    local = Sphere(room_b.pos.frame.globaltolocal(V(102, 102, 10.6)), 0.5)
    assert room_b.structure.sphere_intersects_cell(local) == CELL_OUTSIDE
    assert transit(room_a, source, V(102, 102, 10.6), 0.5) == []


def test_loaded_neighbour_is_reached_by_its_cell_bsp_not_the_portal_polygon(house) -> None:
    _b, room_a, _rb, _land, source = house
    # Retail never consults the portal polygon for a loaded cell (acclient.c:348339-348355): a
    # sphere by the shared wall 1.5 m from the doorway still reaches B.
    assert transit(room_a, source, V(103.7, 103.5, 10.6), 0.5) == [B]


def test_no_portal_no_transit_through_a_wall() -> None:
    # Room C adjoins A's north wall (y = 104) with no doorway: A has no portal to it, so a sphere
    # pressed against that wall reaches nothing (only portals are walked, acclient.c:348290).
    rooms = [*ROOMS, RoomSpec(C, V(100, 104, 10), V(104, 108, 13))]
    room_a, room_b, room_c = build_rooms(rooms, DOORS)
    source = Cells(room_a, room_b, room_c)
    assert (
        room_c.structure.sphere_intersects_cell(
            Sphere(room_c.pos.frame.globaltolocal(V(102, 103.7, 10.6)), 0.5)
        )
        == CELL_PARTIALLY_INSIDE
    )
    assert transit(room_a, source, V(102, 103.7, 10.6), 0.5) == []
    assert [p.other_cell_id for p in room_c.portals] == []


def test_unloaded_neighbour_uses_the_portal_plane_and_side() -> None:
    room_a, _room_b = build_rooms(ROOMS, DOORS)
    source = Cells(room_a)  # B not loaded
    # A's portal to B lies on x = 104, facing into A (N = -x, d = 4 in A's frame), side 0: added as
    # an id when dist < r + EPSILON (acclient.c:348378-348383). (103.7,103.5): dist 0.3.
    assert room_a.portals[0].portal_side == 0
    assert transit(room_a, source, V(103.7, 103.5, 10.6), 0.5) == [B]
    # dist 0.5001 < 0.5002 still adds; 0.5003 does not.
    assert transit(room_a, source, V(103.4999, 103.5, 10.6), 0.5) == [B]
    assert transit(room_a, source, V(103.4997, 103.5, 10.6), 0.5) == []


def test_outside_portal_plane_brings_in_the_outdoor_cells(house) -> None:
    _b, room_a, _rb, _land, source = house
    # An outside portal is crossed when |dist| < r + 0.00019999999 to its unbounded plane
    # (acclient.c:348315-348321), even away from the door polygon; then add_all_outside_cells
    # (acclient.c:348403). A's front portal: y = 100 (local y = 0, N = +y).
    assert room_a.portals[1].other_cell_id == OUTSIDE_CELL_ID
    assert transit(room_a, source, V(102.8, 100.5001, 10.6), 0.5) == [LAND]
    assert transit(room_a, source, V(102.8, 100.5003, 10.6), 0.5) == []
    assert 0.5001 < 0.5 + EPSILON < 0.5003


# --- collisions ---------------------------------------------------------------------------------


def test_sphere_runs_into_an_interior_wall(house) -> None:
    _b, room_a, _rb, _land, _src = house
    # Airborne sphere 0 touching a wall of A's physics BSP: set_collide with the wall's global
    # normal, ADJUSTED (BSPTREE::find_collisions, acclient.c:361295); not in contact -> the
    # environment flag (acclient.c:347846-347847). North wall y = 104, inward N = (0,-1,0).
    t = make_transition(A, V(102, 103.0, 10.1), V(102, 103.7, 10.1), 0.5)
    assert room_a.find_env_collisions(t) == TS.ADJUSTED
    assert t.sphere_path.collide
    assert t.sphere_path.step_up_normal.exactly_equals(V(0, -1, 0))
    assert t.collision_info.collided_with_environment


def test_sphere_passes_the_doorway_but_not_the_wall_beside_it(house) -> None:
    _b, room_a, room_b, _land, _src = house
    # r 0.4 centred (104,101.5,10.6) clears the door edges (y 101/102 at 0.5, lintel z 12 at 1.4).
    for room in (room_a, room_b):
        t = make_transition(room.id, V(103.5, 101.5, 10.1), V(104, 101.5, 10.1), 0.4)
        assert room.find_collisions(t) == TS.OK
    # 1 m along, the wall piece y 102..104 on x = 104 is at distance 0: hit in A.
    t = make_transition(A, V(103.5, 102.5, 10.1), V(104, 102.5, 10.1), 0.4)
    assert room_a.find_collisions(t) == TS.ADJUSTED


def test_env_collisions_need_a_moving_object(house) -> None:
    _b, room_a, _rb, _land, _src = house
    # check_entry_restrictions: no object -> 2 (COLLIDED) before the BSP (acclient.c:347112).
    t = make_transition(A, V(102, 102, 10.1), V(102, 102, 10.1), 0.4)
    t.object_info.object = None
    assert room_a.find_env_collisions(t) == TS.COLLIDED
    assert not t.collision_info.collided_with_environment


def test_initial_placement_in_a_room(house) -> None:
    _b, room_a, _rb, _land, _src = house
    # insert_type 2 runs placement_insert (acclient.c:347838-347839): a sphere clear of every wall
    # is OK where it is.
    t = make_transition(A, V(102, 102, 10.1), V(102, 102, 10.1), 0.4)
    t.sphere_path.insert_type = InsertType.INITIAL_PLACEMENT
    assert room_a.find_env_collisions(t) == TS.OK


# --- buildings ----------------------------------------------------------------------------------


def test_building_portal_leads_from_the_outdoor_cell_into_the_room(house) -> None:
    building, _ra, _rb, land, source = house
    assert land.has_building() and building.pos.objcell_id == LAND
    # find_cell_list from outdoors: the land cell, then CSortCell::find_transit_cells ->
    # find_building_transit_cells -> A's check_building_transit (acclient.c:348109): the sphere
    # (101.5,99.9,10.6) r 0.4 is (1.5,-0.1,0.6) in A, within r + 0.01 of y = 0 -> A is added and
    # hits_interior_cell is set (acclient.c:348145-348147).
    t = make_transition(LAND, V(101.5, 99.9, 10.1), V(101.5, 99.9, 10.1), 0.4)
    path = t.sphere_path
    array = CellArray(source)
    ObjCell.find_cell_list(path.check_pos, path.global_sphere, array, path)
    assert array.cell_ids() == [LAND, A]
    assert path.hits_interior_cell
    # Two metres out the room's cell BSP has it outside: only the land cell.
    t = make_transition(LAND, V(101.5, 98, 10.1), V(101.5, 98, 10.1), 0.4)
    array = CellArray(source)
    ObjCell.find_cell_list(t.sphere_path.check_pos, t.sphere_path.global_sphere, array, t.sphere_path)
    assert array.cell_ids() == [LAND]
    assert not t.sphere_path.hits_interior_cell


def test_building_portal_needs_a_valid_other_portal(house) -> None:
    _b, room_a, _rb, _land, source = house
    # check_building_transit does nothing for portal_id < 0 (acclient.c:348123).
    array = CellArray(source)
    room_a.check_building_transit(-1, Position(LAND), [Sphere(V(101.5, 99.9, 10.6), 0.4)], array, None)
    assert array.cell_ids() == []


def test_building_shell_collides_beside_the_door_not_in_it(house) -> None:
    building, _ra, _rb, land, _src = house
    # Shell front face y = 99.75, facing -y, door hole x 101..102. With bldg_check set during the
    # part's find_collisions and cleared after (acclient.c:719122-719124); airborne touch -> ADJUSTED
    # and the environment flag (acclient.c:719125-719126).
    t = make_transition(LAND, V(103.5, 99.0, 10.1), V(103.5, 99.5, 10.1), 0.4)
    assert building.find_building_collisions(t) == TS.ADJUSTED
    assert t.sphere_path.step_up_normal.exactly_equals(V(0, -1, 0))
    assert t.collision_info.collided_with_environment and not t.sphere_path.bldg_check
    t = make_transition(LAND, V(101.5, 99.0, 10.1), V(101.5, 99.5, 10.1), 0.4)
    assert building.find_building_collisions(t) == TS.OK
    # Via the sort cell hook (CSortCell::find_collisions, acclient.c:356106).
    t = make_transition(LAND, V(103.5, 99.0, 10.1), V(103.5, 99.5, 10.1), 0.4)
    assert super(LandCell, land).find_collisions(t) == TS.ADJUSTED


def test_building_get_object_searches_through_portals(house) -> None:
    building, _ra, room_b, _land, _src = house
    # CBuildingObj::get_object walks the door's cell and its portals (acclient.c:719279,
    # 349403): B is reached through A. ACE's BuildingObj.get_object returns null (divergence).
    body = PhysicsObj(World(), "chair")
    room_b.add_object(body)
    assert building.get_object(body.id) is body
    assert building.get_object(body.id + 1) is None


def test_remove_building_clears_cell(house) -> None:
    building, _ra, _rb, land, _src = house
    building.remove()  # acclient.c:719056
    assert not land.has_building() and building.pos.objcell_id == 0 and building.cell is None


# --- packed portals -----------------------------------------------------------------------------


def test_cell_portal_unpack_flags(house) -> None:
    _b, room_a, _rb, _land, _src = house
    poly = room_a.portals[0].portal
    # CCellPortal::UnPack: exact = bit 0, portal_side = !(bit 1), bit 2 -> -1 (acclient.c:362389-362398).
    p = CellPortal.unpack(0xA9B40000, 0x0, poly, 0x0101, 3)
    assert (p.other_cell_id, p.portal_side, p.exact_match, p.other_portal_id) == (B, 1, False, 3)
    p = CellPortal.unpack(0xA9B40000, 0x3, poly, 0x0101, -1)
    assert (p.portal_side, p.exact_match, p.other_portal_id) == (0, True, -1)
    p = CellPortal.unpack(0xA9B40000, 0x4, poly, 0x0101, 0)
    assert p.other_cell_id == OUTSIDE_CELL_ID
    with pytest.raises(ValueError, match="16-bit"):
        CellPortal.unpack(0xA9B40000, 0x10000, poly, 0x0101, 0)


def test_bld_portal_unpack_and_stablist() -> None:
    # CBldPortal::UnPack: same flag bits, stabs | block_mask (acclient.c:362508-362538).
    portal = BldPortal.unpack(0xA9B40000, 0x2, 0x0100, 1, [0x0100, 0x0101])
    assert (portal.other_cell_id, portal.portal_side, portal.other_portal_id) == (A, 0, 1)
    assert portal.stab_list == [A, B]
    # add_to_stablist appends only ids not yet listed (acclient.c:362436-362470); ACE's
    # BldPortal.add_to_stablist appends the ones already there (divergence).
    stabs = [A, 0xA9B40107]
    portal.add_to_stablist(stabs)
    assert stabs == [A, 0xA9B40107, B]


def test_environment_and_bad_input(house) -> None:
    _b, room_a, _rb, _land, _src = house
    env = Environment([room_a.structure])
    assert env.get_cellstruct(0) is room_a.structure  # acclient.c:352896
    with pytest.raises(ValueError, match="no index 1"):
        env.get_cellstruct(1)
    with pytest.raises(ValueError, match="env cell id"):
        EnvCell(0xA9B40025, room_a.structure)
    with pytest.raises(ValueError, match="not on a wall"):
        build_rooms(ROOMS, [DoorwaySpec(V(103, 101, 10), V(103, 102, 12))])
    with pytest.raises(ValueError, match="overlap"):
        build_rooms([ROOMS[0], RoomSpec(B, V(103, 100, 10), V(108, 104, 13))])
    with pytest.raises(ValueError, match="outside"):
        build_house(ROOMS, DOORS[:1])
