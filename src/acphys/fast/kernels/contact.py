"""The kernel's sphere-sphere contact: a sweep meets another body's spheres and responds.

Ports of :meth:`acphys.body.reports.CollisionReports.find_obj_collisions` (the body side) and of
:class:`acphys.geometry.sphere.Sphere`'s sweep routines (``CSphere::intersects_sphere`` and the
responses it dispatches to) for bodies of one or two spheres with no weenie. Covered: the overlap
tests of placements, walkable checks and ethereal obstructions; stepping down onto a sphere; a body
in contact sliding off a sphere too high to step over (sphere 0) or off one its sphere 1 meets; a
path-clipped or airborne sphere 1 colliding with a point. Left to the reference path (``BAIL``): a
step up onto a sphere (``CTransition::step_up`` nests a whole insert inside the cell walk), landing
on one (``set_collide``, resolved by ``transitional_insert``), a perfect-clip rewind, and a
step-down whose root is of a negative number (retail goes on with NaN).

What a sweep touched is kept as ``COLLISIONINFO``'s collision objects (``tr.collide_body``), which
the commit stamps into the mover's collision records (:mod:`acphys.fast.kernels.tick`).

Every value is computed in double and rounded to float32 where retail stores a ``float`` or a
``Vector3``, as the reference routines' docstrings say, line by line.
"""

from __future__ import annotations

import math

from numba import njit

from acphys.constants import EPSILON
from acphys.fast.kernels.cells import BAIL, R_CLIMB, R_FULL, R_ROOT, R_SHAPE, bail
from acphys.fast.kernels.context import bodies_of
from acphys.fast.kernels.frame import f32, get_block_offset, v_normalize_check_small
from acphys.fast.kernels.path import (
    IT_PLACEMENT,
    add_offset_to_check_pos,
    set_collision_normal,
    set_contact_plane,
)
from acphys.fast.layout import MAX_COLLIDE
from acphys.flags import ObjectInfoState, PhysicsState, TransitionState

OK = int(TransitionState.OK)
COLLIDED = int(TransitionState.COLLIDED)
ADJUSTED = int(TransitionState.ADJUSTED)
SLID = int(TransitionState.SLID)

OI_CONTACT = int(ObjectInfoState.CONTACT)
OI_ON_WALKABLE = int(ObjectInfoState.ON_WALKABLE)
OI_PATH_CLIPPED = int(ObjectInfoState.PATH_CLIPPED)
OI_PERFECT_CLIP = int(ObjectInfoState.PERFECT_CLIP)
PS_MISSILE = int(PhysicsState.MISSILE)
PS_ETHEREAL = int(PhysicsState.ETHEREAL)
PS_STATIC = int(PhysicsState.STATIC)
PS_IGNORE_COLLISIONS = int(PhysicsState.IGNORE_COLLISIONS)

#: ``find_obj_collisions``' reach shortcut (``acphys.body.reports.REACH_MARGIN``).
REACH_MARGIN = 1e-3
#: ``timecheck < -0.1``: how far back a step-down may rewind ``walk_interp``.
MIN_WALK_INTERP = -0.1


@njit(cache=True, inline="always", _nrt=False)
def collides_with_sphere(dx, dy, dz, radsum):
    """Port of :meth:`acphys.geometry.sphere.Sphere.collides_with_sphere` (touching hits).
    Retail: CSphere::collides_with_sphere @ 0x005369E0 (acclient.c:358508)
    """
    return dx * dx + dy * dy + dz * dz <= radsum * radsum


@njit(cache=True, _nrt=False)
def out_of_reach(w, tr, j):
    """Whether every moving sphere at ``check_pos`` misses every sphere of body ``j`` by more than
    ``REACH_MARGIN`` (the reference's shortcut past ``intersects_sphere``).

    Port of :meth:`acphys.body.reports.CollisionReports.out_of_reach`.
    """
    other = bodies_of(w)[j]
    m = other.m
    ox, oy, oz = other.origin[0], other.origin[1], other.origin[2]
    if (tr.check_cell_id >> 16) != (other.cell_id >> 16):
        bx, by, bz = get_block_offset(tr.check_cell_id, other.cell_id)
        ox, oy, oz = ox + bx, oy + by, oz + bz
    scale = other.scale
    for s in range(other.num_sphere):
        cx, cy, cz = other.sphere[s, 0] * scale, other.sphere[s, 1] * scale, other.sphere[s, 2] * scale
        x = m[6] * cz + m[0] * cx + m[3] * cy + ox
        y = m[7] * cz + m[1] * cx + m[4] * cy + oy
        z = m[8] * cz + m[2] * cx + m[5] * cy + oz
        radius = other.sphere[s, 3] * scale + REACH_MARGIN
        for t in range(tr.num_sphere):
            dx = tr.global_sphere[t, 0] - x
            dy = tr.global_sphere[t, 1] - y
            dz = tr.global_sphere[t, 2] - z
            limit = radius + tr.global_sphere[t, 3]
            if not dx * dx + dy * dy + dz * dz > limit * limit:
                return False
    return True


@njit(cache=True, _nrt=False)
def placed_sphere(w, tr, j, s):
    """Body ``j``'s sphere ``s`` at its position and scale, in ``check_pos``'s block:
    ``(x, y, z, radius)``.

    Port of :meth:`acphys.geometry.sphere.Sphere.intersects_sphere_placed` (``localtoglobal`` of
    the scaled centre, then the block offset).
    Retail: CSphere::intersects_sphere @ 0x00537FD0 (acclient.c:359389)
    """
    other = bodies_of(w)[j]
    scale = other.scale
    vx = f32(other.sphere[s, 0] * scale)
    vy = f32(other.sphere[s, 1] * scale)
    vz = f32(other.sphere[s, 2] * scale)
    m, o = other.m, other.origin
    gx = f32(m[3] * vy + m[0] * vx + m[6] * vz + o[0])
    gy = f32(m[4] * vy + m[1] * vx + m[7] * vz + o[1])
    gz = f32(m[5] * vy + m[2] * vx + m[8] * vz + o[2])
    bx, by, bz = get_block_offset(tr.check_cell_id, other.cell_id)
    return f32(bx + gx), f32(by + gy), f32(bz + gz), f32(scale * other.sphere[s, 3])


# -- the responses --------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def step_since_curr(tr, s):
    """``center - curr`` of moving sphere ``s`` plus the curr-to-check block offset: the three
    ``float`` locals the slides build, the z difference stored first.

    Port of :func:`acphys.geometry.sphere._step_since_curr` (acclient.c:358760-358765).
    """
    bx, by, bz = get_block_offset(tr.curr_cell_id, tr.check_cell_id)
    cx, cy, cz = tr.global_sphere[s, 0], tr.global_sphere[s, 1], tr.global_sphere[s, 2]
    ux, uy, uz = tr.global_curr_center[s, 0], tr.global_curr_center[s, 1], tr.global_curr_center[s, 2]
    dz = f32(cz - uz)
    return f32(bx + (cx - ux)), f32(by + (cy - uy)), f32(bz + dz)


@njit(cache=True, inline="always", _nrt=False)
def slide_plane_normal(tr):
    """The normal of the plane a slide runs along: the contact plane, else the last known one."""
    n = tr.contact_n if tr.contact_plane_valid else tr.last_known_contact_n
    return n[0], n[1], n[2]


@njit(cache=True, _nrt=False)
def slide_sphere_normal(tr, s, nx, ny, nz):
    """Slide moving sphere ``s`` (from its current centre) along the collision normal ``n``.

    Port of :meth:`acphys.geometry.sphere.Sphere.slide_sphere_normal`, whose docstring gives the
    stores.
    Retail: CSphere::slide_sphere @ 0x00537440 (acclient.c:358898)
    """
    cx, cy, cz = tr.global_sphere[s, 0], tr.global_sphere[s, 1], tr.global_sphere[s, 2]
    if nx == 0.0 and ny == 0.0 and nz == 0.0:
        ux, uy, uz = tr.global_curr_center[s, 0], tr.global_curr_center[s, 1], tr.global_curr_center[s, 2]
        hx, hy, hz = f32(ux - cx), f32(uy - cy), f32(uz - cz)
        add_offset_to_check_pos(tr, f32(hx * 0.5), f32(hy * 0.5), f32(hz * 0.5))
        return ADJUSTED
    set_collision_normal(tr, nx, ny, nz)
    sx, sy, sz = step_since_curr(tr, s)
    px, py, pz = slide_plane_normal(tr)
    dir_y = px * nz - pz * nx
    dir_z_reg = py * nx - px * ny
    dir_x = f32(ny * pz - nz * py)
    dir_z = f32(dir_z_reg)
    dir2_reg = dir_z_reg * dir_z + dir_y * dir_y + dir_x * dir_x
    if dir2_reg >= EPSILON:
        dot = dir_z * sz + dir_y * sy + dir_x * sx
        ay_, az_ = f32(dir_y * dot), f32(dir_z * dot)
        inv_reg = 1.0 / f32(dir2_reg)
        inv = f32(inv_reg)
        ax = dir_x * dot * inv_reg
        ay, az = f32(ay_ * inv), f32(az_ * inv)
        if az * az + ay * ay + ax * ax < EPSILON:
            return COLLIDED
        add_offset_to_check_pos(tr, f32(ax - sx), f32(ay - sy), f32(az - sz))
        return SLID
    if nz * pz + ny * py + px * nx >= 0.0:
        proj = f32(sx * nx + sz * nz + sy * ny)
        add_offset_to_check_pos(tr, f32(-nx * proj), f32(-ny * proj), f32(-nz * proj))
        return SLID
    small, n = v_normalize_check_small((-sx, -sy, -sz))
    if not small:
        set_collision_normal(tr, n[0], n[1], n[2])
    return COLLIDED


@njit(cache=True, _nrt=False)
def slide_sphere(tr, ox, oy, oz, s):
    """Slide moving sphere ``s`` off the sphere centred at ``o``: the normal runs from ``o`` to the
    sphere's current centre.

    Port of :meth:`acphys.geometry.sphere.Sphere.slide_sphere`.
    Retail: CSphere::slide_sphere @ 0x00537A10 (acclient.c:359138)
    """
    ux, uy, uz = tr.global_curr_center[s, 0], tr.global_curr_center[s, 1], tr.global_curr_center[s, 2]
    small, n = v_normalize_check_small((f32(ux - ox), f32(uy - oy), f32(uz - oz)))
    if small:
        return COLLIDED
    return slide_sphere_normal(tr, s, n[0], n[1], n[2])


@njit(cache=True, _nrt=False)
def slide_sphere_skid(tr, ox, oy, oz, dx, dy, dz, s):
    """Slide moving sphere ``s`` off the sphere centred at ``o`` (``d``: sphere 0 minus ``o``) when it
    is too high to step over.

    Port of :meth:`acphys.geometry.sphere.Sphere.slide_sphere_skid`, whose docstring gives the
    stores and the reading of the lost compare.
    Retail: CSphere::slide_sphere @ 0x00536F40 (acclient.c:358708)
    """
    ux, uy, uz = tr.global_curr_center[s, 0], tr.global_curr_center[s, 1], tr.global_curr_center[s, 2]
    small, n = v_normalize_check_small((f32(ux - ox), f32(uy - oy), f32(uz - oz)))
    if small:
        return COLLIDED
    nx, ny, nz = n
    set_collision_normal(tr, nx, ny, nz)
    px, py, pz = slide_plane_normal(tr)
    cx, cy, cz = f32(ny * pz - nz * py), f32(nz * px - nx * pz), f32(nx * py - ny * px)
    sx, sy, sz = step_since_curr(tr, s)
    dir2 = cz * cz + cy * cy + cx * cx
    if dir2 >= EPSILON:
        dot = sz * cz + sy * cy + sx * cx
        inv = 1.0 / dir2
        ax, ay, az = f32(cx * dot), f32(cy * dot), f32(cz * dot)
        ax, ay, az = f32(ax * inv), f32(ay * inv), f32(az * inv)
        if az * az + ay * ay + ax * ax < EPSILON:
            return COLLIDED
        add_offset_to_check_pos(tr, f32(ax - sx), f32(ay - sy), f32(az - sz))
        return SLID
    if pz * dz + py * dy + px * dx < 0.0:
        return COLLIDED
    proj = f32(sz * nz + sy * ny + sx * nx)
    add_offset_to_check_pos(tr, f32(-nx * proj), f32(-ny * proj), f32(-nz * proj))
    return SLID


@njit(cache=True, _nrt=False)
def collide_with_point(tr, ox, oy, oz, s):
    """A path-clipped (or airborne sphere 1) hit: the normal from ``o`` to moving sphere ``s``'s
    current centre becomes the collision normal, COLLIDED; a perfect clip's rewind is the reference
    path's.

    Port of :meth:`acphys.geometry.sphere.Sphere.collide_with_point`.
    Retail: CSphere::collide_with_point @ 0x00537230 (acclient.c:358807)
    """
    if tr.oi_state & OI_PERFECT_CLIP:
        return bail(tr, R_CLIMB)
    ux, uy, uz = tr.global_curr_center[s, 0], tr.global_curr_center[s, 1], tr.global_curr_center[s, 2]
    small, n = v_normalize_check_small((f32(ux - ox), f32(uy - oy), f32(uz - oz)))
    if not small:
        set_collision_normal(tr, n[0], n[1], n[2])
    return COLLIDED


@njit(cache=True, _nrt=False)
def step_sphere_down(tr, ox, oy, oz, radius, dx, dy, dz, radsum):
    """Lower the moving spheres onto the sphere centred at ``o`` while stepping down; a walkable top
    is the contact plane (``d``: sphere 0 minus ``o``).

    Port of :meth:`acphys.geometry.sphere.Sphere.step_sphere_down`, whose docstring gives the
    stores; a root of a negative number (retail's NaN) is the reference path's.
    Retail: CSphere::step_sphere_down @ 0x00536D20 (acclient.c:358615)
    """
    hx, hy = f32(dx * dx), f32(dy * dy)
    if radsum * radsum < dz * dz + hx + hy:
        if tr.num_sphere <= 1:
            return OK
        d2x = f32(tr.global_sphere[1, 0] - ox)
        d2y = f32(tr.global_sphere[1, 1] - oy)
        d2z = f32(tr.global_sphere[1, 2] - oz)
        if not collides_with_sphere(d2x, d2y, d2z, radsum):
            return OK
    step_reg = tr.step_down_amt * tr.walk_interp
    if abs(step_reg) < EPSILON:
        return COLLIDED
    step = f32(step_reg)
    reach_reg = radsum + EPSILON
    reach = f32(reach_reg)
    square = reach_reg * reach - (hx + hy)
    if square < 0.0:
        return bail(tr, R_ROOT)
    t = (math.sqrt(square) - dz) / step
    interp = (1.0 - t) * tr.walk_interp
    if interp >= tr.walk_interp or interp < MIN_WALK_INTERP:
        return COLLIDED
    drop = f32(step * t)
    rise = drop + dz
    inv = 1.0 / reach
    nx, ny, nz = f32(inv * dx), f32(inv * dy), f32(rise * inv)
    if rise * inv <= tr.walkable_allowance:
        return OK
    px = f32(ox + f32(nx * radius))
    py = f32(oy + f32(ny * radius))
    pz = f32(oz + f32(nz * radius))
    set_contact_plane(tr, nx, ny, nz, f32(-(pz * nz + py * ny + px * nx)), True)  # retail passes 1
    tr.contact_plane_cell_id = tr.check_cell_id
    tr.walk_interp = f32(interp)
    add_offset_to_check_pos(tr, 0.0, 0.0, drop)
    return ADJUSTED


@njit(cache=True, _nrt=False)
def intersects_sphere(w, tr, j, s, ethereal):
    """Test the moving spheres against body ``j``'s sphere ``s`` and respond (``ethereal``: the
    sweep's ``obstruction_ethereal``).

    Port of :meth:`acphys.geometry.sphere.Sphere.intersects_sphere` for an obstacle that is no
    creature (a covered body has no weenie, and a missile obstacle is passed by before this).
    Retail: CSphere::intersects_sphere @ 0x00537A80 (acclient.c:359156)
    """
    ox, oy, oz, radius = placed_sphere(w, tr, j, s)
    dx = f32(tr.global_sphere[0, 0] - ox)
    dy = f32(tr.global_sphere[0, 1] - oy)
    dz = f32(tr.global_sphere[0, 2] - oz)
    radsum = f32(radius + tr.global_sphere[0, 3] - EPSILON)
    second = tr.num_sphere > 1
    d2x = d2y = d2z = 0.0
    if second:
        d2x = f32(tr.global_sphere[1, 0] - ox)
        d2y = f32(tr.global_sphere[1, 1] - oy)
        d2z = f32(tr.global_sphere[1, 2] - oz)
    if ethereal or tr.insert_type == IT_PLACEMENT:
        if radsum * radsum >= dy * dy + dx * dx + dz * dz:
            return COLLIDED
        return COLLIDED if second and collides_with_sphere(d2x, d2y, d2z, radsum) else OK
    if tr.step_down:
        return step_sphere_down(tr, ox, oy, oz, radius, dx, dy, dz, radsum)
    if tr.check_walkable:
        if collides_with_sphere(dx, dy, dz, radsum):
            return COLLIDED
        return COLLIDED if second and collides_with_sphere(d2x, d2y, d2z, radsum) else OK
    if tr.collide:  # only a landing sets it, and a landing is the reference path's
        return bail(tr, R_CLIMB)
    state = tr.oi_state
    if state & (OI_CONTACT | OI_ON_WALKABLE):
        if collides_with_sphere(dx, dy, dz, radsum):
            # CSphere::step_sphere_up (acclient.c:359071): too high to step over, skid off it
            reach = radsum + EPSILON
            if tr.oi_step_up_height < reach - dz:
                return slide_sphere_skid(tr, ox, oy, oz, dx, dy, dz, 0)
            return bail(tr, R_CLIMB)
        if second and collides_with_sphere(d2x, d2y, d2z, radsum):
            return slide_sphere(tr, ox, oy, oz, 1)
    elif state & OI_PATH_CLIPPED:
        if collides_with_sphere(dx, dy, dz, radsum):
            return collide_with_point(tr, ox, oy, oz, 0)
    else:
        if collides_with_sphere(dx, dy, dz, radsum):
            return bail(tr, R_CLIMB)  # land_on_sphere: set_collide, resolved by transitional_insert
        if second and collides_with_sphere(d2x, d2y, d2z, radsum):
            return collide_with_point(tr, ox, oy, oz, 1)
    return OK


# -- the body's side --------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def add_object(tr, j):
    """Record body ``j`` among the collision objects once (False when the list is full: the step
    bails). ``last_collided_object`` is read by nothing a step does, so it is not kept.

    Port of :meth:`acphys.transition.collision_info.CollisionInfo.add_object`.
    Retail: COLLISIONINFO::add_object @ 0x006B4E20 (acclient.c:718728)
    """
    for c in range(tr.num_collide):
        if tr.collide_body[c] == j:
            return True
    if tr.num_collide >= MAX_COLLIDE:
        return False
    tr.collide_body[tr.num_collide] = j
    tr.num_collide += 1
    return True


@njit(cache=True, _nrt=False)
def body_find_obj_collisions(w, tr, j):
    """Collide the sweep's spheres with body ``j`` (found through a cell's shadow list); BAIL for
    what the reference path must do.

    Port of :meth:`acphys.body.reports.CollisionReports.find_obj_collisions` for a body of spheres
    with no weenie (others bail: ``collider`` is False), hence no viewer, player or creature
    exemption, and a static body bails (it reports as the environment).
    Retail: CPhysicsObj::FindObjCollisions @ 0x0050F050 (acclient.c:316158)
    """
    other = bodies_of(w)[j]
    state = other.state
    if state & PS_ETHEREAL and state & PS_IGNORE_COLLISIONS:
        return OK
    if not other.collider:
        return bail(tr, R_SHAPE)
    mover_ethereal = bodies_of(w)[tr.oi_body].state & PS_ETHEREAL
    ethereal = bool(state & PS_ETHEREAL or (mover_ethereal and not state & PS_STATIC))
    if ethereal and tr.step_down:
        return OK
    if state & PS_MISSILE:  # OBJECTINFO::missile_ignore: a missile obstacle is passed through
        return OK
    if not tr.step_down and out_of_reach(w, tr, j):
        return OK
    result = OK
    for s in range(other.num_sphere):
        result = intersects_sphere(w, tr, j, s, ethereal)
        if result != OK:
            break
    if result in (BAIL, OK) or tr.step_down:
        return result
    if state & PS_STATIC:  # the environment: no collision object
        if not tr.oi_state & OI_CONTACT:
            tr.collided_with_environment = True
        return result
    if ethereal:
        result = OK
        tr.collision_normal_valid = False
    if not add_object(tr, j):
        return bail(tr, R_FULL)
    return result
