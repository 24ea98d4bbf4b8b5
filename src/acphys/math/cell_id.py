"""Cell ids and the retail ``LandDefs`` coordinate conversions.

A cell id is ``0xXXYYnnnn``: ``XX``/``YY`` name the 192-m landblock, ``nnnn``
the cell inside it. Outdoor land cells have ``nnnn`` in 1..0x40
(``1 + 8·cx + cy`` for the 24-m cell at column ``cx``, row ``cy``); env cells
(indoors) have ``nnnn`` ≥ 0x100. "lcoord" is the global land-cell grid:
``x = 8·XX + cx``, ``y = 8·YY + cy``, both in [0, 2040).
"""

from __future__ import annotations

import math

from acphys.constants import BLOCK_LENGTH, CELL_LENGTH, CELLS_PER_BLOCK, EPSILON, MAX_LCOORD
from acphys.math.vector import Vector3, zero_vector
from acphys.precision import pack3, unpack3

FIRST_ENV_CELL = 0x100
LAST_LAND_CELL = 0x40


def landblock_of(cell_id: int) -> int:
    """The landblock id ``0xXXYY0000`` ... returned as ``0xXXYY`` (the high word)."""
    return (cell_id >> 16) & 0xFFFF


def cell_of(landblock: int, index: int) -> int:
    """The full cell id for a landblock ``0xXXYY`` and a cell index ``nnnn``."""
    return ((landblock & 0xFFFF) << 16) | (index & 0xFFFF)


def is_outdoor(cell_id: int) -> bool:
    """An outdoor land cell (``nnnn`` < 0x100)."""
    return (cell_id & 0xFFFF) < FIRST_ENV_CELL


def format_cell_id(cell_id: int) -> str:
    """``0xA9B40021`` style, as traces write it."""
    return f"0x{cell_id & 0xFFFFFFFF:08X}"


def _valid_cell_index(cell_id: int) -> bool:
    """The low word names a land cell (1..0x40), an env cell (0x100..0xFFFD) or the block (0xFFFF)."""
    low = cell_id & 0xFFFF
    return 1 <= low <= LAST_LAND_CELL or FIRST_ENV_CELL <= low <= 0xFFFD or low == 0xFFFF


def inbound_valid_cellid(cell_id: int) -> bool:
    """A land cell (1..0x40), env cell (0x100..0xFFFD) or block (0xFFFF) inside the world.

    Retail: LandDefs::inbound_valid_cellid @ 0x004979A0 (acclient.c:209467)
    """
    if not _valid_cell_index(cell_id):
        return False
    x = (cell_id >> 21) & 0x7F8
    y = (cell_id >> 13) & 0x7F8
    return x < MAX_LCOORD and y < MAX_LCOORD


def blockid_to_lcoord(block_id: int) -> tuple[int, int] | None:
    """The lcoord of a landblock's south-west cell, or None for id 0 or out of the world.

    Retail: LandDefs::blockid_to_lcoord @ 0x0043D680 (acclient.c:122259)
    """
    if not block_id:
        return None
    x = (block_id >> 21) & 0x7F8
    y = 8 * ((block_id >> 16) & 0xFF)
    if x < MAX_LCOORD and y < MAX_LCOORD:
        return x, y
    return None


def gid_to_lcoord(cell_id: int) -> tuple[int, int] | None:
    """The lcoord of an outdoor cell id, or None if it is not a valid land cell.

    Retail: LandDefs::gid_to_lcoord @ 0x00497A90 (acclient.c:209520)
    """
    # inbound_valid_cellid and is_outdoor, inlined: a land cell (1..0x40) of a block in the world
    low = cell_id & 0xFFFF
    if not 1 <= low <= LAST_LAND_CELL:
        return None
    block_x = (cell_id >> 21) & 0x7F8
    if block_x >= MAX_LCOORD or ((cell_id >> 13) & 0x7F8) >= MAX_LCOORD:
        return None
    index = low - 1
    x = block_x + (index >> 3)
    y = 8 * ((cell_id >> 16) & 0xFF) + (index & 7)
    if 0 <= x < MAX_LCOORD and 0 <= y < MAX_LCOORD:
        return x, y
    return None


def lcoord_to_gid(x: int, y: int) -> int:
    """The outdoor cell id of lcoord (x, y), or 0 outside the world.

    Retail: LandDefs::lcoord_to_gid @ 0x004A19A0 (acclient.c:218181)
    """
    if x < 0 or y < 0 or x >= MAX_LCOORD or y >= MAX_LCOORD:
        return 0
    return (((y >> 3) | 32 * (x & ~7)) << 16) | ((y & 7) + 8 * (x & 7) + 1)


def outdoor_cell_id(landblock: int, point: Vector3) -> int:
    """The outdoor cell of landblock ``0xXXYY`` holding the landblock-local ``point``.

    The point must lie inside the landblock ([0, 192) on x and y); use
    :func:`adjust_to_outside` for points that may have left it.
    """
    if not (0.0 <= point.x < BLOCK_LENGTH and 0.0 <= point.y < BLOCK_LENGTH):
        raise ValueError(f"point ({point.x}, {point.y}) is outside the 192-m landblock")
    cx = int(point.x // CELL_LENGTH)
    cy = int(point.y // CELL_LENGTH)
    return cell_of(landblock, 1 + CELLS_PER_BLOCK * cx + cy)


def get_outside_lcoord(cell_id: int, loc: Vector3) -> tuple[int, int] | None:
    """The lcoord of the land cell under the block-local point ``loc``, or None off the world.

    Retail: LandDefs::get_outside_lcoord @ 0x005A9B00 (acclient.c:467410)
    """
    if not _valid_cell_index(cell_id):
        return None
    # blockid_to_lcoord writes the block's lcoord even when it then reports failure.
    x = ((cell_id >> 21) & 0x7F8) + math.floor(loc.x / CELL_LENGTH)
    y = 8 * ((cell_id >> 16) & 0xFF) + math.floor(loc.y / CELL_LENGTH)
    if 0 <= x < MAX_LCOORD and 0 <= y < MAX_LCOORD:
        return x, y
    return None


def adjust_to_outside(cell_id: int, loc: Vector3) -> int:
    """Re-home a block-local point into the outdoor cell that holds it.

    Snaps |x|, |y| < EPSILON to 0, finds the land cell under the point, and
    rewrites ``loc`` in place to be local to that cell's landblock (retail
    subtracts multiples of ``flt_8EDE44 = 24.0 * 8.0``, acclient.c:800515). Returns
    the new cell id, or 0 when the point is off the world (``loc`` is then
    left with the snapping only). The moved x and y are stores into ``loc``'s
    ``float`` fields (acclient.c:467457-467460): a point just west of a block,
    moved 192 m east, rounds to float32.

    Retail: LandDefs::adjust_to_outside @ 0x005A9BC0 (acclient.c:467433)
    """
    lcoord = adjust_to_outside_lcoord(cell_id, loc)
    return lcoord_to_gid(*lcoord) if lcoord is not None else 0


def adjust_to_outside_lcoord(cell_id: int, loc: Vector3) -> tuple[int, int] | None:
    """:func:`adjust_to_outside`, giving the lcoord of the new cell (what ``gid_to_lcoord`` of
    the returned cell id gives), or None off the world; ``loc`` is rewritten the same way."""
    if not _valid_cell_index(cell_id):
        return None
    if abs(loc.x) < EPSILON:
        loc.x = 0.0
    if abs(loc.y) < EPSILON:
        loc.y = 0.0
    x, y = loc.x, loc.y
    # get_outside_lcoord, inlined: its cell index check has just passed
    lx = ((cell_id >> 21) & 0x7F8) + math.floor(x / CELL_LENGTH)
    ly = 8 * ((cell_id >> 16) & 0xFF) + math.floor(y / CELL_LENGTH)
    if not (0 <= lx < MAX_LCOORD and 0 <= ly < MAX_LCOORD):
        return None
    loc.x, loc.y, _ = unpack3(
        pack3(
            x - math.floor(x / BLOCK_LENGTH) * BLOCK_LENGTH,
            y - math.floor(y / BLOCK_LENGTH) * BLOCK_LENGTH,
            0.0,
        )
    )
    return lx, ly


def get_block_offset(cell_from: int, cell_to: int) -> Vector3:
    """The offset from ``cell_from``'s landblock origin to ``cell_to``'s: Δblock × 192 m, z = 0.

    Retail reads a cell id of 0 as "no block"; a ``cell_to`` of 0 makes it
    read ``cell_from`` raw as the lcoord, which is meaningless, so acphys
    raises instead.

    Retail: LandDefs::get_block_offset @ 0x0043E630 (acclient.c:123109)
    """
    if (cell_from >> 16) == (cell_to >> 16):
        return zero_vector()
    if not cell_to:
        raise ValueError("get_block_offset: the destination cell id is 0 (no cell)")
    fx, fy = ((cell_from >> 21) & 0x7F8, 8 * ((cell_from >> 16) & 0xFF)) if cell_from else (0, 0)
    tx, ty = (cell_to >> 21) & 0x7F8, 8 * ((cell_to >> 16) & 0xFF)
    return Vector3((tx - fx) * CELL_LENGTH, (ty - fy) * CELL_LENGTH, 0.0)
