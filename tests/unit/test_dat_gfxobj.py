"""``CGfxObj`` records: vertex array, physics polygons and physics BSP as ``CGfxObj::Serialize``
reads them (acclient.c:356682), from a box GfxObj written by ``tests/dat_support.py``; and a DAT
box object that a walking body stops against."""

from __future__ import annotations

import math
import struct
from pathlib import Path

import pytest

import acphys
from acphys.dat import DatError, DatFile, unpack_setup
from acphys.dat.gfxobj import _compressed_u32, setup_physics_bsp, unpack_gfxobj
from acphys.dat.records import Reader
from acphys.geometry.bsp import NODE_TYPE_BOTH_CHILDREN, BSPLeaf, BSPNode
from acphys.geometry.bsp_builder import build_box_tree
from acphys.geometry.sphere import Sphere
from acphys.math.vector import Vector3
from dat_support import (
    BOX_GFXOBJ_ID,
    BOX_SETUP_ID,
    SETUP_ID,
    box_corner,
    box_gfxobj_record,
    box_setup_record,
    compressed_u32,
    setup_record,
    simple_dat,
)
from support import walk_tolerance

LO = (-1.0, -0.5, 0.0)
HI = (1.0, 0.5, 2.0)


def _chain(root: BSPNode) -> tuple[list[BSPNode], BSPLeaf]:
    nodes = []
    node = root
    while not isinstance(node, BSPLeaf):
        nodes.append(node)
        assert node.neg_node is not None
        node = node.neg_node
    return nodes, node


def test_compressed_counts_take_one_two_or_four_bytes() -> None:
    # SB_As32Bit_Compressed::Serialize (acclient.c:489675): < 0x80 one byte; 0x80 flag with the
    # high byte; 0xC0 flag, bits 16-29 in two bytes, then a u16 of the low bits.
    for value, size in ((0x7F, 1), (0x80, 2), (0x3FFF, 2), (0x4000, 4), (0x3FFFFFFF, 4)):
        data = compressed_u32(value) + b"\xaa"
        reader = Reader(data, "test")
        assert _compressed_u32(reader) == value
        assert reader.pos == size
    assert _compressed_u32(Reader(bytes([0x81, 0x02]), "t")) == 0x102
    assert _compressed_u32(Reader(bytes([0xC1, 0x02, 0x04, 0x03]), "t")) == 0x01020304


def test_box_gfxobj_reads_vertices_polygons_and_bsp() -> None:
    record = unpack_gfxobj(box_gfxobj_record(LO, HI))
    assert record.did == BOX_GFXOBJ_ID and record.flags == 3
    assert record.surfaces == [0x08000001]
    # CSWVertex::UnPack (acclient.c:364860): position after id and UV count; normal, UVs skipped.
    assert [(v.x, v.y, v.z) for v in record.vertices] == [box_corner(i, LO, HI) for i in range(8)]
    assert record.physics_poly_ids == [0, 1, 2, 3, 4, 5]
    # CPolygon::UnPack (acclient.c:359808) ends in make_plane: outward unit normals, d = -N.v.
    planes = [(p.plane.N.x, p.plane.N.y, p.plane.N.z, p.plane.d) for p in record.physics_polygons]
    assert planes == [
        (1.0, 0.0, 0.0, -1.0),
        (-1.0, 0.0, 0.0, -1.0),
        (0.0, 1.0, 0.0, -0.5),
        (0.0, -1.0, 0.0, -0.5),
        (0.0, 0.0, 1.0, -2.0),
        (0.0, 0.0, -1.0, 0.0),
    ]
    assert (record.sort_center.x, record.sort_center.y, record.sort_center.z) == (0.0, 0.0, 1.0)
    box = record.gfx_bound_box  # CGfxObj::init_end (acclient.c:356199)
    assert (box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z) == (*LO, *HI)
    assert record.physics_bsp is not None
    nodes, solid = _chain(record.physics_bsp.root_node)
    # BSPNODE::UnPack (acclient.c:363185): BPnN reads pos then neg; a physics node reads its sphere
    # last and no polygons. BSPLEAF::UnPackLeaf (acclient.c:364132): index, solid, sphere, polys.
    assert len(nodes) == 6 and all(n.type == NODE_TYPE_BOTH_CHILDREN and not n.polys for n in nodes)
    assert [n.splitting_plane.d for n in nodes] == [-1.0, -1.0, -0.5, -0.5, -2.0, 0.0]
    empties = [n.pos_node for n in nodes]
    assert all(isinstance(e, BSPLeaf) and not e.solid and not e.polys for e in empties)
    assert [e.leaf_index for e in empties if isinstance(e, BSPLeaf)] == [0, 1, 2, 3, 4, 5]
    assert solid.solid and solid.leaf_index == 6
    assert solid.polys == record.physics_polygons  # the same objects, by index
    assert record.physics_sphere is record.physics_bsp.root_node.sphere  # BSPTREE::GetSphere
    assert math.isclose(nodes[0].sphere.radius, math.sqrt(4 + 1 + 4) / 2, rel_tol=1e-6)


def test_dat_box_answers_like_the_built_box() -> None:
    read = unpack_gfxobj(box_gfxobj_record(LO, HI)).physics_bsp
    built = build_box_tree(Vector3(*LO), Vector3(*HI))
    assert read is not None
    points = [Vector3(x / 4, y / 4, z / 4) for x in range(-6, 7) for y in range(-4, 5) for z in range(-2, 11)]
    inside = 0
    for p in points:
        answer = read.root_node.point_intersects_solid(p)
        assert answer == built.root_node.point_intersects_solid(p), p
        inside += answer
        for radius, center_check in ((0.3, True), (0.3, False), (0.05, False)):
            sphere = Sphere(p, radius)
            assert read.root_node.sphere_intersects_solid(
                sphere, center_check
            ) == built.root_node.sphere_intersects_solid(sphere, center_check), (p, radius)
    # A point on a face plane goes positive (BSPNODE::point_intersects_solid, acclient.c:363025):
    # the solid is the open box, 7 x 3 x 7 lattice points strictly inside.
    assert inside == 7 * 3 * 7


def test_damaged_gfxobjs_are_refused() -> None:
    good = box_gfxobj_record(LO, HI)
    with pytest.raises(DatError, match="truncated"):
        unpack_gfxobj(good[:-30])
    # CVertexArray::UnPack (acclient.c:362801) reads vertices only of type 1.
    with pytest.raises(DatError, match="vertex type 2"):
        unpack_gfxobj(box_gfxobj_record(LO, HI, vertex_type=2))
    with pytest.raises(DatError, match=r"names polygon 9 .* past the 6 physics polygons"):
        unpack_gfxobj(box_gfxobj_record(LO, HI, bad_poly_ref=True))
    # The root's tag is not a physics node tag.
    tag_at = good.index(struct.pack("<I", 0x42506E4E))
    bad_tag = good[:tag_at] + b"XXXX" + good[tag_at + 4 :]
    with pytest.raises(DatError, match="is not a physics node tag"):
        unpack_gfxobj(bad_tag)
    no_physics = unpack_gfxobj(box_gfxobj_record(LO, HI, flags=0x2))
    assert no_physics.physics_bsp is None and no_physics.physics_polygons == []


def test_setup_physics_bsp_reads_part_zero(tmp_path: Path) -> None:
    records = {
        BOX_SETUP_ID: box_setup_record(),
        BOX_GFXOBJ_ID: box_gfxobj_record(LO, HI),
        0x02000011: box_setup_record(0x02000011, parts=(BOX_GFXOBJ_ID, BOX_GFXOBJ_ID)),
        0x02000012: box_setup_record(0x02000012, parts=(0x01000099,)),
        SETUP_ID: setup_record(),
    }
    with DatFile(simple_dat(tmp_path, records)) as dat:
        record = unpack_setup(dat.read(BOX_SETUP_ID))
        bsp = setup_physics_bsp(record, dat)
        assert bsp is not None
        setup = record.to_setup(physics_bsp=bsp)
        assert setup.has_physics_bsp and setup.physics_bsp is bsp
        assert setup_physics_bsp(unpack_setup(dat.read(SETUP_ID)), dat) is None  # flag 8 clear
        with pytest.raises(DatError, match="has a physics BSP and 2 parts"):
            setup_physics_bsp(unpack_setup(dat.read(0x02000011)), dat)
        with pytest.raises(DatError, match="no gfxobj 0x01000099"):
            setup_physics_bsp(unpack_setup(dat.read(0x02000012)), dat)


SCENARIO = """
[data]
portal = "client_portal.dat"

[scenario]
name = "dat-wall"
duration = 3.0
driver_hz = 60.0

[[landblock]]
id = "0xA9B4"
height = 50.0

[[object]]
name = "wall"
setup = "0x02000010"
landblock = "0xA9B4"
origin = [96.0, 100.0, 50.0]

[[body]]
name = "walker"
landblock = "0xA9B4"
origin = [84.0, 96.0, 50.0]
state = ["gravity", "report_collisions", "edge_slide"]
on_ground = true

[[event]]
at = 0.0
body = "walker"
action = "motion"
motion = "WalkForward"
"""


def test_body_walking_into_a_dat_box_stops_like_ladder_rung_3(tmp_path: Path) -> None:
    # The ladder-03-wall box (40 x 0.5 x 2.5 m, south face y = 99.75), now a DAT GfxObj; the
    # human is the portal's 0x02000001 with step-up 0 like the built-in one.
    records = {
        BOX_SETUP_ID: box_setup_record(),
        BOX_GFXOBJ_ID: box_gfxobj_record((-20.0, -0.25, 0.0), (20.0, 0.25, 2.5)),
        SETUP_ID: setup_record(steps=(0.0, 0.0)),
    }
    simple_dat(tmp_path, records)
    path = tmp_path / "wall.toml"
    path.write_text(SCENARIO, encoding="utf-8")
    sim = acphys.load_scenario(path)
    sim.run()
    origin = sim.body("walker").position.frame.origin
    # tests/ladder/test_03_wall.py: one 0.104 m sub-step a step; the step reaching the face fails
    # its step-up (BSPTREE::step_sphere_up, acclient.c:361071) and is rolled back
    # (CTransition::validate_transition, acclient.c:312193): 31 steps, 96 + 31 x 0.104.
    assert abs(origin.y - (96.0 + 31 * 3.12 / 30.0)) < walk_tolerance(99.0, 31)  # float32 stores
    assert origin.x == 84.0
