"""``CSequence``: animation playback, and the root motion it writes into the offset frame.

A sequence is a list of :class:`AnimSequenceNode`: zero or more link
(transition) animations followed by the cyclic ones, from ``first_cyclic``
to the end, which loop. ``curr_anim`` and ``frame_number`` (a double: retail's
``long double`` is 64-bit under MSVC) say where playback is.

Playback is quantized to animation frames, in root motion *and* velocity:
``update_internal`` advances ``frame_number`` by ``framerate * quantum`` and,
for every whole frame boundary crossed, composes that frame's position frame
into the offset frame (reverse playback subtracts it), applies one frame's
worth (``1/framerate`` s) of the sequence's velocity and omega, and queues
the frame's hooks on the body. A quantum that crosses no boundary moves
nothing. The true quantum is used only when the list is empty or the
framerate is zero (docs/01-physics.md section 4).

Precision: ``velocity`` and ``omega`` are float32 vectors and each node's
framerate a float32 (retail ``float`` fields); ``frame_number``, the frame
quantum, the leftover time and the physics step ``1 / framerate`` stay double,
as in ``update_internal``'s locals (acclient.c:340678-340683).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.motion.anim_hooks import ANIM_DONE_HOOK
from acphys.motion.animation import F_EPSILON, AnimData, AnimFrame, AnimSequenceNode
from acphys.precision import pack3, unpack3

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

_floor = math.floor


def combine_anim_frame(frame: Frame, pos: Frame) -> None:
    """``frame = frame ∘ pos``: compose a position frame (retail ``AFrame``) onto ``frame`` in place.

    The same composition as :meth:`Frame.combine`, with this overload's own order of the
    quaternion's x sum (``x1·w2 + w1·x2 + z2·y1 - y2·z1``): with float32 operands and double
    sums the order decides the last bit. The origin and the four components are ``float``
    stores (acclient.c:340437-340457); ``frame`` must be cached.

    Retail: Frame::combine @ 0x00525180 (acclient.c:340419)
    """
    m = frame.m
    o = pos.origin
    fo = frame.origin
    fo.x, fo.y, fo.z = unpack3(
        pack3(
            m[6] * o.z + m[0] * o.x + m[3] * o.y + fo.x,
            m[7] * o.z + m[1] * o.x + m[4] * o.y + fo.y,
            m[8] * o.z + m[2] * o.x + m[5] * o.y + fo.z,
        )
    )
    w1, x1, y1, z1 = frame.qw, frame.qx, frame.qy, frame.qz
    w2, x2, y2, z2 = pos.qw, pos.qx, pos.qy, pos.qz
    frame.set_rotate(
        w1 * w2 - x1 * x2 - y2 * y1 - z2 * z1,
        x1 * w2 + w1 * x2 + z2 * y1 - y2 * z1,
        y2 * w1 - x1 * z2 + z1 * x2 + y1 * w2,
        x1 * y2 + z2 * w1 - y1 * x2 + z1 * w2,
    )


class Sequence:
    """Retail ``CSequence`` (acclient.h:30747).

    ``velocity`` and ``omega`` are in the body's local space. ``hook_obj`` is
    the body the frame hooks are queued on (None: hooks are not fired).
    """

    __slots__ = (
        "anim_list",
        "curr_anim",
        "first_cyclic",
        "frame_number",
        "hook_obj",
        "omega",
        "placement_frame",
        "placement_frame_id",
        "velocity",
    )

    def __init__(self) -> None:
        """Retail: CSequence::CSequence @ 0x005249F0 (acclient.c:339779)"""
        self.anim_list: list[AnimSequenceNode] = []
        self.first_cyclic: AnimSequenceNode | None = None
        self.velocity = Vector3()
        self.omega = Vector3()
        self.hook_obj: PhysicsObj | None = None
        self.frame_number = 0.0
        self.curr_anim: AnimSequenceNode | None = None
        self.placement_frame: AnimFrame | None = None
        self.placement_frame_id = 0

    def __repr__(self) -> str:
        return (
            f"Sequence(anims={len(self.anim_list)}, frame={self.frame_number}, "
            f"velocity={self.velocity!r}, omega={self.omega!r})"
        )

    # -- list navigation (retail's intrusive DLList) -------------------------------------------

    def _next(self, node: AnimSequenceNode) -> AnimSequenceNode | None:
        """Retail: AnimSequenceNode::GetNext @ 0x00525DE0 (acclient.c:341126)"""
        index = self.anim_list.index(node) + 1
        return self.anim_list[index] if index < len(self.anim_list) else None

    def _prev(self, node: AnimSequenceNode) -> AnimSequenceNode | None:
        """Retail: AnimSequenceNode::GetPrev @ 0x00525DF0 (acclient.c:341140)"""
        index = self.anim_list.index(node)
        return self.anim_list[index - 1] if index > 0 else None

    # -- body, physics and placement ----------------------------------------------------------

    def set_object(self, obj: PhysicsObj | None) -> None:
        """Retail: CSequence::set_object @ 0x00524820 (acclient.c:339676)"""
        self.hook_obj = obj

    def set_velocity(self, velocity: Vector3) -> None:
        """Retail: CSequence::set_velocity @ 0x00524880 (acclient.c:339701)"""
        self.velocity = velocity.copy()

    def set_omega(self, omega: Vector3) -> None:
        """Retail: CSequence::set_omega @ 0x005248A0 (acclient.c:339707)"""
        self.omega = omega.copy()

    def combine_physics(self, velocity: Vector3, omega: Vector3) -> None:
        """Add ``velocity`` and ``omega`` to the sequence's.

        Retail: CSequence::combine_physics @ 0x005248C0 (acclient.c:339713)
        """
        self.velocity = self.velocity + velocity
        self.omega = self.omega + omega

    def subtract_physics(self, velocity: Vector3, omega: Vector3) -> None:
        """Take ``velocity`` and ``omega`` off the sequence's.

        Retail: CSequence::subtract_physics @ 0x00524900 (acclient.c:339724)
        """
        self.velocity = self.velocity - velocity
        self.omega = self.omega - omega

    def clear_physics(self) -> None:
        """Retail: CSequence::clear_physics @ 0x00524D50 (acclient.c:340085)"""
        self.velocity = Vector3()
        self.omega = Vector3()

    def set_placement_frame(self, placement_frame: AnimFrame | None, placement_id: int) -> None:
        """The pose shown when no animation plays.

        Retail: CSequence::set_placement_frame @ 0x005249B0 (acclient.c:339766)
        """
        self.placement_frame = placement_frame
        self.placement_frame_id = placement_id

    # -- the list -------------------------------------------------------------------------------

    def has_anims(self) -> bool:
        """Retail: CSequence::has_anims @ 0x00524BD0 (acclient.c:339947)"""
        return bool(self.anim_list)

    def append_animation(self, anim_data: AnimData) -> None:
        """Queue ``anim_data`` at the end; it becomes ``first_cyclic`` (the loop starts at the tail).

        Data without an animation is dropped. If nothing was playing, play
        starts at the head of the list, at its starting frame.

        Retail: CSequence::append_animation @ 0x00525510 (acclient.c:340589)
        """
        node = AnimSequenceNode(anim_data)
        if not node.has_anim():
            return
        self.anim_list.append(node)
        self.first_cyclic = node
        if self.curr_anim is None:
            head = self.anim_list[0]
            self.curr_anim = head
            self.frame_number = head.get_starting_frame()

    def remove_link_animations(self, count: int) -> None:
        """Drop up to ``count`` link animations, each time the one just before ``first_cyclic``.

        If the dropped link was playing, play jumps to the start of
        ``first_cyclic``. (Retail dereferences ``first_cyclic`` unchecked; an
        empty sequence has nothing to drop here.)

        Retail: CSequence::remove_link_animations @ 0x00524BE0 (acclient.c:339953)
        """
        cyclic = self.first_cyclic
        if cyclic is None:
            return
        for _ in range(count):
            link = self._prev(cyclic)
            if link is None:
                break
            if link is self.curr_anim:
                self.curr_anim = cyclic
                self.frame_number = cyclic.get_starting_frame()
            self.anim_list.remove(link)

    def remove_all_link_animations(self) -> None:
        """Drop every animation before ``first_cyclic`` (jumping to its start if a link was playing).

        Retail: CSequence::remove_all_link_animations @ 0x00524CA0 (acclient.c:340019)
        """
        cyclic = self.first_cyclic
        if cyclic is None:
            return
        while (link := self._prev(cyclic)) is not None:
            if link is self.curr_anim:
                self.curr_anim = cyclic
                self.frame_number = cyclic.get_starting_frame()
            self.anim_list.remove(link)

    def remove_cyclic_anims(self) -> None:
        """Drop ``first_cyclic`` and everything after it; the new tail becomes ``first_cyclic``.

        If a dropped node was playing, play moves to the node before it, at
        its ending frame (frame 0 when there is none).

        Retail: CSequence::remove_cyclic_anims @ 0x00524E40 (acclient.c:340153)
        """
        node = self.first_cyclic
        if node is not None:
            anims = self.anim_list
            index = anims.index(node)
            while index < len(anims):
                node = anims[index]
                if node is self.curr_anim:
                    prev = anims[index - 1] if index > 0 else None
                    self.curr_anim = prev
                    self.frame_number = prev.get_ending_frame() if prev is not None else 0.0
                del anims[index]
        self.first_cyclic = self.anim_list[-1] if self.anim_list else None

    def clear_animations(self) -> None:
        """Retail: CSequence::clear_animations @ 0x00524DC0 (acclient.c:340101)"""
        self.anim_list.clear()
        self.first_cyclic = None
        self.frame_number = 0.0
        self.curr_anim = None

    def clear(self) -> None:
        """Drop every animation, the velocity and omega, and the placement frame.

        Retail: CSequence::clear @ 0x005255B0 (acclient.c:340646)
        """
        self.clear_animations()
        self.clear_physics()
        self.placement_frame = None
        self.placement_frame_id = 0

    def apricot(self) -> None:
        """Drop finished animations from the head, stopping at ``curr_anim`` or ``first_cyclic``.

        Retail: CSequence::apricot @ 0x00524B40 (acclient.c:339892)
        """
        anims = self.anim_list
        while True:
            head = anims[0] if anims else None
            if head is self.curr_anim or head is self.first_cyclic:
                return
            del anims[0]

    def multiply_cyclic_animation_framerate(self, rate: float) -> None:
        """Scale the framerate of ``first_cyclic`` and every node after it.

        Retail: CSequence::multiply_cyclic_animation_fr @ 0x00524940 (acclient.c:339735)
        """
        cyclic = self.first_cyclic
        if cyclic is None:
            return
        anims = self.anim_list
        for index in range(anims.index(cyclic), len(anims)):
            anims[index].multiply_framerate(rate)

    # -- where play is ---------------------------------------------------------------------------

    def get_curr_frame_number(self) -> int:
        """Retail: CSequence::get_curr_frame_number @ 0x005249D0 (acclient.c:339773)"""
        return _floor(self.frame_number)

    def get_curr_animframe(self) -> AnimFrame | None:
        """The current frame's :class:`AnimFrame`, or the placement frame when nothing plays.

        Retail: CSequence::get_curr_animframe @ 0x00524970 (acclient.c:339744)
        """
        if self.curr_anim is None:
            return self.placement_frame
        return self.curr_anim.get_part_frame(_floor(self.frame_number))

    # -- playback --------------------------------------------------------------------------------

    def execute_hooks(self, anim_frame: AnimFrame, direction: int) -> None:
        """Queue on the body each hook of ``anim_frame`` whose direction is BOTH (0) or ``direction``.

        Retail: CSequence::execute_hooks @ 0x00524830 (acclient.c:339682)
        """
        obj = self.hook_obj
        if obj is None:
            return
        for hook in anim_frame.hooks:
            hook_dir = hook.direction
            if hook_dir == 0 or hook_dir == direction:
                obj.add_anim_hook(hook)

    def apply_physics(self, frame: Frame, quantum: float, sign: float) -> None:
        """Move ``frame`` by ``|quantum| · velocity`` and rotate it locally by ``|quantum| · omega``.

        The step takes the sign of ``sign`` (negative for reverse playback).
        The translation is added to the origin as is (the offset frame is the
        body's local space); the rotation goes through ``Frame::rotate``
        (skipped for an exactly zero omega, which ``Frame::grotate`` ignores).

        The step stays double; the y and z translations are spilled into the ``float`` vector
        local ``w`` before they are added to the origin, the x one is not, and the three
        rotation components are ``float`` stores into ``w`` (acclient.c:339876-339888).

        Retail: CSequence::apply_physics @ 0x00524AB0 (acclient.c:339859)
        """
        scale = math.fabs(quantum)
        if sign < 0.0:
            scale = -scale
        v = self.velocity
        origin = frame.origin
        dy, dz, _ = unpack3(pack3(scale * v.y, scale * v.z, 0.0))
        origin.x, origin.y, origin.z = unpack3(pack3(scale * v.x + origin.x, dy + origin.y, dz + origin.z))
        w = self.omega
        if w.x != 0.0 or w.y != 0.0 or w.z != 0.0:
            frame.rotate(Vector3(scale * w.x, scale * w.y, scale * w.z))

    def update(self, quantum: float, offset_frame: Frame | None) -> None:
        """Advance play by ``quantum`` seconds, writing root motion into ``offset_frame`` (if any).

        With no animation queued the velocity and omega apply for the whole
        quantum; otherwise ``update_internal`` plays, then ``apricot`` drops
        the finished links.

        Retail: CSequence::update @ 0x00525B80 (acclient.c:340950)
        """
        if self.anim_list:
            self.update_internal(quantum, offset_frame)
            self.apricot()
        elif offset_frame is not None:
            self.apply_physics(offset_frame, quantum, quantum)

    def update_internal(self, quantum: float, frame: Frame | None) -> None:
        """Play ``curr_anim`` from ``frame_number`` for ``quantum`` seconds, across animations.

        For each whole frame boundary crossed (frame ``n`` is crossed going
        from ``n`` to ``n + 1`` forwards, or from ``n`` down past ``n``
        backwards): compose (forwards) or subtract (backwards) frame ``n``'s
        position frame, apply ``1/framerate`` s of physics, and queue ``n``'s
        hooks for that direction. Running past ``high_frame`` (below
        ``low_frame`` backwards) clamps the frame number there, queues
        AnimDone when the head of the list is not ``first_cyclic``, moves to
        the next animation and plays the leftover time in it. A zero
        framerate applies physics for the whole (leftover) quantum.

        Retail plays through ``CSequence`` pointers to ``curr_anim`` and
        ``frame_number``; its only caller passes the sequence's own.

        Retail: CSequence::update_internal @ 0x005255D0 (acclient.c:340658)
        """
        fabs = math.fabs
        while True:
            node = self.curr_anim
            framerate = node.framerate
            frame_quantum = framerate * quantum
            last = _floor(self.frame_number)
            time_left = 0.0
            advance = False
            frame_number = self.frame_number + frame_quantum
            self.frame_number = frame_number
            if frame_quantum > 0.0:
                high = node.high_frame
                if high < _floor(frame_number):
                    overrun = frame_number - high - 1.0
                    if overrun < 0.0:
                        overrun = 0.0
                    time_left = overrun / framerate if fabs(framerate) > F_EPSILON else 0.0
                    advance = True
                    frame_number = self.frame_number = float(high)
                end = _floor(frame_number)
                if last < end:
                    anim = node.animation
                    pos_frames = anim.pos_frames
                    part_frames = anim.part_frames
                    step = 1.0 / framerate if fabs(framerate) > F_EPSILON else 0.0
                    while last < end:
                        if frame is not None:
                            if pos_frames is not None:
                                combine_anim_frame(frame, pos_frames[last])
                            if step:
                                self.apply_physics(frame, step, quantum)
                        if self.hook_obj is not None:
                            self.execute_hooks(part_frames[last], 1)
                        last += 1
            elif frame_quantum >= 0.0:
                if frame is not None and fabs(quantum) > F_EPSILON:
                    self.apply_physics(frame, quantum, quantum)
                return
            else:
                low = node.low_frame
                if low > _floor(frame_number):
                    overrun = frame_number - low
                    if overrun > 0.0:
                        overrun = 0.0
                    time_left = overrun / framerate if fabs(framerate) > F_EPSILON else 0.0
                    advance = True
                    frame_number = self.frame_number = float(low)
                end = _floor(frame_number)
                if last > end:
                    anim = node.animation
                    pos_frames = anim.pos_frames
                    part_frames = anim.part_frames
                    step = 1.0 / framerate if fabs(framerate) > F_EPSILON else 0.0
                    while last > end:
                        if frame is not None:
                            if pos_frames is not None:
                                frame.subtract1(frame, pos_frames[last])
                            if step:
                                self.apply_physics(frame, step, quantum)
                        if self.hook_obj is not None:
                            self.execute_hooks(part_frames[last], -1)
                        last -= 1
            if not advance:
                return
            if self.hook_obj is not None and self.anim_list[0] is not self.first_cyclic:
                self.hook_obj.add_anim_hook(ANIM_DONE_HOOK)
            self.advance_to_next_animation(quantum, frame)
            quantum = time_left

    def advance_to_next_animation(self, quantum: float, frame: Frame | None) -> None:
        """Leave ``curr_anim`` at its end and enter the next animation (previous, for a negative quantum).

        Forwards (``quantum >= 0``): a reverse-playing animation being left
        still subtracts its current (low) frame and applies one frame of
        physics; play moves to the next node (after the tail, back to
        ``first_cyclic``) at its starting frame, and a forward-playing node
        entered composes its starting frame and applies one frame of physics.
        A negative quantum mirrors this: previous node (before the head, the
        tail), at its ending frame.

        Retail: CSequence::advance_to_next_animation @ 0x005252B0 (acclient.c:340472)
        """
        node = self.curr_anim
        if quantum < 0.0:
            if frame is not None and node.framerate >= 0.0:
                self._leave_or_enter(node, frame, quantum, entering=False)
            node = self._prev(node) or self.anim_list[-1]
            self.curr_anim = node
            self.frame_number = node.get_ending_frame()
            if frame is not None and node.framerate < 0.0:
                self._leave_or_enter(node, frame, quantum, entering=True)
        else:
            if frame is not None and node.framerate < 0.0:
                self._leave_or_enter(node, frame, quantum, entering=False)
            node = self._next(node) or self.first_cyclic
            self.curr_anim = node
            self.frame_number = node.get_starting_frame()
            if frame is not None and node.framerate > 0.0:
                self._leave_or_enter(node, frame, quantum, entering=True)

    def _leave_or_enter(
        self, node: AnimSequenceNode, frame: Frame, quantum: float, *, entering: bool
    ) -> None:
        """One frame of ``node`` at ``floor(frame_number)``: compose (entering) or subtract its position
        frame, then apply ``1/framerate`` s of physics with the sign of ``quantum``.

        Retail: AnimSequenceNode::get_pos_frame @ 0x005247B0 (acclient.c:339640)
        """
        if node.animation.pos_frames is not None:
            pos = node.get_pos_frame(_floor(self.frame_number))
            if entering:
                combine_anim_frame(frame, pos)
            else:
                frame.subtract1(frame, pos)
        framerate = node.framerate
        if math.fabs(framerate) > F_EPSILON:
            self.apply_physics(frame, 1.0 / framerate, quantum)
