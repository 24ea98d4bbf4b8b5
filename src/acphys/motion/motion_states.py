"""The two motion states the interpreter keeps: what was asked (raw) and what plays (interpreted).

``RawMotionState`` holds the commands as the user gave them (hold keys, left
and backwards as given); ``InterpretedMotionState`` holds them after
``CMotionInterp::adjust_motion``. Both carry a queue of actions.
"""

from __future__ import annotations

from acphys.motion.commands import (
    ACTION_MASK,
    NON_COMBAT,
    READY,
    RUN_FORWARD,
    SIDE_STEP_LEFT,
    SIDE_STEP_RIGHT,
    STYLE_MASK,
    SUBSTATE_MASK,
    TURN_LEFT,
    TURN_RIGHT,
)
from acphys.motion.movement import HoldKey, MovementFlags, MovementParameters
from acphys.precision import f32

MF = MovementFlags


class ActionNode:
    """One queued action (a one-shot animation) of a motion state; ``speed`` is a ``float`` field.

    Retail: ActionNode (acclient.h:46465)
    """

    __slots__ = ("action", "autonomous", "speed", "stamp")

    def __init__(self, action: int, speed: float, stamp: int, autonomous: bool) -> None:
        self.action = action
        self.speed = f32(speed)
        self.stamp = stamp
        self.autonomous = autonomous

    def copy(self) -> ActionNode:
        return ActionNode(self.action, self.speed, self.stamp, self.autonomous)


class MotionNode:
    """A motion the interpreter sent to the motion table and waits to see completed.

    Retail: CMotionInterp::MotionNode (acclient.h:53293)
    """

    __slots__ = ("context_id", "jump_error_code", "motion")

    def __init__(self, context_id: int, motion: int, jump_error_code: int) -> None:
        self.context_id = context_id
        self.motion = motion
        self.jump_error_code = jump_error_code


class RawMotionState:
    """The motion as commanded, before canonicalization, with the hold key of each channel.

    Retail: RawMotionState::RawMotionState @ 0x0051E7F0 (acclient.c:332561)
    """

    __slots__ = (
        "actions",
        "current_holdkey",
        "current_style",
        "forward_command",
        "forward_holdkey",
        "forward_speed",
        "sidestep_command",
        "sidestep_holdkey",
        "sidestep_speed",
        "turn_command",
        "turn_holdkey",
        "turn_speed",
    )

    def __init__(self) -> None:
        self.actions: list[ActionNode] = []
        self.current_holdkey = HoldKey.NONE
        self.current_style = NON_COMBAT
        self.forward_command = READY
        self.forward_holdkey = HoldKey.INVALID
        self.forward_speed = 1.0
        self.sidestep_command = 0
        self.sidestep_holdkey = HoldKey.INVALID
        self.sidestep_speed = 1.0
        self.turn_command = 0
        self.turn_holdkey = HoldKey.INVALID
        self.turn_speed = 1.0

    def copy(self) -> RawMotionState:
        """A deep copy (actions included).

        Retail: RawMotionState::operator= @ 0x0051EC60 (acclient.c:332923)
        """
        other = RawMotionState()
        for name in RawMotionState.__slots__:
            setattr(other, name, getattr(self, name))
        other.actions = [a.copy() for a in self.actions]
        return other

    def add_action(self, action: int, speed: float, stamp: int, autonomous: bool) -> None:
        """Retail: RawMotionState::AddAction @ 0x0051E840 (acclient.c:332581)"""
        self.actions.append(ActionNode(action, speed, stamp, autonomous))

    def remove_action(self) -> int:
        """Drop the oldest action and return its id (0 when there is none).

        Retail: RawMotionState::RemoveAction @ 0x0051E8A0 (acclient.c:332615)
        """
        return self.actions.pop(0).action if self.actions else 0

    def apply_motion(self, motion: int, params: MovementParameters) -> None:
        """Record a commanded motion in its channel.

        Sidesteps and turns (either direction) take the sidestep/turn channel,
        substates the forward channel (except ``RunForward``, which is never a
        raw command), actions are queued and a new style resets forward to
        Ready. A channel's hold key is ``params.hold_key_to_apply``, or
        ``INVALID`` (follow the current hold key) when the parameters set the
        hold key themselves.

        Retail: RawMotionState::ApplyMotion @ 0x0051EB60 (acclient.c:332851)
        """
        holdkey = HoldKey.INVALID if params.has(MF.SET_HOLD_KEY) else params.hold_key_to_apply
        if motion in (SIDE_STEP_RIGHT, SIDE_STEP_LEFT):
            self.sidestep_command = motion
            self.sidestep_holdkey = holdkey
            self.sidestep_speed = params.speed
        elif motion in (TURN_RIGHT, TURN_LEFT):
            self.turn_command = motion
            self.turn_holdkey = holdkey
            self.turn_speed = params.speed
        elif motion & SUBSTATE_MASK:
            if motion != RUN_FORWARD:
                self.forward_command = motion
                self.forward_holdkey = holdkey
                self.forward_speed = params.speed
        elif not motion & STYLE_MASK:
            if motion & ACTION_MASK:
                self.add_action(motion, params.speed, params.action_stamp, params.has(MF.AUTONOMOUS))
        elif self.current_style != motion:
            self.forward_command = READY
            self.current_style = motion

    def remove_motion(self, motion: int) -> None:
        """Stop a commanded motion: clear its channel (forward goes back to Ready at speed 1).

        Retail: RawMotionState::RemoveMotion @ 0x0051E6E0 (acclient.c:332494)
        """
        if motion in (SIDE_STEP_RIGHT, SIDE_STEP_LEFT):
            self.sidestep_command = 0
        elif motion in (TURN_RIGHT, TURN_LEFT):
            self.turn_command = 0
        elif motion & SUBSTATE_MASK:
            if motion == self.forward_command:
                self.forward_command = READY
                self.forward_speed = 1.0
        elif motion & STYLE_MASK and motion == self.current_style:
            self.current_style = NON_COMBAT


class InterpretedMotionState:
    """The canonical motion the motion table plays: style, forward, sidestep, turn and actions.

    Retail: InterpretedMotionState::InterpretedMotionState @ 0x0051E8D0 (acclient.c:332641)
    """

    __slots__ = (
        "actions",
        "current_style",
        "forward_command",
        "forward_speed",
        "sidestep_command",
        "sidestep_speed",
        "turn_command",
        "turn_speed",
    )

    def __init__(self) -> None:
        self.current_style = NON_COMBAT
        self.forward_command = READY
        self.forward_speed = 1.0
        self.sidestep_command = 0
        self.sidestep_speed = 1.0
        self.turn_command = 0
        self.turn_speed = 1.0
        self.actions: list[ActionNode] = []

    def copy(self) -> InterpretedMotionState:
        """A deep copy (actions included).

        Retail: InterpretedMotionState::operator= @ 0x0051E950 (acclient.c:332682)
        """
        other = InterpretedMotionState()
        other.copy_movement_from(self)
        other.actions = [a.copy() for a in self.actions]
        return other

    def copy_movement_from(self, rhs: InterpretedMotionState) -> None:
        """Take ``rhs``'s style and channels, keeping this state's actions.

        Retail: InterpretedMotionState::copy_movement_from @ 0x0051E750 (acclient.c:332524)
        """
        self.current_style = rhs.current_style
        self.forward_command = rhs.forward_command
        self.forward_speed = rhs.forward_speed
        self.sidestep_command = rhs.sidestep_command
        self.sidestep_speed = rhs.sidestep_speed
        self.turn_command = rhs.turn_command
        self.turn_speed = rhs.turn_speed

    def add_action(self, action: int, speed: float, stamp: int, autonomous: bool) -> None:
        """Retail: InterpretedMotionState::AddAction @ 0x0051E9E0 (acclient.c:332724)"""
        self.actions.append(ActionNode(action, speed, stamp, autonomous))

    def remove_action(self) -> int:
        """Drop the oldest action and return its id (0 when there is none).

        Retail: InterpretedMotionState::RemoveAction @ 0x0051EAD0 (acclient.c:332788)
        """
        return self.actions.pop(0).action if self.actions else 0

    def get_num_actions(self) -> int:
        """Retail: InterpretedMotionState::GetNumActions @ 0x0051EB00 (acclient.c:332814)"""
        return len(self.actions)

    def apply_motion(self, motion: int, params: MovementParameters) -> None:
        """Record a canonical motion: only ``TurnRight`` and ``SideStepRight`` reach the side channels.

        Any other substate (``TurnLeft`` included, if one arrives
        uncanonicalized) goes to the forward channel; a style resets forward
        to Ready without comparing with the current style.

        Retail: InterpretedMotionState::ApplyMotion @ 0x0051EA40 (acclient.c:332758)
        """
        if motion == TURN_RIGHT:
            self.turn_command = TURN_RIGHT
            self.turn_speed = params.speed
        elif motion == SIDE_STEP_RIGHT:
            self.sidestep_command = SIDE_STEP_RIGHT
            self.sidestep_speed = params.speed
        elif motion & SUBSTATE_MASK:
            self.forward_command = motion
            self.forward_speed = params.speed
        elif not motion & STYLE_MASK:
            if motion & ACTION_MASK:
                self.add_action(motion, params.speed, params.action_stamp, params.has(MF.AUTONOMOUS))
        else:
            self.forward_command = READY
            self.current_style = motion

    def remove_motion(self, motion: int) -> None:
        """Stop a canonical motion: clear its channel (forward goes back to Ready at speed 1).

        Retail: InterpretedMotionState::RemoveMotion @ 0x0051E790 (acclient.c:332536)
        """
        if motion == TURN_RIGHT:
            self.turn_command = 0
        elif motion == SIDE_STEP_RIGHT:
            self.sidestep_command = 0
        elif motion & SUBSTATE_MASK:
            if motion == self.forward_command:
                self.forward_command = READY
                self.forward_speed = 1.0
        elif motion & STYLE_MASK and motion == self.current_style:
            self.current_style = NON_COMBAT
