"""The kernel's ``CPhysics::UseTime``: each body's ``update_object`` over its record, in table order.

Ports of :class:`acphys.physics_obj.PhysicsObj`'s tick (``update_object``,
``update_object_internal``, ``update_position_internal``, ``update_physics_internal``,
``calc_friction``, ``transition``, ``set_position_internal``, ``handle_all_collisions``) and of the
shadow bookkeeping of :mod:`acphys.body.cells`, for the bodies :mod:`acphys.fast.coverage` lets the
kernel step.

A body's update is all or nothing. Before it starts, its record, its interpolation row, what the
transition carries from sweep to sweep (its first ``CARRIED`` bytes: the rest the next sweep sets
afresh before reading) and the counters are saved and every change to the shadow pool is
journalled; when anything hands the step back (``BAIL``: something only the reference path does),
all of it is undone and :func:`run_bodies` returns that body's index for the engine to run on the
reference path.
"""

from __future__ import annotations

import math

from numba import njit

from acphys.constants import (
    ACTIVITY_DISTANCE,
    EPSILON,
    FLOOR_Z,
    GRAVITY,
    HUGE_QUANTUM,
    MAX_QUANTUM,
    MAX_VELOCITY,
    MIN_QUANTUM,
    SMALL_VELOCITY,
)
from acphys.fast.kernels.cells import (
    BAIL,
    R_CONTACT,
    R_FULL,
    R_GLIDE,
    R_HOOK,
    R_MOTION,
    R_NO_CELL,
    R_RECORDS,
    R_STATIC,
    R_UNREAD,
    bail,
)
from acphys.fast.kernels.context import (
    anims_of,
    bodies_of,
    cells_of,
    clock_of,
    counters_of,
    glides_of,
    grid_of,
    handback_of,
    heads_of,
    hooks_of,
    journal_of,
    log_of,
    moves_of,
    owed_of,
    pos_frames_of,
    shadow_pool_of,
)
from acphys.fast.kernels.frame import (
    IDENTITY_M,
    f32,
    frame_combine,
    frame_grotate,
    frame_is_valid,
    frame_is_valid_except_for_heading,
    frame_set_vector_heading,
    position_get_offset,
    v_length,
    v_normalized,
    v_sub,
)
from acphys.fast.kernels.grid import MAX_REACH, block_origin, grid_place, reach_now, reach_turned, span_bits
from acphys.fast.kernels.interpolation import GIVE_UP, blips
from acphys.fast.kernels.interpolation import adjust_offset as glide_offset
from acphys.fast.kernels.motion_queues import retire_motions
from acphys.fast.kernels.path import cache_global_curr_center, set_sliding_normal, t3, t4, t9
from acphys.fast.kernels.sequence import STATUS_ANIM_DONE, STATUS_DONE, STATUS_REFERENCE, sequence_update
from acphys.fast.kernels.store import copy_head, copy_record, copy_span, fill, put
from acphys.fast.kernels.sweep import find_transitional_position, nobody_near, transition_init
from acphys.fast.layout import CARRIED, MAX_CELLS, MAX_COLLIDE, MAX_RECORDS, PLANE_BYTES
from acphys.flags import ObjectInfoState, PhysicsState, TransientState

PS_STATIC = int(PhysicsState.STATIC)
PS_ETHEREAL = int(PhysicsState.ETHEREAL)
PS_IGNORE_COLLISIONS = int(PhysicsState.IGNORE_COLLISIONS)
PS_REPORT_AS_ENVIRONMENT = int(PhysicsState.REPORT_COLLISIONS_AS_ENVIRONMENT)
PS_REPORT_COLLISIONS = int(PhysicsState.REPORT_COLLISIONS)
PS_MISSILE = int(PhysicsState.MISSILE)
PS_ALIGN_PATH = int(PhysicsState.ALIGN_PATH)
PS_PATH_CLIPPED = int(PhysicsState.PATH_CLIPPED)
PS_GRAVITY = int(PhysicsState.GRAVITY)
PS_EDGE_SLIDE = int(PhysicsState.EDGE_SLIDE)
PS_SLEDDING = int(PhysicsState.SLEDDING)
PS_FROZEN = int(PhysicsState.FROZEN)
PS_INELASTIC = int(PhysicsState.INELASTIC)
PS_HIDDEN = int(PhysicsState.HIDDEN)
TS_CONTACT = int(TransientState.CONTACT)
TS_ON_WALKABLE = int(TransientState.ON_WALKABLE)
TS_SLIDING = int(TransientState.SLIDING)
TS_WATER_CONTACT = int(TransientState.WATER_CONTACT)
TS_STATIONARY_FALL = int(TransientState.STATIONARY_FALL)
TS_STATIONARY_STOP = int(TransientState.STATIONARY_STOP)
TS_STATIONARY_STUCK = int(TransientState.STATIONARY_STUCK)
TS_ACTIVE = int(TransientState.ACTIVE)
STATIONARY_MASK = TS_STATIONARY_FALL | TS_STATIONARY_STOP | TS_STATIONARY_STUCK
OI_CONTACT = int(ObjectInfoState.CONTACT)
OI_ON_WALKABLE = int(ObjectInfoState.ON_WALKABLE)
OI_EDGE_SLIDE = int(ObjectInfoState.EDGE_SLIDE)
OI_PATH_CLIPPED = int(ObjectInfoState.PATH_CLIPPED)
OI_FREE_ROTATE = int(ObjectInfoState.FREE_ROTATE)

# What run_bodies returns with the index it stopped at.
DONE = 0  # every body from the start index on was updated
FALLBACK = 1  # the body at the index must be updated on the reference path
GROW = 2  # a cell's shadow list is full (counters[GROW_CELL]); grow it and call again from the index
LOG_FULL = 3  # the trace log is full; write it out and call again from the index
UNREAD = 4  # a land cell of a landblock the arrays lack (counters[UNREAD_CELL]); read it, call again

#: ``update_position_internal``'s status when the interpolation manager gave a node up (beside the
#: sequence's ``STATUS_*``): the reference path takes the step.
STATUS_GLIDE = 3

# Slots of the counters array.
STEPS = 0  # body-steps the kernel took
LOGGED = 1  # rows in the trace log
MOVES = 2  # rows in the cell-move log
JOURNAL = 3  # rows in the undo journal
GROW_CELL = 4
REASON = 5  # why the last body handed its update back (acphys.fast.kernels.cells.BAIL_REASONS)
OWED = 6  # rows in the deferred log (DEFERRED_*): what the engine does when the kernel returns
TOUCHING = 7  # body-steps the kernel took whose sweep met another body
UNREAD_CELL = 8
NUM_COUNTERS = 9

#: ``handback``, where the last update handed back was sweeping (the engine writes back only what
#: a reference step from there can read): HB_SWEPT is 1.0 when the update began its sweep, and
#: then the path's two ends follow, each as (cell id, landblock-local x, y, z); else 0.0.
HB_SWEPT = 0
HB_BEGIN = 1
HB_END = 5
HANDBACK_SLOTS = 9

# Trace log row: body, t, quantum, cell id, origin[3], q[4], velocity[3], cached velocity[3],
# omega[3], transient, contact normal[3], events.
LOG_WIDTH = 27
EVENT_HIT_GROUND = 1
EVENT_LEAVE_GROUND = 2
EVENT_COLLISION_ENVIRONMENT = 4
#: The record's events begin with what the object held before the step (its ``step_events``).
EVENT_PENDING = 8
#: The most steps one update takes: HUGE_QUANTUM / MAX_QUANTUM quanta (and a remainder).
MAX_STEPS_PER_UPDATE = 11
JOURNAL_ROWS = 4096
#: Kinds of the deferred log's rows ``(kind, a, b, c, d)``: an AnimDone hook owed
#: ``(body, count)``; a collision report or the report of its end ``(row, receiver, other,
#: own)``: ``receiver`` hears of ``other`` (``collision:NAME``, ``collision_end:NAME``), in the
#: trace row ``row`` when ``own`` (the mover's own step), else before the receiver's next step.
DEFERRED_ANIM_DONE = 0
DEFERRED_COLLISION = 1
DEFERRED_COLLISION_END = 2
DEFERRED_WIDTH = 5
#: The most deferred rows one quantum adds: its AnimDone row, two reports per body touched and
#: per record ended.
DEFERRED_PER_STEP = 1 + 2 * MAX_COLLIDE + 2 * MAX_RECORDS

# Journal row kinds: pool[a] was b; cells[a].num_shadows was b;
# bodies[a // MAX_CELLS].shadow_slot[a % MAX_CELLS] was b.
J_POOL = 0
J_COUNT = 1
J_SLOT = 2


# -- the shadow pool, journalled ---------------------------------------------------------------


@njit(cache=True, _nrt=False)
def _journal(w, kind, a, b):
    journal, counters = journal_of(w), counters_of(w)
    n = counters[JOURNAL]
    if n >= journal.shape[0]:
        return False
    journal[n, 0] = kind
    journal[n, 1] = a
    journal[n, 2] = b
    counters[JOURNAL] = n + 1
    return True


@njit(cache=True, _nrt=False)
def _undo(w):
    bodies, cells, shadow_pool = bodies_of(w), cells_of(w), shadow_pool_of(w)
    journal, counters = journal_of(w), counters_of(w)
    for n in range(counters[JOURNAL] - 1, -1, -1):
        kind, a, b = journal[n, 0], journal[n, 1], journal[n, 2]
        if kind == J_POOL:
            shadow_pool[a] = b
        elif kind == J_COUNT:
            cells[a].num_shadows = b
        else:
            bodies[a // MAX_CELLS].shadow_slot[a % MAX_CELLS] = b
    counters[JOURNAL] = 0


@njit(cache=True, inline="always", _nrt=False)
def remove_shadows_from_cells(w, i):
    """Take each of body ``i``'s shadows out of its cell (the cell's last entry takes its slot).

    Port of :meth:`acphys.body.cells.CellMembership.remove_shadows_from_cells` and
    :meth:`acphys.world.obj_cell.ObjCell.remove_shadow_object`.
    Retail: CPhysicsObj::remove_shadows_from_cells @ 0x00511230 (acclient.c:318417)
    """
    bodies, cells, shadow_pool = bodies_of(w), cells_of(w), shadow_pool_of(w)
    b = bodies[i]
    for s in range(b.num_shadow):
        k = b.shadow_cell[s]
        if k < 0:
            continue
        cell = cells[k]
        index = b.shadow_slot[s]
        last = cell.num_shadows - 1
        start = cell.shadow_start
        if not _journal(w, J_COUNT, k, cell.num_shadows):
            return False
        moved = shadow_pool[start + last]
        if index != last:
            if not _journal(w, J_POOL, start + index, shadow_pool[start + index]):
                return False
            shadow_pool[start + index] = moved
            if moved >= 0:
                other = bodies[moved]
                for t in range(other.num_shadow):
                    if other.shadow_cell[t] == k:
                        slot = moved * MAX_CELLS + t
                        if not _journal(w, J_SLOT, slot, other.shadow_slot[t]):
                            return False
                        other.shadow_slot[t] = index
        cell.num_shadows = last
        cell.dirty = True
    b.num_shadow = 0
    return True


@njit(cache=True, inline="always", _nrt=False)
def add_shadows_to_cells(w, tr, i):
    """One shadow per cell of the transition's cell array, appended to that cell's list. Returns
    -1 when done, else the index of a cell whose list is full.

    Port of :meth:`acphys.body.cells.CellMembership.add_shadows_to_cells` and
    :meth:`acphys.world.obj_cell.ObjCell.add_shadow_object`.
    Retail: CPhysicsObj::add_shadows_to_cells @ 0x00514AE0 (acclient.c:321977)
    """
    cells, shadow_pool = cells_of(w), shadow_pool_of(w)
    b = bodies_of(w)[i]
    for s in range(tr.num_cells):
        k = tr.cells[s]
        b.shadow_cell[s] = k
        b.shadow_cell_id[s] = tr.cell_ids[s]
        b.shadow_slot[s] = -1
        if k < 0:
            continue
        cell = cells[k]
        count = cell.num_shadows
        if count >= cell.shadow_capacity:
            return k
        if not _journal(w, J_COUNT, k, count):
            return -2
        at = cell.shadow_start + count
        if not _journal(w, J_POOL, at, shadow_pool[at]):
            return -2
        shadow_pool[at] = i
        cell.num_shadows = count + 1
        cell.dirty = True
        b.shadow_slot[s] = count
    b.num_shadow = tr.num_cells
    b.shadows_moved = True
    return -1


# -- the body's state -----------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def calc_acceleration(b):
    """Port of :meth:`acphys.physics_obj.PhysicsObj.calc_acceleration`.
    Retail: CPhysicsObj::calc_acceleration @ 0x00510950 (acclient.c:317786)
    """
    ts = b.transient
    if ts & TS_CONTACT and ts & TS_ON_WALKABLE and not b.state & PS_SLEDDING:
        fill(b.acceleration, 0.0)
        fill(b.omega, 0.0)
    elif b.state & PS_GRAVITY:
        b.acceleration[0] = 0.0
        b.acceleration[1] = 0.0
        b.acceleration[2] = GRAVITY
    else:
        fill(b.acceleration, 0.0)


@njit(cache=True, _nrt=False)
def set_on_walkable(b, on, events):
    """Set ON_WALKABLE, note landing and leaving, recompute the acceleration; BAIL when a movement
    manager would have to hear of it (its interpreter replays motions).

    Port of :meth:`acphys.physics_obj.PhysicsObj.set_on_walkable`.
    Retail: CPhysicsObj::set_on_walkable @ 0x00511310 (acclient.c:318501)
    """
    was = b.transient & TS_ON_WALKABLE
    if on:
        b.transient |= TS_ON_WALKABLE
    else:
        b.transient &= ~TS_ON_WALKABLE
    if was and not on:
        if b.has_movement_manager:
            return BAIL, events
        events |= EVENT_LEAVE_GROUND
    elif not was and on:
        if b.has_movement_manager:
            return BAIL, events
        events |= EVENT_HIT_GROUND
    calc_acceleration(b)
    return 0, events


@njit(cache=True, inline="always", _nrt=False)
def set_frame(b, origin, q, m):
    """Make the frame the body's (a sound origin with a NaN quaternion commits an all-zero one).

    Port of :meth:`acphys.physics_obj.PhysicsObj.set_frame` (the parts follow when the record is
    written back; a covered body holds nothing).
    Retail: CPhysicsObj::set_frame @ 0x00514090 (acclient.c:321327)
    """
    if not frame_is_valid(origin, q) and frame_is_valid_except_for_heading(origin, q):
        q = (0.0, 0.0, 0.0, 0.0)
    b.origin[0], b.origin[1], b.origin[2] = origin
    b.q[0], b.q[1], b.q[2], b.q[3] = q
    put(b.m, m)


# -- the candidate frame ------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def calc_friction(b, quantum, velocity_mag2):
    """Port of :meth:`acphys.physics_obj.PhysicsObj.calc_friction` (not a sledding body).
    Retail: CPhysicsObj::calc_friction @ 0x0050EE70 (acclient.c:316090)
    """
    if not b.transient & TS_ON_WALKABLE:
        return
    n = b.contact_n
    v = b.velocity
    normal_speed = v[2] * n[2] + v[1] * n[1] + v[0] * n[0]
    if normal_speed >= 0.25:
        return
    dz = f32(normal_speed * n[2])
    v[0], v[1], v[2] = f32(v[0] - normal_speed * n[0]), f32(v[1] - normal_speed * n[1]), f32(v[2] - dz)
    factor = math.pow(1.0 - b.friction, quantum)
    v[0], v[1], v[2] = f32(factor * v[0]), f32(factor * v[1]), f32(factor * v[2])


@njit(cache=True, inline="always", _nrt=False)
def update_physics_internal(b, quantum, origin, q, m):
    """Euler-integrate velocity, acceleration and omega into the candidate; returns it.

    Port of :meth:`acphys.physics_obj.PhysicsObj.update_physics_internal`.
    Retail: CPhysicsObj::UpdatePhysicsInternal @ 0x00510700 (acclient.c:317700)
    """
    v = b.velocity
    a = b.acceleration
    velocity_mag2 = f32(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
    if velocity_mag2 <= 0.0:
        if not b.has_movement_manager and b.transient & TS_ON_WALKABLE:
            b.transient &= ~TS_ACTIVE
    else:
        if velocity_mag2 > MAX_VELOCITY * MAX_VELOCITY:
            n = v_normalized((v[0], v[1], v[2]))
            v[0], v[1], v[2] = f32(n[0] * MAX_VELOCITY), f32(n[1] * MAX_VELOCITY), f32(n[2] * MAX_VELOCITY)
            velocity_mag2 = MAX_VELOCITY * MAX_VELOCITY
        calc_friction(b, quantum, velocity_mag2)
        if velocity_mag2 - SMALL_VELOCITY * SMALL_VELOCITY < EPSILON:
            fill(v, 0.0)
        ax_half_dt = f32(a[0] * 0.5 * quantum)
        ay_term = f32(a[1] * 0.5 * quantum * quantum)
        vz_term = f32(quantum * v[2])
        half_az = f32(a[2] * 0.5)
        move_x = f32(quantum * v[0] + f32(ax_half_dt * quantum))
        move_z = f32(vz_term + half_az * quantum * quantum)
        origin = (
            f32(move_x + origin[0]),
            f32(quantum * v[1] + ay_term + origin[1]),
            f32(move_z + origin[2]),
        )
    dvz = f32(quantum * a[2])
    v[0], v[1], v[2] = f32(quantum * a[0] + v[0]), f32(quantum * a[1] + v[1]), f32(dvz + v[2])
    w = (f32(b.omega[0] * quantum), f32(b.omega[1] * quantum), f32(b.omega[2] * quantum))
    q, m = frame_grotate(origin, q, m, w)
    return origin, q, m


@njit(cache=True, inline="always", _nrt=False)
def update_position_internal(w, b, quantum):
    """The candidate frame: root motion (the sequence played into an offset frame), scaled on
    walkable ground, combined onto the body's frame, then integrated. ``(status, origin, q, m)``:
    the sequence's status (``STATUS_REFERENCE``, returned at once: a frame hook the reference path
    plays; ``STATUS_ANIM_DONE``: AnimDone hooks for ``process_hooks``, which the caller runs), or
    ``STATUS_GLIDE``, returned at once: the interpolation manager gave a node up.

    Port of :meth:`acphys.physics_obj.PhysicsObj.update_position_internal` and
    :meth:`acphys.part_array.PartArray.update`.
    Retail: CPhysicsObj::UpdatePositionInternal @ 0x00512C30 (acclient.c:319988),
    CPartArray::Update @ 0x00517DB0 (acclient.c:325139), PositionManager::adjust_offset
    @ 0x00555190 (acclient.c:388286)
    """
    o = (0.0, 0.0, 0.0)
    oq = (1.0, 0.0, 0.0, 0.0)
    om = IDENTITY_M
    status = STATUS_DONE
    if not b.state & PS_HIDDEN:
        status, o, oq, om = sequence_update(b, anims_of(w), pos_frames_of(w), hooks_of(w), quantum, o, oq, om)
        if status == STATUS_REFERENCE:
            return status, o, oq, om
        factor = b.scale if b.transient & TS_ON_WALKABLE else 0.0
        o = (f32(o[0] * factor), f32(o[1] * factor), f32(o[2] * factor))
    if b.glide >= 0:  # the position manager: its interpolation manager alone
        return _glided_candidate(w, b, quantum, status, o, oq, om)
    origin, q, m = _candidate(b, quantum, o, oq)
    return status, origin, q, m


@njit(cache=True, inline="always", _nrt=False)
def _candidate(b, quantum, o, oq):
    """The offset frame ``o, oq`` combined onto the body's frame, then integrated (the end of
    ``update_position_internal``)."""
    origin, q, m = frame_combine(
        (0.0, 0.0, 0.0), (1.0, 0.0, 0.0, 0.0), IDENTITY_M, t3(b.origin), t4(b.q), t9(b.m), o, oq
    )
    if not b.state & PS_HIDDEN:
        origin, q, m = update_physics_internal(b, quantum, origin, q, m)
    return origin, q, m


@njit(cache=True, _nrt=False)
def _glided_candidate(w, b, quantum, status, o, oq, om):
    """``update_position_internal`` past the root motion for a body with a position manager: the
    offset ``o, oq, om`` as its interpolation leaves it, then combined and integrated (a call of
    its own, to keep the glide out of other bodies' steps)."""
    glided, o, oq, om = glide_offset(b, glides_of(w)[b.glide], quantum, o, oq, om)
    if glided == GIVE_UP:
        return STATUS_GLIDE, o, oq, om
    origin, q, m = _candidate(b, quantum, o, oq)
    return status, origin, q, m


# -- the sweep and the commit ----------------------------------------------------------------------


@njit(cache=True, inline="always", _nrt=False)
def _lonely_sweep(w, tr, b, end, end_q):
    """Whether no other body is filed near anywhere this sweep can take the spheres. Across the
    ground, a sweep moves its candidate only along its steps (bent, never lengthened, by the
    contact plane and the sliding normal), back towards where it was (rollbacks, edge slides),
    or along a crease by less than a step (cliff slides); lifts, landings and steps up and down
    are vertical. So the spheres stay within the box around the path's two ends widened by the
    body's reach and the path's length (bounded by its run across x plus its run across y, which
    spares a square root; and half a metre): its reach upright when it turns
    from upright to upright (every orientation of the sweep lies on the slerp between the two,
    upright too; :func:`~acphys.fast.kernels.grid.reach_now`). Not retail: a shortcut past
    ``find_obj_collisions``, whose every answer is then OK (:func:`~acphys.fast.kernels.sweep.
    nobody_near`)."""
    x0, y0 = block_origin(b.cell_id)
    bx, by, ex, ey = x0 + b.origin[0], y0 + b.origin[1], x0 + end[0], y0 + end[1]
    widen = max(reach_now(b), reach_turned(b, end_q)) + abs(ex - bx) + abs(ey - by) + 0.5
    return nobody_near(
        w, tr, min(bx, ex) - widen, min(by, ey) - widen, max(bx, ex) + widen, max(by, ey) + widen
    )


@njit(cache=True, _nrt=False)
def transition(w, tr, i, origin, q, m):
    """Sweep body ``i`` from where it is to the candidate: 1 found, 0 not, BAIL.

    Port of :meth:`acphys.physics_obj.PhysicsObj.transition` with ``get_object_info`` and
    ``OBJECTINFO::init`` (no weenie: a covered body has none).
    Retail: CPhysicsObj::transition @ 0x00512DC0 (acclient.c:320060), CPhysicsObj::get_object_info
    @ 0x00511CC0 (acclient.c:319073), OBJECTINFO::init @ 0x0050CF30 (acclient.c:314117)
    """
    b = bodies_of(w)[i]
    transition_init(tr)
    state = OI_EDGE_SLIDE if b.state & PS_EDGE_SLIDE else 0
    ts = b.transient
    if ts & TS_CONTACT:
        is_water = bool(ts & TS_WATER_CONTACT)
        v, n = b.velocity, b.contact_n
        tr.last_known_contact_plane_valid = True
        copy_span(tr, "last_known_contact_n", b, "contact_n", PLANE_BYTES)  # and _d
        tr.last_known_contact_plane_is_water = is_water
        if not v[2] * n[2] + v[1] * n[1] + v[0] * n[0] > EPSILON:  # check_contact(True)
            tr.last_known_contact_plane_cell_id = b.contact_cell_id
            tr.contact_plane_valid = True
            copy_span(tr, "contact_n", b, "contact_n", PLANE_BYTES)  # and contact_d
            tr.contact_plane_is_water = is_water
            state |= OI_CONTACT
            if ts & TS_ON_WALKABLE:
                state |= OI_ON_WALKABLE
        tr.contact_plane_cell_id = b.contact_cell_id
    if ts & TS_SLIDING:
        set_sliding_normal(tr, b.sliding_normal[0], b.sliding_normal[1])
    if b.free_heading:
        state |= OI_FREE_ROTATE
    if b.state & PS_MISSILE:
        state |= OI_PATH_CLIPPED
    tr.oi_body = i
    tr.oi_state = state
    scale = b.scale
    tr.oi_scale = scale
    tr.oi_step_up_height = f32(b.step_up_height * scale)
    tr.oi_step_down_height = f32(b.step_down_height * scale)
    tr.oi_step_down = not b.state & PS_MISSILE
    # SPHEREPATH::init_sphere: the first two spheres, scaled
    tr.num_sphere = b.num_sphere
    for s in range(b.num_sphere):
        x, y, z = f32(b.sphere[s, 0] * scale), f32(b.sphere[s, 1] * scale), f32(b.sphere[s, 2] * scale)
        radius = f32(scale * b.sphere[s, 3])
        tr.local_sphere[s, 0], tr.local_sphere[s, 1], tr.local_sphere[s, 2] = x, y, z
        tr.local_sphere[s, 3] = radius
        if s == 0:  # from the values, not read back: a wide read of fresh narrow stores stalls
            tr.local_low_point[0], tr.local_low_point[1], tr.local_low_point[2] = x, y, f32(z - radius)
    # SPHEREPATH::init_path
    tr.begin_cell = b.cell
    tr.begin_cell_id = b.cell_id
    put(tr.begin_origin, b.origin)
    put(tr.begin_q, b.q)
    tr.end_cell_id = b.cell_id
    tr.end_origin[0], tr.end_origin[1], tr.end_origin[2] = origin
    tr.end_q[0], tr.end_q[1], tr.end_q[2], tr.end_q[3] = q
    tr.curr_cell = b.cell
    tr.curr_cell_id = b.cell_id
    put(tr.curr_origin, b.origin)
    put(tr.curr_q, b.q)
    put(tr.curr_m, b.m)
    cache_global_curr_center(tr)
    tr.insert_type = 0
    tr.lonely = _lonely_sweep(w, tr, b, origin, q)
    if ts & TS_STATIONARY_STUCK:
        tr.frames_stationary_fall = 3
    elif ts & TS_STATIONARY_STOP:
        tr.frames_stationary_fall = 2
    elif ts & TS_STATIONARY_FALL:
        tr.frames_stationary_fall = 1
    return find_transitional_position(w, tr)


@njit(cache=True, _nrt=False)
def _expired(b, r, now):
    age = now - b.record_time[r]
    return age > 1.0 or (b.record_ethereal[r] and age > 0.0)


@njit(cache=True, _nrt=False)
def _body_of(bodies, obj_id):
    for j in range(len(bodies)):
        if bodies[j].obj_id == obj_id:
            return j
    return -1


@njit(cache=True, inline="always", _nrt=False)
def end_collisions(w, i, now):
    """Drop the records of body ``i`` untouched for over a second (an ethereal one for any time)
    and report their ends (``collision_end:NAME``, deferred: :data:`DEFERRED_COLLISION_END`), in
    retail's table order: bucket ``(id ^ (id >> 8)) & 3`` from 0 to 3, the newest record first in
    a bucket (no report of one that reports as the environment). Returns 0, or why the reference
    path must: the other body is not the kernel's to answer for (uncovered, gone, a callback).

    Port of :meth:`acphys.body.reports.CollisionReports.report_collision_end` (not forced) and
    :meth:`~acphys.body.reports.CollisionReports.report_object_collision_end`.
    Retail: CPhysicsObj::report_collision_end @ 0x00514620 (acclient.c:321712),
    CPhysicsObj::report_object_collision_end @ 0x00510A90 (acclient.c:317868)
    """
    bodies = bodies_of(w)
    b = bodies[i]
    count = b.num_records
    any_ended = False
    for r in range(count):
        if _expired(b, r, now):
            any_ended = True
    if not any_ended:
        return 0
    row = counters_of(w)[LOGGED]
    for bucket in range(4):
        for r in range(count - 1, -1, -1):  # records are kept oldest first: newest first here
            obj_id = b.record_obj[r]
            if (obj_id ^ (obj_id >> 8)) & 3 != bucket or not _expired(b, r, now):
                continue
            j = _body_of(bodies, obj_id)
            if j < 0 or not bodies[j].covered or bodies[j].on_collision:
                return R_RECORDS
            other = bodies[j]
            if other.state & PS_REPORT_AS_ENVIRONMENT:  # the environment: no end is reported
                continue
            if b.state & PS_REPORT_COLLISIONS:
                _defer(w, DEFERRED_COLLISION_END, row, i, j, 1)
            if other.state & PS_REPORT_COLLISIONS:
                _defer(w, DEFERRED_COLLISION_END, row, j, i, 0)
    kept = 0
    for r in range(count):  # the survivors keep their order
        if not _expired(b, r, now):
            b.record_obj[kept] = b.record_obj[r]
            b.record_time[kept] = b.record_time[r]
            b.record_ethereal[kept] = b.record_ethereal[r]
            kept += 1
    b.num_records = kept
    return 0


@njit(cache=True, _nrt=False)
def _defer(w, kind, a, b, c, d):
    """Append a row ``(kind, a, b, c, d)`` to the deferred log (:data:`DEFERRED_ANIM_DONE`, ...)."""
    owed, counters = owed_of(w), counters_of(w)
    n = counters[OWED]
    owed[n, 0] = kind
    owed[n, 1] = a
    owed[n, 2] = b
    owed[n, 3] = c
    owed[n, 4] = d
    counters[OWED] = n + 1


@njit(cache=True, inline="always", _nrt=False)
def track_object_collisions(w, tr, i, now):
    """Stamp each body the sweep touched into body ``i``'s collision records with the physics time
    and its ETHEREAL bit; a body touched for the first time gets a record, and the two bodies
    hear of each other (``collision:NAME``, deferred: :data:`DEFERRED_COLLISION`). Returns 0, or
    why the reference path must: a static body (the environment), a missile's attack report, a
    receiver that reports as the environment or calls back, a full table.

    The tracking part of :meth:`acphys.physics_obj.PhysicsObj.handle_all_collisions`,
    :meth:`acphys.body.reports.CollisionReports.track_object_collision` (``clobber`` replaces a
    known record in place and appends a new one) and, for a first touch,
    :meth:`~acphys.body.reports.CollisionReports.report_object_collision`.
    Retail: CPhysicsObj::handle_all_collisions @ 0x00514780 (acclient.c:321807),
    CPhysicsObj::track_object_collision @ 0x00513F10 (acclient.c:321216),
    CPhysicsObj::report_object_collision @ 0x00513060 (acclient.c:320227)
    """
    bodies = bodies_of(w)
    b = bodies[i]
    for c in range(tr.num_collide):
        j = tr.collide_body[c]
        other = bodies[j]
        if other.state & PS_STATIC:
            return R_STATIC
        known = -1
        for r in range(b.num_records):
            if b.record_obj[r] == other.obj_id:
                known = r
        if known >= 0:
            b.record_time[known] = now
            b.record_ethereal[known] = bool(other.state & PS_ETHEREAL)
            continue
        if b.num_records >= MAX_RECORDS:
            return R_FULL
        if b.state & PS_MISSILE or other.on_collision:  # an attack report; a user's callback
            return R_CONTACT
        if other.state & (PS_MISSILE | PS_REPORT_AS_ENVIRONMENT):
            return R_CONTACT
        r = b.num_records
        b.record_obj[r] = other.obj_id
        b.record_time[r] = now
        b.record_ethereal[r] = bool(other.state & PS_ETHEREAL)
        b.num_records = r + 1
        row = counters_of(w)[LOGGED]
        if not other.state & PS_IGNORE_COLLISIONS and b.state & PS_REPORT_COLLISIONS:
            _defer(w, DEFERRED_COLLISION, row, i, j, 1)
        if other.state & PS_REPORT_COLLISIONS and not b.state & PS_IGNORE_COLLISIONS:
            _defer(w, DEFERRED_COLLISION, row, j, i, 0)
    return 0


@njit(cache=True, inline="always", _nrt=False)
def handle_all_collisions(b, tr, prev_contact, prev_on_walkable, events):
    """Report touching the environment, bounce or stop, and keep the stationary bits.

    Port of :meth:`acphys.physics_obj.PhysicsObj.handle_all_collisions` after the tracking
    (:func:`track_object_collisions`, :func:`end_collisions`) and of
    :meth:`acphys.body.reports.CollisionReports.report_environment_collision`.
    Retail: CPhysicsObj::handle_all_collisions @ 0x00514780 (acclient.c:321807),
    CPhysicsObj::report_environment_collision @ 0x00512FC0 (acclient.c:320193)
    """
    on_walkable = b.transient & TS_ON_WALKABLE
    apply_bounce = not (prev_on_walkable and on_walkable) or b.state & PS_SLEDDING
    if b.colliding_with_environment:
        b.colliding_with_environment = tr.collided_with_environment
    elif tr.collided_with_environment or (not prev_on_walkable and on_walkable):
        if b.state & PS_REPORT_COLLISIONS:
            events |= EVENT_COLLISION_ENVIRONMENT
        b.colliding_with_environment = True
        if b.state & PS_MISSILE:
            b.state &= ~(PS_MISSILE | PS_ALIGN_PATH | PS_PATH_CLIPPED)
    frames = tr.frames_stationary_fall
    v = b.velocity
    if frames <= 1:
        if apply_bounce and tr.collision_normal_valid:
            if b.state & PS_INELASTIC:
                fill(v, 0.0)
            else:
                n = tr.collision_normal
                approach = v[2] * n[2] + v[1] * n[1] + n[0] * v[0]
                if approach < 0.0:
                    impulse = -(approach * (b.elasticity + 1.0))
                    dy = f32(impulse * n[1])
                    dz = f32(impulse * n[2])
                    v[0], v[1], v[2] = f32(impulse * n[0] + v[0]), f32(dy + v[1]), f32(dz + v[2])
    else:
        fill(v, 0.0)
    if frames == 0 or frames == 3:
        b.transient &= ~STATIONARY_MASK
    elif frames == 1:
        b.transient |= TS_STATIONARY_FALL
    elif frames == 2:
        b.transient |= TS_STATIONARY_STOP
    else:
        b.transient |= TS_STATIONARY_STUCK
    return events


@njit(cache=True, _nrt=False)
def set_position_internal(w, tr, i, now, events):
    """Commit the sweep: cell, frame, contact, walkable, water, sliding, collisions, shadows.
    Returns ``(status, events)``: 0, BAIL, or ``GROW`` with the full cell in the counters.

    ``now`` is the physics time (the collision records' clock).

    Port of :meth:`acphys.physics_obj.PhysicsObj.set_position_internal`.
    Retail: CPhysicsObj::SetPositionInternal @ 0x00515330 (acclient.c:322503)
    """
    bodies, cells, counters = bodies_of(w), cells_of(w), counters_of(w)
    b = bodies[i]
    prev_on_walkable = b.transient & TS_ON_WALKABLE
    prev_contact = b.transient & TS_CONTACT
    if tr.curr_cell < 0:
        return bail(tr, R_NO_CELL), events
    if b.cell == tr.curr_cell:
        b.cell_id = tr.curr_cell_id
    else:
        moves = moves_of(w)
        n = counters[MOVES]
        if n >= moves.shape[0]:
            return bail(tr, R_FULL), events
        moves[n, 0] = i
        moves[n, 1] = b.cell
        moves[n, 2] = tr.curr_cell
        counters[MOVES] = n + 1
        b.cell = tr.curr_cell
        b.cell_id = cells[tr.curr_cell].cell_id
    set_frame(b, t3(tr.curr_origin), t4(tr.curr_q), t9(tr.curr_m))
    b.contact_cell_id = tr.contact_plane_cell_id
    put(b.contact_n, tr.contact_n)
    b.contact_d = tr.contact_d
    if tr.contact_plane_valid:
        b.transient |= TS_CONTACT
    else:
        b.transient &= ~TS_CONTACT
    calc_acceleration(b)
    if tr.contact_plane_is_water:
        b.transient |= TS_WATER_CONTACT
    else:
        b.transient &= ~TS_WATER_CONTACT
    if b.transient & TS_CONTACT:
        status, events = set_on_walkable(b, b.contact_n[2] >= FLOOR_Z, events)
        if status == BAIL:
            return bail(tr, R_MOTION), events
    else:
        was = b.transient & TS_ON_WALKABLE
        b.transient &= ~TS_ON_WALKABLE
        if was:
            if b.has_movement_manager:
                return bail(tr, R_MOTION), events
            events |= EVENT_LEAVE_GROUND
        calc_acceleration(b)
    put(b.sliding_normal, tr.sliding_normal)
    if tr.sliding_normal_valid:
        b.transient |= TS_SLIDING
    else:
        b.transient &= ~TS_SLIDING
    first_report = counters[OWED]
    reason = track_object_collisions(w, tr, i, now)
    if reason:
        return bail(tr, reason), events
    reason = end_collisions(w, i, now)
    if reason:
        return bail(tr, reason), events
    events = handle_all_collisions(b, tr, prev_contact, prev_on_walkable, events)
    if tr.num_cells:
        if not remove_shadows_from_cells(w, i):
            return bail(tr, R_FULL), events
        full = add_shadows_to_cells(w, tr, i)
        if full == -2:
            return bail(tr, R_FULL), events
        if full >= 0:
            counters[GROW_CELL] = full
            return GROW, events
    owed = owed_of(w)
    for n in range(first_report, counters[OWED]):  # the step stands: the receivers hold events
        if owed[n, 0] != DEFERRED_ANIM_DONE and not owed[n, 4]:
            bodies[owed[n, 2]].step_events = True
    return 0, events


@njit(cache=True, inline="always", _nrt=False)
def update_object_internal(w, tr, i, quantum, now):
    """One physics step of body ``i``: candidate, sweep, commit. Returns ``(status, events)``.

    AnimDone hooks the candidate's quantum queued retire the motions they complete in the record's
    queues (:func:`~acphys.fast.kernels.motion_queues.retire_motions`, with the motion table's
    ``HandleMovement`` check after); those it leaves to the reference path are owed: logged in
    ``owed`` (body, count) for the engine to run after the kernel returns. They reach only the
    body's motion-table manager and motion interpreter, which no step reads, so they may run late.

    Port of :meth:`acphys.physics_obj.PhysicsObj.update_object_internal` (a covered body has no
    managers to tick but its position manager's interpolation).
    Retail: CPhysicsObj::UpdateObjectInternal @ 0x005156B0 (acclient.c:322718),
    PositionManager::UseTime @ 0x00555160 (acclient.c:388266)
    """
    b = bodies_of(w)[i]
    if not b.transient & TS_ACTIVE:
        return 0, 0
    if b.cell < 0:
        return 0, 0
    b.jumped_this_frame = False
    status, origin, q, m = update_position_internal(w, b, quantum)
    if status == STATUS_REFERENCE:
        return bail(tr, R_HOOK), 0
    if status == STATUS_GLIDE:
        return bail(tr, R_GLIDE), 0
    if status == STATUS_ANIM_DONE and not retire_motions(b, b.seq_anim_done):
        b.motions_owed = True
        _defer(w, DEFERRED_ANIM_DONE, i, b.seq_anim_done, 0, 0)
    status, events = move_to_candidate(w, tr, i, quantum, now, origin, q, m)
    # PositionManager::UseTime, the step's last act (the movement manager's and the motion
    # table's, before it, are the engine's after the kernel returns: they read no glide)
    if status == 0 and b.glide >= 0 and blips(glides_of(w)[b.glide]):
        tr.oi_body = -1  # the blip places the body at a node, not where the sweep went (handback)
        return bail(tr, R_GLIDE), events
    return status, events


@njit(cache=True, inline="always", _nrt=False)
def move_to_candidate(w, tr, i, quantum, now, origin, q, m):
    """The second half of an active step: sweep to the candidate and commit (or keep the origin:
    a body of no spheres, which a body without a movement manager on walkable ground also leaves
    inactive, or one whose candidate lies within EPSILON of its origin). A body that aligns with its
    path faces along the step first. Returns ``(status, events)``.

    Part of :meth:`acphys.physics_obj.PhysicsObj.update_object_internal` (and ``_align_heading``:
    the ``ALIGN_PATH`` branch; a ``SLEDDING`` body is not covered).
    Retail: CPhysicsObj::UpdateObjectInternal @ 0x005156B0 (acclient.c:322718)
    """
    b = bodies_of(w)[i]
    events = 0
    if b.num_sphere == 0:
        if not b.has_movement_manager and b.transient & TS_ON_WALKABLE:
            b.transient &= ~TS_ACTIVE
        set_frame(b, t3(b.origin), q, m)
        fill(b.cached_velocity, 0.0)
        return 0, events
    if (
        abs(origin[0] - b.origin[0]) <= EPSILON
        and abs(origin[1] - b.origin[1]) <= EPSILON
        and abs(origin[2] - b.origin[2]) <= EPSILON
    ):
        set_frame(b, t3(b.origin), q, m)
        fill(b.cached_velocity, 0.0)
        return 0, events
    if b.state & PS_ALIGN_PATH:  # face along the step: Frame::set_vector_heading of its direction
        q, m = frame_set_vector_heading(origin, q, m, v_normalized(v_sub(origin, t3(b.origin))))
    found = transition(w, tr, i, origin, q, m)
    if found == BAIL:
        return BAIL, events
    if tr.num_collide:
        counters_of(w)[TOUCHING] += 1
    if not found:
        set_frame(b, t3(b.origin), q, m)
        fill(b.cached_velocity, 0.0)
        return 0, events
    offset = position_get_offset(b.cell_id, t3(b.origin), tr.curr_cell_id, t3(tr.curr_origin))
    inv = 1.0 / f32(quantum)
    inv32 = f32(inv)
    b.cached_velocity[0] = f32(inv * offset[0])
    b.cached_velocity[1] = f32(inv32 * offset[1])
    b.cached_velocity[2] = f32(inv32 * offset[2])
    return set_position_internal(w, tr, i, now, events)


# -- the clock ----------------------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def _log_step(w, b, i, t, quantum, events):
    """One trace row: the body right after a step."""
    log, counters = log_of(w), counters_of(w)
    n = counters[LOGGED]
    log[n, 0] = i
    log[n, 1] = t
    log[n, 2] = quantum
    log[n, 3] = b.cell_id
    for k in range(3):
        log[n, 4 + k] = b.origin[k]
        log[n, 11 + k] = b.velocity[k]
        log[n, 14 + k] = b.cached_velocity[k]
        log[n, 17 + k] = b.omega[k]
        log[n, 21 + k] = b.contact_n[k]
    for k in range(4):
        log[n, 7 + k] = b.q[k]
    log[n, 20] = b.transient
    log[n, 24] = events
    log[n, 25] = b.seq_anim[b.seq_curr] if b.seq_nodes else -1  # the animation playing, if any
    log[n, 26] = b.seq_frame_number
    counters[LOGGED] = n + 1


@njit(cache=True, _nrt=False)
def _run_quantum(w, tr, i, quantum, tracing):
    """``update_object``'s slice: advance the physics timer, step with the float32 quantum, count
    the step and record it with the events the object held before it.

    Port of :meth:`acphys.physics_obj.PhysicsObj._run_quantum`.
    """
    clock = clock_of(w)
    clock[1] += quantum
    step = f32(quantum)
    status, events = update_object_internal(w, tr, i, step, clock[1])
    if status != 0:
        return status
    counters_of(w)[STEPS] += 1
    b = bodies_of(w)[i]
    if b.step_events:
        events |= EVENT_PENDING
        b.step_events = False
    if tracing:
        _log_step(w, b, i, clock[1], step, events)
    return 0


@njit(cache=True, inline="always", _nrt=False)
def update_object(w, tr, i, tracing):
    """Bring body ``i`` up to the clock, one or more quanta at a time. Returns 0 or a status.

    Port of :meth:`acphys.physics_obj.PhysicsObj.update_object` (a covered body has no parent).
    Retail: CPhysicsObj::update_object @ 0x00515D10 (acclient.c:323080)
    """
    bodies, clock = bodies_of(w), clock_of(w)
    b = bodies[i]
    if b.cell < 0 or b.state & PS_FROZEN:
        b.transient &= ~TS_ACTIVE
        return 0
    player = int(clock[2])
    if player >= 0:
        p = bodies[player]
        vector = position_get_offset(p.cell_id, t3(p.origin), b.cell_id, t3(b.origin))
        b.player_vector[0], b.player_vector[1], b.player_vector[2] = vector
        distance = v_length(vector)
        b.player_distance = f32(distance)
        if distance > ACTIVITY_DISTANCE and clock[3] != 0.0:
            b.transient &= ~TS_ACTIVE
        elif not b.state & PS_STATIC:
            if not b.transient & TS_ACTIVE:
                b.update_time = clock[0]
            b.transient |= TS_ACTIVE
    quantum = clock[0] - b.update_time
    clock[1] = b.update_time
    if quantum <= EPSILON or quantum > HUGE_QUANTUM:
        b.update_time = clock[0]
        return 0
    if quantum > MAX_QUANTUM:
        while True:
            status = _run_quantum(w, tr, i, MAX_QUANTUM, tracing)
            if status != 0:
                return status
            quantum -= MAX_QUANTUM
            if quantum <= MAX_QUANTUM:
                break
        if quantum > MIN_QUANTUM:
            status = _run_quantum(w, tr, i, quantum, tracing)
            if status != 0:
                return status
    else:
        status = _run_quantum(w, tr, i, quantum, tracing)
        if status != 0:
            return status
    b.update_time = clock[1]
    return 0


@njit(cache=True, _nrt=False)
def _note_handback(handback, tr, i):
    """Keep where body ``i``'s update was sweeping as it is handed back (``HB_*``): the path of
    the transition, when the transition is this update's."""
    handback[HB_SWEPT] = 1.0 if tr.oi_body == i else 0.0
    handback[HB_BEGIN] = tr.begin_cell_id
    handback[HB_END] = tr.end_cell_id
    for k in range(3):
        handback[HB_BEGIN + 1 + k] = tr.begin_origin[k]
        handback[HB_END + 1 + k] = tr.end_origin[k]


@njit(cache=True, _nrt=False)
def run_bodies(context, tr_array, start, tracing, saved, saved_tr, saved_glide):
    """``CPhysics::UseTime`` from body ``start`` on: update each covered body; stop at the first
    that is not covered or hands its update back, or when a log or a cell's list is full.
    Returns ``(status, index)``: DONE with the number of bodies, or FALLBACK, GROW, LOG_FULL or
    UNREAD with the body to go on from (not started, or rolled back).

    ``context``: the world (:mod:`acphys.fast.kernels.context`), its ``clock``
    ``[cur_time, physics_time, player index (-1: none), activity cull (1/0)]``.

    Port of :meth:`acphys.simulation.Physics.use_time`'s walk.
    Retail: CPhysics::UseTime @ 0x00509950 (acclient.c:311334)
    """
    w = context[0]
    bodies, clock, counters = bodies_of(w), clock_of(w), counters_of(w)
    tr = tr_array[0]
    n = len(bodies)
    for i in range(start, n):
        b = bodies[i]
        if not b.covered:
            return FALLBACK, i
        if tracing and counters[LOGGED] + MAX_STEPS_PER_UPDATE > w.log_rows:
            return LOG_FULL, i
        if counters[MOVES] + MAX_STEPS_PER_UPDATE > w.moves_rows:
            return LOG_FULL, i
        if counters[OWED] + MAX_STEPS_PER_UPDATE * DEFERRED_PER_STEP > w.owed_rows:
            return LOG_FULL, i
        copy_record(saved[0], b)
        copy_head(saved_tr[0], tr, CARRIED)  # what this sweep will not set afresh
        if b.glide >= 0:
            copy_record(saved_glide[0], glides_of(w)[b.glide])
        logged, moved, steps, indebted = counters[LOGGED], counters[MOVES], counters[STEPS], counters[OWED]
        touching = counters[TOUCHING]
        physics_time = clock[1]
        counters[JOURNAL] = 0
        tr.bail = 0
        tr.oi_body = -1  # until this update's sweep begins (handback)
        status = update_object(w, tr, i, tracing)
        if status != 0:
            counters[REASON] = tr.bail
            counters[UNREAD_CELL] = tr.unread_cell
            _note_handback(handback_of(w), tr, i)
            _undo(w)
            copy_record(b, saved[0])
            copy_head(tr, saved_tr[0], CARRIED)
            if b.glide >= 0:
                copy_record(glides_of(w)[b.glide], saved_glide[0])
            counters[LOGGED], counters[MOVES] = logged, moved
            counters[STEPS], counters[OWED] = steps, indebted
            counters[TOUCHING] = touching
            clock[1] = physics_time
            if status == GROW:
                return GROW, i
            if counters[REASON] == R_UNREAD:
                return UNREAD, i
            return FALLBACK, i
        b.stale = True
        grid_place(bodies, heads_of(w), span_bits(grid_of(w)), i)
        grid_of(w)[MAX_REACH] = max(grid_of(w)[MAX_REACH], reach_now(b))
    return DONE, n
