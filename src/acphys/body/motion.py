"""How commands reach a body's animation: movement requests, the motion table, motion completion."""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import PhysicsState, TransientState, member_namespace
from acphys.math.position import Position
from acphys.motion.movement import MovementError, MovementParameters, MovementStruct, MovementType
from acphys.precision import f32

if TYPE_CHECKING:
    from acphys.motion.interp import MotionInterp
    from acphys.motion.motion_table import MotionTable
    from acphys.motion.movement_manager import MovementManager

PS = member_namespace(PhysicsState)
TS = member_namespace(TransientState)


class Motion:
    """Movement and motion-table requests (part of :class:`PhysicsObj`)."""

    # -- motion: commands in, animation out ------------------------------------------------

    def set_motion_table(self, table: MotionTable | None) -> None:
        """Give the body a motion table; with one comes a movement manager in its default state.

        acphys passes the table where retail passes its DAT id.

        Retail: CPhysicsObj::SetMotionTableID @ 0x00512780 (acclient.c:319692)
        """
        if self.part_array is None:
            raise ValueError(f"body {self.name!r} has no part array to hold a motion table")
        self.part_array.set_motion_table(table)
        self.movement_manager = None
        if table is not None:
            self.make_movement_manager(init_motion=True)

    def make_movement_manager(self, init_motion: bool) -> MovementManager:
        """Create the movement manager if the body has none; a non-static body becomes active.

        Retail: CPhysicsObj::MakeMovementManager @ 0x00510270 (acclient.c:317453)
        """
        if self.movement_manager is None:
            from acphys.motion.movement_manager import MovementManager

            self.movement_manager = MovementManager(self, self.weenie_obj)
            if init_motion:
                self.movement_manager.enter_default_state()
            self._activate_for_movement()
        return self.movement_manager

    def _activate_for_movement(self) -> None:
        """The tail of MakeMovementManager and get_minterp: wake a non-static body."""
        if not self._state & PS.STATIC:
            if not self._transient_state & TS.ACTIVE:
                self.update_time = self.world.cur_time
            self._transient_state |= TS.ACTIVE

    def get_minterp(self) -> MotionInterp:
        """The motion interpreter, creating the movement manager (in its default state) if needed.

        Retail: CPhysicsObj::get_minterp @ 0x005120C0 (acclient.c:319279)
        """
        return self.make_movement_manager(init_motion=True).get_minterp()

    def perform_movement(self, ms: MovementStruct) -> int:
        """Hand a movement request to the movement manager (error 7 without one).

        The common body of DoMotion, StopMotion and StopCompletely, which also
        mark the move as autonomous.

        Retail: CPhysicsObj::DoMotion @ 0x00510020 (acclient.c:317314)
        """
        self.last_move_was_autonomous = True
        if self.movement_manager is None:
            return MovementError.NO_ANIMATION_TABLE
        return self.movement_manager.perform_movement(ms)

    def do_motion(self, motion: int, params: MovementParameters) -> int:
        """Retail: CPhysicsObj::DoMotion @ 0x00510020 (acclient.c:317314)"""
        return self.perform_movement(MovementStruct(MovementType.RAW_COMMAND, motion, params=params))

    def stop_motion(self, motion: int, params: MovementParameters) -> int:
        """Retail: CPhysicsObj::StopMotion @ 0x005100D0 (acclient.c:317353)"""
        return self.perform_movement(MovementStruct(MovementType.STOP_RAW_COMMAND, motion, params=params))

    def stop_completely(self) -> None:
        """Retail: CPhysicsObj::StopCompletely @ 0x00510180 (acclient.c:317392)"""
        if self.movement_manager is not None:
            self.movement_manager.perform_movement(MovementStruct(MovementType.STOP_COMPLETELY))

    def turn_to_heading(self, params: MovementParameters) -> None:
        """Turn to ``params.desired_heading``, creating the movement manager if needed.

        Retail: CPhysicsObj::TurnToHeading @ 0x00512980 (acclient.c:319850)
        """
        manager = self.make_movement_manager(init_motion=True)
        manager.perform_movement(MovementStruct(MovementType.TURN_TO_HEADING, params=params))

    def move_to_position(self, pos: Position, params: MovementParameters) -> int:
        """Walk or run to ``pos``: a MoveToPosition request to the movement manager.

        Retail has no CPhysicsObj wrapper for this request; it is the
        ``MovementStruct`` of type 7 that MovementManager::PerformMovement
        hands to the move-to manager, made the way TurnToHeading makes its own.
        """
        manager = self.make_movement_manager(init_motion=True)
        request = MovementStruct(MovementType.MOVE_TO_POSITION, pos=pos.copy(), params=params)
        return manager.perform_movement(request)

    def move_to_object(self, object_id: int, params: MovementParameters) -> None:
        """Walk or run to the body ``object_id`` (nothing when the world has no such body).

        The movement manager is made first (in its default state, the body woken); the
        request carries the target's radius and height and its top-level object (its
        parent when it is held).

        Retail: CPhysicsObj::MoveToObject @ 0x00512860 (acclient.c:319766)
        """
        self.make_movement_manager(init_motion=True)
        target = self.world.get_object(object_id)
        if target is None:
            return
        height = target.part_array.get_height() if target.part_array is not None else 0.0
        radius = target.part_array.get_radius() if target.part_array is not None else 0.0
        top_level = target.parent if target.parent is not None else target
        self.move_to_object_internal(object_id, top_level.id, radius, height, params)

    def move_to_object_internal(
        self,
        object_id: int,
        top_level_id: int,
        object_radius: float,
        object_height: float,
        params: MovementParameters,
    ) -> None:
        """Hand a MoveToObject request (type 6) to the movement manager, made if needed.

        The radius and height are ``float`` parameters.

        Retail: CPhysicsObj::MoveToObject_Internal @ 0x005102E0 (acclient.c:317482)
        """
        manager = self.make_movement_manager(init_motion=True)
        request = MovementStruct(
            MovementType.MOVE_TO_OBJECT,
            object_id=object_id,
            top_level_id=top_level_id,
            radius=f32(object_radius),
            height=f32(object_height),
            params=params,
        )
        manager.perform_movement(request)

    def turn_to_object(self, object_id: int, params: MovementParameters) -> None:
        """Turn to face the body ``object_id`` (nothing when the world has no such body).

        Retail: CPhysicsObj::TurnToObject @ 0x00512940 (acclient.c:319827)
        """
        target = self.world.get_object(object_id)
        if target is None:
            return
        top_level = target.parent if target.parent is not None else target
        self.turn_to_object_internal(object_id, top_level.id, params)

    def turn_to_object_internal(self, object_id: int, top_level_id: int, params: MovementParameters) -> None:
        """Hand a TurnToObject request (type 8) to the movement manager, made if needed.

        Retail: CPhysicsObj::TurnToObject_Internal @ 0x005103F0 (acclient.c:317532)
        """
        manager = self.make_movement_manager(init_motion=True)
        request = MovementStruct(
            MovementType.TURN_TO_OBJECT, object_id=object_id, top_level_id=top_level_id, params=params
        )
        manager.perform_movement(request)

    def cancel_moveto(self) -> None:
        """Retail: CPhysicsObj::cancel_moveto @ 0x005101F0 (acclient.c:317420)"""
        if self.movement_manager is not None:
            self.movement_manager.cancel_move_to(MovementError.ACTION_CANCELLED)

    def is_moving_to(self) -> bool:
        """Retail: CPhysicsObj::IsMovingTo @ 0x0050EB10 (acclient.c:315821)"""
        return self.movement_manager is not None and self.movement_manager.is_moving_to()

    def motions_pending(self) -> bool:
        """Retail: CPhysicsObj::motions_pending @ 0x0050EAB0 (acclient.c:315778)"""
        return self.movement_manager is not None and self.movement_manager.motions_pending()

    def movement_is_autonomous(self) -> bool:
        """Retail: CPhysicsObj::movement_is_autonomous @ 0x0050EB30 (acclient.c:315830)"""
        return self.last_move_was_autonomous

    def is_fully_constrained(self) -> bool:
        """Retail: CPhysicsObj::IsFullyConstrained @ 0x0050EC60 (acclient.c:315932)"""
        manager = self.position_manager
        return manager is not None and manager.is_fully_constrained()

    def do_interpreted_motion(self, motion: int, params: MovementParameters) -> int:
        """Play ``motion`` through the part array's motion table (error 0x47 without a part array).

        Retail: CPhysicsObj::DoInterpretedMotion @ 0x0050EA70 (acclient.c:315752)
        """
        if self.part_array is None:
            return MovementError.GENERAL_MOVEMENT_FAILURE
        return self.part_array.do_interpreted_motion(motion, params)

    def stop_interpreted_motion(self, motion: int, params: MovementParameters) -> int:
        """Retail: CPhysicsObj::StopInterpretedMotion @ 0x0050EA90 (acclient.c:315765)"""
        if self.part_array is None:
            return MovementError.GENERAL_MOVEMENT_FAILURE
        return self.part_array.stop_interpreted_motion(motion, params)

    def stop_completely_internal(self) -> None:
        """Retail: CPhysicsObj::StopCompletely_Internal @ 0x0050EAD0 (acclient.c:315787)"""
        if self.part_array is not None:
            self.part_array.stop_completely_internal()

    def initialize_motion_tables(self) -> None:
        """Retail: CPhysicsObj::InitializeMotionTables @ 0x0050EA60 (acclient.c:315742)"""
        if self.part_array is not None:
            self.part_array.initialize_motion_tables()

    def remove_link_animations(self) -> None:
        """Drop the sequence's link animations (through ``CPartArray::HandleEnterWorld``).

        Retail: CPhysicsObj::RemoveLinkAnimations @ 0x0050FE20 (acclient.c:317144)
        """
        if self.part_array is not None:
            self.part_array.handle_enter_world()

    def check_for_completed_motions(self) -> None:
        """Retail: CPhysicsObj::CheckForCompletedMotions @ 0x0050FE30 (acclient.c:317154)"""
        if self.part_array is not None:
            self.part_array.check_for_completed_motions()

    def motion_done(self, motion: int, success: bool) -> None:
        """A queued motion finished: tell the movement manager.

        Retail: CPhysicsObj::MotionDone @ 0x0050FDB0 (acclient.c:317096)
        """
        if self.movement_manager is not None:
            self.movement_manager.motion_done(motion, success)

    def set_nodraw(self, no_draw: bool, send_event: bool = False) -> bool:
        """Set or clear ``NODRAW`` (drawing itself is not ported).

        Retail: CPhysicsObj::set_nodraw @ 0x0050FCA0 (acclient.c:317008)
        """
        if no_draw:
            self._state |= PS.NODRAW
        else:
            self._state &= ~PS.NODRAW
        return True
