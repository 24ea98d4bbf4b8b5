"""``MovementManager``: a body's movement front door, fanning requests out to its two engines.

Motion commands (raw and interpreted, their stops, stop-completely: movement
types 1-5) go to the motion interpreter; move-to and turn-to requests (types
6-9) go to the move-to manager. Each engine is created the first time it is
needed; a freshly created motion interpreter enters its default state at once
when the manager has a body. The tick reaches the manager through
``use_time`` (the move-to manager's per-tick work) and the ground-contact
notifications ``hit_ground`` / ``leave_ground``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.flags import member_namespace
from acphys.motion.interp import InterpretedMotionState, MotionInterp, RawMotionState
from acphys.motion.move_to import MoveToManager, TargetInfo
from acphys.motion.movement import MovementError, MovementStruct, MovementType

ME = member_namespace(MovementError)
MT = member_namespace(MovementType)

if TYPE_CHECKING:
    from acphys.physics_obj import PhysicsObj

_MOTION_TYPES = frozenset(
    (
        MT.RAW_COMMAND,
        MT.INTERPRETED_COMMAND,
        MT.STOP_RAW_COMMAND,
        MT.STOP_INTERPRETED_COMMAND,
        MT.STOP_COMPLETELY,
    )
)
_MOVE_TO_TYPES = frozenset(
    (
        MT.MOVE_TO_OBJECT,
        MT.MOVE_TO_POSITION,
        MT.TURN_TO_OBJECT,
        MT.TURN_TO_HEADING,
    )
)


class MovementManager:
    """Retail ``MovementManager``: owns a body's ``MotionInterp`` and ``MoveToManager``, both made on demand.

    Retail: MovementManager::Create @ 0x00524050 (acclient.c:339131)
    """

    __slots__ = ("motion_interpreter", "moveto_manager", "physics_obj", "weenie_obj")

    def __init__(self, physics_obj: PhysicsObj | None = None, weenie_obj: object | None = None) -> None:
        self.motion_interpreter: MotionInterp | None = None
        self.moveto_manager: MoveToManager | None = None
        self.physics_obj = physics_obj
        self.weenie_obj = weenie_obj

    def __repr__(self) -> str:
        return f"MovementManager({self.motion_interpreter!r}, {self.moveto_manager!r})"

    # -- the two engines ---------------------------------------------------------------------------

    def get_minterp(self) -> MotionInterp:
        """The motion interpreter, created (and put in its default state when there is a body) if absent.

        Retail: MovementManager::get_minterp @ 0x005242A0 (acclient.c:339329)
        """
        if self.motion_interpreter is None:
            self.motion_interpreter = MotionInterp(self.physics_obj, self.weenie_obj)
            if self.physics_obj is not None:
                self.motion_interpreter.enter_default_state()
        return self.motion_interpreter

    def make_move_to_manager(self) -> None:
        """Retail: MovementManager::MakeMoveToManager @ 0x00524000 (acclient.c:339100)"""
        if self.moveto_manager is None:
            self.moveto_manager = MoveToManager(self.physics_obj, self.weenie_obj)

    def set_weenie_object(self, weenie_obj: object | None) -> None:
        """Retail: MovementManager::SetWeenieObject @ 0x00524020 (acclient.c:339114)"""
        self.weenie_obj = weenie_obj
        if self.motion_interpreter is not None:
            self.motion_interpreter.set_weenie_object(weenie_obj)
        if self.moveto_manager is not None:
            self.moveto_manager.set_weenie_object(weenie_obj)

    # -- requests ----------------------------------------------------------------------------------

    def perform_movement(self, ms: MovementStruct) -> int:
        """Activate the body, then hand types 1-5 to the motion interpreter and 6-9 to the move-to
        manager; any other type is ``GENERAL_MOVEMENT_FAILURE`` (0x47).

        Retail: MovementManager::PerformMovement @ 0x005240D0 (acclient.c:339174)
        """
        self.physics_obj.set_active(True)
        if ms.type in _MOTION_TYPES:
            return self.get_minterp().perform_movement(ms)
        if ms.type in _MOVE_TO_TYPES:
            self.make_move_to_manager()
            return self.moveto_manager.perform_movement(ms)
        return ME.GENERAL_MOVEMENT_FAILURE

    def move_to_interpreted_state(self, state: InterpretedMotionState) -> None:
        """Retail: MovementManager::move_to_interpreted_state @ 0x00524170 (acclient.c:339220)"""
        self.get_minterp().move_to_interpreted_state(state)

    def cancel_move_to(self, err: int) -> None:
        """Retail: MovementManager::CancelMoveTo @ 0x005241B0 (acclient.c:339239)"""
        if self.moveto_manager is not None:
            self.moveto_manager.cancel_move_to(err)

    def enter_default_state(self) -> None:
        """Put the motion interpreter in its default state (nothing without a body).

        A newly created interpreter enters it twice, as in retail.

        Retail: MovementManager::EnterDefaultState @ 0x005241C0 (acclient.c:339249)
        """
        if self.physics_obj is None:
            return
        self.get_minterp().enter_default_state()

    def handle_update_target(self, target_info: TargetInfo) -> None:
        """Retail: MovementManager::HandleUpdateTarget @ 0x00524790 (acclient.c:339630)"""
        if self.moveto_manager is not None:
            self.moveto_manager.handle_update_target(target_info)

    # -- queries -----------------------------------------------------------------------------------

    def inq_raw_motion_state(self) -> RawMotionState:
        """Retail: MovementManager::InqRawMotionState @ 0x00524200 (acclient.c:339273)"""
        return self.get_minterp().raw_state

    def inq_interpreted_motion_state(self) -> InterpretedMotionState:
        """Retail: MovementManager::InqInterpretedMotionState @ 0x00524230 (acclient.c:339292)"""
        return self.get_minterp().interpreted_state

    def is_moving_to(self) -> bool:
        """Retail: MovementManager::IsMovingTo @ 0x00524260 (acclient.c:339311)"""
        return self.moveto_manager is not None and self.moveto_manager.is_moving_to()

    def motions_pending(self) -> bool:
        """Retail: MovementManager::motions_pending @ 0x00524280 (acclient.c:339320)"""
        return self.motion_interpreter is not None and self.motion_interpreter.motions_pending()

    # -- notifications from the body -------------------------------------------------------------

    def motion_done(self, motion: int, success: bool) -> None:
        """A motion finished; only ``success`` reaches the interpreter.

        Retail: MovementManager::MotionDone @ 0x005242D0 (acclient.c:339348)
        """
        if self.motion_interpreter is not None:
            self.motion_interpreter.motion_done(success)

    def use_time(self) -> None:
        """Retail: MovementManager::UseTime @ 0x005242F0 (acclient.c:339358)"""
        if self.moveto_manager is not None:
            self.moveto_manager.use_time()

    def hit_ground(self) -> None:
        """Retail: MovementManager::HitGround @ 0x00524300 (acclient.c:339368)"""
        if self.motion_interpreter is not None:
            self.motion_interpreter.hit_ground()
        if self.moveto_manager is not None:
            self.moveto_manager.hit_ground()

    def leave_ground(self) -> None:
        """Tell the interpreter. Retail also calls the move-to manager's ``LeaveGround``, an empty
        function (folded by the linker into ``gmNoticeHandler::RecvNotice_PrevSpellSelection``).

        Retail: MovementManager::LeaveGround @ 0x00524320 (acclient.c:339384)
        """
        if self.motion_interpreter is not None:
            self.motion_interpreter.leave_ground()

    def handle_enter_world(self) -> None:
        """Nothing: retail calls an empty function on the interpreter (the same folded no-op).

        Retail: MovementManager::HandleEnterWorld @ 0x00524340 (acclient.c:339400)
        """

    def handle_exit_world(self) -> None:
        """Retail: MovementManager::HandleExitWorld @ 0x00524350 (acclient.c:339410)"""
        if self.motion_interpreter is not None:
            self.motion_interpreter.handle_exit_world()

    def report_exhaustion(self) -> None:
        """Tell the interpreter (the move-to manager's part is the folded no-op).

        Retail: MovementManager::ReportExhaustion @ 0x00524360 (acclient.c:339420)
        """
        if self.motion_interpreter is not None:
            self.motion_interpreter.report_exhaustion()
