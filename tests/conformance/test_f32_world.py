"""Float32 at rest in the world: terrain heights, cell re-homing, cell-list and portal bounds.

Each test picks inputs where storing a ``float`` (float32) and keeping a double give different
results, derives the float32 value by hand from the decompiled lines cited, and asserts it
exactly. The last tests check that the numbers the world's objects keep are float32 after use.

``EPSILON`` is retail's ``0.00019999999`` (f32(0.0002)); ``_step32`` steps between float32s.
"""

from __future__ import annotations

import struct
from collections.abc import Iterator

from acphys.constants import EPSILON
from acphys.geometry.bbox import BBox
from acphys.geometry.bsp import BSPLeaf, BSPNode
from acphys.geometry.polygon import Polygon
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import adjust_to_outside
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3 as V
from acphys.precision import f32, is_f32
from acphys.world.env_cell import EnvCell
from acphys.world.landblock import LandBlock
from acphys.world.obj_cell import CellArray, ObjCell
from acphys.world.rooms import DoorwaySpec, RoomSpec, build_house, build_rooms
from acphys.world.terrain import LandBlockStruct, set_height_table
from acphys.world.world import World

BLOCK = 0xA9B4
A, B = 0xA9B40100, 0xA9B40101
GRASS_WORD = 1 << 2


def _step32(x: float, steps: int = 1) -> float:
    """The float32 ``steps`` float32s after (or, negative, before) the positive float32 ``x``."""
    return struct.unpack("<f", struct.pack("<I", struct.unpack("<I", struct.pack("<f", x))[0] + steps))[0]


class Cells:
    """A cell source over a dict (retail's ``CEnvCell::GetVisible`` / ``CLandCell::Get``)."""

    def __init__(self, *cells: ObjCell) -> None:
        self.cells = {cell.id: cell for cell in cells}

    def get_cell(self, cell_id: int) -> ObjCell | None:
        return self.cells.get(cell_id)


# --- terrain heights ------------------------------------------------------------------------------


def test_height_table_and_vertex_heights_are_float32() -> None:
    # LandDefs::set_height_table copies float entries (acclient.c:467321); ConstructVertices stores
    # the table value into the vertex's float z (acclient.c:354657-354658): 0.1 is kept as f32(0.1).
    table = set_height_table([0.1] * 256)
    assert table[0] == f32(0.1) != 0.1
    lb = LandBlockStruct(0xA9B4FFFF, [0] * 81, [GRASS_WORD] * 81, [0.1] * 256)
    assert lb.vertex(3, 4).z == f32(0.1)
    # a height just above 800 that is 800 as a float32 passes the <= 800 test on the stored value
    assert set_height_table([0.0] * 255 + [800.00001])[-1] == 800.0


def test_flat_ground_height_is_the_float32_height() -> None:
    # flat_landblock's table holds f32(0.1); the plane through three vertices at that height is
    # (0, 0, 1), d = -f32(0.1), and set_height gives z = -d / 1 = f32(0.1).
    world = World()
    world.set_flat_ground(BLOCK, 0.1)
    assert world.ground_height(0xA9B40001, V(10.0, 10.0, 50.0)) == f32(0.1)


# --- LandDefs::adjust_to_outside -------------------------------------------------------------------


def test_adjust_to_outside_stores_the_moved_x_as_float32() -> None:
    # acclient.c:467457: loc->x = loc->x - floor(loc->x / 192) * 192, a float store.
    # x = f32(-0.001) (not within EPSILON of 0): floor(x / 192) = -1, x + 192 rounds to float32.
    x = f32(-0.001)
    loc = V(-0.001, 5.0, 2.0)
    assert adjust_to_outside(0xA9B40001, loc) == 0xA8B40039
    assert loc.x == f32(x + 192.0)
    assert loc.x != x + 192.0
    assert (loc.y, loc.z) == (5.0, 2.0)


# --- CLandCell::add_all_outside_cells ------------------------------------------------------------


def test_far_side_bound_is_a_float32_so_a_sphere_at_it_adds_no_neighbour() -> None:
    # acclient.c:355392: max_rad = 24.0 - min_rad, a float local. r = the float32 after 0.5:
    # 24 - r = 23.49999994..., which rounds to max_rad = 23.5. The sphere at x = 47.5 of cell (1, 1)
    # has pt1.x = 47.5 - 24 = 23.5 (acclient.c:355390), and 23.5 > 23.5 is false
    # (acclient.c:355167): the east cell (2, 1) = 0xA9B40012 is not added. With 24 - r kept double
    # it would be.
    r = _step32(0.5)
    assert f32(24.0 - r) == 23.5 > 24.0 - r
    world = World()
    world.set_flat_ground(BLOCK, 0.0)
    cell_array = CellArray(world)
    p = Position(0xA9B4000A, Frame(V(47.5, 36.0, 10.0)))
    ObjCell.find_cell_list(p, [Sphere(V(47.5, 36.0, 10.0), r)], cell_array)
    assert cell_array.cell_ids() == [0xA9B4000A]


# --- CEnvCell portal tests -------------------------------------------------------------------------

#: r with f32(r + EPSILON) below r + EPSILON, and that float32 a multiple of 2^-21.
R_DOWN = 0.5000002980232239
Q_DOWN = 0.5002002716064453
#: r with f32(r + EPSILON) above r + EPSILON (it is 1 + 2^-22).
R_UP = 0.9998002052307129
Q_UP = 1.000000238418579


def test_radius_constants() -> None:
    assert is_f32(R_DOWN) and f32(R_DOWN + EPSILON) == Q_DOWN < R_DOWN + EPSILON
    assert is_f32(R_UP) and f32(R_UP + EPSILON) == Q_UP > R_UP + EPSILON


def _front_door_room() -> EnvCell:
    """Room A, box (0,0,0)-(4,4,3), cell frame at the origin, one door to the outside on y = 0: its
    portal plane is N = (0, 1, 0), d = 0 in the cell frame (facing into the room, portal_side 0)."""
    (room,) = build_rooms([RoomSpec(A, V(0, 0, 0), V(4, 4, 3))], [DoorwaySpec(V(1, 0, 0), V(2, 0, 2))])
    plane = room.portals[0].portal.plane
    assert plane.N.exactly_equals(V(0.0, 1.0, 0.0)) and plane.d == 0.0
    return room


def _two_rooms() -> tuple[EnvCell, EnvCell]:
    """Rooms A (0,0,0)-(4,4,3) and B (4,0,0)-(8,4,3), a doorway on x = 4; A's portal to B has, in A's
    frame (at the origin), N = (-1, 0, 0), d = 4 and portal_side 0."""
    room_a, room_b = build_rooms(
        [RoomSpec(A, V(0, 0, 0), V(4, 4, 3)), RoomSpec(B, V(4, 0, 0), V(8, 4, 3))],
        [DoorwaySpec(V(4, 1, 0), V(4, 2, 2))],
    )
    plane = room_a.portals[0].portal.plane
    assert plane.N.exactly_equals(V(-1.0, 0.0, 0.0)) and plane.d == 4.0
    return room_a, room_b


def _transit(cell: EnvCell, source: Cells, center: V, radius: float) -> list[int]:
    array = CellArray(source)
    cell.find_transit_cells(Position(cell.id), [Sphere(center, radius)], array, None)
    return array.cell_ids()


def test_outside_portal_bound_is_a_float32() -> None:
    # acclient.c:348315: ia = radius + 0.00019999999, a float local; the distance is
    # lz*N.z + ly*N.y + lx*N.x + d (acclient.c:348316-348320) with ly the float spill of
    # (y - 0)*1 (acclient.c:348314) = y. At y = Q_DOWN = ia, dist < ia is false: no outdoor cells;
    # with the double R_DOWN + EPSILON it would be true. One float32 closer and it is crossed.
    room = _front_door_room()
    source = Cells(room)
    assert _transit(room, source, V(2.0, Q_DOWN, 1.0), R_DOWN) == []
    assert 0xA9B40001 in _transit(room, source, V(2.0, _step32(Q_DOWN, -1), 1.0), R_DOWN)


def test_unloaded_neighbour_bound_stays_double() -> None:
    # acclient.c:348371: v28 = radius + 0.00019999999 stays in a register (double). The centre
    # (4 - Q_DOWN, 2, 1) is exact (Q_DOWN is a multiple of 2^-21), so in A's frame lx = 4 - Q_DOWN and
    # dist = ly*0 + lz*0 + lx*(-1) + 4 = Q_DOWN (acclient.c:348378-348381). Side 0 adds B when
    # dist < R_DOWN + EPSILON (acclient.c:348384): true for the double, false for its float32 Q_DOWN.
    room_a, _room_b = _two_rooms()
    assert _transit(room_a, Cells(room_a), V(4.0 - Q_DOWN, 2.0, 1.0), R_DOWN) == [B]


class _Part:
    """The three things the portal tests read from a ``CPhysicsPart``."""

    def __init__(self, pos: Position, radius: float) -> None:
        self.pos = pos
        self._sphere = Sphere(V(0.0, 0.0, 0.0), radius)
        self._box = BBox(V(-1.0, -1.0, -1.0), V(1.0, 1.0, 1.0))

    def get_sphere(self) -> Sphere:
        return self._sphere

    def get_bounding_box(self) -> BBox:
        return self._box


def test_parts_portal_bound_is_a_float32() -> None:
    # acclient.c:348462-348465: radius = sphere radius + 0.00019999999, a float local. The part's
    # sphere centre, taken into A's frame (Position::localtolocal), is (4 - Q_UP, 2, 1), so
    # dist = Q_UP (acclient.c:348468-348471) and side 0 skips the part when dist > radius
    # (acclient.c:348474): Q_UP > f32(R_UP + EPSILON) = Q_UP is false, so the part's box (x from
    # 3 - Q_UP to 5 - Q_UP, crossing the portal) goes through to B, which is not loaded: B's id is
    # added (acclient.c:348500). With the double bound (below Q_UP) the part would be skipped.
    room_a, _room_b = _two_rooms()
    part = _Part(Position(A, Frame(V(4.0 - Q_UP, 2.0, 1.0))), R_UP)
    array = CellArray(Cells(room_a))
    room_a.find_transit_cells_for_parts([part], array)  # type: ignore[list-item]
    assert array.cell_ids() == [B]


# --- the stored numbers are float32 after use ------------------------------------------------------


def _vector_floats(v: V) -> tuple[float, float, float]:
    return (v.x, v.y, v.z)


def _polygon_floats(poly: Polygon) -> Iterator[float]:
    for vertex in poly.vertices:
        yield from _vector_floats(vertex)
    yield from _vector_floats(poly.plane.N)
    yield poly.plane.d


def _bsp_floats(node: BSPNode | None) -> Iterator[float]:
    if node is None:
        return
    if node.sphere is not None:
        yield from _vector_floats(node.sphere.center)
        yield node.sphere.radius
    if isinstance(node, BSPLeaf):
        for poly in node.polys:
            yield from _polygon_floats(poly)
        return
    yield from _vector_floats(node.splitting_plane.N)
    yield node.splitting_plane.d
    yield from _bsp_floats(node.pos_node)
    yield from _bsp_floats(node.neg_node)


def _frame_floats(frame: Frame) -> Iterator[float]:
    yield from _vector_floats(frame.origin)
    yield from (frame.qw, frame.qx, frame.qy, frame.qz)
    yield from frame.m


def test_terrain_and_land_cells_hold_float32_after_use() -> None:
    world = World()
    table = [(i * 3.1) % 800.0 for i in range(256)]  # mostly not float32
    heights = [(7 * i) % 256 for i in range(81)]
    world.add_landblock(LandBlock(LandBlockStruct(0xA9B4FFFF, heights, [GRASS_WORD] * 81, table)))
    # use: heights, normals and a cell list over the block
    for x, y in ((10.3, 20.7), (100.1, 150.9), (191.2, 0.4)):
        assert is_f32(world.ground_height(0xA9B40001, V(x, y, 0.0)))
    cell_array = CellArray(world)
    ObjCell.find_cell_list(
        Position(0xA9B4000A, Frame(V(47.3, 36.1, 10.0))), [Sphere(V(47.3, 36.1, 10.0), 0.7)], cell_array
    )
    block = world.landscape.get_landblock(0xA9B40001)
    assert block is not None
    terrain = block.terrain
    values = list(terrain.height_table)
    for vertex in terrain.vertices:
        values.extend(_vector_floats(vertex))
    for poly in terrain.polygons:
        values.extend(_polygon_floats(poly))
    for cell in block.lcell:
        values.extend(_frame_floats(cell.pos.frame))
    assert all(is_f32(v) for v in values)


def test_rooms_and_building_hold_float32_after_use() -> None:
    # build_house stands for DAT data: everything it stores is float32, from inputs that are not
    building, cells = build_house(
        [
            RoomSpec(A, V(100.1, 100.3, 10.7), V(104.1, 104.3, 13.7)),
            RoomSpec(B, V(104.1, 100.3, 10.7), V(108.1, 104.3, 13.7)),
        ],
        [
            DoorwaySpec(V(104.1, 101.3, 10.7), V(104.1, 102.3, 12.7)),
            DoorwaySpec(V(101.1, 100.3, 10.7), V(102.1, 100.3, 12.7)),
        ],
        wall_thickness=0.1,
    )
    world = World()
    world.set_flat_ground(BLOCK, 10.7)
    for cell in cells:
        world.add_cell(cell)
    land = world.get_cell(0xA9B40025)
    assert land is not None
    building.add_to_cell(land)  # type: ignore[arg-type]
    # use: a cell list through the front door and from room to room
    for center in (V(101.6, 100.2, 11.2), V(104.0, 101.8, 11.2)):
        cell_array = CellArray(world)
        ObjCell.find_cell_list(Position(A, Frame(center)), [Sphere(center, 0.45)], cell_array)
    values: list[float] = []
    for cell in cells:
        values.extend(_frame_floats(cell.pos.frame))
        for poly in cell.structure.polygons:
            values.extend(_polygon_floats(poly))
        values.extend(_bsp_floats(cell.structure.cell_bsp.root_node))
        assert cell.structure.physics_bsp is not None
        values.extend(_bsp_floats(cell.structure.physics_bsp.root_node))
    values.extend(_frame_floats(building.pos.frame))
    values.extend(_vector_floats(building.part.gfxobj_scale))
    assert building.physics_bsp is not None
    values.extend(_bsp_floats(building.physics_bsp.root_node))
    assert all(is_f32(v) for v in values)
