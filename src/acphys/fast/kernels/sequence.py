"""``CSequence`` playback for the compiled engine: :meth:`acphys.motion.sequence.Sequence.update` under Numba.

The sequence lives in a body's record (:data:`acphys.fast.layout.BODY`, the ``seq_*`` fields):
nodes ``0 .. seq_nodes - 1`` are the reference's ``anim_list`` in order, each with its own
``AnimSequenceNode`` fields (``seq_anim`` the animation's row in the animation table,
``seq_framerate``, ``seq_low``, ``seq_high``); ``seq_curr`` and ``seq_first_cyclic`` are the
indices of ``curr_anim`` and ``first_cyclic`` (-1 with an empty list). The animations are one
table for the whole world, built by :func:`animation_table`:

* ``anims``, int32 ``(n, 3)``: per animation ``(first_frame_row, num_frames, has_pos_frames)``;
* ``pos_frames``, float64 ``(rows, 7)`` holding float32 values (see :mod:`acphys.fast.layout`):
  each frame's position frame, origin xyz then quaternion
  wxyz (zeros for an animation without position frames);
* ``hooks``, uint8 ``(rows,)``: bit 0 (:data:`HOOK_FORWARD`) when the frame has a hook that
  forward play fires (direction 0 or +1), bit 1 (:data:`HOOK_BACKWARD`) for backward play (0 or -1).

Every float read from the record or the table goes through ``np.float64`` before any arithmetic
(Numba would multiply two float32 values in float32), so the record's float fields may be float32
or float64.

:func:`sequence_update` plays one quantum. It never does what the reference does through Python
objects; it returns :data:`STATUS_REFERENCE` instead, having changed nothing, when the quantum
would queue a frame hook or the AnimDone hook on the body (the body is assumed to have a hook
object, as every ``PhysicsObj`` does) or would make the reference raise. The caller then plays
that quantum on the reference path.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from acphys.fast.kernels.frame import combine_anim_frame, f32, f32x3, frame_rotate, frame_subtract1
from acphys.fast.layout import MAX_NODES
from acphys.math.vector import Vector3
from acphys.motion.animation import F_EPSILON, Animation, AnimSequenceNode
from acphys.motion.sequence import Sequence
from acphys.precision import is_f32

#: The quantum was played; the record and the returned offset frame hold the result.
STATUS_DONE = 0
#: The quantum needs the reference path (a hook to queue, or something the reference raises on);
#: neither the record nor the offset frame was changed.
STATUS_REFERENCE = 1
#: The quantum was played, and queued the AnimDone hook (``seq_anim_done`` times, the only hooks it
#: queued): the record and the offset frame hold the result; the caller runs the hooks.
STATUS_ANIM_DONE = 2
#: ``hooks`` bits: the frame fires something in forward / backward play.
HOOK_FORWARD = 1
HOOK_BACKWARD = 2
#: Frame numbers the kernel plays (frames are int32); beyond, and for NaN and the infinities, on
#: which the reference's ``math.floor`` raises, the quantum goes back to the reference.
_FRAME_LIMIT = 2.0**31
#: The most animations one quantum advances through before the kernel gives the quantum back. Play
#: ends far sooner (a 1-frame animation at 1,000 frames/s advances 2,000 times in retail's 2-s
#: HUGE_QUANTUM), except where the reference never ends: a node whose range a negative
#: ``multiply_framerate`` turned over (``low_frame > high_frame``) gets back more time than it
#: played on each pass, and ``update_internal`` loops forever. The reference path still hangs on
#: it; the kernel, which no signal can interrupt, does not.
MAX_ADVANCES = 1 << 20


# -- the animation table and the record, from and to the reference ---------------------------------


def animation_table(animations: list[Animation]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(anims, pos_frames, hooks)``: the kernel's table of ``animations`` (row i is ``animations[i]``)."""
    rows = sum(animation.num_frames for animation in animations)
    anims = np.zeros((len(animations), 3), dtype=np.int32)
    pos_frames = np.zeros((rows, 7), dtype=np.float64)
    hooks = np.zeros(rows, dtype=np.uint8)
    row = 0
    for index, animation in enumerate(animations):
        count = animation.num_frames
        anims[index] = (row, count, animation.pos_frames is not None)
        if animation.pos_frames is not None:
            for i, frame in enumerate(animation.pos_frames):
                o = frame.origin
                pos_frames[row + i] = (o.x, o.y, o.z, frame.qw, frame.qx, frame.qy, frame.qz)
        for i, anim_frame in enumerate(animation.part_frames):
            bits = 0
            for hook in anim_frame.hooks:
                if hook.direction == 0 or hook.direction == 1:
                    bits |= HOOK_FORWARD
                if hook.direction == 0 or hook.direction == -1:
                    bits |= HOOK_BACKWARD
            hooks[row + i] = bits
        row += count
    return anims, pos_frames, hooks


def animation_index(animations: list[Animation]) -> dict[int, int]:
    """The ``anim_index`` of :func:`load_sequence`: ``id(animation)`` to its row in the table."""
    return {id(animation): row for row, animation in enumerate(animations)}


def _identity_index(nodes: list[AnimSequenceNode], node: AnimSequenceNode | None) -> int:
    for index, candidate in enumerate(nodes):
        if candidate is node:
            return index
    return -1


def load_sequence(record: np.void, sequence: Sequence, anim_index: dict[int, int]) -> bool:
    """Copy ``sequence`` into ``record``'s ``seq_*`` fields; False (nothing written) if the kernel can't.

    Refused: more than :data:`~acphys.fast.layout.MAX_NODES` nodes, a node whose animation is not
    in ``anim_index``, ``curr_anim`` or ``first_cyclic`` not in the list (or set with an empty
    list), a frame range beyond int32, a framerate, velocity or omega that is not a float32.
    Unused node slots are zeroed.
    """
    nodes = sequence.anim_list
    count = len(nodes)
    if count > MAX_NODES:
        return False
    rows = []
    for node in nodes:
        row = anim_index.get(id(node.animation)) if node.animation is not None else None
        if row is None or not is_f32(node.framerate):
            return False
        if not (-(2**31) <= node.low_frame < 2**31 and -(2**31) <= node.high_frame < 2**31):
            return False
        rows.append(row)
    curr = _identity_index(nodes, sequence.curr_anim)
    first_cyclic = _identity_index(nodes, sequence.first_cyclic)
    if count and (curr < 0 or first_cyclic < 0):
        return False
    if not count and (sequence.curr_anim is not None or sequence.first_cyclic is not None):
        return False
    if not all(is_f32(value) for value in (*sequence.velocity, *sequence.omega)):
        return False
    record["seq_nodes"] = count
    record["seq_curr"] = curr
    record["seq_first_cyclic"] = first_cyclic
    for field in ("seq_anim", "seq_framerate", "seq_low", "seq_high"):
        record[field] = 0
    for index, node in enumerate(nodes):
        record["seq_anim"][index] = rows[index]
        record["seq_framerate"][index] = node.framerate
        record["seq_low"][index] = node.low_frame
        record["seq_high"][index] = node.high_frame
    record["seq_frame_number"] = sequence.frame_number
    record["seq_velocity"] = tuple(sequence.velocity)
    record["seq_omega"] = tuple(sequence.omega)
    return True


def store_sequences(
    records: np.ndarray, sequences: list[Sequence | None], animations: list[Animation]
) -> None:
    """Copy each record's ``seq_*`` fields back into its sequence (None: a body without one;
    ``animations``: the table's rows). Each field is read for all the records at once.

    The kernel only drops nodes from the head of the list, so when the record's nodes match the
    tail of ``sequence.anim_list`` those node objects are kept (the list is trimmed in place);
    otherwise the list is rebuilt with new nodes holding the record's fields.
    """
    names = ("seq_nodes", "seq_anim", "seq_framerate", "seq_low", "seq_high", "seq_curr", "seq_first_cyclic")
    columns = [records[name].tolist() for name in names]
    frame_numbers = records["seq_frame_number"].tolist()
    velocities, omegas = records["seq_velocity"].tolist(), records["seq_omega"].tolist()
    for j, sequence in enumerate(sequences):
        if sequence is None:
            continue
        count, anims, rates, lows, highs, curr, first_cyclic = (column[j] for column in columns)
        played = [animations[row] for row in anims[:count]]
        rows = list(zip(played, rates[:count], lows[:count], highs[:count], strict=True))
        nodes = sequence.anim_list
        dropped = len(nodes) - count
        if dropped >= 0 and all(
            node.animation is row[0] and (node.framerate, node.low_frame, node.high_frame) == row[1:]
            for node, row in zip(nodes[dropped:], rows, strict=True)
        ):
            del nodes[:dropped]
        else:
            fresh = []
            for animation, rate, low, high in rows:
                node = AnimSequenceNode.__new__(AnimSequenceNode)  # the record's fields, unrefitted
                node.animation, node.framerate, node.low_frame, node.high_frame = animation, rate, low, high
                fresh.append(node)
            nodes[:] = fresh
        sequence.curr_anim = nodes[curr] if count else None
        sequence.first_cyclic = nodes[first_cyclic] if count else None
        sequence.frame_number = frame_numbers[j]
        sequence.velocity = Vector3(*velocities[j])
        sequence.omega = Vector3(*omegas[j])


# -- playback --------------------------------------------------------------------------------------


@njit(cache=True, inline="always", _nrt=False)
def apply_physics(velocity, omega, origin, q, m, quantum, sign, memo):
    """The frame ``origin, q, m`` moved by ``|quantum| · velocity`` and turned by ``|quantum| · omega``
    (signed as ``sign``; the turn's terms remembered in ``memo``, the record's ``turn_memo``:
    :func:`~acphys.fast.kernels.frame.frame_rotate`); returns ``(origin, q, m)``.

    Port of :meth:`acphys.motion.sequence.Sequence.apply_physics`.
    Retail: CSequence::apply_physics @ 0x00524AB0 (acclient.c:339859)
    """
    scale = math.fabs(quantum)
    if sign < 0.0:
        scale = -scale
    dy, dz = f32(scale * velocity[1]), f32(scale * velocity[2])
    origin = f32x3(scale * velocity[0] + origin[0], dy + origin[1], dz + origin[2])
    if omega[0] != 0.0 or omega[1] != 0.0 or omega[2] != 0.0:
        q, m = frame_rotate(memo, origin, q, m, f32x3(scale * omega[0], scale * omega[1], scale * omega[2]))
    return origin, q, m


@njit(cache=True, inline="always", _nrt=False)
def _playable(frame_number):
    """A frame number whose floor the kernel takes (NaN and the infinities are not)."""
    return -_FRAME_LIMIT < frame_number < _FRAME_LIMIT


@njit(cache=True, inline="always", _nrt=False)
def _frame_row(anims, anim, frame):
    """The table row of ``frame`` of animation ``anim`` as the reference's list indexing finds it
    (a negative frame counts from the end), or -1 where the reference raises IndexError."""
    count = np.int64(anims[anim, 1])
    if frame < 0:
        frame += count
    if frame < 0 or frame >= count:
        return np.int64(-1)
    return np.int64(anims[anim, 0]) + frame


@njit(cache=True, inline="always", _nrt=False)
def _vec3(values):
    """A record's float32 3-vector as a tuple of float64."""
    return (np.float64(values[0]), np.float64(values[1]), np.float64(values[2]))


@njit(cache=True, inline="always", _nrt=False)
def _pos_origin(pos_frames, row):
    return (np.float64(pos_frames[row, 0]), np.float64(pos_frames[row, 1]), np.float64(pos_frames[row, 2]))


@njit(cache=True, inline="always", _nrt=False)
def _pos_q(pos_frames, row):
    return (
        np.float64(pos_frames[row, 3]),
        np.float64(pos_frames[row, 4]),
        np.float64(pos_frames[row, 5]),
        np.float64(pos_frames[row, 6]),
    )


@njit(cache=True, _nrt=False)
def get_starting_frame(framerate, low_frame, high_frame):
    """``low_frame`` forwards; ``high_frame + 1 - F_EPSILON`` backwards.

    Port of :meth:`acphys.motion.animation.AnimSequenceNode.get_starting_frame`.
    Retail: AnimSequenceNode::get_starting_frame @ 0x00525C80 (acclient.c:341015)
    """
    if framerate < 0.0:
        return np.float64(np.int64(high_frame) + 1) - F_EPSILON
    return np.float64(low_frame)


@njit(cache=True, _nrt=False)
def get_ending_frame(framerate, low_frame, high_frame):
    """``high_frame + 1 - F_EPSILON`` forwards; ``low_frame`` backwards.

    Port of :meth:`acphys.motion.animation.AnimSequenceNode.get_ending_frame`.
    Retail: AnimSequenceNode::get_ending_frame @ 0x00525CB0 (acclient.c:341027)
    """
    if framerate < 0.0:
        return np.float64(low_frame)
    return np.float64(np.int64(high_frame) + 1) - F_EPSILON


@njit(cache=True, _nrt=False)
def leave_or_enter(
    seq, anims, pos_frames, node, frame_number, velocity, omega, origin, q, m, quantum, entering
):
    """``(ok, origin, q, m)``: one frame of ``node`` at ``floor(frame_number)`` composed (entering) or
    subtracted, then ``1/framerate`` s of physics signed as ``quantum``; ``ok`` False (nothing done)
    where the reference's ``get_pos_frame`` finds no frame and the composition raises.

    Port of :meth:`acphys.motion.sequence.Sequence._leave_or_enter`.
    Retail: AnimSequenceNode::get_pos_frame @ 0x005247B0 (acclient.c:339640)
    """
    anim = np.int64(seq.seq_anim[node])
    if anims[anim, 2] != 0:
        if not _playable(frame_number):
            return False, origin, q, m
        frame = np.int64(math.floor(frame_number))
        if frame < 0 or frame >= anims[anim, 1]:
            return False, origin, q, m
        row = np.int64(anims[anim, 0]) + frame
        if entering:
            origin, q, m = combine_anim_frame(
                origin, q, m, _pos_origin(pos_frames, row), _pos_q(pos_frames, row)
            )
        else:
            origin, q, m = frame_subtract1(
                origin, q, m, origin, q, _pos_origin(pos_frames, row), _pos_q(pos_frames, row)
            )
    framerate = np.float64(seq.seq_framerate[node])
    if math.fabs(framerate) > F_EPSILON:
        origin, q, m = apply_physics(velocity, omega, origin, q, m, 1.0 / framerate, quantum, seq.turn_memo)
    return True, origin, q, m


@njit(cache=True, inline="always", _nrt=False)
def sequence_update(seq, anims, pos_frames, hooks, quantum, offset_origin, offset_q, offset_m):
    """Play ``quantum`` seconds of the record's sequence into the offset frame: ``(status, origin, q, m)``.

    ``seq`` is a body's record; ``offset_origin, offset_q, offset_m`` the offset frame (cached).
    With :data:`STATUS_DONE` the record holds the new frame number, current node and list (the
    finished head nodes dropped, as ``apricot`` does) and the returned frame the root motion
    composed into the offset. With :data:`STATUS_REFERENCE` nothing was changed (but the turn
    memo, ``turn_memo``, which holds a turn's terms whatever its use) and the offset frame is
    returned as given: the quantum would queue a frame hook (a crossed frame whose
    ``hooks`` bit for the direction of play is set) or the AnimDone hook, or the reference would
    raise (a NaN, infinite or out-of-int32 frame number, a frame outside its animation), or would
    never end (more than :data:`MAX_ADVANCES` animations ended in the quantum). Playback runs on
    locals; the sequence's fields are written only at the end, on success.

    Ports, inlined into one loop: :meth:`acphys.motion.sequence.Sequence.update`,
    :meth:`~acphys.motion.sequence.Sequence.update_internal`,
    :meth:`~acphys.motion.sequence.Sequence.advance_to_next_animation` and
    :meth:`~acphys.motion.sequence.Sequence.apricot`.
    Retail: CSequence::update @ 0x00525B80 (acclient.c:340950)
    Retail: CSequence::update_internal @ 0x005255D0 (acclient.c:340658)
    Retail: CSequence::advance_to_next_animation @ 0x005252B0 (acclient.c:340472)
    Retail: CSequence::apricot @ 0x00524B40 (acclient.c:339892)
    """
    origin, q, m = offset_origin, offset_q, offset_m
    velocity = _vec3(seq.seq_velocity)
    omega = _vec3(seq.seq_omega)
    nodes = np.int64(seq.seq_nodes)
    if nodes == 0:
        origin, q, m = apply_physics(velocity, omega, origin, q, m, quantum, quantum, seq.turn_memo)
        return STATUS_DONE, origin, q, m
    curr = np.int64(seq.seq_curr)
    first_cyclic = np.int64(seq.seq_first_cyclic)
    if nodes > MAX_NODES or not (0 <= curr < nodes and 0 <= first_cyclic < nodes):
        return STATUS_REFERENCE, offset_origin, offset_q, offset_m
    frame_number = np.float64(seq.seq_frame_number)
    advances = 0
    anim_done = 0

    # -- update_internal
    while True:
        anim = np.int64(seq.seq_anim[curr])
        framerate = np.float64(seq.seq_framerate[curr])
        has_pos = anims[anim, 2] != 0
        frame_quantum = framerate * quantum
        if not _playable(frame_number):
            return STATUS_REFERENCE, offset_origin, offset_q, offset_m
        last = np.int64(math.floor(frame_number))
        time_left = 0.0
        advance = False
        frame_number = frame_number + frame_quantum
        if frame_quantum > 0.0:
            if not _playable(frame_number):
                return STATUS_REFERENCE, offset_origin, offset_q, offset_m
            high = np.int64(seq.seq_high[curr])
            if high < np.int64(math.floor(frame_number)):
                overrun = frame_number - np.float64(high) - 1.0
                if overrun < 0.0:
                    overrun = 0.0
                time_left = overrun / framerate if math.fabs(framerate) > F_EPSILON else 0.0
                advance = True
                frame_number = np.float64(high)
            end = np.int64(math.floor(frame_number))
            if last < end:
                step = 1.0 / framerate if math.fabs(framerate) > F_EPSILON else 0.0
                while last < end:
                    row = _frame_row(anims, anim, last)
                    if row < 0 or hooks[row] & HOOK_FORWARD:
                        return STATUS_REFERENCE, offset_origin, offset_q, offset_m
                    if has_pos:
                        origin, q, m = combine_anim_frame(
                            origin, q, m, _pos_origin(pos_frames, row), _pos_q(pos_frames, row)
                        )
                    if step != 0.0:
                        origin, q, m = apply_physics(
                            velocity, omega, origin, q, m, step, quantum, seq.turn_memo
                        )
                    last += 1
        elif frame_quantum >= 0.0:
            if math.fabs(quantum) > F_EPSILON:
                origin, q, m = apply_physics(velocity, omega, origin, q, m, quantum, quantum, seq.turn_memo)
            break
        else:
            if not _playable(frame_number):
                return STATUS_REFERENCE, offset_origin, offset_q, offset_m
            low = np.int64(seq.seq_low[curr])
            if low > np.int64(math.floor(frame_number)):
                overrun = frame_number - np.float64(low)
                if overrun > 0.0:
                    overrun = 0.0
                time_left = overrun / framerate if math.fabs(framerate) > F_EPSILON else 0.0
                advance = True
                frame_number = np.float64(low)
            end = np.int64(math.floor(frame_number))
            if last > end:
                step = 1.0 / framerate if math.fabs(framerate) > F_EPSILON else 0.0
                while last > end:
                    row = _frame_row(anims, anim, last)
                    if row < 0 or hooks[row] & HOOK_BACKWARD:
                        return STATUS_REFERENCE, offset_origin, offset_q, offset_m
                    if has_pos:
                        origin, q, m = frame_subtract1(
                            origin, q, m, origin, q, _pos_origin(pos_frames, row), _pos_q(pos_frames, row)
                        )
                    if step != 0.0:
                        origin, q, m = apply_physics(
                            velocity, omega, origin, q, m, step, quantum, seq.turn_memo
                        )
                    last -= 1
        if not advance:
            break
        if first_cyclic != 0:
            # the head of the list is not first_cyclic: the reference queues AnimDone
            anim_done += 1
        advances += 1
        if advances > MAX_ADVANCES:
            return STATUS_REFERENCE, offset_origin, offset_q, offset_m

        # -- advance_to_next_animation
        if quantum < 0.0:
            if framerate >= 0.0:
                ok, origin, q, m = leave_or_enter(
                    seq, anims, pos_frames, curr, frame_number, velocity, omega, origin, q, m, quantum, False
                )
                if not ok:
                    return STATUS_REFERENCE, offset_origin, offset_q, offset_m
            curr = curr - 1 if curr > 0 else nodes - 1
            rate = np.float64(seq.seq_framerate[curr])
            frame_number = get_ending_frame(rate, seq.seq_low[curr], seq.seq_high[curr])
            if rate < 0.0:
                ok, origin, q, m = leave_or_enter(
                    seq, anims, pos_frames, curr, frame_number, velocity, omega, origin, q, m, quantum, True
                )
                if not ok:
                    return STATUS_REFERENCE, offset_origin, offset_q, offset_m
        else:
            if framerate < 0.0:
                ok, origin, q, m = leave_or_enter(
                    seq, anims, pos_frames, curr, frame_number, velocity, omega, origin, q, m, quantum, False
                )
                if not ok:
                    return STATUS_REFERENCE, offset_origin, offset_q, offset_m
            curr = curr + 1 if curr + 1 < nodes else first_cyclic
            rate = np.float64(seq.seq_framerate[curr])
            frame_number = get_starting_frame(rate, seq.seq_low[curr], seq.seq_high[curr])
            if rate > 0.0:
                ok, origin, q, m = leave_or_enter(
                    seq, anims, pos_frames, curr, frame_number, velocity, omega, origin, q, m, quantum, True
                )
                if not ok:
                    return STATUS_REFERENCE, offset_origin, offset_q, offset_m
        quantum = time_left

    # -- success: write back, then apricot (drop the head nodes before curr_anim and first_cyclic)
    seq.seq_frame_number = frame_number
    drop = min(curr, first_cyclic)
    if drop > 0:
        for index in range(nodes):
            source = index + drop
            if source < nodes:
                seq.seq_anim[index] = seq.seq_anim[source]
                seq.seq_framerate[index] = seq.seq_framerate[source]
                seq.seq_low[index] = seq.seq_low[source]
                seq.seq_high[index] = seq.seq_high[source]
            else:
                seq.seq_anim[index] = 0
                seq.seq_framerate[index] = 0.0
                seq.seq_low[index] = 0
                seq.seq_high[index] = 0
    seq.seq_nodes = np.int8(nodes - drop)
    seq.seq_curr = np.int8(curr - drop)
    seq.seq_first_cyclic = np.int8(first_cyclic - drop)
    seq.seq_anim_done = anim_done
    return (STATUS_ANIM_DONE if anim_done else STATUS_DONE), origin, q, m
