"""Locomotion end to end: a command goes in, root motion comes out of the body tick.

The chain under test is the retail one: ``CPhysicsObj::DoMotion`` →
``MovementManager::PerformMovement`` → ``CMotionInterp`` (adjust_motion,
DoInterpretedMotion) → ``CPartArray`` → ``MotionTableManager`` →
``CMotionTable::GetObjectSequence`` / ``add_motion`` → ``CSequence``; then
every step ``CPhysicsObj::UpdatePositionInternal`` asks ``CSequence::update``
for the offset frame, scales its origin by ``m_scale`` only on walkable ground,
and composes it onto the body's frame.

Every body stands on the landblock's flat ground (z = 50). The human's sphere 0 (centre 0.475,
radius 0.48) reaches 5 mm below its origin, so the sweep rests the origin at 50.005: placement
and landing lift the sphere onto the terrain plane (OBJECTINFO::validate_walkable,
acclient.c:314275), walking keeps it there (CTransition::adjust_offset, acclient.c:311976).
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import PhysicsState as PS
from acphys.flags import TransientState as TS
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion import commands as cmd
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.motion_table import DEFAULT_SUBSTATE_ONLY, MotionData, MotionTable, cycle_key
from acphys.motion.movement import HoldKey, MovementParameters
from acphys.precision import f32
from acphys.scenario.motion_tables import builtin_motion_table
from support import LANDBLOCK, place

GROUND = 50.0
#: Where the human's origin rests on that ground: sphere 0's bottom on the plane (a float32, as
#: every position coordinate is).
REST = f32(GROUND + (0.48 - 0.475))
#: The float32 spacing of coordinates in [64, 128) m: a body near 96 m moves in steps of this.
ULP_96 = 2.0**-17
#: Headings come from float32 quaternions: one rounding of the components is ~1e-7 rad (6e-6 degrees).
HEADING_F32 = 1e-5
#: One root-motion frame of the 4 m/s run at 30 fps, as the sequence stores it: the step spilled to
#: float ``w.y`` and added to the float offset origin (CSequence::apply_physics, acclient.c:339877-339880).
RUN_FRAME = f32(f32((1.0 / 30.0) * 4.0) + 0.0)
#: 90 degrees per second, clockwise seen from above: TurnRight.
TURN_RATE = math.pi / 2.0


def _data(frames: int, velocity=(0.0, 0.0, 0.0), omega=(0.0, 0.0, 0.0), bitfield: int = 0) -> MotionData:
    animation = Animation([AnimFrame() for _ in range(frames)])
    return MotionData([AnimData(animation, 0, -1, 30.0)], Vector3(*velocity), Vector3(*omega), bitfield)


def run_table() -> MotionTable:
    """NonCombat: Ready; a 30-fps, 30-frame RunForward at 4 m/s and WalkForward at 3.12; TurnRight."""
    style = cmd.NON_COMBAT
    return MotionTable(
        style,
        {style: cmd.READY},
        {
            cycle_key(style, cmd.READY): _data(30),
            cycle_key(style, cmd.RUN_FORWARD): _data(30, velocity=(0.0, 4.0, 0.0)),
            cycle_key(style, cmd.WALK_FORWARD): _data(30, velocity=(0.0, 3.12, 0.0)),
            cycle_key(style, cmd.TURN_RIGHT): _data(
                30, omega=(0.0, 0.0, -TURN_RATE), bitfield=DEFAULT_SUBSTATE_ONLY
            ),
        },
    )


@pytest.fixture
def ground(world):
    world.set_flat_ground(LANDBLOCK, GROUND)
    return world


def _walker(world, table=None, **kwargs):
    kwargs.setdefault("on_ground", True)
    kwargs.setdefault("origin", (96.0, 96.0, GROUND))
    return place(world, motion_table=table or run_table(), **kwargs)


def _params(hold: HoldKey = HoldKey.NONE, speed: float = 1.0) -> MovementParameters:
    return MovementParameters(speed=speed, hold_key_to_apply=hold)


def _advance(world, body, seconds: float, quantum: float = 0.05) -> None:
    """Run the body's clock forward in steps of ``quantum``."""
    start = world.cur_time
    for k in range(1, round(seconds / quantum) + 1):
        world.cur_time = start + k * quantum
        body.update_object()


class TestRootMotion:
    """CPhysicsObj::UpdatePositionInternal @ 0x00512C30 (acclient.c:319988) with CSequence::update_internal
    @ 0x005255D0 (acclient.c:340658): one apply_physics of 1/framerate per frame boundary crossed."""

    def test_first_step_moves_exactly_one_frame(self, ground):
        body = _walker(ground)
        assert body.do_motion(cmd.RUN_FORWARD, _params()) == 0
        _advance(ground, body, 0.05)
        # frame_number 0 -> 30 · 0.05 = 1.5: one boundary, one 1/30-s application of 4 m/s; the body's
        # frame then takes the offset (Frame::combine, acclient.c:319448) into its float origin.
        assert body.position.frame.origin.y == f32(96.0 + RUN_FRAME)
        assert body.position.frame.origin.x == 96.0
        assert body.position.frame.origin.z == pytest.approx(REST, abs=1e-9)
        # Root motion never touches m_velocityVector; cached_velocity is the displacement over the
        # (float32) quantum (UpdateObjectInternal, acclient.c:322718).
        assert body.velocity.exactly_equals(Vector3())
        displacement = body.position.frame.origin.y - 96.0
        assert body.cached_velocity.y == pytest.approx(displacement / f32(0.05), rel=1e-7)

    def test_one_second_of_running_is_four_metres(self, ground):
        body = _walker(ground)
        body.do_motion(cmd.RUN_FORWARD, _params())
        _advance(ground, body, 1.0)
        # 20 quanta of f32(0.05): frame_number reaches 30.0000004, so 29 in-cycle boundaries plus
        # the wrap's entry frame (advance_to_next_animation, acclient.c:340472): 30 × 4/30. Each of the
        # 20 steps stores the body's y as a float32 near 96 m: at most half an ULP_96 off per step.
        assert body.position.frame.origin.y - 96.0 == pytest.approx(4.0, abs=20 * ULP_96 / 2)
        assert body.velocity.exactly_equals(Vector3())

    def test_displacement_comes_only_at_frame_boundaries(self, ground):
        body = _walker(ground)
        body.do_motion(cmd.RUN_FORWARD, _params())
        steps = []
        for k in range(1, 11):
            before = body.position.frame.origin.y
            ground.cur_time = k * 0.05
            body.update_object()
            # The float32 position near 96 m rounds each step by up to ULP_96 / 2: a few 1e-5 frames.
            steps.append(round((body.position.frame.origin.y - before) * 30.0 / 4.0, 3))
        # 1.5 frames per quantum: boundaries alternate 1, 2, 1, 2, ... (floor(1.5 k) - floor(1.5 (k-1))).
        assert steps == [1.0, 2.0] * 5

    def test_the_motion_is_rotated_into_the_world(self, ground):
        body = _walker(ground, heading=90.0)
        body.do_motion(cmd.RUN_FORWARD, _params())
        _advance(ground, body, 0.05)
        # Frame::combine rotates the body-local +y into the heading: east, +x. The heading's float32
        # matrix and the float32 origin near 96 m make that exact to about one ULP_96.
        assert body.position.frame.origin.x - 96.0 == pytest.approx(4.0 / 30.0, abs=ULP_96)
        assert body.position.frame.origin.y == pytest.approx(96.0, abs=ULP_96)

    def test_root_motion_is_scaled_by_the_body_scale_on_walkable_ground(self, ground):
        body = _walker(ground)
        body.set_scale_static(2.0)
        body.do_motion(cmd.RUN_FORWARD, _params())
        _advance(ground, body, 0.05)
        # offset origin × m_scale on ON_WALKABLE (UpdatePositionInternal, acclient.c:319988): the
        # float32 run frame doubled (exact), then added to the body's float origin.
        assert body.position.frame.origin.y == f32(96.0 + 2.0 * RUN_FRAME)

    def test_no_translation_off_walkable_ground_but_rotation_applies(self, ground):
        # No gravity and no contact: the offset origin is multiplied by 0, its rotation is kept.
        body = _walker(ground, on_ground=False, state=PS(0), origin=(96.0, 96.0, 60.0))
        body.do_motion(cmd.TURN_RIGHT, _params())
        body.part_array.sequence.set_velocity(Vector3(0.0, 4.0, 0.0))
        _advance(ground, body, 0.05)
        assert body.position.frame.origin.exactly_equals(Vector3(96.0, 96.0, 60.0))
        assert body.position.frame.get_heading() == pytest.approx(3.0, abs=HEADING_F32)

    def test_a_hidden_body_gets_no_root_motion_at_all(self, ground):
        body = _walker(ground)
        body.do_motion(cmd.RUN_FORWARD, _params())
        body.set_state(body.state | PS.HIDDEN)
        _advance(ground, body, 0.5)
        # HIDDEN skips CPartArray::Update entirely (UpdatePositionInternal, acclient.c:319988).
        assert body.position.frame.origin == Vector3(96.0, 96.0, REST)
        assert body.position.frame.get_heading() == 0.0


class TestTurning:
    """TurnRight is a cycle with omega; TurnLeft is TurnRight at negative speed
    (CMotionInterp::adjust_motion @ 0x00528010, acclient.c:343745), played in reverse."""

    def test_turn_right_turns_by_omega_per_frame_boundary(self, ground):
        body = _walker(ground)
        assert body.do_motion(cmd.TURN_RIGHT, _params()) == 0
        _advance(ground, body, 0.05)
        # One boundary: rotate by omega/30 = 3 degrees clockwise (compass heading grows).
        assert body.position.frame.get_heading() == pytest.approx(3.0, abs=HEADING_F32)
        _advance(ground, body, 0.05)
        assert body.position.frame.get_heading() == pytest.approx(9.0, abs=HEADING_F32)

    def test_a_second_of_turning_right_is_ninety_degrees(self, ground):
        body = _walker(ground)
        body.do_motion(cmd.TURN_RIGHT, _params())
        _advance(ground, body, 1.0)
        # 30 float32 rotations: up to 30 roundings of the quaternion.
        assert body.position.frame.get_heading() == pytest.approx(90.0, abs=30 * HEADING_F32)
        assert body.position.frame.origin == Vector3(96.0, 96.0, REST)

    def test_turn_left_is_turn_right_with_negated_speed(self, ground):
        body = _walker(ground)
        body.do_motion(cmd.TURN_LEFT, _params())
        state = body.get_minterp().interpreted_state
        assert state.turn_command == cmd.TURN_RIGHT
        assert state.turn_speed == -1.0
        # The cycle plays backwards from high + 1 - F_EPSILON = 29.9998: frame -1.5 crosses one
        # boundary going down, which applies -1/30 s of omega: 3 degrees anticlockwise.
        _advance(ground, body, 0.05)
        assert body.position.frame.get_heading() == pytest.approx(357.0, abs=HEADING_F32)
        _advance(ground, body, 0.05)
        assert body.position.frame.get_heading() == pytest.approx(351.0, abs=HEADING_F32)


class TestWalking:
    def test_walk_backwards_plays_walk_forward_in_reverse_at_0_65(self, ground):
        body = _walker(ground)
        body.do_motion(cmd.WALK_BACKWARDS, _params())
        state = body.get_minterp().interpreted_state
        # adjust_motion: WalkBackwards -> WalkForward × -0.64999998 (acclient.c:343745).
        assert state.forward_command == cmd.WALK_FORWARD
        assert state.forward_speed == f32(-0.64999998)
        # add_motion scales the cycle by the speed (acclient.c:337430): framerate 30 × -0.65 = -19.5 and
        # velocity 3.12 × -0.65. Backwards from frame 29.9998, the first quantum (-0.975 frames) stays
        # inside frame 29: no boundary, no motion.
        _advance(ground, body, 0.05)
        assert body.position.frame.origin.y == 96.0
        # The second reaches 28.05: one boundary, apply_physics(1/19.5 s) of -2.028 m/s, which is one
        # frame of walking (3.12/30 m) backwards, to the float32 rounding of the body's y near 96 m.
        _advance(ground, body, 0.05)
        frame_of_walking = 3.12 / 30.0
        assert body.position.frame.origin.y - 96.0 == pytest.approx(-frame_of_walking, abs=ULP_96)
        # After a second: 29.9998 - 19.5 = 10.4998, 19 boundaries.
        _advance(ground, body, 0.9)
        assert body.position.frame.origin.y - 96.0 == pytest.approx(-19 * frame_of_walking, abs=19 * ULP_96)

    def test_hold_run_turns_walking_into_running_at_the_run_rate(self, ground):
        body = _walker(ground)
        body.do_motion(cmd.WALK_FORWARD, _params(hold=HoldKey.RUN))
        state = body.get_minterp().interpreted_state
        # apply_run_to_command (acclient.c:343438): WalkForward with the run key becomes RunForward at
        # the run rate; a body with no weenie runs at my_run_rate, 1.0.
        assert state.forward_command == cmd.RUN_FORWARD
        assert state.forward_speed == 1.0
        _advance(ground, body, 1.0)
        assert body.position.frame.origin.y - 96.0 == pytest.approx(4.0, abs=20 * ULP_96 / 2)


class TestLinksAndCompletion:
    """The built-in humanoid: a 4-frame Ready→WalkForward link plays before the cycle."""

    def test_the_link_plays_first_and_its_anim_done_completes_the_motion(self, ground):
        body = _walker(ground, table=builtin_motion_table("humanoid"))
        body.do_motion(cmd.WALK_FORWARD, _params())
        sequence = body.part_array.sequence
        manager = body.part_array.motion_table_manager
        # GetObjectSequence queued the link then the cycle; the manager waits for one AnimDone.
        assert [node.animation.num_frames for node in sequence.anim_list] == [4, 30]
        assert [(node.motion, node.num_anims) for node in manager.pending_animations] == [
            (cmd.WALK_FORWARD, 1)
        ]
        assert body.motions_pending()
        _advance(ground, body, 0.1)
        # frame_number 3.0: still in the link (high frame 3); the sequence velocity applies throughout.
        assert body.motions_pending()
        assert body.position.frame.origin.y - 96.0 == pytest.approx(3 * f32(3.12) / 30.0, abs=3 * ULP_96)
        _advance(ground, body, 0.05)
        # 4.5 overruns the link: AnimDone fires, the manager completes WalkForward, apricot drops the link.
        assert not body.motions_pending()
        assert list(manager.pending_animations) == []
        assert [node.animation.num_frames for node in sequence.anim_list] == [30]

    def test_stopping_returns_to_ready_through_its_link(self, ground):
        body = _walker(ground, table=builtin_motion_table("humanoid"))
        body.do_motion(cmd.WALK_FORWARD, _params())
        _advance(ground, body, 0.5)
        body.stop_motion(cmd.WALK_FORWARD, _params())
        state = body.get_minterp().interpreted_state
        assert state.forward_command == cmd.READY
        # StopObjectMotion goes back to the style default: the sequence velocity is Ready's, zero.
        assert body.part_array.sequence.velocity.exactly_equals(Vector3())
        where = body.position.frame.origin.copy()
        _advance(ground, body, 0.5)
        assert body.position.frame.origin.exactly_equals(where)
        assert not body.motions_pending()


class TestJump:
    """CMotionInterp::jump @ 0x00528780 (acclient.c:344223), LeaveGround (344456), HitGround (344428)."""

    def test_a_standing_jump_leaves_the_ground_and_landing_restores_the_cycle(self, ground):
        body = _walker(ground, table=builtin_motion_table("humanoid"), state=PS.GRAVITY)
        seen: list[list[str]] = []
        body.observer = lambda obj, _q: seen.append(list(obj.step_events))
        interp = body.get_minterp()
        error, _cost = interp.jump(1.0)
        assert error == 0
        # get_leave_ground_velocity: state velocity (standing: 0) with z = get_jump_v_z, 10 m/s without
        # a weenie (acclient.c:343342); LeaveGround sets it as the local velocity.
        assert body.velocity.exactly_equals(Vector3(0.0, 0.0, 10.0))
        assert not body.transient_state & TS.ON_WALKABLE
        _advance(ground, body, 0.05)
        assert "leave_ground" in seen[0]
        assert body.position.frame.origin.z > GROUND
        assert not body.transient_state & TS.CONTACT
        # In the air the interpreter replays its movement: the cycle is Falling.
        assert body.part_array.motion_table_manager.state.substate == cmd.FALLING
        _advance(ground, body, 2.5)
        assert any("hit_ground" in events for events in seen)
        assert body.transient_state & TS.ON_WALKABLE and body.transient_state & TS.CONTACT
        assert body.position.frame.origin.z == pytest.approx(REST, abs=1e-9)
        # HitGround replays the movement on the ground: back to the Ready cycle.
        assert interp.interpreted_state.forward_command == cmd.READY
        assert body.part_array.motion_table_manager.state.substate == cmd.READY


class TestMoveToAndTurnTo:
    def test_move_to_reaches_the_point_and_stops_within_its_distance(self, ground):
        body = _walker(ground, table=builtin_motion_table("humanoid"))
        target = Vector3(96.0, 106.0, GROUND)
        request = MovementParameters()
        assert (
            body.move_to_position(Position(outdoor_cell_id(LANDBLOCK, target), Frame(target)), request) == 0
        )
        assert body.is_moving_to()
        _advance(ground, body, 6.0)
        assert not body.is_moving_to()
        remaining = (target - body.position.frame.origin).length()
        # Arrival: the default parameters carry USE_SPHERES, so GetCurrentDistance is the cylinder
        # distance (acclient.c:344856, 344880): the gap from the body's 0.48-m cylinder to the point,
        # within distance_to_object (0.6 by default), at most one 0.05-s step (1.5 frames: 1 or 2 walk
        # frames of 0.104 m) inside it.
        gap = remaining - body.get_radius()
        assert request.distance_to_object - 2 * 3.12 / 30.0 < gap <= request.distance_to_object
        state = body.get_minterp().interpreted_state
        assert state.forward_command == cmd.READY
        where = body.position.frame.origin.copy()
        _advance(ground, body, 0.5)
        assert body.position.frame.origin.exactly_equals(where)

    def test_turn_to_ends_on_the_heading(self, ground):
        body = _walker(ground, table=builtin_motion_table("humanoid"))
        body.turn_to_heading(MovementParameters(desired_heading=90.0))
        assert body.is_moving_to()
        _advance(ground, body, 2.0)
        assert not body.is_moving_to()
        # Snapped to the node's heading (set_heading, HandleTurnToHeading), a float32 quaternion.
        assert body.position.frame.get_heading() == pytest.approx(90.0, abs=HEADING_F32)
        assert body.get_minterp().interpreted_state.turn_command == 0
