"""Retail ``CLandBlock`` (a landblock's terrain and its 64 land cells) and the ``LScape`` lookups.

``LandBlock`` wraps a :class:`~acphys.world.terrain.LandBlockStruct` (retail's ``CLandBlock``
derives from ``CLandBlockStruct``) and builds its 8×8 :class:`LandCell` objects the way
``ConstructPolygons`` and ``CalcWater`` fill ``lcell``: id, centre, two triangles, water type,
and ``init_lcell_ptrs`` points each back at the block.

``Landscape`` is the part of retail's ``LScape`` the cell routines use: landblocks by id and
``get_landcell``; it also keeps other cells (env cells) by id, so it is a complete
:class:`~acphys.world.obj_cell.CellSource` for ``CellArray``.

Not ported: static objects, buildings and scenery of ``CLandBlockInfo`` (``init_static_objs``,
``init_buildings``, ``get_land_scenes``), rendering and streaming.
"""

from __future__ import annotations

from acphys.constants import CELL_LENGTH, CELLS_PER_BLOCK
from acphys.math.cell_id import (
    FIRST_ENV_CELL,
    LAST_LAND_CELL,
    cell_of,
    format_cell_id,
    gid_to_lcoord,
    inbound_valid_cellid,
    landblock_of,
)
from acphys.math.vector import Vector3
from acphys.world.land_cell import LandCell
from acphys.world.obj_cell import ObjCell
from acphys.world.terrain import LandBlockStruct, WaterType


class LandBlock:
    """Retail ``CLandBlock``: a landblock's terrain (``terrain``) and its 64 land cells.

    ``lcell[8*cx + cy]`` is the cell at column ``cx``, row ``cy`` (id low word ``8*cx + cy + 1``).

    Retail: CLandBlock::CLandBlock @ 0x0052F950 (acclient.c:351874)
    """

    __slots__ = ("id", "lcell", "terrain")

    def __init__(self, terrain: LandBlockStruct) -> None:
        self.terrain = terrain
        #: The block id ``0xXXYYFFFF``.
        self.id = (terrain.block_id & 0xFFFF0000) | 0xFFFF
        if not inbound_valid_cellid(self.id):
            raise ValueError(f"landblock {format_cell_id(self.id)} is outside the world")
        block = landblock_of(self.id)
        self.lcell: list[LandCell] = []
        for cx in range(CELLS_PER_BLOCK):
            for cy in range(CELLS_PER_BLOCK):
                cell = LandCell(cell_of(block, CELLS_PER_BLOCK * cx + cy + 1), terrain.cell_polygons(cx, cy))
                # ConstructPolygons: the cell's centre (acclient.c:354091-354098).
                half = CELL_LENGTH / 2
                cell.pos.frame.origin = Vector3((2 * cx + 1) * half, (2 * cy + 1) * half, 0.0)
                cell.water_type = terrain.cell_water_types[CELLS_PER_BLOCK * cx + cy]
                self.lcell.append(cell)
        self.init_lcell_ptrs()

    def __repr__(self) -> str:
        return f"LandBlock({format_cell_id(self.id)})"

    @property
    def water_type(self) -> WaterType:
        """The block's water type (``CalcWater``)."""
        return self.terrain.water_type

    def init_lcell_ptrs(self) -> None:
        """Point every land cell at this block (``myLandBlock_``).

        Retail: CLandBlock::init_lcell_ptrs @ 0x0052F410 (acclient.c:351580)
        """
        for cell in self.lcell:
            cell.landblock = self

    def get_landcell(self, cell_id: int) -> LandCell | None:
        """The land cell with exactly this id, or None (another block, or not a land cell).

        Retail: CLandBlock::get_landcell @ 0x0052FD20 (acclient.c:352097)
        """
        lcoord = gid_to_lcoord(cell_id)
        if lcoord is None:
            return None
        cell = self.lcell[(lcoord[0] & 7) * CELLS_PER_BLOCK + (lcoord[1] & 7)]
        return cell if cell.id == cell_id else None

    def calc_water_depth(self, cell_id: int, point: Vector3) -> float:
        """Retail: CLandBlockStruct::calc_water_depth @ 0x005315F0 (acclient.c:353645)"""
        return self.terrain.calc_water_depth(cell_id, point)

    def get_terrain(self, cell_id: int, point: Vector3) -> int:
        """Retail: CLandBlock::get_terrain @ 0x0052FB70 (acclient.c:352008)"""
        return self.terrain.get_terrain(cell_id, point)


class Landscape:
    """Landblocks by id and other cells by id: a ``CellSource`` for cell arrays."""

    __slots__ = ("_blocks", "_cells")

    def __init__(self) -> None:
        self._blocks: dict[int, LandBlock] = {}
        self._cells: dict[int, ObjCell] = {}

    def add_landblock(self, landblock: LandBlock) -> None:
        """Add ``landblock``; its id must be new."""
        key = landblock_of(landblock.id)
        if key in self._blocks:
            raise ValueError(f"landblock {format_cell_id(landblock.id)} is already in the landscape")
        self._blocks[key] = landblock

    def add_cell(self, cell: ObjCell) -> None:
        """Add a cell that is not a land cell (an env cell); its id must be new."""
        if (cell.id & 0xFFFF) < FIRST_ENV_CELL:
            raise ValueError(f"{format_cell_id(cell.id)} is a land cell id; land cells come with landblocks")
        if cell.id in self._cells:
            raise ValueError(f"cell {format_cell_id(cell.id)} is already in the landscape")
        self._cells[cell.id] = cell

    def landblocks(self) -> set[int]:
        """The ids (``0xXXYY``) of the landblocks in the landscape."""
        return set(self._blocks)

    def get_landblock(self, cell_id: int) -> LandBlock | None:
        """The landblock holding ``cell_id`` (any cell of it), or None when it is not there."""
        return self._blocks.get(landblock_of(cell_id))

    def get_landcell(self, cell_id: int) -> LandCell | None:
        """The land cell ``cell_id``, or None when its landblock is not there or the id is
        not a valid land cell.

        Retail: LScape::get_landcell @ 0x00505F10 (acclient.c:307511)
        """
        low = cell_id & 0xFFFF
        if not 1 <= low <= LAST_LAND_CELL:
            return None
        block = self.get_landblock(cell_id)
        return block.get_landcell(cell_id) if block is not None else None

    def env_cells(self, landblock: int) -> list[ObjCell]:
        """The added (indoor) cells of ``landblock`` (``0xXXYY``), in id order."""
        return sorted(
            (cell for cell in self._cells.values() if landblock_of(cell.id) == landblock), key=lambda c: c.id
        )

    def get_cell(self, cell_id: int) -> ObjCell | None:
        """Any cell by id: land cells through their landblock, others from the added cells."""
        if (cell_id & 0xFFFF) < FIRST_ENV_CELL:
            return self.get_landcell(cell_id)
        return self._cells.get(cell_id)
