"""Indoor-cell records: ``CEnvironment`` / ``CCellStruct`` (acclient.c:352987, 355822) with their
cell, physics and drawing trees (``BSPNODE::UnPack`` and friends by ``pack_tree_type``), and
``CEnvCell`` (acclient.c:349133), from records written by ``tests/dat_support.py``."""

from __future__ import annotations

import struct
from pathlib import Path

import pytest

import acphys
from acphys.constants import EPSILON
from acphys.dat import DatError
from acphys.dat.env_cell import make_env_cell, unpack_env_cell, unpack_environment
from acphys.geometry.bsp import NODE_TYPE_PORTAL, BSPLeaf, BSPNode, type_tag
from acphys.geometry.polygon import SidesType
from acphys.math.vector import Vector3
from acphys.world.env_cell import OUTSIDE_CELL_ID, EnvCell
from acphys.world.land_cell import SortCell
from dat_support import (
    BOX_GFXOBJ_ID,
    BOX_SETUP_ID,
    ENVIRONMENT_ID,
    LANDBLOCK_ID,
    LANDBLOCK_INFO_ID,
    REGION_ID,
    bld_portal_bytes,
    box_gfxobj_record,
    box_setup_record,
    build_info_bytes,
    cell_portal_bytes,
    env_cell_record,
    environment_record,
    landblock_info_record,
    landblock_record,
    region_record,
    simple_dat,
    stab_bytes,
)
from dat_support import CELL as CELL_DATA
from support import step_records

CELL = 0xA9B40100


def _vec(v: Vector3) -> tuple[float, float, float]:
    return (v.x, v.y, v.z)


def test_cell_struct_vertices_polygons_and_portals() -> None:
    env = unpack_environment(environment_record())
    assert env.did == ENVIRONMENT_ID
    assert len(env.cells) == 1
    cs = env.cells[0]
    assert cs.cellstruct_id == 0
    # CVertexArray::UnPack (acclient.c:362801): positions by array index.
    assert len(cs.vertices) == 12
    assert _vec(cs.vertices[7]) == (6.0, 6.0, 3.0)
    assert _vec(cs.vertices[10]) == (0.0, pytest.approx(3.6), pytest.approx(2.2))
    # CPolygon::UnPack (acclient.c:359808) per polygon; the floor faces up, the doorway +x.
    assert cs.poly_ids == [0, 1]
    assert _vec(cs.polygons[0].plane.N) == (0.0, 0.0, 1.0)
    assert _vec(cs.polygons[1].plane.N) == (1.0, 0.0, 0.0)
    assert cs.polygons[1].sides_type == SidesType.BOTH
    # portals[i] = &polygons[u16] (acclient.c:355822, the portal loop).
    assert cs.portal_indices == [1]
    assert [_vec(p.plane.N) for p in cs.physics_polygons] == [(0.0, 0.0, 1.0), (-1.0, 0.0, 0.0)]


def test_the_cell_tree_reads_planes_and_children_only() -> None:
    cs = unpack_environment(environment_record()).cells[0]
    root = cs.cell_bsp.root_node
    # BSPNODE::UnPackChild (acclient.c:363343): 'PORT' -> BSPPORTAL::UnPackPortal
    # (acclient.c:364645): plane, pos, neg; nothing more outside a drawing tree.
    assert root.type == NODE_TYPE_PORTAL
    assert _vec(root.splitting_plane.N) == (1.0, 0.0, 0.0)
    assert isinstance(root.neg_node, BSPLeaf) and root.neg_node.leaf_index == 1
    # Cell-tree nodes (type 2) store no sphere (acclient.c:363185, the pack_tree_type test).
    assert root.sphere.radius == 0.0
    tags, planes = [], []
    node = root.pos_node
    while not isinstance(node, BSPLeaf):
        assert node is not None and node.neg_node is None and not node.polys
        tags.append(node.type_string)
        planes.append((_vec(node.splitting_plane.N), node.splitting_plane.d))
        node = node.pos_node
    assert tags == ["BPIn", "BPIn", "BPIn", "BPIn", "BPnn"]
    assert planes[0] == ((-1.0, 0.0, 0.0), 6.0)
    assert planes[-1] == ((0.0, 0.0, -1.0), 3.0)
    # A cell-tree leaf is its index only (BSPLEAF::UnPackLeaf, acclient.c:364132).
    assert node.leaf_index == 0 and not node.solid and not node.polys
    # The chain bounds the room (point_inside_cell_bsp walks pos_node, acclient.c:362943).
    struct_ = unpack_environment(environment_record()).to_environment().get_cellstruct(0)
    assert struct_.point_in_cell(Vector3(3.0, 3.0, 1.0))
    assert not struct_.point_in_cell(Vector3(-0.5, 3.0, 1.0))
    assert not struct_.point_in_cell(Vector3(3.0, 3.0, 3.5))


def test_the_physics_tree_reads_spheres_and_leaf_polygons() -> None:
    cs = unpack_environment(environment_record()).cells[0]
    root = cs.physics_bsp.root_node
    # Physics nodes (type 1): plane, children, sphere (acclient.c:363185).
    assert root.type_string == "BPnN"
    assert (_vec(root.sphere.center), root.sphere.radius) == ((3.0, 3.0, 1.5), 4.5)
    east = root.pos_node
    floor_leaf = root.neg_node
    assert isinstance(east, BSPNode) and isinstance(floor_leaf, BSPLeaf)
    # Physics leaves: index, solid, sphere, polygon indices (acclient.c:364132).
    assert (floor_leaf.leaf_index, floor_leaf.solid) == (2, True)
    assert floor_leaf.sphere.radius == pytest.approx(4.3)
    assert floor_leaf.polys == [cs.physics_polygons[0]]
    inside, wall = east.pos_node, east.neg_node
    assert isinstance(inside, BSPLeaf) and isinstance(wall, BSPLeaf)
    assert (inside.leaf_index, inside.polys) == (0, [])
    assert wall.polys[0] is cs.physics_polygons[1] and not wall.solid


def test_the_drawing_tree_is_read_through_its_portal_node() -> None:
    cs = unpack_environment(environment_record()).cells[0]
    assert cs.drawing_bsp is not None
    root = cs.drawing_bsp.root_node
    # Drawing nodes (type 0): sphere, then dword count and u16 polygon indices (acclient.c:363185).
    assert root.type_string == "BPIN" and root.polys == [cs.polygons[1]]
    port = root.pos_node
    assert port is not None and port.type == NODE_TYPE_PORTAL
    # Drawing portals: sphere, polygon and portal counts, polygons (acclient.c:364645).
    assert port.sphere.radius == 4.5 and port.polys == [cs.polygons[0]]
    assert isinstance(root.neg_node, BSPLeaf) and root.neg_node.leaf_index == 2
    assert unpack_environment(environment_record(drawing=False)).cells[0].drawing_bsp is None


def test_cell_structs_follow_each_other_with_their_padding() -> None:
    # Padding to a dword after the portal ids and after the drawing tree (acclient.c:355822);
    # the second struct starts where the first one's padding ends.
    env = unpack_environment(environment_record(structs=3))
    assert len(env.cells) == 3
    first, last = env.cells[0], env.cells[2]
    assert last.poly_ids == first.poly_ids and last.portal_indices == [1]
    assert last.physics_bsp.root_node.sphere.radius == 4.5
    with pytest.raises(DatError, match="truncated"):
        unpack_environment(environment_record()[:-4])


def test_env_cell_record_fields() -> None:
    objects = [stab_bytes(0x02000010, (12.0, 22.0, 0.5))]
    portals = [cell_portal_bytes(0x6, 1, 0xFFFF, 3), cell_portal_bytes(0x1, 1, 0x0102, -1)]
    data = env_cell_record(
        CELL, (10.0, 20.0, 0.0), portals, stabs=[0x100, 0x102], objects=objects, restriction=0x70000001
    )
    rec = unpack_env_cell(data)
    # CEnvCell::UnPack (acclient.c:349133), field by field.
    assert (rec.did, rec.cell_id, rec.flags) == (CELL, CELL, 0xB)
    assert rec.seen_outside
    assert rec.surfaces == [0x08000123]
    assert (rec.environment_id, rec.cell_struct_index) == (ENVIRONMENT_ID, 0)
    assert _vec(rec.frame.origin) == (10.0, 20.0, 0.0)
    assert [(p.flags, p.poly_id, p.other_cell, p.other_portal_id) for p in rec.portals] == [
        (6, 1, 0xFFFF, 3),
        (1, 1, 0x0102, -1),
    ]
    assert rec.stab_list == [0xA9B40100, 0xA9B40102]
    assert rec.static_object_ids == [0x02000010]
    assert _vec(rec.static_object_frames[0].origin) == (12.0, 22.0, 0.5)
    assert rec.restriction_obj == 0x70000001
    bare = unpack_env_cell(env_cell_record(CELL, (0.0, 0.0, 0.0), [], seen_outside=False))
    assert (bare.flags, bare.static_object_ids, bare.restriction_obj) == (0, [], 0)


def test_make_env_cell_links_portals_by_stored_polygon_id() -> None:
    env = unpack_environment(environment_record(poly_ids=(5, 9)))
    world_env = env.to_environment()
    portals = [cell_portal_bytes(0x6, 9, 0xFFFF, 0), cell_portal_bytes(0x1, 9, 0x0102, 4)]
    cell = make_env_cell(unpack_env_cell(env_cell_record(CELL, (10.0, 20.0, 0.0), portals)), env, world_env)
    assert cell.id == CELL and cell.structure is world_env.cells[0] and cell.env is world_env
    # CCellStruct::get_portal (acclient.c:355463) matches the stored poly_id (9), not the position.
    assert cell.portals[0].portal is cell.structure.polygons[1]
    # CCellPortal::UnPack (acclient.c:362378): bit 2 outside, bit 1 clear -> side 1, bit 0 exact.
    first, second = cell.portals
    assert (first.other_cell_id, first.portal_side, first.exact_match) == (OUTSIDE_CELL_ID, 0, False)
    assert (second.other_cell_id, second.portal_side, second.exact_match) == (0xA9B40102, 1, True)
    assert second.other_portal_id == 4
    assert cell.point_in_cell(Vector3(13.0, 23.0, 1.0)) and not cell.point_in_cell(Vector3(9.0, 23.0, 1.0))
    wrong = env_cell_record(CELL, (10.0, 20.0, 0.0), [cell_portal_bytes(0x6, 1, 0xFFFF, 0)])
    with pytest.raises(DatError, match="names polygon 1"):
        make_env_cell(unpack_env_cell(wrong), env, world_env)
    far = env_cell_record(CELL, (0.0, 0.0, 0.0), [], struct_index=2)
    with pytest.raises(DatError, match="cell struct 2"):
        make_env_cell(unpack_env_cell(far), env, world_env)


def test_bad_tree_tags_and_portal_indices_are_refused() -> None:
    data = bytearray(environment_record())
    port = struct.pack("<I", type_tag("PORT"))
    data[data.index(port) : data.index(port) + 4] = struct.pack("<I", type_tag("XXXX"))
    with pytest.raises(DatError, match="is not a node tag"):
        unpack_environment(bytes(data))
    data = bytearray(environment_record())
    # The portal id u16: after the record's 8 bytes, the struct's 16, the vertex type and count,
    # 12 vertices of 28 bytes (no UVs) and the 20- and 28-byte polygons.
    offset = 8 + 16 + 8 + 12 * 28 + 20 + 28
    assert struct.unpack_from("<H", data, offset) == (1,)
    struct.pack_into("<H", data, offset, 2)
    with pytest.raises(DatError, match="portal names polygon 2 of 2"):
        unpack_environment(bytes(data))


# -- a cell DAT landblock with a building and its room -----------------------------------------

ROOM_ORIGIN = (90.0, 90.0, 0.0)
SHELL_GFXOBJ = 0x01000020
#: Land cell (3, 3) of 0xA9B4, under the building's origin (93, 93): 1 + 8 * 3 + 3.
LAND = 0xA9B4001C
WALK = """
[scenario]
name = "dat-room"
duration = 2.5
driver_hz = 60.0

[data]
portal = "client_portal.dat"
cell = "client_cell_1.dat"

[[landblock]]
id = "0xA9B4"

[setup.walker]
spheres = [{ center = [0.0, 0.0, 0.475], radius = 0.48 }, { center = [0.0, 0.0, 1.35], radius = 0.48 }]
step_up_height = 0.4
step_down_height = 0.4
motion_table = "humanoid"

[[body]]
name = "walker"
setup = "walker"
landblock = "0xA9B4"
origin = [86.0, 93.0, 0.005]
heading = 90.0
state = ["gravity", "report_collisions", "edge_slide"]
on_ground = true

[[event]]
at = 0.2
body = "walker"
action = "motion"
motion = "WalkForward"
hold_run = true
"""


@pytest.fixture
def room_dats(tmp_path: Path) -> Path:
    """Portal: the region, the room's environment, a shell GfxObj without physics data (flags 0).
    Cell: flat dry landblock 0xA9B4 at 0 m; its info (1 cell, the building at (93, 93, 0) with a
    door into 0x0100's portal 0); env cell 0x0100 at ``ROOM_ORIGIN`` whose portal 0 is the doorway,
    to the outside, with a box object (flag 2) in the room's north-east corner."""
    portal = {
        REGION_ID: region_record(),
        ENVIRONMENT_ID: environment_record(),
        SHELL_GFXOBJ: box_gfxobj_record((-3.0, -3.0, 0.0), (3.0, 3.0, 3.0), gfxobj_id=SHELL_GFXOBJ, flags=0),
        BOX_SETUP_ID: box_setup_record(),
        BOX_GFXOBJ_ID: box_gfxobj_record((-0.5, -0.5, 0.0), (0.5, 0.5, 1.0)),
    }
    simple_dat(tmp_path, portal)
    door = bld_portal_bytes(0, 0x0100, 0, [0x0100])
    cell = {
        LANDBLOCK_ID: landblock_record(terrain=[0] * 81, heights=[0] * 81),
        LANDBLOCK_INFO_ID: landblock_info_record(
            num_cells=1, buildings=[build_info_bytes(SHELL_GFXOBJ, (93.0, 93.0, 0.0), 1, [door])]
        ),
        ROOM: env_cell_record(
            ROOM,
            ROOM_ORIGIN,
            [cell_portal_bytes(0x6, 1, 0xFFFF, 0)],
            stabs=[0x0100],
            objects=[stab_bytes(BOX_SETUP_ID, (95.0, 95.0, 0.0))],
        ),
    }
    simple_dat(tmp_path, cell, name="client_cell_1.dat", data_set=CELL_DATA)
    return tmp_path


ROOM = 0xA9B40100


def test_a_cell_dat_building_loads_its_room_and_door(room_dats: Path) -> None:
    path = room_dats / "room.toml"
    path.write_text(WALK, encoding="utf-8")
    sim = acphys.load_scenario(path)
    room = sim.world.get_cell(ROOM)
    assert isinstance(room, EnvCell)
    assert _vec(room.pos.frame.origin) == ROOM_ORIGIN
    # CLandBlock::init_buildings (acclient.c:352113): the building stands in the land cell under
    # its origin, with its BldPortal into 0x0100's portal 0.
    land = sim.world.get_cell(LAND)
    assert isinstance(land, SortCell) and land.has_building()
    building = land.building
    assert building is not None and building.physics_bsp is None
    assert [(p.other_cell_id, p.other_portal_id, p.stab_list) for p in building.portals] == [
        (ROOM, 0, [ROOM])
    ]
    # CEnvCell::init_static_objects (acclient.c:347954): the box object is in the room.
    assert [obj.name for obj in room.objects] == ["0x02000010@0xA9B40100#0"]
    trace = room_dats / "walk.jsonl"
    sim.run(trace=trace)
    records = step_records(trace)
    visited: list[int] = []
    for record in records:
        cell = int(record["cell"], 16)
        x, y, _z = record["origin"]
        # The body is in the room while its sphere 0 centre (above the origin) is inside the
        # room's cell BSP, x 90..96 (CObjCell::find_cell_list, acclient.c:346960); within EPSILON
        # of a wall (a float32 origin lands there: 89.99993896) the BSP's plane test may say either.
        if min(abs(x - 90.0), abs(x - 96.0)) <= EPSILON:
            assert cell in (ROOM, LAND), record
        else:
            assert cell == (ROOM if 90.0 < x < 96.0 else LAND), record
        assert y == 93.0
        if not visited or visited[-1] != cell:
            visited.append(cell)
    assert visited == [LAND, ROOM]


def test_scenario_rooms_are_numbered_after_the_dat_cells(room_dats: Path) -> None:
    # The cell DAT gives 0xA9B4 its env cell 0x0100; a scenario [[building]] in the same landblock
    # numbers its room after it, 0x0101, instead of clashing.
    building = (
        '\n[[building]]\nlandblock = "0xA9B4"\norigin = [40.0, 40.0, 0.0]\n'
        'rooms = [{ name = "hut", min = [-2.0, -2.0, 0.0], max = [2.0, 2.0, 3.0] }]\n'
        'doorways = [{ between = ["hut", "outside"], min = [-0.5, -2.0, 0.0], max = [0.5, -2.0, 2.0] }]\n'
    )
    path = room_dats / "both.toml"
    path.write_text(WALK + building, encoding="utf-8")
    sim = acphys.load_scenario(path)
    assert isinstance(sim.world.get_cell(ROOM), EnvCell)
    hut = sim.world.get_cell(ROOM + 1)
    assert isinstance(hut, EnvCell)
    assert hut.pos.frame.origin.x < 50.0


def test_a_body_starting_in_a_dat_room_starts_in_its_cell(room_dats: Path) -> None:
    # The loader places a body in the room holding its origin (CEnvCell::point_in_cell), DAT rooms
    # included, before enter_world's placement (CPhysicsObj::enter_world, acclient.c:323440).
    path = room_dats / "inside.toml"
    path.write_text(
        WALK.replace("origin = [86.0, 93.0, 0.005]", "origin = [92.0, 93.0, 0.005]"), encoding="utf-8"
    )
    sim = acphys.load_scenario(path)
    assert sim.body("walker").position.objcell_id == ROOM
