"""Retail ``CGfxObj`` records (0x01xxxxxx): the vertex array, the physics polygons, the physics BSP
and the sort centre, as ``CGfxObj::Serialize`` reads them; and the physics BSP of a one-part DAT
setup, or the part descriptions of a many-part one.

Record layout (little-endian, no padding anywhere up to the sort centre):

- DID (``DBObj::Serialize``), a flags dword (1 physics data, 2 drawing data, 8 degrade id);
- surface count (``SB_As32Bit_Compressed``: one byte below 0x80; ``0x80 | hi, lo`` below
  0x4000; else ``0xC0 | b3, b2`` and a u16 of the low bits), then one dword surface id each
  (``SB_AsDataID``'s ``CheckAlignment`` only pads in aligned archives; DAT archives are not
  aligned, which ACE's reader of the real files agrees with);
- the vertex array; with flag 1 the physics polygons (compressed count) and the physics BSP;
- the sort centre (3 floats); with flag 2 the drawing polygons and drawing BSP; with flag 8 the
  degrade id. acphys stops after the sort centre: the drawing data is for rendering only.

Polygon vertex ids and BSP polygon ids index the arrays by position (``vertices[id]``,
``pack_poly[id]``), not by the ids stored with each vertex or polygon.
"""

from __future__ import annotations

from dataclasses import dataclass

from acphys.dat.container import DatError, DatFile
from acphys.dat.records import Reader, SetupRecord
from acphys.geometry.bbox import BBox
from acphys.geometry.bsp import NODE_TYPE_LEAF, NODE_TYPE_PORTAL, BSPLeaf, BSPNode, BSPPolygon, BSPTree
from acphys.geometry.bsp import type_tag as _tag
from acphys.geometry.plane import Plane
from acphys.geometry.polygon import Polygon, SidesType
from acphys.geometry.sphere import Sphere
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.part_array import DEFAULT_PLACEMENT_ID
from acphys.setup import SetupPart

#: ``CGfxObj`` flag bits (the dword after the DID).
GFXOBJ_HAS_PHYSICS = 0x1
GFXOBJ_HAS_DRAWING = 0x2
GFXOBJ_HAS_DEGRADE = 0x8
#: The id high byte of GfxObj records.
GFXOBJ_ID_TYPE = 0x01
#: ``CVertexArray::vertex_type`` of software vertices, the only kind ``UnPack`` reads.
VERTEX_TYPE_SW = 1
#: ``CPolygon::stippling`` bits: no positive / negative UV indices stored.
STIPPLING_NO_POS_UVS = 0x4
STIPPLING_NO_NEG_UVS = 0x8
#: Interior tags and the children ``BSPNODE::UnPack`` reads for each (pos, neg).
NODE_CHILDREN: dict[int, tuple[bool, bool]] = {
    _tag("BPIN"): (True, True),
    _tag("BPnN"): (True, True),
    _tag("BPIn"): (True, False),
    _tag("BPnn"): (True, False),
    _tag("BpIN"): (False, True),
    _tag("BpnN"): (False, True),
}


@dataclass
class GfxObjRecord:
    """The physics side of a ``CGfxObj`` record (acclient.h ``CGfxObj``)."""

    did: int
    flags: int
    #: ``m_rgSurfaces`` as their surface ids (0 for ``AnID``, retail's "no surface").
    surfaces: list[int]
    #: ``vertex_array``: the positions, by array index (normals and UVs are drawing data).
    vertices: list[Vector3]
    #: ``physics_polygons`` in stored order (their stored ``poly_id``s are in ``physics_poly_ids``).
    physics_polygons: list[Polygon]
    physics_poly_ids: list[int]
    physics_bsp: BSPTree | None
    sort_center: Vector3
    #: ``gfx_bound_box``: the box around the vertex positions (``CGfxObj::init_end``).
    gfx_bound_box: BBox

    @property
    def physics_sphere(self) -> Sphere | None:
        """``physics_sphere``: the physics BSP's root sphere (``BSPTREE::GetSphere``)."""
        return self.physics_bsp.get_sphere() if self.physics_bsp is not None else None


def _compressed_u32(reader: Reader) -> int:
    """Retail: SB_As32Bit_Compressed::Serialize @ 0x005BE430 (acclient.c:489675)"""
    first = reader.take(1)[0]
    if not first & 0x80:
        return first
    second = reader.take(1)[0]
    if not first & 0x40:
        return (first & 0x7F) << 8 | second
    low = int(reader.unpack("H")[0])
    return ((first & 0x3F) << 8 | second) << 16 | low


def read_vertex_array(reader: Reader) -> list[Vector3]:
    """The vertex type, a count, then per vertex: u16 id, u16 UV count, position, normal, UVs.

    Retail: CVertexArray::UnPack @ 0x0053C030 (acclient.c:362801)
    """
    vertex_type = reader.u32()
    if vertex_type != VERTEX_TYPE_SW:
        raise DatError(f"{reader.what}: vertex type {vertex_type}; retail reads only type 1 vertices")
    positions = []
    for _ in range(reader.count(28, "vertex")):
        positions.append(_sw_vertex(reader))
    return positions


def _sw_vertex(reader: Reader) -> Vector3:
    """One vertex; the position is kept, the stored id, normal and UVs are skipped.

    Retail: CSWVertex::UnPack @ 0x0053DE50 (acclient.c:364860)
    """
    _vert_id, num_uvs = reader.unpack("2H")
    position = reader.vector()
    reader.take(12 + 8 * int(num_uvs))
    return position


def read_polygon(reader: Reader, vertices: list[Vector3]) -> tuple[int, Polygon]:
    """u16 poly id, u8 point count, u8 stippling, i32 sides type, u16 pos / neg surface, u16
    vertex ids, then (unless stippling 4) pos UV indices and (sides type 2, unless stippling 8)
    neg UV indices, a byte a point. The plane comes from ``make_plane`` (:class:`Polygon`).

    Retail: CPolygon::UnPack @ 0x00538650 (acclient.c:359808)
    """
    start = reader.pos
    poly_id, num_pts, stippling, sides_type, _pos_surface, _neg_surface = reader.unpack("HBBi2H")
    ids = reader.unpack(f"{num_pts}H")
    if not stippling & STIPPLING_NO_POS_UVS:
        reader.take(num_pts)
    if sides_type == SidesType.BOTH and not stippling & STIPPLING_NO_NEG_UVS:
        reader.take(num_pts)
    where = f"{reader.what}: polygon {poly_id} at byte {start}"
    if sides_type not in (SidesType.SINGLE, SidesType.DOUBLE, SidesType.BOTH):
        raise DatError(f"{where}: sides type {sides_type} is not 0, 1 or 2")
    bad = [i for i in ids if i >= len(vertices)]
    if bad:
        raise DatError(f"{where}: vertex id {bad[0]} is past the {len(vertices)} vertices")
    try:
        polygon = Polygon([vertices[int(i)] for i in ids], int(sides_type))
    except ValueError as error:
        raise DatError(f"{where}: {error}") from None
    return int(poly_id), polygon


def read_poly_refs(reader: Reader, polygons: list[Polygon], what: str) -> list[BSPPolygon]:
    """A dword count and that many u16 indices into the physics polygons."""
    refs: list[BSPPolygon] = []
    for _ in range(reader.count(2, f"{what} polygon")):
        index = int(reader.unpack("H")[0])
        if index >= len(polygons):
            raise DatError(
                f"{reader.what}: {what} names polygon {index} at byte {reader.pos - 2}, past the "
                f"{len(polygons)} physics polygons"
            )
        refs.append(polygons[index])
    return refs


def read_leaf(reader: Reader, polygons: list[Polygon]) -> BSPLeaf:
    """A physics leaf after its tag: i32 leaf index, dword solid, sphere, polygon ids.

    Retail: BSPLEAF::UnPackLeaf @ 0x0053D4A0 (acclient.c:364132)
    """
    leaf_index = int(reader.unpack("i")[0])
    solid = reader.u32()
    sphere = reader.sphere()
    polys = read_poly_refs(reader, polygons, f"leaf {leaf_index}")
    return BSPLeaf(leaf_index, bool(solid), sphere, polys)


def _node(reader: Reader, polygons: list[Polygon], tag: int) -> BSPNode:
    """A physics interior node after its tag: plane (normal, d), the children its tag names
    (pos first), then its sphere; physics nodes store no polygons.

    Retail: BSPNODE::UnPack @ 0x0053C540 (acclient.c:363185)
    """
    children = NODE_CHILDREN.get(tag)
    if children is None:
        name = tag.to_bytes(4, "big").decode("ascii", errors="replace")
        raise DatError(
            f"{reader.what}: BSP node tag {name!r} ({tag:#010x}) at byte {reader.pos - 4} is not a "
            "physics node tag (BPIN, BPnN, BPIn, BPnn, BpIN, BpnN, LEAF)"
        )
    normal = reader.vector()
    plane = Plane(normal, reader.coordinate())
    pos = _child(reader, polygons) if children[0] else None
    neg = _child(reader, polygons) if children[1] else None
    return BSPNode(plane, pos, neg, reader.sphere(), type=tag)


def _child(reader: Reader, polygons: list[Polygon]) -> BSPNode:
    """A tag dword, then a leaf or an interior node (a portal has no place in a physics tree).

    Retail: BSPNODE::UnPackChild @ 0x0053C770 (acclient.c:363343)
    """
    tag = reader.u32()
    if tag == NODE_TYPE_LEAF:
        return read_leaf(reader, polygons)
    if tag == NODE_TYPE_PORTAL:
        raise DatError(f"{reader.what}: a PORT node at byte {reader.pos - 4} in the physics BSP")
    return _node(reader, polygons, tag)


def _physics_bsp(reader: Reader, polygons: list[Polygon]) -> BSPTree:
    """The tree is its root child.

    Retail: BSPTREE::UnPack @ 0x00539830 (acclient.c:360685)
    """
    try:
        return BSPTree(_child(reader, polygons))
    except RecursionError:
        raise DatError(f"{reader.what}: the physics BSP nests too deep to read") from None


def unpack_gfxobj(data: bytes) -> GfxObjRecord:
    """Parse a ``CGfxObj`` record up to its sort centre (see the module docstring).

    Retail: CGfxObj::Serialize @ 0x00534970 (acclient.c:356682)
    """
    reader = Reader(data, "gfxobj")
    did = reader.u32()
    reader.what = f"gfxobj {did:#010x}"
    flags = reader.u32()
    num_surfaces = _compressed_u32(reader)
    if num_surfaces * 4 > len(data) - reader.pos:
        raise DatError(f"{reader.what}: surface count {num_surfaces} overruns the record")
    surfaces = [reader.u32() for _ in range(num_surfaces)]
    vertices = read_vertex_array(reader)
    polygons: list[Polygon] = []
    poly_ids: list[int] = []
    bsp = None
    if flags & GFXOBJ_HAS_PHYSICS:
        num_polys = _compressed_u32(reader)
        if num_polys * 12 > len(data) - reader.pos:
            raise DatError(f"{reader.what}: physics polygon count {num_polys} overruns the record")
        for _ in range(num_polys):
            poly_id, polygon = read_polygon(reader, vertices)
            poly_ids.append(poly_id)
            polygons.append(polygon)
        bsp = _physics_bsp(reader, polygons)
    sort_center = reader.vector()
    return GfxObjRecord(
        did, flags, surfaces, vertices, polygons, poly_ids, bsp, sort_center, BBox.around(vertices)
    )


def _is_identity(frame_values: tuple[float, ...]) -> bool:
    return frame_values == (0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0)


def setup_physics_bsp(record: SetupRecord, dat: DatFile) -> BSPTree | None:
    """The physics BSP of ``record``'s part 0 GfxObj, read from ``dat``; None without flag 8.

    acphys places a setup's BSP in the body's frame, unscaled, so only one-part setups whose
    part has no default scale and identity placement frames are read; others raise DatError.
    """
    if not record.has_physics_bsp:
        return None
    what = f"setup {record.did:#010x}"
    if len(record.parts) != 1:
        raise DatError(
            f"{what} has a physics BSP and {len(record.parts)} parts; acphys reads the physics BSP "
            "of one-part setups only"
        )
    for scale in record.default_scale:
        if (scale.x, scale.y, scale.z) != (1.0, 1.0, 1.0):
            raise DatError(f"{what} has a physics BSP and part default scale {scale!r}; acphys reads 1 only")
    for key, frames in record.placement_frames.items():
        f = frames[0]
        if not _is_identity((f.origin.x, f.origin.y, f.origin.z, f.qw, f.qx, f.qy, f.qz)):
            raise DatError(
                f"{what} has a physics BSP and placement frame {key} moves its part; acphys reads "
                "identity part frames only"
            )
    gfx_id = record.parts[0]
    gfxobj = _part_gfxobj(what, 0, gfx_id, dat)
    if gfxobj.physics_bsp is None:
        raise DatError(f"{what} has a physics BSP flag but its gfxobj {gfx_id:#010x} has no physics data")
    return gfxobj.physics_bsp


def _part_gfxobj(what: str, index: int, gfx_id: int, dat: DatFile) -> GfxObjRecord:
    """Part ``index``'s GfxObj record ``gfx_id``, read from ``dat``."""
    if gfx_id >> 24 != GFXOBJ_ID_TYPE:
        raise DatError(f"{what}: part {index} is {gfx_id:#010x}, not a GfxObj (0x01xxxxxx)")
    if dat.lookup(gfx_id) is None:
        raise DatError(f"{what}: no gfxobj {gfx_id:#010x} in {dat.path}")
    gfxobj = unpack_gfxobj(dat.read(gfx_id))
    if gfxobj.did != gfx_id:
        raise DatError(f"record {gfx_id:#010x} holds gfxobj {gfxobj.did:#010x}")
    return gfxobj


def default_placement(record: SetupRecord) -> tuple[int, list[Frame]] | None:
    """The placement ``CPartArray::SetPlacementFrame(0x65)`` picks: 0x65 if the setup has it, else
    placement 0, else none (retail then leaves the parts unplaced).

    Retail: CPartArray::SetPlacementFrame @ 0x005193D0 (acclient.c:326817)
    """
    for key in (DEFAULT_PLACEMENT_ID, 0):
        frames = record.placement_frames.get(key)
        if frames is not None:
            return key, frames
    return None


def needs_setup_parts(record: SetupRecord) -> bool:
    """Whether ``record`` needs :func:`setup_parts`: it has a physics BSP and more than one part, a
    part default scale other than 1, or a placement frame that moves its part: the setups
    :func:`setup_physics_bsp` refuses for their shape. Others are one-part setups it reads."""
    if not record.has_physics_bsp:
        return False
    if len(record.parts) != 1:
        return True
    if any((s.x, s.y, s.z) != (1.0, 1.0, 1.0) for s in record.default_scale):
        return True
    return any(
        not _is_identity((f.origin.x, f.origin.y, f.origin.z, f.qw, f.qx, f.qy, f.qz))
        for frames in record.placement_frames.values()
        for f in frames
    )


def setup_parts(record: SetupRecord, dat: DatFile) -> list[SetupPart]:
    """Every part of ``record``, read from ``dat``: its GfxObj's physics BSP (None for a GfxObj
    without physics data) and ``gfx_bound_box``, its default scale (1 without flag 2) and its
    frame in the default placement (:func:`default_placement`). A setup with no placement 0x65
    or 0 is refused: retail would leave its parts where they were made, at no frame of the body's.

    Retail: CPartArray::InitParts @ 0x00517F40 (acclient.c:325273)
    """
    what = f"setup {record.did:#010x}"
    if not record.parts:
        raise DatError(f"{what} has no parts")
    placement = default_placement(record)
    if placement is None:
        raise DatError(f"{what} has no placement frame {DEFAULT_PLACEMENT_ID:#x} or 0 to place its parts by")
    parts = []
    for index, gfx_id in enumerate(record.parts):
        try:
            gfxobj = _part_gfxobj(what, index, gfx_id, dat)
        except DatError as error:
            if not record.has_physics_bsp:
                raise
            raise DatError(f"{what} has a physics BSP but part {index} cannot be read: {error}") from None
        scale = record.default_scale[index].copy() if record.default_scale else Vector3(1.0, 1.0, 1.0)
        parts.append(
            SetupPart(
                physics_bsp=gfxobj.physics_bsp,
                bounding_box=BBox(gfxobj.gfx_bound_box.min, gfxobj.gfx_bound_box.max),
                default_scale=scale,
                placement_frame=placement[1][index].copy(),
            )
        )
    if record.has_physics_bsp and all(part.physics_bsp is None for part in parts):
        raise DatError(f"{what} has a physics BSP flag but none of its parts' gfxobjs has physics data")
    return parts
