"""Where a building could answer a sweep: its shell's ball and the walls of the cells behind its doors.

A land cell holding a building asks it twice in a sweep. ``CLandCell::find_collisions``
(acclient.c:354886) collides with the shell, one part with a physics BSP
(``CBuildingObj::find_building_collisions`` @ 0x006B5300, acclient.c:719115), which first tests the
part's bounding sphere against the moving spheres where ``cache_localspace_sphere`` puts them
(``CGfxObj::find_obj_collisions``, acclient.c:356514): a **part ball**, as a static object's
(:mod:`acphys.fast.statics`). ``CObjCell::find_cell_list`` (acclient.c:346960) lets the cell add
the env cells behind the doors (``CBuildingObj::find_building_transit_cells``, acclient.c:719067):
each door's cell (one with ``other_portal_id >= 0`` that the world has) takes a sphere whose centre,
in the cell's frame, is not more than ``radius + 0.01`` behind any plane of its cell BSP's
``pos_node`` chain (``BSPNODE::sphere_intersects_cell_bsp``, acclient.c:362979). The planes are
kept here in the landblock frame of the env cell (the global spheres' coordinates are read in it
as they are, across a landblock seam too, as retail reads them).

Far from the ball and behind a plane of every door's cell by more than that and :data:`MARGIN`,
a sweep passes the building by in the kernel: the shell answers OK having written only the
path's localspace spheres (a cache every reader writes first) and no cell is added. Nearer, the
step runs on the reference path. Not retail: the kernel's bookkeeping.
"""

from __future__ import annotations

import math

from acphys.fast.statics import PART_BALL, Shape, placed
from acphys.precision import f32
from acphys.world.building import BuildingObj
from acphys.world.env_cell import EnvCell

#: How much farther than the test's own slack behind a plane a sphere must be: far beyond the
#: float32 roundings of the centre taken into the cell's frame, which the kernel skips.
MARGIN = 0.01

#: A plane ``(nx, ny, nz, d)`` in an env cell's landblock frame.
Plane = tuple[float, float, float, float]


def building_reach(building: BuildingObj) -> tuple[Shape | None, list[list[Plane]]] | None:
    """The shell's part ball (None: a shell without a physics BSP, which answers OK) and each
    door's cell's planes, or None when the kernel cannot bound the building (a BSP without a
    bounding sphere, a scale that is not positive, no world to find the doors' cells in, a cell
    BSP of no planes, a number that is not finite)."""
    part = building.part
    ball: Shape | None = None
    if part.physics_bsp is not None:
        bound, size = part.physics_sphere, f32(part.gfxobj_scale.z)
        if bound is None or not size > 0.0 or not part.pos.objcell_id:
            return None
        ball = (*placed(part.pos, bound.center * size), abs(bound.radius) * size, PART_BALL)
        if not all(math.isfinite(value) for value in ball):
            return None
    doors: list[list[Plane]] = []
    for portal in building.portals:
        if portal.other_portal_id < 0:
            continue
        if building.source is None:
            return None
        cell = portal.get_other_cell(building.source)
        if not isinstance(cell, EnvCell):
            continue
        planes = _chain_planes(cell)
        if not planes:
            return None
        doors.append(planes)
    return ball, doors


def _chain_planes(cell: EnvCell) -> list[Plane]:
    """The planes of ``cell``'s cell BSP ``pos_node`` chain moved into the landblock frame: a
    point's distance ``n·local + d`` from each is ``n'·p + d'`` for its landblock point ``p``."""
    m, o = cell.pos.frame.m, cell.pos.frame.origin
    node = cell.structure.cell_bsp.root_node
    planes: list[Plane] = []
    while node is not None:
        n, d = node.splitting_plane.N, node.splitting_plane.d
        # local = R (p - o), R's rows m[0:3], m[3:6], m[6:9] (Frame.globaltolocal): n·local = (Rᵀn)·(p - o)
        nx = n.x * m[0] + n.y * m[3] + n.z * m[6]
        ny = n.x * m[1] + n.y * m[4] + n.z * m[7]
        nz = n.x * m[2] + n.y * m[5] + n.z * m[8]
        plane = (nx, ny, nz, d - (nx * o.x + ny * o.y + nz * o.z))
        if not all(math.isfinite(value) for value in plane):
            return []
        planes.append(plane)
        node = node.pos_node
    return planes
