"""Static objects with solid geometry shadow into cells by their parts' bounding boxes.

CPhysicsObj::add_obj_to_cell (acclient.c:322896) places the parts (CPartArray::SetFrame, 326765)
and calls calc_cross_cells_static (322404) → find_bbox_cell_list (318275) →
CPartArray::calc_cross_cells_static (325457) → the cell's parts overload of find_transit_cells:
CLandCell (355432: add_all_outside_cells 355191, then the building 356096 → 719091 →
CEnvCell::check_building_transit 348153) or CEnvCell (348406).

Outdoor cell low word = 1 + 8·cx + cy (cx, cy the cell's column and row in its landblock).
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState as PS
from acphys.geometry.bbox import BBox
from acphys.geometry.bsp_builder import build_box_tree
from acphys.geometry.plane import Plane, Sidedness
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.physics_obj import PhysicsObj
from acphys.physics_part import PhysicsPart
from acphys.setup import Setup
from acphys.world.rooms import DoorwaySpec, RoomSpec, build_house, build_rooms
from acphys.world.static_objects import add_static_object
from acphys.world.world import World

BLOCK = 0xA9B4
EAST = 0xAAB4  # the landblock east of BLOCK (x + 1)


def _cell(block: int, low: int) -> int:
    return (block << 16) | low


def _box(half: float = 1.0, height: float = 2.0) -> Setup:
    return Setup("box", physics_bsp=build_box_tree(Vector3(-half, -half, 0.0), Vector3(half, half, height)))


def _place(
    world: World, cell_id: int, origin: Vector3, heading: float = 0.0, scale: float = 1.0
) -> PhysicsObj:
    frame = Frame.from_heading(origin, heading)
    return add_static_object(world, "box", _box(), Position(cell_id, frame), scale)


def _shadow_cells(obj: PhysicsObj) -> list[int]:
    """The cells holding a shadow of ``obj`` (checked on the cells themselves), in shadow order."""
    cells = []
    for shadow in obj.shadow_objects:
        assert shadow.cell is not None
        assert any(s is shadow for s in shadow.cell.shadow_objects)
        cells.append(shadow.cell.id)
    return cells


@pytest.fixture
def ground() -> World:
    world = World()
    world.set_flat_ground(BLOCK, 0.0)
    return world


# -- the part --------------------------------------------------------------------------------


def test_the_part_box_is_the_physics_bsp_vertices_and_the_part_follows_the_body(ground):
    obj = _place(ground, _cell(BLOCK, 0x0A), Vector3(36.0, 30.0, 0.0), heading=90.0)
    assert obj.state & PS.HAS_PHYSICS_BSP
    (part,) = obj.part_array.parts
    box = part.get_bounding_box()  # CPhysicsPart::GetBoundingBox returns gfx_bound_box (acclient.c:314453)
    assert box.min.exactly_equals(Vector3(-1.0, -1.0, 0.0)) and box.max.exactly_equals(Vector3(1.0, 1.0, 2.0))
    # enter_cell → CPartArray::SetCellID (acclient.c:318230-318233); add_obj_to_cell → SetFrame (322911).
    assert part.pos.objcell_id == _cell(BLOCK, 0x0A)
    assert part.pos.frame.origin == Vector3(36.0, 30.0, 0.0)
    assert part.pos.frame.get_heading() == pytest.approx(90.0)
    assert part.always_2d() is False  # no degrade info (acclient.c:314648-314651)
    # physics_sphere is the physics BSP's root sphere (CGfxObj::Serialize, acclient.c:356682).
    assert part.get_sphere() is obj.part_array.setup.physics_bsp.get_sphere()


def test_set_scale_internal_gives_every_part_the_scale(ground):
    obj = _place(ground, _cell(BLOCK, 0x0A), Vector3(36.0, 36.0, 0.0), scale=1.5)
    # SetScaleStatic → SetScaleInternal: gfxobj_scale = scale without a default_scale
    # (acclient.c:326219-326225)
    assert obj.part_array.parts[0].gfxobj_scale.exactly_equals(Vector3(1.5, 1.5, 1.5))
    assert obj.part_array.scale == 1.5


def test_intersect_box_is_crossing_unless_every_corner_is_beyond_epsilon_on_one_side():
    plane = Plane(Vector3(1.0, 0.0, 0.0), -10.0)  # x = 10
    # Plane::intersect_box (acclient.c:467717): all corners > EPSILON → POSITIVE, < -EPSILON → NEGATIVE.
    assert plane.intersect_box(BBox(Vector3(10.001, 0, 0), Vector3(11, 1, 1))) == Sidedness.POSITIVE
    assert plane.intersect_box(BBox(Vector3(8, 0, 0), Vector3(9.999, 1, 1))) == Sidedness.NEGATIVE
    # The min corner within EPSILON (0.0002) of the plane is CROSSING at once (acclient.c:467742-467746).
    assert plane.intersect_box(BBox(Vector3(10.0001, 0, 0), Vector3(11, 1, 1))) == Sidedness.CROSSING
    # ... and so is a later corner within EPSILON (which_side says IN_PLANE, not the min's side).
    assert plane.intersect_box(BBox(Vector3(9, 0, 0), Vector3(9.9999, 1, 1))) == Sidedness.CROSSING


def test_local_to_global_is_the_box_around_the_moved_corners_in_the_target_landblock():
    box = BBox(Vector3(-1.0, -1.0, 0.0), Vector3(1.0, 1.0, 2.0))
    part_pos = Position(_cell(EAST, 0x01), Frame.from_heading(Vector3(1.0, 5.0, 0.0), 45.0))
    out = BBox.local_to_global(box, part_pos, Position(_cell(BLOCK, 0x3D)))
    # Position::localtoglobal adds get_block_offset(to, from): EAST is 192 m east (acclient.c:147154).
    r = math.sqrt(2.0)
    assert out.min.x == pytest.approx(193.0 - r) and out.max.x == pytest.approx(193.0 + r)
    assert out.min.y == pytest.approx(5.0 - r) and out.max.y == pytest.approx(5.0 + r)
    assert out.min.z == pytest.approx(0.0) and out.max.z == pytest.approx(2.0)


# -- outdoors --------------------------------------------------------------------------------


def test_a_box_on_a_cell_corner_shadows_into_the_four_cells(ground):
    obj = _place(ground, _cell(BLOCK, 0x0A), Vector3(24.0, 24.0, 0.0))
    # Box [23, 25]²: floor(c/24) spans columns and rows 0..1 around the anchor (1,1)
    # (acclient.c:355312-355331); find_bbox_cell_list puts the body's own cell first (acclient.c:318285),
    # then add_cell_block adds column by column (acclient.c:355139): (0,0), (0,1), (1,0), (1,1).
    expected = [_cell(BLOCK, low) for low in (0x0A, 0x01, 0x02, 0x09)]
    assert _shadow_cells(obj) == expected


def test_a_box_well_inside_a_cell_shadows_only_there(ground):
    obj = _place(ground, _cell(BLOCK, 0x0A), Vector3(36.0, 36.0, 0.0))
    assert _shadow_cells(obj) == [_cell(BLOCK, 0x0A)]  # [35, 37]² stays in column and row 1


def test_a_turned_box_shadows_by_the_box_around_its_turned_corners(ground):
    # Unturned, [45.8, 47.8] stays in column 1; turned 45°, the corners reach 46.8 + √2 = 48.21, column 2
    # (BBox::LocalToGlobal through the part's frame, acclient.c:476912).
    straight = _place(ground, _cell(BLOCK, 0x0A), Vector3(46.8, 36.0, 0.0))
    turned = _place(ground, _cell(BLOCK, 0x0A), Vector3(46.8, 36.0, 0.0), heading=45.0)
    assert _shadow_cells(straight) == [_cell(BLOCK, 0x0A)]
    assert _shadow_cells(turned) == [_cell(BLOCK, 0x0A), _cell(BLOCK, 0x12)]


def test_a_scaled_box_shadows_by_its_unscaled_box(ground):
    # GetBoundingBox is the gfx object's box, unscaled (acclient.c:314453), and LocalToGlobal moves it by the
    # part frame only: scaled ×2 the box would reach 48.5, but the unscaled [45.5, 47.5] stays in column 1.
    obj = _place(ground, _cell(BLOCK, 0x0A), Vector3(46.5, 36.0, 0.0), scale=2.0)
    assert _shadow_cells(obj) == [_cell(BLOCK, 0x0A)]


def test_a_box_across_a_landblock_seam_shadows_into_both_landblocks(ground):
    ground.set_flat_ground(EAST, 0.0)
    obj = _place(ground, _cell(BLOCK, 0x3D), Vector3(191.0, 100.0, 0.0))
    # Anchor (7, 4) = 0x3D; box x [190, 192] floors to columns 7..8, i.e. one column past the anchor
    # (acclient.c:355318-355337): global lcoord x + 1 is EAST's column 0, row 4 → 0x05.
    assert _shadow_cells(obj) == [_cell(BLOCK, 0x3D), _cell(EAST, 0x05)]


# -- indoors ---------------------------------------------------------------------------------

ROOM_A = _cell(BLOCK, 0x100)
ROOM_B = _cell(BLOCK, 0x101)


@pytest.fixture
def rooms(ground) -> World:
    """Rooms A [50,60]×[50,60] and B [60,70]×[50,60], a doorway between them at x = 60 (y 54..56) and
    one from A to the outside at y = 50 (x 52..54); every portal has portal_side 0."""
    cells = build_rooms(
        [
            RoomSpec(ROOM_A, Vector3(50.0, 50.0, 0.0), Vector3(60.0, 60.0, 4.0)),
            RoomSpec(ROOM_B, Vector3(60.0, 50.0, 0.0), Vector3(70.0, 60.0, 4.0)),
        ],
        [
            DoorwaySpec(Vector3(60.0, 54.0, 0.0), Vector3(60.0, 56.0, 3.0)),
            DoorwaySpec(Vector3(52.0, 50.0, 0.0), Vector3(54.0, 50.0, 3.0)),
        ],
    )
    for cell in cells:
        ground.add_cell(cell)
    return ground


def test_a_box_inside_a_room_stays_in_the_room(rooms):
    obj = _place(rooms, ROOM_A, Vector3(55.0, 55.0, 0.5))
    # Its sphere (radius √3) is 5 m from either portal plane: side 0 needs dist <= r + EPSILON
    # (acclient.c:348472-348475).
    assert _shadow_cells(obj) == [ROOM_A]


def test_a_box_whose_sphere_reaches_a_doorway_but_whose_box_does_not_stays_in_the_room(rooms):
    # Sphere centre 1.5 m from the x = 60 portal (radius √3: it passes), box x [57.5, 59.5] wholly on the
    # positive side, which equals portal_side 0: skipped (acclient.c:348487).
    obj = _place(rooms, ROOM_A, Vector3(58.5, 55.0, 0.5))
    assert _shadow_cells(obj) == [ROOM_A]


def test_a_box_across_a_doorway_shadows_into_both_rooms(rooms):
    obj = _place(rooms, ROOM_A, Vector3(60.0, 55.0, 0.5))
    # Box x [59, 61] crosses the portal; B is loaded and the box in B's frame is in its cell BSP
    # (acclient.c:348511-348515).
    assert _shadow_cells(obj) == [ROOM_A, ROOM_B]


def test_a_box_across_the_outside_doorway_shadows_into_the_land_cell(rooms):
    obj = _place(rooms, ROOM_A, Vector3(53.0, 50.0, 0.5))
    # The outside portal sets check_outside (acclient.c:348492); add_all_outside_cells anchors on the part's
    # origin re-homed outdoors, (53, 50) → (2, 2) = 0x13, and the box [52, 54] × [49, 51] stays there.
    assert _shadow_cells(obj) == [ROOM_A, _cell(BLOCK, 0x13)]


# -- through a building's door -----------------------------------------------------------------


@pytest.fixture
def house(ground) -> World:
    """A one-room house [50,60]² with a door at y = 50 (x 54..56), standing in land cell (2,2) = 0x13."""
    building, cells = build_house(
        [RoomSpec(ROOM_A, Vector3(50.0, 50.0, 0.0), Vector3(60.0, 60.0, 4.0))],
        [DoorwaySpec(Vector3(54.0, 50.0, 0.0), Vector3(56.0, 50.0, 3.0))],
    )
    for cell in cells:
        ground.add_cell(cell)
    building.add_to_cell(ground.get_cell(_cell(BLOCK, 0x13)))
    return ground


def test_a_box_across_a_building_door_shadows_into_the_room(house):
    obj = _place(house, _cell(BLOCK, 0x13), Vector3(55.0, 49.5, 0.5))
    # Box y [48.5, 50.5] crosses the door's plane: CROSSING is taken (acclient.c:348222), the box is in the
    # room's cell BSP, the room is added (348225-348227). Its own outside portal then finds the land cells
    # already added (added_outside).
    assert _shadow_cells(obj) == [_cell(BLOCK, 0x13), ROOM_A]


def test_a_box_wholly_inside_a_building_room_reaches_it_through_the_door(house):
    # An outdoor-registered box 0.5 m inside the door: its sphere reaches the door plane (1.5 < √3), its box
    # y [50.5, 52.5] is wholly POSITIVE, and retail takes intersect_box == portal_side (0)
    # (acclient.c:348222).
    # ACE (EnvCell.check_building_transit) takes Negative for portal_side 0 and would leave the room out.
    obj = _place(house, _cell(BLOCK, 0x13), Vector3(55.0, 51.5, 0.5))
    assert _shadow_cells(obj) == [_cell(BLOCK, 0x13), ROOM_A]


def test_a_box_outside_a_building_door_stays_outdoors(house):
    # Sphere centre 2.5 m outside the door (dist -2.5 < -(√3 + EPSILON)): skipped (acclient.c:348215).
    # The box y [46.5, 48.5] still reaches row 1 outdoors: (2,1) = 0x12 (acclient.c:355337).
    obj = _place(house, _cell(BLOCK, 0x13), Vector3(55.0, 47.5, 0.5))
    assert _shadow_cells(obj) == [_cell(BLOCK, 0x13), _cell(BLOCK, 0x12)]


def test_a_part_without_a_sphere_is_skipped_at_portals(rooms):
    # No physics BSP and no sorting sphere: no sphere, so the portal tests skip the part
    # (acclient.c:348454-348457); the cell it stands in is still there.
    setup = Setup("spheres", spheres=[Sphere(Vector3(0.0, 0.0, 1.0), 1.0)])
    part = PhysicsPart(setup)
    assert part.get_sphere() is None
    assert part.get_bounding_box().min.exactly_equals(Vector3(-1.0, -1.0, 0.0))
    obj = add_static_object(rooms, "ball", setup, Position(ROOM_A, Frame(Vector3(60.0, 55.0, 0.5))))
    assert _shadow_cells(obj) == [ROOM_A]
