"""Outdoor terrain: retail ``CLandBlockStruct`` and the terrain queries of ``CLandCell``.

A landblock is 192 m square: 8×8 land cells of 24 m over a 9×9 grid of vertices. Vertex
``(x, y)`` (``x`` east, ``y`` north, 0..8) is record index ``x*9 + y``; its height byte indexes
the region's 256-entry height table and its 16-bit terrain word carries the terrain type in bits
2..6 (``(word >> 2) & 0x1F``). Each cell is cut into two triangles along one diagonal, chosen by a
32-bit hash of the cell's global coordinates (``split_hash``). Everything here is landblock-local.

Height table: retail reads ``LandDefs::Land_Height_Table`` from the region record (DAT
0x13000000). acphys ships no default: no public source with the 256 values could be found and
checked, so every ``LandBlockStruct`` takes the table as input, validated as
``LandDefs::set_height_table`` does (256 entries, each in [0, 800]) and kept as float32 (the
table is ``float``; so are the vertices, ``ConstructVertices`` stores the heights in them).

Float constants the decompilation names but does not print (``flt_844C88``, ``flt_844C8C``,
``flt_844AF0``) are read from their use: 192.0 (block length, divided by the 8 polygons a side
to give the 24-m vertex spacing), 12.0 (half a cell: the land-cell origins ``(2i+1)·12`` and the
nearest-vertex tests). ACE's LandblockStruct.cs uses the same values.

Divergences from ACE (the decompilation wins):

- ACE compares ``hash * 2.3283064e-10 < 0.5`` with a float64 literal slightly below 2^-32, so
  hashes 0x80000000..0x80000021 split SE-NW in ACE and SW-NE in retail, whose literal is the
  float32 2^-32 (an exact top-bit test). No global cell coordinate in 0..2047 hashes into that
  range, so the worlds agree; ``cut_from_hash`` pins the retail test.
- ACE's ``calc_water_depth`` picks the nearest vertex with ``coord % 24 >= 12``; retail's test is
  ``(2i+1)·12 >= coord`` (as ``CLandBlock::get_terrain`` prints it), so a point exactly on a
  cell's centre line takes the west / south vertex in retail and the east / north one in ACE.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from enum import IntEnum

from acphys.constants import CELL_LENGTH, CELLS_PER_BLOCK
from acphys.geometry.plane import Sidedness
from acphys.geometry.polygon import Polygon, SidesType
from acphys.math.cell_id import LAST_LAND_CELL, inbound_valid_cellid
from acphys.math.vector import Vector3
from acphys.precision import f32

#: Vertices along a landblock side (``side_vertex_count`` at full detail).
SIDE_VERTEX_COUNT = CELLS_PER_BLOCK + 1
#: Height bytes / terrain words in a landblock record (9×9).
NUM_VERTICES = SIDE_VERTEX_COUNT * SIDE_VERTEX_COUNT
#: Entries in ``LandDefs::Land_Height_Table``.
HEIGHT_TABLE_SIZE = 256
#: ``set_height_table`` accepts entries in [0, sky height 1000 - max object height 200]
#: (acclient.c:467329; the two values from ``LandDefs::get_vars``, acclient.c:467316-467317).
MAX_LAND_HEIGHT = 1000.0 - 200.0
#: Half a land cell (``flt_844C8C`` / ``flt_844AF0``): cell centres are at ``(2i+1)·12``.
HALF_CELL = CELL_LENGTH / 2.0

#: ``calc_water_depth`` for a point whose nearest vertex is solid ground (acclient.c:353707).
SOLID_VERTEX_WATER_DEPTH = f32(0.1)
#: ``calc_water_depth`` for a point whose nearest vertex is water (acclient.c:353701).
WATER_VERTEX_WATER_DEPTH = f32(0.44999999)
#: ``get_water_depth`` of a cell whose four vertices are all water (acclient.c:347247).
ENTIRELY_WATER_DEPTH = f32(0.89999998)


class SurfChar(IntEnum):
    """Retail ``SURFCHAR`` (acclient.h:3618): what a terrain type is underfoot."""

    SOLID = 0
    WATER = 1


class WaterType(IntEnum):
    """Retail ``LandDefs::WaterType`` (acclient.h:4103), per cell and per landblock."""

    NOT_WATER = 0
    PARTIALLY_WATER = 1
    ENTIRELY_WATER = 2


#: Retail ``TERRAIN_SURF_CHAR`` / ``TERRAIN_SURF_CHAR_0`` (acclient_data.h:2356, 2395, identical):
#: terrain types 16..20 (the water types) are WATER, all others SOLID.
TERRAIN_SURF_CHAR: tuple[SurfChar, ...] = tuple(
    SurfChar.WATER if 16 <= t <= 20 else SurfChar.SOLID for t in range(32)
)

_U32 = 0xFFFFFFFF


def terrain_type(word: int) -> int:
    """The terrain type (0..31) of a terrain word: bits 2..6 (acclient.c:352035, 353629)."""
    return (word >> 2) & 0x1F


def split_hash(x: int, y: int) -> int:
    """The uint32 hash ``ConstructPolygons`` computes for the land cell at global ``(x, y)``:
    ``y·(214614067·x + 1813693831) - 1109124029·x - 1369149221``, wrapped to 32 bits
    (acclient.c:354046; the int32 wrap and the unsigned read agree modulo 2^32).
    """
    return (y * (214614067 * x + 1813693831) - 1109124029 * x - 1369149221) & _U32


def cut_from_hash(value: int) -> bool:
    """Whether a split hash cuts the cell SW-NE: retail tests ``hash · 2^-32 >= 0.5``
    (acclient.c:354050, the literal is the float32 2^-32), i.e. the top bit is set.
    """
    return value >= 0x80000000


def sw_to_ne_cut(x: int, y: int) -> bool:
    """``SWtoNEcut`` of the land cell at global lcoord ``(x, y)`` (acclient.c:354050-354068)."""
    return cut_from_hash(split_hash(x, y))


def set_height_table(table: Iterable[float]) -> tuple[float, ...]:
    """Check a region height table and return it as a tuple of float32 heights.

    The table is retail's ``float[256]`` read from the region record, so each entry is narrowed
    to float32 before it is checked and kept. Retail copies entries while each is ``>= 0`` and
    ``<= 800`` (so NaN stops it) and returns 0 on the first bad one, leaving the table
    half-replaced; acphys raises ``ValueError`` instead.

    Retail: LandDefs::set_height_table @ 0x005A99E0 (acclient.c:467321)
    """
    values = tuple(table)
    if len(values) != HEIGHT_TABLE_SIZE:
        raise ValueError(f"height table needs {HEIGHT_TABLE_SIZE} entries, got {len(values)}")
    heights = []
    for i, value in enumerate(values):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ValueError(f"height table entry {i} is not a number: {value!r}")
        # an int is exact (and one beyond the float range fails the test as it is)
        height = f32(value) if isinstance(value, float) else value
        if not (0.0 <= height <= MAX_LAND_HEIGHT):
            raise ValueError(f"height table entry {i} = {value!r} is outside [0, {MAX_LAND_HEIGHT}]")
        heights.append(float(height))  # an int in [0, 800] is a float32
    return tuple(heights)


def _check_words(name: str, values: Iterable[int], limit: int) -> tuple[int, ...]:
    """81 integers in [0, limit], or a ValueError naming what is wrong."""
    words = tuple(values)
    if len(words) != NUM_VERTICES:
        raise ValueError(f"a landblock needs {NUM_VERTICES} {name}, got {len(words)}")
    for i, word in enumerate(words):
        if isinstance(word, bool) or not isinstance(word, int) or not 0 <= word <= limit:
            raise ValueError(f"{name}[{i}] = {word!r} is not an integer in [0, {limit:#x}]")
    return words


def _check_point(point: Vector3) -> None:
    if not (math.isfinite(point.x) and math.isfinite(point.y)):
        raise ValueError(f"terrain query point must have finite x and y, got {point!r}")


def _land_cell_xy(cell_id: int) -> tuple[int, int]:
    """Cell column and row (0..7) of a valid outdoor cell id (acclient.c:353669-353670)."""
    low = cell_id & 0xFFFF
    if not (inbound_valid_cellid(cell_id) and 1 <= low <= LAST_LAND_CELL):
        raise ValueError(f"{cell_id:#010x} is not a valid outdoor land cell id")
    return (low - 1) >> 3, (low - 1) & 7


class LandBlockStruct:
    """Retail ``CLandBlockStruct`` at full detail: vertices, the two triangles of each cell,
    the cut directions and the water types, built from one landblock record.

    ``polygons[2*(8*cx + cy) + k]`` is triangle ``k`` of cell ``(cx, cy)``; ``sw_to_ne_cut`` and
    ``cell_water_types`` are indexed ``8*cx + cy`` (the outdoor cell id's low word minus one).
    """

    __slots__ = (
        "block_id",
        "cell_water_types",
        "height",
        "height_table",
        "polygons",
        "sw_to_ne_cut",
        "terrain",
        "vertices",
        "water_type",
    )

    def __init__(
        self,
        block_id: int,
        height: Sequence[int] | bytes,
        terrain: Sequence[int],
        height_table: Iterable[float],
    ) -> None:
        """``block_id`` is the landblock's id (``0xXXYYFFFF``; only the high word is read),
        ``height`` the 81 height bytes, ``terrain`` the 81 terrain words, ``height_table`` the
        region's 256 heights.
        """
        if isinstance(block_id, bool) or not isinstance(block_id, int) or not 0 < block_id <= _U32:
            raise ValueError(f"block_id must be a nonzero 32-bit landblock id, got {block_id!r}")
        self.block_id = block_id
        self.height = _check_words("height bytes", height, 0xFF)
        self.terrain = _check_words("terrain words", terrain, 0xFFFF)
        self.height_table = set_height_table(height_table)
        self.vertices: list[Vector3] = []
        self.polygons: list[Polygon] = []
        self.sw_to_ne_cut: list[bool] = []
        self.cell_water_types: list[WaterType] = []
        self.water_type = WaterType.NOT_WATER
        self.construct_vertices()
        self.construct_polygons()
        self.calc_water()

    def __repr__(self) -> str:
        return f"LandBlockStruct({self.block_id:#010x}, water_type={self.water_type.name})"

    # --- construction ---------------------------------------------------------------------

    def construct_vertices(self) -> None:
        """Vertex ``(x, y)`` = ``(24x, 24y, table[height[9x + y]])``.

        Retail: CLandBlockStruct::ConstructVertices @ 0x005328D0 (acclient.c:354620)
        """
        table, height = self.height_table, self.height
        self.vertices = [
            Vector3(ix * CELL_LENGTH, iy * CELL_LENGTH, table[height[ix * SIDE_VERTEX_COUNT + iy]])
            for ix in range(SIDE_VERTEX_COUNT)
            for iy in range(SIDE_VERTEX_COUNT)
        ]

    def construct_polygons(self) -> None:
        """Cut every cell into two single-sided triangles, wound counter-clockwise from above.

        With SW, SE, NE, NW the cell's corners: a SW-NE cut gives (SW, SE, NE) and
        (SW, NE, NW); otherwise the SE-NW cut gives (SW, SE, NW) and (NE, NW, SE).

        Retail: CLandBlockStruct::ConstructPolygons @ 0x00531D10 (acclient.c:354000)
        """
        block_x = (self.block_id >> 21) & 0x7F8
        block_y = 8 * ((self.block_id >> 16) & 0xFF)
        v = self.vertices
        self.polygons = []
        self.sw_to_ne_cut = []
        for cx in range(CELLS_PER_BLOCK):
            for cy in range(CELLS_PER_BLOCK):
                sw = v[cx * SIDE_VERTEX_COUNT + cy]
                nw = v[cx * SIDE_VERTEX_COUNT + cy + 1]
                se = v[(cx + 1) * SIDE_VERTEX_COUNT + cy]
                ne = v[(cx + 1) * SIDE_VERTEX_COUNT + cy + 1]
                cut = sw_to_ne_cut(block_x + cx, block_y + cy)
                corners = ((sw, se, ne), (sw, ne, nw)) if cut else ((sw, se, nw), (ne, nw, se))
                self.sw_to_ne_cut.append(cut)
                # AddPolygon leaves sides_type as InitPVArrays set it: 0 (acclient.c:353211).
                self.polygons.extend(Polygon(list(tri), SidesType.SINGLE) for tri in corners)

    def calc_cell_water(self, cell_x: int, cell_y: int) -> tuple[bool, bool]:
        """``(has_water, all_water)`` over the cell's four corner vertices.

        Retail: CLandBlockStruct::CalcCellWater @ 0x00531550 (acclient.c:353607)
        """
        chars = [
            TERRAIN_SURF_CHAR[terrain_type(self.terrain[ix * SIDE_VERTEX_COUNT + iy])]
            for ix in (cell_x, cell_x + 1)
            for iy in (cell_y, cell_y + 1)
        ]
        return SurfChar.WATER in chars, all(c == SurfChar.WATER for c in chars)

    def calc_water(self) -> None:
        """Set each cell's water type, and the block's: ENTIRELY only when every cell is,
        NOT_WATER when no cell has any water, PARTIALLY otherwise.

        Retail: CLandBlockStruct::CalcWater @ 0x005327E0 (acclient.c:354565)
        """
        self.cell_water_types = []
        for cx in range(CELLS_PER_BLOCK):
            for cy in range(CELLS_PER_BLOCK):
                has_water, all_water = self.calc_cell_water(cx, cy)
                if not has_water:
                    self.cell_water_types.append(WaterType.NOT_WATER)
                elif all_water:
                    self.cell_water_types.append(WaterType.ENTIRELY_WATER)
                else:
                    self.cell_water_types.append(WaterType.PARTIALLY_WATER)
        if all(t == WaterType.ENTIRELY_WATER for t in self.cell_water_types):
            self.water_type = WaterType.ENTIRELY_WATER
        elif any(t != WaterType.NOT_WATER for t in self.cell_water_types):
            self.water_type = WaterType.PARTIALLY_WATER
        else:
            self.water_type = WaterType.NOT_WATER

    # --- lookups --------------------------------------------------------------------------

    def vertex(self, x: int, y: int) -> Vector3:
        """Vertex ``(x, y)``, 0..8 each."""
        if not (0 <= x < SIDE_VERTEX_COUNT and 0 <= y < SIDE_VERTEX_COUNT):
            raise ValueError(f"vertex ({x}, {y}) is outside the 9x9 grid")
        return self.vertices[x * SIDE_VERTEX_COUNT + y]

    def cell_polygons(self, cell_x: int, cell_y: int) -> tuple[Polygon, Polygon]:
        """The two triangles of cell ``(cell_x, cell_y)``, 0..7 each, in retail order."""
        if not (0 <= cell_x < CELLS_PER_BLOCK and 0 <= cell_y < CELLS_PER_BLOCK):
            raise ValueError(f"cell ({cell_x}, {cell_y}) is outside the 8x8 landblock")
        index = 2 * (cell_x * CELLS_PER_BLOCK + cell_y)
        return self.polygons[index], self.polygons[index + 1]

    def cell_of_point(self, point: Vector3) -> tuple[int, int]:
        """The cell ``(cx, cy)`` whose square holds the landblock-local ``point``."""
        _check_point(point)
        block = CELL_LENGTH * CELLS_PER_BLOCK
        if not (0.0 <= point.x < block and 0.0 <= point.y < block):
            raise ValueError(f"point ({point.x}, {point.y}) is outside the 192-m landblock")
        return int(point.x // CELL_LENGTH), int(point.y // CELL_LENGTH)

    def find_terrain_poly(self, point: Vector3, cell_id: int | None = None) -> Polygon | None:
        """The triangle of the cell that ``point`` lies over (2D test, edges count as inside).

        Retail tests the cell's two triangles in order with ``point_in_poly2D(origin, 0)``, so a
        point on the diagonal gets the first. ``cell_id`` names the cell to search (as retail's
        caller does; a point outside it gives None); by default the cell under the point.

        Retail: CLandCell::find_terrain_poly @ 0x00532CF0 (acclient.c:354858)
        """
        _check_point(point)
        cell = self.cell_of_point(point) if cell_id is None else _land_cell_xy(cell_id)
        for poly in self.cell_polygons(*cell):
            if poly.point_in_poly2D(point, Sidedness.POSITIVE):
                return poly
        return None

    def get_height(self, point: Vector3) -> float:
        """The terrain height under the landblock-local ``point``: ``find_terrain_poly`` then
        ``Plane::set_height`` on that triangle's plane, as ``CLandBlock::get_land_scenes`` does
        (acclient.c:352698-352702; ``adjust_scene_obj_height`` inlines the same, 352219-352222)."""
        poly = self._poly_under(point)
        foot = point.copy()
        # Terrain triangles project onto non-degenerate xy triangles, so |N.z| > EPSILON always.
        poly.plane.set_height(foot)
        return foot.z

    def get_normal(self, point: Vector3) -> Vector3:
        """The unit normal of the terrain triangle under the landblock-local ``point``."""
        return self._poly_under(point).plane.N.copy()

    def _poly_under(self, point: Vector3) -> Polygon:
        poly = self.find_terrain_poly(point)
        if poly is None:  # Unreachable: the two triangles tile their cell's square.
            raise ValueError(f"no terrain triangle under {point!r}")
        return poly

    # --- terrain type and water -----------------------------------------------------------

    def _nearest_vertex_index(self, cell_x: int, cell_y: int, point: Vector3) -> int:
        """Record index of the cell corner nearest ``point``: west when the cell centre line
        ``(2cx+1)·12 >= x``, south when ``y <= (2cy+1)·12`` (acclient.c:352030-352041).
        """
        _check_point(point)
        ix = cell_x if (2 * cell_x + 1) * HALF_CELL >= point.x else cell_x + 1
        iy = cell_y if point.y <= (2 * cell_y + 1) * HALF_CELL else cell_y + 1
        return ix * SIDE_VERTEX_COUNT + iy

    def get_terrain(self, cell_id: int, point: Vector3) -> int:
        """The terrain type (0..31) of the corner of cell ``cell_id`` nearest the
        landblock-local ``point``.

        Retail: CLandBlock::get_terrain @ 0x0052FB70 (acclient.c:352008)
        """
        cell_x, cell_y = _land_cell_xy(cell_id)
        return terrain_type(self.terrain[self._nearest_vertex_index(cell_x, cell_y, point)])

    def find_terrain(self, cell_id: int, point: Vector3) -> SurfChar:
        """``TERRAIN_SURF_CHAR`` of ``get_terrain`` (retail first makes ``point`` local to the
        cell's landblock; here it already is).

        Retail: CLandCell::find_terrain @ 0x00532E20 (acclient.c:354950)
        """
        return TERRAIN_SURF_CHAR[self.get_terrain(cell_id, point)]

    def walkable_surface_type(self, cell_id: int, walkable: Polygon, point: Vector3) -> SurfChar:
        """SOLID unless ``walkable`` is one of the cell's two triangles (by identity); then
        ``find_terrain`` at ``point``.

        Retail: CLandCell::walkable_surface_type @ 0x00533190 (acclient.c:355121)
        """
        if not any(walkable is poly for poly in self.cell_polygons(*_land_cell_xy(cell_id))):
            return SurfChar.SOLID
        return self.find_terrain(cell_id, point)

    def cell_water_type(self, cell_id: int) -> WaterType:
        """The ``water_type`` ``calc_water`` gave the outdoor cell ``cell_id``."""
        cell_x, cell_y = _land_cell_xy(cell_id)
        return self.cell_water_types[cell_x * CELLS_PER_BLOCK + cell_y]

    def calc_water_depth(self, cell_id: int, point: Vector3) -> float:
        """Water depth at ``point`` from the cell corner nearest it: 0.45 for a water corner,
        0.1 for a solid one.

        The decompilation lost both coordinate compares (only the x87 condition bits remain,
        acclient.c:353679); acphys reads them as ``CLandBlock::get_terrain`` prints its own
        (same branch order, same flag sets), which ties the centre lines to west and south.

        Retail: CLandBlockStruct::calc_water_depth @ 0x005315F0 (acclient.c:353645)
        """
        cell_x, cell_y = _land_cell_xy(cell_id)
        word = self.terrain[self._nearest_vertex_index(cell_x, cell_y, point)]
        if TERRAIN_SURF_CHAR[terrain_type(word)] == SurfChar.WATER:
            return WATER_VERTEX_WATER_DEPTH
        return SOLID_VERTEX_WATER_DEPTH

    def get_water_depth(self, cell_id: int, point: Vector3) -> float:
        """``CObjCell::get_water_depth`` for outdoor cell ``cell_id``: 0 for a dry cell, 0.9 for
        an all-water cell, ``calc_water_depth`` for a partly wet one.

        Retail: CObjCell::get_water_depth @ 0x0052B8A0 (acclient.c:347232)
        """
        water = self.cell_water_type(cell_id)
        if water == WaterType.NOT_WATER:
            return 0.0
        if water == WaterType.ENTIRELY_WATER:
            return ENTIRELY_WATER_DEPTH
        return self.calc_water_depth(cell_id, point)
