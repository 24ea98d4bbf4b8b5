"""``MoveToManager``: walking to a point or an object and turning to a heading, one node at a time.

A move-to is a short queue of nodes: "turn to heading H" and "move to the
target position". ``BeginNextNode`` starts the head node by issuing a motion
through the motion interpreter (``TurnRight``/``TurnLeft`` for a turn,
``WalkForward``/``WalkBackwards`` with a hold key for a move); ``UseTime``
then services the head node every tick while the body is in contact with
the ground, steering with an auxiliary turn command when the heading error
exceeds 20 degrees, watching progress, and finishing (or failing) the node.
When the queue is empty the move ends: the commands are stopped, the body
stops completely and, for a sticky move, the position manager sticks it to
the target.

The module also holds the small pure helpers the manager relies on:
``heading_diff``/``heading_greater`` (file-static in retail), the
``MovementParameters`` command choice (``get_command``,
``towards_and_away``, ``get_desired_heading``) and the ``Position`` heading
and distance measures.

Time is retail's ``Timer::cur_time``, which acphys keeps as ``world.cur_time``.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from acphys.constants import EPSILON
from acphys.flags import TransientState
from acphys.managers.target import TargetInfo
from acphys.math.position import Position
from acphys.math.vector import Vector3, compass_heading
from acphys.motion.commands import RUN_FORWARD, TURN_LEFT, TURN_RIGHT, WALK_BACKWARDS, WALK_FORWARD
from acphys.motion.movement import (
    FLT_MAX,
    HoldKey,
    MovementError,
    MovementFlags,
    MovementParameters,
    MovementStruct,
    MovementType,
)
from acphys.precision import f32, pack3, pack4, unpack3, unpack4

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

#: Heading error (degrees) beyond which ``HandleMoveToPosition`` steers with an aux turn (acclient.c:345636).
HEADING_TOLERANCE = 20.0
#: ``CheckProgressMade``: sampling interval (s) and the minimum closing rate (m/s) (acclient.c:344843-344849).
PROGRESS_INTERVAL = 1.0
MIN_CLOSING_RATE = 0.25
#: ``HandleMoveToPosition``: the target quantum is retuned only above this speed (acclient.c:345700).
TARGET_QUANTUM_MIN_SPEED = 0.1
#: ``MoveToObject``/``TurnToObject`` ask the target manager for updates with this radius (acclient.c:345220).
TARGET_RADIUS = 0.5
#: ``TargetStatus::Ok_TargetStatus`` (acclient.h:7267).
TARGET_STATUS_OK = 1


# -- pure helpers ----------------------------------------------------------------------------


def heading_greater(x: float, y: float, motion: int) -> bool:
    """Whether heading ``x`` has passed heading ``y`` when turning with ``motion``.

    Compares along the shorter arc: within 180 degrees ``x > y`` means
    "further clockwise", across the 0/360 seam the comparison flips. For
    ``TurnRight`` the answer is that strict comparison; for any other motion
    it is its negation, so equal headings count as passed when turning left.

    ``x`` and ``y`` are ``float`` parameters.

    Retail: heading_greater @ 0x00528F60 (acclient.c:344714)
    """
    x, y, _ = unpack3(pack3(x, y, 0.0))
    not_greater = x <= y if abs(x - y) <= 180.0 else y <= x
    if motion != TURN_RIGHT:
        return not_greater
    return not not_greater


def heading_diff(x: float, y: float, motion: int) -> float:
    """How far heading ``x`` lies from ``y`` in the turning direction of ``motion``, in [0, 360).

    ``x - y`` with a EPSILON dead zone, wrapped into [0, 360); for any motion
    other than ``TurnRight`` a non-zero result is mirrored to ``360 - d``.

    ``x`` and ``y`` are ``float`` parameters; the difference and the result stay double.

    Retail: heading_diff @ 0x00528FB0 (acclient.c:344737)
    """
    x, y, _ = unpack3(pack3(x, y, 0.0))
    diff = x - y
    if abs(diff) < EPSILON:
        diff = 0.0
    if diff < -EPSILON:
        diff += 360.0
    if diff > EPSILON and motion != TURN_RIGHT:
        diff = 360.0 - diff
    return diff


def _relative_heading(heading: float, current: float) -> float:
    """``heading - current`` with the EPSILON dead zone and the negative side wrapped by +360.

    The inline idiom retail repeats in ``BeginMoveForward``, ``MoveToPosition``,
    ``MoveToObject_Internal`` and ``HandleMoveToPosition`` (e.g. acclient.c:345631-345635).
    """
    diff = heading - current
    if abs(diff) < EPSILON:
        diff = 0.0
    if diff < -EPSILON:
        diff += 360.0
    return diff


def position_heading(p1: Position, p2: Position) -> float:
    """Compass heading (degrees) from ``p1`` to ``p2`` on the horizontal plane; 0 when they coincide.

    Retail: Position::heading @ 0x005A9520 (acclient.c:467050)
    """
    offset = p1.get_offset(p2)
    direction = Vector3(offset.x, offset.y, 0.0)
    if direction.normalize_check_small():
        return 0.0
    return compass_heading(direction.x, direction.y)


def position_distance(p1: Position, p2: Position) -> float:
    """Straight-line distance between two positions, across landblocks.

    Retail: Position::distance @ 0x005A94B0 (acclient.c:467031)
    """
    return p1.get_offset(p2).length()


def cylinder_distance(r1: float, h1: float, p1: Position, r2: float, h2: float, p2: Position) -> float:
    """Distance between two upright cylinders (radius, height, base position).

    ``reach`` is the full 3-D centre distance less both radii; ``gap`` is the
    vertical gap between the lower cylinder's top and the higher one's base.
    Overlapping vertically (``gap <= 0``): ``reach`` when apart, else
    ``-sqrt(gap² + reach²)``. Separated vertically: ``sqrt(gap² + reach²)``
    when also apart horizontally, else ``gap``.

    The decompilation lost the operands of the first compare (an ``fnstsw``
    test of 0x41 on ``gap``); it is read as ``gap <= 0``, the only reading under
    which a vertically separated pair measures its separation.

    The radii and heights are ``float`` parameters and ``reach`` is stored into one
    (``p2a``, acclient.c:467238); the rest stays double.

    Retail: Position::cylinder_distance @ 0x005A97F0 (acclient.c:467220)
    """
    r1, h1, r2, h2 = unpack4(pack4(r1, h1, r2, h2))
    reach = f32(p1.get_offset(p2).length() - (r1 + r2))
    z1 = p1.frame.origin.z
    z2 = p2.frame.origin.z
    gap = z2 - (z1 + h1) if z1 <= z2 else z1 - (z2 + h2)
    if gap <= 0.0:
        return -math.sqrt(gap * gap + reach * reach) if reach <= 0.0 else reach
    return math.sqrt(gap * gap + reach * reach) if reach > 0.0 else gap


def towards_and_away(params: MovementParameters, curr_distance: float) -> tuple[int, bool | None]:
    """Command for a move both towards and away: close in beyond ``distance_to_object``, back off
    inside ``min_distance`` (walking backwards), else nothing.

    Returns ``(command, moving_away)``; ``moving_away`` is None where retail leaves it unwritten.

    Retail: MovementParameters::towards_and_away @ 0x0052A9A0 (acclient.c:346152)
    """
    if curr_distance > params.distance_to_object:
        return WALK_FORWARD, False
    if curr_distance - params.min_distance < EPSILON:
        return WALK_BACKWARDS, True
    return 0, None


def get_command(params: MovementParameters, curr_distance: float) -> tuple[int, HoldKey, bool | None]:
    """The locomotion command for the current distance: ``(command, hold_key, moving_away)``.

    ``MOVE_TOWARDS`` with ``MOVE_AWAY`` goes both ways; ``MOVE_AWAY`` alone
    walks forward (turned away) while nearer than ``min_distance``; otherwise
    walk forward while beyond ``distance_to_object``. Command 0 means "already
    there". The hold key is ``RUN`` when ``CAN_CHARGE``, or when ``CAN_RUN`` and
    either walking is not allowed or the distance beyond ``distance_to_object``
    exceeds ``walk_run_threshhold``; else ``NONE``. ``moving_away`` is None
    where retail leaves it unwritten (only with command 0). Retail also takes
    the heading to the target, and ignores it.

    ``curr_distance`` is a ``float`` parameter.

    Retail: MovementParameters::get_command @ 0x0052AA00 (acclient.c:346174)
    """
    curr_distance = f32(curr_distance)
    flags = params.flags
    moving_away: bool | None = None
    if flags & MovementFlags.MOVE_TOWARDS and flags & MovementFlags.MOVE_AWAY:
        command, moving_away = towards_and_away(params, curr_distance)
    elif flags & MovementFlags.MOVE_AWAY and not flags & MovementFlags.MOVE_TOWARDS:
        if curr_distance < params.min_distance:
            command, moving_away = WALK_FORWARD, True
        else:
            command = 0
    elif curr_distance > params.distance_to_object:
        command, moving_away = WALK_FORWARD, False
    else:
        command = 0
    if flags & MovementFlags.CAN_CHARGE or (
        flags & MovementFlags.CAN_RUN
        and (
            not flags & MovementFlags.CAN_WALK
            or curr_distance - params.distance_to_object > params.walk_run_threshhold
        )
    ):
        return command, HoldKey.RUN, moving_away
    return command, HoldKey.NONE, moving_away


def get_desired_heading(command: int, moving_away: bool) -> float:
    """Heading offset (degrees) from the bearing to the target that ``command`` wants to face.

    Forward (walk or run): 0 towards, 180 away. Backwards: 180 towards, 0 away.

    Retail: MovementParameters::get_desired_heading @ 0x0052AAD0 (acclient.c:346223)
    """
    if command in (RUN_FORWARD, WALK_FORWARD):
        return 180.0 if moving_away else 0.0
    if command == WALK_BACKWARDS:
        return 0.0 if moving_away else 180.0
    return 0.0


def _copy_params(dst: MovementParameters, src: MovementParameters) -> None:
    """Retail's field-by-field copy of a ``MovementParameters`` into the manager's own."""
    dst.flags = src.flags
    dst.distance_to_object = src.distance_to_object
    dst.min_distance = src.min_distance
    dst.desired_heading = src.desired_heading
    dst.speed = src.speed
    dst.fail_distance = src.fail_distance
    dst.walk_run_threshhold = src.walk_run_threshhold
    dst.context_id = src.context_id
    dst.hold_key_to_apply = src.hold_key_to_apply
    dst.action_stamp = src.action_stamp


class MovementNode:
    """One pending action: move to the target position, or turn to ``heading``.

    Retail ``MoveToManager::MovementNode`` (acclient.h): a list link, a type and a ``float`` heading.
    """

    __slots__ = ("heading", "type")

    def __init__(self, type: MovementType, heading: float = 0.0) -> None:
        self.type = type
        self.heading = f32(heading)

    def __repr__(self) -> str:
        return f"MovementNode({self.type.name}, {self.heading})"


def _params_for_motion(hold_key: HoldKey, speed: float = 1.0) -> MovementParameters:
    """Fresh default parameters without ``CANCEL_MOVETO``, with a speed and hold key: what every
    motion the manager issues carries (e.g. acclient.c:345410-345414)."""
    params = MovementParameters()
    params.flags &= ~MovementFlags.CANCEL_MOVETO
    params.speed = speed
    params.hold_key_to_apply = hold_key
    return params


class MoveToManager:
    """Retail ``MoveToManager`` (acclient.h:31473): move-to-position/object and turn-to-heading/object.

    Retail: MoveToManager::Create @ 0x00529470 (acclient.c:345028)
    """

    __slots__ = (
        "aux_command",
        "current_command",
        "current_target_position",
        "fail_progress_count",
        "initialized",
        "movement_params",
        "movement_type",
        "moving_away",
        "original_distance",
        "original_distance_time",
        "pending_actions",
        "physics_obj",
        "previous_distance",
        "previous_distance_time",
        "previous_heading",
        "sought_object_height",
        "sought_object_id",
        "sought_object_radius",
        "sought_position",
        "starting_position",
        "top_level_object_id",
        "weenie_obj",
    )

    def __init__(self, physics_obj: PhysicsObj | None = None, weenie_obj: object | None = None) -> None:
        """Retail: MoveToManager::MoveToManager @ 0x005293B0 (acclient.c:344977)"""
        self.physics_obj = physics_obj
        self.weenie_obj = weenie_obj
        self.sought_position = Position()
        self.current_target_position = Position()
        self.starting_position = Position()
        self.movement_params = MovementParameters()
        self.pending_actions: list[MovementNode] = []
        self.initialize_local_variables()

    def __repr__(self) -> str:
        return f"MoveToManager({self.movement_type.name}, {self.pending_actions!r})"

    # -- bookkeeping -----------------------------------------------------------------------------

    def _now(self) -> float:
        """``Timer::cur_time`` (the world's wall clock); 0 before the manager has a body."""
        return self.physics_obj.world.cur_time if self.physics_obj is not None else 0.0

    def set_physics_object(self, obj: PhysicsObj | None) -> None:
        """Retail: MoveToManager::SetPhysicsObject @ 0x00529240 (acclient.c:344906)"""
        self.physics_obj = obj

    def set_weenie_object(self, wobj: object | None) -> None:
        """Retail: MoveToManager::SetWeenieObject @ 0x00529230 (acclient.c:344900)"""
        self.weenie_obj = wobj

    def initialize_local_variables(self) -> None:
        """Back to idle: no movement, zeroed commands and ids, distances FLT_MAX, clocks now.

        Only ``bitfield`` and ``context_id`` of ``movement_params`` are reset;
        ``starting_position`` and the node list are left alone.

        Retail: MoveToManager::InitializeLocalVariables @ 0x00529250 (acclient.c:344912)
        """
        now = self._now()
        self.movement_type = MovementType.INVALID
        self.movement_params.flags = MovementFlags(0)
        self.movement_params.context_id = 0
        self.previous_distance = FLT_MAX
        self.previous_distance_time = now
        self.original_distance = FLT_MAX
        self.original_distance_time = now
        self.previous_heading = 0.0
        self.fail_progress_count = 0
        self.current_command = 0
        self.aux_command = 0
        self.moving_away = False
        self.initialized = False
        self.sought_position = Position()
        self.current_target_position = Position()
        self.sought_object_id = 0
        self.top_level_object_id = 0
        self.sought_object_radius = 0.0
        self.sought_object_height = 0.0

    def is_moving_to(self) -> bool:
        """Retail: MoveToManager::is_moving_to @ 0x00529220 (acclient.c:344894)"""
        return self.movement_type != MovementType.INVALID

    def add_turn_to_heading_node(self, global_heading: float) -> None:
        """Retail: MoveToManager::AddTurnToHeadingNode @ 0x00529530 (acclient.c:345095)"""
        self.pending_actions.append(MovementNode(MovementType.TURN_TO_HEADING, global_heading))

    def add_move_to_position_node(self) -> None:
        """Retail: MoveToManager::AddMoveToPositionNode @ 0x00529580 (acclient.c:345119)"""
        self.pending_actions.append(MovementNode(MovementType.MOVE_TO_POSITION))

    def remove_pending_actions_head(self) -> None:
        """Retail: MoveToManager::RemovePendingActionsHead @ 0x00529380 (acclient.c:344961)"""
        if self.pending_actions:
            del self.pending_actions[0]

    # -- issuing motions -----------------------------------------------------------------------

    def _do_motion(self, motion: int, params: MovementParameters) -> int:
        """Canonicalise ``motion`` (``adjust_motion``, which rewrites ``params.speed``) and do it
        as an interpreted motion.

        Retail: MoveToManager::_DoMotion @ 0x00529010 (acclient.c:344752)
        """
        if self.physics_obj is None:
            return MovementError.NO_PHYSICS_OBJECT
        minterp = self.physics_obj.get_minterp()
        motion, params.speed = minterp.adjust_motion(motion, params.speed, params.hold_key_to_apply)
        return minterp.do_interpreted_motion(motion, params)

    def _stop_motion(self, motion: int, params: MovementParameters) -> int:
        """As ``_do_motion``, stopping the interpreted motion instead.

        Retail: MoveToManager::_StopMotion @ 0x00529080 (acclient.c:344792)
        """
        if self.physics_obj is None:
            return MovementError.NO_PHYSICS_OBJECT
        minterp = self.physics_obj.get_minterp()
        motion, params.speed = minterp.adjust_motion(motion, params.speed, params.hold_key_to_apply)
        return minterp.stop_interpreted_motion(motion, params)

    # -- measuring -------------------------------------------------------------------------------

    def get_current_distance(self) -> float:
        """Distance to ``current_target_position``: cylinder distance with ``USE_SPHERES``, else
        the plain distance; FLT_MAX without a body.

        Retail: MoveToManager::GetCurrentDistance @ 0x005291B0 (acclient.c:344855)
        """
        obj = self.physics_obj
        if obj is None:
            return FLT_MAX
        if self.movement_params.flags & MovementFlags.USE_SPHERES:
            return cylinder_distance(
                obj.get_radius(),
                obj.get_height(),
                obj.position,
                self.sought_object_radius,
                self.sought_object_height,
                self.current_target_position,
            )
        return position_distance(obj.position, self.current_target_position)

    def check_progress_made(self, curr_distance: float) -> bool:
        """False when, more than 1 s after the last sample, the closing rate since that sample, or
        else since the start, is below 0.25 m/s. A passing sample becomes the new last sample.

        ``curr_distance`` is a ``float`` parameter (stored into ``previous_distance``); the
        rates stay double.

        Retail: MoveToManager::CheckProgressMade @ 0x005290F0 (acclient.c:344832)
        """
        curr_distance = f32(curr_distance)
        now = self._now()
        elapsed = now - self.previous_distance_time
        if elapsed <= PROGRESS_INTERVAL:
            return True
        if self.moving_away:
            closed = curr_distance - self.previous_distance
        else:
            closed = self.previous_distance - curr_distance
        if closed / elapsed < MIN_CLOSING_RATE:
            return False
        self.previous_distance = curr_distance
        self.previous_distance_time = now
        if self.moving_away:
            closed = curr_distance - self.original_distance
        else:
            closed = self.original_distance - curr_distance
        return closed / (now - self.original_distance_time) >= MIN_CLOSING_RATE

    # -- starting a move -----------------------------------------------------------------------

    def perform_movement(self, mvs: MovementStruct) -> int:
        """Cancel any move in progress (0x36), unstick, and start the requested one; always 0.

        Retail: MoveToManager::PerformMovement @ 0x0052A900 (acclient.c:346118)
        """
        self.cancel_move_to(MovementError.ACTION_CANCELLED)
        self.physics_obj.unstick_from_object()
        if mvs.type == MovementType.MOVE_TO_OBJECT:
            self.move_to_object(mvs.object_id, mvs.top_level_id, mvs.radius, mvs.height, mvs.params)
        elif mvs.type == MovementType.MOVE_TO_POSITION:
            self.move_to_position(mvs.pos, mvs.params)
        elif mvs.type == MovementType.TURN_TO_OBJECT:
            self.turn_to_object(mvs.object_id, mvs.top_level_id, mvs.params)
        elif mvs.type == MovementType.TURN_TO_HEADING:
            self.turn_to_heading(mvs.params)
        return MovementError.NONE

    def move_to_position(self, p: Position, params: MovementParameters) -> None:
        """Stop, then queue "turn to face p, walk to p" when not already there, and a final
        turn to ``desired_heading`` with ``USE_FINAL_HEADING``; start the first node.

        The sticky bit is dropped: only a move to an object can stick.

        The distance and the bearing are ``float`` locals (acclient.c:345818, 345831).

        Retail: MoveToManager::MoveToPosition @ 0x0052A240 (acclient.c:345789)
        """
        obj = self.physics_obj
        if obj is None:
            return
        obj.stop_completely()
        self.current_target_position = p.copy()
        self.sought_object_radius = 0.0
        distance = f32(self.get_current_distance())
        bearing = f32(position_heading(obj.position, p))
        command, _, _ = get_command(params, distance)
        if command:
            self.add_turn_to_heading_node(bearing)
            self.add_move_to_position_node()
        if params.flags & MovementFlags.USE_FINAL_HEADING:
            self.add_turn_to_heading_node(params.desired_heading)
        self.sought_position = p.copy()
        self.starting_position = obj.position.copy()
        self.movement_type = MovementType.MOVE_TO_POSITION
        _copy_params(self.movement_params, params)
        self.movement_params.flags &= ~MovementFlags.STICKY
        self.begin_next_node()

    def move_to_object(
        self,
        object_id: int,
        top_level_id: int,
        object_radius: float,
        object_height: float,
        params: MovementParameters,
    ) -> None:
        """Stop, record the sought object, and ask the target manager to track its top-level
        object; the nodes are built when the first target update arrives. Moving to oneself
        ends at once.

        Retail: MoveToManager::MoveToObject @ 0x00529680 (acclient.c:345183)
        """
        obj = self.physics_obj
        if obj is None:
            return
        obj.stop_completely()
        self.starting_position = obj.position.copy()
        self.sought_object_id = object_id
        self.sought_object_radius, self.sought_object_height, _ = unpack3(
            pack3(object_radius, object_height, 0.0)
        )
        self.movement_type = MovementType.MOVE_TO_OBJECT
        self.top_level_object_id = top_level_id
        _copy_params(self.movement_params, params)
        self.initialized = False
        if top_level_id != obj.id:
            obj.set_target(0, self.top_level_object_id, TARGET_RADIUS, 0.0)
            return
        self.clean_up()
        obj.stop_completely()

    def move_to_object_internal(self, target_position: Position, interpolated_position: Position) -> None:
        """First target update of a move to an object: queue "turn to face it, walk to it" when
        not already there and a final turn (bearing + ``desired_heading``) with
        ``USE_FINAL_HEADING``; start the first node.

        The bearing, the distance and the final heading are ``float`` locals; the final
        heading's wrap is decided on the double sum (acclient.c:345879-345898).

        Retail: MoveToManager::MoveToObject_Internal @ 0x0052A400 (acclient.c:345858)
        """
        obj = self.physics_obj
        if obj is None:
            self.cancel_move_to(MovementError.NO_PHYSICS_OBJECT)
            return
        self.sought_position = interpolated_position.copy()
        self.current_target_position = target_position.copy()
        bearing = f32(position_heading(obj.position, interpolated_position))
        distance = f32(self.get_current_distance())
        command, _, _ = get_command(self.movement_params, distance)
        if command:
            self.add_turn_to_heading_node(bearing)
            self.add_move_to_position_node()
        if self.movement_params.flags & MovementFlags.USE_FINAL_HEADING:
            total = bearing + self.movement_params.desired_heading
            final = f32(total)
            if total >= 360.0:
                final = f32(final - 360.0)
            self.add_turn_to_heading_node(final)
        self.initialized = True
        self.begin_next_node()

    def turn_to_object(self, object_id: int, top_level_id: int, params: MovementParameters) -> None:
        """Record the object to face (``desired_heading`` is an offset from its bearing) and ask
        the target manager to track it; turning to oneself ends at once.

        Retail: MoveToManager::TurnToObject @ 0x005297D0 (acclient.c:345241)
        """
        obj = self.physics_obj
        if obj is None:
            self.movement_params.context_id = params.context_id
            return
        if params.flags & MovementFlags.STOP_COMPLETELY:
            obj.stop_completely()
        self.movement_type = MovementType.TURN_TO_OBJECT
        self.sought_object_id = object_id
        self.current_target_position.frame.set_heading(params.desired_heading)
        self.top_level_object_id = top_level_id
        _copy_params(self.movement_params, params)
        if top_level_id != obj.id:
            self.initialized = False
            obj.set_target(0, top_level_id, TARGET_RADIUS, 0.0)
            return
        self.clean_up()
        obj.stop_completely()

    def turn_to_object_internal(self, target_position: Position) -> None:
        """First target update of a turn to an object: queue a turn to (bearing + the heading
        stored in ``sought_position``) mod 360 and start it.

        Retail quirk kept: the offset is read from ``sought_position``'s frame, which
        ``TurnToObject`` never set (it wrote ``current_target_position``'s, then replaced
        that position here).

        The offset and the new heading are ``float`` locals (acclient.c:345923-345924).

        Retail: MoveToManager::TurnToObject_Internal @ 0x0052A550 (acclient.c:345910)
        """
        obj = self.physics_obj
        if obj is None:
            self.cancel_move_to(MovementError.NO_PHYSICS_OBJECT)
            return
        self.current_target_position = target_position.copy()
        offset = f32(self.sought_position.frame.get_heading())
        heading = f32(math.fmod(position_heading(obj.position, self.current_target_position) + offset, 360.0))
        self.sought_position.frame.set_heading(heading)
        self.add_turn_to_heading_node(heading)
        self.initialized = True
        self.begin_next_node()

    def turn_to_heading(self, params: MovementParameters) -> None:
        """Queue a turn to ``params.desired_heading`` and start it (stopping first with
        ``STOP_COMPLETELY``); the sticky bit is dropped.

        Retail: MoveToManager::TurnToHeading @ 0x0052A630 (acclient.c:345953)
        """
        obj = self.physics_obj
        if obj is None:
            self.movement_params.context_id = params.context_id
            return
        if params.flags & MovementFlags.STOP_COMPLETELY:
            obj.stop_completely()
        _copy_params(self.movement_params, params)
        self.movement_params.flags &= ~MovementFlags.STICKY
        self.sought_position.frame.set_heading(params.desired_heading)
        self.movement_type = MovementType.TURN_TO_HEADING
        self.add_turn_to_heading_node(params.desired_heading)
        self.begin_next_node()

    # -- running the nodes -----------------------------------------------------------------------

    def begin_next_node(self) -> None:
        """Start the head node; with none left, finish: clean up, stop completely and, for a
        sticky move, stick to the top-level object through the position manager.

        Retail: MoveToManager::BeginNextNode @ 0x00529CB0 (acclient.c:345520)
        """
        if self.pending_actions:
            node_type = self.pending_actions[0].type
            if node_type == MovementType.MOVE_TO_POSITION:
                self.begin_move_forward()
            elif node_type == MovementType.TURN_TO_HEADING:
                self.begin_turn_to_heading()
            return
        if not self.movement_params.flags & MovementFlags.STICKY:
            self.clean_up()
            if self.physics_obj is not None:
                self.physics_obj.stop_completely()
            return
        height = self.sought_object_height
        radius = self.sought_object_radius
        top_level_id = self.top_level_object_id
        self.clean_up()
        if self.physics_obj is not None:
            self.physics_obj.stop_completely()
        self.physics_obj.get_position_manager().stick_to(top_level_id, radius, height)

    def begin_move_forward(self) -> None:
        """Start the move node: pick the command for the current distance; none means arrived
        (drop the node, go on); else issue it and take the first progress sample.

        The distance is a ``float`` local (acclient.c:345396), stored as both progress samples.

        Retail: MoveToManager::BeginMoveForward @ 0x00529A00 (acclient.c:345370)
        """
        obj = self.physics_obj
        if obj is None:
            self.cancel_move_to(MovementError.NO_PHYSICS_OBJECT)
            return
        distance = f32(self.get_current_distance())
        command, hold_key, moving_away = get_command(self.movement_params, distance)
        if not command:
            self.remove_pending_actions_head()
            self.begin_next_node()
            return
        params = _params_for_motion(hold_key, self.movement_params.speed)
        err = self._do_motion(command, params)
        if err:
            self.cancel_move_to(err)
            return
        now = self._now()
        self.current_command = command
        self.moving_away = bool(moving_away)
        self.movement_params.hold_key_to_apply = hold_key
        self.previous_distance = distance
        self.previous_distance_time = now
        self.original_distance = distance
        self.original_distance_time = now

    def begin_turn_to_heading(self) -> None:
        """Start the turn node (unless animations are still pending): ``TurnRight`` when the
        clockwise difference is within (EPSILON, 180], ``TurnLeft`` when above 180; a
        difference of at most EPSILON finishes the node at once.

        ``previous_heading`` is seeded with the heading *difference*, not a heading, as retail does;
        the difference is double until that ``float`` store.

        Retail: MoveToManager::BeginTurnToHeading @ 0x00529B90 (acclient.c:345455)
        """
        obj = self.physics_obj
        if not self.pending_actions or obj is None:
            self.cancel_move_to(MovementError.NO_PHYSICS_OBJECT)
            return
        if obj.motions_pending():
            return
        diff = heading_diff(self.pending_actions[0].heading, obj.position.frame.get_heading(), TURN_RIGHT)
        if diff <= 180.0:
            if diff <= EPSILON:
                self.remove_pending_actions_head()
                self.begin_next_node()
                return
            command = TURN_RIGHT
        else:
            if diff + EPSILON >= 360.0:
                self.remove_pending_actions_head()
                self.begin_next_node()
                return
            command = TURN_LEFT
        params = _params_for_motion(self.movement_params.hold_key_to_apply, self.movement_params.speed)
        err = self._do_motion(command, params)
        if err:
            self.cancel_move_to(err)
            return
        self.current_command = command
        self.previous_heading = f32(diff)

    def use_time(self) -> None:
        """Service the head node, only while the body has ``CONTACT`` and, for a move to an
        object, only once the target has reported in.

        Retail: MoveToManager::UseTime @ 0x0052A780 (acclient.c:346017)
        """
        obj = self.physics_obj
        if obj is None or not obj._transient_state & TransientState.CONTACT or not self.pending_actions:
            return
        if self.top_level_object_id and self.movement_type != MovementType.INVALID and not self.initialized:
            return
        node_type = self.pending_actions[0].type
        if node_type == MovementType.MOVE_TO_POSITION:
            self.handle_move_to_position()
        elif node_type == MovementType.TURN_TO_HEADING:
            self.handle_turn_to_heading()

    def handle_move_to_position(self) -> None:
        """One tick of the move node.

        Steering: unless animations are pending, face the bearing to the
        target plus the command's desired offset; an error above 20 degrees
        (and below 340) issues ``TurnRight`` (error under 180) or ``TurnLeft``
        as the aux command, a smaller one stops the aux command. Progress:
        when ``check_progress_made`` passes and the distance is within
        ``distance_to_object`` (moving towards) or at least ``min_distance``
        (moving away), the node is done: stop both commands and start the next
        node; otherwise beyond ``fail_distance`` from the start cancels with
        0x3D. Finally, tracking an object, retune the target quantum to the
        time to get there when it differs by more than 1 s.

        The same parameter block serves every motion issued in one tick, so a
        speed rewritten by ``adjust_motion`` carries into the later stops, as in retail.

        The bearing is spilled to a ``float``, the wanted heading and the distance are ``float``
        locals (the wanted heading's wrap is decided on the double sum), the heading error
        stays double (acclient.c:345626-345630, 345655).

        Retail: MoveToManager::HandleMoveToPosition @ 0x00529D80 (acclient.c:345576)
        """
        obj = self.physics_obj
        if obj is None:
            self.cancel_move_to(MovementError.NO_PHYSICS_OBJECT)
            return
        curr_pos = obj.position.copy()
        params = _params_for_motion(self.movement_params.hold_key_to_apply, self.movement_params.speed)
        if obj.motions_pending():
            self._stop_aux_command(params)
        else:
            total = get_desired_heading(self.current_command, self.moving_away) + f32(
                position_heading(curr_pos, self.current_target_position)
            )
            heading = f32(total)
            if total >= 360.0:
                heading = f32(heading - 360.0)
            error = _relative_heading(heading, obj.position.frame.get_heading())
            if error <= HEADING_TOLERANCE or error >= 360.0 - HEADING_TOLERANCE:
                self._stop_aux_command(params)
            else:
                turn = TURN_LEFT if error >= 180.0 else TURN_RIGHT
                if turn != self.aux_command:
                    self._do_motion(turn, params)
                    self.aux_command = turn

        distance = f32(self.get_current_distance())
        if not self.check_progress_made(distance):
            if not obj.is_interpolating() and not obj.motions_pending():
                self.fail_progress_count += 1
        else:
            self.fail_progress_count = 0
            if self.moving_away:
                arrived = distance >= self.movement_params.min_distance
            else:
                arrived = distance <= self.movement_params.distance_to_object
            if arrived:
                self.remove_pending_actions_head()
                self._stop_motion(self.current_command, params)
                self.current_command = 0
                self._stop_aux_command(params)
                self.begin_next_node()
            elif position_distance(self.starting_position, obj.position) > self.movement_params.fail_distance:
                self.cancel_move_to(MovementError.YOU_CHARGED_TOO_FAR)

        if self.top_level_object_id and self.movement_type != MovementType.INVALID:
            speed = obj.get_velocity().length()  # cached_velocity (CPhysicsObj::get_velocity)
            if speed > TARGET_QUANTUM_MIN_SPEED:
                time_to_get_there = distance / speed
                if abs(time_to_get_there - obj.get_target_quantum()) > 1.0:
                    obj.set_target_quantum(time_to_get_there)

    def _stop_aux_command(self, params: MovementParameters) -> None:
        """Stop the aux turn, if any (inline in retail, e.g. acclient.c:345638-345643)."""
        if self.aux_command:
            self._stop_motion(self.aux_command, params)
            self.aux_command = 0

    def handle_turn_to_heading(self) -> None:
        """One tick of the turn node: once the heading has passed the node's heading (in the
        turning direction) snap to it exactly, stop the turn and start the next node; else
        count a stalled tick when the heading did not advance by (EPSILON, 180).

        Without a turn command running, (re)start the node instead. The current heading is a
        ``float`` local (acclient.c:345738), which becomes ``previous_heading``.

        Retail: MoveToManager::HandleTurnToHeading @ 0x0052A0C0 (acclient.c:345711)
        """
        obj = self.physics_obj
        if obj is None:
            self.cancel_move_to(MovementError.NO_PHYSICS_OBJECT)
            return
        if self.current_command not in (TURN_RIGHT, TURN_LEFT):
            self.begin_turn_to_heading()
            return
        node = self.pending_actions[0]
        curr_heading = f32(obj.position.frame.get_heading())
        if heading_greater(curr_heading, node.heading, self.current_command):
            self.fail_progress_count = 0
            obj.set_heading(node.heading)
            self.remove_pending_actions_head()
            params = _params_for_motion(self.movement_params.hold_key_to_apply)
            self._stop_motion(self.current_command, params)
            self.current_command = 0
            self.begin_next_node()
            return
        advanced = heading_diff(curr_heading, self.previous_heading, self.current_command)
        self.previous_heading = curr_heading
        if advanced >= 180.0 or advanced <= EPSILON:
            if not obj.is_interpolating() and not obj.motions_pending():
                self.fail_progress_count += 1
        else:
            self.fail_progress_count = 0

    # -- ending ----------------------------------------------------------------------------------

    def clean_up(self) -> None:
        """Stop the current and aux commands, drop the target, and go idle (the node list stays).

        Retail: MoveToManager::CleanUp @ 0x005295C0 (acclient.c:345142)
        """
        params = _params_for_motion(self.movement_params.hold_key_to_apply)
        obj = self.physics_obj
        if obj is not None:
            if self.current_command:
                self._stop_motion(self.current_command, params)
            if self.aux_command:
                self._stop_motion(self.aux_command, params)
            if self.top_level_object_id and self.movement_type != MovementType.INVALID:
                obj.clear_target()
        self.initialize_local_variables()

    def clean_up_and_call_weenie(self, status: int) -> None:
        """``clean_up`` then stop completely; retail ignores ``status`` on the client.

        Retail: MoveToManager::CleanUpAndCallWeenie @ 0x00529650 (acclient.c:345170)
        """
        self.clean_up()
        if self.physics_obj is not None:
            self.physics_obj.stop_completely()

    def cancel_move_to(self, retval: int) -> None:
        """Abandon a move in progress: drop every node, clean up, stop completely. ``retval``
        (the reason) is not used by the client.

        Retail: MoveToManager::CancelMoveTo @ 0x00529930 (acclient.c:345296)
        """
        if self.movement_type == MovementType.INVALID:
            return
        self.pending_actions.clear()
        self.clean_up()
        if self.physics_obj is not None:
            self.physics_obj.stop_completely()

    def hit_ground(self) -> None:
        """Landing restarts the head node of a move in progress.

        Retail: MoveToManager::HitGround @ 0x00529D70 (acclient.c:345569)
        """
        if self.movement_type != MovementType.INVALID:
            self.begin_next_node()

    def handle_update_target(self, target_info: TargetInfo) -> None:
        """A target-manager report about the tracked object.

        Once started: an OK report of a move to an object re-aims it (and resets
        the progress samples); any other status cancels with 0x37. Before the
        start: a target that is the body itself ends the move where it stands;
        an OK report starts the move (or turn) to the object; any other status
        cancels with 0x38.

        Retail: MoveToManager::HandleUpdateTarget @ 0x0052A7D0 (acclient.c:346050)
        """
        obj = self.physics_obj
        if obj is None:
            self.cancel_move_to(MovementError.NO_PHYSICS_OBJECT)
            return
        if self.top_level_object_id != target_info.object_id:
            return
        if self.initialized:
            if target_info.status != TARGET_STATUS_OK:
                self.cancel_move_to(MovementError.OBJECT_GONE)
            elif self.movement_type == MovementType.MOVE_TO_OBJECT:
                now = self._now()
                self.sought_position = target_info.interpolated_position.copy()
                self.current_target_position = target_info.target_position.copy()
                self.previous_distance = FLT_MAX
                self.previous_distance_time = now
                self.original_distance = FLT_MAX
                self.original_distance_time = now
        elif self.top_level_object_id == obj.id:
            self.sought_position = obj.position.copy()
            self.current_target_position = obj.position.copy()
            self.clean_up_and_call_weenie(MovementError.NONE)
        elif target_info.status == TARGET_STATUS_OK:
            if self.movement_type == MovementType.MOVE_TO_OBJECT:
                self.move_to_object_internal(target_info.target_position, target_info.interpolated_position)
            elif self.movement_type == MovementType.TURN_TO_OBJECT:
                self.turn_to_object_internal(target_info.target_position)
        else:
            self.cancel_move_to(MovementError.NO_OBJECT)
