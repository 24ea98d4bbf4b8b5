"""CSequence playback against the retail decompilation (canim/CSequence.c, canim/CSeqPrim.c).

Every expected value is worked out by hand from the retail code at the cited
``acclient.c`` line. Position frames are small integer translations (exact in
floating point) so the sums name exactly which frames were composed.
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState as PS
from acphys.math.frame import Frame
from acphys.math.vector import Vector3
from acphys.motion.anim_hooks import (
    ANIM_DONE_HOOK,
    AnimHookDir,
    EtherealHook,
    NoDrawHook,
    NOOPHook,
    ScaleHook,
    SetOmegaHook,
    SoundHook,
)
from acphys.motion.animation import F_EPSILON, Animation, AnimData, AnimFrame
from acphys.motion.sequence import Sequence
from acphys.precision import f32
from support import place


def anim(frames: int, ys: list[float] | None = None, hooks: dict[int, list] | None = None) -> Animation:
    """An animation of ``frames`` frames; position frame i moves ``ys[i]`` along local +y."""
    hooks = hooks or {}
    part_frames = [AnimFrame([Frame()], hooks.get(i, [])) for i in range(frames)]
    pos = None if ys is None else [Frame(Vector3(0.0, y, 0.0)) for y in ys]
    return Animation(part_frames, pos)


def sequence_of(*datas: AnimData, velocity: Vector3 | None = None, omega: Vector3 | None = None) -> Sequence:
    seq = Sequence()
    for data in datas:
        seq.append_animation(data)
    if velocity is not None:
        seq.set_velocity(velocity)
    if omega is not None:
        seq.set_omega(omega)
    return seq


class TestForwardVelocity:
    """Velocity is applied once per frame boundary with dt = 1/framerate (acclient.c:340723)."""

    def test_first_update_crosses_one_boundary(self):
        seq = sequence_of(AnimData(anim(30), framerate=30.0), velocity=Vector3(0.0, 4.0, 0.0))
        offset = Frame()
        seq.update(0.05, offset)
        # frame_number 0 + 30 * 0.05 = 1.5 (acclient.c:340690-340695): boundary 0 crossed once.
        assert seq.frame_number == 1.5
        # apply_physics(retval, 1/30, quantum) once (acclient.c:340723): |1/30| * 4, spilled into
        # the float local w.y (acclient.c:339877), then added to the float origin (339880).
        assert offset.origin.y == f32(f32((1.0 / 30.0) * 4.0) + 0.0)
        assert offset.origin.x == 0.0 and offset.origin.z == 0.0

    def test_one_second_of_updates_moves_exactly_four_metres(self):
        seq = sequence_of(AnimData(anim(30), framerate=30.0), velocity=Vector3(0.0, 4.0, 0.0))
        offset = Frame()
        for _ in range(20):
            seq.update(0.05, offset)
        # Updates 1-19 cross frames 0..27 (28 boundaries). Update 20 reaches 30.0 > high 29
        # (acclient.c:340700): clamped to 29, frame 28 crosses (340713), then the wrap enters
        # frame 0 of the cycle with one more frame of physics (advance_to_next_animation,
        # acclient.c:340568-340582): 30 applications of 4/30 m, each spilled to float w.y and
        # added to the float origin (acclient.c:339877-339880): four metres to float32 rounding.
        expected = 0.0
        for _ in range(30):
            expected = f32(f32((1.0 / 30.0) * 4.0) + expected)
        assert offset.origin.y == expected
        assert offset.origin.y == pytest.approx(4.0, abs=2e-6)
        # The leftover 30 - 29 - 1 = 0 frames give time_left 0 (acclient.c:340702-340708): a
        # zero quantum applies nothing (acclient.c:340778) and play sits at frame 0.
        assert seq.frame_number == 0.0
        assert seq.curr_anim is seq.first_cyclic

    def test_no_boundary_crossed_moves_nothing(self):
        seq = sequence_of(AnimData(anim(30), framerate=30.0), velocity=Vector3(0.0, 4.0, 0.0))
        offset = Frame()
        seq.update(0.02, offset)
        # 0 -> 0.6: the loop at acclient.c:340713 never runs and update_internal returns at 340762.
        assert seq.frame_number == pytest.approx(0.6)
        assert offset.origin.y == 0.0

    def test_omega_rotates_per_boundary(self):
        seq = sequence_of(AnimData(anim(10), framerate=10.0), omega=Vector3(0.0, 0.0, 1.0))
        offset = Frame()
        seq.update(0.05, offset)
        # 0 -> 0.5 crosses nothing: no rotation (acclient.c:340762).
        assert offset.rotation == (1.0, 0.0, 0.0, 0.0)
        seq.update(0.2, offset)
        # 0.5 -> 2.5 crosses frames 0 and 1: two Frame::rotate of omega * 1/10 (acclient.c:339889),
        # w.z the float store f32(0.1 * 1.0) (acclient.c:339885-339886); 0.2 rad about z in all:
        # q = (cos 0.1, 0, 0, sin 0.1) to float32 precision.
        expected = Frame()
        for _ in range(2):
            expected.rotate(Vector3(0.0, 0.0, f32(0.1 * 1.0)))
        assert offset.rotation == expected.rotation
        assert offset.qw == pytest.approx(math.cos(0.1), abs=1e-7)
        assert offset.qz == pytest.approx(math.sin(0.1), abs=1e-7)
        assert offset.qx == 0.0 and offset.qy == 0.0


class TestPositionFrames:
    """Frame::combine(retval, retval, get_pos_frame(n)) per boundary (acclient.c:340719-340720)."""

    def test_each_crossed_frame_is_composed_once(self):
        seq = sequence_of(AnimData(anim(4, [1.0, 2.0, 4.0, 8.0]), framerate=10.0))
        offset = Frame()
        seq.update(0.25, offset)
        # 0 -> 2.5: frames 0 and 1 composed.
        assert offset.origin.y == 3.0
        seq.update(0.1, offset)
        # 2.5 -> 3.5: frame 2 composed.
        assert offset.origin.y == 7.0

    def test_composition_is_in_the_local_space_of_the_running_offset(self):
        turn = Frame(Vector3(0.0, 1.0, 0.0), math.cos(math.pi / 4), 0.0, 0.0, math.sin(math.pi / 4))
        step = Frame(Vector3(0.0, 1.0, 0.0))
        animation = Animation([AnimFrame([Frame()]) for _ in range(3)], [turn, step, Frame()])
        seq = sequence_of(AnimData(animation, framerate=10.0))
        offset = Frame()
        seq.update(0.25, offset)
        # After frame 0 the offset is at (0, 1, 0) turned 90 deg about z (local +y -> global -x);
        # frame 1's (0, 1, 0) then lands at (-1, 1, 0) (Frame::combine, acclient.c:340419). The
        # turn's quaternion is float32 (cos and sin of pi/4 rounded), so its matrix takes local +y
        # to global -x only to float32 precision: the tolerance is float32's, not the geometry's.
        assert offset.origin.x == pytest.approx(-1.0, abs=1e-6)
        assert offset.origin.y == pytest.approx(1.0, abs=1e-6)

    def test_a_wrap_composes_the_first_frame_twice_and_never_the_last(self):
        seq = sequence_of(AnimData(anim(4, [1.0, 2.0, 4.0, 8.0]), framerate=10.0))
        offset = Frame()
        seq.update(0.4, offset)
        # 0 -> 4.0 > high 3: clamped to 3 (acclient.c:340710), frames 0, 1, 2 composed in the loop,
        # then the wrap composes frame 0 on entry (acclient.c:340568-340575). Frame 3 never is.
        assert offset.origin.y == 1.0 + 2.0 + 4.0 + 1.0
        seq.update(0.1, offset)
        # 0 -> 1: frame 0 again.
        assert offset.origin.y == 9.0


class TestReverse:
    """Negative framerates: the start bias, subtract1 and the reverse wrap."""

    def test_starting_frame_is_just_inside_the_last_frame(self):
        seq = sequence_of(AnimData(anim(30), framerate=-30.0))
        # get_starting_frame: (high + 1) - F_EPSILON (acclient.c:341021), F_EPSILON a float32 0.0002
        # (F_EPSILON_37, acclient_data.h:598).
        assert F_EPSILON == 0.00019999999494757503
        assert seq.frame_number == 30.0 - F_EPSILON

    def test_the_bias_keeps_a_tiny_step_inside_the_last_frame(self):
        seq = sequence_of(AnimData(anim(4, [1.0, 2.0, 4.0, 8.0]), framerate=-10.0))
        offset = Frame()
        seq.update(0.00001, offset)
        # 3.9998 - 0.0001 = 3.9997: floor 3 is not below floor 3 (acclient.c:340746), nothing moves.
        # Without the bias (start 4.0) this step would have crossed the non-existent frame 4.
        assert offset.origin.y == 0.0
        assert seq.frame_number == pytest.approx(4.0 - F_EPSILON - 0.0001)

    def test_reverse_play_subtracts_position_frames(self):
        seq = sequence_of(AnimData(anim(4, [1.0, 2.0, 4.0, 8.0]), framerate=-10.0))
        offset = Frame()
        seq.update(0.25, offset)
        # 3.9998 - 2.5 = 1.4998: frames 3 and 2 subtracted (Frame::subtract1, acclient.c:340753).
        assert offset.origin.y == -(8.0 + 4.0)
        assert seq.frame_number == pytest.approx(1.4998)

    def test_reverse_velocity_takes_the_sign_of_the_quantum(self):
        seq = sequence_of(AnimData(anim(4), framerate=-10.0), velocity=Vector3(0.0, 1.0, 0.0))
        offset = Frame()
        seq.update(0.25, offset)
        # Two boundaries, each apply_physics(1/-10, quantum 0.25) (acclient.c:340756): |1/-10|
        # with the sign of the *quantum* (acclient.c:339872-339874), so +0.1 each, spilled to float
        # w.y (acclient.c:339877) and added to the float origin (339880).
        assert offset.origin.y == f32(f32(0.1 * 1.0) + f32(f32(0.1 * 1.0) + 0.0))

    def test_reverse_wrap_subtracts_the_low_frame_on_the_way_out(self, world):
        body = place(world)
        hooks = {i: [NOOPHook()] for i in range(4)}
        seq = sequence_of(AnimData(anim(4, [1.0, 2.0, 4.0, 8.0], hooks), framerate=-10.0))
        seq.set_object(body)
        offset = Frame()
        seq.update(0.4, offset)
        # 3.9998 - 4 = -0.0002 < low 0 (acclient.c:340733): clamped to 0, frames 3, 2, 1 in the
        # loop; leaving the reverse node subtracts frame 0 (acclient.c:340549-340560). The leftover
        # -0.0002 / -10 s (acclient.c:340735-340743) plays from the new start 3.9998 to 3.9996.
        assert offset.origin.y == -15.0
        assert seq.frame_number == pytest.approx(4.0 - 2 * F_EPSILON)
        # Hooks fire only in the loop: frames 3, 2, 1; the low frame's never do in reverse play.
        assert body.anim_hooks == [hooks[3][0], hooks[2][0], hooks[1][0]]

    def test_negative_quantum_rewinds_a_forward_cycle_to_its_ending_frame(self):
        seq = sequence_of(AnimData(anim(4, [1.0, 2.0, 4.0, 8.0]), framerate=10.0))
        offset = Frame()
        seq.update(-0.15, offset)
        # framerate * quantum = -1.5 < 0: reverse branch with a forward node. 0 - 1.5 < low 0:
        # time_left = -1.5 / 10; the quantum < 0 advance (acclient.c:340498-340529) subtracts frame 0,
        # moves to the previous node (none: the tail, itself) at get_ending_frame = 4 - F_EPSILON
        # (acclient.c:341035); -1.5 more frames reach 2.4998, subtracting frame 3.
        assert offset.origin.y == -(1.0 + 8.0)
        assert seq.frame_number == pytest.approx(4.0 - F_EPSILON - 1.5)


class TestHooks:
    """execute_hooks: ``!direction_ || dir == direction_`` (acclient.c:339695)."""

    def test_direction_filter_forward_and_backward(self, world):
        body = place(world)
        fwd = NOOPHook(direction=AnimHookDir.FORWARD)
        both = NOOPHook(direction=AnimHookDir.BOTH)
        back = NOOPHook(direction=AnimHookDir.BACKWARD)
        unknown = NOOPHook(direction=AnimHookDir.UNKNOWN)
        hooks = {1: [fwd, both, back, unknown], 2: [fwd, both, back, unknown]}
        forward = sequence_of(AnimData(anim(4, hooks=hooks), framerate=10.0))
        forward.set_object(body)
        forward.update(0.25, Frame())
        # Forward 0 -> 2.5 crosses frames 0 and 1: on frame 1 FORWARD and BOTH fire, in the
        # frame's order (execute_hooks(frame, 1), acclient.c:340726); UNKNOWN (-2) never matches.
        assert body.anim_hooks == [fwd, both]
        body.anim_hooks.clear()
        backward = sequence_of(AnimData(anim(4, hooks=hooks), framerate=-10.0))
        backward.set_object(body)
        backward.update(0.25, Frame())
        # Backward 3.9998 -> 1.4998 crosses frames 3 and 2: on frame 2 BOTH and BACKWARD fire
        # (execute_hooks(frame, -1), acclient.c:340759).
        assert body.anim_hooks == [both, back]

    def test_no_body_no_hooks(self):
        hook = NOOPHook()
        seq = sequence_of(AnimData(anim(4, hooks={0: [hook]}), framerate=10.0))
        seq.update(0.25, Frame())  # hook_obj is None: execute_hooks does nothing (acclient.c:339690)
        assert seq.frame_number == 2.5

    def test_last_frame_hooks_never_fire_forward(self, world):
        body = place(world)
        first, last = NOOPHook(), NOOPHook()
        seq = sequence_of(AnimData(anim(4, hooks={0: [first], 3: [last]}), framerate=10.0))
        seq.set_object(body)
        for _ in range(8):
            seq.update(0.1, Frame())
        # Forward play clamps to high_frame (acclient.c:340710) and the loop stops below it, so
        # frame 3's hooks never fire; the wrap's entry step fires no hooks either. Two cycles:
        # frame 0 crossed twice.
        assert body.anim_hooks == [first, first]

    def test_hooks_act_on_a_real_body(self, world):
        body = place(world)
        spin = SetOmegaHook(Vector3(0.0, 0.0, 2.0))
        hooks = [spin, EtherealHook(True), ScaleHook(2.0, 0.0), NoDrawHook(True), SoundHook(0x0A000001)]
        seq = sequence_of(AnimData(anim(4, hooks={0: hooks}), framerate=10.0))
        seq.set_object(body)
        seq.update(0.1, Frame())
        body.process_hooks()
        # SetOmegaHook::Execute -> set_omega (acclient.c:342550); EtherealHook -> set_ethereal
        # (342314); ScaleHook -> SetScale(end, time) with time < EPSILON: immediate (342476);
        # NoDrawHook -> set_nodraw (342320); SoundHook plays a sound (recorded) (342190).
        # ACE executes only AnimDone (ACE AnimHook.Execute); retail runs them all.
        assert body.omega.exactly_equals(Vector3(0.0, 0.0, 2.0))
        assert body.omega is not spin.axis
        assert body.state & PS.ETHEREAL
        assert body.scale == 2.0
        assert body.state & PS.NODRAW
        assert "hook:SoundHook" in body.step_events
        assert body.anim_hooks == []


class TestLinkThenCycle:
    """A link animation followed by the cycle: overrun, AnimDone, apricot."""

    def test_overrun_carries_leftover_time_into_the_next_node(self, world):
        body = place(world)
        link = AnimData(anim(3, [1.0, 2.0, 4.0]), framerate=10.0)
        cycle = AnimData(anim(4, [8.0, 16.0, 32.0, 64.0]), framerate=30.0)
        seq = sequence_of(link, cycle)
        seq.set_object(body)
        cycle_node = seq.first_cyclic
        offset = Frame()
        seq.update(0.35, offset)
        # Link: 0 -> 3.5 > high 2: overrun 3.5 - 2 - 1 = 0.5 frames = 0.05 s (acclient.c:340700-340710);
        # frames 0, 1 composed. AnimDone queued: the head (the link) is not first_cyclic
        # (acclient.c:340767-340773). Entering the cycle composes its frame 0 (acclient.c:340575);
        # 0.05 s at 30 fps = 1.5 frames crosses cycle frame 0 again.
        assert offset.origin.y == 1.0 + 2.0 + 8.0 + 8.0
        assert seq.curr_anim is cycle_node
        assert seq.frame_number == 1.5
        assert body.anim_hooks == [ANIM_DONE_HOOK]
        # apricot drops the finished link (acclient.c:339910-339913).
        assert seq.anim_list == [cycle_node]

    def test_a_cycle_wrapping_on_its_own_queues_no_anim_done(self, world):
        body = place(world)
        seq = sequence_of(AnimData(anim(4), framerate=10.0))
        seq.set_object(body)
        seq.update(1.0, Frame())
        # Wrapped twice, but the head is first_cyclic (acclient.c:340772).
        assert body.anim_hooks == []

    def test_anim_done_per_finished_link_and_again_on_a_wrap_before_apricot(self, world):
        body = place(world)
        seq = sequence_of(*(AnimData(anim(2), framerate=10.0) for _ in range(3)))
        seq.set_object(body)
        seq.update(0.65, Frame())
        # 6.5 frames: link 1 ends (AnimDone), link 2 ends (AnimDone), the cycle wraps once. The
        # test at acclient.c:340767-340772 reads the *head*, still link 1 until apricot runs after
        # update_internal, so the cycle's wrap queues a third AnimDone.
        assert body.anim_hooks == [ANIM_DONE_HOOK] * 3
        assert len(seq.anim_list) == 1

    def test_apricot_stops_at_the_current_node(self):
        a, b, c = (AnimData(anim(2)) for _ in range(3))
        seq = sequence_of(a, b, c)
        _, second, cyclic = seq.anim_list
        seq.curr_anim = second
        seq.apricot()
        # Removes from the head until curr_anim (acclient.c:339910).
        assert seq.anim_list == [second, cyclic]
        seq.curr_anim = cyclic
        seq.apricot()
        assert seq.anim_list == [cyclic]

    def test_apricot_stops_at_first_cyclic(self):
        seq = sequence_of(AnimData(anim(2)), AnimData(anim(2)))
        cyclic = seq.anim_list[1]
        seq.curr_anim = None
        seq.apricot()
        # head != curr_anim, but the loop breaks at first_cyclic (acclient.c:339912-339913).
        assert seq.anim_list == [cyclic]


class TestListOperations:
    def test_append_starts_play_at_the_head_and_moves_first_cyclic_to_the_tail(self):
        seq = Sequence()
        seq.append_animation(AnimData(None))
        # No animation: the node is dropped (acclient.c:340612).
        assert not seq.has_anims()
        seq.append_animation(AnimData(anim(3), framerate=-10.0))
        head = seq.anim_list[0]
        assert seq.curr_anim is head and seq.first_cyclic is head
        assert seq.frame_number == 3.0 - F_EPSILON  # get_starting_frame (acclient.c:340631)
        seq.append_animation(AnimData(anim(2)))
        assert seq.first_cyclic is seq.anim_list[1]  # acclient.c:340624
        assert seq.curr_anim is head

    def test_remove_link_animations_removes_the_link_before_first_cyclic(self):
        seq = sequence_of(AnimData(anim(2)), AnimData(anim(2)), AnimData(anim(3), framerate=-10.0))
        l1, l2, cyclic = seq.anim_list
        seq.curr_anim, seq.frame_number = l2, 1.25
        seq.remove_link_animations(1)
        # GetPrev(first_cyclic) is l2, which is playing: play jumps to the cycle's start
        # (acclient.c:339975-339980).
        assert seq.anim_list == [l1, cyclic]
        assert seq.curr_anim is cyclic
        assert seq.frame_number == 3.0 - F_EPSILON
        seq.remove_link_animations(5)
        # Stops when first_cyclic has no predecessor (acclient.c:339973-339974).
        assert seq.anim_list == [cyclic]

    def test_remove_all_link_animations(self):
        seq = sequence_of(AnimData(anim(2)), AnimData(anim(2)), AnimData(anim(3), low_frame=1))
        cyclic = seq.anim_list[2]
        seq.frame_number = 0.5
        seq.remove_all_link_animations()
        # curr_anim was the first link: play moves to first_cyclic's start, low_frame 1
        # (acclient.c:340039-340044).
        assert seq.anim_list == [cyclic]
        assert seq.curr_anim is cyclic and seq.frame_number == 1.0

    def test_remove_cyclic_anims_falls_back_to_the_link_at_its_ending_frame(self):
        seq = sequence_of(AnimData(anim(3)), AnimData(anim(4)))
        link, cyclic = seq.anim_list
        seq.curr_anim = cyclic
        seq.remove_cyclic_anims()
        # The playing cycle goes; play moves to GetPrev at get_ending_frame = 3 - F_EPSILON
        # (acclient.c:340172-340178); first_cyclic becomes the tail (acclient.c:340222-340225).
        assert seq.anim_list == [link]
        assert seq.curr_anim is link and seq.first_cyclic is link
        assert seq.frame_number == 3.0 - F_EPSILON
        seq.remove_cyclic_anims()
        # Nothing before it: frame 0 and no animation (acclient.c:340180-340183).
        assert seq.anim_list == [] and seq.curr_anim is None and seq.first_cyclic is None
        assert seq.frame_number == 0.0

    def test_multiply_cyclic_framerate_touches_only_the_cycle(self):
        seq = sequence_of(AnimData(anim(3), framerate=10.0), AnimData(anim(4), framerate=30.0))
        link, cyclic = seq.anim_list
        seq.multiply_cyclic_animation_framerate(2.0)
        assert link.framerate == 10.0 and cyclic.framerate == 60.0  # acclient.c:339740
        seq.multiply_cyclic_animation_framerate(-0.5)
        # A negative multiplier also swaps low and high (acclient.c:340972-340977).
        assert cyclic.framerate == -30.0
        assert (cyclic.low_frame, cyclic.high_frame) == (3, 0)

    def test_clear(self):
        seq = sequence_of(AnimData(anim(3)), velocity=Vector3(1.0, 0.0, 0.0), omega=Vector3(0.0, 0.0, 1.0))
        seq.set_placement_frame(AnimFrame([Frame()]), 7)
        seq.clear()
        assert not seq.has_anims() and seq.curr_anim is None and seq.first_cyclic is None
        assert seq.velocity.exactly_equals(Vector3()) and seq.omega.exactly_equals(Vector3())
        assert seq.placement_frame is None and seq.placement_frame_id == 0

    def test_combine_and_subtract_physics(self):
        seq = Sequence()
        seq.combine_physics(Vector3(1.0, 2.0, 3.0), Vector3(0.0, 0.0, 1.0))
        seq.combine_physics(Vector3(1.0, 0.0, 0.0), Vector3(0.0, 0.0, 0.5))
        seq.subtract_physics(Vector3(0.0, 2.0, 0.0), Vector3(0.0, 0.0, 1.0))
        assert seq.velocity.exactly_equals(Vector3(2.0, 0.0, 3.0))  # acclient.c:339716-339732
        assert seq.omega.exactly_equals(Vector3(0.0, 0.0, 0.5))

    def test_current_frame_and_animframe(self):
        animation = anim(4)
        seq = sequence_of(AnimData(animation, framerate=10.0))
        seq.update(0.27, Frame())
        assert seq.get_curr_frame_number() == 2  # floor(2.7) (acclient.c:339776)
        assert seq.get_curr_animframe() is animation.part_frames[2]  # acclient.c:339757
        placement = AnimFrame([Frame()])
        empty = Sequence()
        empty.set_placement_frame(placement, 0x65)
        assert empty.get_curr_animframe() is placement  # acclient.c:339761


class TestWholeQuantum:
    """The true quantum is used only with no animation or a zero framerate."""

    def test_no_animations_applies_velocity_for_the_whole_quantum(self):
        seq = Sequence()
        seq.set_velocity(Vector3(0.0, 4.0, 0.0))
        offset = Frame()
        seq.update(0.05, offset)
        # CSequence::update with an empty list: apply_physics(retval, quantum, quantum) (acclient.c:340963),
        # the product spilled to float w.y (acclient.c:339877).
        assert offset.origin.y == f32(0.05 * 4.0)

    def test_zero_framerate_applies_velocity_for_the_whole_quantum(self):
        seq = sequence_of(AnimData(anim(4), framerate=0.0), velocity=Vector3(0.0, 4.0, 0.0))
        offset = Frame()
        seq.update(0.05, offset)
        # framerate * quantum == 0: the loop breaks to apply_physics(quantum) (acclient.c:340778-340779).
        assert offset.origin.y == f32(0.05 * 4.0)
        assert seq.frame_number == 0.0

    def test_no_offset_frame_still_plays_and_fires_hooks(self, world):
        body = place(world)
        hook = NOOPHook()
        seq = sequence_of(AnimData(anim(4, [1.0, 2.0, 4.0, 8.0], {0: [hook]}), framerate=10.0))
        seq.set_object(body)
        seq.update(0.15, None)
        # retval is null: no composition or physics, but hooks still run (acclient.c:340715, 340725-340726).
        assert seq.frame_number == 1.5
        assert body.anim_hooks == [hook]
