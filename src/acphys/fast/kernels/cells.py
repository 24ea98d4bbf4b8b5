"""Kernel cells: which land cells a sweep's spheres touch, the terrain under a point, and the
shadows of other bodies in a cell.

Ports of :mod:`acphys.world.land_cell` and of the outdoor half of
:meth:`acphys.world.obj_cell.ObjCell.find_cell_list`, over the :data:`~acphys.fast.layout.CELL`
records. A cell id the kernel does not know (an env cell, a land cell of a landblock the arrays
lack) gives the index -1, and whoever meets one hands the step back (``BAIL``; for a land cell
``R_UNREAD``, and the engine reads its landblock and runs the step again).
"""

from __future__ import annotations

import math

from numba import njit

from acphys.constants import CELL_LENGTH, EPSILON, MAX_LCOORD
from acphys.fast.kernels.context import cells_of, landblock_index_of
from acphys.fast.kernels.frame import adjust_to_outside_lcoord, f32, lcoord_to_gid
from acphys.fast.layout import MAX_CELLS

#: A transition state only the kernel returns: "the reference path must take this step".
BAIL = -1

#: Why a step was handed back (``TRANSITION.bail``, counted by the engine): the names are
#: :data:`BAIL_REASONS`, by code.
BAIL_REASONS = (
    "none",
    "a static object within reach",
    "stepping up onto a body, landing on one, or a perfect clip",
    "a body the kernel cannot collide with",
    "a first touch the kernel does not report (a missile's, a callback's, as the environment)",
    "a cell the kernel does not know (indoors, a building or watchers)",
    "leaving the known cells",
    "the water depth of a partly wet cell",
    "a walkable polygon, a collision or a back-face hit",
    "nesting deeper than the compiled levels",
    "landing or leaving the ground with a movement manager",
    "a full journal, log, list or collision table",
    "an animation hook",
    "a collision record ending with a body the kernel does not answer for",
    "a step down past a sphere (a root of a negative number)",
    "a land cell of a landblock the world does not make",
    "an interpolation node given up (a failed audit or a blip)",
)
R_STATIC, R_CLIMB, R_SHAPE, R_CONTACT, R_CELL, R_NO_CELL, R_WATER = 1, 2, 3, 4, 5, 6, 7
R_SHAPES, R_DEEP, R_MOTION, R_FULL, R_HOOK, R_RECORDS, R_ROOT = 8, 9, 10, 11, 12, 13, 14
#: A land cell of a landblock the arrays lack (``TRANSITION.unread_cell``): the engine reads the
#: landblock (the world makes one without terrain past its edge) and the step runs again.
R_UNREAD = 15
#: An interpolation audit failed or a blip is due (:mod:`acphys.fast.kernels.interpolation`).
R_GLIDE = 16


@njit(cache=True, inline="always", _nrt=False)
def bail(tr, reason):
    """Hand the step back to the reference path, saying why."""
    tr.bail = reason
    return BAIL


@njit(cache=True, inline="always", _nrt=False)
def cell_index(landblock_index, cell_id):
    """The kernel index of land cell ``cell_id``, or -1."""
    low = cell_id & 0xFFFF
    if low < 1 or low > 64:
        return -1
    block = landblock_index[(cell_id >> 16) & 0xFFFF]
    if block < 0:
        return -1
    return 64 * block + low - 1


@njit(cache=True, _nrt=False)
def cell_array_clear(tr):
    """``CELLARRAY``: ``num_cells = 0; added_outside = 0`` (acclient.c:346987-346988)."""
    tr.num_cells = 0
    tr.added_outside = False


@njit(cache=True, _nrt=False)
def cell_array_add(w, tr, cell_id):
    """Append ``cell_id`` unless it is there; False when the array is full (the step bails).

    Port of :meth:`acphys.world.obj_cell.CellArray.add_cell`.
    Retail: CELLARRAY::add_cell @ 0x006B4FF0 (acclient.c:718895)
    """
    for i in range(tr.num_cells):
        if tr.cell_ids[i] == cell_id:
            return True
    if tr.num_cells >= MAX_CELLS:
        return False
    tr.cell_ids[tr.num_cells] = cell_id
    tr.cells[tr.num_cells] = cell_index(landblock_index_of(w), cell_id)
    tr.num_cells += 1
    return True


@njit(cache=True, _nrt=False)
def add_outside_cell(w, tr, x, y):
    """Add the land cell at global lcoord ``(x, y)`` when it is inside the world.

    Port of :meth:`acphys.world.land_cell.LandCell.add_outside_cell`.
    Retail: CLandCell::add_outside_cell @ 0x00532EC0 (acclient.c:354974)
    """
    if 0 <= x < MAX_LCOORD and 0 <= y < MAX_LCOORD:
        return cell_array_add(w, tr, lcoord_to_gid(x, y))
    return True


@njit(cache=True, _nrt=False)
def check_add_cell_boundary(w, tr, px, py, x, y, incell_max, incell_min):
    """Add the neighbours of cell ``(x, y)`` a circle at ``(px, py)`` within it reaches.

    Port of :meth:`acphys.world.land_cell.LandCell.check_add_cell_boundary`.
    Retail: CLandCell::check_add_cell_boundary @ 0x00533260 (acclient.c:355161)
    """
    ok = True
    if px > incell_max:
        ok &= add_outside_cell(w, tr, x + 1, y)
        if py > incell_max:
            ok &= add_outside_cell(w, tr, x + 1, y + 1)
        if py < incell_min:
            ok &= add_outside_cell(w, tr, x + 1, y - 1)
    if px < incell_min:
        ok &= add_outside_cell(w, tr, x - 1, y)
        if py > incell_max:
            ok &= add_outside_cell(w, tr, x - 1, y + 1)
        if py < incell_min:
            ok &= add_outside_cell(w, tr, x - 1, y - 1)
    if py > incell_max:
        ok &= add_outside_cell(w, tr, x, y + 1)
    if py < incell_min:
        ok &= add_outside_cell(w, tr, x, y - 1)
    return ok


@njit(cache=True, inline="always", _nrt=False)
def _footprint_seen(tr, s):
    """Whether an earlier global sphere has sphere ``s``'s x, y and radius (an upright human's
    two): the cells it overlaps are then in the array already."""
    for t in range(s):
        if (
            tr.global_sphere[t, 0] == tr.global_sphere[s, 0]
            and tr.global_sphere[t, 1] == tr.global_sphere[s, 1]
            and tr.global_sphere[t, 3] == tr.global_sphere[s, 3]
        ):
            return True
    return False


@njit(cache=True, inline="always", _nrt=False)
def cell_clear_of_edges(cell_id, x, y, radius):
    """The land cell of ``cell_id``'s landblock whose square holds the circle at block-local
    ``(x, y)`` clear of its edges as :func:`add_all_outside_cells` measures them (it adds that cell
    and no neighbour), or 0 when the circle is not so placed (or ``cell_id`` is no land cell of a
    landblock on the world).

    There ``adjust_to_outside_lcoord`` leaves ``x`` and ``y`` as they are (at least EPSILON, in the
    landblock) and the in-cell coordinates ``x - 24·column`` are exact (a float32 value less an
    integer it exceeds), so the test below is the one ``check_add_cell_boundary`` makes. A column
    the product by 1/24 puts one off fails the test (the in-cell coordinate leaves [0, 24)), and
    so does a NaN.

    Not retail: a shortcut through ``CLandCell::add_all_outside_cells`` (acclient.c:355345) for a
    sphere well inside a cell.
    """
    low = cell_id & 0xFFFF
    if not (1 <= low <= 64) or (cell_id >> 24) & 0xFF == 0xFF or (cell_id >> 16) & 0xFF == 0xFF:
        return 0
    column = math.floor(x * (1.0 / CELL_LENGTH))
    row = math.floor(y * (1.0 / CELL_LENGTH))
    if not (0.0 <= column < 8.0 and 0.0 <= row < 8.0 and x >= EPSILON and y >= EPSILON):
        return 0
    in_x = x - column * CELL_LENGTH
    in_y = y - row * CELL_LENGTH
    max_rad = f32(CELL_LENGTH - radius)
    if radius <= in_x <= max_rad and radius <= in_y <= max_rad:
        return (cell_id & 0xFFFF0000) | (8 * int(column) + int(row) + 1)
    return 0


@njit(cache=True, _nrt=False)
def add_all_outside_cells(w, tr, cell_id):
    """Once per array: every land cell the global spheres (in ``cell_id``'s landblock) overlap.

    A sphere over the same ground point with the same radius as an earlier one is skipped: the
    cells, their order and the answer are those of the earlier one (z is never read). A sphere
    clear of its cell's edges adds that cell alone (:func:`cell_clear_of_edges`).

    Port of :meth:`acphys.world.land_cell.LandCell.add_all_outside_cells` (the kernel always has
    spheres). Retail: CLandCell::add_all_outside_cells @ 0x00533630 (acclient.c:355345)
    """
    if tr.added_outside:
        return True
    tr.added_outside = True
    ok = True
    for s in range(tr.num_sphere):
        if _footprint_seen(tr, s):
            continue
        radius = tr.global_sphere[s, 3]
        clear = cell_clear_of_edges(cell_id, tr.global_sphere[s, 0], tr.global_sphere[s, 1], radius)
        if clear:
            ok &= cell_array_add(w, tr, clear)
            continue
        center = (tr.global_sphere[s, 0], tr.global_sphere[s, 1], tr.global_sphere[s, 2])
        on_world, lx, ly, point = adjust_to_outside_lcoord(cell_id, center)
        if not on_world:
            break
        in_x = f32(point[0] - math.floor(point[0] / CELL_LENGTH) * CELL_LENGTH)
        in_y = f32(point[1] - math.floor(point[1] / CELL_LENGTH) * CELL_LENGTH)
        max_rad = f32(CELL_LENGTH - radius)
        ok &= add_outside_cell(w, tr, lx, ly)
        ok &= check_add_cell_boundary(w, tr, in_x, in_y, lx, ly, max_rad, radius)
    return ok


@njit(cache=True, _nrt=False)
def point_in_poly2d(w, k, p, px, py):
    """Whether ``(px, py)`` lies inside triangle ``p`` of cell ``k`` projected on the xy plane
    (side POSITIVE: a positive cross value is outside).

    Port of :meth:`acphys.geometry.polygon.Polygon.point_in_poly2D`.
    Retail: CPolygon::point_in_poly2D @ 0x00538060 (acclient.c:359419)
    """
    vertex = cells_of(w)[k].vertex
    fx, fy = vertex[p, 0, 0], vertex[p, 0, 1]
    for i in range(2, -1, -1):
        vx, vy = vertex[p, i, 0], vertex[p, i, 1]
        ey = fy - vy
        ex = vx - fx
        value = -(ey * vx) - ex * vy + ex * py + ey * px
        if value > 0.0:
            return False
        fx, fy = vx, vy
    return True


@njit(cache=True, _nrt=False)
def find_terrain_poly(w, k, px, py):
    """The first of cell ``k``'s triangles whose xy projection holds the point, or -1.

    Port of :meth:`acphys.world.land_cell.LandCell.find_terrain_poly`.
    Retail: CLandCell::find_terrain_poly @ 0x00532CF0 (acclient.c:354858)
    """
    for p in range(cells_of(w)[k].num_polys):
        if point_in_poly2d(w, k, p, px, py):
            return p
    return -1


@njit(cache=True, inline="always", _nrt=False)
def point_in_cell(w, k, px, py):
    """Whether the landblock-local point lies over one of cell ``k``'s triangles.

    Port of :meth:`acphys.world.land_cell.LandCell.point_in_cell` (for cells with terrain; a
    cell without is its 24-m square, low edges closed).
    Retail: CLandCell::point_in_cell @ 0x00532D40 (acclient.c:354880)
    """
    cell = cells_of(w)[k]
    if cell.num_polys == 0:
        low = (cell.cell_id & 0xFFFF) - 1
        x0 = (low // 8) * CELL_LENGTH
        y0 = (low % 8) * CELL_LENGTH
        return x0 <= px < x0 + CELL_LENGTH and y0 <= py < y0 + CELL_LENGTH
    return find_terrain_poly(w, k, px, py) >= 0
