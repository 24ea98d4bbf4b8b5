"""The kernel's ``CTransition``: a body's sweep over outdoor terrain, among other bodies.

Ports of :mod:`acphys.transition.transition` and :mod:`acphys.transition.object_info` for what an
outdoor sweep meets: the terrain triangles of land cells (``validate_walkable``) and other
bodies' spheres (:mod:`acphys.fast.kernels.contact`), static objects passed out of their reach
(:func:`statics_out_of_reach`); the sphere path and collision record it moves and fills are
:mod:`acphys.fast.kernels.path`. Everything else (a static object within reach, a building,
water depth of a partly wet cell, a cell the kernel does not know, a climb onto another body,
nesting deeper than the compiled levels) hands the step back to the reference path: every
routine returns ``BAIL`` (-1) up the chain, and the tick restores the body as it was.

The transition record ``tr`` (:data:`~acphys.fast.layout.TRANSITION`) is retail's pooled
transition; ``w`` is the world (:mod:`acphys.fast.kernels.context`: the bodies, the cells, the
shadow lists and the broad phase's grid, :mod:`acphys.fast.kernels.grid`).

Retail recurses (``transitional_insert`` → ``step_down`` → ``transitional_insert`` ...); Numba
cannot cache recursive functions, so each nesting level is its own compiled function
(``transitional_insert``, ``_insert_level_2``), made of the one body ``transitional_insert_body``
given the level below as ``deeper``; below the second the step bails (``R_DEEP``). Two levels
are what a sweep over terrain and spheres takes: the step-down's inserts nest once, and its
placement insert starts with the contact plane the insert before it found still valid (only a
slide clears it), so it returns before stepping down again. No step of the bundled scenarios,
the bench workloads or the corpus nests deeper on the reference path
(``tests/fast/test_engines_agree.py`` holds them to it); each further level took the compile
about 15 s.
The body and the routines that nest (``step_down``, ``edge_slide``) are inlined into each level
(``inline="always"``), so ``deeper`` is a constant there: passed on as a value, Numba would type
it as a first-class function, which it cannot cache.
"""

from __future__ import annotations

import math

from numba import njit

from acphys.constants import EPSILON, FLOOR_Z, LANDING_Z, SMALL_STEP_DOWN_HEIGHT
from acphys.fast.buildings import MARGIN as BUILDING_MARGIN
from acphys.fast.kernels.cells import (
    BAIL,
    R_CELL,
    R_DEEP,
    R_NO_CELL,
    R_SHAPES,
    R_STATIC,
    R_UNREAD,
    R_WATER,
    add_all_outside_cells,
    bail,
    cell_array_clear,
    cell_index,
    find_terrain_poly,
    point_in_cell,
)
from acphys.fast.kernels.contact import body_find_obj_collisions, out_of_reach
from acphys.fast.kernels.context import (
    bodies_of,
    building_shapes_of,
    cells_of,
    door_planes_of,
    door_spans_of,
    grid_of,
    heads_of,
    landblock_index_of,
    other_shapes_of,
    other_spans_of,
    shadow_pool_of,
)
from acphys.fast.kernels.frame import (
    f32,
    frame_interpolate_rotation,
    frame_is_equal,
    frame_localtoglobal,
    frame_set_rotate,
    get_block_offset,
    position_get_offset,
    v_length,
    v_normalize_check_small,
)
from acphys.fast.kernels.grid import MAX_REACH, MAX_TILES, TILE, block_origin, bucket_of, reach_now, span_bits
from acphys.fast.kernels.path import (
    IT_INITIAL_PLACEMENT,
    IT_PLACEMENT,
    IT_TRANSITION,
    add_offset_to_check_pos,
    adjust_check_pos,
    cache_global_curr_center,
    cache_global_sphere_at_check,
    collision_info_init,
    restore_check_pos,
    save_check_pos,
    set_check_pos_to_curr,
    set_collision_normal,
    set_contact_plane,
    set_sliding_normal,
    t3,
    t4,
    t9,
)
from acphys.fast.kernels.store import put
from acphys.fast.statics import COLUMN, PART_BALL, UNBOUNDED
from acphys.fast.statics import MARGIN as STATIC_MARGIN
from acphys.flags import ObjectInfoState, PhysicsState, TransitionState
from acphys.geometry.bsp import CELL_SPHERE_SLACK
from acphys.world.terrain import WaterType

OK = int(TransitionState.OK)
COLLIDED = int(TransitionState.COLLIDED)
ADJUSTED = int(TransitionState.ADJUSTED)
SLID = int(TransitionState.SLID)
INVALID = int(TransitionState.INVALID)

OI_CONTACT = int(ObjectInfoState.CONTACT)
OI_ON_WALKABLE = int(ObjectInfoState.ON_WALKABLE)
OI_IS_VIEWER = int(ObjectInfoState.IS_VIEWER)
OI_PATH_CLIPPED = int(ObjectInfoState.PATH_CLIPPED)
OI_FREE_ROTATE = int(ObjectInfoState.FREE_ROTATE)
OI_EDGE_SLIDE = int(ObjectInfoState.EDGE_SLIDE)
PS_GRAVITY = int(PhysicsState.GRAVITY)
PS_MISSILE = int(PhysicsState.MISSILE)
PS_ETHEREAL = int(PhysicsState.ETHEREAL)
PS_STATIC = int(PhysicsState.STATIC)
PS_IGNORE_COLLISIONS = int(PhysicsState.IGNORE_COLLISIONS)

WT_NOT_WATER = int(WaterType.NOT_WATER)
WT_PARTIALLY_WATER = int(WaterType.PARTIALLY_WATER)
WT_ENTIRELY_WATER = int(WaterType.ENTIRELY_WATER)
ENTIRELY_WATER_DEPTH = 0.9


# -- the transition's set-up ------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def transition_init(tr):
    """Clear the object, the path's per-sweep fields, the collision record, the cell array and the
    kernel's triangle memo.

    Port of :meth:`acphys.transition.transition.Transition.init` (with ``SpherePath.init``).
    Retail: CTransition::init @ 0x00509DD0 (acclient.c:311595)
    """
    tr.oi_body = -1
    tr.oi_state = 0
    tr.num_sphere = 0
    tr.begin_cell = -1
    tr.curr_cell = -1
    tr.check_cell = -1
    tr.insert_type = IT_TRANSITION
    tr.step_down = False
    tr.step_up = False
    tr.collide = False
    tr.hits_interior_cell = False
    tr.backup_cell = -1
    tr.walkable_allowance = 0.0
    tr.walkable = False
    tr.check_walkable = False
    tr.cell_array_valid = False
    tr.neg_poly_hit = False
    tr.poly_memo_cell = -1
    collision_info_init(tr)
    cell_array_clear(tr)


# -- OBJECTINFO -------------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def kill_velocity(w, tr):
    """Zero the moving body's velocity (``CPhysicsObj::set_velocity(0)``: it is already no more
    than 50 m/s, marks ``jumped_this_frame`` when it changes, and keeps the body active).

    Port of :meth:`acphys.transition.object_info.ObjectInfo.kill_velocity`.
    Retail: OBJECTINFO::kill_velocity @ 0x0050CFE0 (acclient.c:314147)
    """
    b = bodies_of(w)[tr.oi_body]
    v = b.velocity
    if abs(v[0]) > EPSILON or abs(v[1]) > EPSILON or abs(v[2]) > EPSILON:
        v[0] = 0.0
        v[1] = 0.0
        v[2] = 0.0
        b.jumped_this_frame = True


@njit(cache=True, _nrt=False)
def x87_divide(numerator, denominator):
    """Port of :func:`acphys.transition.object_info.x87_divide`: ±inf or NaN instead of an error."""
    if denominator != 0.0:
        return numerator / denominator
    if numerator == 0.0 or math.isnan(numerator):
        return math.nan
    return math.copysign(math.inf, numerator) * math.copysign(1.0, denominator)


@njit(cache=True, inline="always", _nrt=False)
def validate_walkable(tr, cx, cy, cz, radius, nx, ny, nz, d, is_water, water_depth, land_cell_id):
    """Rest sphere 0 (centre ``(cx, cy, cz)``, cell-local) on a terrain plane lowered by the water.

    Port of :meth:`acphys.transition.object_info.ObjectInfo.validate_walkable` (not a viewer).
    Retail: OBJECTINFO::validate_walkable @ 0x0050D010 (acclient.c:314160)
    """
    state = tr.oi_state
    dist = cy * ny + (cz - radius) * nz + cx * nx + d + f32(water_depth)
    contact = tr.step_down or not state & OI_ON_WALKABLE or nz >= FLOOR_Z
    if dist >= -EPSILON:
        if dist > EPSILON:
            return OK
        if contact:
            set_contact_plane(tr, nx, ny, nz, d, is_water)
            tr.contact_plane_cell_id = land_cell_id
        result = OK
    else:
        if tr.check_walkable:
            return COLLIDED
        depth = f32(x87_divide(dist, nz))
        result = OK
        if contact:
            set_contact_plane(tr, nx, ny, nz, d, is_water)
            tr.contact_plane_cell_id = land_cell_id
            if tr.step_down:
                scale = x87_divide(-1.0, tr.step_down_amt * tr.walk_interp)
                interp = (1.0 - scale * depth) * tr.walk_interp
                if interp >= tr.walk_interp or interp < -0.1:
                    return COLLIDED
                tr.walk_interp = f32(interp)
            add_offset_to_check_pos(tr, 0.0, 0.0, f32(-depth))
            result = ADJUSTED
    if not state & OI_CONTACT and not tr.step_down:
        set_collision_normal(tr, nx, ny, nz)
        tr.collided_with_environment = True
    return result


# -- what a cell holds ------------------------------------------------------------------------


@njit(cache=True, inline="always", _nrt=False)
def _poly_remembered(tr, k, px, py):
    """Whether the sweep's last terrain triangle (``tr.poly_memo``) was found in cell ``k`` under
    ``(px, py)``."""
    return k == tr.poly_memo_cell and px == tr.poly_memo_x and py == tr.poly_memo_y


@njit(cache=True, inline="always", _nrt=False)
def find_env_collisions(w, tr, k):
    """Collide sphere 0 with the terrain triangle of cell ``k`` under the low point.

    Entry restrictions (a cell with one is ``uncovered``) and the all-water stop come first; a
    partly wet cell's water depth is the reference path's. The triangle found last in the sweep
    is reused for the same cell and point (a step down or a lift moves the low point's z alone).

    Port of :meth:`acphys.world.land_cell.LandCell.find_env_collisions`.
    Retail: CLandCell::find_env_collisions @ 0x00532F20 (acclient.c:354991)
    """
    cell = cells_of(w)[k]
    ox, oy, oz = get_block_offset(tr.check_cell_id, cell.cell_id)
    px = f32(tr.global_low_point[0] - ox)
    py = f32(tr.global_low_point[1] - oy)
    if _poly_remembered(tr, k, px, py):
        poly = tr.poly_memo
    else:
        poly = find_terrain_poly(w, k, px, py)
        tr.poly_memo_cell, tr.poly_memo_x, tr.poly_memo_y, tr.poly_memo = k, px, py, poly
    if poly < 0:
        return OK
    if cell.block_water_type == WT_ENTIRELY_WATER and not bodies_of(w)[tr.oi_body].state & PS_MISSILE:
        return COLLIDED
    if cell.water_type == WT_PARTIALLY_WATER:
        return bail(tr, R_WATER)
    water_depth = ENTIRELY_WATER_DEPTH if cell.water_type == WT_ENTIRELY_WATER else 0.0
    cx = f32(tr.global_sphere[0, 0] - ox)
    cy = f32(tr.global_sphere[0, 1] - oy)
    cz = f32(tr.global_sphere[0, 2] - oz)
    plane = cell.plane[poly]
    return validate_walkable(
        tr,
        cx,
        cy,
        cz,
        tr.global_sphere[0, 3],
        plane[0],
        plane[1],
        plane[2],
        plane[3],
        cell.water_type != WT_NOT_WATER,
        water_depth,
        cell.cell_id,
    )


@njit(cache=True, inline="always", _nrt=False)
def nobody_near(w, tr, x0, y0, x1, y1):
    """Whether no body but the mover reaches into the landblock-global box ``[x0, x1] × [y0, y1]``
    (its origin within its reach of the box)."""
    bodies, heads = bodies_of(w), heads_of(w)
    reach, bits = grid_of(w)[MAX_REACH], span_bits(grid_of(w))
    tx0, tx1 = math.floor((x0 - reach) / TILE), math.floor((x1 + reach) / TILE)
    ty0, ty1 = math.floor((y0 - reach) / TILE), math.floor((y1 + reach) / TILE)
    if (tx1 - tx0 + 1) * (ty1 - ty0 + 1) > MAX_TILES:
        return False
    for tx in range(tx0, tx1 + 1):
        for ty in range(ty0, ty1 + 1):
            j = heads[bucket_of(tx, ty, bits)]
            while j >= 0:
                other = bodies[j]
                if j != tr.oi_body:
                    ox, oy = block_origin(other.cell_id)
                    x, y, r = ox + other.origin[0], oy + other.origin[1], reach_now(other)
                    if x0 - r <= x <= x1 + r and y0 - r <= y <= y1 + r:
                        return False
                j = other.grid_next
    return True


@njit(cache=True, _nrt=False)
def _asks(w, tr, j, k):
    """Whether cell ``k``'s ``find_obj_collisions`` would ask body ``j`` (a body's index, never a
    static object's entry): shadowed there, not the mover, not held."""
    other = bodies_of(w)[j]
    if j == tr.oi_body or other.has_parent:
        return False
    for s in range(other.num_shadow):  # noqa: SIM110 (Numba compiles no generator expressions)
        if other.shadow_cell[s] == k:
            return True
    return False


@njit(cache=True, inline="always", _nrt=False)
def _may_answer(w, tr, j):
    """Whether body ``j`` could answer the sweep other than OK, or touch anything: within reach,
    or of shapes the kernel does not know."""
    return not bodies_of(w)[j].collider or not out_of_reach(w, tr, j)


@njit(cache=True, _nrt=False)
def statics_out_of_reach(w, tr, k):
    """Whether every static object shadowed in cell ``k`` lies out of the sweep's reach: each of
    its balls and columns (:mod:`acphys.fast.statics`) farther from every moving sphere than their
    largest radius (which ``radsum`` gives the second sphere too) and ``MARGIN`` (a part ball from
    the spheres where the BSP test sees them). Such objects answer OK and change nothing a step
    reads, wherever they stand in the list; an object the kernel cannot bound is never out of
    reach, nor is anything from a sphere that is not a number. Not retail: passes
    ``CPhysicsObj::FindObjCollisions`` (acclient.c:316158) by.
    """
    cell = cells_of(w)[k]
    pool, spans, shapes = shadow_pool_of(w), other_spans_of(w), other_shapes_of(w)
    seen = 0
    for i in range(cell.num_shadows):
        if seen == cell.num_others:  # the rest of the list holds bodies only
            break
        entry = pool[cell.shadow_start + i]
        if entry >= 0:
            continue
        seen += 1
        first, count = spans[-1 - entry, 0], spans[-1 - entry, 1]
        if count == UNBOUNDED or not shapes_out_of_reach(tr, shapes, first, count):
            return False
    return True


@njit(cache=True, _nrt=False)
def shapes_out_of_reach(tr, shapes, first, count):
    """Whether rows ``first, first + count`` of ``shapes`` (balls, columns and part balls,
    :mod:`acphys.fast.statics`) all lie farther from every moving sphere than their radius, the
    largest moving radius and ``MARGIN`` (see :func:`statics_out_of_reach`)."""
    bx, by = block_origin(tr.check_cell_id)
    reach = 0.0
    for t in range(tr.num_sphere):
        reach = max(reach, tr.global_sphere[t, 3])
    for row in range(first, first + count):
        limit = shapes[row, 3] + reach + STATIC_MARGIN
        kind = shapes[row, 4]
        for t in range(tr.num_sphere):
            x, y, z = tr.global_sphere[t, 0], tr.global_sphere[t, 1], tr.global_sphere[t, 2]
            if kind == PART_BALL:  # where cache_localspace_sphere puts the sphere: local at check_pos
                local = (tr.local_sphere[t, 0], tr.local_sphere[t, 1], tr.local_sphere[t, 2])
                x, y, z = frame_localtoglobal(t3(tr.check_origin), t9(tr.check_m), local)
            dx, dy, dz = bx + x - shapes[row, 0], by + y - shapes[row, 1], z - shapes[row, 2]
            if kind == COLUMN:
                dz = 0.0
            if not dx * dx + dy * dy + dz * dz > limit * limit:
                return False
    return True


@njit(cache=True, _nrt=False)
def building_shell_out_of_reach(w, tr, k):
    """Whether cell ``k``'s building's shell answers the sweep OK, changing nothing a step reads:
    its part ball lies out of reach (:mod:`acphys.fast.buildings`). Not retail: passes
    ``CBuildingObj::find_building_collisions`` (acclient.c:719115) by.
    """
    ball = cells_of(w)[k].building_ball
    return ball < 0 or shapes_out_of_reach(tr, building_shapes_of(w), ball, 1)


@njit(cache=True, _nrt=False)
def building_doors_out_of_reach(w, tr, k):
    """Whether no cell behind cell ``k``'s building's doors takes any global sphere: each lies
    behind a plane of each door's cell by more than ``radius + 0.01`` and ``MARGIN``
    (:mod:`acphys.fast.buildings`). Not retail: passes ``CBuildingObj::find_building_transit_cells``
    (acclient.c:719067) by.
    """
    cell = cells_of(w)[k]
    spans = door_spans_of(w)
    for door in range(cell.building_doors, cell.building_doors + cell.num_building_doors):
        for t in range(tr.num_sphere):
            if not _behind_a_plane(w, tr, t, spans[door, 0], spans[door, 1]):
                return False
    return True


@njit(cache=True, inline="always", _nrt=False)
def _behind_a_plane(w, tr, t, first, count):
    """Whether global sphere ``t`` lies behind one of door planes ``first, first + count`` by more
    than its radius, ``0.01`` (``BSPNODE::sphere_intersects_cell_bsp``'s slack) and ``MARGIN``."""
    planes = door_planes_of(w)
    x, y, z = tr.global_sphere[t, 0], tr.global_sphere[t, 1], tr.global_sphere[t, 2]
    behind = -(tr.global_sphere[t, 3] + CELL_SPHERE_SLACK + BUILDING_MARGIN)
    for row in range(first, first + count):
        if planes[row, 0] * x + planes[row, 1] * y + planes[row, 2] * z + planes[row, 3] <= behind:
            return True
    return False


@njit(cache=True, inline="always", _nrt=False)
def find_obj_collisions(w, tr, k):
    """Ask the bodies shadowed in cell ``k``, in the list's order, to collide with the sweep
    (:func:`~acphys.fast.kernels.contact.body_find_obj_collisions`) until one answers other than
    OK; a static object shadowed there within the sweep's reach bails.

    The bodies within reach are found through the grid (:mod:`acphys.fast.kernels.grid`): with
    none, every answer is OK and touches nothing; with one, it is the only answer that counts;
    with more, or a search too wide, the cell's list is walked in order, as retail walks it.

    Port of :meth:`acphys.world.obj_cell.ObjCell.find_obj_collisions`.
    Retail: CObjCell::find_obj_collisions @ 0x0052B750 (acclient.c:347141)
    """
    if tr.insert_type == IT_INITIAL_PLACEMENT:
        return OK
    if cells_of(w)[k].num_others and not statics_out_of_reach(w, tr, k):
        return bail(tr, R_STATIC)  # a static object's shapes are the reference's
    if tr.lonely:
        return OK
    return _ask_bodies_near(w, tr, k)


@njit(cache=True, _nrt=False)
def _ask_bodies_near(w, tr, k):
    """:func:`find_obj_collisions` past its quick answers: the bodies the grid finds near the
    sweep, or the cell's whole list."""
    bodies, heads = bodies_of(w), heads_of(w)
    cell = cells_of(w)[k]
    x0, y0 = block_origin(tr.check_cell_id)
    reach, bits = grid_of(w)[MAX_REACH], span_bits(grid_of(w))
    low_x = low_y = math.inf
    high_x = high_y = -math.inf
    for s in range(tr.num_sphere):
        r = tr.global_sphere[s, 3] + reach
        x, y = x0 + tr.global_sphere[s, 0], y0 + tr.global_sphere[s, 1]
        low_x, high_x = min(low_x, x - r), max(high_x, x + r)
        low_y, high_y = min(low_y, y - r), max(high_y, y + r)
    tx0, tx1 = math.floor(low_x / TILE), math.floor(high_x / TILE)
    ty0, ty1 = math.floor(low_y / TILE), math.floor(high_y / TILE)
    if (tx1 - tx0 + 1) * (ty1 - ty0 + 1) <= MAX_TILES:
        count = 0
        found = -1
        for tx in range(tx0, tx1 + 1):
            for ty in range(ty0, ty1 + 1):
                j = heads[bucket_of(tx, ty, bits)]
                while j >= 0:
                    if _asks(w, tr, j, k) and _may_answer(w, tr, j):
                        count += 1
                        found = j
                    j = bodies[j].grid_next
        if count == 0:
            return OK
        if count == 1:
            return body_find_obj_collisions(w, tr, found)
    shadow_pool = shadow_pool_of(w)
    for i in range(cell.num_shadows):  # in the list's order, as retail asks
        entry = shadow_pool[cell.shadow_start + i]  # a static object's (< 0) is out of reach: OK
        if entry >= 0 and _asks(w, tr, entry, k):
            result = body_find_obj_collisions(w, tr, entry)
            if result != OK:
                return result
    return OK


@njit(cache=True, _nrt=False)
def find_collisions(w, tr, k):
    """Terrain, then the building (within its reach, the reference path's), then the shadowed
    objects.

    Port of :meth:`acphys.world.land_cell.LandCell.find_collisions`.
    Retail: CLandCell::find_collisions @ 0x00532D60 (acclient.c:354886)
    """
    cell = cells_of(w)[k]
    if cell.uncovered:
        return bail(tr, R_CELL)
    result = find_env_collisions(w, tr, k)
    if result == OK and cell.building and not building_shell_out_of_reach(w, tr, k):
        return bail(tr, R_CELL)
    if result == OK:
        result = find_obj_collisions(w, tr, k)
    return result


@njit(cache=True, inline="always", _nrt=False)
def insert_into_cell(w, tr, k, attempts):
    """Collide with everything in cell ``k`` until OK or COLLIDED, at most ``attempts`` times.

    Port of :meth:`acphys.transition.transition.Transition.insert_into_cell`.
    Retail: CTransition::insert_into_cell @ 0x00509E70 (acclient.c:311631)
    """
    if k < 0:
        return COLLIDED
    ts = OK
    for _ in range(attempts):
        ts = find_collisions(w, tr, k)
        if ts in (OK, COLLIDED, BAIL):
            return ts
        if ts == SLID:
            tr.contact_plane_valid = False
            tr.contact_plane_is_water = False
    return ts


@njit(cache=True, inline="always", _nrt=False)
def find_cell_list(w, tr, want_cell):
    """Fill the cell array with the land cells the global spheres touch at ``check_pos``; with
    ``want_cell``, also the cell holding sphere 0's centre (-1 for none, -2 to bail).

    Port of :meth:`acphys.world.obj_cell.ObjCell.find_cell_list` for an outdoor ``check_pos``
    (land cells have no transit cells of their own beyond ``add_all_outside_cells``; a building's
    doors' cells must take no sphere, or the step bails). Without a building the list is a
    function of ``check_pos``'s cell id and the spheres' x, y and radii alone, so the last one
    found is reused while they stay the same (the z of a step-down or a landing does not change
    it); the terrain test's last triangle answers
    ``point_in_cell`` for its cell and point when the cell has terrain (an upright body's low point
    lies under its sphere's centre).
    Retail: CObjCell::find_cell_list @ 0x0052B4E0 (acclient.c:346960)
    """
    cells = cells_of(w)
    cell_id = tr.check_cell_id
    if _memo_matches(tr):
        tr.num_cells = tr.memo_num_cells
        for i in range(tr.num_cells):
            tr.cells[i] = tr.memo_cells[i]
            tr.cell_ids[i] = tr.memo_cell_ids[i]
        tr.added_outside = True
        return tr.memo_curr if want_cell else -1
    cell_array_clear(tr)
    if (cell_id & 0xFFFF) >= 0x100 or not add_all_outside_cells(w, tr, cell_id):
        tr.bail = R_CELL
        return -2
    buildings = False
    for i in range(tr.num_cells):
        k = tr.cells[i]
        if k < 0:
            return _unread(tr, tr.cell_ids[i])
        if cells[k].uncovered or (cells[k].building and not building_doors_out_of_reach(w, tr, k)):
            tr.bail = R_CELL
            return -2
        buildings |= bool(cells[k].building)
    if cell_index(landblock_index_of(w), cell_id) < 0:
        return _unread(tr, cell_id)
    curr = -1
    for i in range(tr.num_cells):
        k = tr.cells[i]
        ox, oy, _ = get_block_offset(cell_id, cells[k].cell_id)
        px, py = f32(tr.global_sphere[0, 0] - ox), f32(tr.global_sphere[0, 1] - oy)
        if cells[k].num_polys and _poly_remembered(tr, k, px, py):  # the terrain test's triangle
            if tr.poly_memo >= 0:
                curr = k
        elif point_in_cell(w, k, px, py):
            curr = k
    if not buildings:  # a building's doors see the spheres' z as well
        _memo_store(tr, curr)
    return curr if want_cell else -1


@njit(cache=True, _nrt=False)
def _unread(tr, cell_id):
    """Bail for land cell ``cell_id``, of a landblock the arrays lack (-2)."""
    tr.bail = R_UNREAD if 1 <= (cell_id & 0xFFFF) <= 64 else R_CELL
    tr.unread_cell = cell_id
    return -2


@njit(cache=True, inline="always", _nrt=False)
def _memo_matches(tr):
    """Whether the last cell list found holds for ``check_pos``'s cell and spheres."""
    if not tr.memo_valid or tr.memo_cell_id != tr.check_cell_id or tr.memo_num_sphere != tr.num_sphere:
        return False
    for s in range(tr.num_sphere):
        if (
            tr.memo_spheres[s, 0] != tr.global_sphere[s, 0]
            or tr.memo_spheres[s, 1] != tr.global_sphere[s, 1]
            or tr.memo_spheres[s, 2] != tr.global_sphere[s, 3]
        ):
            return False
    return True


@njit(cache=True, inline="always", _nrt=False)
def _memo_store(tr, curr):
    tr.memo_valid = True
    tr.memo_cell_id = tr.check_cell_id
    tr.memo_num_sphere = tr.num_sphere
    for s in range(tr.num_sphere):
        tr.memo_spheres[s, 0] = tr.global_sphere[s, 0]
        tr.memo_spheres[s, 1] = tr.global_sphere[s, 1]
        tr.memo_spheres[s, 2] = tr.global_sphere[s, 3]
    tr.memo_num_cells = tr.num_cells
    for i in range(tr.num_cells):
        tr.memo_cells[i] = tr.cells[i]
        tr.memo_cell_ids[i] = tr.cell_ids[i]
    tr.memo_curr = curr


@njit(cache=True, _nrt=False)
def check_other_cells(w, tr, curr_cell):
    """Collide with every other cell the spheres reach, then re-home ``check_pos``.

    Port of :meth:`acphys.transition.transition.Transition.check_other_cells`; the kernel's cells
    collide without stepping, so the array does not change under the walk.
    Retail: CTransition::check_other_cells @ 0x0050AE50 (acclient.c:312380)
    """
    ts = OK
    tr.cell_array_valid = True
    tr.hits_interior_cell = False
    new_cell = find_cell_list(w, tr, True)
    if new_cell == -2:
        return BAIL
    index = 0
    while index < tr.num_cells:
        k = tr.cells[index]
        index += 1
        if k == curr_cell:
            continue
        ts = find_collisions(w, tr, k)
        if ts == BAIL:
            return ts
        if ts == SLID:
            tr.contact_plane_valid = False
            tr.contact_plane_is_water = False
            return ts
        if ts in (COLLIDED, ADJUSTED):
            return ts
    tr.check_cell = new_cell
    if new_cell >= 0:
        adjust_check_pos(tr, cells_of(w)[new_cell].cell_id)
        return ts
    if tr.step_down:
        return COLLIDED
    return bail(tr, R_NO_CELL)  # no cell holds sphere 0's centre: leaving the known cells


@njit(cache=True, inline="always", _nrt=False)
def calc_num_steps(tr):
    """``(offset, offset_per_step, num_steps)`` for the path (not a viewer).

    Port of :meth:`acphys.transition.transition.Transition.calc_num_steps`.
    Retail: CTransition::calc_num_steps @ 0x0050A0B0 (acclient.c:311763)
    """
    offset = position_get_offset(
        tr.begin_cell_id,
        (tr.begin_origin[0], tr.begin_origin[1], tr.begin_origin[2]),
        tr.end_cell_id,
        (tr.end_origin[0], tr.end_origin[1], tr.end_origin[2]),
    )
    radius = tr.local_sphere[0, 3]
    dist = v_length(offset)
    steps = dist / (1.0 * radius)
    if steps > 1.0:
        num_steps = math.ceil(steps)
        inv = 1.0 / num_steps
        return offset, (f32(offset[0] * inv), f32(offset[1] * inv), f32(offset[2] * inv)), num_steps
    if offset[0] != 0.0 or offset[1] != 0.0 or offset[2] != 0.0:
        return offset, offset, 1
    return offset, (0.0, 0.0, 0.0), 0


@njit(cache=True, _nrt=False)
def snap_to_plane(nx, ny, nz, d, x, y, z):
    """The offset with the z that keeps it in the plane (unchanged when ``|N.z| <= EPSILON``).

    Port of :meth:`acphys.geometry.plane.Plane.snap_to_plane`.
    Retail: Plane::snap_to_plane @ 0x00509C50 (acclient.c:311526)
    """
    if abs(nz) > EPSILON:
        inv = 1.0 / nz
        return (x, y, f32(-(y * ny + x * nx + nz * 0.0 + d) * inv - inv * -d))
    return (x, y, z)


@njit(cache=True, inline="always", _nrt=False)
def adjust_offset(tr, x, y, z):
    """Bend one step's offset by the sliding normal and the contact plane.

    Port of :meth:`acphys.transition.transition.Transition.adjust_offset`.
    Retail: CTransition::adjust_offset @ 0x0050A370 (acclient.c:311863)
    """
    new = (x, y, z)
    sx, sy, sz = tr.sliding_normal[0], tr.sliding_normal[1], tr.sliding_normal[2]
    slide = False
    if tr.sliding_normal_valid:
        if z * sz + y * sy + x * sx < 0.0:
            slide = True
        else:
            tr.sliding_normal_valid = False
    if tr.contact_plane_valid:
        nx, ny, nz = tr.contact_n[0], tr.contact_n[1], tr.contact_n[2]
        d = tr.contact_d
        into_plane = f32(z * nz + y * ny + x * nx)
        if slide:
            small, line = v_normalize_check_small(
                (f32(sz * ny - sy * nz), f32(sx * nz - sz * nx), f32(sy * nx - sx * ny))
            )
            if small:
                new = (0.0, 0.0, 0.0)
            else:
                along = line[2] * z + line[1] * y + line[0] * x
                new = (f32(line[0] * along), f32(line[1] * along), f32(line[2] * along))
        elif into_plane <= 0.0:
            new = (f32(x - into_plane * nx), f32(y - into_plane * ny), f32(z - f32(into_plane * nz)))
        else:
            new = snap_to_plane(nx, ny, nz, d, x, y, z)
        if not tr.contact_plane_is_water and tr.contact_plane_cell_id:
            bx, by, bz = get_block_offset(tr.check_cell_id, tr.contact_plane_cell_id)
            cx, cy, cz = tr.global_sphere[0, 0], tr.global_sphere[0, 1], tr.global_sphere[0, 2]
            radius = tr.global_sphere[0, 3]
            dist = (cz - bz) * nz + (cy - by) * ny + (cx - bx) * nx + d
            if dist < radius - EPSILON:
                lift = x87_divide(radius - dist, nz)
                if radius > abs(lift):
                    add_offset_to_check_pos(tr, 0.0, 0.0, f32(lift))
    elif slide:
        along = x * sx + z * sz + y * sy
        new = (f32(x - along * sx), f32(y - f32(along * sy)), f32(z - f32(along * sz)))
    return new


# -- steps, slides and validation ----------------------------------------------------------


@njit(cache=True, _nrt=False)
def cliff_slide(tr, nx, ny, nz):
    """Slide along the crease between the too-steep contact plane and the last known one.

    Port of :meth:`acphys.transition.transition.Transition.cliff_slide`.
    Retail: CTransition::cliff_slide @ 0x0050A6D0 (acclient.c:312004)
    """
    lx, ly, lz = tr.last_known_contact_n[0], tr.last_known_contact_n[1], tr.last_known_contact_n[2]
    cx = ny * lz - nz * ly
    cy = lx * nz - lz * nx
    cz = (nx * ly - ny * lx) * 0.0
    small, normal = v_normalize_check_small((f32(cz - cy), f32(cx - cz), f32(cy * 0.0 - cx * 0.0)))
    if small:
        return OK
    bx, by, bz = get_block_offset(tr.curr_cell_id, tr.check_cell_id)
    step_x = tr.global_sphere[0, 0] - tr.global_curr_center[0, 0]
    step_y = tr.global_sphere[0, 1] - tr.global_curr_center[0, 1]
    step_z = f32(tr.global_sphere[0, 2] - tr.global_curr_center[0, 2])
    along_x = f32(bx + step_x)
    along = (bz + step_z) * normal[2] + (by + step_y) * normal[1] + along_x * normal[0]
    if along <= 0.0:
        add_offset_to_check_pos(tr, f32(normal[0] * along), f32(normal[1] * along), f32(normal[2] * along))
        set_collision_normal(tr, normal[0], normal[1], normal[2])
    else:
        add_offset_to_check_pos(tr, f32(normal[0] * -along), f32(normal[1] * -along), f32(normal[2] * -along))
        set_collision_normal(tr, -normal[0], -normal[1], -normal[2])
    return ADJUSTED


@njit(cache=True, inline="always", _nrt=False)
def placement_settled(tr, cell):
    """Whether the placement insert that follows a landed step-down would answer OK and change
    nothing, so that :func:`step_down` may take its answer without running it. ``cell`` is the
    check cell the step-down's insert started in.

    That insert returned OK with a valid contact plane, so its last pass collided the check
    position with its check cell and then every other cell of the array there, each answering OK,
    and re-homed the position into the cell holding sphere 0's centre. When that cell is the one
    it started in and the array holds it alone, the placement insert repeats at the same position
    that one cell's collisions: the same terrain triangle and distance (at least ``-EPSILON``, or
    the step-down's pass would have been ADJUSTED); the contact plane it may set is the one the
    step-down's pass set last; the cell list is the same; the re-homing adds a zero block offset
    to float32 values the step-down's pass re-homed already. What the two inserts do differently
    is ruled out by the rest: a body without CONTACT gets a collision normal from a placement
    (``validate_walkable`` outside a step-down), and other bodies answer a placement otherwise
    (``lonely``: no body is near the sweep; static objects the step-down's pass found out of
    reach are so again). The placement then returns OK at the contact-plane test, as the
    step-down's insert did.

    Not retail: a shortcut past ``CTransition::transitional_insert`` (acclient.c:312833) called
    from ``CTransition::step_down`` @ 0x0050B2A0 (acclient.c:312628), whose answer it gives.
    """
    return tr.lonely and tr.oi_state & OI_CONTACT and tr.check_cell == cell and tr.num_cells == 1


@njit(cache=True, inline="always", _nrt=False)
def step_down(w, tr, step_down_ht, z_val, deeper):
    """Lower the candidate by ``step_down_ht`` and insert it: 1 when it lands on a contact plane
    with normal z at least ``z_val`` and a placement re-insert there is OK, else 0 (or BAIL).

    Port of :meth:`acphys.transition.transition.Transition.step_down` (the kernel records no
    walkable polygon, so its ``check_walkable`` always finds ground).
    Retail: CTransition::step_down @ 0x0050B2A0 (acclient.c:312628)
    """
    step_down_ht = f32(step_down_ht)
    z_val = f32(z_val)
    tr.neg_poly_hit = False
    tr.step_down = True
    tr.step_down_amt = step_down_ht
    tr.walk_interp = 1.0
    if not tr.step_up:
        add_offset_to_check_pos(tr, 0.0, 0.0, -step_down_ht)
    cell = tr.check_cell
    ts = deeper(w, tr, 5)
    if ts == BAIL:
        return BAIL
    tr.step_down = False
    if not (ts == OK and tr.contact_plane_valid and tr.contact_n[2] >= z_val):
        return 0
    if tr.oi_state & OI_EDGE_SLIDE and not tr.step_up and tr.walkable:
        return bail(tr, R_SHAPES)  # check_walkable against a recorded walkable polygon
    tr.backup = tr.insert_type
    if placement_settled(tr, cell):
        return 1
    tr.insert_type = IT_PLACEMENT
    ts = deeper(w, tr, 1)
    if ts == BAIL:
        return BAIL
    tr.insert_type = tr.backup
    return 1 if ts == OK else 0


@njit(cache=True, inline="always", _nrt=False)
def edge_slide(w, tr, ts, step_down_ht, z_val, deeper):
    """A body that found nothing to step down onto: ``(stop, ts)``.

    Port of :meth:`acphys.transition.transition.Transition.edge_slide` (no walkable polygon is
    ever recorded by the kernel, so the precipice slides are not reached).
    Retail: CTransition::edge_slide @ 0x0050B3D0 (acclient.c:312684)
    """
    state = tr.oi_state
    if not (state & OI_ON_WALKABLE and state & OI_EDGE_SLIDE):
        tr.walkable = False
        restore_check_pos(tr)
        tr.contact_plane_valid = False
        tr.contact_plane_is_water = False
        tr.cell_array_valid = True
        return True, OK
    if tr.contact_plane_valid and tr.contact_n[2] < z_val:
        tr.walkable = False
        restore_check_pos(tr)
        ts = cliff_slide(tr, tr.contact_n[0], tr.contact_n[1], tr.contact_n[2])
        tr.contact_plane_valid = False
        tr.contact_plane_is_water = False
        return False, ts
    if tr.walkable:
        return True, bail(tr, R_SHAPES)
    if tr.contact_plane_valid:
        tr.walkable = False
        restore_check_pos(tr)
        tr.cell_array_valid = True
        tr.contact_plane_valid = False
        tr.contact_plane_is_water = False
        return True, OK
    add_offset_to_check_pos(
        tr,
        f32(tr.global_curr_center[0, 0] - tr.global_sphere[0, 0]),
        f32(tr.global_curr_center[0, 1] - tr.global_sphere[0, 1]),
        f32(tr.global_curr_center[0, 2] - tr.global_sphere[0, 2]),
    )
    if step_down(w, tr, step_down_ht, z_val, deeper) == BAIL:
        return True, BAIL
    tr.contact_plane_valid = False
    tr.contact_plane_is_water = False
    restore_check_pos(tr)
    if tr.walkable:
        return True, bail(tr, R_SHAPES)
    tr.walkable = False
    tr.cell_array_valid = True
    return True, COLLIDED


@njit(cache=True, inline="always", _nrt=False)
def transitional_insert_body(w, tr, attempts, deeper):
    """Insert ``check_pos`` into its cell and the cells around, resolving what it meets.

    Port of :meth:`acphys.transition.transition.Transition.transitional_insert` (a sweep over
    terrain never sets ``collide`` or ``neg_poly_hit``: those come from shapes the kernel leaves
    to the reference path).
    Retail: CTransition::transitional_insert @ 0x0050B6F0 (acclient.c:312833)
    """
    if tr.check_cell < 0:
        return OK
    ts = INVALID
    for _ in range(attempts):
        ts = insert_into_cell(w, tr, tr.check_cell, attempts)
        if ts == BAIL:
            return BAIL
        if ts == OK:
            ts = check_other_cells(w, tr, tr.check_cell)
            if ts == BAIL:
                return BAIL
            if ts != OK:
                tr.neg_poly_hit = False
            if ts == COLLIDED:
                return ts
        elif ts == SLID:
            tr.contact_plane_valid = False
            tr.contact_plane_is_water = False
            tr.neg_poly_hit = False
        elif ts == ADJUSTED:
            tr.neg_poly_hit = False
        elif ts == COLLIDED:
            tr.neg_poly_hit = False
            return ts
        if ts != OK:
            continue
        if tr.collide or tr.neg_poly_hit:
            return bail(tr, R_SHAPES)
        if tr.contact_plane_valid:
            return OK
        state = tr.oi_state
        if not state & OI_CONTACT or tr.step_down or tr.check_cell < 0 or not tr.oi_step_down:
            return OK
        step_down_ht = SMALL_STEP_DOWN_HEIGHT
        z_val = LANDING_Z
        if state & OI_ON_WALKABLE:
            z_val = FLOOR_Z
            step_down_ht = tr.oi_step_down_height
        tr.walkable_allowance = z_val
        save_check_pos(tr)
        radius = tr.global_sphere[0, 3]
        if tr.num_sphere < 2 and radius + radius < step_down_ht:
            step_down_ht = f32(radius * 0.5)
        if radius + radius >= step_down_ht:
            stepped = step_down(w, tr, step_down_ht, z_val, deeper)
        else:
            step_down_ht = f32(step_down_ht * 0.5)
            stepped = step_down(w, tr, step_down_ht, z_val, deeper)
            if stepped == 0:
                stepped = step_down(w, tr, step_down_ht, z_val, deeper)
        if stepped == BAIL:
            return BAIL
        if stepped:
            tr.walkable = False
            return OK
        done, ts = edge_slide(w, tr, ts, step_down_ht, z_val, deeper)
        if done or ts == BAIL:
            return ts
    return ts


@njit(cache=True, _nrt=False)
def _insert_too_deep(w, tr, attempts):
    """Below the deepest compiled level: the reference path nests further."""
    return bail(tr, R_DEEP)


@njit(cache=True, _nrt=False)
def _insert_level_2(w, tr, attempts):
    return transitional_insert_body(w, tr, attempts, _insert_too_deep)


@njit(cache=True, _nrt=False)
def transitional_insert(w, tr, attempts):
    """The outermost ``transitional_insert``; one nested level follows it."""
    return transitional_insert_body(w, tr, attempts, _insert_level_2)


@njit(cache=True, inline="always", _nrt=False)
def validate_transition(w, tr, ts):
    """Accept or roll back one step; update the sliding normal, the stationary-fall counter and the
    contact state.

    Port of :meth:`acphys.transition.transition.Transition.validate_transition`.
    Retail: CTransition::validate_transition @ 0x0050AA70 (acclient.c:312193)
    """
    bodies = bodies_of(w)
    moved = True
    unchanged = tr.check_cell_id == tr.curr_cell_id and frame_is_equal(
        t3(tr.check_origin), t4(tr.check_q), t3(tr.curr_origin), t4(tr.curr_q)
    )
    if ts != OK or unchanged:
        moved = False
    if ts == OK:
        tr.curr_cell_id = tr.check_cell_id
        put(tr.curr_origin, tr.check_origin)
        put(tr.curr_q, tr.check_q)
        put(tr.curr_m, tr.check_m)
        tr.curr_cell = tr.check_cell
        cache_global_curr_center(tr)
        # set_check_pos(curr_pos): the check position holds the values just copied
        tr.cell_array_valid = False
        cache_global_sphere_at_check(tr)
    elif COLLIDED <= ts <= SLID:
        if tr.last_known_contact_plane_valid:
            kill_velocity(w, tr)
            n = tr.last_known_contact_n
            cx, cy, cz = tr.global_curr_center[0, 0], tr.global_curr_center[0, 1], tr.global_curr_center[0, 2]
            dist = cz * n[2] + cy * n[1] + cx * n[0] + tr.last_known_contact_d
            if tr.global_sphere[0, 3] + EPSILON > abs(dist):
                set_contact_plane(
                    tr, n[0], n[1], n[2], tr.last_known_contact_d, tr.last_known_contact_plane_is_water
                )
                tr.contact_plane_cell_id = tr.last_known_contact_plane_cell_id
                if tr.oi_state & OI_ON_WALKABLE:
                    moved = True
        if not tr.collision_normal_valid:
            set_collision_normal(tr, 0.0, 0.0, 1.0)
        set_check_pos_to_curr(tr)
        tr.cell_array_valid = True
        tr.hits_interior_cell = False
        if find_cell_list(w, tr, False) == -2:
            return BAIL
        ts = OK
    if tr.collision_normal_valid:
        set_sliding_normal(tr, tr.collision_normal[0], tr.collision_normal[1])
    if bodies[tr.oi_body].state & PS_GRAVITY:
        if moved:
            tr.frames_stationary_fall = 0
        elif tr.frames_stationary_fall == 0:
            tr.frames_stationary_fall = 1
        elif tr.frames_stationary_fall == 1:
            tr.frames_stationary_fall = 2
        else:
            tr.frames_stationary_fall = 3
            cx, cy, cz = tr.global_sphere[0, 0], tr.global_sphere[0, 1], tr.global_sphere[0, 2]
            height = (cy + cx) * 0.0 + cz
            set_contact_plane(tr, 0.0, 0.0, 1.0, f32(tr.global_sphere[0, 3] - height), False)
            tr.contact_plane_cell_id = tr.check_cell_id
            if not tr.oi_state & OI_CONTACT:
                set_collision_normal(tr, 0.0, 0.0, 1.0)
                tr.collided_with_environment = True
    tr.last_known_contact_plane_valid = tr.contact_plane_valid
    if tr.contact_plane_valid:
        put(tr.last_known_contact_n, tr.contact_n)
        tr.last_known_contact_d = tr.contact_d
        tr.last_known_contact_plane_cell_id = tr.contact_plane_cell_id
        tr.last_known_contact_plane_is_water = tr.contact_plane_is_water
        tr.oi_state |= OI_CONTACT
        if tr.contact_n[2] >= FLOOR_Z:
            tr.oi_state |= OI_ON_WALKABLE
        else:
            tr.oi_state &= ~OI_ON_WALKABLE
    else:
        tr.oi_state &= ~(OI_CONTACT | OI_ON_WALKABLE)
    return ts


@njit(cache=True, _nrt=False)
def find_transitional_position(w, tr):
    """Sweep from ``curr_pos`` to ``end_pos`` in steps of at most sphere 0's radius: 1 when the last
    step validated OK, 0 when not, BAIL when the reference path must sweep.

    Port of :meth:`acphys.transition.transition.Transition.find_transitional_position` (not a
    viewer).
    Retail: CTransition::find_transitional_position @ 0x0050BDF0 (acclient.c:313170)
    """
    if tr.begin_cell < 0:
        return 0
    ts = OK
    _, per_step, num_steps = calc_num_steps(tr)
    free = tr.oi_state & OI_FREE_ROTATE
    if free:
        set_curr_rotation(tr, tr.end_q)
    set_check_pos_to_curr(tr)
    if num_steps <= 0:
        if not free:
            set_curr_rotation(tr, tr.end_q)
        set_check_pos_to_curr(tr)
        tr.cell_array_valid = True
        tr.hits_interior_cell = False
        if find_cell_list(w, tr, False) == -2:
            return BAIL
        return 1
    for step in range(num_steps):
        gx, gy, gz = adjust_offset(tr, per_step[0], per_step[1], per_step[2])
        tr.global_offset[0], tr.global_offset[1], tr.global_offset[2] = gx, gy, gz
        if gx * gx + gy * gy + gz * gz < EPSILON * EPSILON:
            return 1 if step != 0 and ts == OK else 0
        if not free:
            q, m = frame_interpolate_rotation(
                t3(tr.check_origin),
                t4(tr.check_q),
                t9(tr.check_m),
                t4(tr.begin_q),
                t4(tr.end_q),
                (step + 1) / num_steps,
            )
            put(tr.check_q, q)
            put(tr.check_m, m)
        tr.sliding_normal_valid = False
        tr.contact_plane_valid = False
        tr.contact_plane_is_water = False
        add_offset_to_check_pos(tr, gx, gy, gz)
        inserted = transitional_insert(w, tr, 3)
        if inserted == BAIL:
            return BAIL
        ts = validate_transition(w, tr, inserted)
        if ts == BAIL:
            return BAIL
        if tr.frames_stationary_fall:
            break
        if tr.collision_normal_valid and tr.oi_state & OI_PATH_CLIPPED:
            break
    return 1 if ts == OK else 0


@njit(cache=True, _nrt=False)
def set_curr_rotation(tr, new_q):
    """``curr_pos.frame.set_rotate(new_q)`` (kept when the result is not a valid frame)."""
    q, m = frame_set_rotate(t3(tr.curr_origin), t4(tr.curr_q), t9(tr.curr_m), t4(new_q))
    put(tr.curr_q, q)
    put(tr.curr_m, m)
