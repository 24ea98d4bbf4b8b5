"""MoveToManager and its helpers, against the retail decompilation (CMoveToManager.c, CMovementDefs.c).

Expected values are worked by hand from the cited acclient.c lines.
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import TransientState
from acphys.math.cell_id import outdoor_cell_id
from acphys.math.frame import Frame
from acphys.math.position import Position
from acphys.math.vector import Vector3
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.commands import (
    NON_COMBAT,
    READY,
    RUN_FORWARD,
    TURN_LEFT,
    TURN_RIGHT,
    WALK_BACKWARDS,
    WALK_FORWARD,
)
from acphys.motion.motion_table import DEFAULT_SUBSTATE_ONLY, MotionData, MotionTable, cycle_key
from acphys.motion.move_to import (
    MoveToManager,
    TargetInfo,
    cylinder_distance,
    get_command,
    get_desired_heading,
    heading_diff,
    heading_greater,
    position_distance,
    position_heading,
)
from acphys.motion.movement import (
    FLT_MAX,
    HoldKey,
    MovementFlags,
    MovementParameters,
    MovementStruct,
    MovementType,
)
from acphys.physics_obj import PhysicsObj
from acphys.precision import f32
from acphys.world.world import World
from support import LANDBLOCK, place


def pos(x: float, y: float, z: float = 0.0, heading: float = 0.0, landblock: int = LANDBLOCK) -> Position:
    point = Vector3(x, y, z)
    return Position(outdoor_cell_id(landblock, point), Frame.from_heading(point, heading))


# -- heading helpers ---------------------------------------------------------------------------


class TestHeadingDiff:
    def test_turn_right_wraps_negative_into_0_360(self) -> None:
        # 10 - 350 = -340 < -EPSILON -> +360 = 20; TurnRight keeps it (acclient.c:344742-344746).
        assert heading_diff(10.0, 350.0, TURN_RIGHT) == pytest.approx(20.0)
        assert heading_diff(350.0, 10.0, TURN_RIGHT) == pytest.approx(340.0)

    def test_other_motions_mirror_to_360_minus(self) -> None:
        # result > EPSILON and motion != 0x6500000D -> 360 - result (acclient.c:344747-344748).
        assert heading_diff(10.0, 350.0, TURN_LEFT) == pytest.approx(340.0)
        assert heading_diff(350.0, 10.0, TURN_LEFT) == pytest.approx(20.0)

    def test_dead_zone_is_zero_for_both_directions(self) -> None:
        # |x - y| < EPSILON -> 0, and 0 is not mirrored (acclient.c:344743-344748).
        assert heading_diff(90.0, 90.0001, TURN_RIGHT) == 0.0
        assert heading_diff(90.0, 90.0001, TURN_LEFT) == 0.0


class TestHeadingGreater:
    def test_turn_right_within_half_circle(self) -> None:
        # |x - y| <= 180: greater means x > y (acclient.c:344721-344731).
        assert heading_greater(100.0, 90.0, TURN_RIGHT) is True
        assert heading_greater(80.0, 90.0, TURN_RIGHT) is False

    def test_turn_right_across_the_seam(self) -> None:
        # |10 - 350| > 180: the compare flips, so 10 has passed 350 going clockwise
        # (acclient.c:344726-344731).
        assert heading_greater(10.0, 350.0, TURN_RIGHT) is True
        assert heading_greater(350.0, 10.0, TURN_RIGHT) is False

    def test_other_motions_negate_so_equal_counts_as_passed(self) -> None:
        # result = !(x <= y) for TurnRight, (x <= y) otherwise (acclient.c:344731-344733).
        assert heading_greater(90.0, 90.0, TURN_RIGHT) is False
        assert heading_greater(90.0, 90.0, TURN_LEFT) is True
        assert heading_greater(80.0, 90.0, TURN_LEFT) is True


class TestPositionMeasures:
    @pytest.mark.parametrize(
        ("dx", "dy", "expected"),
        [(0.0, 5.0, 0.0), (5.0, 0.0, 90.0), (0.0, -5.0, 180.0), (-5.0, 0.0, 270.0), (3.0, 3.0, 45.0)],
    )
    def test_heading_is_compass_bearing(self, dx: float, dy: float, expected: float) -> None:
        # fmod(450 - atan2 in degrees, 360) of the horizontal offset (acclient.c:467061).
        assert position_heading(pos(50.0, 50.0), pos(50.0 + dx, 50.0 + dy, 7.0)) == pytest.approx(expected)

    def test_heading_of_a_vertical_offset_is_zero(self) -> None:
        # z zeroed, normalize_check_small -> 0.0 (acclient.c:467057-467059).
        assert position_heading(pos(50.0, 50.0, 0.0), pos(50.0, 50.0, 9.0)) == 0.0

    def test_distance_crosses_landblocks(self) -> None:
        # get_offset adds the 192-m block offset: (190,10) in A9B4 to (2,10) in AAB4 is 4 m
        # (acclient.c:467038).
        assert position_distance(pos(190.0, 10.0), pos(2.0, 10.0, landblock=0xAAB4)) == pytest.approx(4.0)


class TestCylinderDistance:
    def test_side_by_side_is_reach(self) -> None:
        # Same base z: gap = 0 - (0 + 2) = -2 <= 0, reach = 3 - 1 = 2 > 0 -> reach (acclient.c:467238-467259).
        assert cylinder_distance(0.5, 2.0, pos(50, 50), 0.5, 2.0, pos(53, 50)) == pytest.approx(2.0)

    def test_overlapping_is_negative_hypotenuse(self) -> None:
        # gap = -2, reach = 0.6 - 1 = -0.4 -> -sqrt(4 + 0.16) (acclient.c:467257).
        d = cylinder_distance(0.5, 2.0, pos(50, 50), 0.5, 2.0, pos(50.6, 50))
        assert d == pytest.approx(-math.sqrt(4.16))

    def test_reach_uses_the_full_3d_distance(self) -> None:
        # 3 m across, 5 m up: reach = sqrt(34) - 1; gap = 5 - (0 + 2) = 3 > 0 -> sqrt(9 + reach^2)
        # (acclient.c:467238, 467263).
        reach = math.sqrt(34.0) - 1.0
        d = cylinder_distance(0.5, 2.0, pos(50, 50, 0), 0.5, 2.0, pos(53, 50, 5))
        assert d == pytest.approx(math.sqrt(9.0 + reach * reach))

    def test_stacked_is_the_vertical_gap(self) -> None:
        # Fat cylinders stacked: reach = 4 - 6 = -2, gap = 4 - 1 = 3 > 0 -> v11 stays the gap
        # (acclient.c:467250, 467261).
        # ACE's CylinderDistance returns reach (-2) here: decompile wins.
        assert cylinder_distance(3.0, 1.0, pos(50, 50, 0), 3.0, 1.0, pos(50, 50, 4)) == pytest.approx(3.0)

    def test_higher_first_body_measures_from_the_other_top(self) -> None:
        # z1 > z2: gap = z1 - (z2 + h2) = 6 - (0 + 2) = 4; reach = 6 - 1 = 5 -> sqrt(16 + 25)
        # (acclient.c:467248).
        d = cylinder_distance(0.5, 1.0, pos(50, 50, 6), 0.5, 2.0, pos(50, 50, 0))
        assert d == pytest.approx(math.sqrt(41.0))


# -- MovementParameters command choice ---------------------------------------------------------


def params(flags: int, **kw: float) -> MovementParameters:
    p = MovementParameters()
    p.flags = MovementFlags(flags)
    for key, value in kw.items():
        setattr(p, key, value)
    return p


class TestGetCommand:
    def test_default_flags_walk_towards(self) -> None:
        # Default 0x1EE0F: MOVE_TOWARDS only -> WalkForward beyond distance_to_object 0.6
        # (acclient.c:346195-346198);
        # CAN_WALK set and 10 - 0.6 < 15 -> HoldKey None (acclient.c:346217-346220).
        assert get_command(MovementParameters(), 10.0) == (WALK_FORWARD, HoldKey.NONE, False)

    def test_default_flags_run_beyond_threshold(self) -> None:
        # 20 - 0.6 > walk_run_threshhold 15 -> HoldKey Run (acclient.c:346217-346218).
        assert get_command(MovementParameters(), 20.0) == (WALK_FORWARD, HoldKey.RUN, False)

    def test_default_flags_arrived(self) -> None:
        # 0.5 <= 0.6 -> command 0 (acclient.c:346202).
        assert get_command(MovementParameters(), 0.5)[0] == 0

    def test_towards_and_away(self) -> None:
        f = MovementFlags.MOVE_TOWARDS | MovementFlags.MOVE_AWAY | MovementFlags.CAN_WALK
        p = params(f, min_distance=2.0, distance_to_object=5.0)
        # dist > 5 -> WalkForward towards; dist - 2 < EPSILON -> WalkBackwards away; else 0
        # (acclient.c:346155-346170).
        assert get_command(p, 6.0) == (WALK_FORWARD, HoldKey.NONE, False)
        assert get_command(p, 1.0) == (WALK_BACKWARDS, HoldKey.NONE, True)
        assert get_command(p, 3.0)[0] == 0

    def test_away_only_walks_forward_turned_away(self) -> None:
        p = params(MovementFlags.MOVE_AWAY | MovementFlags.CAN_WALK, min_distance=4.0)
        # MOVE_AWAY without MOVE_TOWARDS: dist < min_distance -> WalkForward, moving_away
        # (acclient.c:346206-346213).
        assert get_command(p, 3.0) == (WALK_FORWARD, HoldKey.NONE, True)
        assert get_command(p, 5.0)[0] == 0

    def test_charge_runs_even_without_can_run(self) -> None:
        # bitfield & 0x10 (CAN_CHARGE) alone gives HoldKey Run (acclient.c:346217). ACE omits the charge test.
        p = params(MovementFlags.MOVE_TOWARDS | MovementFlags.CAN_WALK | MovementFlags.CAN_CHARGE)
        assert get_command(p, 2.0)[1] == HoldKey.RUN

    def test_run_without_walk_always_runs(self) -> None:
        # CAN_RUN and !CAN_WALK -> Run regardless of distance (acclient.c:346217).
        p = params(MovementFlags.MOVE_TOWARDS | MovementFlags.CAN_RUN)
        assert get_command(p, 2.0)[1] == HoldKey.RUN

    @pytest.mark.parametrize(
        ("command", "away", "expected"),
        [
            (WALK_FORWARD, False, 0.0),
            (WALK_FORWARD, True, 180.0),
            (RUN_FORWARD, True, 180.0),
            (WALK_BACKWARDS, False, 180.0),
            (WALK_BACKWARDS, True, 0.0),
            (TURN_RIGHT, True, 0.0),
        ],
    )
    def test_desired_heading(self, command: int, away: bool, expected: float) -> None:
        # acclient.c:346226-346236
        assert get_desired_heading(command, away) == expected


# -- progress and distance ---------------------------------------------------------------------


class TestCheckProgressMade:
    def manager(self, world: World, *, moving_away: bool = False) -> MoveToManager:
        m = MoveToManager(place(world))
        m.moving_away = moving_away
        m.previous_distance = m.original_distance = 10.0
        m.previous_distance_time = m.original_distance_time = 0.0
        return m

    def test_within_one_second_always_passes(self, world: World) -> None:
        # elapsed 1.0 is not > 1.0 -> result stays 1 (acclient.c:344842-344843).
        m = self.manager(world)
        world.cur_time = 1.0
        assert m.check_progress_made(10.0) is True
        assert m.previous_distance == 10.0

    def test_slow_closing_since_last_sample_fails(self, world: World) -> None:
        # (10 - 9.7) / 1.5 = 0.2 < 0.25 -> 0, sample kept (acclient.c:344846-344847).
        m = self.manager(world)
        world.cur_time = 1.5
        assert m.check_progress_made(9.7) is False
        assert m.previous_distance == 10.0

    def test_good_closing_updates_the_sample(self, world: World) -> None:
        # 0.5 / 1.5 = 0.33 both since the sample and since the start (acclient.c:344847-344849).
        m = self.manager(world)
        world.cur_time = 1.5
        assert m.check_progress_made(9.5) is True
        assert (m.previous_distance, m.previous_distance_time) == (9.5, 1.5)

    def test_slow_since_start_fails_after_updating_the_sample(self, world: World) -> None:
        # Since the sample (9.9 at t=4): 0.4 / 1.1 = 0.36 passes and the sample moves to (9.5, 5.1);
        # since the start: 0.5 / 5.1 = 0.098 < 0.25 -> 0 (acclient.c:344848-344850).
        m = self.manager(world)
        m.previous_distance, m.previous_distance_time = 9.9, 4.0
        world.cur_time = 5.1
        assert m.check_progress_made(9.5) is False
        assert (m.previous_distance, m.previous_distance_time) == (9.5, 5.1)

    def test_moving_away_counts_opening(self, world: World) -> None:
        # moving_away: curr - previous = 0.5 / 1.5 passes; closing in would fail (acclient.c:344846).
        m = self.manager(world, moving_away=True)
        world.cur_time = 1.5
        assert m.check_progress_made(10.5) is True
        m = self.manager(world, moving_away=True)
        assert m.check_progress_made(9.5) is False


def test_initialize_local_variables_resets_distances_and_bitfield(world: World) -> None:
    # previous/original distance = FLT_MAX, times = Timer::cur_time, bitfield and context_id = 0, but
    # distance_to_object kept (acclient.c:344920-344928). ACE zeroes DistanceToObject instead of the bitfield.
    world.cur_time = 7.0
    m = MoveToManager(place(world))
    m.movement_params.distance_to_object = 3.0
    m.movement_params.context_id = 9
    m.previous_distance = m.original_distance = 1.0
    m.movement_type = MovementType.MOVE_TO_POSITION
    m.initialize_local_variables()
    assert m.movement_params.flags == 0
    assert m.movement_params.context_id == 0
    assert m.movement_params.distance_to_object == 3.0
    assert m.previous_distance == FLT_MAX and m.original_distance == FLT_MAX
    assert m.previous_distance_time == 7.0 and m.original_distance_time == 7.0
    assert m.movement_type == MovementType.INVALID


# -- integrated: a body with a motion table on flat ground ---------------------------------------


def _cycle(velocity: Vector3 | None = None, omega: Vector3 | None = None, bitfield: int = 0) -> MotionData:
    animation = Animation([AnimFrame([Frame()]) for _ in range(30)])
    return MotionData([AnimData(animation, framerate=30.0)], velocity, omega, bitfield)


def small_table() -> MotionTable:
    """Ready, WalkForward at 3.12 m/s, TurnRight at 90 deg/s (a cycle from Ready, a modifier over walking)."""
    nc = NON_COMBAT
    turn = Vector3(0.0, 0.0, -math.pi / 2)
    return MotionTable(
        nc,
        {nc: READY},
        {
            cycle_key(nc, READY): _cycle(),
            cycle_key(nc, WALK_FORWARD): _cycle(velocity=Vector3(0.0, 3.12, 0.0)),
            cycle_key(nc, TURN_RIGHT): _cycle(omega=turn, bitfield=DEFAULT_SUBSTATE_ONLY),
        },
        modifiers={cycle_key(nc, TURN_RIGHT): _cycle(omega=turn)},
    )


class RecordingTargetManager:
    """Stands in for the target manager acphys does not have yet; records what the move-to asks of it."""

    def __init__(self) -> None:
        self.calls: list[tuple] = []
        self.target_info = None

    def set_target(self, context_id: int, object_id: int, radius: float, quantum: float) -> None:
        self.calls.append(("set_target", context_id, object_id, radius, quantum))

    def clear_target(self) -> None:
        self.calls.append(("clear_target",))

    def set_target_quantum(self, quantum: float) -> None:
        self.calls.append(("set_target_quantum", quantum))

    def handle_targetting(self) -> None:
        pass


class RecordingPositionManager:
    """Stands in for the position manager acphys does not have yet; records stick and unstick requests."""

    def __init__(self) -> None:
        self.calls: list[tuple] = []

    def stick_to(self, object_id: int, radius: float, height: float) -> None:
        self.calls.append(("stick_to", object_id, radius, height))

    def unstick(self) -> None:
        self.calls.append(("unstick",))

    def is_interpolating(self) -> bool:
        return False

    def adjust_offset(self, offset_frame: Frame, quantum: float) -> None:
        pass

    def use_time(self) -> None:
        pass

    def is_fully_constrained(self) -> bool:
        return False


TICK = 1.0 / 30.0
NO_SPHERES = MovementFlags(0x1EE0F) & ~MovementFlags.USE_SPHERES


def tick(body: PhysicsObj) -> None:
    body.world.cur_time += TICK
    body.update_object()


@pytest.fixture
def walker(world: World) -> PhysicsObj:
    """A grounded body at (96, 96, 50) facing north, its default-state Ready already played out."""
    world.set_flat_ground(LANDBLOCK, 50.0)
    body = place(world, on_ground=True)
    body.set_motion_table(small_table())
    tick(body)
    assert not body.motions_pending()
    return body


def move_to(body: PhysicsObj, x: float, y: float, flags: int = NO_SPHERES, **kw: float) -> MoveToManager:
    p = params(flags, **kw)
    request = MovementStruct(MovementType.MOVE_TO_POSITION, pos=pos(x, y, 50.0), params=p)
    body.movement_manager.perform_movement(request)
    return body.movement_manager.moveto_manager


def teleport(body: PhysicsObj, x: float, y: float) -> None:
    body.position.frame.origin = Vector3(x, y, 50.0)


def test_walks_to_a_point_and_stops(walker: PhysicsObj) -> None:
    m = move_to(walker, 96.0, 106.0)
    # Facing the target: the turn node ends at once (heading_diff 0 <= EPSILON, acclient.c:345487-345495) and
    # BeginMoveForward issues WalkForward (acclient.c:345406-345424).
    assert m.current_command == WALK_FORWARD
    distances = []
    for _ in range(200):
        tick(walker)
        distances.append(position_distance(walker.position, pos(96.0, 106.0, 50.0)))
        if not m.is_moving_to():
            break
    # Walking 3.12 m/s closes 0.104 m a tick; the move ends on the first tick within distance_to_object 0.6
    # (acclient.c:345688), after which BeginNextNode cleans up and stops (acclient.c:345550-345553).
    assert distances[-1] <= 0.6 < distances[-2]
    # The walker rests 5 mm above the target's z (sphere 0, centre 0.475 and radius 0.48, sits on the
    # ground: OBJECTINFO::validate_walkable, acclient.c:314275): the last tick's 0.104 m shortens the
    # horizontal part of the 3-D distance.
    dz = walker.position.frame.origin.z - 50.0
    assert dz == f32(50.0 + 0.005) - 50.0  # the float32 origin z
    flat = math.sqrt(distances[-2] ** 2 - dz * dz)
    # Positions near 100 m are float32 (spacing 2^-17 = 7.6 µm): the distances agree to about that.
    assert distances[-1] == pytest.approx(math.hypot(flat - 3.12 / 30.0, dz), abs=2.0**-17)
    assert m.movement_type == MovementType.INVALID and m.pending_actions == []
    assert walker.movement_manager.motion_interpreter.interpreted_state.forward_command == READY
    resting = walker.position.frame.origin.copy()
    for _ in range(10):
        tick(walker)
    assert walker.position.frame.origin == resting


class TestSteering:
    def walking(self, walker: PhysicsObj) -> MoveToManager:
        m = move_to(walker, 96.0, 106.0)
        tick(walker)  # let the WalkForward link play out so no motion is pending
        assert not walker.motions_pending()
        return m

    @pytest.mark.parametrize(
        ("heading", "aux"), [(300.0, TURN_RIGHT), (339.0, TURN_RIGHT), (60.0, TURN_LEFT)]
    )
    def test_error_above_20_degrees_turns(self, walker: PhysicsObj, heading: float, aux: int) -> None:
        # Bearing 0; error = 0 - heading wrapped: 60 and 21 -> TurnRight, 300 (>= 180) -> TurnLeft
        # (acclient.c:345631-345652).
        m = self.walking(walker)
        walker.set_heading(heading)
        m.handle_move_to_position()
        assert m.aux_command == aux
        # The interpreter plays TurnLeft as TurnRight at negative speed (adjust_motion).
        state = walker.movement_manager.motion_interpreter.interpreted_state
        assert state.turn_command == TURN_RIGHT
        assert (state.turn_speed > 0) == (aux == TURN_RIGHT)

    @pytest.mark.parametrize("heading", [341.0, 10.0, 0.0])
    def test_error_within_20_degrees_does_not_turn(self, walker: PhysicsObj, heading: float) -> None:
        # error 19, 350 (>= 340) and 0: no aux command (acclient.c:345636-345640).
        m = self.walking(walker)
        walker.set_heading(heading)
        m.handle_move_to_position()
        assert m.aux_command == 0
        assert walker.movement_manager.motion_interpreter.interpreted_state.turn_command == 0

    def test_pending_motions_stop_the_turn(self, walker: PhysicsObj) -> None:
        # With motions pending the aux turn is stopped whatever the error (acclient.c:345618-345624).
        m = self.walking(walker)
        walker.set_heading(300.0)
        m.handle_move_to_position()
        assert m.aux_command == TURN_RIGHT and walker.motions_pending()
        m.handle_move_to_position()
        assert m.aux_command == 0

    def test_back_within_tolerance_stops_the_turn_without_snapping(self, walker: PhysicsObj) -> None:
        # Error 355 with TurnRight running: _StopMotion(aux), aux = 0 (acclient.c:345638-345643); the heading
        # is left as it is. ACE also snaps the heading to the bearing here (a server-tick-rate addition).
        m = self.walking(walker)
        walker.set_heading(300.0)
        m.handle_move_to_position()
        walker.part_array.handle_movement()  # the motion table completes the turn; nothing is pending
        assert m.aux_command == TURN_RIGHT and not walker.motions_pending()
        walker.set_heading(5.0)
        m.handle_move_to_position()
        assert m.aux_command == 0
        assert walker.position.frame.get_heading() == pytest.approx(5.0)
        assert walker.movement_manager.motion_interpreter.interpreted_state.turn_command == 0


class TestArrival:
    def test_towards_arrives_within_distance_to_object(self, walker: PhysicsObj) -> None:
        # !moving_away and dist <= distance_to_object -> drop node, stop, BeginNextNode
        # (acclient.c:345669-345689).
        m = move_to(walker, 96.0, 106.0)
        teleport(walker, 96.0, 105.5)
        m.handle_move_to_position()
        assert m.movement_type == MovementType.INVALID and m.current_command == 0

    def test_towards_not_yet_there(self, walker: PhysicsObj) -> None:
        m = move_to(walker, 96.0, 106.0)
        teleport(walker, 96.0, 105.3)  # 0.7 > 0.6 (acclient.c:345688)
        m.handle_move_to_position()
        assert m.movement_type == MovementType.MOVE_TO_POSITION and m.current_command == WALK_FORWARD

    def test_away_arrives_at_min_distance(self, walker: PhysicsObj) -> None:
        # MOVE_AWAY only, 1 m off, min_distance 3: WalkForward with moving_away (acclient.c:346206-346209);
        # done once dist >= min_distance (acclient.c:345665-345668).
        m = move_to(walker, 96.0, 97.0, MovementFlags.MOVE_AWAY | MovementFlags.CAN_WALK, min_distance=3.0)
        assert (m.current_command, m.moving_away) == (WALK_FORWARD, True)
        teleport(walker, 96.0, 94.5)  # 2.5 m: still going
        m.handle_move_to_position()
        assert m.is_moving_to()
        teleport(walker, 96.0, 93.5)  # 3.5 m: there
        m.handle_move_to_position()
        assert not m.is_moving_to()

    def test_away_steers_to_face_away(self, walker: PhysicsObj) -> None:
        # Moving away the wanted heading is bearing + 180 (get_desired_heading, acclient.c:345627); facing the
        # target that is an error of exactly 180 -> TurnLeft (acclient.c:345647-345648).
        m = move_to(walker, 96.0, 97.0, MovementFlags.MOVE_AWAY | MovementFlags.CAN_WALK, min_distance=3.0)
        tick(walker)
        walker.set_heading(0.0)
        m.handle_move_to_position()
        assert m.aux_command == TURN_LEFT

    def test_beyond_fail_distance_cancels(self, walker: PhysicsObj) -> None:
        # Not arrived and more than fail_distance from the start: CancelMoveTo(0x3D)
        # (acclient.c:345691-345692).
        m = move_to(walker, 96.0, 106.0, fail_distance=2.0)
        teleport(walker, 99.0, 96.0)
        m.handle_move_to_position()
        assert not m.is_moving_to() and m.pending_actions == []

    def test_within_fail_distance_carries_on(self, walker: PhysicsObj) -> None:
        m = move_to(walker, 96.0, 106.0, fail_distance=5.0)
        teleport(walker, 99.0, 96.0)
        m.handle_move_to_position()
        assert m.is_moving_to()

    def test_arrival_is_only_checked_when_progress_is_made(self, walker: PhysicsObj, world: World) -> None:
        # CheckProgressMade fails -> only ++fail_progress_count, no arrival test (acclient.c:345656-345660).
        m = move_to(walker, 96.0, 106.0)
        tick(walker)  # no motion pending, so the stalled tick is counted (acclient.c:345658)
        teleport(walker, 96.0, 105.5)  # within 0.6 ...
        m.previous_distance = 0.3  # ... but farther than the last sample, over 1 s ago
        world.cur_time += 1.5
        m.handle_move_to_position()
        assert m.is_moving_to()
        assert m.fail_progress_count == 1


class TestTurnToHeading:
    def turn(self, body: PhysicsObj, heading: float) -> MoveToManager:
        p = MovementParameters()
        p.desired_heading = heading
        body.movement_manager.perform_movement(MovementStruct(MovementType.TURN_TO_HEADING, params=p))
        return body.movement_manager.moveto_manager

    def test_turns_right_and_lands_exactly_on_the_heading(self, walker: PhysicsObj) -> None:
        # heading_diff(90, 0, TurnRight) = 90 <= 180 -> TurnRight, previous_heading = 90 (the diff)
        # (acclient.c:345484-345489, 345516). ACE's TurnToHeading never starts the node.
        m = self.turn(walker, 90.0)
        assert m.current_command == TURN_RIGHT
        assert m.previous_heading == pytest.approx(90.0)
        for _ in range(60):
            tick(walker)
            if not m.is_moving_to():
                break
        # heading_greater -> set_heading(node heading), stop the turn, next node (acclient.c:345740-345748).
        assert not m.is_moving_to()
        # The heading of the float32 quaternion set_heading(90) stores: within 1e-5 degrees.
        assert walker.position.frame.get_heading() == pytest.approx(90.0, abs=1e-5)
        assert walker.movement_manager.motion_interpreter.interpreted_state.turn_command == 0

    def test_more_than_180_turns_left(self, walker: PhysicsObj) -> None:
        # heading_diff(270, 0, TurnRight) = 270 > 180 and 270 + EPSILON < 360 -> TurnLeft
        # (acclient.c:345497-345499).
        m = self.turn(walker, 270.0)
        assert m.current_command == TURN_LEFT

    def test_within_epsilon_is_done_at_once(self, walker: PhysicsObj) -> None:
        # heading_diff within EPSILON is 0 -> RemovePendingActionsHead, BeginNextNode: finished
        # (acclient.c:345492-345494).
        m = self.turn(walker, 0.0001)
        assert not m.is_moving_to() and m.current_command == 0

    def test_waits_while_motions_are_pending(self, walker: PhysicsObj) -> None:
        # BeginTurnToHeading returns while motions are pending (acclient.c:345480-345481).
        walker.movement_manager.get_minterp().add_to_queue(0, READY, 0)
        m = self.turn(walker, 90.0)
        assert m.current_command == 0 and m.is_moving_to()


class TestUseTime:
    def test_only_while_in_contact(self, walker: PhysicsObj) -> None:
        # UseTime services the head node only with CONTACT_TS (acclient.c:346027).
        m = move_to(walker, 96.0, 106.0)
        teleport(walker, 96.0, 105.5)
        walker.transient_state &= ~TransientState.CONTACT
        m.use_time()
        assert m.is_moving_to()
        walker.transient_state |= TransientState.CONTACT
        m.use_time()
        assert not m.is_moving_to()

    def test_waits_for_the_target_of_a_move_to_object(self, walker: PhysicsObj) -> None:
        # !top_level_object_id || movement_type == Invalid || initialized (acclient.c:346032).
        # ACE tests `top_level != 0 || type != Invalid || initialized`, which would run this node.
        m = move_to(walker, 96.0, 106.0)
        teleport(walker, 96.0, 105.5)
        m.top_level_object_id = 0x50000002
        m.initialized = False
        m.use_time()
        assert m.is_moving_to()
        m.initialized = True
        m.use_time()
        assert not m.is_moving_to()


def test_final_heading_comes_from_the_request(walker: PhysicsObj) -> None:
    # MoveToPosition tests the argument's USE_FINAL_HEADING (acclient.c:345835-345836) and clears STICKY on
    # its copy (acclient.c:345853). ACE reads the manager's old parameters for the final-heading test.
    walker.set_heading(90.0)
    flags = NO_SPHERES | MovementFlags.USE_FINAL_HEADING | MovementFlags.STICKY
    m = move_to(walker, 96.0, 106.0, flags, desired_heading=45.0)
    assert [(n.type, n.heading) for n in m.pending_actions] == [
        (MovementType.TURN_TO_HEADING, pytest.approx(0.0)),
        (MovementType.MOVE_TO_POSITION, 0.0),
        (MovementType.TURN_TO_HEADING, 45.0),
    ]
    assert m.current_command == TURN_LEFT  # 0 - 90 -> heading_diff 270 > 180
    assert not m.movement_params.flags & MovementFlags.STICKY


class TestMoveToObject:
    TARGET = 0x50000002

    @pytest.fixture
    def tracked(self, walker: PhysicsObj) -> PhysicsObj:
        walker.id = 0x50000001
        walker.target_manager = RecordingTargetManager()
        walker.position_manager = RecordingPositionManager()
        return walker

    def start(self, body: PhysicsObj) -> MoveToManager:
        ms = MovementStruct(
            MovementType.MOVE_TO_OBJECT,
            object_id=self.TARGET,
            top_level_id=self.TARGET,
            radius=0.4,
            height=1.5,
            params=params(MovementFlags(0x1EE0F) | MovementFlags.STICKY),
        )
        body.movement_manager.perform_movement(ms)
        return body.movement_manager.moveto_manager

    def report(self, m: MoveToManager, status: int = 1) -> None:
        there = pos(96.0, 106.0, 50.0)
        m.handle_update_target(TargetInfo(self.TARGET, status, there, there.copy()))

    def test_asks_the_target_manager_then_waits(self, tracked: PhysicsObj) -> None:
        # PerformMovement unsticks (acclient.c:346126); MoveToObject: set_target(0, top_level, 0.5, 0.0) and
        # no nodes until the target reports (acclient.c:345218-345222).
        m = self.start(tracked)
        assert tracked.position_manager.calls == [("unstick",)]
        assert tracked.target_manager.calls == [("set_target", 0, self.TARGET, 0.5, 0.0)]
        assert m.movement_type == MovementType.MOVE_TO_OBJECT and m.pending_actions == []

    def test_first_report_starts_the_walk(self, tracked: PhysicsObj) -> None:
        # Status OK before initialized -> MoveToObject_Internal: turn + move nodes, BeginNextNode
        # (acclient.c:346095-346099).
        m = self.start(tracked)
        self.report(m)
        assert m.initialized is True
        assert m.current_command == WALK_FORWARD
        assert [n.type for n in m.pending_actions] == [MovementType.MOVE_TO_POSITION]

    def test_bad_first_report_cancels(self, tracked: PhysicsObj) -> None:
        # Status not OK before initialized -> CancelMoveTo(0x38) (acclient.c:346108).
        m = self.start(tracked)
        self.report(m, status=2)
        assert not m.is_moving_to()

    def test_bad_later_report_cancels(self, tracked: PhysicsObj) -> None:
        # Initialized and status not OK -> CancelMoveTo(0x37) (acclient.c:346086).
        m = self.start(tracked)
        self.report(m)
        self.report(m, status=2)
        assert not m.is_moving_to()

    def test_sticky_arrival_sticks_to_the_object(self, tracked: PhysicsObj) -> None:
        # USE_SPHERES: cylinder distance 0.9 - (0 + 0.4) = 0.5 <= 0.6 -> arrived; no nodes left and STICKY ->
        # CleanUp (clear_target), StopCompletely, StickTo(top_level, radius, height)
        # (acclient.c:345557-345565).
        m = self.start(tracked)
        self.report(m)
        teleport(tracked, 96.0, 105.1)
        m.handle_move_to_position()
        assert not m.is_moving_to()
        assert tracked.target_manager.calls[-1] == ("clear_target",)
        # The radius and height travel as float fields (sought_object_radius/height, the float locals
        # old_object_radius/height, acclient.c:345557-345565).
        assert tracked.position_manager.calls[-1] == ("stick_to", self.TARGET, f32(0.4), f32(1.5))

    def test_retunes_the_target_quantum(self, tracked: PhysicsObj) -> None:
        # Tracking and |v| = 2 > 0.1: time = dist / |v| with dist the cylinder distance, 5 m less the
        # target's 0.4 and the body's 0.48 radius: (5 - 0.4 - 0.48) / 2 = 2.06, more than 1 s off the
        # target quantum 0 -> set_target_quantum (acclient.c:345694-345704). The speed is that of
        # CPhysicsObj::get_velocity, which is cached_velocity (acclient.c:318565), not m_velocityVector.
        m = self.start(tracked)
        self.report(m)
        teleport(tracked, 96.0, 101.0)
        tracked.cached_velocity = Vector3(0.0, 2.0, 0.0)
        m.handle_move_to_position()
        assert tracked.target_manager.calls[-1] == ("set_target_quantum", pytest.approx(2.06))

    def test_moving_to_oneself_ends_at_once(self, tracked: PhysicsObj) -> None:
        # top_level_id == the body's id: no set_target; CleanUp (which clears the target, since top_level and
        # movement_type are set) and StopCompletely (acclient.c:345218-345223, 345236-345238, 345164-345165).
        ms = MovementStruct(MovementType.MOVE_TO_OBJECT, object_id=0x50000001, top_level_id=0x50000001)
        tracked.movement_manager.perform_movement(ms)
        assert not tracked.movement_manager.is_moving_to()
        assert tracked.target_manager.calls == [("clear_target",)]
