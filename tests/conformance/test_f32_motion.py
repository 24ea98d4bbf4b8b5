"""Float32 at rest in the motion code: framerates, speeds, the sequence's root motion, move-tos.

Each test works a retail function by hand: double arithmetic between stores, ``f32`` at each
store into a ``float`` (field, local, 4-byte spill, float parameter), citing the decompiled
lines. Inputs are chosen so that narrowing at a different place (or not at all) gives a
different answer, and each test checks that too, so it cannot pass by accident.
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState as PS
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion import commands as cmd
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.interp import MotionInterp
from acphys.motion.motion_table import MotionData, MotionState, MotionTable, cycle_key
from acphys.motion.move_to import cylinder_distance, heading_diff
from acphys.motion.movement import HoldKey, MovementParameters, MovementStruct, MovementType
from acphys.motion.sequence import Sequence, combine_anim_frame
from acphys.motion.weenie import Weenie, get_jump_height
from acphys.part_array import PartArray, combine_scaled
from acphys.precision import f32, is_f32
from acphys.scenario.motion_tables import builtin_motion_table
from acphys.setup import Setup
from support import LANDBLOCK, place

#: The scenario tick: 30 Hz. CPartArray::Update takes its quantum as a ``float`` parameter
#: (acclient.c:325139-325142), so the sequence plays f32(1/30).
TICK = 1.0 / 30.0


def _animation(frames: int) -> Animation:
    return Animation([AnimFrame([Frame()]) for _ in range(frames)])


def _walk_table(frames: int = 100) -> MotionTable:
    """NonCombat: Ready and a 30-fps WalkForward cycle of ``frames`` frames at 3.12 m/s, no links."""
    style = cmd.NON_COMBAT
    return MotionTable(
        style,
        {style: cmd.READY},
        {
            cycle_key(style, cmd.READY): MotionData([AnimData(_animation(frames), 0, -1, 30.0)]),
            cycle_key(style, cmd.WALK_FORWARD): MotionData(
                [AnimData(_animation(frames), 0, -1, 30.0)], Vector3(0.0, 3.12, 0.0)
            ),
        },
    )


def _crossing_steps(framerate: float, quantum: float, steps: int) -> list[int]:
    """The steps on which ``update_internal`` crosses a frame boundary (one entry per boundary).

    ``frame_quantum = framerate * quantum`` and ``frame_number += frame_quantum`` in double, each
    whole ``floor`` passed is one boundary (acclient.c:340690, 340695, 340713).
    """
    frame_number = 0.0
    crossed: list[int] = []
    for step in range(1, steps + 1):
        before = math.floor(frame_number)
        frame_quantum = framerate * quantum
        frame_number = frame_quantum + frame_number
        crossed += [step] * (math.floor(frame_number) - before)
    return crossed


class TestWalkAtSpeed064:
    """The acceptance case: WalkForward at 0.64 crosses its frames where the float32 framerate puts them."""

    def test_the_node_framerate_is_the_float_store_of_30_times_f32_064(self) -> None:
        table = _walk_table()
        state, seq = MotionState(), Sequence()
        table.set_default_state(state, seq)
        ok, _ = table.do_object_motion(cmd.WALK_FORWARD, state, seq, 0.64)
        assert ok
        # GetObjectSequence takes speed_mod as a float parameter (acclient.c:337640) and adds the
        # cycle at it (337810); add_motion builds speed_mod * anim (337465), operator* stores
        # rhs->framerate * lhs into the result's float framerate (acclient.c:341061-341064), which
        # the node copies (AnimSequenceNode::AnimSequenceNode, acclient.c:341288).
        expected = f32(30.0 * f32(0.64))
        assert expected == 19.19999885559082
        assert [node.framerate for node in seq.anim_list] == [expected]
        assert expected != 19.2 and expected != f32(19.2)  # neither the double product nor its store
        assert state.substate_mod == f32(0.64)

    def test_frames_are_crossed_on_the_float32_framerate_not_19_2(self) -> None:
        table = _walk_table()
        parts = PartArray(Setup("walker"))
        state = MotionState()
        table.set_default_state(state, parts.sequence)
        table.do_object_motion(cmd.WALK_FORWARD, state, parts.sequence, 0.64)
        seq = parts.sequence
        crossed = []
        for step in range(1, 101):
            before = seq.get_curr_frame_number()
            parts.update(TICK, Frame())
            crossed += [step] * (seq.get_curr_frame_number() - before)
        # 100 steps of f32(1/30) at f32(30 · f32(0.64)) = 19.19999886 fps: 0.639999995 frames a step,
        # so frames 16, 32 and 48 are reached on steps 26, 51 and 76 (16 / 0.639999995 > 25). At
        # 19.2 fps a step is 0.640000033 frames and they are reached one step early: 25, 50, 75.
        quantum = f32(TICK)
        retail = _crossing_steps(f32(30.0 * f32(0.64)), quantum, 100)
        double = _crossing_steps(19.2, quantum, 100)
        assert crossed == retail
        assert crossed != double
        assert [retail[n - 1] for n in (16, 32, 48)] == [26, 51, 76]
        assert [double[n - 1] for n in (16, 32, 48)] == [25, 50, 75]
        assert seq.frame_number == pytest.approx(64.0, abs=1e-4)

    def test_a_body_walking_at_064_plays_the_humanoid_cycle_at_the_float32_framerate(self, world) -> None:
        world.set_flat_ground(LANDBLOCK, 50.0)
        body = place(world, on_ground=True, motion_table=builtin_motion_table("humanoid"))
        assert body.do_motion(cmd.WALK_FORWARD, MovementParameters(speed=0.64)) == 0
        # The built-in table's framerates are float32 (30.0) and the link and the cycle are both
        # added at the float32 speed: 30 · f32(0.64) stored as float.
        assert [node.framerate for node in body.part_array.sequence.anim_list] == [f32(30.0 * f32(0.64))] * 2


class TestSequenceStores:
    def test_speed_rescale_stores_the_ratio_and_the_framerate(self) -> None:
        table = _walk_table()
        state, seq = MotionState(), Sequence()
        table.set_default_state(state, seq)
        table.do_object_motion(cmd.WALK_FORWARD, state, seq, 0.64)
        table.do_object_motion(cmd.WALK_FORWARD, state, seq, 0.33)
        # Same substate and sign: change_cycle_speed spills new/old to the float multiplier
        # (acclient.c:337280), multiply_framerate stores multiplier * framerate (acclient.c:340978).
        old = f32(30.0 * f32(0.64))
        multiplier = f32(f32(0.33) / f32(0.64))
        assert seq.anim_list[-1].framerate == f32(multiplier * old)
        assert f32(multiplier * old) != f32(f32(0.33) / f32(0.64) * old)  # the spill matters here
        assert state.substate_mod == f32(0.33)

    def test_apply_physics_spills_y_and_z_but_not_x(self) -> None:
        seq = Sequence()
        seq.set_velocity(Vector3(1.1, 1.1, 1.1))
        frame = Frame(Vector3(0.37, 0.37, 0.37))
        seq.apply_physics(frame, 1.0 / 19.19999885559082, 1.0)
        # CSequence::apply_physics (acclient.c:339876-339881): x = v5 · velocity.x + origin.x in
        # registers; y and z are first stored into the float local w (w.y, w.z), then added.
        step = 1.0 / 19.19999885559082
        v = f32(1.1)
        o = f32(0.37)
        assert frame.origin.x == f32(step * v + o)
        assert frame.origin.y == f32(f32(step * v) + o)
        assert frame.origin.y == frame.origin.z
        assert frame.origin.x != frame.origin.y  # same inputs, different stores

    def test_the_position_frame_composition_stores_the_origin_once(self) -> None:
        frame = Frame(Vector3(3.7, 0.0, 0.0), 0.9, 0.1, 0.2, 0.3)
        pos = Frame(Vector3(0.37, 1.9, 0.5))
        m, o, fo = frame.m, pos.origin, frame.origin
        # Frame::combine(Frame*, Frame*, AFrame*) (acclient.c:340437-340440): the rotated offset
        # plus the origin, summed z, x, y, origin in registers, stored into the float origin.
        x = f32(m[6] * o.z + m[0] * o.x + m[3] * o.y + fo.x)
        stored_offset = f32(m[6] * o.z + m[0] * o.x + m[3] * o.y) + fo.x
        combine_anim_frame(frame, pos)
        assert frame.origin.x == x
        assert f32(stored_offset) != x  # narrowing the rotated offset first would differ

    def test_a_part_is_placed_with_the_scaled_offset_in_registers(self) -> None:
        body = Frame(Vector3(10.3, 0.0, 0.0), 0.9, 0.1, 0.2, 0.3)
        placement = Frame(Vector3(-0.14, 0.83, -2.1))
        scale = f32(2.59)
        dst = Frame()
        combine_scaled(dst, body, placement, scale)
        # Frame::combine with a scale (acclient.c:326581-326589): v5 = f2.x · scale.x etc. stay in
        # registers, x = v5·m0 + v8·m6 + v6·m3 + origin.x stored once.
        m, o = body.m, placement.origin
        sx, sy, sz = o.x * scale, o.y * scale, o.z * scale
        assert dst.origin.x == f32(sx * m[0] + sz * m[6] + sy * m[3] + body.origin.x)
        narrowed = Vector3(sx, sy, sz)  # scaling into a stored vector first, as acphys did
        assert dst.origin.x != f32(narrowed.x * m[0] + narrowed.z * m[6] + narrowed.y * m[3] + body.origin.x)

    def test_the_part_array_plays_the_float32_quantum(self) -> None:
        parts = PartArray(Setup("walker"))
        parts.sequence.append_animation(AnimData(_animation(30), 0, -1, 30.0))
        parts.update(0.05, Frame())
        # CPartArray::Update(float quantum, ...) (acclient.c:325139-325142): 30 · f32(0.05).
        assert parts.sequence.frame_number == 30.0 * f32(0.05)
        assert parts.sequence.frame_number != 30.0 * 0.05


class TestInterpreterStores:
    def test_walk_backwards_stores_the_scaled_speed(self) -> None:
        interp = MotionInterp(None)
        # adjust_motion: v7 = -0.64999998 (a float constant), *speed = v7 · *speed (acclient.c:343777-343779).
        motion, speed = interp.adjust_motion(cmd.WALK_BACKWARDS, f32(0.7))
        assert motion == cmd.WALK_FORWARD
        assert speed == f32(-f32(0.64999998) * f32(0.7))
        assert speed != -f32(0.64999998) * f32(0.7)

    def test_a_sidestep_stores_its_scaled_speed_and_the_run_key_clamps_it(self) -> None:
        interp = MotionInterp(None)
        # adjust_motion: v7 = 3.1199999 / 1.25 · 0.5 from the float constant, *speed = v7 · *speed
        # (acclient.c:343779).
        _, speed = interp.adjust_motion(cmd.SIDE_STEP_RIGHT, f32(2.0))
        factor = f32(3.1199999) / 1.25 * 0.5
        assert speed == f32(factor * f32(2.0))
        assert not is_f32(factor * f32(2.0))
        # With the run key, apply_run_to_command stores rate · speed and clamps above 3 in magnitude
        # to ±3 (acclient.c:343472-343477); no weenie: the rate is 1.
        interp.raw_state.current_holdkey = HoldKey.RUN
        assert interp.adjust_motion(cmd.SIDE_STEP_LEFT, f32(2.5)) == (cmd.SIDE_STEP_RIGHT, -3.0)
        assert interp.adjust_motion(cmd.SIDE_STEP_RIGHT, f32(2.0)) == (cmd.SIDE_STEP_RIGHT, speed)

    def test_a_capped_state_velocity_is_scaled_and_stored_once(self, world) -> None:
        body = place(world, motion_table=builtin_motion_table("humanoid"), on_ground=True)
        interp = body.get_minterp()
        # A creature that is not the player cannot say its run rate: my_run_rate stands in.
        interp.weenie_obj = Weenie(the_player=False)
        interp.my_run_rate = rate = f32(1.37)
        state = interp.interpreted_state
        state.forward_command, state.forward_speed = cmd.RUN_FORWARD, rate
        state.sidestep_command, state.sidestep_speed = cmd.SIDE_STEP_RIGHT, f32(1.3)
        velocity = interp.get_state_velocity()
        # get_state_velocity (acclient.c:343558-343592): v->x = 1.25 · sidestep, v->y = 4 · forward
        # (float stores); over top = run_rate · 4 each becomes 1/len · v · top, stored once.
        x, y = f32(1.25 * f32(1.3)), f32(4.0 * rate)
        top = rate * 4.0
        length = math.sqrt(x * x + y * y)
        assert (velocity.x, velocity.y) == (f32(1.0 / length * x * top), f32(1.0 / length * y * top))
        assert velocity.z == 0.0
        twice = Vector3(x, y, 0.0) * (1.0 / length) * top  # two vector stores, as acphys did
        assert not twice.exactly_equals(velocity)

    def test_the_leave_ground_fallback_rotates_in_retails_order(self, world) -> None:
        body = place(world, motion_table=builtin_motion_table("humanoid"), heading=33.0)
        interp = body.get_minterp()
        body.velocity = Vector3(1.3, -2.7, 0.9)
        velocity = interp.get_leave_ground_velocity()
        # Standing and uncharged: the state velocity and v_z are 0, so the body velocity is taken
        # into local space with m[1]·vy + m[0]·vx + m[2]·vz per row, stored once (acclient.c:343828-343840).
        m, g = body.position.frame.m, body.velocity
        assert velocity.x == f32(m[1] * g.y + m[0] * g.x + m[2] * g.z)
        assert velocity.y == f32(m[4] * g.y + m[3] * g.x + m[5] * g.z)
        assert velocity.z == f32(m[7] * g.y + m[6] * g.x + m[8] * g.z)
        assert not is_f32(m[1] * g.y + m[0] * g.x + m[2] * g.z)  # the store is what makes it float32

    def test_the_launch_speed_is_the_weenies_float_answer_for_the_float_extent(self, world) -> None:
        world.set_flat_ground(LANDBLOCK, 50.0)
        body = place(world, motion_table=builtin_motion_table("humanoid"), on_ground=True, state=PS.GRAVITY)
        interp = body.get_minterp()
        interp.weenie_obj = Weenie(jump_skill=191, load=0.37)
        assert interp.jump(0.7)[0] == 0
        # CMotionInterp::jump(float extent) stores jump_extent = extent (acclient.c:344246); LeaveGround
        # asks get_jump_v_z, whose weenie writes sqrt(height · 19.6) into the float local extent
        # (CACQualities::InqJumpVelocity, acclient.c:443772; get_jump_v_z, acclient.c:343342).
        v_z = math.sqrt(get_jump_height(f32(0.37), 191, f32(0.7)) * 19.6)
        assert body.velocity.z == f32(v_z)
        assert not is_f32(v_z)


class TestWeenieStores:
    def test_jump_height_takes_float_load_and_power(self) -> None:
        # GetJumpHeight(const float load, ..., const float _power, ...) (acclient.c:713805-713826):
        # LoadMod(load) · (skill / (skill + 1300) · 22.200001 + 0.050000001) · power.
        load, power = 1.3, 0.7
        span, base = f32(22.200001), f32(0.050000001)
        expected = (2.0 - f32(load)) * (200.0 / 1500.0 * span + base) * f32(power) / 1.0
        assert get_jump_height(load, 200, power) == expected
        assert expected != (2.0 - load) * (200.0 / 1500.0 * span + base) * power

    def test_the_weenie_load_is_a_float(self) -> None:
        assert Weenie(load=1.3).load == f32(1.3)


class TestMoveToStores:
    def test_heading_diff_narrows_its_float_parameters(self) -> None:
        # heading_diff(float x, float y, motion) (acclient.c:344737): x - y in st7 of the floats.
        assert heading_diff(90.1, 33.3, cmd.TURN_RIGHT) == f32(90.1) - f32(33.3)
        assert heading_diff(90.1, 33.3, cmd.TURN_RIGHT) != 90.1 - 33.3

    def test_cylinder_distance_stores_the_reach(self) -> None:
        p1 = Position(0xA9B40001, Frame(Vector3(10.0, 10.0, 0.0)))
        p2 = Position(0xA9B40001, Frame(Vector3(13.1, 14.3, 0.0)))
        # Position::cylinder_distance: p2a = |offset| - (r1 + r2), a float (acclient.c:467238);
        # vertically overlapping and apart: the reach itself.
        offset = p1.get_offset(p2)
        reach = f32(offset.length() - (f32(0.48) + f32(0.31)))
        assert cylinder_distance(0.48, 1.83, p1, 0.31, 1.0, p2) == reach
        assert reach != offset.length() - (0.48 + 0.31)

    def test_the_turn_seeds_previous_heading_with_the_float_difference(self, world) -> None:
        world.set_flat_ground(LANDBLOCK, 50.0)
        body = place(world, motion_table=builtin_motion_table("humanoid"), on_ground=True, heading=10.3)
        body.turn_to_heading(MovementParameters(desired_heading=97.1))
        moveto = body.movement_manager.moveto_manager
        # BeginTurnToHeading: heading_diff(node heading, y = get_heading()) with float parameters
        # (acclient.c:345483-345484), then previous_heading = (float) diff (acclient.c:345516).
        diff = f32(97.1) - f32(body.position.frame.get_heading())
        assert moveto.current_command == cmd.TURN_RIGHT
        assert moveto.previous_heading == f32(diff)
        assert not is_f32(diff)  # the double difference, narrowed only by the store
        assert moveto.pending_actions[0].heading == f32(97.1)


def test_motion_stores_are_float32_after_real_use(world) -> None:
    world.set_flat_ground(LANDBLOCK, 50.0)
    body = place(world, motion_table=builtin_motion_table("humanoid"), on_ground=True, state=PS.GRAVITY)
    body.movement_manager.set_weenie_object(Weenie(run_skill=237, jump_skill=191, load=0.37))
    interp = body.get_minterp()
    body.do_motion(cmd.WALK_FORWARD, MovementParameters(speed=0.91, hold_key_to_apply=HoldKey.RUN))
    body.do_motion(cmd.SIDE_STEP_LEFT, MovementParameters(speed=0.77))
    body.do_motion(cmd.TURN_LEFT, MovementParameters(speed=1.13))
    for k in range(1, 31):
        world.cur_time = k * TICK
        body.update_object()
    interp.jump(0.63)
    for k in range(31, 61):
        world.cur_time = k * TICK
        body.update_object()
    target = Vector3(101.7, 103.3, 50.0)
    body.move_to_position(Position(outdoor_cell_id(LANDBLOCK, target), Frame(target)), MovementParameters())
    for k in range(61, 91):
        world.cur_time = k * TICK
        body.update_object()

    seq = body.part_array.sequence
    values = [*seq.velocity, *seq.omega, *(node.framerate for node in seq.anim_list)]
    for state in (interp.raw_state, interp.interpreted_state):
        values += [state.forward_speed, state.sidestep_speed, state.turn_speed]
    values += [interp.my_run_rate, interp.jump_extent, interp.current_speed_factor]
    values += [*interp.get_state_velocity(), *interp.get_leave_ground_velocity()]
    mstate = body.part_array.motion_table_manager.state
    values += [mstate.substate_mod, *(node.speed_mod for node in mstate.modifiers)]
    moveto = body.movement_manager.moveto_manager
    params = moveto.movement_params
    values += [moveto.previous_heading, moveto.previous_distance, moveto.original_distance]
    values += [moveto.sought_object_radius, moveto.sought_object_height]
    values += [params.distance_to_object, params.min_distance, params.desired_heading, params.speed]
    values += [params.fail_distance, params.walk_run_threshhold]
    values += [node.heading for node in moveto.pending_actions]
    setup = body.part_array.setup
    values += [
        body.part_array.scale,
        setup.height,
        setup.radius,
        setup.step_up_height,
        setup.step_down_height,
    ]
    request = MovementStruct(MovementType.MOVE_TO_OBJECT, radius=0.48, height=1.83)
    values += [request.radius, request.height]
    assert values and all(is_f32(v) for v in values), [v for v in values if not is_f32(v)]
