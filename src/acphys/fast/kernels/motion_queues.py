"""Kernel motion queues: what a covered body's AnimDone hooks retire.

A link animation that ends queues an AnimDone hook (``CSequence``); the step's ``process_hooks``
runs it: the motion table's manager counts it and completes every head node whose animations have
all played, each completion telling the motion interpreter, which retires its oldest pending
motion; the step's ``HandleMovement`` then completes the nodes left waiting for no animation.
The record mirrors the two queues (:data:`~acphys.fast.layout.BODY`, ``table_*`` and
``interp_*``) and :func:`retire_motions` does all that on it. Completing an action (which also
pops the motion states' action queues and unsticks the body) and a queue longer than the record
holds are the reference path's: the hooks are then owed to the engine, which runs them on the
objects after the kernel returns (nothing a step reads depends on them), with every later hook of
the body until it has.

The engine writes the queues back by popping their heads down to the record's lengths
(:func:`acphys.fast.sync.store_motion_queues`): the kernel only ever retires head nodes.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, inline="always", _nrt=False)
def _motion_done(b, t, k, interp_len):
    """Complete table node ``t`` with the interpreter's head at ``k`` of ``interp_len``: the
    interpreter's next head (``k`` or ``k + 1``), or -1 when it is the reference path's (the
    node or the interpreter's head an action, or an interpreter queue the record does not hold).

    Retail: MotionTableManager::AnimationDone @ 0x0051BCE0 (acclient.c:329892, an action pops
    the state's action head), CPhysicsObj::MotionDone @ 0x0050FDB0 (acclient.c:317096),
    MovementManager::MotionDone @ 0x005242D0 (acclient.c:339348),
    CMotionInterp::MotionDone @ 0x00527EC0 (acclient.c:343640: an empty queue pops nothing,
    acclient.c:343655; an action head unsticks the body and pops both states' actions,
    acclient.c:343657)
    """
    if not b.table_plain[t] or interp_len < 0:
        return -1
    if k == interp_len:
        return k
    if not b.interp_plain[k]:
        return -1
    return k + 1


@njit(cache=True, inline="always", _nrt=False)
def _drop_head(values, length, count):
    """Drop the first ``count`` of the first ``length`` of ``values``, moving the rest up."""
    for n in range(length - count):
        values[n] = values[n + count]


@njit(cache=True, _nrt=False)
def retire_motions(b, hooks):
    """Run ``hooks`` AnimDone hooks of body record ``b``, then its motion table's check for motions
    waiting for no animation; False, with the record as it was, when they are the reference
    path's (:func:`_motion_done`, ``table_len`` -1, or an earlier hook owed).

    Port of :meth:`acphys.motion.table_manager.MotionTableManager.animation_done` (each hook)
    and ``check_for_completed_motions`` (after), over the record's queues.
    Retail: MotionTableManager::AnimationDone @ 0x0051BCE0 (acclient.c:329872),
    MotionTableManager::CheckForCompletedMotions @ 0x0051BE00 (acclient.c:329959),
    CPartArray::HandleMovement @ 0x00517D60 (acclient.c:325105)
    """
    table_len = np.int64(b.table_len)
    interp_len = np.int64(b.interp_len)
    if b.motions_owed or table_len < 0:
        return False
    counter = np.int64(b.table_counter)
    t = 0  # the table's nodes completed
    k = 0  # the interpreter's nodes retired
    for _ in range(hooks):
        if t == table_len:
            continue  # no head: the hook counts nothing (acclient.c:329885)
        counter += 1
        while t < table_len and np.int64(b.table_anims[t]) <= counter:  # acclient.c:329890
            k = _motion_done(b, t, k, interp_len)
            if k < 0:
                return False
            counter -= np.int64(b.table_anims[t])
            t += 1
        if counter != 0 and t == table_len:
            counter = 0  # acclient.c:329933
    while t < table_len and b.table_anims[t] == 0:  # CheckForCompletedMotions, acclient.c:329973
        k = _motion_done(b, t, k, interp_len)
        if k < 0:
            return False
        t += 1
    _drop_head(b.table_anims, table_len, t)
    _drop_head(b.table_plain, table_len, t)
    _drop_head(b.interp_plain, interp_len, k)
    b.table_len = table_len - t
    b.interp_len = interp_len - k
    b.table_counter = counter
    return True
