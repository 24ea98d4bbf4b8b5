"""``CMotionInterp``: turns movement commands into motion-table calls and locomotion speeds.

A body keeps two views of what it is doing. The *raw* state is what was asked
for (``WalkBackwards`` with the run key held, ``TurnLeft``, ...). The
*interpreted* state is the canonical form the motion table plays:
``adjust_motion`` folds ``TurnLeft``, ``SideStepLeft`` and ``WalkBackwards``
into their right/forward twins with a negative speed, scales sidesteps, and
with the run key held turns walking into running at the weenie's run rate.
``apply_interpreted_movement`` replays the interpreted state into the part
array (style, forward, sidestep, turn), ``get_state_velocity`` is the planar
speed those motions stand for, and the jump and ground handlers launch and
land the body.

Speeds the interpreter writes into its own (float) fields, the jump extent
and the velocities it builds are rounded to float32 where retail stores them
(see :mod:`acphys.precision`); the rates and lengths between those stores
are float64.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from acphys.constants import EPSILON
from acphys.flags import PhysicsState, TransientState, member_namespace
from acphys.math.vector import Vector3
from acphys.motion.commands import (
    ACTION_MASK,
    CROUCH,
    DEAD,
    FALLEN,
    FALLING,
    NON_COMBAT,
    READY,
    RUN_FORWARD,
    SIDE_STEP_LEFT,
    SIDE_STEP_RIGHT,
    SITTING,
    SLEEPING,
    TURN_LEFT,
    TURN_RIGHT,
    WALK_BACKWARDS,
    WALK_FORWARD,
)
from acphys.motion.motion_states import InterpretedMotionState, MotionNode, RawMotionState
from acphys.motion.movement import (
    DEFAULT_MOVEMENT_FLAGS,
    HoldKey,
    MovementError,
    MovementFlags,
    MovementParameters,
    MovementStruct,
    MovementType,
)
from acphys.precision import f32, pack3, unpack3

if TYPE_CHECKING:
    from acphys.motion.weenie import Weenie
    from acphys.physics_obj import PhysicsObj

PS = member_namespace(PhysicsState)
TS = member_namespace(TransientState)
MF = member_namespace(MovementFlags)
ME = member_namespace(MovementError)
MT = member_namespace(MovementType)
HK = member_namespace(HoldKey)

#: Locomotion speeds of the standard human cycles at speed 1 (m/s); float32 as the binary holds them.
WALK_ANIM_SPEED = f32(3.1199999)
RUN_ANIM_SPEED = 4.0
SIDESTEP_ANIM_SPEED = 1.25
#: Walking backwards is walking forwards at -0.65 of the speed.
BACKWARDS_FACTOR = f32(0.64999998)
#: Sidestep speed scale, ``3.1199999 / 1.25 * 0.5`` evaluated from the float32 operands (≈ 1.248).
SIDESTEP_FACTOR = WALK_ANIM_SPEED / SIDESTEP_ANIM_SPEED * 0.5
#: With the run key held, turning is 1.5 times faster ...
RUN_TURN_FACTOR = 1.5
#: ... and the sidestep rate is clamped to ±3.
MAX_SIDESTEP_ANIM_RATE = 3.0
#: ``DoMotion`` refuses a new action while this many are queued.
MAX_ACTIONS = 6
#: Default jump speed (m/s) when the body has no weenie.
DEFAULT_JUMP_V_Z = 10.0

#: ``MovementParameters`` bits ``apply_interpreted_movement`` clears before setting its own.
_REPLAY_CLEARED = (
    MF.SET_HOLD_KEY | MF.MODIFY_INTERPRETED_STATE | MF.CANCEL_MOVETO | MF.DISABLE_JUMP_DURING_LINK
)
#: What that clearing gives on a new ``MovementParameters`` (the constructor's bits), computed
#: once: ``IntFlag``'s ``&`` and ``~`` build flag members, which costs more than the replay's test.
_REPLAY_FLAGS = DEFAULT_MOVEMENT_FLAGS & ~_REPLAY_CLEARED
#: ``DoMotion``: the chat-emote bit of a motion id, refused outside NonCombat.
_CHAT_EMOTE_BIT = 0x02000000


def on_ground(obj: PhysicsObj) -> bool:
    """In contact with walkable ground.

    Retail: CPhysicsObj::on_ground @ 0x00527B20 (acclient.c:343372)
    """
    return bool(obj._transient_state & TS.CONTACT) and bool(obj._transient_state & TS.ON_WALKABLE)


def motion_allows_jump(substate: int) -> int:
    """0 when a body in ``substate`` may jump, else ``CANT_JUMP_FROM_THIS_POSITION`` (0x48).

    Refused: Fallen, Reload/Unload/Pickup, Crouch/Sitting/Sleeping, AimLevel
    through MagicPray (0x4000001E-0x40000039) and the two magic power-up
    action ranges (0x1000006F-0x10000078, 0x10000128-0x10000131). Falling
    (0x40000015) is allowed.

    Retail: CMotionInterp::motion_allows_jump @ 0x005279E0 (acclient.c:343294)
    """
    refused = (
        substate == FALLEN
        or 0x40000016 <= substate <= 0x40000018
        or CROUCH <= substate <= SLEEPING
        or 0x4000001E <= substate <= 0x40000039
        or 0x1000006F <= substate <= 0x10000078
        or 0x10000128 <= substate <= 0x10000131
    )
    return ME.CANT_JUMP_FROM_THIS_POSITION if refused else ME.NONE


class MotionInterp:
    """Retail ``CMotionInterp`` (acclient.h:31407): one body's motion interpreter.

    Made by ``MovementManager``; ``initted`` stays False (and the body is not
    driven) until ``enter_default_state``.

    Retail: CMotionInterp::Create @ 0x00528C00 (acclient.c:344525)
    """

    __slots__ = (
        "current_speed_factor",
        "initted",
        "interpreted_state",
        "jump_extent",
        "my_run_rate",
        "pending_motions",
        "physics_obj",
        "raw_state",
        "server_action_stamp",
        "standing_longjump",
        "weenie_obj",
    )

    def __init__(self, physics_obj: PhysicsObj | None, weenie_obj: Weenie | None = None) -> None:
        self.initted = False
        self.weenie_obj: Weenie | None = None
        self.physics_obj: PhysicsObj | None = None
        self.raw_state = RawMotionState()
        self.interpreted_state = InterpretedMotionState()
        self.current_speed_factor = 1.0
        self.standing_longjump = False
        self.jump_extent = 0.0
        self.server_action_stamp = 0
        #: The run rate last seen in an interpreted RunForward (for weenies that cannot say).
        self.my_run_rate = 1.0
        self.pending_motions: list[MotionNode] = []
        self.set_weenie_object(weenie_obj)
        self.set_physics_object(physics_obj)

    # -- wiring ------------------------------------------------------------------------------

    def set_weenie_object(self, weenie_obj: Weenie | None) -> None:
        """Attach the weenie; an initialized interpreter replays its movement (cancelling move-tos).

        Retail: CMotionInterp::SetWeenieObject @ 0x00528920 (acclient.c:344334)
        """
        self.weenie_obj = weenie_obj
        self.apply_current_movement(True, False)

    def set_physics_object(self, physics_obj: PhysicsObj | None) -> None:
        """Attach the body; an initialized interpreter replays its movement (cancelling move-tos).

        Retail: CMotionInterp::SetPhysicsObject @ 0x00528970 (acclient.c:344353)
        """
        self.physics_obj = physics_obj
        self.apply_current_movement(True, False)

    def inq_style(self) -> int:
        """Retail: CMotionInterp::InqStyle @ 0x00527B10 (acclient.c:343366)"""
        return self.interpreted_state.current_style

    def _is_non_creature(self) -> bool:
        """A weenie that says it is not a creature: the interpreter leaves its motions alone."""
        return self.weenie_obj is not None and not self.weenie_obj.is_creature()

    def _run_rate(self) -> float:
        """The weenie's run rate, ``my_run_rate`` when it cannot say, 1.0 without a weenie."""
        if self.weenie_obj is None:
            return 1.0
        rate = self.weenie_obj.inq_run_rate()
        return self.my_run_rate if rate is None else rate

    def _remove_links_if_no_cell(self) -> None:
        """Outside the world (no cell) link animations are dropped at once."""
        obj = self.physics_obj
        if obj is not None and obj.cell is None:
            obj.remove_link_animations()

    # -- speeds ------------------------------------------------------------------------------

    def apply_run_to_command(self, motion: int, speed: float) -> tuple[int, float]:
        """The run key's effect: walk forward becomes run (x run rate), turns x1.5, sidesteps x rate (±3 max).

        Walking backwards (a negative WalkForward) stays a walk but is scaled
        by the run rate too.

        Retail: CMotionInterp::apply_run_to_command @ 0x00527BE0 (acclient.c:343438)
        """
        rate = self._run_rate()
        if motion == WALK_FORWARD:
            if speed > 0.0:
                motion = RUN_FORWARD
            speed = f32(rate * speed)
        elif motion == TURN_RIGHT:
            speed = f32(RUN_TURN_FACTOR * speed)
        elif motion == SIDE_STEP_RIGHT:
            speed = rate * speed
            if abs(speed) > MAX_SIDESTEP_ANIM_RATE:
                speed = MAX_SIDESTEP_ANIM_RATE if speed > 0.0 else -MAX_SIDESTEP_ANIM_RATE
            speed = f32(speed)
        return motion, speed

    def adjust_motion(self, motion: int, speed: float, key: HoldKey = HK.INVALID) -> tuple[int, float]:
        """Canonicalize a motion: left/backwards become right/forward with a negative speed.

        ``TurnLeft`` → ``TurnRight`` x -1; ``WalkBackwards`` → ``WalkForward``
        x -0.65; ``SideStepLeft`` → ``SideStepRight`` x -1; sidesteps are then
        scaled by ``SIDESTEP_FACTOR``. ``RunForward`` is returned untouched.
        With the run key (``key``, or the current hold key when ``key`` is
        INVALID) the result goes through ``apply_run_to_command``. A weenie
        that is not a creature gets its motion back unchanged.

        Retail: CMotionInterp::adjust_motion @ 0x00528010 (acclient.c:343745)
        """
        if self._is_non_creature() or motion == RUN_FORWARD:
            return motion, speed
        if motion == TURN_LEFT:
            motion, speed = TURN_RIGHT, f32(-speed)
        elif motion == WALK_BACKWARDS:
            motion, speed = WALK_FORWARD, f32(-BACKWARDS_FACTOR * speed)
        elif motion in (SIDE_STEP_RIGHT, SIDE_STEP_LEFT):
            if motion == SIDE_STEP_LEFT:
                motion, speed = SIDE_STEP_RIGHT, f32(-speed)
            speed = f32(SIDESTEP_FACTOR * speed)
        if key == HK.INVALID:
            key = self.raw_state.current_holdkey
        if key == HK.RUN:
            motion, speed = self.apply_run_to_command(motion, speed)
        return motion, speed

    def get_state_velocity(self) -> Vector3:
        """Body-local planar velocity of the interpreted motion, capped at ``run_rate * 4``.

        x = 1.25 x sidestep speed (SideStepRight), y = 3.12 x forward speed
        (WalkForward) or 4.0 x forward speed (RunForward), z = 0.

        Each component is stored into the ``float`` result before its length is taken; a
        capped component is ``1 / length · x · max_speed`` evaluated in double and stored once
        (acclient.c:343590-343592).

        Retail: CMotionInterp::get_state_velocity @ 0x00527D50 (acclient.c:343538)
        """
        state = self.interpreted_state
        x = SIDESTEP_ANIM_SPEED * state.sidestep_speed if state.sidestep_command == SIDE_STEP_RIGHT else 0.0
        if state.forward_command == WALK_FORWARD:
            y = WALK_ANIM_SPEED * state.forward_speed
        elif state.forward_command == RUN_FORWARD:
            y = RUN_ANIM_SPEED * state.forward_speed
        else:
            y = 0.0
        velocity = Vector3(x, y, 0.0)
        max_speed = self._run_rate() * RUN_ANIM_SPEED
        length = velocity.length()
        if length > max_speed:
            inv = 1.0 / length
            velocity.x, velocity.y, velocity.z = unpack3(
                pack3(
                    inv * velocity.x * max_speed, inv * velocity.y * max_speed, inv * velocity.z * max_speed
                )
            )
        return velocity

    def get_max_speed(self) -> float:
        """``run_rate * 4``.

        Retail: CMotionInterp::get_max_speed @ 0x00527CB0 (acclient.c:343485)
        """
        return self._run_rate() * RUN_ANIM_SPEED

    def get_adjusted_max_speed(self) -> float:
        """``run_rate * 4``, where a running body's rate is ``forward_speed / current_speed_factor``.

        Retail: CMotionInterp::get_adjusted_max_speed @ 0x00527D00 (acclient.c:343511)
        """
        rate = self._run_rate()
        if self.interpreted_state.forward_command == RUN_FORWARD:
            rate = self.interpreted_state.forward_speed / self.current_speed_factor
        return rate * RUN_ANIM_SPEED

    # -- contact and jumping ---------------------------------------------------------------

    def contact_allows_move(self, motion: int) -> bool:
        """Whether ``motion`` may play now: airborne gravity creatures may only turn, fall or die.

        Retail: CMotionInterp::contact_allows_move @ 0x00528240 (acclient.c:343881)
        """
        obj = self.physics_obj
        if obj is None:
            return False
        if motion in (DEAD, FALLING, TURN_RIGHT, TURN_LEFT):
            return True
        if self._is_non_creature() or not obj._state & PS.GRAVITY:
            return True
        return on_ground(obj)

    def jump_charge_is_allowed(self) -> int:
        """0, or why a jump cannot be charged: too loaded (0x49) or Fallen/Crouch/Sitting/Sleeping (0x48).

        Retail: CMotionInterp::jump_charge_is_allowed @ 0x00527A50 (acclient.c:343317)
        """
        if self.weenie_obj is not None and not self.weenie_obj.can_jump(self.jump_extent):
            return ME.CANT_JUMP_LOADED_DOWN
        forward = self.interpreted_state.forward_command
        if forward == FALLEN or CROUCH <= forward <= SLEEPING:
            return ME.CANT_JUMP_FROM_THIS_POSITION
        return ME.NONE

    def charge_jump(self) -> int:
        """Start charging a jump; a body dead still on walkable ground charges a standing long jump.

        Retail: CMotionInterp::charge_jump @ 0x005281C0 (acclient.c:343844)
        """
        error = self.jump_charge_is_allowed()
        if error:
            return error
        if self.is_standing_still():
            self.standing_longjump = True
        return ME.NONE

    def jump_is_allowed(self, extent: float) -> tuple[int, int]:
        """``(error, stamina_cost)`` for a jump of ``extent``; the cost is 0 unless the weenie priced it.

        Airborne gravity creatures cannot jump (0x24); a fully constrained body
        fails (0x47); the oldest pending motion's jump error wins next; then
        the charge checks, the forward substate and the weenie's stamina price.

        Retail: CMotionInterp::jump_is_allowed @ 0x005282B0 (acclient.c:343921)
        """
        obj = self.physics_obj
        if obj is None or not (self._is_non_creature() or not obj._state & PS.GRAVITY or on_ground(obj)):
            return ME.CANT_JUMP_WHILE_IN_THE_AIR, 0
        if obj.is_fully_constrained():
            return ME.GENERAL_MOVEMENT_FAILURE, 0
        if self.pending_motions and self.pending_motions[0].jump_error_code:
            return self.pending_motions[0].jump_error_code, 0
        error = self.jump_charge_is_allowed()
        if error:
            return error, 0
        error = motion_allows_jump(self.interpreted_state.forward_command)
        if error or self.weenie_obj is None:
            return error, 0
        cost = self.weenie_obj.jump_stamina_cost(extent)
        if cost is None:
            return ME.GENERAL_MOVEMENT_FAILURE, 0
        return ME.NONE, cost

    def jump(self, extent: float) -> tuple[int, int]:
        """Jump with charge ``extent``: on success leave walkable ground (LeaveGround launches the body).

        Returns ``(error, stamina_cost)``; a refused jump also cancels a
        standing long jump. Any move-to is cancelled first. ``extent`` is a
        ``float`` parameter, stored in the ``float`` field ``jump_extent``.

        Retail: CMotionInterp::jump @ 0x00528780 (acclient.c:344223)
        """
        obj = self.physics_obj
        if obj is None:
            return ME.NO_PHYSICS_OBJECT, 0
        extent = f32(extent)
        obj.cancel_moveto()
        error, cost = self.jump_is_allowed(extent)
        if error:
            self.standing_longjump = False
        else:
            self.jump_extent = extent
            obj.set_on_walkable(False)
        return error, cost

    def get_jump_v_z(self) -> float:
        """Upward launch speed: 0 uncharged, 10 without a weenie, else the weenie's (0 if it cannot say).

        The weenie writes its answer into the ``float`` local ``extent``, which is returned.

        Retail: CMotionInterp::get_jump_v_z @ 0x00527AA0 (acclient.c:343342)
        """
        extent = self.jump_extent
        if extent < EPSILON:
            return 0.0
        extent = min(extent, 1.0)
        if self.weenie_obj is None:
            return DEFAULT_JUMP_V_Z
        v_z = self.weenie_obj.inq_jump_velocity(extent)
        return 0.0 if v_z is None else f32(v_z)

    def get_leave_ground_velocity(self) -> Vector3:
        """Body-local launch velocity: the state velocity with z = jump speed.

        When all three are (within EPSILON) zero, the body's current global
        velocity rotated into its local frame is used instead. The jump speed is a
        ``float`` local; the rotation is ``Position::globaltolocalvec`` inlined (its row sums,
        stored once per component, acclient.c:343822-343840).

        Retail: CMotionInterp::get_leave_ground_velocity @ 0x005280C0 (acclient.c:343805)
        """
        velocity = self.get_state_velocity()
        velocity.z = self.get_jump_v_z()  # a float32 already: the float local va
        if abs(velocity.x) < EPSILON and abs(velocity.y) < EPSILON and abs(velocity.z) < EPSILON:
            obj = self.physics_obj
            velocity = obj.position.globaltolocalvec(obj.velocity)
        return velocity

    def leave_ground(self) -> None:
        """Left walkable ground: launch a gravity creature with its leave-ground velocity and replay.

        Clears the standing long jump and the jump charge, drops link animations
        and reapplies the current movement (which now plays Falling).

        Retail: CMotionInterp::LeaveGround @ 0x00528B00 (acclient.c:344456)
        """
        obj = self.physics_obj
        if obj is None or self._is_non_creature() or not obj._state & PS.GRAVITY:
            return
        obj.set_local_velocity(self.get_leave_ground_velocity())
        self.standing_longjump = False
        self.jump_extent = 0.0
        obj.remove_link_animations()
        self.apply_current_movement(False, False)

    def hit_ground(self) -> None:
        """Landed on walkable ground: a gravity creature drops link animations and replays its movement.

        Retail: CMotionInterp::HitGround @ 0x00528AC0 (acclient.c:344428)
        """
        obj = self.physics_obj
        if obj is None or self._is_non_creature() or not obj._state & PS.GRAVITY:
            return
        obj.remove_link_animations()
        self.apply_current_movement(False, False)

    def is_standing_still(self) -> bool:
        """On walkable ground, Ready, no sidestep, no turn.

        Retail: CMotionInterp::is_standing_still @ 0x00527FA0 (acclient.c:343715)
        """
        state = self.interpreted_state
        return (
            on_ground(self.physics_obj)
            and state.forward_command == READY
            and not state.sidestep_command
            and not state.turn_command
        )

    # -- the pending-motion queue ------------------------------------------------------------

    def add_to_queue(self, context_id: int, motion: int, jump_error_code: int) -> None:
        """Retail: CMotionInterp::add_to_queue @ 0x00527B80 (acclient.c:343405)"""
        self.pending_motions.append(MotionNode(context_id, motion, jump_error_code))

    def motions_pending(self) -> bool:
        """Retail: CMotionInterp::motions_pending @ 0x00527FE0 (acclient.c:343728)"""
        return bool(self.pending_motions)

    def _pop_pending(self) -> None:
        """Retire the oldest pending motion; a finished action also leaves both action queues."""
        head = self.pending_motions[0]
        if head.motion & ACTION_MASK:
            self.physics_obj.unstick_from_object()
            self.interpreted_state.remove_action()
            self.raw_state.remove_action()
        self.pending_motions.pop(0)

    def motion_done(self, success: bool) -> None:
        """The motion table finished the oldest pending motion (``success`` is not consulted).

        Retail: CMotionInterp::MotionDone @ 0x00527EC0 (acclient.c:343640)
        """
        if self.physics_obj is not None and self.pending_motions:
            self._pop_pending()

    def handle_exit_world(self) -> None:
        """Leaving the world: retire every pending motion.

        Without a body retail's loop never advances (it spins on the head
        node); acphys leaves the queue as it is instead.

        Retail: CMotionInterp::HandleExitWorld @ 0x00527F30 (acclient.c:343678)
        """
        while self.pending_motions and self.physics_obj is not None:
            self._pop_pending()

    # -- interpreted motions -----------------------------------------------------------------

    def do_interpreted_motion(self, motion: int, params: MovementParameters) -> int:
        """Play a canonical motion through the body's motion table and queue it.

        When contact does not allow it (an airborne gravity creature), a
        non-action is only recorded and an action fails with 0x24. During a
        standing long jump, walk/run/sidestep are only recorded. Dead first
        drops link animations. The queued node carries the jump error of the
        motion (0x48 when ``DISABLE_JUMP_DURING_LINK``). ``MODIFY_INTERPRETED_STATE``
        records the motion in the interpreted state.

        Retail: CMotionInterp::DoInterpretedMotion @ 0x00528360 (acclient.c:343974)
        """
        obj = self.physics_obj
        if obj is None:
            return ME.NO_PHYSICS_OBJECT
        modify = params.has(MF.MODIFY_INTERPRETED_STATE)
        if not self.contact_allows_move(motion):
            if motion & ACTION_MASK:
                result = ME.CANT_JUMP_WHILE_IN_THE_AIR
            else:
                if modify:
                    self.interpreted_state.apply_motion(motion, params)
                result = ME.NONE
        elif self.standing_longjump and motion in (WALK_FORWARD, RUN_FORWARD, SIDE_STEP_RIGHT):
            if modify:
                self.interpreted_state.apply_motion(motion, params)
            result = ME.NONE
        else:
            if motion == DEAD:
                obj.remove_link_animations()
            result = obj.do_interpreted_motion(motion, params)
            if not result:
                if params.has(MF.DISABLE_JUMP_DURING_LINK):
                    jump_error = ME.CANT_JUMP_FROM_THIS_POSITION
                else:
                    jump_error = motion_allows_jump(motion)
                    if not jump_error and not motion & ACTION_MASK:
                        jump_error = motion_allows_jump(self.interpreted_state.forward_command)
                self.add_to_queue(params.context_id, motion, jump_error)
                if modify:
                    self.interpreted_state.apply_motion(motion, params)
        self._remove_links_if_no_cell()
        return result

    def stop_interpreted_motion(self, motion: int, params: MovementParameters) -> int:
        """Stop a canonical motion in the motion table (queueing a Ready) and in the interpreted state.

        Airborne, or walk/run/sidestep during a standing long jump, it is only
        removed from the interpreted state.

        Retail: CMotionInterp::StopInterpretedMotion @ 0x00528470 (acclient.c:344033)
        """
        obj = self.physics_obj
        if obj is None:
            return ME.NO_PHYSICS_OBJECT
        modify = params.has(MF.MODIFY_INTERPRETED_STATE)
        longjump_held = self.standing_longjump and motion in (WALK_FORWARD, RUN_FORWARD, SIDE_STEP_RIGHT)
        if not self.contact_allows_move(motion) or longjump_held:
            if modify:
                self.interpreted_state.remove_motion(motion)
            result = ME.NONE
        else:
            result = obj.stop_interpreted_motion(motion, params)
            if not result:
                self.add_to_queue(params.context_id, READY, ME.NONE)
                if modify:
                    self.interpreted_state.remove_motion(motion)
        self._remove_links_if_no_cell()
        return result

    # -- raw motions -------------------------------------------------------------------------

    def do_motion(self, motion: int, params: MovementParameters) -> int:
        """A commanded motion: hold key, canonicalization, combat refusals, then the interpreted motion.

        Outside NonCombat, Crouch/Sitting/Sleeping and chat emotes are
        refused (0x3F-0x42); a seventh queued action is refused (0x45). On
        success ``MODIFY_RAW_STATE`` records the motion as commanded.

        Retail: CMotionInterp::DoMotion @ 0x00528D20 (acclient.c:344599)
        """
        obj = self.physics_obj
        if obj is None:
            return ME.NO_PHYSICS_OBJECT
        adjusted = params.copy()
        if params.has(MF.CANCEL_MOVETO):
            obj.cancel_moveto()
        if params.has(MF.SET_HOLD_KEY):
            self.set_hold_key(params.hold_key_to_apply, params.has(MF.CANCEL_MOVETO))
        new_motion, adjusted.speed = self.adjust_motion(motion, adjusted.speed, params.hold_key_to_apply)
        if self.interpreted_state.current_style != NON_COMBAT:
            if motion == CROUCH:
                return ME.CANT_CROUCH_IN_COMBAT
            if motion == SITTING:
                return ME.CANT_SIT_IN_COMBAT
            if motion == SLEEPING:
                return ME.CANT_LIE_DOWN_IN_COMBAT
            if motion & _CHAT_EMOTE_BIT:
                return ME.CANT_CHAT_EMOTE_IN_COMBAT
        if motion & ACTION_MASK and self.interpreted_state.get_num_actions() >= MAX_ACTIONS:
            return ME.TOO_MANY_ACTIONS
        result = self.do_interpreted_motion(new_motion, adjusted)
        if not result and params.has(MF.MODIFY_RAW_STATE):
            self.raw_state.apply_motion(motion, params)
        return result

    def stop_motion(self, motion: int, params: MovementParameters) -> int:
        """Stop a commanded motion: canonicalize, stop it interpreted, then clear it from the raw state.

        Retail: CMotionInterp::StopMotion @ 0x00528530 (acclient.c:344080)
        """
        obj = self.physics_obj
        if obj is None:
            return ME.NO_PHYSICS_OBJECT
        if params.has(MF.CANCEL_MOVETO):
            obj.cancel_moveto()
        adjusted = params.copy()
        new_motion, adjusted.speed = self.adjust_motion(motion, adjusted.speed, params.hold_key_to_apply)
        result = self.stop_interpreted_motion(new_motion, adjusted)
        if not result and params.has(MF.MODIFY_RAW_STATE):
            self.raw_state.remove_motion(motion)
        return result

    def stop_completely(self) -> int:
        """Back to Ready at speed 1 with no sidestep or turn, raw and interpreted; stop the motion table.

        Queues a Ready carrying the jump error of the forward motion it replaced.

        Retail: CMotionInterp::StopCompletely @ 0x00527E40 (acclient.c:343596)
        """
        obj = self.physics_obj
        if obj is None:
            return ME.NO_PHYSICS_OBJECT
        obj.cancel_moveto()
        jump_error = motion_allows_jump(self.interpreted_state.forward_command)
        for state in (self.raw_state, self.interpreted_state):
            state.forward_command = READY
            state.forward_speed = 1.0
            state.sidestep_command = 0
            state.turn_command = 0
        obj.stop_completely_internal()
        self.add_to_queue(0, READY, jump_error)
        self._remove_links_if_no_cell()
        return ME.NONE

    def perform_movement(self, ms: MovementStruct) -> int:
        """Dispatch movement types 1-5, then let the part array report completed motions (else 0x47).

        Retail: CMotionInterp::PerformMovement @ 0x00528E80 (acclient.c:344669)
        """
        if ms.type == MT.RAW_COMMAND:
            result = self.do_motion(ms.motion, ms.params)
        elif ms.type == MT.INTERPRETED_COMMAND:
            result = self.do_interpreted_motion(ms.motion, ms.params)
        elif ms.type == MT.STOP_RAW_COMMAND:
            result = self.stop_motion(ms.motion, ms.params)
        elif ms.type == MT.STOP_INTERPRETED_COMMAND:
            result = self.stop_interpreted_motion(ms.motion, ms.params)
        elif ms.type == MT.STOP_COMPLETELY:
            self.stop_completely()
            result = ME.NONE
        else:
            return ME.GENERAL_MOVEMENT_FAILURE
        self.physics_obj.check_for_completed_motions()
        return result

    # -- replaying the state -----------------------------------------------------------------

    def apply_interpreted_movement(self, cancel_moveto: bool, disallow_jump: bool) -> None:
        """Replay the interpreted state into the motion table without changing it.

        Style; then forward and sidestep (Ready and no sidestep during a
        standing long jump, Falling when contact forbids moving); then turn
        (a TurnRight stop goes straight to the body). A running state first
        teaches ``my_run_rate`` its speed.

        Retail: CMotionInterp::apply_interpreted_movement @ 0x00528600 (acclient.c:344146)
        """
        obj = self.physics_obj
        if obj is None:
            return
        params = MovementParameters()
        params.flags = _REPLAY_FLAGS  # params.flags &= ~_REPLAY_CLEARED, on the constructor's bits
        if cancel_moveto:
            params.flags |= MF.CANCEL_MOVETO
        if disallow_jump:
            params.flags |= MF.DISABLE_JUMP_DURING_LINK
        state = self.interpreted_state
        if state.forward_command == RUN_FORWARD:
            self.my_run_rate = state.forward_speed
        self.do_interpreted_motion(state.current_style, params)
        if not self.contact_allows_move(state.forward_command):
            params.speed = 1.0
            self.do_interpreted_motion(FALLING, params)
        elif self.standing_longjump:
            params.speed = 1.0
            self.do_interpreted_motion(READY, params)
            self.stop_interpreted_motion(SIDE_STEP_RIGHT, params)
        else:
            params.speed = state.forward_speed
            self.do_interpreted_motion(state.forward_command, params)
            if state.sidestep_command:
                params.speed = state.sidestep_speed
                self.do_interpreted_motion(state.sidestep_command, params)
            else:
                self.stop_interpreted_motion(SIDE_STEP_RIGHT, params)
        if state.turn_command:
            params.speed = state.turn_speed
            self.do_interpreted_motion(state.turn_command, params)
        else:
            if not obj.stop_interpreted_motion(TURN_RIGHT, params):
                self.add_to_queue(params.context_id, READY, ME.NONE)
            self._remove_links_if_no_cell()

    def apply_raw_movement(self, cancel_moveto: bool, disallow_jump: bool) -> None:
        """Rebuild the interpreted state from the raw one (canonicalizing each channel) and replay it.

        Retail: CMotionInterp::apply_raw_movement @ 0x005287E0 (acclient.c:344258)
        """
        if self.physics_obj is None:
            return
        raw, state = self.raw_state, self.interpreted_state
        state.current_style = raw.current_style
        state.forward_command, state.forward_speed = self.adjust_motion(
            raw.forward_command, raw.forward_speed, raw.forward_holdkey
        )
        state.sidestep_command, state.sidestep_speed = self.adjust_motion(
            raw.sidestep_command, raw.sidestep_speed, raw.sidestep_holdkey
        )
        state.turn_command, state.turn_speed = self.adjust_motion(
            raw.turn_command, raw.turn_speed, raw.turn_holdkey
        )
        self.apply_interpreted_movement(cancel_moveto, disallow_jump)

    def apply_current_movement(self, cancel_moveto: bool, disallow_jump: bool) -> None:
        """Replay the movement once initialized: from the raw state when the player (or a body with no
        weenie) moved autonomously, else from the interpreted state.

        Retail: CMotionInterp::apply_current_movement @ 0x00528870 (acclient.c:344300)
        """
        obj = self.physics_obj
        if obj is None or not self.initted:
            return
        weenie = self.weenie_obj
        if (weenie is None or weenie.is_the_player()) and obj.movement_is_autonomous():
            self.apply_raw_movement(cancel_moveto, disallow_jump)
        else:
            self.apply_interpreted_movement(cancel_moveto, disallow_jump)

    def report_exhaustion(self) -> None:
        """Stamina ran out: replay the movement (the run rate the weenie reports has changed).

        Retail: CMotionInterp::ReportExhaustion @ 0x005288D0 (acclient.c:344317)
        """
        self.apply_current_movement(False, False)

    def set_hold_run(self, val: bool, cancel_moveto: bool = False) -> None:
        """Press or release the run key; a change replays the movement.

        Retail: CMotionInterp::set_hold_run @ 0x00528B70 (acclient.c:344491)
        """
        if bool(val) != (self.raw_state.current_holdkey == HK.RUN):
            self.raw_state.current_holdkey = HK.RUN if val else HK.NONE
            self.apply_current_movement(cancel_moveto, False)

    def set_hold_key(self, key: HoldKey, cancel_moveto: bool) -> None:
        """Switch the current hold key to NONE or RUN (INVALID is ignored); a change replays the movement.

        Retail: CMotionInterp::SetHoldKey @ 0x00528BB0 (acclient.c:344501)
        """
        current = self.raw_state.current_holdkey
        if key == current:
            return
        if (key == HK.NONE and current == HK.RUN) or key == HK.RUN:
            self.raw_state.current_holdkey = key
            self.apply_current_movement(cancel_moveto, False)

    def move_to_interpreted_state(self, new_state: InterpretedMotionState) -> bool:
        """Adopt a server-sent interpreted state, then play its actions newer than ``server_action_stamp``.

        Stamps are compared in 15 bits with wrap-around. The player's own
        autonomous actions are skipped (they were played when commanded).

        Retail: CMotionInterp::move_to_interpreted_state @ 0x005289C0 (acclient.c:344371)
        """
        obj = self.physics_obj
        if obj is None:
            return False
        self.raw_state.current_style = new_state.current_style
        obj.cancel_moveto()
        disallow_jump = motion_allows_jump(self.interpreted_state.forward_command) != 0
        self.interpreted_state.copy_movement_from(new_state)
        self.apply_current_movement(True, disallow_jump)
        params = MovementParameters()
        for action in new_state.actions:
            stamp = action.stamp & 0x7FFF
            server = self.server_action_stamp & 0x7FFF
            newer = server < stamp if abs(stamp - server) <= 0x3FFF else stamp < server
            if not newer:
                continue
            weenie = self.weenie_obj
            if (weenie is not None and not weenie.is_the_player()) or not action.autonomous:
                self.server_action_stamp = action.stamp
                params.speed = action.speed
                if action.autonomous:
                    params.flags |= MF.AUTONOMOUS
                else:
                    params.flags &= ~MF.AUTONOMOUS
                self.do_interpreted_motion(action.action, params)
        return True

    def enter_default_state(self) -> None:
        """Reset both states, reinitialize the motion tables, queue a Ready and take the body off the ground.

        Pending motions from before are kept (the Ready is appended).

        Retail: CMotionInterp::enter_default_state @ 0x00528C80 (acclient.c:344559)
        """
        self.raw_state = RawMotionState()
        self.interpreted_state = InterpretedMotionState()
        self.physics_obj.initialize_motion_tables()
        self.add_to_queue(0, READY, ME.NONE)
        self.initted = True
        self.leave_ground()
