"""``CSequence``: the animation sequencer that emits root motion into the offset frame.

This issue ports the sequencer's physics channel: its baked ``velocity`` and
``omega`` and how ``apply_physics`` writes them into a body's offset frame.
The animation list (frame-quantized playback, links, hooks) arrives with the
motion issue; until then the list is always empty, which is the branch of
``CSequence::update`` that applies the velocity for the whole quantum.
"""

from __future__ import annotations

import math

from acphys.math.frame import Frame
from acphys.math.vector import Vector3


class Sequence:
    """Retail ``CSequence`` (acclient.h): velocity and omega in the body's local space."""

    __slots__ = ("omega", "velocity")

    def __init__(self) -> None:
        self.velocity = Vector3()
        self.omega = Vector3()

    def set_velocity(self, velocity: Vector3) -> None:
        """Retail: CSequence::set_velocity @ 0x00524880 (acclient.c:339701)"""
        self.velocity = velocity.copy()

    def set_omega(self, omega: Vector3) -> None:
        """Retail: CSequence::set_omega @ 0x005248A0 (acclient.c:339707)"""
        self.omega = omega.copy()

    def apply_physics(self, frame: Frame, quantum: float, sign: float) -> None:
        """Move ``frame`` by ``|quantum| · velocity`` and rotate it locally by ``|quantum| · omega``.

        The step takes the sign of ``sign`` (negative for reverse playback).
        The translation is added to the origin as is (the offset frame is the
        body's local space); the rotation goes through ``Frame::rotate``.

        Retail: CSequence::apply_physics @ 0x00524AB0 (acclient.c:339859)
        """
        scale = math.fabs(quantum)
        if sign < 0.0:
            scale = -scale
        frame.origin.x += scale * self.velocity.x
        frame.origin.y += scale * self.velocity.y
        frame.origin.z += scale * self.velocity.z
        frame.rotate(self.omega * scale)

    def update(self, quantum: float, offset_frame: Frame) -> None:
        """Advance the sequence by ``quantum``, writing root motion into ``offset_frame``.

        With no animation queued (always, until the motion issue) this is
        ``apply_physics(frame, quantum, quantum)``.

        Retail: CSequence::update @ 0x00525B80 (acclient.c:340950)
        """
        self.apply_physics(offset_frame, quantum, quantum)
