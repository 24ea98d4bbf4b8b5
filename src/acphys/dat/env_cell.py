"""Retail indoor-cell records: ``CEnvironment`` (0x0Dxxxxxx, portal DAT) with its ``CCellStruct``s,
and ``CEnvCell`` (0xXXYY0100 and up, cell DAT); and making the world's cells of them.

``CEnvironment`` record: DID, a dword cell-struct count, then the cell structs one after the
other. ``CEnvCell::get_cellstruct`` picks them by position (ACE keys them by the stored id).

``CCellStruct`` (little-endian): ``cellstruct_id``; dword counts of polygons, physics polygons
and portals; the vertex array (as a GfxObj's); the polygons (as a GfxObj's); one u16 polygon
index per portal (``portals[i] = &polygons[index]``, by position); zero padding to a dword; the
cell BSP; the physics polygons; the physics BSP; a dword, then the drawing BSP when it is not 0;
zero padding to a dword. Padding is to the buffer address, which is the record's offset here
(records start dword-aligned).

The three trees share ``BSPNODE::UnPackChild``: a tag dword, then ``PORT``, ``LEAF`` or an
interior node (plane, then the children its tag names, pos first). What follows depends on the
tree (``BSPNODE::pack_tree_type``):

- cell tree (type 2): nothing; a leaf is its i32 index only, a portal its plane and both children;
- physics tree (type 1): an interior node's sphere; a leaf's index, dword solid, sphere, and u16
  physics-polygon indices (dword count first); a portal nothing more (its sphere stays zero);
- drawing tree (type 0): an interior node's sphere and u16 polygon indices (dword count first);
  a leaf its index only; a portal its sphere, dword counts of polygons and portal polygons, the
  u16 polygon indices, then per portal polygon a u16 polygon index and an i16 portal index.

Retail reads an unknown interior tag as a node without children; acphys refuses it, as the
GfxObj reader does. The drawing tree is read (the next cell struct follows it) but its portal
polygon lists (``CPortalPoly``, visibility data) are only checked, not kept.

``CEnvCell`` record: DID; a flags dword (1 ``seen_outside``, 2 static objects, 8 restriction
object); the cell id again (retail's block mask comes from it); u8 surface count, u8 portal
count, u16 stab count; u16 surface numbers (ids ``0x08000000 |``); u16 environment number (id
``0x0D000000 |``), u16 cell struct index; the frame (origin, qw qx qy qz); the portals
(``CCellPortal``: u16 flags, u16 polygon id, u16 other cell, i16 other portal); u16 stab cell
numbers (ids get the block's high word); with flag 2 a dword count and that many {DID, frame}
static objects; with flag 8 the restriction object dword. There is no padding anywhere.

A cell portal names its polygon by the polygon's *stored* id, which ``CCellStruct::get_portal``
looks for among the structure's portals.
"""

from __future__ import annotations

from dataclasses import dataclass

from acphys.dat.container import DatError
from acphys.dat.gfxobj import NODE_CHILDREN, read_leaf, read_poly_refs, read_polygon, read_vertex_array
from acphys.dat.landblock_info import LandBlockInfoRecord, ObjectSetup
from acphys.dat.records import Reader
from acphys.geometry.bsp import NODE_TYPE_LEAF, NODE_TYPE_PORTAL, BSPLeaf, BSPNode, BSPTree
from acphys.geometry.plane import Plane
from acphys.geometry.polygon import Polygon
from acphys.math.cell_id import FIRST_ENV_CELL, adjust_to_outside, format_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.physics_obj import PhysicsObj
from acphys.world.building import BldPortal, BuildingObj
from acphys.world.env_cell import CellPortal, CellStruct, EnvCell, Environment
from acphys.world.landblock import LandBlock
from acphys.world.static_objects import add_static_object
from acphys.world.world import World

#: ``BSPNODE::pack_tree_type`` values (``BSPTreeType``).
DRAWING_BSP = 0
PHYSICS_BSP = 1
CELL_BSP = 2
#: ``CEnvCell`` pack flags.
ENV_CELL_SEEN_OUTSIDE = 0x1
ENV_CELL_HAS_STATIC_OBJS = 0x2
ENV_CELL_HAS_RESTRICTION = 0x8
#: The id high bytes env cells give their surface and environment numbers.
SURFACE_ID_BASE = 0x08000000
ENVIRONMENT_ID_BASE = 0x0D000000
#: The id high byte of environment records.
ENVIRONMENT_ID_TYPE = 0x0D


@dataclass
class CellStructRecord:
    """A ``CCellStruct`` (acclient.h:32275) as stored, physics side and trees."""

    cellstruct_id: int
    vertices: list[Vector3]
    #: The polygons by array position, with their stored ``poly_id``s in ``poly_ids``.
    polygons: list[Polygon]
    poly_ids: list[int]
    #: ``portals``: positions in ``polygons``.
    portal_indices: list[int]
    cell_bsp: BSPTree
    physics_polygons: list[Polygon]
    physics_poly_ids: list[int]
    physics_bsp: BSPTree
    #: Nodes hold drawing polygons; portal nodes' portal-polygon lists are not kept.
    drawing_bsp: BSPTree | None

    def to_cell_struct(self) -> CellStruct:
        """The world's structure (portals as the polygons themselves)."""
        return CellStruct(
            self.cell_bsp,
            self.physics_bsp,
            self.polygons,
            [self.polygons[i] for i in self.portal_indices],
            self.physics_polygons,
            self.cellstruct_id,
        )


@dataclass
class EnvironmentRecord:
    """A ``CEnvironment`` (acclient.h:32293): its cell structs, by position."""

    did: int
    cells: list[CellStructRecord]

    def to_environment(self) -> Environment:
        return Environment([cell.to_cell_struct() for cell in self.cells], self.did)


@dataclass
class CellPortalRecord:
    """A ``CCellPortal`` as stored (the words ``CCellPortal::UnPack`` reads)."""

    flags: int
    #: The stored ``poly_id`` of the portal polygon.
    poly_id: int
    #: The other cell's number (low word), meaningless with flags bit 2 (to the outside).
    other_cell: int
    #: Signed 16 bits.
    other_portal_id: int


@dataclass
class EnvCellRecord:
    """A ``CEnvCell`` record (acclient.h:32072), every stored field."""

    did: int
    flags: int
    #: The second id dword (the one retail takes the block mask from).
    cell_id: int
    surfaces: list[int]
    environment_id: int
    cell_struct_index: int
    frame: Frame
    portals: list[CellPortalRecord]
    #: Visible cells, full ids.
    stab_list: list[int]
    static_object_ids: list[int]
    #: One landblock-local frame per static object (like the cell's own frame).
    static_object_frames: list[Frame]
    #: ``restriction_obj``: 0 when not stored.
    restriction_obj: int

    @property
    def seen_outside(self) -> bool:
        return bool(self.flags & ENV_CELL_SEEN_OUTSIDE)

    @property
    def block_mask(self) -> int:
        return self.cell_id & 0xFFFF0000


def _tree(reader: Reader, polygons: list[Polygon], tree_type: int, what: str) -> BSPTree:
    """One tree; ``polygons`` are the ones its indices name (``BSPNODE::pack_poly``).

    Retail: BSPTREE::UnPack @ 0x00539830 (acclient.c:360685)
    """
    try:
        return BSPTree(_child(reader, polygons, tree_type))
    except RecursionError:
        raise DatError(f"{reader.what}: the {what} nests too deep to read") from None


def _child(reader: Reader, polygons: list[Polygon], tree_type: int) -> BSPNode:
    """A tag dword, then a portal, a leaf or an interior node.

    Retail: BSPNODE::UnPackChild @ 0x0053C770 (acclient.c:363343)
    """
    tag = reader.u32()
    if tag == NODE_TYPE_PORTAL:
        return _portal(reader, polygons, tree_type)
    if tag == NODE_TYPE_LEAF:
        if tree_type == PHYSICS_BSP:
            return read_leaf(reader, polygons)
        return BSPLeaf(int(reader.unpack("i")[0]))
    return _node(reader, polygons, tree_type, tag)


def _node(reader: Reader, polygons: list[Polygon], tree_type: int, tag: int) -> BSPNode:
    """An interior node after its tag: plane, children, then (physics) its sphere or (drawing)
    its sphere and polygon indices; a cell-tree node stores nothing more.

    Retail: BSPNODE::UnPack @ 0x0053C540 (acclient.c:363185)
    """
    children = NODE_CHILDREN.get(tag)
    if children is None:
        name = tag.to_bytes(4, "big").decode("ascii", errors="replace")
        raise DatError(
            f"{reader.what}: BSP node tag {name!r} ({tag:#010x}) at byte {reader.pos - 4} is not a "
            "node tag (BPIN, BPnN, BPIn, BPnn, BpIN, BpnN, LEAF, PORT)"
        )
    normal = reader.vector()
    plane = Plane(normal, reader.coordinate())
    pos = _child(reader, polygons, tree_type) if children[0] else None
    neg = _child(reader, polygons, tree_type) if children[1] else None
    if tree_type == CELL_BSP:
        return BSPNode(plane, pos, neg, type=tag)
    sphere = reader.sphere()
    polys = read_poly_refs(reader, polygons, "drawing node") if tree_type == DRAWING_BSP else None
    return BSPNode(plane, pos, neg, sphere, polys, type=tag)


def _portal(reader: Reader, polygons: list[Polygon], tree_type: int) -> BSPNode:
    """A ``PORT`` node after its tag: plane, both children; in a drawing tree then its sphere,
    polygon and portal counts, polygon indices and {polygon index, portal index} pairs.

    Retail: BSPPORTAL::UnPackPortal @ 0x0053DB70 (acclient.c:364645)
    """
    normal = reader.vector()
    plane = Plane(normal, reader.coordinate())
    pos = _child(reader, polygons, tree_type)
    neg = _child(reader, polygons, tree_type)
    if tree_type != DRAWING_BSP:
        return BSPNode(plane, pos, neg, type=NODE_TYPE_PORTAL)
    sphere = reader.sphere()
    num_polys = reader.u32()
    num_portals = reader.count(4, "portal polygon")
    if num_polys * 2 > len(reader.data) - reader.pos:
        raise DatError(f"{reader.what}: portal node polygon count {num_polys} overruns the record")
    indices = [int(v) for v in reader.unpack(f"{num_polys}H")]
    indices += [int(v) for v in reader.unpack(f"{2 * num_portals}H")[::2]]
    bad = [i for i in indices if i >= len(polygons)]
    if bad:
        raise DatError(f"{reader.what}: a drawing portal node names polygon {bad[0]} of {len(polygons)}")
    return BSPNode(plane, pos, neg, sphere, [polygons[i] for i in indices[:num_polys]], type=NODE_TYPE_PORTAL)


def _polygons(
    reader: Reader, count: int, vertices: list[Vector3], what: str
) -> tuple[list[int], list[Polygon]]:
    if count * 12 > len(reader.data) - reader.pos:
        raise DatError(f"{reader.what}: {what} count {count} overruns the record")
    ids: list[int] = []
    polygons: list[Polygon] = []
    for _ in range(count):
        poly_id, polygon = read_polygon(reader, vertices)
        ids.append(poly_id)
        polygons.append(polygon)
    return ids, polygons


def _cell_struct(reader: Reader) -> CellStructRecord:
    """One cell struct (layout in the module docstring).

    Retail: CCellStruct::UnPack @ 0x00533D00 (acclient.c:355822)
    """
    cellstruct_id, num_polygons, num_physics, num_portals = reader.unpack("4I")
    where = f"cell struct {cellstruct_id}"
    vertices = read_vertex_array(reader)
    poly_ids, polygons = _polygons(reader, int(num_polygons), vertices, f"{where} polygon")
    if int(num_portals) * 2 > len(reader.data) - reader.pos:
        raise DatError(f"{reader.what}: {where} portal count {num_portals} overruns the record")
    portal_indices = [int(v) for v in reader.unpack(f"{num_portals}H")]
    bad = [i for i in portal_indices if i >= len(polygons)]
    if bad:
        raise DatError(f"{reader.what}: {where} portal names polygon {bad[0]} of {len(polygons)}")
    reader.align()
    cell_bsp = _tree(reader, polygons, CELL_BSP, f"{where} cell BSP")
    physics_ids, physics_polygons = _polygons(reader, int(num_physics), vertices, f"{where} physics polygon")
    physics_bsp = _tree(reader, physics_polygons, PHYSICS_BSP, f"{where} physics BSP")
    drawing_bsp = _tree(reader, polygons, DRAWING_BSP, f"{where} drawing BSP") if reader.u32() else None
    reader.align()
    return CellStructRecord(
        int(cellstruct_id), vertices, polygons, poly_ids, portal_indices, cell_bsp,
        physics_polygons, physics_ids, physics_bsp, drawing_bsp,
    )  # fmt: skip


def unpack_environment(data: bytes) -> EnvironmentRecord:
    """Parse a ``CEnvironment`` record: DID, count, cell structs.

    Retail: CEnvironment::UnPack @ 0x00530CF0 (acclient.c:352987)
    """
    reader = Reader(data, "environment")
    did = reader.u32()
    reader.what = f"environment {did:#010x}"
    cells = [_cell_struct(reader) for _ in range(reader.count(16, "cell struct"))]
    return EnvironmentRecord(did, cells)


def _cell_portal(reader: Reader) -> CellPortalRecord:
    """Retail: CCellPortal::UnPack @ 0x0053BAB0 (acclient.c:362378)"""
    flags, poly_id, other_cell, other_portal = reader.unpack("HHHh")
    return CellPortalRecord(int(flags), int(poly_id), int(other_cell), int(other_portal))


def unpack_env_cell(data: bytes) -> EnvCellRecord:
    """Parse a ``CEnvCell`` record (layout in the module docstring).

    Retail: CEnvCell::UnPack @ 0x0052D470 (acclient.c:349133)
    """
    reader = Reader(data, "env cell")
    did = reader.u32()
    reader.what = f"env cell {did:#010x}"
    flags = reader.u32()
    cell_id = reader.u32()
    block_mask = cell_id & 0xFFFF0000
    num_surfaces, num_portals, num_stabs = reader.unpack("BBH")
    surfaces = [SURFACE_ID_BASE | int(v) for v in reader.unpack(f"{num_surfaces}H")]
    env_number, cell_struct_index = reader.unpack("2H")
    frame = reader.frame()
    portals = [_cell_portal(reader) for _ in range(int(num_portals))]
    stab_list = [block_mask | int(v) for v in reader.unpack(f"{num_stabs}H")]
    object_ids: list[int] = []
    object_frames: list[Frame] = []
    if flags & ENV_CELL_HAS_STATIC_OBJS:
        for _ in range(reader.count(32, "static object")):
            object_ids.append(reader.u32())
            object_frames.append(reader.frame())
    restriction = reader.u32() if flags & ENV_CELL_HAS_RESTRICTION else 0
    return EnvCellRecord(
        did, flags, cell_id, surfaces, ENVIRONMENT_ID_BASE | int(env_number), int(cell_struct_index),
        frame, portals, stab_list, object_ids, object_frames, restriction,
    )  # fmt: skip


def make_env_cell(record: EnvCellRecord, env_record: EnvironmentRecord, environment: Environment) -> EnvCell:
    """The world's cell of ``record``. ``env_record`` is the environment ``record.environment_id``
    names and ``environment`` the world's environment made of it (``env_record.to_environment()``,
    shared by the cells that use it). The cell's structure is picked by index; each portal's
    polygon is the first of the structure's portals whose stored id is the portal's
    ``poly_id`` (``CCellStruct::get_portal``); a portal naming none is a DatError (retail keeps
    a null polygon).

    Retail: CEnvCell::UnPack @ 0x0052D470 (acclient.c:349133)
    """
    what = f"env cell {record.did:#010x}"
    if (record.cell_id & 0xFFFF) < FIRST_ENV_CELL or (record.cell_id & 0xFFFF) == 0xFFFF:
        raise DatError(f"{what}: stored cell id {record.cell_id:#010x} is not an env cell id")
    if environment.env_id != env_record.did or environment.num_cells != len(env_record.cells):
        raise ValueError(
            f"environment {environment.env_id:#010x} is not made of record {env_record.did:#010x}"
        )
    index = record.cell_struct_index
    if not 0 <= index < len(env_record.cells):
        raise DatError(
            f"{what}: cell struct {index} of environment {env_record.did:#010x}, which has "
            f"{len(env_record.cells)}"
        )
    stored_struct = env_record.cells[index]
    structure = environment.get_cellstruct(index)
    portals: list[CellPortal] = []
    for number, stored in enumerate(record.portals):
        polygon = _get_portal(stored_struct, structure, stored.poly_id)
        if polygon is None:
            raise DatError(
                f"{what}: portal {number} names polygon {stored.poly_id}, not a portal of its structure"
            )
        try:
            portals.append(
                CellPortal.unpack(
                    record.block_mask, stored.flags, polygon, stored.other_cell, stored.other_portal_id
                )
            )
        except ValueError as error:
            raise DatError(f"{what}: portal {number}: {error}") from None
    return EnvCell(record.cell_id, structure, record.frame, portals, environment)


def _get_portal(stored: CellStructRecord, structure: CellStruct, poly_id: int) -> Polygon | None:
    """The first portal of ``structure`` whose stored polygon id is ``poly_id``, or None.

    Retail: CCellStruct::get_portal @ 0x005338B0 (acclient.c:355463)
    """
    for index in stored.portal_indices:
        if stored.poly_ids[index] == poly_id:
            return structure.polygons[index]
    return None


def init_static_objects(
    world: World, cell: EnvCell, record: EnvCellRecord, object_setup: ObjectSetup
) -> list[PhysicsObj]:
    """Make ``record``'s static objects in ``cell`` (which must be in ``world``), at their
    stored frames. A zero DID, or one ``object_setup`` makes nothing of, is skipped, as retail
    skips it. Objects are named ``<did>@<cell>#<index>``.

    Retail: CEnvCell::init_static_objects @ 0x0052C350 (acclient.c:347954)
    """
    placed: list[PhysicsObj] = []
    for index, (object_id, frame) in enumerate(
        zip(record.static_object_ids, record.static_object_frames, strict=True)
    ):
        setup = object_setup(object_id) if object_id else None
        if setup is None:
            continue
        name = f"{object_id:#010x}@{format_cell_id(cell.id)}#{index}"
        placed.append(add_static_object(world, name, setup, Position(cell.id, frame.copy())))
    return placed


def init_buildings(
    world: World, landblock: LandBlock, info: LandBlockInfoRecord, object_setup: ObjectSetup
) -> list[BuildingObj]:
    """Make ``info``'s buildings: each one's shell is the physics BSP of the setup
    ``object_setup`` makes of its model DID (a building it makes nothing of is dropped, as
    retail's ``makeBuilding`` fails), its portals are its ``CBldPortal``s, and it stands in the
    land cell of ``landblock`` under its origin (dropped when there is none). Its cells are
    looked up in ``world``.

    Not ported: the landblock's stab list (drawing) and the leaf cells (``num_leaves``).

    Retail: CLandBlock::init_buildings @ 0x0052FD80 (acclient.c:352113)
    """
    if info.block_mask != landblock.id & 0xFFFF0000:
        raise ValueError(
            f"landblock info {info.did:#010x} is not the info of landblock {format_cell_id(landblock.id)}"
        )
    built: list[BuildingObj] = []
    for record in info.buildings:
        setup = object_setup(record.building_id)
        if setup is None:
            continue
        if setup.parts is not None:
            # A BuildingObj holds one part (CBuildingObj::makeBuilding); a shell of several parts
            # would lose its collision shape, so it is refused rather than built without one.
            raise DatError(
                f"building 0x{record.building_id:08X} has a shell of {len(setup.parts)} parts; "
                "acphys builds one-part building shells only"
            )
        cell_id = adjust_to_outside(landblock.id, record.frame.origin.copy())
        cell = landblock.get_landcell(cell_id) if cell_id else None
        if cell is None:
            continue
        portals = [
            BldPortal(p.other_cell_id, p.other_portal_id, int(p.portal_side), p.exact_match, p.stab_list)
            for p in record.portals
        ]
        building = BuildingObj(
            setup.physics_bsp, record.frame.copy(), portals, building_id=record.building_id, source=world
        )
        building.add_to_cell(cell)
        built.append(building)
    return built
