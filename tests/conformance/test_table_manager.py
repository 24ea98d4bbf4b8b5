"""MotionTableManager: the pending-motion queue, AnimDone counting and completion order.

Expectations derived by hand from CMTableManager.c; the ``acclient.c`` line
of the deciding statement sits beside each assertion. A real ``Sequence`` and
``MotionTable`` run underneath; completions are watched on a ``PhysicsObj``
whose ``motion_done`` also notes the call (and the state's actions at that
moment) before doing what ``PhysicsObj`` does.
"""

from __future__ import annotations

import pytest

from acphys.math.vector import Vector3
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.commands import HAND_COMBAT, JUMP, MOTION_IDS, NON_COMBAT, READY, RUN_FORWARD, WALK_FORWARD
from acphys.motion.motion_table import MotionData, MotionTable
from acphys.motion.movement import MovementError, MovementParameters, MovementStruct, MovementType
from acphys.motion.sequence import Sequence
from acphys.motion.table_manager import AnimNode, MotionTableManager
from acphys.physics_obj import PhysicsObj
from acphys.world.world import World

CHEER = MOTION_IDS["Cheer"]


class WatchedBody(PhysicsObj):
    """A real body whose MotionDone is also written down."""

    def __init__(self, world: World) -> None:
        super().__init__(world, "watched")
        self.done: list[tuple[int, bool, int]] = []
        self.manager: MotionTableManager | None = None

    def motion_done(self, motion: int, success: bool) -> None:
        actions = len(self.manager.state.actions) if self.manager is not None else -1
        self.done.append((motion, success, actions))
        super().motion_done(motion, success)


def _md(*names: str, velocity: Vector3 | None = None) -> MotionData:
    return MotionData([AnimData(Animation([AnimFrame()], name=name)) for name in names], velocity)


def build_table() -> MotionTable:
    return MotionTable(
        default_style=NON_COMBAT,
        style_defaults={NON_COMBAT: READY},
        cycles={
            0x003D0003: _md("ready"),
            0x003D0005: _md("walk", velocity=Vector3(0.0, 3.12, 0.0)),
            0x003D0007: _md("run", velocity=Vector3(0.0, 4.0, 0.0)),
        },
        modifiers={0x0000003B: _md(velocity=Vector3(0.0, 0.0, 2.0))},
        links={
            0x003D0003: {WALK_FORWARD: _md("ready_walk_a", "ready_walk_b"), CHEER: _md("cheer")},
            0x003D0005: {READY: _md("walk_ready")},
        },
    )


@pytest.fixture
def body(world: World) -> WatchedBody:
    return WatchedBody(world)


def started(body: WatchedBody) -> tuple[MotionTableManager, Sequence]:
    manager = MotionTableManager(build_table(), body)
    body.manager = manager
    seq = Sequence()
    manager.initialize_state(seq)
    return manager, seq


def command(motion: int, speed: float = 1.0) -> MovementStruct:
    return MovementStruct(MovementType.INTERPRETED_COMMAND, motion, params=MovementParameters(speed=speed))


def queue(manager: MotionTableManager) -> list[tuple[int, int]]:
    return [(node.motion, node.num_anims) for node in manager.pending_animations]


def names(seq: Sequence) -> list[str]:
    return [node.animation.name for node in seq.anim_list]


# -- queueing --------------------------------------------------------------------------------


def test_initialize_state_queues_ready(body: WatchedBody) -> None:
    manager, seq = started(body)
    assert queue(manager) == [(READY, 0)]  # 0x41000003 with the cycle's count - 1 (acclient.c:330194-330195)
    assert (manager.state.style, manager.state.substate) == (NON_COMBAT, READY)  # acclient.c:330185
    assert names(seq) == ["ready"]


def test_initialize_state_without_a_table_still_queues_ready(body: WatchedBody) -> None:
    manager = MotionTableManager(None, body)
    manager.initialize_state(Sequence())
    assert queue(manager) == [(READY, 0)]  # num_anims = 0 (acclient.c:330187-330195)


def test_perform_movement_queues_the_command_with_its_link_count(body: WatchedBody) -> None:
    manager, seq = started(body)
    assert manager.perform_movement(command(WALK_FORWARD), seq) == MovementError.NONE  # acclient.c:330228
    assert queue(manager) == [(READY, 0), (WALK_FORWARD, 2)]  # add_to_queue at the tail (acclient.c:330227)


def test_perform_movement_errors(body: WatchedBody) -> None:
    manager, seq = started(body)
    # acclient.c:330219
    assert MotionTableManager(None, body).perform_movement(command(WALK_FORWARD), seq) == 7
    # the table refuses Crouch (no cycle): 67, nothing queued (acclient.c:330230)
    assert manager.perform_movement(command(0x41000012), seq) == 0x43
    stop_run = MovementStruct(MovementType.STOP_INTERPRETED_COMMAND, RUN_FORWARD)
    assert manager.perform_movement(stop_run, seq) == 0x43  # acclient.c:330240
    assert queue(manager) == [(READY, 0)]
    with pytest.raises(ValueError, match="MOVE_TO_OBJECT"):
        manager.perform_movement(MovementStruct(MovementType.MOVE_TO_OBJECT), seq)


def test_stops_queue_ready(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.perform_movement(command(WALK_FORWARD), seq)
    stop_walk = MovementStruct(MovementType.STOP_INTERPRETED_COMMAND, WALK_FORWARD)
    assert manager.perform_movement(stop_walk, seq) == 0
    # queued as Ready, not as the stopped motion (acclient.c:330237)
    assert queue(manager)[-1] == (READY, 1)
    manager.perform_movement(command(JUMP), seq)
    # acclient.c:330246
    assert manager.perform_movement(MovementStruct(MovementType.STOP_COMPLETELY), seq) == 0
    assert queue(manager)[-2:] == [(JUMP, 0), (READY, 0)]  # acclient.c:330245
    assert manager.state.modifiers == []


# -- completion ------------------------------------------------------------------------------


def test_check_for_completed_motions_completes_zero_count_heads_in_order(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.perform_movement(command(JUMP), seq)
    manager.perform_movement(command(WALK_FORWARD), seq)
    manager.check_for_completed_motions()
    # heads with num_anims 0 complete with success 1; the walk (2) stops the loop (acclient.c:329973-329977)
    assert [(m, s) for m, s, _ in body.done] == [(READY, True), (JUMP, True)]
    assert queue(manager) == [(WALK_FORWARD, 2)]


def test_use_time_is_check_for_completed_motions(body: WatchedBody) -> None:
    manager, _ = started(body)
    manager.use_time()
    assert [(m, s) for m, s, _ in body.done] == [(READY, True)]
    assert manager.pending_animations == []


def test_animation_done_counts_anim_done_hooks(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.check_for_completed_motions()
    manager.perform_movement(command(WALK_FORWARD), seq)
    manager.animation_done(True)
    assert body.done == [(READY, True, 0)]  # counter 1 < 2: nothing (acclient.c:329887-329890)
    assert manager.animation_counter == 1
    manager.animation_done(True)
    assert body.done[-1] == (WALK_FORWARD, True, 0)  # acclient.c:329894
    assert manager.animation_counter == 0  # 2 - 2 (acclient.c:329895)
    assert manager.pending_animations == []


def test_animation_done_carries_the_counter_to_the_next_motion(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.perform_movement(command(WALK_FORWARD), seq)
    # Ready (0) completes on the first AnimDone and leaves the counter at 1 - 0 = 1 for the walk
    # (acclient.c:329887-329895)
    manager.animation_done(False)
    assert queue(manager) == [(WALK_FORWARD, 2)]
    assert manager.animation_counter == 1
    manager.animation_done(True)
    assert [(m, s) for m, s, _ in body.done] == [(READY, False), (WALK_FORWARD, True)]


def test_animation_done_resets_a_counter_left_with_an_empty_queue(body: WatchedBody) -> None:
    manager, _ = started(body)
    manager.animation_done(True)
    # Ready (0) done, counter 1 - 0 = 1 with nothing pending: reset (acclient.c:329931-329934)
    assert manager.animation_counter == 0
    manager.animation_done(True)  # empty queue: not even counted (acclient.c:329885)
    assert manager.animation_counter == 0


def test_action_head_is_popped_before_motion_done(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.check_for_completed_motions()
    assert manager.perform_movement(command(CHEER), seq) == 0
    assert [n.motion for n in manager.state.actions] == [CHEER]
    assert queue(manager) == [(CHEER, 1)]
    manager.animation_done(True)
    # motion & 0x10000000: remove_action_head, *then* MotionDone (acclient.c:329892-329894)
    assert body.done[-1] == (CHEER, True, 0)
    assert manager.state.actions == []


def test_handle_exit_world_force_completes_with_failure(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.perform_movement(command(WALK_FORWARD), seq)
    manager.perform_movement(command(CHEER), seq)
    manager.handle_exit_world()
    # AnimationDone(0) until the queue is empty (acclient.c:329944)
    assert [(m, s) for m, s, _ in body.done] == [(READY, False), (WALK_FORWARD, False), (CHEER, False)]
    assert manager.pending_animations == [] and manager.animation_counter == 0
    assert manager.state.actions == []


def test_handle_enter_world_drops_links_then_force_completes(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.perform_movement(command(WALK_FORWARD), seq)
    assert names(seq) == ["ready_walk_a", "ready_walk_b", "walk"]
    manager.handle_enter_world(seq)
    assert names(seq) == ["walk"]  # remove_all_link_animations (acclient.c:329954)
    assert [(m, s) for m, s, _ in body.done] == [(READY, False), (WALK_FORWARD, False)]  # acclient.c:329956


def test_without_a_body_completions_are_dropped() -> None:
    manager = MotionTableManager(build_table())
    seq = Sequence()
    manager.initialize_state(seq)
    manager.check_for_completed_motions()
    assert manager.pending_animations == []


# -- redundant links -------------------------------------------------------------------------


def test_walk_stop_walk_truncates_the_redundant_links(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.check_for_completed_motions()
    manager.perform_movement(command(WALK_FORWARD), seq)
    manager.perform_movement(MovementStruct(MovementType.STOP_INTERPRETED_COMMAND, WALK_FORWARD), seq)
    manager.perform_movement(command(WALK_FORWARD), seq)
    # newest waiting node Walk(2); back past Ready(1) (no 0xB0000000 bit) to Walk(2): truncate there,
    # zeroing Ready and the new Walk and dropping 1 + 2 link animations (acclient.c:330099-330141,
    # 329858-329864, 329855)
    assert queue(manager) == [(WALK_FORWARD, 2), (READY, 0), (WALK_FORWARD, 0)]
    assert names(seq) == ["ready_walk_a", "ready_walk_b", "walk"]
    manager.animation_done(True)
    manager.animation_done(True)
    assert [m for m, _, _ in body.done[1:]] == [WALK_FORWARD, READY, WALK_FORWARD]


def test_substate_search_stops_at_a_waiting_action(body: WatchedBody) -> None:
    manager = MotionTableManager(build_table(), body)
    seq = Sequence()
    for motion in (WALK_FORWARD, CHEER, WALK_FORWARD):
        manager.add_to_queue(motion, 1, seq)
    assert queue(manager) == [(WALK_FORWARD, 1), (CHEER, 1), (WALK_FORWARD, 1)]  # acclient.c:330112-330118


def test_substate_search_needs_a_waiting_match_style_search_does_not(body: WatchedBody) -> None:
    manager = MotionTableManager(build_table(), body)
    seq = Sequence()
    manager.add_to_queue(WALK_FORWARD, 0, seq)
    manager.add_to_queue(WALK_FORWARD, 2, seq)
    # match needs num_anims (acclient.c:330107-330109)
    assert queue(manager) == [(WALK_FORWARD, 0), (WALK_FORWARD, 2)]
    styles = MotionTableManager(build_table(), body)
    styles.add_to_queue(HAND_COMBAT, 0, seq)
    styles.add_to_queue(READY, 0, seq)
    styles.add_to_queue(HAND_COMBAT, 2, seq)
    # style: any earlier node of the same style, skipping nodes that wait for nothing
    # (acclient.c:330130-330141)
    assert queue(styles) == [(HAND_COMBAT, 0), (READY, 0), (HAND_COMBAT, 0)]


def test_only_the_newest_waiting_node_is_examined(body: WatchedBody) -> None:
    # ACE moves on to older nodes when the newest finds neither match nor stop; retail returns
    # (acclient.c:330115-330119). add_to_queue runs the check on every append, so such a queue is
    # built here by hand to show the difference.
    manager = MotionTableManager(build_table(), body)
    manager.pending_animations = [
        AnimNode(WALK_FORWARD, 1),
        AnimNode(WALK_FORWARD, 1),
        AnimNode(RUN_FORWARD, 1),
    ]
    manager.remove_redundant_links(Sequence())
    assert queue(manager) == [(WALK_FORWARD, 1), (WALK_FORWARD, 1), (RUN_FORWARD, 1)]


def test_truncate_animation_list_with_a_node_not_queued_zeroes_everything(body: WatchedBody) -> None:
    manager, seq = started(body)
    manager.perform_movement(command(WALK_FORWARD), seq)
    manager.truncate_animation_list(AnimNode(READY, 0), seq)
    # the walk back zeroes as it goes and never reaches the node (acclient.c:329858-329866)
    assert queue(manager) == [(READY, 0), (WALK_FORWARD, 0)]
    assert names(seq) == ["ready_walk_a", "ready_walk_b", "walk"]
