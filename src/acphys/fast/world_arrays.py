"""The world as the kernel reads it: land cells with their terrain, and who shadows into each.

The kernel knows the land cells of the loaded landblocks (``LandBlock.lcell``), indexed
``64 * landblock + (low word - 1)``, with their two triangles and water type, and those of the
landblocks past the world's edge that bodies have reached (the terrain-less cells ``World.get_cell``
makes there, read by :meth:`WorldArrays.add_landblocks` when the kernel asks). A cell it cannot
sweep through alone is marked ``uncovered``: global detection watches it (voyeurs), an entry
restriction is set, or a building stands in it that the kernel cannot bound; a step that would
touch such a cell (or an env cell) runs on the reference path instead. A building it can bound
(:mod:`acphys.fast.buildings`) is kept as its shell's ball and its doors' planes, and a step that
comes within their reach runs there too.

Each cell's shadow list is kept in the shadow pool, in the order of the reference
``ObjCell.shadow_objects``: a body's entry is its index in the engine's body table, any other
object's (a static object) is ``-1 - k``, ``k`` its index in :attr:`WorldArrays.others`. The kernel
adds and removes entries exactly as ``add_shadow_object`` and ``remove_shadow_object`` do
(append; the last entry takes a removed one's slot), so the two lists stay the same list.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from acphys.fast.buildings import building_reach
from acphys.fast.layout import CELL
from acphys.fast.statics import SHAPE_WIDTH, shape_arrays
from acphys.math.cell_id import landblock_of
from acphys.physics_obj import PhysicsObj
from acphys.world.land_cell import LandCell
from acphys.world.obj_cell import ObjCell, ShadowObj
from acphys.world.world import World

#: Cells per landblock (8 × 8).
BLOCK_CELLS = 64
#: The shadow slots a cell starts with; a cell that fills them is given twice as many.
INITIAL_SHADOW_CAPACITY = 8


@dataclass
class WorldArrays:
    """The kernel's cells (:data:`~acphys.fast.layout.CELL` records), the landblock lookup, and the
    shadow pool; ``land_cells[k]`` is the reference cell of kernel cell ``k``."""

    cells: np.ndarray
    #: ``landblock_index[0xXXYY]``: the landblock's index in ``cells // 64``, or -1.
    landblock_index: np.ndarray
    shadow_pool: np.ndarray
    land_cells: list[LandCell]
    #: Objects other than the engine's bodies that shadow into known cells (static objects).
    others: list[PhysicsObj] = field(default_factory=list)
    #: Each other object's shadow entries by kernel cell (they never move).
    other_shadows: dict[tuple[int, int], ShadowObj] = field(default_factory=dict)
    #: ``id(object)`` to its index in ``others``.
    other_index: dict[int, int] = field(default_factory=dict)
    #: Where each other object's shapes could answer a sweep (:mod:`acphys.fast.statics`):
    #: ``other_spans[k]`` its rows of ``other_shapes``, as :func:`~acphys.fast.statics.shape_arrays`.
    other_spans: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int32))
    other_shapes: np.ndarray = field(default_factory=lambda: np.zeros((0, SHAPE_WIDTH), dtype=np.float64))
    #: The buildings' shell balls (rows as ``other_shapes``), their doors (``door_spans``: each
    #: door's rows ``(first, count)`` of ``door_planes``) and those planes (nx, ny, nz, d), for
    #: the cells' ``building_*`` fields.
    building_shapes: np.ndarray = field(default_factory=lambda: np.zeros((0, SHAPE_WIDTH), dtype=np.float64))
    door_spans: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int32))
    door_planes: np.ndarray = field(default_factory=lambda: np.zeros((0, 4), dtype=np.float64))
    #: The landblocks (``0xXXYY``) read as the terrain-less cells the world makes past its edge.
    void_blocks: set[int] = field(default_factory=set)

    def land_cell(self, cell_id: int) -> LandCell | None:
        """The reference cell the kernel knows as ``cell_id``, or None."""
        k = self.cell_index(cell_id)
        return self.land_cells[k] if k >= 0 else None

    def cell_index(self, cell_id: int) -> int:
        """The kernel index of land cell ``cell_id``, or -1 (not a land cell of a landblock read)."""
        low = cell_id & 0xFFFF
        if not 1 <= low <= BLOCK_CELLS:
            return -1
        block = int(self.landblock_index[landblock_of(cell_id)])
        return -1 if block < 0 else BLOCK_CELLS * block + low - 1

    def shadow_list(self, k: int) -> np.ndarray:
        """Kernel cell ``k``'s shadow entries, in order (a view into the pool)."""
        cell = self.cells[k]
        start = int(cell["shadow_start"])
        return self.shadow_pool[start : start + int(cell["num_shadows"])]

    def grow(self, k: int) -> None:
        """Give kernel cell ``k`` twice its shadow capacity (the kernel asked for room): a new pool,
        every list copied to its new place."""
        cells = self.cells
        old_start, old_pool = cells["shadow_start"].copy(), self.shadow_pool
        capacity = cells["shadow_capacity"].copy()
        capacity[k] *= 2
        start = np.concatenate(([0], np.cumsum(capacity)[:-1])).astype(np.int32)
        pool = np.full(int(capacity.sum()), -(2**31), dtype=np.int32)
        for i in np.flatnonzero(cells["num_shadows"]).tolist():
            count = int(cells[i]["num_shadows"])
            pool[start[i] : start[i] + count] = old_pool[old_start[i] : old_start[i] + count]
        cells["shadow_start"] = start
        cells["shadow_capacity"] = capacity
        self.shadow_pool = pool

    def add_landblocks(self, blocks: Sequence[tuple[Sequence[LandCell], int]], index: dict[int, int]) -> None:
        """Know more landblocks, each its 64 land cells (in the order of their ids) and its water
        type, with the shadow lists read from their cells (``index``: ``id(body)`` to the
        engine's number). Indices already given stay: the cells go after the others, in new
        arrays."""
        first, known = len(self.land_cells), len(self.others)
        records = []
        for land_cells, block_water_type in blocks:
            b = len(self.land_cells) // BLOCK_CELLS
            self.landblock_index[landblock_of(land_cells[0].id)] = b
            self.land_cells.extend(land_cells)
            records.append(_cell_records(land_cells, b, block_water_type))
        if not records:
            return
        new = self.land_cells[first:]
        lists = [shadow_entries(self, first + i, cell, index) for i, cell in enumerate(new)]
        capacity = np.array([_room(len(entries)) for entries in lists], dtype=np.int32)
        cells = np.concatenate(records)
        self._place_buildings(cells, new)
        cells["shadow_capacity"] = capacity
        cells["shadow_start"] = len(self.shadow_pool) + np.concatenate(([0], np.cumsum(capacity)[:-1]))
        self.cells = np.concatenate((self.cells, cells))
        room = np.full(int(capacity.sum()), -(2**31), dtype=np.int32)
        self.shadow_pool = np.concatenate((self.shadow_pool, room))
        for i, entries in enumerate(lists):
            self.set_shadow_list(first + i, entries)
        if len(self.others) != known:
            self.place_others()

    def _place_buildings(self, records: np.ndarray, land_cells: Sequence[LandCell]) -> None:
        """Fill the ``building_*`` fields of new cell ``records`` and the building arrays (a
        building the kernel cannot bound leaves its cell uncovered)."""
        balls, spans, planes = [], [], []
        ball_row, span_row, plane_row = len(self.building_shapes), len(self.door_spans), len(self.door_planes)
        for record, cell in zip(records, land_cells, strict=True):
            record["building_ball"] = -1
            reach = building_reach(cell.building) if cell.building is not None else None
            if reach is None:
                continue
            ball, doors = reach
            record["building"] = True
            if ball is not None:
                record["building_ball"] = ball_row + len(balls)
                balls.append(ball)
            record["building_doors"] = span_row + len(spans)
            record["num_building_doors"] = len(doors)
            for door in doors:
                spans.append((plane_row + len(planes), len(door)))
                planes.extend(door)
        if balls:
            self.building_shapes = np.concatenate((self.building_shapes, np.array(balls, dtype=np.float64)))
        if spans:
            self.door_spans = np.concatenate((self.door_spans, np.array(spans, dtype=np.int32)))
            self.door_planes = np.concatenate((self.door_planes, np.array(planes, dtype=np.float64)))

    def place_others(self) -> None:
        """Measure again where the other objects' shapes lie (new arrays; a static object only
        moves when something outside a step moves it)."""
        self.other_spans, self.other_shapes = shape_arrays(self.others)

    def refresh_uncovered(self) -> None:
        """Mark again the cells the kernel cannot sweep through (global detection adds and drops
        voyeurs as it runs)."""
        self.cells["uncovered"] = [_uncovered(cell) for cell in self.land_cells]

    def set_shadow_list(self, k: int, entries: Sequence[int]) -> None:
        """Make ``entries`` kernel cell ``k``'s shadow list (growing its room as needed)."""
        while len(entries) > self.cells[k]["shadow_capacity"]:
            self.grow(k)
        start = int(self.cells[k]["shadow_start"])
        self.shadow_pool[start : start + len(entries)] = entries
        self.cells[k]["num_shadows"] = len(entries)
        self.cells[k]["num_others"] = sum(1 for entry in entries if entry < 0)


def _uncovered(cell: LandCell) -> bool:
    """What the kernel leaves to the reference path in a land cell: watching voyeurs, an entry
    restriction, a building it cannot bound."""
    unbounded = cell.building is not None and building_reach(cell.building) is None
    return unbounded or bool(cell.voyeur_table) or bool(cell.restriction_obj)


def build_world_arrays(world: World, bodies: Sequence[PhysicsObj]) -> WorldArrays:
    """The kernel's view of ``world``'s landblocks, whose simulated ``bodies`` are numbered in
    table order."""
    landscape = world.landscape
    blocks = [landscape.get_landblock(key << 16) for key in sorted(landscape.landblocks())]
    arrays = WorldArrays(
        np.zeros(0, dtype=CELL), np.full(0x10000, -1, dtype=np.int32), np.zeros(0, dtype=np.int32), []
    )
    index = {id(body): i for i, body in enumerate(bodies)}
    arrays.add_landblocks([(block.lcell, int(block.water_type)) for block in blocks], index)
    return arrays


def _cell_records(land_cells: Sequence[LandCell], b: int, block_water_type: int) -> np.ndarray:
    """The records of landblock ``b``'s land cells (their triangles, water, what is uncovered);
    their shadow lists are set apart."""
    records = np.zeros(len(land_cells), dtype=CELL)
    for record, cell in zip(records, land_cells, strict=True):
        record["cell_id"] = cell.id
        record["landblock"] = b
        record["water_type"] = int(cell.water_type)
        record["block_water_type"] = block_water_type
        record["num_polys"] = len(cell.polygons)
        for p, poly in enumerate(cell.polygons):
            for v, vertex in enumerate(poly.vertices):
                record["vertex"][p, v] = (vertex.x, vertex.y, vertex.z)
            n = poly.plane.N
            record["plane"][p] = (n.x, n.y, n.z, poly.plane.d)
        record["uncovered"] = _uncovered(cell)
    return records


def _room(count: int) -> int:
    """The shadow slots a cell holding ``count`` shadows starts with: twice as many, at least
    ``INITIAL_SHADOW_CAPACITY``, a power of two."""
    room = INITIAL_SHADOW_CAPACITY
    while room < 2 * count:
        room *= 2
    return room


def shadow_entries(arrays: WorldArrays, k: int, cell: ObjCell, index: dict[int, int]) -> list[int]:
    """Kernel cell ``k``'s shadow list read from the reference ``cell``: bodies by their index in
    ``index`` (``id(body)`` → index), other objects as ``-1 - k`` (added to ``arrays.others``)."""
    entries = []
    for shadow in cell.shadow_objects:
        body = shadow.physobj
        number = index.get(id(body))
        if number is None:
            other = arrays.other_index.setdefault(id(body), len(arrays.others))
            if other == len(arrays.others):
                arrays.others.append(body)
            arrays.other_shadows[(other, k)] = shadow
            number = -1 - other
        entries.append(number)
    return entries
