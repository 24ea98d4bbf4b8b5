"""The kernel's ``SPHEREPATH`` and ``COLLISIONINFO``: where a sweep's candidate is, what it
touched.

Ports of :mod:`acphys.transition.sphere_path` and :mod:`acphys.transition.collision_info` for the
transition record ``tr`` (:data:`~acphys.fast.layout.TRANSITION`); the sweep
(:mod:`acphys.fast.kernels.sweep`) and the sphere responses (:mod:`acphys.fast.kernels.contact`)
move the candidate and record contacts through them.
"""

from __future__ import annotations

from numba import njit

from acphys.fast.kernels.frame import f32, get_block_offset, v_normalize_check_small
from acphys.fast.kernels.store import put

#: ``SPHEREPATH::insert_type`` (:class:`acphys.transition.sphere_path.InsertType`).
IT_TRANSITION = 0
IT_PLACEMENT = 1
IT_INITIAL_PLACEMENT = 2


@njit(cache=True, inline="always", _nrt=False)
def t3(a):
    """A record's 3-array as the tuple the frame kernels take."""
    return (a[0], a[1], a[2])


@njit(cache=True, inline="always", _nrt=False)
def t4(a):
    return (a[0], a[1], a[2], a[3])


@njit(cache=True, inline="always", _nrt=False)
def t9(a):
    return (a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7], a[8])


# -- SPHEREPATH -----------------------------------------------------------------------------


@njit(cache=True, inline="always", _nrt=False)
def cache_global_curr_center(tr):
    """Place each local sphere centre in ``curr_pos``'s frame.

    Port of :meth:`acphys.transition.sphere_path.SpherePath.cache_global_curr_center`.
    Retail: SPHEREPATH::cache_global_curr_center @ 0x0050C740 (acclient.c:313696)
    """
    m, o = tr.curr_m, tr.curr_origin
    for s in range(tr.num_sphere):
        cx, cy, cz = tr.local_sphere[s, 0], tr.local_sphere[s, 1], tr.local_sphere[s, 2]
        tr.global_curr_center[s, 0] = f32(cx * m[0] + cy * m[3] + cz * m[6] + o[0])
        tr.global_curr_center[s, 1] = f32(m[7] * cz + cx * m[1] + m[4] * cy + o[1])
        tr.global_curr_center[s, 2] = f32(m[8] * cz + m[5] * cy + m[2] * cx + o[2])


@njit(cache=True, inline="always", _nrt=False)
def cache_global_sphere_at_check(tr):
    """Rebuild the global spheres and low point at ``check_pos``.

    Port of :meth:`acphys.transition.sphere_path.SpherePath.cache_global_sphere` (``offset`` None).
    Retail: SPHEREPATH::cache_global_sphere @ 0x0050C810 (acclient.c:313747)
    """
    m, o = tr.check_m, tr.check_origin
    for s in range(tr.num_sphere):
        cx, cy, cz = tr.local_sphere[s, 0], tr.local_sphere[s, 1], tr.local_sphere[s, 2]
        tr.global_sphere[s, 0] = f32(cx * m[0] + cy * m[3] + cz * m[6] + o[0])
        tr.global_sphere[s, 1] = f32(m[7] * cz + cx * m[1] + m[4] * cy + o[1])
        tr.global_sphere[s, 2] = f32(m[8] * cz + m[2] * cx + m[5] * cy + o[2])
        tr.global_sphere[s, 3] = tr.local_sphere[s, 3]
    px, py, pz = tr.local_low_point[0], tr.local_low_point[1], tr.local_low_point[2]
    tr.global_low_point[0] = f32(m[6] * pz + m[0] * px + m[3] * py + o[0])
    tr.global_low_point[1] = f32(m[7] * pz + m[1] * px + m[4] * py + o[1])
    tr.global_low_point[2] = f32(m[8] * pz + m[2] * px + m[5] * py + o[2])


@njit(cache=True, inline="always", _nrt=False)
def cache_global_sphere_offset(tr, dx, dy, dz):
    """Move the global spheres and low point by an offset (float32 stores: Vector3 sums).

    Port of :meth:`acphys.transition.sphere_path.SpherePath.cache_global_sphere` (with an offset).
    Retail: SPHEREPATH::cache_global_sphere @ 0x0050C810 (acclient.c:313747)
    """
    for s in range(tr.num_sphere):
        tr.global_sphere[s, 0] = f32(tr.global_sphere[s, 0] + dx)
        tr.global_sphere[s, 1] = f32(tr.global_sphere[s, 1] + dy)
        tr.global_sphere[s, 2] = f32(tr.global_sphere[s, 2] + dz)
    tr.global_low_point[0] = f32(tr.global_low_point[0] + dx)
    tr.global_low_point[1] = f32(tr.global_low_point[1] + dy)
    tr.global_low_point[2] = f32(tr.global_low_point[2] + dz)


@njit(cache=True, inline="always", _nrt=False)
def add_offset_to_check_pos(tr, dx, dy, dz):
    """Move ``check_pos`` and the global spheres; the cell array goes stale.

    Port of :meth:`acphys.transition.sphere_path.SpherePath.add_offset_to_check_pos`.
    Retail: SPHEREPATH::add_offset_to_check_pos @ 0x00509D10 (acclient.c:311556)
    """
    tr.cell_array_valid = False
    tr.check_origin[0] = f32(tr.check_origin[0] + dx)
    tr.check_origin[1] = f32(tr.check_origin[1] + dy)
    tr.check_origin[2] = f32(tr.check_origin[2] + dz)
    cache_global_sphere_offset(tr, dx, dy, dz)


@njit(cache=True, inline="always", _nrt=False)
def set_check_pos_to_curr(tr):
    """``set_check_pos(curr_pos, curr_cell)``: the candidate restarts where the sweep is.

    Port of :meth:`acphys.transition.sphere_path.SpherePath.set_check_pos`.
    Retail: SPHEREPATH::set_check_pos @ 0x0050A8B0 (acclient.c:312090)
    """
    tr.check_cell_id = tr.curr_cell_id
    put(tr.check_origin, tr.curr_origin)
    put(tr.check_q, tr.curr_q)
    put(tr.check_m, tr.curr_m)
    tr.check_cell = tr.curr_cell
    tr.cell_array_valid = False
    cache_global_sphere_at_check(tr)


@njit(cache=True, _nrt=False)
def save_check_pos(tr):
    """Port of :meth:`acphys.transition.sphere_path.SpherePath.save_check_pos`.
    Retail: SPHEREPATH::save_check_pos @ 0x0050A880 (acclient.c:312082)
    """
    tr.backup_cell = tr.check_cell
    tr.backup_cell_id = tr.check_cell_id
    put(tr.backup_origin, tr.check_origin)
    put(tr.backup_q, tr.check_q)
    put(tr.backup_m, tr.check_m)


@njit(cache=True, _nrt=False)
def restore_check_pos(tr):
    """Port of :meth:`acphys.transition.sphere_path.SpherePath.restore_check_pos`.
    Retail: SPHEREPATH::restore_check_pos @ 0x0050B100 (acclient.c:312527)
    """
    tr.check_cell_id = tr.backup_cell_id
    put(tr.check_origin, tr.backup_origin)
    put(tr.check_q, tr.backup_q)
    put(tr.check_m, tr.backup_m)
    tr.check_cell = tr.backup_cell
    tr.cell_array_valid = False
    cache_global_sphere_at_check(tr)


@njit(cache=True, inline="always", _nrt=False)
def adjust_check_pos(tr, cell_id):
    """Re-home ``check_pos`` into outdoor cell ``cell_id`` (shifting by the block offset).

    Port of :meth:`acphys.transition.sphere_path.SpherePath.adjust_check_pos`.
    Retail: SPHEREPATH::adjust_check_pos @ 0x0050CC00 (acclient.c:313961)
    """
    if (cell_id & 0xFFFF) < 0x100:
        dx, dy, dz = get_block_offset(cell_id, tr.check_cell_id)
        cache_global_sphere_offset(tr, dx, dy, dz)
        tr.check_origin[0] = f32(tr.check_origin[0] + dx)
        tr.check_origin[1] = f32(tr.check_origin[1] + dy)
        tr.check_origin[2] = f32(tr.check_origin[2] + dz)
    tr.check_cell_id = cell_id


# -- COLLISIONINFO --------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def set_contact_plane(tr, nx, ny, nz, d, is_water):
    """Port of :meth:`acphys.transition.collision_info.CollisionInfo.set_contact_plane`.
    Retail: COLLISIONINFO::set_contact_plane @ 0x00509D80 (acclient.c:311580)
    """
    tr.contact_plane_valid = True
    tr.contact_n[0] = nx
    tr.contact_n[1] = ny
    tr.contact_n[2] = nz
    tr.contact_d = d
    tr.contact_plane_is_water = is_water


@njit(cache=True, _nrt=False)
def set_collision_normal(tr, nx, ny, nz):
    """Store the normal normalised (zero when shorter than EPSILON; valid either way).

    Port of :meth:`acphys.transition.collision_info.CollisionInfo.set_collision_normal`.
    Retail: COLLISIONINFO::set_collision_normal @ 0x0050A000 (acclient.c:311725)
    """
    tr.collision_normal_valid = True
    small, n = v_normalize_check_small((f32(nx), f32(ny), f32(nz)))
    if small:
        n = (0.0, 0.0, 0.0)
    tr.collision_normal[0], tr.collision_normal[1], tr.collision_normal[2] = n


@njit(cache=True, _nrt=False)
def set_sliding_normal(tr, nx, ny):
    """Store the horizontal part of a normal, normalised (zero when too short).

    Port of :meth:`acphys.transition.collision_info.CollisionInfo.set_sliding_normal`.
    Retail: COLLISIONINFO::set_sliding_normal @ 0x0050A060 (acclient.c:311743)
    """
    tr.sliding_normal_valid = True
    small, n = v_normalize_check_small((f32(nx), f32(ny), 0.0))
    if small:
        n = (0.0, 0.0, 0.0)
    tr.sliding_normal[0], tr.sliding_normal[1], tr.sliding_normal[2] = n


@njit(cache=True, _nrt=False)
def collision_info_init(tr):
    """Port of :meth:`acphys.transition.collision_info.CollisionInfo.init`.
    Retail: COLLISIONINFO::init @ 0x00509D60 (acclient.c:311566)
    """
    tr.last_known_contact_plane_valid = False
    tr.contact_plane_valid = False
    tr.sliding_normal_valid = False
    tr.collision_normal_valid = False
    tr.collided_with_environment = False
    tr.contact_plane_cell_id = 0
    tr.frames_stationary_fall = 0
    tr.num_collide = 0
