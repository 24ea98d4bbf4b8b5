"""Movement requests as retail passes them around: types, parameters, hold keys and error codes.

``MovementStruct`` is what ``MovementManager::PerformMovement`` fans out
(types 1-5 to the motion interpreter, 6-9 to the move-to manager) and what
``MotionTableManager::PerformMovement`` receives from ``CPartArray``.
"""

from __future__ import annotations

import enum
import struct
from dataclasses import dataclass, field

from acphys.math.position import Position
from acphys.precision import f32, pack3, unpack3

_F6 = struct.Struct("6f")


class MovementType(enum.IntEnum):
    """``MovementTypes::Type`` (acclient.h:2856)."""

    INVALID = 0
    RAW_COMMAND = 1
    INTERPRETED_COMMAND = 2
    STOP_RAW_COMMAND = 3
    STOP_INTERPRETED_COMMAND = 4
    STOP_COMPLETELY = 5
    MOVE_TO_OBJECT = 6
    MOVE_TO_POSITION = 7
    TURN_TO_OBJECT = 8
    TURN_TO_HEADING = 9


class HoldKey(enum.IntEnum):
    """``HoldKey`` (acclient.h:3394): whether a motion is held with the run key."""

    INVALID = 0
    NONE = 1
    RUN = 2


class MovementError(enum.IntEnum):
    """The ``WERROR`` codes the movement code returns (0 is success).

    Retail returns bare integers; the names are those of the game protocol's
    error enumeration.
    """

    NONE = 0x00
    NO_ANIMATION_TABLE = 0x07
    NO_PHYSICS_OBJECT = 0x08
    CANT_JUMP_WHILE_IN_THE_AIR = 0x24
    ACTION_CANCELLED = 0x36
    OBJECT_GONE = 0x37
    NO_OBJECT = 0x38
    CANT_GET_THERE = 0x39
    YOU_CHARGED_TOO_FAR = 0x3D
    CANT_CROUCH_IN_COMBAT = 0x3F
    CANT_SIT_IN_COMBAT = 0x40
    CANT_LIE_DOWN_IN_COMBAT = 0x41
    CANT_CHAT_EMOTE_IN_COMBAT = 0x42
    NO_MTABLE_DATA = 0x43
    CANT_CHAT_EMOTE_NOT_STANDING = 0x44
    TOO_MANY_ACTIONS = 0x45
    HIDDEN = 0x46
    GENERAL_MOVEMENT_FAILURE = 0x47
    CANT_JUMP_FROM_THIS_POSITION = 0x48
    CANT_JUMP_LOADED_DOWN = 0x49


class MovementFlags(enum.IntFlag):
    """The ``MovementParameters`` bitfield (acclient.h:31423), least significant bit first."""

    CAN_WALK = 0x1
    CAN_RUN = 0x2
    CAN_SIDESTEP = 0x4
    CAN_WALK_BACKWARDS = 0x8
    CAN_CHARGE = 0x10
    FAIL_WALK = 0x20
    USE_FINAL_HEADING = 0x40
    STICKY = 0x80
    MOVE_AWAY = 0x100
    MOVE_TOWARDS = 0x200
    USE_SPHERES = 0x400
    SET_HOLD_KEY = 0x800
    AUTONOMOUS = 0x1000
    MODIFY_RAW_STATE = 0x2000
    MODIFY_INTERPRETED_STATE = 0x4000
    CANCEL_MOVETO = 0x8000
    STOP_COMPLETELY = 0x10000
    DISABLE_JUMP_DURING_LINK = 0x20000


#: The constructor's bitfield: ``bitfield & 0xFFFDEE0F | 0x1EE0F`` from a zeroed field.
DEFAULT_MOVEMENT_FLAGS = MovementFlags(0x1EE0F)

#: ``fail_distance`` default: FLT_MAX (0x7F7FFFFF).
FLT_MAX = 3.4028234663852886e38


@dataclass
class MovementParameters:
    """How a motion or a move-to is to be carried out.

    The defaults are those of the constructor (``distance_to_object`` is the
    float32 0.6, bits 0x3F19999A). The six distances, heading and speed are
    ``float`` fields (acclient.h:31453): the constructor narrows them to float32,
    and code that assigns one later stores a float32.

    Retail: MovementParameters::MovementParameters @ 0x00524380 (acclient.c:339436)
    """

    flags: MovementFlags = DEFAULT_MOVEMENT_FLAGS
    distance_to_object: float = f32(0.6)
    min_distance: float = 0.0
    desired_heading: float = 0.0
    speed: float = 1.0
    fail_distance: float = FLT_MAX
    walk_run_threshhold: float = 15.0
    context_id: int = 0
    hold_key_to_apply: HoldKey = HoldKey.INVALID
    action_stamp: int = 0

    def __post_init__(self) -> None:
        (
            self.distance_to_object,
            self.min_distance,
            self.desired_heading,
            self.speed,
            self.fail_distance,
            self.walk_run_threshhold,
        ) = _F6.unpack(
            _F6.pack(
                self.distance_to_object,
                self.min_distance,
                self.desired_heading,
                self.speed,
                self.fail_distance,
                self.walk_run_threshhold,
            )
        )

    def has(self, flag: MovementFlags) -> bool:
        """Whether ``flag`` is set in the bitfield (tested on the plain ints: ``IntFlag``'s ``&``
        builds a new flag member, which costs more than the test)."""
        return int(self.flags) & int(flag) != 0

    def copy(self) -> MovementParameters:
        return MovementParameters(
            self.flags,
            self.distance_to_object,
            self.min_distance,
            self.desired_heading,
            self.speed,
            self.fail_distance,
            self.walk_run_threshhold,
            self.context_id,
            self.hold_key_to_apply,
            self.action_stamp,
        )


@dataclass
class MovementStruct:
    """A movement request (acclient.h ``MovementStruct``); ``radius`` and ``height`` are floats."""

    type: MovementType
    motion: int = 0
    object_id: int = 0
    top_level_id: int = 0
    pos: Position = field(default_factory=Position)
    radius: float = 0.0
    height: float = 0.0
    params: MovementParameters = field(default_factory=MovementParameters)

    def __post_init__(self) -> None:
        if self.radius or self.height:  # the motion requests carry neither
            self.radius, self.height, _ = unpack3(pack3(self.radius, self.height, 0.0))
