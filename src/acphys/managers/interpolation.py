"""``InterpolationManager``: glide a remote body to the positions the server sends.

Each server position becomes a node in a queue. Every step, while the body
touches the ground, the head node pulls the body's offset towards it at twice
the body's adjusted top speed; every fifth step an audit checks that the
body closed on the node at least 30 % as fast as it could. A node too far
away to glide to (the blip distance), or a glide that keeps failing its
audits, teleports the body instead.

Retail's nodes carry a type: 1 a position, 2 a jump, 3 a velocity. The 2013
client only ever queues positions (``InterpolateTo`` is the sole producer), so
the queue here holds positions and the branches of ``adjust_offset`` and
``UseTime`` that handle the other two types, unreachable in retail, are not
ported.
"""

from __future__ import annotations

from collections import deque
from typing import TYPE_CHECKING

from acphys.constants import EPSILON
from acphys.flags import TransientState as TS
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion.move_to import position_distance
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

#: ``MAX_INTERPOLATED_VELOCITY`` (``const float``, acclient_data.h:2589): the speed when the body's own is ~0.
MAX_INTERPOLATED_VELOCITY: float = 7.5
#: ``BIG_DISTANCE`` (``const float``, acclient_data.h:2590): ``original_distance`` with no node under way.
BIG_DISTANCE: float = 999999.0
#: A node is reached within this distance, the float32 0.05 (acclient.c:389057, 389217, 389258).
DESIRED_DISTANCE: float = f32(0.050000001)
#: The queue never holds more than this many nodes after a glide is queued (acclient.c:389084).
MAX_QUEUE_LENGTH: int = 20
#: Steps between progress audits (acclient.c:389244).
AUDIT_FRAMES: int = 5
#: The least fraction of the possible closing rate an audit accepts, the float32 0.3 (acclient.c:389248).
MIN_PROGRESS_RATIO: float = f32(0.30000001)
#: A node failing its audit this close counts as reached (acclient.c:389270). The decompilation's
#: ``0.2`` may be the double or the float32 constant: against the float ``curr_distance`` both
#: compare alike (float32(0.2) is the next float32 above 0.2).
NEAR_ENOUGH: float = 0.2
#: ``node_fail_counter`` set by a blip (acclient.c:389164); above 3 ``UseTime`` snaps (389302).
BLIP_FAIL_COUNT: int = 4
MAX_FAILED_NODES: int = 3


def position_subtract2(p1: Position, p2: Position) -> Frame:
    """The frame that takes ``p2`` to ``p1``, in ``p2``'s local space (across landblocks).

    The rotation is ``Frame::subtract2`` of the two frames; the origin is
    ``p1``'s origin seen from ``p2`` (``localtolocal`` of the zero vector).

    Retail: Position::subtract2 @ 0x00555A90 (acclient.c:388972)
    """
    result = Frame()
    result.subtract2(p1.frame, p2.frame)
    result.origin.set(p2.localtolocal(p1, Vector3()))
    return result


class InterpolationManager:
    """Retail ``InterpolationManager`` (acclient.h): the queue of server positions to glide to.

    Retail: InterpolationManager::InterpolationManager @ 0x005558D0 (acclient.c:388814)
    """

    __slots__ = (
        "blipto_position",
        "frame_counter",
        "keep_heading",
        "node_fail_counter",
        "original_distance",
        "physics_obj",
        "position_queue",
        "progress_quantum",
    )

    def __init__(self, physics_obj: PhysicsObj) -> None:
        self.physics_obj = physics_obj
        #: ``position_queue``: the nodes, head first.
        self.position_queue: deque[Position] = deque()
        #: Retail's constructor leaves ``keep_heading`` unwritten (heap garbage until the first
        #: glide is queued); acphys starts it False.
        self.keep_heading = False
        self.frame_counter = 0
        self.original_distance = BIG_DISTANCE
        self.progress_quantum = 0.0
        self.node_fail_counter = 0
        self.blipto_position = Position()

    def interpolate_to(self, p: Position, keep_heading: bool) -> None:
        """Queue a server position.

        Measured from the last queued node (else the body): beyond the blip
        distance the node is queued with ``node_fail_counter`` 4, so the next
        ``use_time`` teleports there; this branch neither bounds the queue nor
        updates ``keep_heading`` (it reuses the last glide's). Otherwise, with
        the body already within 0.05 m of ``p``, it takes ``p``'s heading
        (unless keeping its own) and stops interpolating; else the trailing
        nodes within 0.05 m of ``p`` are dropped, the oldest nodes go until
        fewer than 20 remain, and ``p`` is queued. A kept heading replaces the
        node's heading with the body's.

        The distance tested against the blip distance is a ``float`` local; the
        0.05-m tests compare the unnarrowed distances (acclient.c:389054-389062).

        Retail: InterpolationManager::InterpolateTo @ 0x00555B20 (acclient.c:389016)
        """
        if not p.frame.origin.is_finite():
            raise ValueError(f"interpolation target must have a finite origin, got {p!r}")
        obj = self.physics_obj
        queue = self.position_queue
        reference = queue[-1] if queue else obj.position
        if f32(position_distance(reference, p)) > obj.get_autonomy_blip_distance():
            self._append(p)
            self.node_fail_counter = BLIP_FAIL_COUNT
            return
        if position_distance(obj.position, p) <= DESIRED_DISTANCE:
            if not keep_heading:
                obj.set_heading(p.frame.get_heading())
            self.stop_interpolating()
            return
        while queue and position_distance(queue[-1], p) < DESIRED_DISTANCE:
            queue.pop()
        while len(queue) >= MAX_QUEUE_LENGTH:
            queue.popleft()
        self.keep_heading = keep_heading
        self._append(p)

    def _append(self, p: Position) -> None:
        """Queue a copy of ``p``, facing the body's heading when ``keep_heading`` is set."""
        node = p.copy()
        if self.keep_heading:
            node.frame.set_heading(self.physics_obj.position.frame.get_heading())
        self.position_queue.append(node)

    def is_interpolating(self) -> bool:
        """A node is queued (``PositionManager::IsInterpolating`` reads the queue head directly).

        Retail: PositionManager::IsInterpolating @ 0x005553B0 (acclient.c:388475)
        """
        return bool(self.position_queue)

    def stop_interpolating(self) -> None:
        """Empty the queue and reset the audit and the failure count.

        Retail: InterpolationManager::StopInterpolating @ 0x00555950 (acclient.c:388852)
        """
        self.position_queue.clear()
        self.frame_counter = 0
        self.progress_quantum = 0.0
        self.node_fail_counter = 0
        self.original_distance = BIG_DISTANCE

    def node_completed(self, success: bool) -> None:
        """Pop the head node and restart the audit.

        With a next node, ``original_distance`` becomes the body's distance to
        it. With none left: ``original_distance`` is reset, and a success stops
        interpolating while a failure remembers the popped node as the
        ``blipto_position`` (``use_time`` then teleports there, the failure
        count being above zero). ``original_distance`` is a ``float`` field.

        Retail: InterpolationManager::NodeCompleted @ 0x005559A0 (acclient.c:388881)
        """
        self.frame_counter = 0
        self.progress_quantum = 0.0
        queue = self.position_queue
        done = queue.popleft() if queue else None
        if queue:
            self.original_distance = f32(position_distance(self.physics_obj.position, queue[0]))
            return
        self.original_distance = BIG_DISTANCE
        if success:
            self.stop_interpolating()
        elif done is not None:
            self.blipto_position = done

    def adjust_offset(self, offset: Frame, quantum: float) -> None:
        """Replace the step's offset with a glide towards the head node (bodies in contact only).

        Within 0.05 m the node completes. The speed is twice the motion
        interpreter's adjusted max speed (``MAX_INTERPOLATED_VELOCITY`` only
        when that is below EPSILON). Every fifth step the audit compares the
        distance closed since the last audit with the time elapsed: a body
        stuck to an object, or one that closed at least EPSILON at 30 % of
        its speed, passes and restarts the audit; otherwise the node completes
        if within 0.2 m, else fails (``node_fail_counter`` + 1) and the offset
        is left alone. The glide is the frame from the body to the node,
        its origin cut to ``speed × quantum``; with ``keep_heading`` its
        heading is reset to 0 (no turn). An origin within 0.05 m completes the
        node but is still applied.

        ``curr_distance``, ``my_max_speed``, ``progress_made``, the step length, the
        adjustment's length and the scale are ``float`` locals, as are the
        ``progress_quantum`` and ``original_distance`` fields; the two 0.05-m tests read
        the distances before they are narrowed (acclient.c:389215-389263).

        Retail: InterpolationManager::adjust_offset @ 0x00555D30 (acclient.c:389177)
        """
        queue = self.position_queue
        obj = self.physics_obj
        if not queue or not obj._transient_state & TS.CONTACT:
            return
        head = queue[0]
        distance = position_distance(obj.position, head)
        if distance < DESIRED_DISTANCE:
            self.node_completed(True)
            return
        curr_distance = f32(distance)
        max_speed = f32(obj.get_minterp().get_adjusted_max_speed() * 2.0)
        if max_speed < EPSILON:
            max_speed = MAX_INTERPOLATED_VELOCITY
        self.frame_counter += 1
        self.progress_quantum = f32(quantum + self.progress_quantum)
        if self.frame_counter >= AUDIT_FRAMES:
            progress_made = f32(self.original_distance - curr_distance)
            if obj.get_sticky_object_id() or (
                progress_made >= EPSILON
                and progress_made / self.progress_quantum / max_speed >= MIN_PROGRESS_RATIO
            ):
                self.frame_counter = 0
                self.progress_quantum = 0.0
                self.original_distance = curr_distance
            else:
                if curr_distance < NEAR_ENOUGH:
                    self.node_completed(True)
                else:
                    self.node_fail_counter += 1
                    self.node_completed(False)
                return
        adjustment = position_subtract2(head, obj.position)
        max_step = f32(max_speed * quantum)
        length = adjustment.origin.length()
        if length <= DESIRED_DISTANCE:
            self.node_completed(True)
        adjustment_distance = f32(length)
        if adjustment_distance > max_step:
            adjustment.origin.set(adjustment.origin * f32(max_step / adjustment_distance))
        if self.keep_heading:
            adjustment.set_heading(0.0)
        offset.assign(adjustment)

    def use_time(self) -> None:
        """Teleport when gliding has given up: more than 3 failures, or any with the queue empty.

        The target is the last queued node, else ``blipto_position``; only a
        successful placement stops interpolating (a refused one retries next
        step).

        Retail: InterpolationManager::UseTime @ 0x00555F20 (acclient.c:389277)
        """
        queue = self.position_queue
        if self.node_fail_counter <= MAX_FAILED_NODES and (queue or self.node_fail_counter <= 0):
            return
        target = queue[-1] if queue else self.blipto_position
        if self.physics_obj.set_position_simple(target, True) == 0:
            self.stop_interpolating()
