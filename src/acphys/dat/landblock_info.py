"""Retail ``CLandBlockInfo`` records (0xXXYYFFFE, cell DAT): a landblock's static objects, its
buildings with their portals, and its restriction table; and placing the static objects.

Record layout (little-endian, after the DID that ``DBObj::Serialize`` reads):

- ``num_cells`` (the landblock's env cell count; the cells are records 0xXXYY0100 + i);
- ``num_objects``, then per object its DID and a 28-byte frame (origin, qw qx qy qz),
  landblock-local;
- one dword: the building count in the low 16 bits, ``pack_mask`` in the high 16;
- per building: its model DID, frame, ``num_leaves``, ``num_portals`` and the portals
  (``CBldPortal``: u16 flags, u16 other cell, i16 other portal, u16 stab count, u16 stabs,
  2 bytes of padding after an odd stab count; cell numbers get the block's high word);
- with ``pack_mask`` bit 0 the restriction table: a dword of count (low 16 bits) and bucket
  count (high 16), then ``count`` pairs {land cell id, restriction object iid}.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from acphys.dat.container import DatError
from acphys.dat.records import Reader
from acphys.math.cell_id import FIRST_ENV_CELL, adjust_to_outside, format_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.physics_obj import PhysicsObj
from acphys.setup import Setup
from acphys.world.landblock import LandBlock
from acphys.world.static_objects import add_static_object
from acphys.world.world import World

#: The low word of a landblock info record's id.
LANDBLOCK_INFO_LOW = 0xFFFE
#: ``pack_mask`` bit: a restriction table follows the buildings.
PACK_HAS_RESTRICTIONS = 0x1
#: ``CBldPortal`` flag bits (the u16 before the other cell).
PORTAL_EXACT_MATCH = 0x1
PORTAL_FLAG_SIDE = 0x2


@dataclass
class BldPortalRecord:
    """A ``CBldPortal`` (acclient.h:32094) as stored: a building's doorway into its cells."""

    #: ``exact_match``: flags bit 0.
    exact_match: bool
    #: ``portal_side``: set when flags bit 1 is clear.
    portal_side: bool
    #: ``other_cell_id``: the env cell behind the portal (block high word | stored u16).
    other_cell_id: int
    #: ``other_portal_id``: that cell's portal index, sign-extended from 16 bits (-1: none).
    other_portal_id: int
    #: ``stab_list``: the cells seen through the portal (block high word | stored u16 each).
    stab_list: list[int]


@dataclass
class BuildInfoRecord:
    """A ``BuildInfo`` (acclient.h:32035): one building's model, placement and portals."""

    building_id: int
    frame: Frame
    num_leaves: int
    portals: list[BldPortalRecord]


@dataclass
class LandBlockInfoRecord:
    """A ``CLandBlockInfo`` record (acclient.h:31893), every stored field."""

    did: int
    num_cells: int
    object_ids: list[int]
    #: One landblock-local frame per object.
    object_frames: list[Frame]
    buildings: list[BuildInfoRecord]
    pack_mask: int
    #: ``restriction_table``: land cell id -> restriction object iid; None when not stored.
    restriction_table: dict[int, int] | None

    @property
    def block_mask(self) -> int:
        """The landblock's high word (``m_DID & 0xFFFF0000``), which portal cell numbers get."""
        return self.did & 0xFFFF0000

    def get_restriction_iid(self, landcell_id: int) -> int:
        """The restriction object of ``landcell_id``, 0 when it has none.

        Retail: CLandBlockInfo::GetRestrictionIID @ 0x0052EF70 (acclient.c:351249)
        """
        if self.restriction_table is None:
            return 0
        return self.restriction_table.get(landcell_id, 0)


def _bld_portal(reader: Reader, block_mask: int) -> BldPortalRecord:
    """A portal into the building's env cells (a cell number below 0x0100 is a DatError: it
    names a land cell, which no building portal leads into).

    Retail: CBldPortal::UnPack @ 0x0053BC40 (acclient.c:362498)
    """
    start = reader.pos
    flags, other_cell, other_portal = reader.unpack("HHh")
    if other_cell < FIRST_ENV_CELL:
        raise DatError(
            f"{reader.what}: the building portal at byte {start} leads into cell {int(other_cell):#06x}, "
            f"not an env cell ({FIRST_ENV_CELL:#06x} and up)"
        )
    num_stabs = int(reader.unpack("H")[0])
    stabs = [block_mask | int(v) for v in reader.unpack(f"{num_stabs}H")]
    reader.align()
    return BldPortalRecord(
        bool(int(flags) & PORTAL_EXACT_MATCH),
        not int(flags) & PORTAL_FLAG_SIDE,
        block_mask | int(other_cell),
        int(other_portal),
        stabs,
    )


def _restriction_table(reader: Reader) -> dict[int, int]:
    """A ``PackableHashTable<unsigned long, unsigned long>``: count and bucket count, then pairs.

    Retail fails the record when the bucket count is 0 but the count is not, and on a repeated
    key (the table is built with ``m_fThrowawayDuplicateKeysOnUnPack`` 0); both raise DatError.
    The decompilation shows this template's body for its ``<IDClass, int>`` instance, the same
    code (a dword key, a dword value).

    Retail: PackableHashTable<IDClass<_tagDataID,32,0>,int>::UnPack @ 0x004FDC30 (acclient.c:297934)
    """
    start = reader.pos
    word = reader.u32()
    count, buckets = word & 0xFFFF, word >> 16
    if buckets == 0:
        if count:
            raise DatError(
                f"{reader.what}: restriction table at byte {start} has {count} entries and 0 buckets"
            )
        return {}
    if count * 8 > len(reader.data) - reader.pos:
        raise DatError(f"{reader.what}: restriction table count {count} at byte {start} overruns the record")
    table: dict[int, int] = {}
    for _ in range(count):
        key, value = reader.unpack("2I")
        if key in table:
            raise DatError(f"{reader.what}: restriction table names cell {int(key):#010x} twice")
        table[int(key)] = int(value)
    return table


def unpack_landblock_info(data: bytes) -> LandBlockInfoRecord:
    """Parse a ``CLandBlockInfo`` record (layout in the module docstring). Frames are read as
    ``Frame::UnPack`` reads them (origin, then qw qx qy qz); retail ignores its validity result.

    Retail: CLandBlockInfo::UnPack @ 0x0052ECA0 (acclient.c:351048)
    """
    reader = Reader(data, "landblock info")
    did = reader.u32()
    reader.what = f"landblock info {did:#010x}"
    if did & 0xFFFF != LANDBLOCK_INFO_LOW:
        raise DatError(f"{reader.what}: a landblock info id ends in 0xFFFE")
    block_mask = did & 0xFFFF0000
    num_cells = reader.u32()
    object_ids: list[int] = []
    object_frames: list[Frame] = []
    for _ in range(reader.count(32, "object")):
        object_ids.append(reader.u32())
        object_frames.append(reader.frame())
    word = reader.u32()
    num_buildings, pack_mask = word & 0xFFFF, word >> 16
    if num_buildings * 40 > len(data) - reader.pos:
        raise DatError(f"{reader.what}: building count {num_buildings} overruns the record")
    buildings: list[BuildInfoRecord] = []
    for _ in range(num_buildings):
        building_id = reader.u32()
        frame = reader.frame()
        num_leaves = reader.u32()
        portals = [_bld_portal(reader, block_mask) for _ in range(reader.count(8, "portal"))]
        buildings.append(BuildInfoRecord(building_id, frame, num_leaves, portals))
    restrictions = _restriction_table(reader) if pack_mask & PACK_HAS_RESTRICTIONS else None
    return LandBlockInfoRecord(did, num_cells, object_ids, object_frames, buildings, pack_mask, restrictions)


#: Makes the physics view of a static object's DID (a setup, or a GfxObj wrapped in a one-part
#: setup); None for a DID retail's ``makeObject`` makes nothing of.
ObjectSetup = Callable[[int], Setup | None]


def init_static_objs(
    world: World, landblock: LandBlock, info: LandBlockInfoRecord, object_setup: ObjectSetup
) -> list[PhysicsObj]:
    """Make ``info``'s static objects and put each in the land cell of ``landblock`` under its
    origin. An object ``object_setup`` makes nothing of, or whose origin is in no land cell of
    this landblock, is dropped, as retail drops it. Objects are named ``<did>@<cell>#<index>``.

    Not ported here: the restriction ids retail then copies onto the land cells (acphys's
    land cells have no restriction field; read them with ``info.get_restriction_iid``), and
    the scene objects (``get_land_scenes``), which are drawing only.

    Retail: CLandBlock::init_static_objs @ 0x00530A40 (acclient.c:352786)
    """
    if info.block_mask != landblock.id & 0xFFFF0000:
        raise ValueError(
            f"landblock info {info.did:#010x} is not the info of landblock {format_cell_id(landblock.id)}"
        )
    placed: list[PhysicsObj] = []
    for index, (object_id, frame) in enumerate(zip(info.object_ids, info.object_frames, strict=True)):
        setup = object_setup(object_id)
        if setup is None:
            continue
        cell_id = adjust_to_outside(landblock.id, frame.origin.copy())
        cell = landblock.get_landcell(cell_id) if cell_id else None
        if cell is None:
            continue
        name = f"{object_id:#010x}@{format_cell_id(cell.id)}#{index}"
        placed.append(add_static_object(world, name, setup, Position(cell.id, frame.copy())))
    return placed
