"""The kernel's broad phase: bodies filed by the square of the ground their origin is over.

Not retail. A cell's ``find_obj_collisions`` asks every body shadowed there; a body whose spheres
stay out of reach of the sweep can only answer OK and change nothing (the reference's own
shortcut, :meth:`acphys.body.reports.CollisionReports.out_of_reach`). So the kernel asks only the
bodies filed near the sweep: each body is filed by the ``TILE``-metre square (landblock-global
metres) under its origin, in a hash of squares whose chains run through the records
(``grid_bucket``, ``grid_next``, ``grid_prev``), and a sweep looks in every square within the
reach of its spheres plus the longest reach of any body (``grid[MAX_REACH]``). The hash has
four buckets a body or more (:func:`heads_for`), so few far bodies share a near square's chain.
Any body that
could answer other than OK is found that way, and the kernel hands such a step to the reference
path; if none could, the reference would have answered OK too, whatever its list order.

The searches are across the ground, so a body's reach there is what counts (:func:`reach_now`):
while it stands upright (its quaternion turns it about z alone: ``x`` and ``y`` are exactly
zero, as a yaw, a turn about z or a slerp between two such keeps them), its spheres' centres
keep their distance from its vertical axis, and it reaches ``hreach`` (a human: 0.48 m);
otherwise as far as any centre is from its origin, ``reach`` (a human: 1.83 m).
``grid[MAX_REACH]`` is the longest such reach of any body since the records were read, raised
after each update that lengthens one.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from acphys.constants import BLOCK_LENGTH

#: The side of a grid square, in metres.
TILE = 4.0
#: The hash's buckets are a block of squares ``2 ** bits`` a side (``bits`` from ``MIN_BITS`` to
#: ``MAX_BITS``: 65,536 to 4,194,304 buckets, 1 to 8 km of ground).
MIN_BITS = 8
MAX_BITS = 11
#: ``grid`` (float64) slots: the longest reach, and the hash's ``bits``.
MAX_REACH = 0
SPAN_BITS = 1
GRID_SLOTS = 2
#: A sweep whose search would cover more squares than this asks the cell's whole list instead.
MAX_TILES = 64


@njit(cache=True, inline="always", _nrt=False)
def block_origin(cell_id):
    """The landblock-global metres of ``cell_id``'s landblock's south-west corner."""
    return ((cell_id >> 24) & 0xFF) * BLOCK_LENGTH, ((cell_id >> 16) & 0xFF) * BLOCK_LENGTH


def heads_for(count: int) -> tuple[np.ndarray, int]:
    """Empty chain heads for ``count`` bodies, at least four buckets a body, and their ``bits``."""
    bits = MIN_BITS
    while 4**bits < 4 * count and bits < MAX_BITS:
        bits += 1
    return np.full(4**bits, -1, dtype=np.int32), bits


@njit(cache=True, inline="always", _nrt=False)
def span_bits(grid):
    """The hash's ``bits`` (``grid[SPAN_BITS]``)."""
    return np.int64(grid[SPAN_BITS])


@njit(cache=True, inline="always", _nrt=False)
def bucket_of(tx, ty, bits):
    """The hash bucket of square ``(tx, ty)``: the square's place in its block of ``2 ** bits``
    squares a side (in rows of x), its run of 16 moved elsewhere by a hash of the block. Squares
    side by side share a cache line of heads, so one search and the next body's read a few
    lines."""
    side = np.int64(1) << bits
    local = ((ty & (side - 1)) << bits) | (tx & (side - 1))
    block = ((tx >> bits) * 73856093) ^ ((ty >> bits) * 19349663)
    return (local ^ (block << 4)) & ((side << bits) - 1)


@njit(cache=True, inline="always", _nrt=False)
def reach_turned(b, q):
    """How far body record ``b``'s spheres reach across the ground from its origin when turned
    by quaternion ``q`` (``hreach`` upright, else ``reach``)."""
    return b.hreach if q[1] == 0.0 and q[2] == 0.0 else b.reach


@njit(cache=True, inline="always", _nrt=False)
def reach_now(b):
    """:func:`reach_turned` as body record ``b`` is turned now."""
    return reach_turned(b, b.q)


def reaches_now(records: np.ndarray) -> np.ndarray:
    """:func:`reach_now` of every record (for the engine, in NumPy)."""
    upright = (records["q"][:, 1] == 0.0) & (records["q"][:, 2] == 0.0)
    return np.where(upright, records["hreach"], records["reach"])


@njit(cache=True, _nrt=False)
def grid_remove(bodies, heads, i):
    """Take body ``i`` out of the grid (nothing if it is not filed)."""
    b = bodies[i]
    bucket = b.grid_bucket
    if bucket < 0:
        return
    if b.grid_prev >= 0:
        bodies[b.grid_prev].grid_next = b.grid_next
    else:
        heads[bucket] = b.grid_next
    if b.grid_next >= 0:
        bodies[b.grid_next].grid_prev = b.grid_prev
    b.grid_bucket = -1
    b.grid_next = -1
    b.grid_prev = -1


@njit(cache=True, _nrt=False)
def grid_place(bodies, heads, bits, i):
    """File body ``i`` by the square under its origin; a body without shadows is not filed. A body
    already in its square's bucket stays where it is in the chain (searches do not depend on
    the chains' order: they count the bodies they find, or look for any)."""
    b = bodies[i]
    if b.num_shadow <= 0 or not b.cell_id:
        grid_remove(bodies, heads, i)
        return
    x0, y0 = block_origin(b.cell_id)
    bucket = bucket_of(math.floor((x0 + b.origin[0]) / TILE), math.floor((y0 + b.origin[1]) / TILE), bits)
    if bucket == b.grid_bucket:
        return
    grid_remove(bodies, heads, i)
    head = heads[bucket]
    b.grid_bucket = bucket
    b.grid_prev = -1
    b.grid_next = head
    if head >= 0:
        bodies[head].grid_prev = i
    heads[bucket] = i


@njit(cache=True, _nrt=False)
def grid_place_all(bodies, heads, bits):
    """File every body afresh."""
    heads[:] = -1
    for i in range(len(bodies)):
        bodies[i].grid_bucket = -1
        bodies[i].grid_next = -1
        bodies[i].grid_prev = -1
    for i in range(len(bodies)):
        grid_place(bodies, heads, bits, i)
