"""MovementManager against the retail decompilation (CMovementManager.c).

Bodies carry a small hand-built motion table (Ready, WalkForward, TurnRight) played by the real
motion interpreter, motion-table manager and sequence.
"""

from __future__ import annotations

import math

import pytest

from acphys.flags import TransientState
from acphys.math.vector import Vector3
from acphys.motion.animation import Animation, AnimData, AnimFrame
from acphys.motion.commands import NON_COMBAT, READY, TURN_RIGHT, WALK_FORWARD
from acphys.motion.interp import MotionInterp
from acphys.motion.motion_table import DEFAULT_SUBSTATE_ONLY, MotionData, MotionTable, cycle_key
from acphys.motion.move_to import MoveToManager
from acphys.motion.movement import MovementError, MovementParameters, MovementStruct, MovementType
from acphys.motion.movement_manager import MovementManager
from acphys.physics_obj import PhysicsObj
from acphys.world.world import World
from support import LANDBLOCK, place


def _cycle(velocity: Vector3 | None = None, omega: Vector3 | None = None, bitfield: int = 0) -> MotionData:
    from acphys.math.frame import Frame

    animation = Animation([AnimFrame([Frame()]) for _ in range(30)])
    return MotionData([AnimData(animation, framerate=30.0)], velocity, omega, bitfield)


def small_table() -> MotionTable:
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


@pytest.fixture
def body(world: World) -> PhysicsObj:
    """A grounded body whose part array has the table but which has no movement manager yet."""
    world.set_flat_ground(LANDBLOCK, 50.0)
    obj = place(world, on_ground=True)
    obj.part_array.set_motion_table(small_table())
    return obj


def test_create_makes_neither_engine(body: PhysicsObj) -> None:
    # MovementManager::Create zeroes both pointers (acclient.c:339145-339148); ACE's constructor builds both.
    manager = MovementManager(body)
    assert manager.motion_interpreter is None
    assert manager.moveto_manager is None
    # Without the engines the queries answer "no" (acclient.c:339316, 339325).
    assert manager.is_moving_to() is False
    assert manager.motions_pending() is False


@pytest.mark.parametrize(
    ("ms_type", "motion", "channel", "expected"),
    [
        (MovementType.RAW_COMMAND, WALK_FORWARD, "raw", WALK_FORWARD),
        (MovementType.INTERPRETED_COMMAND, WALK_FORWARD, "interpreted", WALK_FORWARD),
        (MovementType.STOP_COMPLETELY, 0, "interpreted", READY),
    ],
)
def test_types_1_to_5_go_to_the_motion_interpreter(
    body: PhysicsObj, ms_type: MovementType, motion: int, channel: str, expected: int
) -> None:
    # case 1..5: create the interpreter (enter_default_state when there is a body), then
    # CMotionInterp::PerformMovement (acclient.c:339192-339200).
    manager = MovementManager(body)
    assert manager.perform_movement(MovementStruct(ms_type, motion)) == 0
    assert isinstance(manager.motion_interpreter, MotionInterp)
    assert manager.moveto_manager is None
    minterp = manager.motion_interpreter
    state = minterp.raw_state if channel == "raw" else minterp.interpreted_state
    assert state.forward_command == expected


@pytest.mark.parametrize(
    ("ms_type", "expected"),
    [
        (MovementType.TURN_TO_HEADING, MovementType.TURN_TO_HEADING),
        (MovementType.MOVE_TO_POSITION, MovementType.MOVE_TO_POSITION),
    ],
)
def test_types_6_to_9_go_to_the_move_to_manager(
    body: PhysicsObj, ms_type: MovementType, expected: MovementType
) -> None:
    # case 6..9: create the move-to manager, then MoveToManager::PerformMovement (acclient.c:339206-339211).
    body.movement_manager = manager = MovementManager(body)
    target = body.position.copy()
    target.frame.origin = Vector3(96.0, 106.0, 50.0)
    params = MovementParameters()
    params.desired_heading = 90.0
    assert manager.perform_movement(MovementStruct(ms_type, pos=target, params=params)) == 0
    assert isinstance(manager.moveto_manager, MoveToManager)
    assert manager.moveto_manager.movement_type == expected
    assert manager.is_moving_to() is True


def test_unknown_type_fails_after_activating(body: PhysicsObj) -> None:
    # set_active(1) comes first, then default: 71 = 0x47 (acclient.c:339184, 339213-339214).
    body.transient_state &= ~TransientState.ACTIVE
    manager = MovementManager(body)
    result = manager.perform_movement(MovementStruct(MovementType.INVALID))
    assert result == MovementError.GENERAL_MOVEMENT_FAILURE
    assert body.transient_state & TransientState.ACTIVE
    assert manager.motion_interpreter is None and manager.moveto_manager is None


def test_get_minterp_enters_the_default_state_once_made(body: PhysicsObj) -> None:
    # A new interpreter gets enter_default_state when the manager has a body (acclient.c:339337-339343):
    # that queues a Ready, so a motion is pending straight away.
    manager = MovementManager(body)
    minterp = manager.get_minterp()
    assert minterp.initted is True
    assert manager.motions_pending() is True
    assert manager.get_minterp() is minterp


def test_get_minterp_without_a_body_skips_the_default_state() -> None:
    # `if ( v3 )` guards enter_default_state on the physics object (acclient.c:339342-339343).
    manager = MovementManager(None)
    assert manager.get_minterp().initted is False


def test_enter_default_state_needs_a_body() -> None:
    # Nothing at all without a physics object (acclient.c:339259).
    manager = MovementManager(None)
    manager.enter_default_state()
    assert manager.motion_interpreter is None


def test_motion_done_reaches_the_interpreter(body: PhysicsObj) -> None:
    # MotionDone forwards success only; the interpreter retires its oldest pending motion
    # (acclient.c:339354-339355).
    manager = MovementManager(body)
    pending = manager.get_minterp().pending_motions
    before = [node.motion for node in pending]
    manager.motion_done(0, False)
    assert [node.motion for node in pending] == before[1:]


def test_hit_ground_restarts_the_move_to_node(body: PhysicsObj, world: World) -> None:
    # HitGround: interpreter, then MoveToManager::HitGround -> BeginNextNode
    # (acclient.c:339377-339381, 345572-345573),
    # which re-seeds the progress samples at Timer::cur_time (acclient.c:345427-345433).
    body.movement_manager = manager = MovementManager(body)
    target = body.position.copy()
    target.frame.origin = Vector3(96.0, 106.0, 50.0)
    manager.perform_movement(MovementStruct(MovementType.MOVE_TO_POSITION, pos=target))
    world.cur_time = 4.0
    manager.hit_ground()
    assert manager.moveto_manager.original_distance_time == 4.0
    assert manager.moveto_manager.previous_distance_time == 4.0


def test_leave_ground_leaves_the_move_to_alone(body: PhysicsObj, world: World) -> None:
    # LeaveGround calls only an empty function on the move-to manager (acclient.c:339395-339397).
    body.movement_manager = manager = MovementManager(body)
    target = body.position.copy()
    target.frame.origin = Vector3(96.0, 106.0, 50.0)
    manager.perform_movement(MovementStruct(MovementType.MOVE_TO_POSITION, pos=target))
    world.cur_time = 4.0
    manager.leave_ground()
    assert manager.moveto_manager.previous_distance_time == 0.0
    assert manager.is_moving_to() is True


def test_cancel_move_to_ends_the_move(body: PhysicsObj) -> None:
    # CancelMoveTo forwards to MoveToManager::CancelMoveTo (acclient.c:339245-339246).
    body.movement_manager = manager = MovementManager(body)
    manager.cancel_move_to(MovementError.ACTION_CANCELLED)  # no move-to manager: nothing happens
    target = body.position.copy()
    target.frame.origin = Vector3(96.0, 106.0, 50.0)
    manager.perform_movement(MovementStruct(MovementType.MOVE_TO_POSITION, pos=target))
    manager.cancel_move_to(MovementError.ACTION_CANCELLED)
    assert manager.is_moving_to() is False
    assert manager.moveto_manager.pending_actions == []


def test_inquiries_return_the_interpreter_states(body: PhysicsObj) -> None:
    # InqRawMotionState / InqInterpretedMotionState hand out the interpreter's own states
    # (acclient.c:339289, 339308).
    manager = MovementManager(body)
    assert manager.inq_raw_motion_state() is manager.motion_interpreter.raw_state
    assert manager.inq_interpreted_motion_state() is manager.motion_interpreter.interpreted_state


def test_handle_exit_world_retires_every_pending_motion(body: PhysicsObj) -> None:
    # HandleExitWorld -> CMotionInterp::HandleExitWorld, which empties the pending queue
    # (acclient.c:339416-339417).
    manager = MovementManager(body)
    manager.get_minterp()
    assert manager.motions_pending()
    manager.handle_exit_world()
    assert not manager.motions_pending()


def test_use_time_services_the_move_to(body: PhysicsObj) -> None:
    # UseTime -> MoveToManager::UseTime (acclient.c:339364-339365): within distance_to_object the move ends.
    body.movement_manager = manager = MovementManager(body)
    manager.use_time()  # no move-to manager yet: nothing to do
    target = body.position.copy()
    target.frame.origin = Vector3(96.0, 106.0, 50.0)
    manager.perform_movement(MovementStruct(MovementType.MOVE_TO_POSITION, pos=target))
    body.position.frame.origin = Vector3(96.0, 105.9, 50.0)
    manager.use_time()
    assert not manager.is_moving_to()
