"""Animations as the physics sees them: frames, hooks, playback ranges and sequence nodes.

Retail loads ``CAnimation`` records from the portal DAT; acphys builds them in
memory (scenario files, tests, or a DAT reader elsewhere), so an
:class:`AnimData` holds the :class:`Animation` itself where retail holds its
DAT id. Everything else keeps retail's shape and behaviour.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.constants import EPSILON
from acphys.math.frame import Frame
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.motion.anim_hooks import AnimHook

#: ``F_EPSILON`` (acclient_data.h:598) is a float32 0.0002; the frame bias of
#: get_starting_frame / get_ending_frame subtracts exactly this value.
F_EPSILON: float = f32(EPSILON)

#: Retail's AnimData / AnimSequenceNode default framerate (the literal 1106247680 = 0x41F00000).
DEFAULT_FRAMERATE: float = 30.0


class AnimFrame:
    """Retail ``AnimFrame`` (acclient.h:31072): one frame's per-part frames and the hooks fired on it.

    ``hooks`` keeps the DAT order (``CAnimHook::add_to_list`` appends to the
    end of the chain, acclient.c:342124).
    """

    __slots__ = ("frames", "hooks")

    def __init__(self, frames: list[Frame] | None = None, hooks: list[AnimHook] | None = None) -> None:
        self.frames: list[Frame] = list(frames) if frames is not None else []
        self.hooks: list[AnimHook] = list(hooks) if hooks is not None else []

    @property
    def num_parts(self) -> int:
        return len(self.frames)

    def __repr__(self) -> str:
        return f"AnimFrame(parts={len(self.frames)}, hooks={self.hooks!r})"


class Animation:
    """Retail ``CAnimation`` (acclient.h): part frames for every frame, optional root-motion frames.

    ``pos_frames`` is ``None`` when the animation has no position frames
    (retail leaves the array null unless bit 0 of the DAT bitfield is set).
    Position frames are applied in the body's local space, one per frame
    boundary crossed.
    """

    __slots__ = ("name", "part_frames", "pos_frames")

    def __init__(
        self,
        part_frames: list[AnimFrame],
        pos_frames: list[Frame] | None = None,
        name: str = "",
    ) -> None:
        """Retail: CAnimation::CAnimation @ 0x0051F690 (acclient.c:333676)"""
        part_frames = list(part_frames)
        if not part_frames:
            raise ValueError(f"animation {name!r} has no frames")
        for index, anim_frame in enumerate(part_frames):
            if not isinstance(anim_frame, AnimFrame):
                raise ValueError(f"animation {name!r}: frame {index} is not an AnimFrame")
        if pos_frames is not None:
            pos_frames = list(pos_frames)
            if len(pos_frames) != len(part_frames):
                raise ValueError(
                    f"animation {name!r}: {len(pos_frames)} position frames for {len(part_frames)} "
                    "frames (retail keeps one of each per frame)"
                )
            for index, frame in enumerate(pos_frames):
                if not isinstance(frame, Frame):
                    raise ValueError(f"animation {name!r}: position frame {index} is not a Frame")
        counts = {len(f.frames) for f in part_frames}
        if len(counts) > 1:
            raise ValueError(f"animation {name!r}: frames disagree on the number of parts {sorted(counts)}")
        self.name = name
        self.part_frames = part_frames
        self.pos_frames = pos_frames

    @property
    def num_frames(self) -> int:
        return len(self.part_frames)

    @property
    def num_parts(self) -> int:
        return len(self.part_frames[0].frames)

    def __repr__(self) -> str:
        moves = "with" if self.pos_frames is not None else "no"
        return f"Animation({self.name!r}, frames={self.num_frames}, {moves} pos frames)"


class AnimData:
    """Retail ``AnimData`` (acclient.h:52536): an animation reference, its frame range and its rate.

    ``high_frame = -1`` means "to the last frame"; the range is resolved
    when a :class:`AnimSequenceNode` is made from it. ``framerate`` is a
    ``float`` field: it is stored as a float32.
    """

    __slots__ = ("animation", "framerate", "high_frame", "low_frame")

    def __init__(
        self,
        animation: Animation | None,
        low_frame: int = 0,
        high_frame: int = -1,
        framerate: float = DEFAULT_FRAMERATE,
    ) -> None:
        """Retail: AnimData::AnimData @ 0x00525CE0 (acclient.c:341039)"""
        if animation is not None and not isinstance(animation, Animation):
            kind = type(animation).__name__
            raise ValueError(f"AnimData animation must be an Animation or None, not {kind}")
        if not isinstance(low_frame, int) or not isinstance(high_frame, int):
            raise ValueError(f"AnimData frame range must be integers, got {low_frame!r}, {high_frame!r}")
        if not math.isfinite(framerate):
            raise ValueError(f"AnimData framerate must be finite, got {framerate!r}")
        self.animation = animation
        self.low_frame = low_frame
        self.high_frame = high_frame
        self.framerate = f32(framerate)

    def copy(self) -> AnimData:
        return AnimData(self.animation, self.low_frame, self.high_frame, self.framerate)

    def __rmul__(self, speed: float) -> AnimData:
        """``speed * anim_data``: the same animation and range at ``speed`` times the framerate.

        ``speed`` is a ``float`` parameter; the product (exact in double) is stored into the
        result's ``float`` framerate (acclient.c:341061-341064), so a speed of 0.64 gives
        ``f32(30 * f32(0.64))`` = 19.19999886, not 19.2.

        Retail: operator* @ 0x00525D00 (acclient.c:341050)
        """
        return AnimData(self.animation, self.low_frame, self.high_frame, self.framerate * f32(speed))

    def __repr__(self) -> str:
        return f"AnimData({self.animation!r}, {self.low_frame}, {self.high_frame}, {self.framerate})"


class AnimSequenceNode:
    """Retail ``AnimSequenceNode`` (acclient.h:31063): one queued animation of a sequence.

    The node owns its own copy of the range and framerate (the sequence's
    ``multiply_cyclic_animation_framerate`` changes them in place).
    """

    __slots__ = ("animation", "framerate", "high_frame", "low_frame")

    def __init__(self, data: AnimData) -> None:
        """Retail: AnimSequenceNode::AnimSequenceNode @ 0x00525F90 (acclient.c:341288)"""
        self.framerate = data.framerate
        self.low_frame = data.low_frame
        self.high_frame = data.high_frame
        self.animation: Animation | None = None
        self.set_animation(data.animation)

    def __repr__(self) -> str:
        return (
            f"AnimSequenceNode({self.animation!r}, low={self.low_frame}, high={self.high_frame}, "
            f"framerate={self.framerate})"
        )

    def set_animation(self, animation: Animation | None) -> None:
        """Attach ``animation`` and fit the frame range to it.

        ``high_frame < 0`` becomes the last frame; a low or high frame past
        the end is pulled back to the last frame; ``low > high`` raises high
        to low. Retail compares the signed frames against the *unsigned*
        frame count, so a negative ``low_frame`` also counts as past the end
        (it becomes the last frame).

        Retail: AnimSequenceNode::set_animation_id @ 0x00525D60 (acclient.c:341084)
        """
        self.animation = animation
        if animation is None:
            return
        count = animation.num_frames
        if self.high_frame < 0:
            self.high_frame = count - 1
        if self.low_frame < 0 or self.low_frame >= count:
            self.low_frame = count - 1
        if self.high_frame >= count:
            self.high_frame = count - 1
        if self.low_frame > self.high_frame:
            self.high_frame = self.low_frame

    def has_anim(self) -> bool:
        """Retail: AnimSequenceNode::has_anim @ 0x00525C70 (acclient.c:341009)"""
        return self.animation is not None

    def multiply_framerate(self, multiplier: float) -> None:
        """Scale the framerate; a negative multiplier also swaps the low and high frames.

        ``multiplier`` is a ``float`` parameter and ``framerate`` a ``float`` field.

        Retail: AnimSequenceNode::multiply_framerate @ 0x00525BE0 (acclient.c:340967)
        """
        multiplier = f32(multiplier)
        if multiplier < 0.0:
            self.low_frame, self.high_frame = self.high_frame, self.low_frame
        self.framerate = f32(multiplier * self.framerate)

    def get_starting_frame(self) -> float:
        """``low_frame`` forwards; ``high_frame + 1 - F_EPSILON`` backwards (just inside the last frame).

        Retail: AnimSequenceNode::get_starting_frame @ 0x00525C80 (acclient.c:341015)
        """
        if self.framerate < 0.0:
            return float(self.high_frame + 1) - F_EPSILON
        return float(self.low_frame)

    def get_ending_frame(self) -> float:
        """``high_frame + 1 - F_EPSILON`` forwards; ``low_frame`` backwards.

        Retail: AnimSequenceNode::get_ending_frame @ 0x00525CB0 (acclient.c:341027)
        """
        if self.framerate < 0.0:
            return float(self.low_frame)
        return float(self.high_frame + 1) - F_EPSILON

    def get_pos_frame(self, frame_number: int) -> Frame | None:
        """The root-motion frame of ``frame_number``, or None out of range or without position frames.

        Retail: AnimSequenceNode::get_pos_frame @ 0x00525C10 (acclient.c:340981)
        """
        anim = self.animation
        if anim is None or anim.pos_frames is None or not 0 <= frame_number < len(anim.part_frames):
            return None
        return anim.pos_frames[frame_number]

    def get_part_frame(self, frame_number: int) -> AnimFrame | None:
        """The :class:`AnimFrame` of ``frame_number``, or None out of range.

        Retail: AnimSequenceNode::get_part_frame @ 0x00525C40 (acclient.c:340995)
        """
        anim = self.animation
        if anim is None or not 0 <= frame_number < len(anim.part_frames):
            return None
        return anim.part_frames[frame_number]
