"""Kernel interpolation: a covered body gliding to the positions a server sent.

Ports of :class:`acphys.managers.interpolation.InterpolationManager` over a body's row of the
interpolation table (:data:`~acphys.fast.layout.INTERPOLATION`, ``BODY.glide``): the offset a
step takes towards the head node, the audit every fifth step, a node completed. Two things are
the reference path's, and the step is then handed back whole: an audit the glide fails
(:data:`GIVE_UP`: the node counts as failed, and the queue may end in a blip), and the blip
``UseTime`` makes when the failures pile up (:func:`blips`).
"""

from __future__ import annotations

from numba import njit

from acphys.constants import EPSILON
from acphys.fast.kernels.frame import (
    IDENTITY_M,
    f32,
    frame_set_heading,
    frame_subtract2,
    position_get_offset,
    position_localtolocal,
    v_length,
    v_scale,
)
from acphys.fast.kernels.path import t3, t4, t9
from acphys.flags import TransientState
from acphys.managers.interpolation import (
    AUDIT_FRAMES,
    BIG_DISTANCE,
    DESIRED_DISTANCE,
    MAX_FAILED_NODES,
    MAX_INTERPOLATED_VELOCITY,
    MIN_PROGRESS_RATIO,
    NEAR_ENOUGH,
)

_TS_CONTACT = int(TransientState.CONTACT)

#: ``adjust_offset``'s answer when the glide fails its audit (the reference path takes the step).
GIVE_UP = -1


@njit(cache=True, inline="always", _nrt=False)
def _distance_to(b, g, n):
    """``Position::distance`` from the body to node ``n`` (a double)."""
    offset = position_get_offset(b.cell_id, t3(b.origin), g.node_cell_id[n], t3(g.node_origin[n]))
    return v_length(offset)


@njit(cache=True, _nrt=False)
def stop_interpolating(g):
    """Port of :meth:`acphys.managers.interpolation.InterpolationManager.stop_interpolating`.
    Retail: InterpolationManager::StopInterpolating @ 0x00555950 (acclient.c:388852)
    """
    g.num_nodes = 0
    g.frame_counter = 0
    g.progress_quantum = 0.0
    g.node_fail_counter = 0
    g.original_distance = BIG_DISTANCE


@njit(cache=True, _nrt=False)
def node_reached(b, g):
    """``NodeCompleted(success=1)``: drop the head node and restart the audit (at the next node's
    distance, or stopping when none is left).

    Port of :meth:`acphys.managers.interpolation.InterpolationManager.node_completed` (a success;
    a failure is the reference path's).
    Retail: InterpolationManager::NodeCompleted @ 0x005559A0 (acclient.c:388881)
    """
    g.frame_counter = 0
    g.progress_quantum = 0.0
    if g.num_nodes:
        g.first += 1
        g.num_nodes -= 1
    if g.num_nodes:
        g.original_distance = f32(_distance_to(b, g, g.first))
        return
    g.original_distance = BIG_DISTANCE
    stop_interpolating(g)


@njit(cache=True, _nrt=False)
def adjust_offset(b, g, quantum, origin, q, m):
    """The step's offset frame after the glide towards the head node: ``(status, origin, q, m)``,
    ``status`` 0 or :data:`GIVE_UP` (a failed audit, for the reference path). The offset is kept
    when nothing is queued or the body is not in contact (``contact``: the transient bit).

    Port of :meth:`acphys.managers.interpolation.InterpolationManager.adjust_offset` (a covered
    body sticks to nothing).
    Retail: InterpolationManager::adjust_offset @ 0x00555D30 (acclient.c:389177)
    """
    if not g.num_nodes or not b.transient & _TS_CONTACT:
        return 0, origin, q, m
    head = g.first
    distance = _distance_to(b, g, head)
    if distance < DESIRED_DISTANCE:
        node_reached(b, g)
        return 0, origin, q, m
    curr_distance = f32(distance)
    max_speed = f32(g.max_speed * 2.0)
    if max_speed < EPSILON:
        max_speed = MAX_INTERPOLATED_VELOCITY
    frame_counter = g.frame_counter + 1
    progress_quantum = f32(quantum + g.progress_quantum)
    if frame_counter >= AUDIT_FRAMES:
        progress_made = f32(g.original_distance - curr_distance)
        rate = progress_made / progress_quantum / max_speed if progress_made >= EPSILON else 0.0
        if not (progress_made >= EPSILON and rate >= MIN_PROGRESS_RATIO):
            if curr_distance < NEAR_ENOUGH:
                node_reached(b, g)
                return 0, origin, q, m
            return GIVE_UP, origin, q, m
        frame_counter = 0
        progress_quantum = 0.0
        g.original_distance = curr_distance
    g.frame_counter = frame_counter
    g.progress_quantum = progress_quantum
    # Position::subtract2(head, body): the rotation by Frame::subtract2, the origin by localtolocal
    _, aq, am = frame_subtract2(
        (0.0, 0.0, 0.0),
        (1.0, 0.0, 0.0, 0.0),
        IDENTITY_M,
        t3(g.node_origin[head]),
        t4(g.node_q[head]),
        t3(b.origin),
        t4(b.q),
        t9(b.m),
    )
    adjustment = position_localtolocal(
        b.cell_id,
        t3(b.origin),
        t9(b.m),
        g.node_cell_id[head],
        t3(g.node_origin[head]),
        t9(g.node_m[head]),
        (0.0, 0.0, 0.0),
    )
    max_step = f32(max_speed * quantum)
    length = v_length(adjustment)
    if length <= DESIRED_DISTANCE:
        node_reached(b, g)
    adjustment_distance = f32(length)
    if adjustment_distance > max_step:
        adjustment = v_scale(adjustment, f32(max_step / adjustment_distance))
    if g.keep_heading:
        aq, am = frame_set_heading(adjustment, aq, am, 0.0)
    return 0, adjustment, aq, am


@njit(cache=True, inline="always", _nrt=False)
def blips(g):
    """Whether ``UseTime`` would teleport the body (more than three failed nodes, or any with
    the queue empty): the reference path's.

    Port of the test in :meth:`acphys.managers.interpolation.InterpolationManager.use_time`.
    Retail: InterpolationManager::UseTime @ 0x00555F20 (acclient.c:389277)
    """
    return g.node_fail_counter > MAX_FAILED_NODES or (g.num_nodes == 0 and g.node_fail_counter > 0)
