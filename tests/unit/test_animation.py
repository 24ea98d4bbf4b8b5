"""AnimData, AnimSequenceNode and the hook kinds against canim/CSeqPrim.c and canim/CAnimHook.c."""

from __future__ import annotations

import pytest

from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.motion.anim_hooks import ANIM_DONE_HOOK, AnimHookDir, AnimHookType, SetOmegaHook, SoundHook
from acphys.motion.animation import F_EPSILON, Animation, AnimData, AnimFrame, AnimSequenceNode


def anim(frames: int, moves: bool = False) -> Animation:
    pos = [Frame(Vector3(0.0, float(i), 0.0)) for i in range(frames)] if moves else None
    return Animation([AnimFrame([Frame()]) for _ in range(frames)], pos)


class TestRangeFitting:
    """AnimSequenceNode::set_animation_id (acclient.c:341084)."""

    def test_defaults_cover_the_whole_animation(self):
        node = AnimSequenceNode(AnimData(anim(5)))
        # high_frame -1 -> num_frames - 1 (acclient.c:341112-341113);
        # default framerate 30 (acclient.c:341046).
        assert (node.low_frame, node.high_frame, node.framerate) == (0, 4, 30.0)

    def test_frames_past_the_end_come_back_to_the_last(self):
        node = AnimSequenceNode(AnimData(anim(5), low_frame=7, high_frame=9))
        # low >= num -> num - 1 (acclient.c:341115-341116), high likewise (acclient.c:341118-341119).
        assert (node.low_frame, node.high_frame) == (4, 4)

    def test_a_negative_low_frame_is_past_the_end_in_the_unsigned_compare(self):
        node = AnimSequenceNode(AnimData(anim(5), low_frame=-1, high_frame=2))
        # low_frame (int) >= num_frames (unsigned int): -1 becomes 0xFFFFFFFF, so low -> 4, and
        # then low > high raises high to 4 (acclient.c:341114-341122).
        assert (node.low_frame, node.high_frame) == (4, 4)

    def test_low_above_high_raises_high(self):
        node = AnimSequenceNode(AnimData(anim(5), low_frame=3, high_frame=1))
        assert (node.low_frame, node.high_frame) == (3, 3)  # acclient.c:341121-341122

    def test_no_animation_means_no_anim(self):
        node = AnimSequenceNode(AnimData(None, 0, -1))
        # anim_id 0: anim = 0 (acclient.c:341107), has_anim false (acclient.c:341011).
        assert not node.has_anim() and node.high_frame == -1


class TestNodeFrames:
    def test_starting_and_ending_frames(self):
        forward = AnimSequenceNode(AnimData(anim(5), 1, 3, 30.0))
        backward = AnimSequenceNode(AnimData(anim(5), 1, 3, -30.0))
        # acclient.c:341020-341023 and 341032-341035: (high + 1) - F_EPSILON on the playing side.
        assert forward.get_starting_frame() == 1.0
        assert forward.get_ending_frame() == 4.0 - F_EPSILON
        assert backward.get_starting_frame() == 4.0 - F_EPSILON
        assert backward.get_ending_frame() == 1.0

    def test_frame_lookups_are_bounded_by_the_animation(self):
        animation = anim(3, moves=True)
        node = AnimSequenceNode(AnimData(animation, 1, 1))
        # Bounded by num_frames, not by the node's range (acclient.c:340988, 341002); out of range
        # is null (ACE returns an identity AFrame instead).
        assert node.get_pos_frame(0) is animation.pos_frames[0]
        assert node.get_part_frame(2) is animation.part_frames[2]
        assert node.get_pos_frame(3) is None and node.get_part_frame(-1) is None
        assert AnimSequenceNode(AnimData(anim(3))).get_pos_frame(0) is None

    def test_speed_times_anim_data(self):
        data = AnimData(anim(4), 1, 2, 30.0)
        scaled = 0.5 * data
        # operator*(float, AnimData) (acclient.c:341058-341064): the same range at framerate * speed.
        assert (scaled.animation, scaled.low_frame, scaled.high_frame, scaled.framerate) == (
            data.animation,
            1,
            2,
            15.0,
        )
        assert data.framerate == 30.0


class TestValidation:
    def test_bad_animations_are_refused(self):
        with pytest.raises(ValueError, match="no frames"):
            Animation([])
        with pytest.raises(ValueError, match="position frames"):
            Animation([AnimFrame([Frame()])], [Frame(), Frame()])
        with pytest.raises(ValueError, match="number of parts"):
            Animation([AnimFrame([Frame()]), AnimFrame([Frame(), Frame()])])

    def test_bad_anim_data_is_refused(self):
        with pytest.raises(ValueError, match="framerate"):
            AnimData(anim(2), framerate=float("nan"))
        with pytest.raises(ValueError, match="integers"):
            AnimData(anim(2), low_frame=1.5)
        with pytest.raises(ValueError, match="Animation"):
            AnimData("walk")

    def test_bad_hook_direction_is_refused(self):
        with pytest.raises(ValueError, match="direction"):
            SoundHook(direction=2)


class TestHookKinds:
    def test_types_and_directions_are_retail_values(self):
        # acclient.h:7278 (hook kinds) and CAnimHook::AnimHookDir.
        assert SetOmegaHook(Vector3()).hook_type == AnimHookType.SET_OMEGA == 0x16
        assert ANIM_DONE_HOOK.hook_type == AnimHookType.ANIM_DONE == 4
        # The static anim_done_hook carries direction -2 (acclient_data.h:6271).
        assert ANIM_DONE_HOOK.direction == AnimHookDir.UNKNOWN == -2
