"""AnimDone hooks retired in the kernel (issue 14): the record's motion queues.

A link animation's end queues an AnimDone hook; ``MotionTableManager::AnimationDone``
(acclient.c:329872) counts it and completes every head node whose animations have all played, each
completion reaching ``CMotionInterp::MotionDone`` (acclient.c:343640), which retires the oldest
pending motion; ``CheckForCompletedMotions`` (acclient.c:329959) then completes nodes that wait for
no animation. The kernel does that on the record's mirror of the two queues
(:func:`acphys.fast.kernels.motion_queues.retire_motions`); actions and queues longer than the record
holds are the reference path's (the record is left as it was). The hand-derived cases cite the
deciding line; the differential ones run the reference's hook chain on real bodies.
"""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from numba import njit

import acphys
from acphys.bench import WORKLOADS
from acphys.fast.differential import same_run
from acphys.fast.kernels.motion_queues import retire_motions
from acphys.fast.layout import BODY, MAX_PENDING
from acphys.fast.sync import load_motion_queues, motion_queues, store_motion_queues
from acphys.motion.anim_hooks import ANIM_DONE_HOOK
from acphys.motion.commands import ACTION_MASK
from acphys.motion.motion_states import MotionNode
from acphys.motion.table_manager import AnimNode
from acphys.physics_obj import PhysicsObj
from acphys.scenario import parse_scenario

pytestmark = pytest.mark.kernels

WALK = 0x45000005
CHEER = ACTION_MASK | 0x0087  # an action: completing it pops the states' action queues


@njit(cache=False)
def _retire(bodies: np.ndarray, hooks: int) -> bool:
    return retire_motions(bodies[0], hooks)


def _record(
    anims: list[int],
    counter: int = 0,
    interp: int = 0,
    table_actions: tuple[int, ...] = (),
    interp_actions: tuple[int, ...] = (),
) -> np.ndarray:
    """A record whose table holds nodes of ``anims`` animations (those at ``table_actions``
    actions), its counter at ``counter``, and an interpreter of ``interp`` pending motions."""
    bodies = np.zeros(1, dtype=BODY)
    bodies["table_len"] = len(anims)
    bodies["table_counter"] = counter
    for n, count in enumerate(anims):
        bodies["table_anims"][0, n] = count
        bodies["table_plain"][0, n] = n not in table_actions
    bodies["interp_len"] = interp
    for n in range(interp):
        bodies["interp_plain"][0, n] = n not in interp_actions
    return bodies


def _queues(bodies: np.ndarray) -> tuple[list[int], int, int]:
    record = bodies[0]
    length = int(record["table_len"])
    return record["table_anims"][:length].tolist(), int(record["table_counter"]), int(record["interp_len"])


# -- by hand --------------------------------------------------------------------------------------


def test_a_link_of_one_animation_completes_its_motion() -> None:
    # The counter goes to 1 (acclient.c:329887), the head's 1 is not above it (329890): MotionDone
    # pops the interpreter's head (343655), the counter loses the head's 1 (329895), the node goes.
    bodies = _record([1], interp=1)
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([], 0, 0)


def test_a_node_waits_for_all_its_animations() -> None:
    # Two animations: the first hook leaves the counter at 1 < 2 (329890 breaks); the second completes.
    bodies = _record([2], interp=1)
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([2], 1, 1)
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([], 0, 0)


def test_the_next_node_moves_up_and_waits() -> None:
    # [1, 3]: the first completes (counter back to 0), the second's 3 is above it: it stays, head now.
    bodies = _record([1, 3], interp=2)
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([3], 0, 1)


def test_a_node_waiting_for_no_animation_completes_in_handle_movement() -> None:
    # [1, 0]: the hook completes the first; the loop then meets 0 <= 0 and completes the second too
    # (329890 again); [2, 0] after one hook: the head waits, CheckForCompletedMotions stops at it
    # (329973: a head with animations to wait for).
    bodies = _record([1, 0], interp=2)
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([], 0, 0)
    bodies = _record([2, 0], interp=2)
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([2, 0], 1, 2)
    # a zero node at the head (left by an earlier step) completes with no hook at all
    bodies = _record([0, 2], interp=2)
    assert _retire(bodies, 0)
    assert _queues(bodies) == ([2], 0, 1)


def test_a_counter_left_over_an_emptied_queue_is_reset() -> None:
    # Counter 2 and [1]: the hook makes 3, the node takes 1 off (2 left), the queue is empty: the
    # counter is reset (acclient.c:329931-329934).
    bodies = _record([1], counter=2, interp=1)
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([], 0, 0)


def test_a_hook_with_no_queue_counts_nothing() -> None:
    # No head: AnimationDone does nothing, not even count (329885); a counter stays as it was.
    bodies = _record([], counter=5)
    assert _retire(bodies, 3)
    assert _queues(bodies) == ([], 5, 0)


def test_more_hooks_than_nodes() -> None:
    # [1, 1] and three hooks: each of the first two completes a node; the third finds no head.
    bodies = _record([1, 1], interp=2)
    assert _retire(bodies, 3)
    assert _queues(bodies) == ([], 0, 0)


def test_an_interpreter_with_fewer_motions_pops_what_it_has() -> None:
    # MotionDone with no pending motion pops nothing (acclient.c:343655).
    bodies = _record([1, 0], interp=1)
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([], 0, 0)


@pytest.mark.parametrize(
    ("bodies", "hooks"),
    [
        (_record([1], interp=1, table_actions=(0,)), 1),  # remove_action_head (329892)
        (_record([1], interp=1, interp_actions=(0,)), 1),  # unstick, RemoveAction (343657)
        (_record([1, 0], interp=2, interp_actions=(1,)), 1),  # the second completion's
        (_record([1], interp=-1), 1),  # an interpreter queue longer than the record holds
    ],
    ids=["table action", "interpreter action", "later action", "long interpreter queue"],
)
def test_what_the_reference_path_must_do_leaves_the_record_as_it_was(bodies: np.ndarray, hooks: int) -> None:
    before = bodies.tobytes()
    assert not _retire(bodies, hooks)
    assert bodies.tobytes() == before


def test_an_action_not_yet_complete_or_an_owed_hook() -> None:
    # An action waiting for its second animation: counted, not completed, so the kernel does it.
    bodies = _record([2], interp=1, table_actions=(0,), interp_actions=(0,))
    assert _retire(bodies, 1)
    assert _queues(bodies) == ([2], 1, 1)
    # once a hook of the body is owed (or its queue is not held), every later one is too
    for field, value in (("motions_owed", 1), ("table_len", -1)):
        bodies = _record([1], interp=1)
        bodies[field] = value
        before = bodies.tobytes()
        assert not _retire(bodies, 1)
        assert bodies.tobytes() == before


# -- against the reference's hook chain -----------------------------------------------------------


def _walker_pair() -> tuple[PhysicsObj, PhysicsObj]:
    """The default scenario's walker, twice (one for each path)."""
    return tuple(next(b for b in acphys.load_scenario().bodies if b.name == "walker") for _ in range(2))  # type: ignore[return-value]


def _set_queues(body: PhysicsObj, nodes: list[tuple[int, int]], counter: int, motions: list[int]) -> None:
    table = body.part_array.motion_table_manager
    table.pending_animations = [AnimNode(motion, count) for motion, count in nodes]
    table.animation_counter = counter
    interp = body.movement_manager.motion_interpreter
    interp.pending_motions = [MotionNode(0, motion, 0) for motion in motions]


def _state(body: PhysicsObj) -> tuple[Any, ...]:
    table = body.part_array.motion_table_manager
    interp = body.movement_manager.motion_interpreter
    return (
        [(node.motion, node.num_anims) for node in table.pending_animations],
        table.animation_counter,
        [node.motion for node in interp.pending_motions],
        len(table.state.actions),
    )


def _reference_hooks(body: PhysicsObj, hooks: int) -> None:
    """What the engine runs for owed hooks: process_hooks, then HandleMovement's check."""
    body.anim_hooks.extend([ANIM_DONE_HOOK] * hooks)
    body.process_hooks()
    table = body.part_array.motion_table_manager
    if table.pending_animations and not table.pending_animations[0].num_anims:
        body.part_array.handle_movement()


def test_the_kernel_retires_what_the_reference_chain_does() -> None:
    """Random queues of plain motions (up to the record's bound): load, retire, write back equals
    the reference's hooks on an identical body, queue for queue; with an action somewhere, the
    kernel either does the same or leaves everything to the reference path."""
    rng = random.Random(14)
    kernel_done = handed_back = 0
    for _ in range(300):
        length = rng.randint(0, MAX_PENDING)
        nodes = [(CHEER if rng.random() < 0.15 else WALK, rng.choice((0, 1, 1, 2, 3))) for _ in range(length)]
        motions = [CHEER if rng.random() < 0.15 else WALK for _ in range(rng.randint(0, MAX_PENDING))]
        counter = rng.choice((0, 0, 1, 2))
        hooks = rng.randint(0, 3)
        mine, theirs = _walker_pair()
        for body in (mine, theirs):
            _set_queues(body, nodes, counter, motions)
        bodies = np.zeros(1, dtype=BODY)
        load_motion_queues(bodies[0], mine)
        before = _state(mine)
        _reference_hooks(theirs, hooks)
        if _retire(bodies, hooks):
            store_motion_queues(bodies[0], mine)
            assert _state(mine) == _state(theirs), (nodes, counter, motions, hooks)
            kernel_done += 1
        else:
            assert any(motion & ACTION_MASK for motion, _ in nodes) or any(m & ACTION_MASK for m in motions)
            assert _state(mine) == before
            handed_back += 1
    assert kernel_done > 150 and handed_back > 20, (kernel_done, handed_back)


def test_writing_back_again_changes_nothing() -> None:
    """The write-back retires head nodes down to the record's lengths: a second write of the same
    record (a copy written back, then the live record later) changes nothing."""
    mine, _ = _walker_pair()
    _set_queues(mine, [(WALK, 1), (WALK, 2)], 0, [WALK, WALK])
    bodies = np.zeros(1, dtype=BODY)
    load_motion_queues(bodies[0], mine)
    assert _retire(bodies, 1)
    store_motion_queues(bodies[0], mine)
    once = _state(mine)
    store_motion_queues(bodies[0], mine)
    assert _state(mine) == once == ([(WALK, 2)], 0, [WALK], 0)


def test_queues_the_record_cannot_hold_are_the_reference_paths() -> None:
    mine, _ = _walker_pair()
    record = np.zeros(1, dtype=BODY)[0]
    _set_queues(mine, [(WALK, 1)] * (MAX_PENDING + 1), 0, [WALK])
    load_motion_queues(record, mine)
    assert record["table_len"] == -1
    _set_queues(mine, [(WALK, 1)], 0, [WALK] * (MAX_PENDING + 1))
    load_motion_queues(record, mine)
    assert (record["table_len"], record["interp_len"]) == (1, -1)
    _set_queues(mine, [(WALK, 2**31)], 0, [])
    load_motion_queues(record, mine)
    assert record["table_len"] == -1


def test_a_subclass_on_the_hook_chain_keeps_its_hooks_on_the_reference_path() -> None:
    class Watching(PhysicsObj):
        def motion_done(self, motion: int, success: bool) -> None:
            super().motion_done(motion, success)

    mine, _ = _walker_pair()
    assert motion_queues(mine) is not None
    mine.__class__ = Watching
    assert motion_queues(mine) is None
    record = np.zeros(1, dtype=BODY)[0]
    load_motion_queues(record, mine)
    assert record["table_len"] == -1


# -- in the engine --------------------------------------------------------------------------------


def _walkers(engine: str) -> acphys.Simulation:
    sim = WORKLOADS["hills"][1](40, 1.0, engine)
    sim.run()
    return sim


def test_walkers_starting_owe_no_hook_and_end_as_on_the_reference() -> None:
    """Forty walkers start on hills: every link's AnimDone is retired in the kernel (none owed to
    the engine), and after the run every body's queues are the reference engine's."""
    fast, reference = _walkers("fast"), _walkers("reference")
    counts = fast.physics.counts
    assert counts.kernel > 0 and counts.owed_hooks == 0
    for mine, theirs in zip(fast.bodies, reference.bodies, strict=True):
        assert _state(mine) == _state(theirs), mine.name
    assert all(not _state(body)[0] for body in fast.bodies)  # the links did end: their nodes are gone


def _table_entry(kind: str, motion: str, frames: int, extra: str = "") -> str:
    lines = [f"[[motion_table.cheerful.{kind}]]", motion, "framerate = 30.0", f"frames = {frames}", extra]
    return "\n".join(line for line in lines if line) + "\n\n"


def _event(at: float, action: str, motion: str) -> str:
    return f'[[event]]\nat = {at}\nbody = "fan"\naction = "{action}"\nmotion = "{motion}"\n\n'


#: A human whose motion table has an action (Cheer: ``ACTION_MASK``) linked from Ready and
#: from a walk, standing, then cheering, walking, cheering as it walks, stopping.
_CHEERING = (
    '[scenario]\nname = "cheering"\nduration = 3.0\ndriver_hz = 30.0\n\n'
    '[motion_table.cheerful]\ndefault_style = "NonCombat"\n\n'
    + _table_entry("cycle", 'motion = "Ready"', 30)
    + _table_entry("cycle", 'motion = "WalkForward"', 30, "velocity = [0.0, 3.12, 0.0]")
    + "".join(
        _table_entry("link", f'from = "{start}"\nto = "{end}"', frames)
        for start, end, frames in (
            ("Ready", "WalkForward", 4),
            ("WalkForward", "Ready", 3),
            ("Ready", "Cheer", 9),
            ("WalkForward", "Cheer", 6),
        )
    )
    + '[[body]]\nname = "fan"\nsetup = "human"\nmotion_table = "cheerful"\nlandblock = "0xA9B4"\n'
    "origin = [40.0, 40.0, 0.0]\non_ground = true\n\n"
    + _event(0.2, "motion", "Cheer")
    + _event(1.0, "motion", "WalkForward")
    + _event(1.6, "motion", "Cheer")
    + _event(2.4, "stop_motion", "WalkForward")
)


def test_an_actions_hooks_are_owed_and_end_as_on_the_reference(tmp_path: Path) -> None:
    """A cheer's AnimDone completes an action: the kernel owes it to the engine, which writes the
    record's queues back, runs the reference's chain and reads them again. Traces byte for byte
    the reference's, the queues and the action queue the same after, and the walk's links still
    retired in the kernel around them."""
    sims = {}
    for engine in ("reference", "fast"):
        sims[engine] = parse_scenario(_CHEERING, "<cheering>", engine=engine)
        sims[engine].run(trace=tmp_path / f"{engine}.jsonl")
    assert same_run(tmp_path / "reference.jsonl", tmp_path / "fast.jsonl")
    counts = sims["fast"].physics.counts
    assert counts.owed_hooks >= 2 and counts.kernel > 60, counts
    (mine,), (theirs,) = sims["fast"].bodies, sims["reference"].bodies
    assert _state(mine) == _state(theirs)
