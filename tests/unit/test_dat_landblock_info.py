"""``CLandBlockInfo`` records (0xXXYYFFFE): static objects, buildings with their portals, the
restriction table; and placing the static objects (``CLandBlock::init_static_objs``), directly
and through a scenario's ``[[landblock]]`` with only ``id``.

Records are written by ``tests/dat_support.py`` from the layout CLandBlockInfo::UnPack reads
(acclient.c:351048); expected values are derived from that routine by hand.
"""

from __future__ import annotations

import math
import struct
from pathlib import Path

import pytest

import acphys
from acphys.dat.container import DatError
from acphys.dat.landblock_info import init_static_objs, unpack_landblock_info
from acphys.flags import PhysicsState
from acphys.geometry.sphere import Sphere
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.vector import Vector3
from acphys.setup import Setup
from acphys.world.landblock import LandBlock
from acphys.world.terrain import LandBlockStruct
from acphys.world.world import World
from dat_support import (
    BOX_GFXOBJ_ID,
    BOX_SETUP_ID,
    CELL,
    LANDBLOCK_ID,
    LANDBLOCK_INFO_ID,
    REGION_ID,
    SETUP_ID,
    bld_portal_bytes,
    box_gfxobj_record,
    box_setup_record,
    build_info_bytes,
    f32,
    landblock_info_record,
    landblock_record,
    region_record,
    setup_record,
    simple_dat,
    stab_bytes,
)

#: A quarter turn about z: qw = qz = sqrt(1/2).
QUARTER = (math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5))


def full_record() -> bytes:
    """Two objects, one building with two portals, a two-entry restriction table."""
    portals = [
        bld_portal_bytes(0x1, 0x0105, -1, [0x0100, 0x0101, 0x0102]),  # odd: 2 bytes of padding
        bld_portal_bytes(0x2, 0x0107, 3, [0x0107, 0x0108]),
    ]
    return landblock_info_record(
        num_cells=9,
        objects=[
            stab_bytes(0x02000010, (10.0, 20.5, 3.0)),
            stab_bytes(0x01000010, (100.0, 50.0, 0.0), QUARTER),
        ],
        buildings=[build_info_bytes(0x01001234, (96.0, 96.0, 12.0), 4, portals)],
        restrictions=[(0xA9B40011, 0x7A000001), (0xA9B40012, 0x7A000002)],
    )


def test_objects_buildings_and_portals_unpack_in_retail_order() -> None:
    info = unpack_landblock_info(full_record())
    assert info.did == LANDBLOCK_INFO_ID and info.num_cells == 9  # first dword (acclient.c:351088)
    assert info.object_ids == [0x02000010, 0x01000010]  # id then frame each (acclient.c:351137)
    second = info.object_frames[1]
    assert (second.origin.x, second.origin.y, second.origin.z) == (100.0, 50.0, 0.0)
    assert (second.qw, second.qz) == (f32(math.sqrt(0.5)), f32(math.sqrt(0.5)))
    assert info.object_frames[0].origin.y == 20.5
    (building,) = info.buildings
    assert building.building_id == 0x01001234 and building.num_leaves == 4  # acclient.c:351184
    assert building.frame.origin.z == 12.0
    first, other = building.portals
    # Cell numbers get the block's high word (acclient.c:362520, 362537).
    assert first.other_cell_id == 0xA9B40105
    assert first.stab_list == [0xA9B40100, 0xA9B40101, 0xA9B40102]
    # other_portal_id is a sign-extended 16-bit read (acclient.c:362523).
    assert first.other_portal_id == -1 and other.other_portal_id == 3
    # exact_match = flags bit 0; portal_side = bit 1 clear (acclient.c:362516-362517).
    assert (first.exact_match, first.portal_side) == (True, True)
    assert (other.exact_match, other.portal_side) == (False, False)
    # The odd stab count's padding was skipped (acclient.c:362541): the second portal read right.
    assert other.other_cell_id == 0xA9B40107 and other.stab_list == [0xA9B40107, 0xA9B40108]
    assert info.pack_mask == 1  # high word of the building dword (acclient.c:351148)
    assert info.restriction_table == {0xA9B40011: 0x7A000001, 0xA9B40012: 0x7A000002}
    assert info.get_restriction_iid(0xA9B40012) == 0x7A000002
    assert info.get_restriction_iid(0xA9B40013) == 0  # not in the table (acclient.c:351249)


def test_no_restriction_table_without_pack_mask_bit_0() -> None:
    info = unpack_landblock_info(landblock_info_record(objects=[stab_bytes(0x02000010, (1.0, 2.0, 3.0))]))
    assert info.restriction_table is None and info.buildings == []  # acclient.c:351216
    assert info.get_restriction_iid(0xA9B40001) == 0


def test_empty_restriction_table_with_no_buckets_is_accepted() -> None:
    # table size 0 returns "count == 0" (acclient.c:297974): empty is fine.
    info = unpack_landblock_info(landblock_info_record(restrictions=[], buckets=0))
    assert info.restriction_table == {}


def test_bad_records_raise() -> None:
    with pytest.raises(DatError, match="ends in 0xFFFE"):
        unpack_landblock_info(landblock_info_record(info_id=0xA9B4FFFF))
    # A count with table size 0 fails the unpack (acclient.c:297974).
    with pytest.raises(DatError, match="1 entries and 0 buckets"):
        unpack_landblock_info(landblock_info_record(restrictions=[(0xA9B40001, 5)], buckets=0))
    # A repeated key fails ``add`` with m_fThrowawayDuplicateKeysOnUnPack 0 (acclient.c:297997).
    with pytest.raises(DatError, match="twice"):
        unpack_landblock_info(landblock_info_record(restrictions=[(0xA9B40001, 5), (0xA9B40001, 6)]))
    with pytest.raises(DatError, match="truncated"):
        unpack_landblock_info(full_record()[:-21])  # into the last portal
    with pytest.raises(DatError, match="object count"):
        unpack_landblock_info(struct.pack("<III", LANDBLOCK_INFO_ID, 0, 1000))


def _world() -> tuple[World, LandBlock]:
    world = World()
    block = LandBlock(LandBlockStruct(LANDBLOCK_ID, [0] * 81, [0] * 81, [0.0] * 256))
    world.add_landblock(block)
    return world, block


def test_init_static_objs_places_objects_in_the_land_cell_under_their_origin() -> None:
    world, block = _world()
    setups = {
        0x02000010: Setup("pillar", spheres=[Sphere(Vector3(0.0, 0.0, 1.0), 0.5)]),
        0x02000011: Setup("post", spheres=[Sphere(Vector3(0.0, 0.0, 1.0), 0.25)]),
    }
    info = unpack_landblock_info(
        landblock_info_record(
            objects=[
                stab_bytes(0x02000010, (30.0, 40.0, 0.0)),
                stab_bytes(0x03000001, (50.0, 50.0, 0.0)),  # makeObject makes nothing: dropped
                stab_bytes(0x02000011, (200.0, 10.0, 0.0)),  # next block's cell: dropped
                stab_bytes(0x02000011, (191.5, 0.0, 0.0), QUARTER),
            ]
        )
    )
    placed = init_static_objs(world, block, info, setups.get)
    # acclient.c:352841 (makeObject), 352851-352852 (adjust_to_outside, get_landcell of this
    # block), 352860 (an object in no cell of the block is deleted).
    assert [obj.name for obj in placed] == ["0x02000010@0xA9B4000A#0", "0x02000011@0xA9B40039#3"]
    pillar, post = placed
    # (30, 40) is cell x 1, y 1: 1 + 8*1 + 1 = 0x0A; (191.5, 0) is x 7, y 0: 1 + 56 = 0x39.
    assert pillar.position.objcell_id == 0xA9B4000A
    assert pillar in world.get_cell(0xA9B4000A).objects
    assert post.position.frame.qz == f32(math.sqrt(0.5))  # the stored frame, rotation kept
    assert pillar.state & PhysicsState.STATIC and not pillar.state & PhysicsState.HAS_PHYSICS_BSP
    with pytest.raises(ValueError, match="not the info of landblock"):
        init_static_objs(world, block, unpack_landblock_info(landblock_info_record(0xA9B5FFFE)), setups.get)


# -- scenario ---------------------------------------------------------------------------------

BODY = '[[body]]\nname = "a"\nlandblock = "0xA9B4"\norigin = [96.0, 96.0, 50.0]\n'
DATA = '[data]\nportal = "client_portal.dat"\ncell = "client_cell_1.dat"\n[[landblock]]\nid = "0xA9B4"\n'


def _dats(folder: Path, info: bytes | None, lbi_exists: int = 1) -> None:
    portal = {
        SETUP_ID: setup_record(),
        REGION_ID: region_record(),
        BOX_SETUP_ID: box_setup_record(),
        BOX_GFXOBJ_ID: box_gfxobj_record((-1.0, -2.0, 0.0), (1.0, 2.0, 4.0)),
    }
    simple_dat(folder, portal)
    cell = {LANDBLOCK_ID: landblock_record(lbi_exists=lbi_exists)}
    if info is not None:
        cell[LANDBLOCK_INFO_ID] = info
    simple_dat(folder, cell, name="client_cell_1.dat", data_set=CELL)


def _load(folder: Path) -> acphys.Simulation:
    path = folder / "world.toml"
    path.write_text(DATA + BODY, encoding="utf-8")
    return acphys.load_scenario(path)


def test_a_dat_landblock_loads_its_static_objects(tmp_path: Path) -> None:
    info = landblock_info_record(
        objects=[stab_bytes(BOX_SETUP_ID, (30.0, 40.0, 0.0)), stab_bytes(BOX_GFXOBJ_ID, (100.0, 50.0, 0.0))]
    )
    _dats(tmp_path, info)
    world = _load(tmp_path).world
    (box,) = world.get_cell(outdoor_cell_id(0xA9B4, Vector3(30.0, 40.0, 0.0))).objects
    assert box.name == "0x02000010@0xA9B4000A#0"
    assert box.state & PhysicsState.HAS_PHYSICS_BSP  # the setup's part has a physics BSP
    (mesh,) = world.get_cell(outdoor_cell_id(0xA9B4, Vector3(100.0, 50.0, 0.0))).objects
    # A GfxObj id makes a one-part setup (InitPartArrayObject acclient.c:319659-319661) whose
    # sorting sphere is the GfxObj's physics sphere (makeSimpleSetup acclient.c:334504-334507):
    # the box's root sphere, centre (0, 0, 2), radius half the diagonal sqrt(4 + 16 + 16) / 2 = 3.
    setup = mesh.part_array.setup
    assert setup.name == "0x01000010" and setup.physics_bsp is not None
    assert mesh.state & PhysicsState.HAS_PHYSICS_BSP
    assert setup.sorting_sphere.center.z == 2.0 and setup.sorting_sphere.radius == 3.0
    assert setup.spheres == [] and setup.cylspheres == []


def test_no_objects_when_the_landblock_says_there_is_no_info(tmp_path: Path) -> None:
    # lbi_exists 0: CLandBlock::InitLoad reads no 0xXXYYFFFE record (acclient.c:352062).
    _dats(
        tmp_path, landblock_info_record(objects=[stab_bytes(BOX_SETUP_ID, (30.0, 40.0, 0.0))]), lbi_exists=0
    )
    world = _load(tmp_path).world
    assert world.get_cell(outdoor_cell_id(0xA9B4, Vector3(30.0, 40.0, 0.0))).objects == []


def test_object_problems_are_scenario_errors(tmp_path: Path) -> None:
    # A zero high byte is an anim object (InitPartArrayObject acclient.c:319667), not made here.
    _dats(tmp_path, landblock_info_record(objects=[stab_bytes(0x00000010, (30.0, 40.0, 0.0))]))
    with pytest.raises(acphys.ScenarioError, match=r"landblock\[0\].id: static object 0x00000010 is an anim"):
        _load(tmp_path)
    _dats(tmp_path, landblock_info_record(objects=[stab_bytes(0x02000099, (30.0, 40.0, 0.0))]))
    with pytest.raises(acphys.ScenarioError, match="no setup 0x02000099"):
        _load(tmp_path)
    _dats(tmp_path, landblock_info_record(restrictions=[(1, 2), (1, 3)]))
    with pytest.raises(acphys.ScenarioError, match="restriction table names cell 0x00000001 twice"):
        _load(tmp_path)
