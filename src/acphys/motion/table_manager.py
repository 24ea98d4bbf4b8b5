"""``MotionTableManager``: the motion table, the body's ``MotionState`` and the queue of pending motions.

Each command the table accepts is queued as an ``AnimNode`` holding the
number of animations it put ahead of its cycle. Every AnimDone hook the
sequence fires reaches ``animation_done``, which counts them: once the head
node's count is reached its motion is done and goes to
``PhysicsObj.motion_done`` (retail ``CPhysicsObj::MotionDone``). Nodes that
queued nothing complete on the next ``check_for_completed_motions``.

``SetMotionTableID`` (DAT loading) is not ported: the table is passed in.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import member_namespace
from acphys.motion.commands import ACTION_MASK, MODIFIER_MASK, READY, STYLE_MASK, SUBSTATE_MASK
from acphys.motion.motion_table import MotionState
from acphys.motion.movement import MovementError, MovementStruct, MovementType

ME = member_namespace(MovementError)
MT = member_namespace(MovementType)

if TYPE_CHECKING:
    from acphys.motion.motion_table import MotionTable
    from acphys.motion.sequence import Sequence
    from acphys.physics_obj import PhysicsObj

_U32 = 0xFFFFFFFF
#: A node stops the substate walk of ``remove_redundant_links`` when it is a style, modifier or action.
_STOPS_SUBSTATE_SEARCH = 0xB0000000
#: A node stops the style walk when it is a substate, modifier or action.
_STOPS_STYLE_SEARCH = 0x70000000


class AnimNode:
    """Retail ``MotionTableManager::AnimNode`` (acclient.h:57614): a queued motion and its animation count."""

    __slots__ = ("motion", "num_anims")

    def __init__(self, motion: int, num_anims: int) -> None:
        self.motion = motion
        self.num_anims = num_anims

    def __repr__(self) -> str:
        return f"AnimNode(0x{self.motion:08X}, {self.num_anims})"


class MotionTableManager:
    """Retail ``MotionTableManager`` (acclient.h:31097).

    ``pending_animations`` is the retail doubly linked list, head first.
    """

    __slots__ = ("animation_counter", "pending_animations", "physics_obj", "state", "table")

    def __init__(self, table: MotionTable | None, physics_obj: PhysicsObj | None = None) -> None:
        """Retail: MotionTableManager::Create @ 0x0051BC50 (acclient.c:329813)"""
        self.table = table
        self.physics_obj = physics_obj
        self.state = MotionState()
        self.animation_counter = 0
        self.pending_animations: list[AnimNode] = []

    # -- requests ----------------------------------------------------------------------------

    def perform_movement(self, ms: MovementStruct, seq: Sequence) -> int:
        """Run an interpreted command, a stop or a full stop through the table; 0 or an error code.

        No table: 7 (NO_ANIMATION_TABLE). A command or stop the table refuses:
        0x43 (NO_MTABLE_DATA). A stop (either kind) is queued as Ready. Retail
        handles only types 2, 4 and 5 and returns a leftover register for the
        others; acphys raises ``ValueError`` for them.

        Retail: MotionTableManager::PerformMovement @ 0x0051C0B0 (acclient.c:330205)
        """
        if self.table is None:
            return ME.NO_ANIMATION_TABLE
        if ms.type == MT.INTERPRETED_COMMAND:
            ok, num_anims = self.table.do_object_motion(ms.motion, self.state, seq, ms.params.speed)
            if not ok:
                return ME.NO_MTABLE_DATA
            self.add_to_queue(ms.motion, num_anims, seq)
            return ME.NONE
        if ms.type == MT.STOP_INTERPRETED_COMMAND:
            ok, num_anims = self.table.stop_object_motion(ms.motion, ms.params.speed, self.state, seq)
            if not ok:
                return ME.NO_MTABLE_DATA
            self.add_to_queue(READY, num_anims, seq)
            return ME.NONE
        if ms.type == MT.STOP_COMPLETELY:
            _, num_anims = self.table.stop_object_completely(self.state, seq)
            self.add_to_queue(READY, num_anims, seq)
            return ME.NONE
        raise ValueError(
            f"MotionTableManager.perform_movement handles interpreted commands, stops and full stops, "
            f"not {ms.type!r}"
        )

    def initialize_state(self, seq: Sequence) -> None:
        """Put the body in the table's default state and queue Ready with the cycle's count.

        Retail: MotionTableManager::initialize_state @ 0x0051C030 (acclient.c:330171)
        """
        num_anims = 0
        if self.table is not None:
            _, num_anims = self.table.set_default_state(self.state, seq)
        self.add_to_queue(READY, num_anims, seq)

    def add_to_queue(self, motion: int, num_anims: int, seq: Sequence) -> None:
        """Append ``motion`` to the pending queue, then drop links a newer motion made redundant.

        Retail: MotionTableManager::add_to_queue @ 0x0051BFE0 (acclient.c:330148)
        """
        self.pending_animations.append(AnimNode(motion, num_anims & _U32))
        self.remove_redundant_links(seq)

    def remove_redundant_links(self, seq: Sequence) -> None:
        """Cut the links of motions that a newer identical motion supersedes.

        Looks only at the newest node still waiting for animations. If it is a
        plain substate (not a modifier), the walk back stops at any waiting
        style, modifier or action and truncates at an earlier *waiting* node of
        the same motion. If it is a style, the walk stops at any waiting
        substate, modifier or action and truncates at an earlier node of the
        same style, waiting or not. Anything else truncates nothing.

        Retail: MotionTableManager::remove_redundant_links @ 0x0051BF20 (acclient.c:330078)
        """
        nodes = self.pending_animations
        newest = len(nodes) - 1
        while newest >= 0 and nodes[newest].num_anims == 0:
            newest -= 1
        if newest < 0:
            return
        motion = nodes[newest].motion
        if motion & SUBSTATE_MASK and not motion & MODIFIER_MASK:
            for index in range(newest - 1, -1, -1):
                node = nodes[index]
                if node.motion == motion and node.num_anims:
                    self.truncate_animation_list(node, seq)
                    return
                if node.num_anims and node.motion & _STOPS_SUBSTATE_SEARCH:
                    return
        elif motion & STYLE_MASK:
            for index in range(newest - 1, -1, -1):
                node = nodes[index]
                if node.motion == motion:
                    self.truncate_animation_list(node, seq)
                    return
                if node.num_anims and node.motion & _STOPS_STYLE_SEARCH:
                    return

    def truncate_animation_list(self, node: AnimNode | None, seq: Sequence) -> None:
        """Zero the counts of every node after ``node`` and drop that many link animations.

        Walks from the tail back to ``node`` (exclusive), summing and zeroing
        counts, then ``seq.remove_link_animations(sum)``. A ``node`` not in the
        queue zeroes every count and removes nothing, as in retail.

        Retail: MotionTableManager::truncate_animation_list @ 0x0051BCA0 (acclient.c:329841)
        """
        if node is None:
            return
        total = 0
        for later in reversed(self.pending_animations):
            if later is node:
                seq.remove_link_animations(total & _U32)
                return
            total += later.num_anims
            later.num_anims = 0

    # -- completion --------------------------------------------------------------------------

    def _complete_head(self, success: bool) -> None:
        head = self.pending_animations[0]
        if head.motion & ACTION_MASK:
            self.state.remove_action_head()
        if self.physics_obj is not None:
            self.physics_obj.motion_done(head.motion, success)

    def animation_done(self, success: bool) -> None:
        """One AnimDone hook fired: count it and complete every head node whose count is reached.

        For each completed node: an action first pops the state's action head,
        then ``physics_obj.motion_done(motion, success)``, then the node's count
        is taken off the counter and the node leaves the queue. A counter left
        over with the queue empty is reset.

        Retail: MotionTableManager::AnimationDone @ 0x0051BCE0 (acclient.c:329872)
        """
        if not self.pending_animations:
            return
        self.animation_counter += 1
        while self.pending_animations:
            head = self.pending_animations[0]
            if head.num_anims > self.animation_counter:
                break
            self._complete_head(success)
            self.animation_counter -= head.num_anims
            if self.pending_animations:
                self.pending_animations.pop(0)
        if self.animation_counter and not self.pending_animations:
            self.animation_counter = 0

    def check_for_completed_motions(self) -> None:
        """Complete (successfully) every head node that waits for no animation.

        Retail: MotionTableManager::CheckForCompletedMotions @ 0x0051BE00 (acclient.c:329959)
        """
        while self.pending_animations and self.pending_animations[0].num_anims == 0:
            self._complete_head(True)
            if self.pending_animations:
                self.pending_animations.pop(0)

    def use_time(self) -> None:
        """The manager's per-tick service (``CPartArray::HandleMovement``).

        The decompilation has only the prototype of ``MotionTableManager::UseTime``
        (acclient_protos.h:6738) and the call at acclient.c:325112, no body;
        like ACE, acphys takes it to be ``CheckForCompletedMotions``.

        Retail: CPartArray::HandleMovement @ 0x00517D60 (acclient.c:325105)
        """
        self.check_for_completed_motions()

    def handle_exit_world(self) -> None:
        """Force every pending motion to complete, unsuccessfully.

        Retail: MotionTableManager::HandleExitWorld @ 0x0051BDA0 (acclient.c:329939)
        """
        while self.pending_animations:
            self.animation_done(False)

    def handle_enter_world(self, seq: Sequence) -> None:
        """Drop every link animation, then force every pending motion to complete, unsuccessfully.

        Retail: MotionTableManager::HandleEnterWorld @ 0x0051BDD0 (acclient.c:329948)
        """
        seq.remove_all_link_animations()
        while self.pending_animations:
            self.animation_done(False)
