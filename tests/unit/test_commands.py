"""The retail motion command table and the movement-request defaults."""

from __future__ import annotations

import pytest

from acphys.motion import commands
from acphys.motion.movement import (
    FLT_MAX,
    HoldKey,
    MovementFlags,
    MovementParameters,
)
from acphys.precision import f32


class TestCommandTable:
    def test_the_table_has_all_408_retail_commands_with_distinct_ids(self) -> None:
        # command_strings[408] / command_ids_1[408]: acclient.c:43453 and acclient.c:43864.
        assert len(commands.COMMANDS) == 408
        assert len(commands.MOTION_IDS) == 408
        assert len(commands.MOTION_NAMES) == 408

    @pytest.mark.parametrize(
        ("name", "motion"),
        [
            # Index-aligned pairs of the two retail tables (docs/01-physics.md §5 lists these).
            ("Ready", 0x41000003),
            ("WalkForward", 0x45000005),
            ("WalkBackwards", 0x45000006),
            ("RunForward", 0x44000007),
            ("TurnRight", 0x6500000D),
            ("TurnLeft", 0x6500000E),
            ("SideStepRight", 0x6500000F),
            ("SideStepLeft", 0x65000010),
            ("Falling", 0x40000015),
            ("Jump", 0x2500003B),
            ("NonCombat", 0x8000003D),
        ],
    )
    def test_names_map_to_the_retail_ids(self, name: str, motion: int) -> None:
        assert commands.motion_id(name) == motion
        assert commands.motion_name(motion) == name

    def test_the_named_constants_agree_with_the_table(self) -> None:
        # The constants the code branches on (CMotionInterp::adjust_motion, acclient.c:343746).
        assert commands.MOTION_IDS["TurnLeft"] == commands.TURN_LEFT
        assert commands.MOTION_IDS["WalkBackwards"] == commands.WALK_BACKWARDS
        assert commands.MOTION_IDS["SideStepLeft"] == commands.SIDE_STEP_LEFT
        assert commands.MOTION_IDS["Ready"] == commands.READY

    def test_the_class_bits(self) -> None:
        # GetObjectSequence: 0x80000000 is a style, 0x40000000 a cycle (acclient.c:337699, 337763).
        assert commands.NON_COMBAT & commands.STYLE_MASK
        assert commands.RUN_FORWARD & commands.SUBSTATE_MASK
        assert not commands.RUN_FORWARD & commands.MODIFIER_MASK
        assert commands.TURN_RIGHT & commands.MODIFIER_MASK and commands.TURN_RIGHT & commands.SUBSTATE_MASK

    def test_ids_are_accepted_and_unknowns_rejected(self) -> None:
        assert commands.motion_id(0x44000007) == commands.RUN_FORWARD
        with pytest.raises(KeyError, match="unknown motion 'Sprint'"):
            commands.motion_id("Sprint")
        with pytest.raises(KeyError, match="0x12345678"):
            commands.motion_id(0x12345678)
        assert commands.motion_name(0x12345678) == "0x12345678"


class TestMovementParameters:
    def test_constructor_defaults(self) -> None:
        # MovementParameters::MovementParameters, acclient.c:339436-339458.
        params = MovementParameters()
        assert params.min_distance == 0.0
        assert params.distance_to_object == f32(0.6)  # LODWORD 1058642330 = 0x3F19999A
        assert params.distance_to_object != 0.6
        assert params.fail_distance == FLT_MAX  # LODWORD 2139095039 = 0x7F7FFFFF
        assert params.fail_distance == f32(FLT_MAX)
        assert params.desired_heading == 0.0
        assert params.speed == 1.0  # 1065353216 = 0x3F800000
        assert params.walk_run_threshhold == 15.0  # 1097859072 = 0x41700000
        assert params.context_id == 0 and params.action_stamp == 0
        assert params.hold_key_to_apply == HoldKey.INVALID

    def test_the_default_bitfield(self) -> None:
        # bitfield & 0xFFFDEE0F | 0x1EE0F (acclient.c:339451): walk, run, sidestep, backwards,
        # towards, spheres, set hold key, modify raw + interpreted, cancel moveto, stop completely.
        flags = MovementParameters().flags
        assert int(flags) == 0x1EE0F
        on = [
            MovementFlags.CAN_WALK,
            MovementFlags.CAN_RUN,
            MovementFlags.CAN_SIDESTEP,
            MovementFlags.CAN_WALK_BACKWARDS,
            MovementFlags.MOVE_TOWARDS,
            MovementFlags.USE_SPHERES,
            MovementFlags.SET_HOLD_KEY,
            MovementFlags.MODIFY_RAW_STATE,
            MovementFlags.MODIFY_INTERPRETED_STATE,
            MovementFlags.CANCEL_MOVETO,
            MovementFlags.STOP_COMPLETELY,
        ]
        off = [
            MovementFlags.CAN_CHARGE,
            MovementFlags.FAIL_WALK,
            MovementFlags.USE_FINAL_HEADING,
            MovementFlags.STICKY,
            MovementFlags.MOVE_AWAY,
            MovementFlags.AUTONOMOUS,
            MovementFlags.DISABLE_JUMP_DURING_LINK,
        ]
        assert all(flags & flag for flag in on)
        assert not any(flags & flag for flag in off)

    def test_copy_is_independent(self) -> None:
        params = MovementParameters(speed=2.0)
        clone = params.copy()
        clone.speed = 3.0
        clone.flags |= MovementFlags.STICKY
        assert params.speed == 2.0 and not params.has(MovementFlags.STICKY)
